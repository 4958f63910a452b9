// NLopt (S. G. Johnson, "The NLopt nonlinear-optimization package") on a single-objective
// Problem, algorithms chosen by name.
//
//   name        NLopt algorithm   kind    gradient  constraints
//   DIRECT_L    GN_DIRECT_L       global  no        none
//   DIRECT      GN_DIRECT         global  no        none
//   CRS2        GN_CRS2_LM        global  no        none
//   ESCH        GN_ESCH           global  no        none
//   ISRES       GN_ISRES          global  no        h = 0 and g <= 0
//   MLSL        G_MLSL_LDS        global  local's   none (local_algorithm does the descents)
//   SLSQP       LD_SLSQP          local   yes       h = 0 and g <= 0
//   COBYLA      LN_COBYLA         local   no        h = 0 and g <= 0
//   BOBYQA      LN_BOBYQA         local   no        none
//   MMA         LD_MMA            local   yes       g <= 0
//   CCSAQ       LD_CCSAQ          local   yes       g <= 0
//   LBFGS       LD_LBFGS          local   yes       none
//   NELDERMEAD  LN_NELDERMEAD     local   no        none
//   SBPLX       LN_SBPLX          local   no        none
//   AUGLAG      AUGLAG            local   local's   h = 0 and g <= 0 (penalised, local_algorithm)
// Names are case-insensitive; NLopt's own names (e.g. "LD_SLSQP") are accepted too. Gradient
// algorithms use the problem's gradient, or central finite differences when it has none.
// Global algorithms need finite bounds. An algorithm that cannot take the problem's constraints
// is refused before running by nlopt_explain_unsupported (and solve_with_nlopt throws
// std::invalid_argument with the same message). NLopt's stochastic algorithms draw from NLopt's
// global generator, seeded with `seed` before each run (so concurrent runs are not supported).
//
// Example:
//   pkmopt::NloptOptions options;
//   options.algorithm = "COBYLA";
//   pkmopt::SolveResult result = pkmopt::solve_with_nlopt(hs71, {1, 5, 5, 1}, options);
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "optimizer/problem.hpp"
#include "optimizer/solve_result.hpp"

namespace pkmopt {

struct NloptOptions {
  std::string algorithm = "SLSQP";        ///< see the table above
  std::string local_algorithm = "SLSQP";  ///< for MLSL and AUGLAG (a local algorithm)
  long long max_evaluations = 20000;      ///< objective evaluations, >= 1
  double max_seconds = 0.0;               ///< 0 = no limit
  double relative_tolerance_f = 1e-10;    ///< ftol_rel, >= 0
  double relative_tolerance_x = 1e-8;     ///< xtol_rel, >= 0
  double constraint_tolerance = 1e-8;     ///< per constraint, > 0
  unsigned population = 0;                ///< for CRS2/ISRES/ESCH/MLSL; 0 = NLopt's default
  std::uint64_t seed = 1;
  double finite_difference_step = 1e-7;  ///< relative, when the problem has no gradient

  std::optional<std::string> validate() const;
};

/// The algorithm names of the table above.
std::vector<std::string> nlopt_algorithm_names();

/// Why this algorithm cannot solve this problem (unknown name, several objectives,
/// unsupported constraints, infinite bounds for a global algorithm), or empty.
std::optional<std::string> nlopt_explain_unsupported(const Problem& problem,
                                                     const NloptOptions& options);

/// Runs NLopt from x0 (clamped into the bounds).
SolveResult solve_with_nlopt(const Problem& problem, const std::vector<double>& x0,
                             const NloptOptions& options);

}  // namespace pkmopt
