// Tests of models/hexapod/hexapod_enclosure.cpp (Hexapod::enclose_jacobian): at random poses of
// random boxes the hexapod's own inverse Jacobian (angular columns divided by rho) lies in the
// interval matrix, its derivatives by central differences lie in the slopes, and a box of one
// pose gives that pose's Jacobian to rounding.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "models/hexapod/hexapod.hpp"
#include "models/sample_machines.hpp"

namespace pkmopt {
namespace {

double random_in(std::mt19937_64& engine, double lo, double hi) {
  return lo + std::uniform_real_distribution<double>(0.0, 1.0)(engine) * (hi - lo);
}

// J_c at a pose of the box's parameters (the hexapod's inverse Jacobian, columns 4..6 / rho).
Eigen::Matrix<double, 6, 6> jc(const Hexapod& h, const PoseBox& box, const double (&x)[6]) {
  Pose pose;
  pose.position = Eigen::Vector3d(x[0], x[1], x[2]);
  pose.angles = angles_from_rotation(box_rotation(box.R0, x[3], x[4], x[5]));
  Eigen::Matrix<double, 6, 6> J = h.inverse_jacobian(pose);
  J.rightCols<3>() /= h.enclosure_length();
  return J;
}

PoseBox random_box(std::mt19937_64& engine, double size) {
  PoseBox box;
  box.R0 = rotation_zyx<double>(Eigen::Vector3d(
      random_in(engine, -0.2, 0.2), random_in(engine, -0.2, 0.2), random_in(engine, -1.0, 1.0)));
  const Eigen::Vector3d c(random_in(engine, -0.2, 0.2), random_in(engine, -0.2, 0.2),
                          random_in(engine, 0.7, 1.0));
  box.position_lo = c - Eigen::Vector3d::Constant(size);
  box.position_hi = c + Eigen::Vector3d::Constant(size);
  const double t = random_in(engine, 0.0, 0.3);
  box.theta = Interval(t, t + 4 * size);
  const double p = random_in(engine, 0.0, 6.0);
  box.phi = Interval(p, p + 10 * size);
  const double g = random_in(engine, -0.5, 0.5);
  box.gamma = Interval(g - 4 * size, g + 4 * size);
  return box;
}

TEST(HexapodEnclosure, HoldsTheJacobianAndItsDerivativesOverTheBox) {
  const Hexapod hexapod(sample_machines::conventions_hexapod_design());
  EXPECT_NEAR(hexapod.enclosure_length(), hexapod.platform_rel_tcp().colwise().norm().mean(),
              1e-15);
  std::mt19937_64 engine(17);
  for (int trial = 0; trial < 60; ++trial) {
    const PoseBox box = random_box(engine, trial % 2 ? 0.002 : 0.03);
    IntervalJacobian J, plain;
    IntervalJacobianSlopes slopes;
    ASSERT_TRUE(hexapod.enclose_jacobian(box, J, &slopes));
    ASSERT_TRUE(hexapod.enclose_jacobian(box, plain));
    const double lo[6] = {box.position_lo(0), box.position_lo(1), box.position_lo(2),
                          box.theta.lo,       box.phi.lo,         box.gamma.lo};
    const double hi[6] = {box.position_hi(0), box.position_hi(1), box.position_hi(2),
                          box.theta.hi,       box.phi.hi,         box.gamma.hi};
    for (int k = 0; k < 10; ++k) {
      double x[6];
      for (int c = 0; c < 6; ++c) x[c] = random_in(engine, lo[c], hi[c]);
      const auto M = jc(hexapod, box, x);
      for (int r = 0; r < 6; ++r)
        for (int c = 0; c < 6; ++c) {
          EXPECT_TRUE(J[r][c].contains(M(r, c))) << trial;
          EXPECT_TRUE(plain[r][c].contains(M(r, c))) << trial;
        }
      for (int d = 0; d < 6; ++d) {
        const double h = 1e-6;
        double up[6], down[6];
        for (int c = 0; c < 6; ++c) up[c] = down[c] = x[c];
        up[d] += h;
        down[d] -= h;
        const auto D = (jc(hexapod, box, up) - jc(hexapod, box, down)) / (2 * h);
        for (int r = 0; r < 6; ++r)
          for (int c = 0; c < 6; ++c) {
            EXPECT_LE(slopes[d][r][c].lo, D(r, c) + 1e-8) << trial << " d" << d;
            EXPECT_GE(slopes[d][r][c].hi, D(r, c) - 1e-8) << trial << " d" << d;
          }
      }
    }
  }
}

TEST(HexapodEnclosure, ABoxOfOnePoseGivesItsJacobian) {
  const Hexapod hexapod(sample_machines::conventions_hexapod_design());
  PoseBox box;
  box.position_lo = box.position_hi = Eigen::Vector3d(0.05, -0.02, 0.9);
  box.theta = 0.1;
  box.phi = 2.0;
  box.gamma = 0.3;
  IntervalJacobian J;
  ASSERT_TRUE(hexapod.enclose_jacobian(box, J));
  const double x[6] = {0.05, -0.02, 0.9, 0.1, 2.0, 0.3};
  const auto M = jc(hexapod, box, x);
  for (int r = 0; r < 6; ++r)
    for (int c = 0; c < 6; ++c) {
      EXPECT_TRUE(J[r][c].contains(M(r, c)));
      EXPECT_LT(J[r][c].width(), 1e-13);
    }
}

TEST(HexapodEnclosure, ALegOfLengthZeroIsRefused) {
  const Hexapod hexapod(sample_machines::conventions_hexapod_design());
  // The TCP placed so that platform joint 1 sits on base joint 1.
  PoseBox box;
  const Eigen::Vector3d p = hexapod.design().base_joints.col(0) - hexapod.platform_rel_tcp().col(0);
  box.position_lo = p - Eigen::Vector3d::Constant(1e-3);
  box.position_hi = p + Eigen::Vector3d::Constant(1e-3);
  IntervalJacobian J;
  EXPECT_FALSE(hexapod.enclose_jacobian(box, J));
}

}  // namespace
}  // namespace pkmopt
