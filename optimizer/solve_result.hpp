// The outcome of one run of a single-objective solver (Ipopt, NLopt): non-convergence is a
// result with a status and a message, never an exception.
//
// Example:
//   pkmopt::SolveResult result = pkmopt::solve_with_ipopt(problem, x0);
//   if (!result.usable()) std::puts(result.summary().c_str());
//   // "ipopt on 'hs71': converged, f = 17.0140173, violation 0, 9 iterations, ..."
#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace pkmopt {

enum class SolveStatus {
  converged,         ///< optimality tolerances met
  acceptable,        ///< only the looser "acceptable" tolerances met (Ipopt) or a stopping
                     ///< criterion on f or x met (NLopt): a usable point
  max_iterations,    ///< iteration or evaluation budget exhausted
  max_time,          ///< time budget exhausted
  infeasible,        ///< the solver found the constraints locally infeasible
  diverging,         ///< iterates diverged or the search direction vanished
  evaluation_error,  ///< the problem returned non-finite values where the solver needed them
  failed,            ///< any other solver failure (message says which)
};

/// "converged", "acceptable", "max_iterations", ...
std::string_view to_string(SolveStatus status);

struct SolveResult {
  std::string solver;   ///< "ipopt" or "nlopt:<ALGORITHM>"
  std::string problem;  ///< the problem's name
  SolveStatus status = SolveStatus::failed;
  std::string message;                ///< the solver's own words (Ipopt/NLopt status text)
  std::vector<double> x;              ///< the last (best) point, within the bounds
  std::vector<double> fitness;        ///< [objective | eq | ineq] at x (empty if never evaluated)
  double objective = 0.0;             ///< fitness[0]
  double constraint_violation = 0.0;  ///< sum |h| + sum max(g, 0) at x
  int iterations = 0;
  long long fitness_evaluations = 0;   ///< including those for finite differences
  long long gradient_evaluations = 0;  ///< calls to the problem's gradient
  double seconds = 0.0;

  /// Converged or acceptable, with a feasible point (violation <= 1e-6).
  bool usable() const;
  /// One readable line.
  std::string summary() const;
};

}  // namespace pkmopt
