#include "models/geometry/joint_layout.hpp"

#include <cmath>

#include "models/core/pose.hpp"

namespace pkmopt {
namespace {

Eigen::Matrix<double, 3, 6> hexagon(double radius, const double (&angles_deg)[6]) {
  Eigen::Matrix<double, 3, 6> joints;
  for (int i = 0; i < 6; ++i) {
    const double theta = deg_to_rad(angles_deg[i]);
    joints.col(i) << radius * std::cos(theta), radius * std::sin(theta), 0.0;
  }
  return joints;
}

}  // namespace

Eigen::Matrix<double, 3, 6> semi_regular_base_joints(double radius, double pair_separation) {
  const double half = rad_to_deg(pair_separation) / 2.0;
  double angles[6];
  for (int i = 0; i < 6; ++i) {
    const double k = i / 2;
    angles[i] = 120.0 * k + (i % 2 == 0 ? -half : half);
  }
  return hexagon(radius, angles);
}

Eigen::Matrix<double, 3, 6> semi_regular_platform_joints(double radius, double pair_separation) {
  const double half = rad_to_deg(pair_separation) / 2.0;
  double angles[6];
  for (int i = 0; i < 6; ++i) {
    const double k = i / 2;
    angles[i] = i % 2 == 0 ? 120.0 * k - 60.0 + half : 120.0 * k + 60.0 - half;
  }
  return hexagon(radius, angles);
}

}  // namespace pkmopt
