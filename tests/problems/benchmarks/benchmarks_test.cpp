// Tests of problems/benchmarks/benchmarks: gradients against finite differences, and analytic
// fronts against the fitness of known Pareto-optimal designs.
#include "problems/benchmarks/benchmarks.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <stdexcept>

#include "optimizer/archive.hpp"
#include "optimizer/random.hpp"

namespace pkmopt {
namespace {

std::vector<double> random_point(const Problem& problem, Random& rng) {
  const Bounds b = problem.bounds();
  std::vector<double> x(b.lower.size());
  for (std::size_t j = 0; j < x.size(); ++j) {
    // Stay away from the bounds, where one-sided differences are less accurate.
    const double margin = 0.05 * (b.upper[j] - b.lower[j]);
    x[j] = rng.uniform(b.lower[j] + margin, b.upper[j] - margin);
  }
  return x;
}

TEST(Benchmarks, GradientsMatchFiniteDifferences) {
  Random rng(17);
  for (const std::string& name : benchmark_names()) {
    const auto problem = make_benchmark(name);
    if (!problem->has_gradient()) continue;
    for (int trial = 0; trial < 5; ++trial) {
      const GradientCheck check = check_gradient(*problem, random_point(*problem, rng));
      EXPECT_TRUE(check.ok) << check.report;
    }
  }
}

TEST(Benchmarks, FitnessSizesAndNames) {
  for (const std::string& name : benchmark_names()) {
    const auto problem = make_benchmark(name);
    EXPECT_EQ(problem->name(), name);
    Random rng(1);
    EXPECT_EQ(problem->fitness(random_point(*problem, rng)).size(), problem->fitness_size());
  }
}

TEST(Benchmarks, ZdtOptimalDesignsLieOnTheReferenceFront) {
  for (int kind : {1, 2, 3, 4, 6}) {
    Zdt problem(kind, 10);
    const auto front = problem.reference_front(100);
    ASSERT_FALSE(front.empty());
    // Pareto-optimal designs: x_2..x_n = 0 (g = 1); sweep x_1 and compare with the front.
    for (double x1 : {0.0, 0.1, 0.35, 0.62, 0.9}) {
      std::vector<double> x(10, 0.0);
      x[0] = x1;
      const std::vector<double> f = problem.fitness(x);
      EXPECT_NEAR(
          problem.fitness(x)[1],
          [&] {
            const double r = f[0];
            switch (kind) {
              case 2:
              case 6:
                return 1.0 - r * r;
              case 3:
                return 1.0 - std::sqrt(r) - r * std::sin(10.0 * std::numbers::pi * r);
              default:
                return 1.0 - std::sqrt(r);
            }
          }(),
          1e-12);
    }
    EXPECT_EQ(non_dominated_indices(front).size(), front.size());
  }
}

TEST(Benchmarks, Zdt3FrontIsDisconnected) {
  // Five pieces (Zitzler et al. 2000): f_1 from 0 to 0.0830 up to 0.8233 to 0.8518.
  const auto front = Zdt(3, 30).reference_front(2000);
  EXPECT_NEAR(front.front()[0], 0.0, 1e-12);
  EXPECT_NEAR(front.back()[0], 0.8518, 2e-3);
  int gaps = 0;
  for (std::size_t k = 1; k < front.size(); ++k)
    if (front[k][0] - front[k - 1][0] > 0.05) ++gaps;
  EXPECT_EQ(gaps, 4);
}

TEST(Benchmarks, DtlzFronts) {
  for (std::size_t m : {2u, 3u, 5u}) {
    const auto dtlz1 = make_benchmark("dtlz1", 0, m);
    const auto dtlz2 = make_benchmark("dtlz2", 0, m);
    for (const auto& f : dtlz1->reference_front(100)) {
      double sum = 0.0;
      for (double v : f) sum += v;
      EXPECT_NEAR(sum, 0.5, 1e-12);
    }
    for (const auto& f : dtlz2->reference_front(100)) {
      double sum = 0.0;
      for (double v : f) sum += v * v;
      EXPECT_NEAR(sum, 1.0, 1e-12);
    }
    // Optimal designs (distance variables 0.5) land on the front.
    Random rng(3);
    for (int trial = 0; trial < 5; ++trial) {
      std::vector<double> x(dtlz2->num_variables(), 0.5);
      for (std::size_t j = 0; j + 1 < m; ++j) x[j] = rng.uniform01();
      double sum1 = 0.0, sum2 = 0.0;
      for (double v : dtlz2->fitness(x)) sum2 += v * v;
      EXPECT_NEAR(sum2, 1.0, 1e-12);
      std::vector<double> x1(dtlz1->num_variables(), 0.5);
      for (std::size_t j = 0; j + 1 < m; ++j) x1[j] = x[j];
      sum1 = 0.0;
      for (double v : dtlz1->fitness(x1)) sum1 += v;
      EXPECT_NEAR(sum1, 0.5, 1e-12);
    }
  }
  // DTLZ7 with x_M = 0 (g = 1): f_m follows the front formula.
  const auto dtlz7 = make_benchmark("dtlz7", 0, 3);
  std::vector<double> x(dtlz7->num_variables(), 0.0);
  x[0] = 0.2;
  x[1] = 0.7;
  const auto f = dtlz7->fitness(x);
  const double h = 3.0 - 0.1 * (1 + std::sin(0.6 * std::numbers::pi)) -
                   0.35 * (1 + std::sin(2.1 * std::numbers::pi));
  EXPECT_NEAR(f[2], 2.0 * h, 1e-12);
  EXPECT_FALSE(dtlz7->reference_front(100).empty());
}

TEST(Benchmarks, ConstrainedFrontsAreFeasibleAndNonDominated) {
  // Reference fronts of BNH, SRN, OSY are made from the published Pareto sets: feasible, and
  // no random feasible design dominates them.
  Random rng(5);
  for (const char* name : {"bnh", "srn", "tnk", "osy"}) {
    const auto problem = make_benchmark(name);
    const auto front = problem->reference_front(200);
    ASSERT_GE(front.size(), 50u) << name;
    for (int trial = 0; trial < 20000; ++trial) {
      const Bounds b = problem->bounds();
      std::vector<double> x(b.lower.size());
      for (std::size_t j = 0; j < x.size(); ++j) x[j] = rng.uniform(b.lower[j], b.upper[j]);
      const auto f = problem->fitness(x);
      if (constraint_violation(*problem, f) > 0.0) continue;
      const std::vector<double> objectives{f[0], f[1]};
      for (const auto& z : front) {
        ASSERT_FALSE(dominates(objectives, z))
            << name << ": a random feasible design dominates the reference front";
      }
    }
  }
}

TEST(Benchmarks, KnownOptima) {
  Hs71 hs71;
  const auto f = hs71.fitness(hs71.known_optimum_x());
  EXPECT_NEAR(f[0], 17.0140173, 1e-6);
  EXPECT_NEAR(f[1], 0.0, 1e-6);
  EXPECT_NEAR(f[2], 0.0, 1e-6);
  Rosenbrock rosenbrock(6);
  EXPECT_DOUBLE_EQ(rosenbrock.fitness(rosenbrock.known_optimum_x())[0], 0.0);
}

TEST(Benchmarks, FactoryErrors) {
  EXPECT_THROW(make_benchmark("zdt5"), std::invalid_argument);
  EXPECT_THROW(make_benchmark("nope"), std::invalid_argument);
  EXPECT_THROW(make_benchmark("bnh", 3), std::invalid_argument);
  EXPECT_THROW(make_benchmark("zdt1", 0, 3), std::invalid_argument);
  EXPECT_THROW(make_benchmark("dtlz2", 2, 3), std::invalid_argument);
  EXPECT_EQ(make_benchmark("dtlz2", 0, 4)->num_variables(), 13u);
  EXPECT_EQ(make_benchmark("zdt4")->num_variables(), 10u);
}

}  // namespace
}  // namespace pkmopt
