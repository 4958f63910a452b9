#include "models/geometry/installation_space.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace pkmopt {

double InstallationSpace::excess(const Eigen::Vector3d& c, double r) const {
  switch (kind) {
    case Kind::kNone:
      return -std::numeric_limits<double>::infinity();
    case Kind::kBox: {
      double e = -std::numeric_limits<double>::infinity();
      for (int a = 0; a < 3; ++a) e = std::max({e, min(a) + r - c(a), c(a) + r - max(a)});
      return e;
    }
    case Kind::kCylinder:
      return std::max(
          {(c.head<2>() - centre).norm() + r - radius, z_min + r - c.z(), c.z() + r - z_max});
  }
  return 0.0;
}

void check_installation_space(const InstallationSpace& s) {
  if (s.kind == InstallationSpace::Kind::kBox) {
    if (!(s.min.allFinite() && s.max.allFinite() && (s.max - s.min).minCoeff() > 0.0))
      throw std::invalid_argument(
          "installation_space.box: expected finite min and max with max > min on every axis");
  } else if (s.kind == InstallationSpace::Kind::kCylinder) {
    if (!(std::isfinite(s.radius) && s.radius > 0.0 && std::isfinite(s.z_min) &&
          std::isfinite(s.z_max) && s.z_max > s.z_min && s.centre.allFinite()))
      throw std::invalid_argument(
          "installation_space.cylinder: expected a finite radius > 0 and z_max > z_min");
  }
}

}  // namespace pkmopt
