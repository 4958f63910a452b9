// Tests of optimizer/anchors: lexicographic anchors of ZDT1 and a constrained problem.
#include "optimizer/anchors.hpp"

#include <gtest/gtest.h>

#include "problems/benchmarks/benchmarks.hpp"

namespace pkmopt {
namespace {

TEST(Anchors, Zdt1AnchorsAreTheFrontEnds) {
  Zdt problem(1, 8);
  const AnchorSet anchors = compute_anchors(problem, default_start(problem), IpoptOptions{});
  ASSERT_EQ(anchors.failed, 0u) << anchors.points[0].summary << "\n" << anchors.points[1].summary;
  // min f_1 alone leaves g free (f_2 = g); the lexicographic step brings g to 1: f = (0, 1).
  EXPECT_NEAR(anchors.points[0].fitness[0], 0.0, 1e-6);
  // At f_1 = 0 the slope of f_2 is infinite and Ipopt stops a little short: g within 1e-3.
  EXPECT_NEAR(anchors.points[0].fitness[1], 1.0, 1e-3);
  EXPECT_NEAR(anchors.points[1].fitness[0], 1.0, 1e-6);
  EXPECT_NEAR(anchors.points[1].fitness[1], 0.0, 1e-6);
  EXPECT_NEAR(anchors.range[0], 1.0, 1e-5);
  EXPECT_NEAR(anchors.range[1], 1.0, 1e-3);
}

// ZDT2's first stage-1 objective f_1 + 1e-3 f_2 / s is concave in x_1: plain L-BFGS skipped
// its updates there and ran to its 1000-iteration limit (1,975 fitness evaluations for the two
// anchors with 30 variables). Switching to SR1 after 30 BFGS iterations converges.
TEST(Anchors, Zdt2ConcaveAugmentationDoesNotStall) {
  Zdt zdt(2, 30);
  CountingProblem problem(zdt);
  const AnchorSet anchors = compute_anchors(problem, default_start(problem), IpoptOptions{});
  ASSERT_EQ(anchors.failed, 0u);
  EXPECT_NEAR(anchors.points[0].fitness[0], 0.0, 1e-6);
  EXPECT_NEAR(anchors.points[0].fitness[1], 1.0, 1e-5);
  EXPECT_NEAR(anchors.points[1].fitness[0], 1.0, 1e-6);
  EXPECT_NEAR(anchors.points[1].fitness[1], 0.0, 1e-6);
  // 20 solves (2 anchors x (1 + 8 Latin-hypercube starts + 1 refinement)): 503 evaluations.
  EXPECT_LT(problem.fitness_evaluations(), 1000u);
}

TEST(Anchors, DefaultStartIsInside) {
  Srn problem;
  EXPECT_EQ(default_start(problem), (std::vector<double>{0.0, 0.0}));
}

}  // namespace
}  // namespace pkmopt

namespace pkmopt {
namespace {

TEST(FrontBuilderHelpers, SegmentStartsAreQuarterPoints) {
  const auto starts = segment_starts({0.0, 4.0}, {4.0, 0.0});
  ASSERT_EQ(starts.size(), 3u);
  EXPECT_EQ(starts[0], (std::vector<double>{1.0, 3.0}));
  EXPECT_EQ(starts[1], (std::vector<double>{2.0, 2.0}));
  EXPECT_EQ(starts[2], (std::vector<double>{3.0, 1.0}));
}

TEST(FrontBuilderHelpers, JumpIsMeasuredInNormalisedObjectivesOnly) {
  AnchorSet anchors;
  anchors.range = {2.0, 4.0};  // two objectives; a third fitness entry is a constraint
  // Normalised distance of (0,0) -> (0.6, 0.8): sqrt(0.3^2 + 0.2^2) = 0.3606.
  EXPECT_FALSE(continuation_jumped(anchors, {0.0, 0.0, 0.0}, {0.6, 0.8, 100.0}, 0.121));
  EXPECT_TRUE(continuation_jumped(anchors, {0.0, 0.0, 0.0}, {0.6, 0.8, 100.0}, 0.12));
  EXPECT_FALSE(continuation_jumped(anchors, {}, {0.6, 0.8}, 1e-9));
}

}  // namespace
}  // namespace pkmopt
