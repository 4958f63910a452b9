// Tests of models/geometry/installation_space: the excess of balls and capsules over a box and a
// vertical cylinder against hand-computed values (inside negative, touching 0, outside positive),
// and the validation of the region.
#include "models/geometry/installation_space.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

namespace pkmopt {
namespace {

TEST(InstallationSpace, BoxExcessOfBallsAndCapsules) {
  InstallationSpace box;
  box.kind = InstallationSpace::Kind::kBox;
  box.min = {-1, -1, 0};
  box.max = {1, 1, 2};
  EXPECT_DOUBLE_EQ(box.excess({0, 0, 1}, 0.0), -1.0);     // the centre: 1 m from every face
  EXPECT_DOUBLE_EQ(box.excess({0.5, 0, 1}, 0.2), -0.3);   // x face: 1 - 0.5 - 0.2
  EXPECT_DOUBLE_EQ(box.excess({0.9, 0, 1}, 0.1), 0.0);    // touching
  EXPECT_DOUBLE_EQ(box.excess({0, 0, 2.25}, 0.0), 0.25);  // above the top by 0.25 m
  // A capsule is out by its worse end.
  const Capsule leg{{0, 0, 0.1}, {0, 1.05, 1.0}, 0.05, 0, true, true};
  EXPECT_NEAR(box.excess(leg), 0.1, 1e-15);
  EXPECT_FALSE(InstallationSpace{}.present());
  EXPECT_EQ(InstallationSpace{}.excess({5, 5, 5}, 1.0), -std::numeric_limits<double>::infinity());
}

TEST(InstallationSpace, CylinderExcessOfBalls) {
  InstallationSpace c;
  c.kind = InstallationSpace::Kind::kCylinder;
  c.centre = {0.1, 0};
  c.radius = 1.0;
  c.z_min = 0.0;
  c.z_max = 1.5;
  EXPECT_DOUBLE_EQ(c.excess({0.1, 0, 0.75}, 0.0), -0.75);  // on the axis: the ends are nearer
  EXPECT_NEAR(c.excess({0.1 + 0.6, 0.8, 0.75}, 0.1), 0.1, 1e-15);  // radius 1.0 + 0.1 - 1.0
  EXPECT_NEAR(c.excess({0.1, 0.0, -0.2}, 0.05), 0.25, 1e-15);      // below the floor
  EXPECT_NEAR(c.excess({0.1, 0.3, 1.45}, 0.05), 0.0, 1e-15);       // touching the top
}

TEST(InstallationSpace, RegionIsValidated) {
  InstallationSpace box;
  box.kind = InstallationSpace::Kind::kBox;
  box.min = {0, 0, 0};
  box.max = {1, 0, 1};
  EXPECT_THROW(check_installation_space(box), std::invalid_argument);
  box.max = {1, 1, 1};
  EXPECT_NO_THROW(check_installation_space(box));
  InstallationSpace c;
  c.kind = InstallationSpace::Kind::kCylinder;
  c.radius = 1.0;
  c.z_min = 1.0;
  c.z_max = 1.0;
  EXPECT_THROW(check_installation_space(c), std::invalid_argument);
  c.z_max = 2.0;
  c.radius = std::nan("");
  EXPECT_THROW(check_installation_space(c), std::invalid_argument);
}

}  // namespace
}  // namespace pkmopt
