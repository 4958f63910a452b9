// Tests of models/geometry/joint_layout: the semi-regular hexagon of docs/conventions.md, joint by
// joint against the angles written out by hand.
#include "models/geometry/joint_layout.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "models/core/pose.hpp"

namespace pkmopt {
namespace {

TEST(JointLayout, SemiRegularJointAnglesFollowConventions) {
  const auto base = semi_regular_base_joints(0.6, deg_to_rad(20));
  const auto platform = semi_regular_platform_joints(0.25, deg_to_rad(30));
  const double base_deg[6] = {-10, 10, 110, 130, 230, 250};
  const double platform_deg[6] = {-45, 45, 75, 165, 195, 285};
  for (int i = 0; i < 6; ++i) {
    EXPECT_NEAR(base(0, i), 0.6 * std::cos(deg_to_rad(base_deg[i])), 1e-15);
    EXPECT_NEAR(base(1, i), 0.6 * std::sin(deg_to_rad(base_deg[i])), 1e-15);
    EXPECT_EQ(base(2, i), 0.0);
    EXPECT_NEAR(platform(0, i), 0.25 * std::cos(deg_to_rad(platform_deg[i])), 1e-15);
    EXPECT_NEAR(platform(1, i), 0.25 * std::sin(deg_to_rad(platform_deg[i])), 1e-15);
  }
}

}  // namespace
}  // namespace pkmopt
