// The epsilon-constraint method (Haimes, Lasdon & Wismer 1971) driven by Ipopt.
//
// With anchors (see anchors.hpp) giving the ideal point z and the pay-off nadir N, each
// subproblem minimises the primary objective p with bounds on the others:
//   min f_p(x) / s_p   s.t.  (f_j(x) - epsilon_j) / s_j <= 0  (j != p),  h(x) = 0,  g(x) <= 0
// with s_j = N_j - z_j. Two objectives: epsilon runs over `points` - 2 evenly spaced interior
// values between the anchors (plus the two anchors, `points` in all). More objectives: a grid
// of q = max(2, floor(points^(1/(m-1)))) values z_j + k (N_j - z_j) / q, k = 1..q, per other
// objective, visited in serpentine order. Each subproblem starts from the previous successful
// solution (continuation along the front). Extra starts are spent only when that solve fails,
// lands on a point a known one weakly dominates (within 1e-5 of the ranges), or jumps (lands
// farther than 3 grid steps from the previous result, in objectives scaled by the ranges): then
// the subproblem is also solved from 3 points on the design-space segment between the previous
// and the new result (a piece of a disconnected front the continuation skipped lies between
// them), from the anchors, and from `global_starts` Latin-hypercube points (seeded by `seed`, at
// most 100 Ipopt iterations each); the usable result with the lowest f_p is kept. A repair pass
// then re-solves every subproblem whose result (or failure) a known point beats, i.e. a point
// satisfying its epsilon bounds with a lower f_p (typically the neighbour with the tighter
// bound): this moves results stuck on dominated pieces (ZDT3) and gives failed subproblems a
// feasible start. Subproblems with no feasible point are counted as failed; results that a kept
// one weakly dominates within 1e-5 of the ranges (levels in a gap of the front repeat the end of
// the piece before the gap; inactive bounds) are counted as dominated and dropped.
// The sweep, restarts, repair and front collection are run_front_sweep's (front_sweep.hpp);
// this builder supplies the epsilon grid and its subproblems.
//
// Example:
//   pkmopt::EpsilonConstraintOptions options;
//   options.points = 50;
//   pkmopt::FrontResult front = pkmopt::run_epsilon_constraint(zdt1, options);
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "optimizer/front_result.hpp"
#include "optimizer/ipopt_solver.hpp"
#include "optimizer/problem.hpp"

namespace pkmopt {

struct EpsilonConstraintOptions {
  std::size_t points = 21;            ///< >= 2 (see header comment)
  std::size_t primary_objective = 0;  ///< p, 0-based
  IpoptOptions ipopt;                 ///< for every subproblem
  std::vector<double> start;          ///< first start point; empty = default_start()
  std::size_t global_starts = 2;      ///< Latin-hypercube starts per restarted subproblem
  std::uint64_t seed = 1;             ///< seeds the Latin hypercubes (anchors and subproblems)

  std::optional<std::string> validate() const;
};

/// Why the method cannot take this problem (one objective, bad bounds, primary out of range).
std::optional<std::string> epsilon_constraint_explain_unsupported(
    const Problem& problem, const EpsilonConstraintOptions& options);

/// Builds the front. Throws std::invalid_argument for bad options or an unsupported problem;
/// solver failures are counted in the result (and `message` explains an empty front).
FrontResult run_epsilon_constraint(const Problem& problem, const EpsilonConstraintOptions& options);

}  // namespace pkmopt
