// Tests of optimizer/hybrid: the Ipopt polish moves an NSGA-II front onto the true front.
#include "optimizer/hybrid.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "optimizer/indicators.hpp"
#include "problems/benchmarks/benchmarks.hpp"

namespace pkmopt {
namespace {

TEST(Hybrid, PolishImprovesAnEarlyNsga2Front) {
  Zdt problem(1, 10);
  HybridOptions options;
  options.nsga2.population = 40;
  options.nsga2.generations = 30;  // deliberately short: the front is still far from optimal
  options.nsga2.threads = 1;
  const FrontResult explored = run_nsga2(problem, options.nsga2);
  const FrontResult polished = run_hybrid(problem, options);
  const auto reference = problem.reference_front(500);
  const double before = igd_plus(explored.objectives(), reference);
  const double after = igd_plus(polished.objectives(), reference);
  // The polish moves points onto the front but does not spread them: IGD+ (coverage) and the
  // hypervolume both improve.
  EXPECT_LT(after, before) << "before " << before << ", after " << after;
  EXPECT_GT(hypervolume(polished.objectives(), {1.1, 1.1}),
            hypervolume(explored.objectives(), {1.1, 1.1}) + 0.01);
  EXPECT_GT(polished.gradient_evaluations, 0);
  // Polished designs lie on the front (g = 1).
  std::size_t on_front = 0;
  for (const auto& f : polished.objectives())
    if (std::abs(f[1] - (1.0 - std::sqrt(f[0]))) < 1e-6) ++on_front;
  EXPECT_GE(on_front, polished.x.size() / 2);
}

TEST(Hybrid, ConstrainedTnk) {
  Tnk problem;
  HybridOptions options;
  options.nsga2.population = 40;
  options.nsga2.generations = 40;
  const FrontResult front = run_hybrid(problem, options);
  ASSERT_FALSE(front.x.empty());
  for (const auto& f : front.fitness) EXPECT_LE(constraint_violation(problem, f, 1e-6, 1e-7), 0.0);
  EXPECT_LT(igd_plus(front.objectives(), problem.reference_front(500)), 0.02);
}

TEST(Hybrid, RefusesSingleObjective) {
  EXPECT_THROW(run_hybrid(Rosenbrock(2), HybridOptions{}), std::invalid_argument);
}

}  // namespace
}  // namespace pkmopt
