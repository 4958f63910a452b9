// Tests of models/geometry/segment_distance: the closest distance of two segments against
// brute-force sampling of both segments (a fine grid of parameter pairs, refined around its best
// pair), on random, parallel, collinear, crossing, touching and point-like segments; the returned
// parameters lie in [0, 1] and give the returned distance.
#include "models/geometry/segment_distance.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

namespace pkmopt {
namespace {

using Eigen::Vector3d;

// min |p(s) - q(t)| by sampling: a 201 x 201 grid, then three zooms around the best pair.
double brute_force(const Vector3d& a0, const Vector3d& a1, const Vector3d& b0, const Vector3d& b1) {
  double best = std::numeric_limits<double>::infinity(), bs = 0.5, bt = 0.5, half = 0.5;
  for (int level = 0; level < 4; ++level) {
    const double s_lo = std::max(0.0, bs - half), s_hi = std::min(1.0, bs + half);
    const double t_lo = std::max(0.0, bt - half), t_hi = std::min(1.0, bt + half);
    const int n = 200;
    for (int i = 0; i <= n; ++i) {
      const double s = s_lo + (s_hi - s_lo) * i / n;
      for (int j = 0; j <= n; ++j) {
        const double t = t_lo + (t_hi - t_lo) * j / n;
        const double d = ((a0 + s * (a1 - a0)) - (b0 + t * (b1 - b0))).norm();
        if (d < best) {
          best = d;
          bs = s;
          bt = t;
        }
      }
    }
    half *= 0.02;
  }
  return best;
}

void expect_closest(const Vector3d& a0, const Vector3d& a1, const Vector3d& b0, const Vector3d& b1,
                    const char* what) {
  const SegmentClosest c = segment_closest(a0, a1, b0, b1);
  EXPECT_GE(c.s, 0.0) << what;
  EXPECT_LE(c.s, 1.0) << what;
  EXPECT_GE(c.t, 0.0) << what;
  EXPECT_LE(c.t, 1.0) << what;
  EXPECT_NEAR(((a0 + c.s * (a1 - a0)) - (b0 + c.t * (b1 - b0))).norm(), c.distance, 1e-14) << what;
  const double sampled = brute_force(a0, a1, b0, b1);
  // Sampling finds an upper bound close to the minimum; the exact value is never above it.
  EXPECT_LE(c.distance, sampled + 1e-12) << what;
  EXPECT_NEAR(c.distance, sampled, 1e-7) << what;
  // Symmetric in the two segments and in each segment's direction.
  EXPECT_NEAR(segment_distance(b0, b1, a0, a1), c.distance, 1e-13) << what;
  EXPECT_NEAR(segment_distance(a1, a0, b1, b0), c.distance, 1e-13) << what;
}

TEST(SegmentDistance, RandomSegmentsMatchBruteForce) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  auto point = [&] { return Vector3d(u(rng), u(rng), u(rng)); };
  for (int k = 0; k < 200; ++k) expect_closest(point(), point(), point(), point(), "random");
}

TEST(SegmentDistance, ParallelCollinearAndNearlyParallel) {
  const Vector3d x = Vector3d::UnitX(), y = Vector3d::UnitY();
  // Parallel with an overlap: the offset.
  expect_closest({0, 0, 0}, {1, 0, 0}, {0.5, 1, 0}, {2, 1, 0}, "parallel overlap");
  EXPECT_NEAR(segment_distance({0, 0, 0}, x, {0.5, 1, 0}, {2, 1, 0}), 1.0, 1e-15);
  // Parallel without an overlap: end to end.
  expect_closest({0, 0, 0}, x, {2, 1, 0}, {3, 1, 0}, "parallel apart");
  EXPECT_NEAR(segment_distance({0, 0, 0}, x, {2, 1, 0}, {3, 1, 0}), std::sqrt(2.0), 1e-15);
  expect_closest({0, 0, 0}, x, {-3, 1, 0}, {-2, 1, 0}, "parallel apart, behind");
  // Antiparallel.
  expect_closest({0, 0, 0}, x, {3, 1, 0}, {2, 1, 0}, "antiparallel apart");
  // Collinear, apart and overlapping.
  EXPECT_NEAR(segment_distance({0, 0, 0}, x, {1.5, 0, 0}, {3, 0, 0}), 0.5, 1e-15);
  EXPECT_EQ(segment_distance({0, 0, 0}, x, {0.5, 0, 0}, {3, 0, 0}), 0.0);
  // Nearly parallel (1e-9 rad): the distance is the offset to 1e-12.
  const Vector3d tilted(1.0, 1e-9, 0.0);
  expect_closest({0, 0, 0}, x, Vector3d(0.2, 0.3, 0.0), Vector3d(0.2, 0.3, 0.0) + tilted,
                 "nearly parallel");
  EXPECT_NEAR(segment_distance({0, 0, 0}, x, y * 0.3, y * 0.3 + tilted), 0.3, 1e-9);
}

TEST(SegmentDistance, CrossingTouchingAndPoints) {
  // Crossing in a plane: 0; skew perpendicular lines: their offset.
  EXPECT_NEAR(segment_distance({-1, 0, 0}, {1, 0, 0}, {0, -1, 0}, {0, 1, 0}), 0.0, 1e-16);
  EXPECT_NEAR(segment_distance({-1, 0, 0}, {1, 0, 0}, {0, -1, 0.25}, {0, 1, 0.25}), 0.25, 1e-16);
  // Touching at an end (an L and a T).
  EXPECT_EQ(segment_distance({0, 0, 0}, {1, 0, 0}, {1, 0, 0}, {1, 1, 0}), 0.0);
  EXPECT_NEAR(segment_distance({-1, 0, 0}, {1, 0, 0}, {0, 0, 0}, {0, 1, 1}), 0.0, 1e-16);
  // The closest point at an end of one and inside the other.
  expect_closest({0, 0, 0}, {1, 0, 0}, {2, -1, 0.5}, {2, 1, 0.5}, "end to interior");
  EXPECT_NEAR(segment_distance({0, 0, 0}, {1, 0, 0}, {2, -1, 0.5}, {2, 1, 0.5}), std::sqrt(1.25),
              1e-15);
  // Points: point to segment and point to point.
  const Vector3d p(0.3, 0.4, 0.0);
  EXPECT_NEAR(segment_distance(p, p, {-1, 0, 0}, {1, 0, 0}), 0.4, 1e-16);
  EXPECT_NEAR(segment_distance({-1, 0, 0}, {1, 0, 0}, p, p), 0.4, 1e-16);
  EXPECT_NEAR(segment_distance(p, p, {3, 4, 0}, {3, 4, 0}), (p - Vector3d(3, 4, 0)).norm(), 1e-15);
  expect_closest(p, p, {-1, 2, 0}, {1, 3, 1}, "point and segment");
}

}  // namespace
}  // namespace pkmopt
