// Tests of models/hexapod/swept_envelope: the hull of a hexapod at one pose with its platform
// parallel to the base is a prismatoid, V = h/6 (A_base + A_platform + 4 A_mid) with A_mid the area
// of the hull of the joints' pairwise midpoints (all areas by a gift-wrapping hull written here);
// the footprint is the area of the joints' projected hull; solids enlarge both as their outlines
// say.
#include "models/hexapod/swept_envelope.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include "tests/sample_machines.hpp"

namespace pkmopt {
namespace {

// Area of the convex hull of 2D points: gift wrapping, then the shoelace formula.
double hull_area(std::vector<Eigen::Vector2d> pts) {
  std::sort(pts.begin(), pts.end(), [](const auto& a, const auto& b) {
    return a.x() < b.x() || (a.x() == b.x() && a.y() < b.y());
  });
  std::vector<Eigen::Vector2d> hull;
  const Eigen::Vector2d start = pts.front();
  Eigen::Vector2d current = start;
  do {
    hull.push_back(current);
    Eigen::Vector2d next = pts[0] == current ? pts[1] : pts[0];
    for (const auto& q : pts) {
      const Eigen::Vector2d u = next - current, v = q - current;
      const double cross = u.x() * v.y() - u.y() * v.x();
      if (cross < -1e-15 || (std::abs(cross) <= 1e-15 && v.norm() > u.norm())) next = q;
    }
    current = next;
  } while (current != start && hull.size() <= pts.size());
  double area = 0.0;
  for (std::size_t i = 0; i < hull.size(); ++i) {
    const Eigen::Vector2d& a = hull[i];
    const Eigen::Vector2d& b = hull[(i + 1) % hull.size()];
    area += a.x() * b.y() - a.y() * b.x();
  }
  return std::abs(area) / 2.0;
}

TEST(SweptEnvelope, OnePoseIsAPrismatoid) {
  for (const double yaw_deg : {0.0, 25.0}) {
    const Hexapod hexapod(sample_machines::conventions_hexapod_design());
    const HexapodDesign& d = hexapod.design();
    const Pose pose{{0.05, -0.03, 0.8}, {0, 0, deg_to_rad(yaw_deg)}};
    const SweptEnvelope e = swept_envelope(hexapod, {pose});
    const Eigen::Matrix3d R = rotation_zyx<double>(pose.angles);
    std::vector<Eigen::Vector2d> base, platform, mid, all;
    std::vector<Eigen::Vector3d> top;
    for (int i = 0; i < 6; ++i) {
      base.push_back(d.base_joints.col(i).head<2>());
      top.push_back(pose.position + R * (d.platform_joints.col(i) - d.tcp));
      platform.push_back(top.back().head<2>());
    }
    for (const auto& a : base)
      for (const auto& b : platform) mid.push_back(0.5 * (a + b));
    all = base;
    all.insert(all.end(), platform.begin(), platform.end());
    const double h = top[0].z() - d.base_joints(2, 0);
    ASSERT_NEAR(top[3].z(), top[0].z(), 1e-12);  // the platform joints lie in one plane
    const double expected =
        h / 6.0 * (hull_area(base) + hull_area(platform) + 4.0 * hull_area(mid));
    EXPECT_NEAR(e.volume, expected, 1e-12 * expected) << yaw_deg;
    EXPECT_NEAR(e.footprint, hull_area(all), 1e-12) << yaw_deg;
  }
}

TEST(SweptEnvelope, MorePosesAndSolidsOnlyAdd) {
  HexapodDesign design = sample_machines::conventions_hexapod_design();
  const Hexapod bare(design);
  const Pose home{{0, 0, 0.8}, Eigen::Vector3d::Zero()};
  const Pose tilted{{0.1, 0, 0.9}, deg_to_rad(Eigen::Vector3d(10, -5, 20))};
  const SweptEnvelope one = swept_envelope(bare, {home});
  const SweptEnvelope two = swept_envelope(bare, {home, tilted});
  EXPECT_GT(two.volume, one.volume);
  EXPECT_GE(two.footprint, one.footprint);
  // A base disc of radius 0.9 beyond the joints: the footprint is its circumscribed 32-gon.
  design.leg_shape.cylinder_diameter = 0.08;  // rods for the base plate to see
  design.leg_shape.cylinder_length = 0.5;
  design.leg_shape.rod_diameter = 0.05;
  design.bodies.base.radius = 0.9;
  design.bodies.base.z_min = -0.05;
  const Hexapod based(design);
  const SweptEnvelope b = swept_envelope(based, {home});
  const double n = 32, polygon = n * 0.9 * 0.9 * std::tan(std::numbers::pi / n);
  EXPECT_NEAR(b.footprint, polygon, 1e-9);
  EXPECT_GT(b.footprint, std::numbers::pi * 0.9 * 0.9);
  EXPECT_GT(b.volume, one.volume);
}

}  // namespace
}  // namespace pkmopt
