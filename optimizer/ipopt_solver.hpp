// Ipopt (interior-point NLP solver, Wächter & Biegler 2006) on a single-objective Problem.
//
// Solves  min f(x)  s.t.  h(x) = 0,  g(x) <= 0,  lower <= x <= upper  with the problem's exact
// gradient and sparsity pattern when it has one, otherwise with finite differences of the
// fitness (central: 2n evaluations per Jacobian, step `finite_difference_step` * max(1, |x_j|),
// one-sided at a bound). The Hessian of the Lagrangian is always the limited-memory (L-BFGS)
// approximation, so problems never supply second derivatives.
//
// Options are plain data with defaults; `validate()` names a bad option and its constraint
// ("IpoptOptions::tolerance = -1. Violated constraint: tolerance > 0"). solve_with_ipopt throws
// std::invalid_argument for invalid options or an unsupported problem (see
// ipopt_explain_unsupported); a run that does not converge is returned as a SolveResult.
//
// Example:
//   pkmopt::Hs71 hs71;
//   pkmopt::SolveResult result = pkmopt::solve_with_ipopt(hs71, {1, 5, 5, 1});
//   // result.status == SolveStatus::converged, result.objective ~ 17.0140173
#pragma once

#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "optimizer/problem.hpp"
#include "optimizer/solve_result.hpp"

namespace pkmopt {

struct IpoptOptions {
  int max_iterations = 1000;             ///< Ipopt max_iter, >= 0
  double tolerance = 1e-8;               ///< Ipopt tol (scaled NLP error), > 0
  double acceptable_tolerance = 1e-6;    ///< Ipopt acceptable_tol, >= tolerance
  double constraint_tolerance = 1e-8;    ///< Ipopt constr_viol_tol (absolute), > 0
  double max_seconds = 0.0;              ///< Ipopt max_cpu_time; 0 = no limit
  int limited_memory_history = 6;        ///< L-BFGS pairs kept, >= 1
  double finite_difference_step = 1e-6;  ///< relative step when the problem has no gradient
  int print_level = 0;                   ///< Ipopt print_level, 0..12
  /// Further Ipopt options by name and value ("mu_strategy", "adaptive"); a value that parses
  /// as an integer or a number is set as one. Ipopt rejects unknown names or bad values, and
  /// the run then ends with status failed and Ipopt's message.
  std::vector<std::pair<std::string, std::string>> extra_options;

  /// Empty when valid, else "IpoptOptions::<name> = <value>. Violated constraint: <rule>".
  std::optional<std::string> validate() const;
};

/// Why Ipopt cannot take this problem (several objectives, inconsistent bounds, a gradient
/// whose sparsity pattern is out of range), or empty when it can.
std::optional<std::string> ipopt_explain_unsupported(const Problem& problem);

/// Runs Ipopt from x0 (clamped into the bounds). See the header comment for what throws.
SolveResult solve_with_ipopt(const Problem& problem, const std::vector<double>& x0,
                             const IpoptOptions& options = {});

}  // namespace pkmopt
