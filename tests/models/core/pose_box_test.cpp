// Tests of models/core/pose_box: the rotation of a box is the header's matrix written out, it is
// a rotation, its interval enclosure holds it at random points of random boxes, and its
// derivatives (IntervalGradient) hold central differences.
#include "models/core/pose_box.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "models/core/pose.hpp"

namespace pkmopt {
namespace {

double random_in(std::mt19937_64& engine, const Interval& x) {
  return x.lo + std::uniform_real_distribution<double>(0.0, 1.0)(engine) * (x.hi - x.lo);
}

Interval random_angles(std::mt19937_64& engine, double centre_scale, double width) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const double c = centre_scale * u(engine), w = width * (0.5 + 0.5 * u(engine));
  return {c - w, c + w};
}

TEST(PoseBox, RotationIsTheHeadersMatrix) {
  const double theta = 0.3, phi = 1.1, gamma = -0.4;
  const double ct = std::cos(theta), st = std::sin(theta), c = std::cos(phi), s = std::sin(phi);
  Eigen::Matrix3d A;
  A << ct + (1 - ct) * c * c, (1 - ct) * c * s, st * s,  //
      (1 - ct) * c * s, ct + (1 - ct) * s * s, -st * c,  //
      -st * s, st * c, ct;
  Eigen::Matrix3d Rz;
  Rz << std::cos(gamma), -std::sin(gamma), 0, std::sin(gamma), std::cos(gamma), 0, 0, 0, 1;
  const Eigen::Matrix3d R0 = rotation_zyx<double>(Eigen::Vector3d(0.2, -0.1, 0.7));
  const Eigen::Matrix3d R = box_rotation(R0, theta, phi, gamma);
  EXPECT_LT((R - R0 * A * Rz).norm(), 1e-15);
  EXPECT_LT((R.transpose() * R - Eigen::Matrix3d::Identity()).norm(), 1e-15);
  // The tool axis is tilted by theta from R0's.
  EXPECT_NEAR(std::acos((R0.col(2)).dot(R.col(2))), theta, 1e-12);
  // The template at double gives the same.
  const auto T = box_rotation_of<double>(R0, theta, phi, gamma);
  for (int r = 0; r < 3; ++r)
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(T[r][k], R(r, k), 1e-15);
}

TEST(PoseBox, EnclosureHoldsTheRotationsOfTheBox) {
  std::mt19937_64 engine(5);
  for (int trial = 0; trial < 300; ++trial) {
    PoseBox box;
    box.R0 = rotation_zyx<double>(Eigen::Vector3d(0.3 * trial, -0.2, 0.1 * trial));
    box.theta = random_angles(engine, 1.0, 0.4);
    box.phi = random_angles(engine, 3.0, 1.0);
    box.gamma = random_angles(engine, 2.0, 0.5);
    const IntervalRotation E = enclose_rotation(box);
    for (int k = 0; k < 20; ++k) {
      const Eigen::Matrix3d R =
          box_rotation(box.R0, random_in(engine, box.theta), random_in(engine, box.phi),
                       random_in(engine, box.gamma));
      for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) EXPECT_TRUE(E[r][c].contains(R(r, c))) << trial;
    }
  }
  // A box of one rotation: the enclosure is that rotation, to a few dozen units in the last
  // place (each sine and cosine is widened by 1e-15).
  PoseBox point;
  point.theta = 0.2;
  point.phi = 0.9;
  point.gamma = -0.3;
  const IntervalRotation E = enclose_rotation(point);
  const Eigen::Matrix3d R = box_rotation(point.R0, 0.2, 0.9, -0.3);
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) {
      EXPECT_TRUE(E[r][c].contains(R(r, c)));
      EXPECT_LT(E[r][c].width(), 1e-13);
    }
}

TEST(PoseBox, DerivativesHoldCentralDifferences) {
  using G = IntervalGradient<3>;
  std::mt19937_64 engine(8);
  const Eigen::Matrix3d R0 = rotation_zyx<double>(Eigen::Vector3d(0.1, 0.2, 0.3));
  for (int trial = 0; trial < 100; ++trial) {
    const Interval theta = random_angles(engine, 0.5, 0.1), phi = random_angles(engine, 3.0, 0.2),
                   gamma = random_angles(engine, 1.0, 0.1);
    const auto R = box_rotation_of<G>(R0, G::coordinate(theta, 0), G::coordinate(phi, 1),
                                      G::coordinate(gamma, 2));
    for (int k = 0; k < 5; ++k) {
      double x[3] = {random_in(engine, theta), random_in(engine, phi), random_in(engine, gamma)};
      for (int c = 0; c < 3; ++c) {
        const double h = 1e-6;
        double up[3] = {x[0], x[1], x[2]}, down[3] = {x[0], x[1], x[2]};
        up[c] += h;
        down[c] -= h;
        const Eigen::Matrix3d D =
            (box_rotation(R0, up[0], up[1], up[2]) - box_rotation(R0, down[0], down[1], down[2])) /
            (2 * h);
        for (int r = 0; r < 3; ++r)
          for (int s = 0; s < 3; ++s) {
            EXPECT_LE(R[r][s].d[c].lo, D(r, s) + 1e-9);
            EXPECT_GE(R[r][s].d[c].hi, D(r, s) - 1e-9);
          }
      }
    }
  }
}

}  // namespace
}  // namespace pkmopt
