// Tests of optimizer/nbi on ZDT1, ZDT2, ZDT3 and constrained problems.
#include "optimizer/nbi.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "optimizer/indicators.hpp"
#include "problems/benchmarks/benchmarks.hpp"

namespace pkmopt {
namespace {

FrontResult run(const Problem& problem, std::size_t points, bool equality_form = false) {
  NbiOptions options;
  options.points = points;
  options.equality_form = equality_form;
  return run_nbi(problem, options);
}

TEST(SimplexLattice, CountsAndSums) {
  // C(H + m - 1, m - 1) vectors: C(6, 2) = 15 for m = 3, H = 4.
  const auto lattice = simplex_lattice(3, 4);
  EXPECT_EQ(lattice.size(), 15u);
  for (const auto& w : lattice) EXPECT_NEAR(w[0] + w[1] + w[2], 1.0, 1e-15);
  EXPECT_EQ(lattice.front(), (std::vector<double>{1.0, 0.0, 0.0}));
}

TEST(Nbi, ConvexFrontZdt1) {
  Zdt problem(1, 5);
  const FrontResult front = run(problem, 21);
  EXPECT_EQ(front.failed_subproblems, 0u) << front.message;
  EXPECT_GE(front.x.size(), 20u);
  EXPECT_LT(igd_plus(front.objectives(), problem.reference_front(500)), 0.02);
  for (const auto& f : front.objectives()) EXPECT_NEAR(f[1], 1.0 - std::sqrt(f[0]), 1e-6);
}

TEST(Nbi, ConcaveFrontZdt2BothForms) {
  Zdt problem(2, 5);
  for (bool equality : {false, true}) {
    const FrontResult front = run(problem, 21, equality);
    EXPECT_GE(front.x.size(), 19u) << "equality form " << equality << ": " << front.message;
    EXPECT_LT(igd_plus(front.objectives(), problem.reference_front(500)), 0.02);
    for (const auto& f : front.objectives()) EXPECT_NEAR(f[1], 1.0 - f[0] * f[0], 1e-6);
  }
}

// ZDT3's front is disconnected: NBI lattice points facing a gap give weakly dominated points,
// which must be detected and dropped. Continuation alone skips pieces or stops on locally
// optimal ones (IGD+ 0.17 at 31 points); the restarts after a jump (from the segment between
// consecutive results, the anchors, a Latin hypercube) and the repair pass reach 0.03.
TEST(Nbi, DisconnectedFrontZdt3DropsDominated) {
  Zdt problem(3, 5);
  const FrontResult front = run(problem, 21);
  EXPECT_LT(igd_plus(front.objectives(), problem.reference_front(500)), 0.03);
  EXPECT_GT(front.dominated_subproblems, 0u);
}

TEST(Nbi, ConstrainedBnh) {
  Bnh problem;
  const FrontResult front = run(problem, 21);
  EXPECT_GE(front.x.size(), 15u) << front.message;
  for (const auto& f : front.fitness) EXPECT_LE(constraint_violation(problem, f, 1e-6, 1e-7), 0.0);
  EXPECT_LT(igd_plus(front.objectives(), problem.reference_front(500)), 1.0);
}

TEST(Nbi, RefusesSingleObjective) { EXPECT_THROW(run(Rosenbrock(2), 5), std::invalid_argument); }

}  // namespace
}  // namespace pkmopt
