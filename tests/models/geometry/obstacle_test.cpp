// Obstacle boxes (models/geometry/obstacle.hpp): a point's depth by hand, and a segment's
// intrusion against a dense sampling of the segment (the exact maximum of a concave function
// is never below the samples and within the sampling step's change of them).
#include "models/geometry/obstacle.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "tests/sample_machines.hpp"

namespace pkmopt {
namespace {

TEST(Obstacle, DepthIsTheDistanceToTheNearestFaceInside) {
  const ObstacleBox box{{-0.2, -0.1, 0.0}, {0.2, 0.3, 0.5}};
  EXPECT_DOUBLE_EQ(depth(box, {0.0, 0.1, 0.25}), 0.2);    // x and y faces 0.2 away
  EXPECT_DOUBLE_EQ(depth(box, {0.15, 0.1, 0.25}), 0.05);  // the +x face
  EXPECT_DOUBLE_EQ(depth(box, {0.3, 0.1, 0.25}), -0.1);   // outside by 0.1 along x
  EXPECT_DOUBLE_EQ(depth(box, {0.2, 0.1, 0.25}), 0.0);    // on a face
}

TEST(Obstacle, IntrusionIsTheDeepestPointOfTheSegment) {
  const ObstacleBox box{{-0.2, -0.1, 0.0}, {0.2, 0.3, 0.5}};
  // Straight through the middle along x: the centre line's depth, min(0.2, 0.25).
  EXPECT_DOUBLE_EQ(intrusion(box, {-1.0, 0.1, 0.25}, {1.0, 0.1, 0.25}), 0.2);
  // Past the box: negative.
  EXPECT_LT(intrusion(box, {-1.0, 0.5, 0.25}, {1.0, 0.5, 0.25}), 0.0);
  // A diagonal: against dense sampling, for random boxes and segments.
  sample_machines::Uniform u(17);
  for (int k = 0; k < 400; ++k) {
    ObstacleBox b;
    for (int a = 0; a < 3; ++a) {
      const double c = u(-0.5, 0.5), h = u(0.05, 0.4);
      b.min(a) = c - h;
      b.max(a) = c + h;
    }
    const Eigen::Vector3d p(u(-1, 1), u(-1, 1), u(-1, 1)), q(u(-1, 1), u(-1, 1), u(-1, 1));
    const double exact = intrusion(b, p, q);
    double sampled = -std::numeric_limits<double>::infinity();
    constexpr int kSteps = 20000;
    for (int i = 0; i <= kSteps; ++i)
      sampled = std::max(sampled, depth(b, p + (q - p) * (static_cast<double>(i) / kSteps)));
    EXPECT_GE(exact, sampled - 1e-12) << k;
    EXPECT_LE(exact, sampled + (q - p).norm() / kSteps + 1e-12) << k;
  }
}

TEST(Obstacle, CheckNamesAnEmptyOrNonFiniteBox) {
  EXPECT_NO_THROW(check_obstacle({{0, 0, 0}, {1, 1, 1}}));
  EXPECT_THROW(check_obstacle({{0, 0, 0}, {1, 0, 1}}), std::invalid_argument);
  EXPECT_THROW(check_obstacle({{0, 0, std::nan("")}, {1, 1, 1}}), std::invalid_argument);
}

}  // namespace
}  // namespace pkmopt
