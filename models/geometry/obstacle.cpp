#include "models/geometry/obstacle.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>

namespace pkmopt {

double depth(const ObstacleBox& box, const Eigen::Vector3d& p) {
  return std::min((p - box.min).minCoeff(), (box.max - p).minCoeff());
}

double intrusion(const ObstacleBox& box, const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  // The six faces' distances as affine functions c + s t of the segment parameter t.
  const Eigen::Vector3d d = b - a;
  std::array<double, 6> c{}, s{};
  for (int k = 0; k < 3; ++k) {
    c[static_cast<std::size_t>(k)] = a(k) - box.min(k);
    s[static_cast<std::size_t>(k)] = d(k);
    c[static_cast<std::size_t>(k + 3)] = box.max(k) - a(k);
    s[static_cast<std::size_t>(k + 3)] = -d(k);
  }
  auto at = [&](double t) {
    double v = c[0] + s[0] * t;
    for (std::size_t k = 1; k < 6; ++k) v = std::min(v, c[k] + s[k] * t);
    return v;
  };
  double best = std::max(at(0.0), at(1.0));
  for (std::size_t i = 0; i < 6; ++i)
    for (std::size_t j = i + 1; j < 6; ++j) {
      if (s[i] == s[j]) continue;
      const double t = (c[j] - c[i]) / (s[i] - s[j]);
      if (t > 0.0 && t < 1.0) best = std::max(best, at(t));
    }
  return best;
}

void check_obstacle(const ObstacleBox& box) {
  for (int k = 0; k < 3; ++k)
    if (!std::isfinite(box.min(k)) || !std::isfinite(box.max(k)) || !(box.min(k) < box.max(k)))
      throw std::invalid_argument(fmt::format(
          "obstacle: expected finite min < max on every axis, found min [{}, {}, {}], max [{}, "
          "{}, {}]",
          box.min.x(), box.min.y(), box.min.z(), box.max.x(), box.max.y(), box.max.z()));
}

}  // namespace pkmopt
