// Tests of optimizer/anchors: lexicographic anchors of ZDT1 and a constrained problem.
#include "optimizer/anchors.hpp"

#include <gtest/gtest.h>

#include "problems/benchmarks.hpp"

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

TEST(Anchors, DefaultStartIsInside) {
  Srn problem;
  EXPECT_EQ(default_start(problem), (std::vector<double>{0.0, 0.0}));
}

}  // namespace
}  // namespace pkmopt
