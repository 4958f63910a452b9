#include "models/geometry/leg_interference.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "models/geometry/segment_distance.hpp"

namespace pkmopt {

namespace {

void require(bool ok, const std::string& message) {
  if (!ok) throw std::invalid_argument(message);
}

bool size_ok(double x) { return std::isfinite(x) && x >= 0.0; }

}  // namespace

void check_leg_shape(const LegShape& s, double min_clearance) {
  require(size_ok(s.diameter), "legs.diameter must be a finite number >= 0");
  require(size_ok(s.cylinder_diameter), "legs.cylinder.diameter must be a finite number >= 0");
  require(size_ok(s.cylinder_length), "legs.cylinder.length must be a finite number >= 0");
  require(size_ok(s.rod_diameter), "legs.rod.diameter must be a finite number >= 0");
  require(!(s.diameter > 0.0 && (s.cylinder_diameter > 0.0 || s.rod_diameter > 0.0)),
          "legs: either diameter (one capsule per leg) or cylinder and rod, not both");
  require((s.cylinder_diameter > 0.0) == (s.cylinder_length > 0.0),
          "legs.cylinder needs both diameter and length");
  require(!(s.rod_diameter > 0.0) || s.cylinder_diameter > 0.0,
          "legs.rod needs legs.cylinder (the rod runs from the platform joint into it)");
  require(std::isfinite(min_clearance) && min_clearance >= 0.0,
          "min_clearance must be a finite number >= 0");
}

int leg_bodies(const LegShape& shape, const Eigen::Vector3d& a, const Eigen::Vector3d& p, int leg,
               Capsule* out) {
  if (!shape.present()) return 0;
  if (!shape.two_bodies()) {
    out[0] = {a, p, 0.5 * shape.diameter, leg, true, true};
    return 1;
  }
  const double length = (p - a).norm();
  const Eigen::Vector3d s =
      length > 0.0 ? Eigen::Vector3d((p - a) / length) : Eigen::Vector3d::Zero();
  // The cylinder's open end, never beyond the platform joint.
  const Eigen::Vector3d mouth = a + std::min(shape.cylinder_length, length) * s;
  out[0] = {a, mouth, 0.5 * shape.cylinder_diameter, leg, true, false};
  if (shape.rod_diameter <= 0.0) return 1;
  out[1] = {p, mouth, 0.5 * shape.rod_diameter, leg, false, true};
  return 2;
}

std::vector<Capsule> leg_capsules(const LegShape& shape, const Eigen::Matrix3Xd& base,
                                  const Eigen::Matrix3Xd& platform) {
  std::vector<Capsule> out;
  Capsule bodies[2];
  for (Eigen::Index i = 0; i < base.cols(); ++i) {
    const int n = leg_bodies(shape, base.col(i), platform.col(i), static_cast<int>(i), bodies);
    out.insert(out.end(), bodies, bodies + n);
  }
  return out;
}

Clearance leg_clearance(std::span<const Capsule> bodies) {
  Clearance best;
  for (std::size_t u = 0; u < bodies.size(); ++u) {
    for (std::size_t v = u + 1; v < bodies.size(); ++v) {
      const Capsule &x = bodies[u], &y = bodies[v];
      if (x.leg == y.leg) continue;
      const double gap = segment_distance(x.a, x.b, y.a, y.b) - x.radius - y.radius;
      if (gap < best.value) {
        best.value = gap;
        best.first = std::min(x.leg, y.leg);
        best.second = std::max(x.leg, y.leg);
      }
    }
  }
  return best;
}

bool legs_apart(std::span<const Capsule> bodies, double min_clearance) {
  for (std::size_t u = 0; u < bodies.size(); ++u) {
    const Capsule& x = bodies[u];
    const Eigen::Vector3d x_lo = x.a.cwiseMin(x.b), x_hi = x.a.cwiseMax(x.b);
    for (std::size_t v = u + 1; v < bodies.size(); ++v) {
      const Capsule& y = bodies[v];
      if (x.leg == y.leg) continue;
      const double need = x.radius + y.radius + min_clearance;
      // The distance between the axes' bounding boxes is a lower bound of the axes' distance.
      const Eigen::Vector3d y_lo = y.a.cwiseMin(y.b), y_hi = y.a.cwiseMax(y.b);
      const Eigen::Vector3d gap = (y_lo - x_hi).cwiseMax(x_lo - y_hi).cwiseMax(0.0);
      if (gap.squaredNorm() >= need * need) continue;
      if (segment_distance(x.a, x.b, y.a, y.b) - x.radius - y.radius < min_clearance) return false;
    }
  }
  return true;
}

std::string clearance_pair_text(int first, int second) {
  if (first < 0 || second < 0) return "";
  const std::string leg = std::to_string(first + 1) + "-";
  if (second == kPlatformBody) return leg + "platform";
  if (second == kBaseBody) return leg + "base";
  if (second == kToolBody) return leg + "tool";
  return leg + std::to_string(second + 1);
}

}  // namespace pkmopt
