#include "models/core/pose_box.hpp"

#include <Eigen/Geometry>

namespace pkmopt {

Eigen::Matrix3d box_rotation(const Eigen::Matrix3d& R0, double theta, double phi, double gamma) {
  const Eigen::Vector3d u(std::cos(phi), std::sin(phi), 0.0);
  return R0 * Eigen::AngleAxisd(theta, u).toRotationMatrix() *
         Eigen::AngleAxisd(gamma, Eigen::Vector3d::UnitZ()).toRotationMatrix();
}

}  // namespace pkmopt
