// Tests of optimizer/moead: on DTLZ2 with 3 objectives (91 weights, 250 generations) the front's
// IGD+ to a dense sample of the analytic front is within 35 % of the best its weights allow (the
// Tchebycheff optima of the 91 weights, computed here in closed form) and the members lie on the
// sphere; the same seed gives the same front on 1 and 2 threads; constrained problems (BNH, TNK)
// end feasible and near their fronts; bad options are refused.
#include "optimizer/moead.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "optimizer/indicators.hpp"
#include "optimizer/reference_directions.hpp"
#include "problems/benchmarks/benchmarks.hpp"

namespace pkmopt {
namespace {

TEST(Moead, Dtlz2WithThreeObjectivesReachesItsTchebycheffOptima) {
  const auto dtlz2 = make_benchmark("dtlz2", 0, 3);
  MoeadOptions options;
  options.divisions = 12;
  options.generations = 250;
  options.seed = 2;
  const FrontResult front = run_moead(*dtlz2, options);
  EXPECT_EQ(front.fitness_evaluations, 91u * 251u);
  ASSERT_GE(front.fitness.size(), 40u);
  const ObjectiveSet reference = dtlz2->reference_front(5000);
  // With the ideal point at 0 and the nadir at 1, the Tchebycheff optimum of weight w on the unit
  // sphere is the point along (1/w_1, 1/w_2, 1/w_3) (w_i = 0 taken as 1e-6, as the algorithm does).
  ObjectiveSet optima;
  for (const std::vector<double>& w : das_dennis_directions(3, 12)) {
    std::vector<double> f(3);
    double norm = 0.0;
    for (int i = 0; i < 3; ++i) {
      f[i] = 1.0 / std::max(w[i], 1e-6);
      norm += f[i] * f[i];
    }
    for (double& v : f) v /= std::sqrt(norm);
    optima.push_back(f);
  }
  const double best = igd_plus(optima, reference);
  const double reached = igd_plus(front.fitness, reference);
  EXPECT_LT(reached, 1.35 * best) << "IGD+ " << reached << " against " << best;
  std::vector<double> radius;
  for (const std::vector<double>& f : front.fitness)
    radius.push_back(std::sqrt(f[0] * f[0] + f[1] * f[1] + f[2] * f[2]));
  std::sort(radius.begin(), radius.end());
  // Converged onto the sphere as far as DE with CR = 1 gets in 250 generations: pagmo 2.18's
  // MOEA/D with the same settings ends at median radii 1.007, 1.007 and 1.009 (seeds 1-3).
  EXPECT_NEAR(radius[radius.size() / 2], 1.0, 1.5e-2);
}

TEST(Moead, TheSameSeedGivesTheSameFrontOnAnyThreadCount) {
  const auto dtlz1 = make_benchmark("dtlz1", 0, 4);
  MoeadOptions options;
  options.divisions = 5;
  options.generations = 30;
  options.seed = 9;
  options.threads = 1;
  const FrontResult one = run_moead(*dtlz1, options);
  options.threads = 2;
  const FrontResult two = run_moead(*dtlz1, options);
  EXPECT_EQ(one.x, two.x);
  EXPECT_EQ(one.fitness, two.fitness);
}

TEST(Moead, ConstrainedProblemsEndFeasibleNearTheirFronts) {
  for (const char* name : {"bnh", "tnk"}) {
    const auto problem = make_benchmark(name);
    MoeadOptions options;
    options.divisions = 59;  // 60 weights in two objectives
    options.generations = 150;
    const FrontResult front = run_moead(*problem, options);
    ASSERT_GE(front.x.size(), 10u) << name << ": " << front.message;
    ObjectiveSet f;
    for (const std::vector<double>& v : front.fitness) {
      for (std::size_t k = 2; k < v.size(); ++k) EXPECT_LE(v[k], 0.0) << name;
      f.push_back({v[0], v[1]});
    }
    // IGD+ in units of the front's extent: within 2 % of it.
    const ObjectiveSet reference = problem->reference_front(2000);
    const std::vector<double> lo = ideal_point(reference), hi = nadir_point(reference);
    const double extent = std::hypot(hi[0] - lo[0], hi[1] - lo[1]);
    EXPECT_LT(igd_plus(f, reference), 0.02 * extent) << name;
  }
}

TEST(Moead, BadOptionsAreRefused) {
  const auto dtlz2 = make_benchmark("dtlz2", 0, 3);
  MoeadOptions options;
  options.neighbours = 1;
  EXPECT_THROW(run_moead(*dtlz2, options), std::invalid_argument);
  options.neighbours = 20;
  options.differential_weight = 0.0;
  EXPECT_THROW(run_moead(*dtlz2, options), std::invalid_argument);
  options.differential_weight = 0.5;
  options.weights = {{1.0, 0.0}};  // two components for three objectives
  EXPECT_THROW(run_moead(*dtlz2, options), std::invalid_argument);
  options.weights = {{1.0, 0.0, 0.0}, {0.0, 1.0, 0.0}};  // a population of 2
  EXPECT_THROW(run_moead(*dtlz2, options), std::invalid_argument);
}

}  // namespace
}  // namespace pkmopt
