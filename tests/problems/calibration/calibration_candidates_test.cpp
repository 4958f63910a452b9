// Candidate poses for calibration (problems/calibration/calibration_candidates.hpp) on the
// docs/conventions.md hexapod, whose TCP reaches z = 0.9 m (x, y within 5 cm, angles within 2 deg)
// but not z = 5 m; with leg diameters, poses where legs collide are no candidates.
#include "problems/calibration/calibration_candidates.hpp"

#include <gtest/gtest.h>

#include <stdexcept>

#include "models/hexapod/hexapod.hpp"
#include "models/sample_machines.hpp"

namespace {

using pkmopt::Pose;

const pkmopt::Hexapod& hexapod() {
  static const pkmopt::Hexapod h(pkmopt::sample_machines::conventions_hexapod_design());
  return h;
}

Pose at(double x, double y, double z) {
  Pose p;
  p.position = {x, y, z};
  return p;
}

TEST(ReachableCandidates, KeepsReachablePosesWithTheirLabels) {
  const auto c = pkmopt::reachable_candidates(
      hexapod(), {at(0, 0, 0.9), at(0, 0, 5.0), at(0.05, 0, 0.85), at(0, 0, -1.0)}, {4, 5, 6, 7});
  ASSERT_EQ(c.poses.size(), 2u);
  EXPECT_EQ(c.poses[0].position, at(0, 0, 0.9).position);
  EXPECT_EQ(c.poses[1].position, at(0.05, 0, 0.85).position);
  EXPECT_EQ(c.labels, (std::vector<int>{4, 6}));
  EXPECT_EQ(c.unreachable, 2);
}

TEST(ReachableCandidates, OneLabelPerPose) {
  EXPECT_THROW(pkmopt::reachable_candidates(hexapod(), {at(0, 0, 0.9)}, {}), std::invalid_argument);
}

// Legs of 80 mm (no joint limits, long stroke): a pose turned by 100 degrees about z, where legs
// cross, is no candidate; the same pose with line legs is.
TEST(ReachableCandidates, PosesWhereLegsCollideAreDropped) {
  pkmopt::HexapodDesign design = pkmopt::sample_machines::conventions_hexapod_design();
  design.joints = pkmopt::HexapodJointLimits{};
  design.max_length = 1.4;
  Pose turned = at(0, 0, 0.9);
  turned.angles = {0, 0, pkmopt::deg_to_rad(100.0)};
  const pkmopt::Hexapod lines(design);
  EXPECT_EQ(pkmopt::reachable_candidates(lines, {at(0, 0, 0.9), turned}, {1, 2}).poses.size(), 2u);
  design.leg_shape.diameter = 0.08;
  const pkmopt::Hexapod legs(design);
  ASSERT_LT(legs.leg_clearance(turned).value, 0.0);
  const auto c = pkmopt::reachable_candidates(legs, {at(0, 0, 0.9), turned}, {1, 2});
  EXPECT_EQ(c.labels, (std::vector<int>{1}));
  EXPECT_EQ(c.unreachable, 1);
}

TEST(GridCandidates, OrderLevelsAndLabels) {
  pkmopt::CandidateGrid grid;
  grid.xy_range = 0.05;
  grid.z_min = 0.9;  // reachable everywhere on the grid
  grid.z_max = 5.0;  // reachable nowhere
  grid.angle_range = pkmopt::deg_to_rad(2.0);
  grid.steps = 2;
  const auto c = pkmopt::grid_candidates(hexapod(), grid);
  // 2^6 = 64 grid poses, the 32 at z = 5 m unreachable.
  ASSERT_EQ(c.poses.size(), 32u);
  EXPECT_EQ(c.unreachable, 32);
  const double a = pkmopt::deg_to_rad(2.0);
  for (int k = 0; k < 32; ++k) {
    // x slowest, then y, (z), rx, ry, rz fastest; levels -range and +range.
    const auto level = [](int bit, double range) { return bit ? range : -range; };
    const Pose& p = c.poses[static_cast<std::size_t>(k)];
    EXPECT_DOUBLE_EQ(p.position(0), level((k >> 4) & 1, 0.05)) << k;
    EXPECT_DOUBLE_EQ(p.position(1), level((k >> 3) & 1, 0.05)) << k;
    EXPECT_EQ(p.position(2), 0.9) << k;
    EXPECT_DOUBLE_EQ(p.angles(0), level((k >> 2) & 1, a)) << k;
    EXPECT_DOUBLE_EQ(p.angles(1), level((k >> 1) & 1, a)) << k;
    EXPECT_DOUBLE_EQ(p.angles(2), level(k & 1, a)) << k;
    EXPECT_EQ(c.labels[static_cast<std::size_t>(k)], k + 1);
  }
}

TEST(GridCandidates, ThreeLevelsIncludeTheMiddle) {
  pkmopt::CandidateGrid grid;
  grid.xy_range = 0.04;
  grid.z_min = 0.86;
  grid.z_max = 0.9;
  grid.angle_range = 0.0;
  grid.steps = 3;
  const auto c = pkmopt::grid_candidates(hexapod(), grid);
  ASSERT_EQ(c.poses.size() + static_cast<std::size_t>(c.unreachable), 729u);  // 3^6
  ASSERT_EQ(c.unreachable, 0);
  // Each (x, y, z) level holds 27 poses (rx, ry, rz levels, all 0 here), so the first pose at
  // ix = iy = iz = 1, the middle of the box, is number ((1 * 3 + 1) * 3 + 1) * 27.
  const Pose& middle = c.poses[static_cast<std::size_t>(((1 * 3 + 1) * 3 + 1) * 27)];
  EXPECT_DOUBLE_EQ(middle.position(0), 0.0);
  EXPECT_DOUBLE_EQ(middle.position(1), 0.0);
  EXPECT_DOUBLE_EQ(middle.position(2), 0.88);
}

TEST(GridCandidates, NeedsTwoLevels) {
  pkmopt::CandidateGrid grid;
  grid.steps = 1;
  EXPECT_THROW(pkmopt::grid_candidates(hexapod(), grid), std::invalid_argument);
}

}  // namespace
