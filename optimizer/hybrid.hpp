// Hybrid front builder: NSGA-II explores, then Ipopt polishes every design of its front.
//
// Polishing a design x with objectives f(x) solves the epsilon-constraint subproblem
//   min f_1(y) / s_1  s.t.  (f_j(y) - f_j(x)) / s_j <= 0 (j >= 2),  h(y) = 0,  g(y) <= 0
// from y = x (s = the front's objective ranges), so a converged, feasible result is at least as
// good as x in every objective and lies on the (local) Pareto front. The result is the
// non-dominated set of the NSGA-II front and the polished designs; a polish that fails keeps
// the original design (counted in failed_subproblems).
//
// Example:
//   pkmopt::HybridOptions options;
//   options.nsga2.generations = 100;
//   pkmopt::FrontResult front = pkmopt::run_hybrid(zdt1, options);
#pragma once

#include <optional>
#include <string>

#include "optimizer/front_result.hpp"
#include "optimizer/ipopt_solver.hpp"
#include "optimizer/nsga2.hpp"

namespace pkmopt {

struct HybridOptions {
  Nsga2Options nsga2;
  IpoptOptions ipopt = [] {
    IpoptOptions polish;
    polish.max_iterations = 100;
    return polish;
  }();

  std::optional<std::string> validate() const;
};

/// Runs NSGA-II then the polish. Throws std::invalid_argument for bad options or an
/// unsupported problem (one objective, infinite bounds).
FrontResult run_hybrid(const Problem& problem, const HybridOptions& options);

}  // namespace pkmopt
