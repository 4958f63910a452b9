// Tests of models/core/pose: the rotation convention R = Rz Ry Rx and its inverse.
#include "models/core/pose.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include "tests/sample_machines.hpp"

namespace pkmopt {
namespace {

TEST(Pose, RotationIsFixedAxesXThenYThenZ) {
  sample_machines::Uniform u(1);
  for (int k = 0; k < 100; ++k) {
    const Eigen::Vector3d a(u(-3, 3), u(-1.5, 1.5), u(-3, 3));
    const Eigen::Matrix3d expected = (Eigen::AngleAxisd(a(2), Eigen::Vector3d::UnitZ()) *
                                      Eigen::AngleAxisd(a(1), Eigen::Vector3d::UnitY()) *
                                      Eigen::AngleAxisd(a(0), Eigen::Vector3d::UnitX()))
                                         .toRotationMatrix();
    EXPECT_LT((rotation_zyx<double>(a) - expected).norm(), 4e-15);
  }
  // rx = 90 deg turns +y into +z.
  const Eigen::Vector3d y =
      rotation_zyx<double>(Eigen::Vector3d(M_PI / 2, 0, 0)) * Eigen::Vector3d::UnitY();
  EXPECT_LT((y - Eigen::Vector3d::UnitZ()).norm(), 1e-15);
}

TEST(Pose, AnglesFromRotationRoundTrip) {
  sample_machines::Uniform u(2);
  for (int k = 0; k < 1000; ++k) {
    const Eigen::Vector3d a(u(-M_PI + 1e-9, M_PI), u(-M_PI / 2 + 1e-6, M_PI / 2 - 1e-6),
                            u(-M_PI + 1e-9, M_PI));
    const Eigen::Vector3d back = angles_from_rotation(rotation_zyx<double>(a));
    EXPECT_LT((back - a).norm(), 1e-9);
  }
  // Gimbal lock: the rotation is still reproduced.
  const Eigen::Vector3d lock(0.3, M_PI / 2, 0.7);
  const Eigen::Matrix3d R = rotation_zyx<double>(lock);
  EXPECT_LT((rotation_zyx<double>(angles_from_rotation(R)) - R).norm(), 1e-12);
}

TEST(Pose, RotationVectorRoundTrip) {
  sample_machines::Uniform u(3);
  for (int k = 0; k < 100; ++k) {
    const Eigen::Vector3d w(u(-1, 1), u(-1, 1), u(-1, 1));
    EXPECT_LT((rotation_vector(rotation_from_vector(w)) - w).norm(), 1e-12);
  }
  EXPECT_EQ(rotation_from_vector(Eigen::Vector3d::Zero()), Eigen::Matrix3d::Identity());
}

}  // namespace
}  // namespace pkmopt
