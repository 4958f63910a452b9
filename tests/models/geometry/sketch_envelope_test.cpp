// The space a drawn machine takes over poses (models/geometry/sketch_envelope.hpp), checked
// against the drawing itself: every drawn point inside the hull's box, the TCP's square inside
// the footprint, more poses never less space, and the linear delta's envelope by hand.
#include "models/geometry/sketch_envelope.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <optional>
#include <vector>

#include "models/core/machine_sketch.hpp"
#include "models/leg_chain/leg_chain.hpp"

namespace pkmopt {
namespace {

std::vector<Pose> square_poses(double z, double half) {
  std::vector<Pose> poses;
  for (double x : {-half, half})
    for (double y : {-half, half}) {
      Pose p;
      p.position = {x, y, z};
      poses.push_back(p);
    }
  return poses;
}

TEST(SketchEnvelope, HoldsTheDrawingAndGrowsWithThePoses) {
  const std::unique_ptr<Machine> delta = make_linear_delta(LinearDeltaDesign{});
  // Poses the default linear delta reaches (its TCP 0.05 m around the centre).
  const auto data = delta->make_data();
  double z = 10.0;
  for (double c = 1.0; c > -1.0; c -= 0.01) {
    bool all = true;
    for (const Pose& p : square_poses(c, 0.05)) all = all && delta->reachable(*data, p);
    if (all) {
      z = c;
      break;
    }
  }
  ASSERT_LT(z, 5.0) << "no reachable square found";
  const std::vector<Pose> four = square_poses(z, 0.05);
  const SketchEnvelope e = sketch_envelope(*delta, four);
  EXPECT_EQ(e.drawn, 4u);
  // The TCP alone spans the 0.1 x 0.1 m square: the footprint holds it.
  EXPECT_GE(e.footprint, 0.01 - 1e-12);
  // The hull is inside the box of the drawn points, and at least as large as the TCP's square
  // swept along the drawn z extent would be zero: check against the box of every drawn point.
  Eigen::AlignedBox3d box;
  for (const Pose& p : four) {
    MachineSketch s;
    ASSERT_TRUE(delta->sketch(*data, p, s));
    for (const auto& line : s.lines) {
      box.extend(line.from);
      box.extend(line.to);
    }
    box.extend(s.tcp);
  }
  EXPECT_GT(e.volume, 0.0);
  EXPECT_LE(e.volume, box.volume() + 1e-12);
  EXPECT_LE(e.footprint, box.sizes().x() * box.sizes().y() + 1e-12);
  // The guide feet are drawn: the footprint holds the triangle of the three guides (radius r):
  // (3 sqrt(3) / 4) r^2.
  const double r = LinearDeltaDesign{}.guide_radius;
  EXPECT_GE(e.footprint, 3.0 * std::sqrt(3.0) / 4.0 * r * r - 1e-9);
  // More poses never take less space; the same poses twice take the same.
  std::vector<Pose> more = four;
  for (const Pose& p : square_poses(z - 0.01, 0.05)) more.push_back(p);
  const SketchEnvelope bigger = sketch_envelope(*delta, more);
  EXPECT_GE(bigger.volume, e.volume - 1e-12);
  EXPECT_GE(bigger.footprint, e.footprint - 1e-12);
  std::vector<Pose> twice = four;
  twice.insert(twice.end(), four.begin(), four.end());
  EXPECT_NEAR(sketch_envelope(*delta, twice).volume, e.volume, 1e-12);
  // No poses: no points, no space.
  const SketchEnvelope none = sketch_envelope(*delta, {});
  EXPECT_EQ(none.drawn, 0u);
  EXPECT_EQ(none.volume, 0.0);
  EXPECT_EQ(none.footprint, 0.0);
}

// sketch_excess: the drawing's farthest point outside a box or cylinder, by hand from the drawn
// points (the TCP, joints and line ends); <= 0 when it is inside; nullopt where the model cannot
// draw (a pose far outside its reach, where a rod cannot close).
TEST(SketchEnvelope, ExcessIsTheFarthestDrawnPointOutside) {
  const std::unique_ptr<Machine> delta = make_linear_delta(LinearDeltaDesign{});
  const auto data = delta->make_data();
  Pose pose;
  pose.position = {0.02, -0.03, 0.2};
  MachineSketch s;
  ASSERT_TRUE(delta->sketch(*data, pose, s));
  std::vector<Eigen::Vector3d> points = {s.tcp};
  for (const auto& line : s.lines) {
    points.push_back(line.from);
    points.push_back(line.to);
  }
  for (const auto& p : s.base_joints) points.push_back(p);
  for (const auto& p : s.platform_joints) points.push_back(p);
  InstallationSpace cylinder;
  cylinder.kind = InstallationSpace::Kind::kCylinder;
  cylinder.radius = 0.2;
  cylinder.z_min = 0.25;
  cylinder.z_max = 2.0;
  double expected = -1e9;
  for (const auto& p : points)
    expected = std::max({expected, p.head<2>().norm() - 0.2, 0.25 - p.z(), p.z() - 2.0});
  const std::optional<double> excess = sketch_excess(*delta, *data, pose, cylinder);
  ASSERT_TRUE(excess.has_value());
  EXPECT_NEAR(*excess, expected, 1e-12);
  EXPECT_GT(*excess, 0.0);  // the guides stand at 0.25 m from the axis
  cylinder.radius = 5.0;
  cylinder.z_min = -5.0;
  cylinder.z_max = 5.0;
  EXPECT_LE(*sketch_excess(*delta, *data, pose, cylinder), 0.0);
  pose.position = {3.0, 0.0, 0.2};
  EXPECT_FALSE(sketch_excess(*delta, *data, pose, cylinder).has_value());
}

// The intrusion into obstacles is the deepest drawn line (not the tool's) or joint, recomputed
// here from the drawing; the tool may reach into an obstacle.
TEST(SketchEnvelope, IntrusionIsTheDeepestDrawnLineOrJointButTheTool) {
  const std::unique_ptr<Machine> delta = make_linear_delta(LinearDeltaDesign{});
  const auto data = delta->make_data();
  Pose pose;
  pose.position = {0.02, -0.03, 0.2};
  MachineSketch s;
  ASSERT_TRUE(delta->sketch(*data, pose, s));
  // A box around the first guide's lower half and a box around the TCP only.
  const MachineSketch::Line* guide = nullptr;
  const MachineSketch::Line* tool = nullptr;
  for (const auto& line : s.lines) {
    if (line.part == MachineSketch::Part::kGuide && guide == nullptr) guide = &line;
    if (line.part == MachineSketch::Part::kTool) tool = &line;
  }
  ASSERT_NE(guide, nullptr);
  const Eigen::Vector3d mid = 0.5 * (guide->from + guide->to);
  const ObstacleBox column{mid - Eigen::Vector3d(0.03, 0.03, 0.05),
                           mid + Eigen::Vector3d(0.03, 0.03, 0.05)};
  double expected = -1e9;
  for (const auto& line : s.lines)
    if (line.part != MachineSketch::Part::kTool)
      expected = std::max(expected, intrusion(column, line.from, line.to));
  for (const auto& p : s.base_joints) expected = std::max(expected, depth(column, p));
  for (const auto& p : s.platform_joints) expected = std::max(expected, depth(column, p));
  const std::optional<double> in = sketch_intrusion(*delta, *data, pose, {column});
  ASSERT_TRUE(in.has_value());
  EXPECT_NEAR(*in, expected, 1e-12);
  EXPECT_NEAR(*in, 0.03, 1e-12);  // the guide runs through the column's middle
  if (tool != nullptr) {
    const ObstacleBox at_tcp{s.tcp - Eigen::Vector3d::Constant(0.005),
                             s.tcp + Eigen::Vector3d::Constant(0.005)};
    EXPECT_LE(*sketch_intrusion(*delta, *data, pose, {at_tcp}), 0.0);
  }
  EXPECT_FALSE(sketch_intrusion(*delta, *data, pose, {}).has_value());
}

}  // namespace
}  // namespace pkmopt
