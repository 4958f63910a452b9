// Tests of models/geometry/leg_interference on hexapods: a pose where two known legs touch (two
// legs turned into each other by a yaw, the touching clearance found by bisection agrees with the
// capsules' geometry computed here), the clearance against brute-force sampling of the legs'
// surfaces' axes, the cylinder-and-rod form, reachability with min_clearance, the
// SIMD batch path against the scalar one, and the validation of the shape.
#include "models/geometry/leg_interference.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>
#include <vector>

#include "models/hexapod/hexapod.hpp"
#include "models/hexapod/hexapod_batch.hpp"
#include "tests/sample_machines.hpp"

namespace pkmopt {
namespace {

using sample_machines::Uniform;

// The legs' axes sampled at 400 points each: the smallest distance between two legs' axes.
double sampled_axis_distance(const Eigen::Vector3d& a0, const Eigen::Vector3d& a1,
                             const Eigen::Vector3d& b0, const Eigen::Vector3d& b1) {
  double best = std::numeric_limits<double>::infinity();
  const int n = 400;
  for (int i = 0; i <= n; ++i) {
    const Eigen::Vector3d p = a0 + (a1 - a0) * (double(i) / n);
    for (int j = 0; j <= n; ++j)
      best = std::min(best, (p - (b0 + (b1 - b0) * (double(j) / n))).norm());
  }
  return best;
}

// The platform joints of a hexapod at a pose, base axes.
Eigen::Matrix<double, 3, 6> platform_points(const Hexapod& h, const Pose& pose) {
  const Eigen::Matrix3d R = rotation_zyx<double>(pose.angles);
  Eigen::Matrix<double, 3, 6> P;
  for (int i = 0; i < 6; ++i) P.col(i) = pose.position + R * h.platform_rel_tcp().col(i);
  return P;
}

TEST(LegInterference, ClearanceIsTheSmallestGapBetweenLegSurfaces) {
  Uniform u(5);
  for (int g = 0; g < 20; ++g) {
    HexapodDesign design = sample_machines::random_hexapod_design(u);
    design.leg_shape.diameter = u(0.02, 0.1);
    const Hexapod hexapod(design);
    const Pose pose = sample_machines::random_pose(u);
    const Clearance c = hexapod.leg_clearance(pose);
    const Eigen::Matrix<double, 3, 6> P = platform_points(hexapod, pose);
    double best = std::numeric_limits<double>::infinity();
    int first = -1, second = -1;
    for (int i = 0; i < 6; ++i) {
      for (int j = i + 1; j < 6; ++j) {
        const double d = sampled_axis_distance(design.base_joints.col(i), P.col(i),
                                               design.base_joints.col(j), P.col(j)) -
                         design.leg_shape.diameter;
        if (d < best) {
          best = d;
          first = i;
          second = j;
        }
      }
    }
    // Sampling at 1/400 of a leg can only overestimate the gap, by at most a sample step.
    EXPECT_LE(c.value, best + 1e-12) << g;
    EXPECT_NEAR(c.value, best, 2e-3) << g;
    if (best - c.value < 1e-6) {
      EXPECT_EQ(c.first, first);
      EXPECT_EQ(c.second, second);
    }
  }
}

// Two legs turned into each other: the sample hexapod of docs/conventions.md with 80 mm legs (and
// no joint limits) has a positive clearance at home; a yaw of 120 degrees crosses legs (near 92
// degrees the platform joints of legs 1 and 6 pass those of other legs). At the yaw where the
// clearance is 0 (bisection), the closest legs' axes are one diameter apart (sampled here).
TEST(LegInterference, YawTurnsTwoLegsIntoEachOther) {
  HexapodDesign design = sample_machines::conventions_hexapod_design();
  design.leg_shape.diameter = 0.08;
  design.joints = HexapodJointLimits{};
  design.max_length = 1.4;  // a yaw of 90 degrees needs 1.28 m
  const Hexapod hexapod(design);
  const Pose home{{0, 0, 0.9}, {0, 0, 0}};
  const Clearance at_home = hexapod.leg_clearance(home);
  ASSERT_GT(at_home.value, 0.0);
  // Find the yaw where the clearance crosses 0 (bisection on 0..60 degrees).
  double lo = 0.0, hi = deg_to_rad(120.0);
  ASSERT_LT(hexapod.leg_clearance(Pose{home.position, {0, 0, hi}}).value, 0.0);
  for (int k = 0; k < 60; ++k) {
    const double mid = 0.5 * (lo + hi);
    (hexapod.leg_clearance(Pose{home.position, {0, 0, mid}}).value > 0.0 ? lo : hi) = mid;
  }
  const Pose touching{home.position, {0, 0, lo}};
  const Clearance c = hexapod.leg_clearance(touching);
  EXPECT_NEAR(c.value, 0.0, 1e-9);
  const Eigen::Matrix<double, 3, 6> P = platform_points(hexapod, touching);
  const double axes = sampled_axis_distance(design.base_joints.col(c.first), P.col(c.first),
                                            design.base_joints.col(c.second), P.col(c.second));
  EXPECT_NEAR(axes, 0.08, 1e-4);
  EXPECT_GT(rad_to_deg(lo), 85.0);
  EXPECT_LT(rad_to_deg(lo), 95.0);
  // Reachability (the legs' lengths stay within their stroke here): at the touching yaw with
  // min_clearance 0 the pose is on the edge; a little further it is unreachable; asking for 5 mm
  // makes a smaller yaw unreachable too.
  auto data = hexapod.make_data();
  EXPECT_FALSE(hexapod.reachable(*data, Pose{home.position, {0, 0, lo + 1e-3}}));
  PoseMetrics m;
  hexapod.analyze(*data, Pose{home.position, {0, 0, lo + 1e-3}}, Wrench::Zero(), m);
  EXPECT_FALSE(m.reachable);
  EXPECT_LT(m.leg_clearance, 0.0);
  HexapodDesign careful = design;
  careful.min_clearance = 0.005;
  const Hexapod careful_hexapod(careful);
  const Pose near{home.position, {0, 0, lo - 1e-3}};
  EXPECT_TRUE(hexapod.reachable(*data, near));
  EXPECT_FALSE(careful_hexapod.reachable(*careful_hexapod.make_data(), near));
  // Without a shape nothing is checked.
  const Hexapod bare(sample_machines::conventions_hexapod_design());
  EXPECT_EQ(bare.leg_clearance(touching).value, std::numeric_limits<double>::infinity());
  EXPECT_FALSE(bare.checks_leg_interference());
}

// Cylinder and rod: a fat cylinder near the base and a thin rod near the platform. Legs whose
// platform joints are close but whose base joints are far apart collide only through their rods
// near the platform, where the rods are thinner than a one-capsule leg of the cylinder's size.
TEST(LegInterference, CylinderAndRodBodies) {
  LegShape shape;
  shape.cylinder_diameter = 0.1;
  shape.cylinder_length = 0.5;
  shape.rod_diameter = 0.04;
  Capsule bodies[2];
  ASSERT_EQ(leg_bodies(shape, {0, 0, 0}, {0, 0, 1}, 3, bodies), 2);
  EXPECT_EQ(bodies[0].b, Eigen::Vector3d(0, 0, 0.5));
  EXPECT_EQ(bodies[1].a, Eigen::Vector3d(0, 0, 1));
  EXPECT_EQ(bodies[1].b, Eigen::Vector3d(0, 0, 0.5));
  EXPECT_EQ(bodies[0].radius, 0.05);
  EXPECT_EQ(bodies[1].radius, 0.02);
  EXPECT_EQ(bodies[1].leg, 3);
  // A leg shorter than its cylinder: the cylinder ends at the platform joint.
  ASSERT_EQ(leg_bodies(shape, {0, 0, 0}, {0, 0, 0.3}, 0, bodies), 2);
  EXPECT_EQ(bodies[0].b, Eigen::Vector3d(0, 0, 0.3));
  // Two legs from (±0.5, 0, 0) to (±0.03, 0, 1): the rods (r = 0.02) at the top are
  // 0.06 - 0.04 = 0.02 apart, the cylinders far apart.
  const std::vector<Capsule> legs =
      leg_capsules(shape, (Eigen::Matrix3Xd(3, 2) << 0.5, -0.5, 0, 0, 0, 0).finished(),
                   (Eigen::Matrix3Xd(3, 2) << 0.03, -0.03, 0, 0, 1, 1).finished());
  ASSERT_EQ(legs.size(), 4u);
  const Clearance c = leg_clearance(legs);
  EXPECT_NEAR(c.value, 0.02, 1e-12);
  EXPECT_EQ(clearance_pair_text(c.first, c.second), "1-2");
  // One capsule of the cylinder's diameter would intersect.
  LegShape fat;
  fat.diameter = 0.1;
  EXPECT_LT(
      leg_clearance(leg_capsules(fat, (Eigen::Matrix3Xd(3, 2) << 0.5, -0.5, 0, 0, 0, 0).finished(),
                                 (Eigen::Matrix3Xd(3, 2) << 0.03, -0.03, 0, 0, 1, 1).finished()))
          .value,
      0.0);
  EXPECT_EQ(clearance_pair_text(-1, -1), "");
}

TEST(LegInterference, BatchPathAgreesWithTheScalarPath) {
  Uniform u(11);
  int intersecting = 0;
  for (int g = 0; g < 10; ++g) {
    HexapodDesign design = sample_machines::random_hexapod_design(u);
    if (g % 2 == 0) {
      design.leg_shape.diameter = u(0.03, 0.12);
    } else {  // cylinder and rod
      design.leg_shape.cylinder_diameter = u(0.05, 0.12);
      design.leg_shape.cylinder_length = u(0.3, 0.8);
      design.leg_shape.rod_diameter = u(0.02, 0.05);
    }
    design.min_clearance = u(0.0, 0.01);
    const Hexapod hexapod(design);
    std::vector<Pose> poses;
    for (int k = 0; k < 37; ++k) poses.push_back(sample_machines::random_pose(u));
    std::vector<PoseMetrics> batch(poses.size());
    analyze_hexapod_batch(hexapod, poses.data(), poses.size(), Wrench::Zero(), batch.data());
    HexapodData data(hexapod);
    for (std::size_t k = 0; k < poses.size(); ++k) {
      if (batch[k].leg_clearance < 0.0) ++intersecting;
      PoseMetrics m;
      hexapod.analyze(data, poses[k], Wrench::Zero(), m);
      // The same formulas without branches (and with FMA in the AVX2 kernel): equal to
      // rounding; the pair and the verdict equal unless the values tie to rounding.
      EXPECT_NEAR(batch[k].leg_clearance, m.leg_clearance, 1e-12) << g << " " << k;
      if (std::abs(m.leg_clearance - design.min_clearance) > 1e-12) {
        EXPECT_EQ(batch[k].reachable, m.reachable) << g << " " << k;
      }
      if (batch[k].clearance_first != m.clearance_first ||
          batch[k].clearance_second != m.clearance_second) {
        // Another pair only at a tie: its gap in the scalar model equals the minimum.
        const Eigen::Matrix<double, 3, 6> P = platform_points(hexapod, poses[k]);
        const int i = batch[k].clearance_first, j = batch[k].clearance_second;
        Eigen::Matrix3Xd a(3, 2), p(3, 2);
        a << design.base_joints.col(i), design.base_joints.col(j);
        p << P.col(i), P.col(j);
        EXPECT_NEAR(leg_clearance(leg_capsules(design.leg_shape, a, p)).value, m.leg_clearance,
                    1e-12)
            << g << " " << k;
      }
    }
  }
  EXPECT_GT(intersecting, 20);  // the test sees colliding poses too
}

// legs_apart (the bounding-box shortcut of reachable) decides as the full clearance does, on
// random designs, shapes, poses and min_clearance values, both near and far from the threshold.
TEST(LegInterference, LegsApartAgreesWithTheClearance) {
  Uniform u(17);
  int apart = 0, close = 0;
  for (int g = 0; g < 200; ++g) {
    HexapodDesign design = sample_machines::random_hexapod_design(u);
    LegShape shape;
    if (g % 2 == 0) {
      shape.diameter = u(0.03, 0.15);
    } else {
      shape.cylinder_diameter = u(0.05, 0.15);
      shape.cylinder_length = u(0.3, 0.8);
      shape.rod_diameter = u(0.02, 0.05);
    }
    const Pose pose = sample_machines::random_pose(u);
    const Eigen::Matrix3d R = rotation_zyx<double>(pose.angles);
    Eigen::Matrix3Xd a(3, 6), p(3, 6);
    for (int i = 0; i < 6; ++i) {
      a.col(i) = design.base_joints.col(i);
      p.col(i) = pose.position + R * (design.platform_joints.col(i) - design.tcp);
    }
    const std::vector<Capsule> bodies = leg_capsules(shape, a, p);
    const double clearance = leg_clearance(bodies).value;
    for (const double min_clearance : {0.0, u(0.0, 0.05), std::max(0.0, clearance)}) {
      if (std::abs(clearance - min_clearance) < 1e-12 && min_clearance != clearance) continue;
      EXPECT_EQ(legs_apart(bodies, min_clearance), clearance >= min_clearance)
          << g << " " << clearance << " " << min_clearance;
      (clearance >= min_clearance ? apart : close)++;
    }
  }
  EXPECT_GT(apart, 50);
  EXPECT_GT(close, 50);
}

TEST(LegInterference, ShapeIsValidated) {
  auto refused = [](LegShape s, double min_clearance) {
    try {
      check_leg_shape(s, min_clearance);
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_EQ(refused(LegShape{.diameter = 0.08}, 0.0), "");
  EXPECT_NE(refused(LegShape{.diameter = -1}, 0.0).find("legs.diameter"), std::string::npos);
  EXPECT_NE(
      refused(LegShape{.diameter = 0.08, .cylinder_diameter = 0.1, .cylinder_length = 0.5}, 0.0)
          .find("not both"),
      std::string::npos);
  EXPECT_NE(refused(LegShape{.cylinder_diameter = 0.1}, 0.0).find("both diameter and length"),
            std::string::npos);
  EXPECT_NE(refused(LegShape{.rod_diameter = 0.04}, 0.0).find("legs.rod needs"), std::string::npos);
  EXPECT_NE(refused(LegShape{.diameter = std::nan("")}, 0.0).find("legs.diameter"),
            std::string::npos);
  EXPECT_NE(refused(LegShape{.diameter = 0.08}, -0.001).find("min_clearance"), std::string::npos);
  HexapodDesign design = sample_machines::conventions_hexapod_design();
  design.leg_shape.cylinder_diameter = 0.1;
  EXPECT_THROW(Hexapod{design}, std::invalid_argument);
}

}  // namespace
}  // namespace pkmopt
