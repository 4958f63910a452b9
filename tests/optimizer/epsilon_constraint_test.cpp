// Tests of optimizer/epsilon_constraint on ZDT1, ZDT2, ZDT3 and constrained problems.
#include "optimizer/epsilon_constraint.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <utility>
#include <vector>

#include "optimizer/archive.hpp"
#include "optimizer/indicators.hpp"
#include "problems/benchmarks/benchmarks.hpp"

namespace pkmopt {
namespace {

FrontResult run(const Problem& problem, std::size_t points) {
  EpsilonConstraintOptions options;
  options.points = points;
  return run_epsilon_constraint(problem, options);
}

TEST(EpsilonConstraint, ConvexFrontZdt1) {
  Zdt problem(1, 5);
  const FrontResult front = run(problem, 21);
  EXPECT_EQ(front.failed_subproblems, 0u) << front.message;
  EXPECT_GE(front.x.size(), 20u);
  EXPECT_LT(igd_plus(front.objectives(), problem.reference_front(500)), 0.02);
  // Every point lies on the analytic front f_2 = 1 - sqrt(f_1).
  for (const auto& f : front.objectives()) EXPECT_NEAR(f[1], 1.0 - std::sqrt(f[0]), 1e-6);
}

TEST(EpsilonConstraint, ConcaveFrontZdt2) {
  Zdt problem(2, 5);
  const FrontResult front = run(problem, 21);
  EXPECT_GE(front.x.size(), 20u);
  EXPECT_LT(igd_plus(front.objectives(), problem.reference_front(500)), 0.02);
  for (const auto& f : front.objectives()) EXPECT_NEAR(f[1], 1.0 - f[0] * f[0], 1e-6);
}

// ZDT3's front (g = 1): the f_1 where h(f_1) = 1 - sqrt(f_1) - f_1 sin(10 pi f_1) is below its
// value at every smaller f_1, as intervals [begin, end] (from 200,001 samples).
std::vector<std::pair<double, double>> zdt3_pieces() {
  std::vector<std::pair<double, double>> pieces;
  double lowest = INFINITY;
  bool inside = false;
  const int samples = 200000;
  for (int k = 0; k <= samples; ++k) {
    const double f1 = static_cast<double>(k) / samples;
    const double h = 1.0 - std::sqrt(f1) - f1 * std::sin(10.0 * std::numbers::pi * f1);
    const bool on_front = h < lowest;
    if (on_front && !inside) pieces.emplace_back(f1, f1);
    if (on_front) pieces.back().second = f1;
    inside = on_front;
    lowest = std::min(lowest, h);
  }
  return pieces;
}

// Distance from f_1 to the nearest piece of ZDT3's front (0 inside one).
double distance_to_pieces(double f1, const std::vector<std::pair<double, double>>& pieces) {
  double distance = INFINITY;
  for (const auto& [begin, end] : pieces)
    distance = std::min(distance, std::max({begin - f1, f1 - end, 0.0}));
  return distance;
}

void expect_mutually_non_dominated(const ObjectiveSet& front) {
  for (std::size_t a = 0; a < front.size(); ++a)
    for (std::size_t b = 0; b < front.size(); ++b)
      if (a != b) {
        EXPECT_FALSE(dominates(front[a], front[b])) << a << " dominates " << b;
      }
}

// Bounding f_2 (primary f_1): ZDT3's pieces abut in f_2, so every epsilon level has its own
// Pareto point, found even where the level's feasible set is the narrow last piece (local
// solves from the previous level end infeasible there; the neighbour with the tighter bound is
// a feasible restart). The front is the analytic one: nothing fails, nothing is dropped.
TEST(EpsilonConstraint, DisconnectedFrontZdt3BoundingF2) {
  Zdt problem(3, 10);
  const FrontResult front = run(problem, 21);
  SCOPED_TRACE(::testing::Message()
               << front.message << "; subproblems " << front.subproblems << ", failed "
               << front.failed_subproblems << ", dominated " << front.dominated_subproblems
               << ", points " << front.x.size());
  EXPECT_EQ(front.failed_subproblems, 0u);
  EXPECT_EQ(front.x.size(), 21u);
  EXPECT_EQ(front.dominated_subproblems, 0u);
  const auto pieces = zdt3_pieces();
  for (const auto& f : front.objectives()) {
    EXPECT_LT(distance_to_pieces(f[0], pieces), 1e-4) << "f_1 = " << f[0];
    EXPECT_NEAR(f[1], 1.0 - std::sqrt(f[0]) - f[0] * std::sin(10.0 * std::numbers::pi * f[0]),
                1e-6);
  }
  expect_mutually_non_dominated(front.objectives());
  EXPECT_LT(igd_plus(front.objectives(), problem.reference_front(500)), 0.03);
}

// Bounding f_1 (primary f_2): every level in a gap of the front between two pieces has the
// end of the piece before the gap as its optimum. The first such level of each gap adds that
// end point; the others repeat it, and each repeat is detected, counted as dominated and
// dropped.
TEST(EpsilonConstraint, DisconnectedFrontZdt3BoundingF1DropsRepeats) {
  Zdt problem(3, 5);
  EpsilonConstraintOptions options;
  options.points = 21;
  options.primary_objective = 1;
  const FrontResult front = run_epsilon_constraint(problem, options);
  SCOPED_TRACE(::testing::Message()
               << front.message << "; subproblems " << front.subproblems << ", failed "
               << front.failed_subproblems << ", dominated " << front.dominated_subproblems
               << ", points " << front.x.size());
  EXPECT_EQ(front.failed_subproblems, 0u);
  // Levels f_1 <= eps_k, eps_k = k/20 * f_1max (the ideal f_1 is 0), k = 1..19.
  const auto pieces = zdt3_pieces();
  const double f1_max = pieces.back().second;
  std::size_t in_gaps = 0;
  std::vector<bool> gap_used(pieces.size(), false);
  for (int k = 1; k <= 19; ++k) {
    const double eps = k / 20.0 * f1_max;
    if (distance_to_pieces(eps, pieces) == 0.0) continue;
    ++in_gaps;
    for (std::size_t i = 0; i + 1 < pieces.size(); ++i)
      if (eps > pieces[i].second && eps < pieces[i + 1].first) gap_used[i] = true;
  }
  const auto gaps_with_levels =
      static_cast<std::size_t>(std::count(gap_used.begin(), gap_used.end(), true));
  EXPECT_GE(in_gaps, 8u);  // the gaps cover more than half of f_1's range
  EXPECT_EQ(front.dominated_subproblems, in_gaps - gaps_with_levels);
  EXPECT_EQ(front.x.size(), 21u - front.dominated_subproblems);
  for (const auto& f : front.objectives()) {
    EXPECT_LT(distance_to_pieces(f[0], pieces), 1e-4) << "f_1 = " << f[0];
    EXPECT_NEAR(f[1], 1.0 - std::sqrt(f[0]) - f[0] * std::sin(10.0 * std::numbers::pi * f[0]),
                1e-6);
  }
  expect_mutually_non_dominated(front.objectives());
  EXPECT_LT(igd_plus(front.objectives(), problem.reference_front(500)), 0.06);
}

TEST(EpsilonConstraint, ConstrainedSrn) {
  Srn problem;
  const FrontResult front = run(problem, 21);
  EXPECT_GE(front.x.size(), 15u) << front.message;
  for (const auto& f : front.fitness) EXPECT_LE(constraint_violation(problem, f, 1e-6, 1e-7), 0.0);
  // SRN's front spans ~220 in f_1: 21 points leave gaps of ~10, so IGD+ of a few units is the
  // discretisation alone; 5 is 2% of the range.
  EXPECT_LT(igd_plus(front.objectives(), problem.reference_front(500)), 5.0);
}

TEST(EpsilonConstraint, RefusesSingleObjective) {
  EXPECT_THROW(run(Hs71(), 5), std::invalid_argument);
  EpsilonConstraintOptions options;
  options.points = 1;
  EXPECT_TRUE(options.validate().has_value());
}

}  // namespace
}  // namespace pkmopt
