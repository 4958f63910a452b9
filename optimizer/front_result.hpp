// The outcome of a Pareto front builder (NSGA-II, epsilon-constraint, NBI, hybrid).
//
// `x[k]` and `fitness[k]` ([objectives | eq | ineq], in the problem's own sign) are the k-th
// feasible, mutually non-dominated design found, sorted by objective vector. Evaluations count
// every call of the problem's fitness (finite differences included) and gradient.
// Subproblem counts are 0 for NSGA-II.
//
// Example:
//   pkmopt::FrontResult front = pkmopt::run_nsga2(zdt1, options);
//   double hv = pkmopt::hypervolume(front.objectives(), {1.1, 1.1});
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "optimizer/indicators.hpp"
#include "optimizer/problem.hpp"

namespace pkmopt {

struct FrontResult {
  std::string algorithm;                     ///< "nsga2", "epsilon_constraint", "nbi", "hybrid"
  std::vector<std::vector<double>> x;        ///< designs on the front
  std::vector<std::vector<double>> fitness;  ///< their full fitness vectors
  std::size_t num_objectives = 0;
  long long fitness_evaluations = 0;
  long long gradient_evaluations = 0;
  double seconds = 0.0;
  std::size_t subproblems = 0;            ///< scalarised problems solved (epsilon, NBI, polish)
  std::size_t failed_subproblems = 0;     ///< not converged, or infeasible result
  std::size_t dominated_subproblems = 0;  ///< converged to a point another result dominates
  std::string message;                    ///< notes for the user (may be empty)

  /// The objective vectors of the front (first num_objectives entries of each fitness).
  ObjectiveSet objectives() const;
};

/// Builds a FrontResult from candidates: keeps those with constraint violation <= tolerance
/// (equalities within `equality_tolerance`) and finite objectives, then the non-dominated ones,
/// sorted by objective vector. The default tolerances agree with SolveResult::usable() (1e-6).
FrontResult make_front(const Problem& problem, const std::vector<std::vector<double>>& xs,
                       const std::vector<std::vector<double>>& fitness,
                       double equality_tolerance = 1e-6, double inequality_tolerance = 1e-6);

}  // namespace pkmopt
