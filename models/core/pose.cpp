#include "models/core/pose.hpp"

#include <Eigen/Geometry>

namespace pkmopt {

Eigen::Vector3d angles_from_rotation(const Eigen::Matrix3d& R) {
  const double cy = std::hypot(R(0, 0), R(1, 0));
  const double ry = std::atan2(-R(2, 0), cy);
  if (cy > 1e-12) {
    return {std::atan2(R(2, 1), R(2, 2)), ry, std::atan2(R(1, 0), R(0, 0))};
  }
  // Gimbal lock: only rz - rx (ry = +90 deg) or rz + rx (ry = -90 deg) is defined; take rx = 0.
  return {0.0, ry, std::atan2(-R(0, 1), R(1, 1))};
}

Eigen::Matrix3d rotation_from_vector(const Eigen::Vector3d& omega) {
  const double angle = omega.norm();
  if (angle < 1e-300) return Eigen::Matrix3d::Identity();
  return Eigen::AngleAxisd(angle, omega / angle).toRotationMatrix();
}

Eigen::Vector3d rotation_vector(const Eigen::Matrix3d& R) {
  const Eigen::AngleAxisd aa(R);
  return aa.angle() * aa.axis();
}

}  // namespace pkmopt
