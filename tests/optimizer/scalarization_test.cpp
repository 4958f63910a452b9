// Tests of optimizer/scalarization: values and chain-rule gradients of the subproblems.
#include "optimizer/scalarization.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "problems/benchmarks/benchmarks.hpp"

namespace pkmopt {
namespace {

TEST(ScalarizedProblem, ValuesAndGradient) {
  Bnh bnh;  // 2 objectives, 2 inequalities
  ScalarizedProblem sub(bnh, {0.5, 0.0}, {{1, 10.0, 4.0}});
  const std::vector<double> x{1.5, 2.0};
  const std::vector<double> base = bnh.fitness(x);
  const std::vector<double> f = sub.fitness(x);
  ASSERT_EQ(f.size(), 4u);  // objective, 2 base inequalities, 1 epsilon bound
  EXPECT_DOUBLE_EQ(f[0], 0.5 * base[0]);
  EXPECT_DOUBLE_EQ(f[1], base[2]);
  EXPECT_DOUBLE_EQ(f[3], (base[1] - 10.0) / 4.0);
  const GradientCheck check = check_gradient(sub, x);
  EXPECT_TRUE(check.ok) << check.report;
}

TEST(NbiProblem, ValuesAndGradientInBothForms) {
  Zdt zdt(2, 4);
  for (bool equality : {false, true}) {
    NbiProblem sub(zdt, {0.0, 0.0}, {1.0, 2.0}, {0.3, 0.7}, {-0.6, -0.8}, equality);
    const std::vector<double> xt{0.4, 0.1, 0.2, 0.3, 0.25};
    const std::vector<double> f = sub.fitness(xt);
    ASSERT_EQ(f.size(), 3u);
    EXPECT_DOUBLE_EQ(f[0], -0.25);
    const std::vector<double> base = zdt.fitness({0.4, 0.1, 0.2, 0.3});
    EXPECT_DOUBLE_EQ(f[2], base[1] / 2.0 - 0.7 + 0.25 * 0.8);
    EXPECT_EQ(sub.num_equality(), equality ? 2u : 0u);
    const GradientCheck check = check_gradient(sub, xt);
    EXPECT_TRUE(check.ok) << check.report;
  }
}

TEST(NbiProblem, FeasibleT) {
  Zdt zdt(1, 3);
  NbiProblem sub(zdt, {0.0, 0.0}, {1.0, 1.0}, {0.5, 0.5}, {-std::sqrt(0.5), -std::sqrt(0.5)},
                 false);
  const std::vector<double> x{0.25, 0.0, 0.0};  // f = (0.25, 0.5)
  const double t = sub.feasible_t(zdt.fitness(x));
  std::vector<double> xt = x;
  xt.push_back(t);
  const std::vector<double> f = sub.fitness(xt);
  EXPECT_LE(std::max(f[1], f[2]), 1e-15);
  EXPECT_NEAR(std::max(f[1], f[2]), 0.0, 1e-15);  // the largest feasible t is active
}

}  // namespace
}  // namespace pkmopt
