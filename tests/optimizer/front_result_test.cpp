// Tests of optimizer/front_result: feasibility and dominance filtering of candidates.
#include "optimizer/front_result.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "problems/benchmarks/benchmarks.hpp"

namespace pkmopt {
namespace {

TEST(MakeFront, KeepsFeasibleNonDominatedSorted) {
  Bnh problem;
  const std::vector<std::vector<double>> xs{{0}, {1}, {2}, {3}, {4}};
  const std::vector<std::vector<double>> fitness{{5.0, 1.0, -1.0, -1.0},   // kept
                                                 {1.0, 5.0, -1.0, -1.0},   // kept (sorted first)
                                                 {0.5, 0.5, 0.1, -1.0},    // infeasible
                                                 {6.0, 2.0, -1.0, -1.0},   // dominated
                                                 {NAN, 0.0, -1.0, -1.0}};  // not finite
  const FrontResult front = make_front(problem, xs, fitness);
  ASSERT_EQ(front.x.size(), 2u);
  EXPECT_EQ(front.x[0], std::vector<double>{1});
  EXPECT_EQ(front.x[1], std::vector<double>{0});
  EXPECT_EQ(front.objectives()[0], (std::vector<double>{1.0, 5.0}));
}

}  // namespace
}  // namespace pkmopt
