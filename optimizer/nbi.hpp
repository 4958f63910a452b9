// Normal Boundary Intersection (Das & Dennis 1998) driven by Ipopt.
//
// Anchors (anchors.hpp) give the ideal point z, the ranges s and the normalised pay-off matrix
// Phi (row i = (f(anchor_i) - z) / s). For each weight vector beta on a Das–Dennis lattice of
// the unit simplex (H divisions, C(H + m - 1, m - 1) >= `points` vectors; H = points - 1 for
// two objectives) the subproblem of NbiProblem (scalarization.hpp) is solved:
//   max t  s.t.  (f(x) - z) / s - Phi^T beta - t n  (= 0 or <= 0),  h(x) = 0,  g(x) <= 0
// walking the lattice in order so each subproblem starts from its neighbour's solution (with
// t reset to the largest feasible value for the new beta). Vertices of the lattice are the
// anchors themselves and are not re-solved. Extra starts only when a solve fails, lands on a
// point a known one weakly dominates (within 1e-5 of the ranges), or jumps (farther than
// 3 / H from the previous result in scaled objectives): 3 points on the design-space segment
// between the previous and the new result, the anchors (largest weight first), and
// `global_starts` Latin-hypercube points (seeded by `seed`, t set to its largest feasible value,
// at most 100 Ipopt iterations each); the largest t wins. A repair pass re-solves each lattice
// point from any known point reaching a larger t on its line. Failed subproblems are counted;
// results a kept one weakly dominates within 1e-5 of the ranges (lattice points facing a gap of
// the front) are counted as dominated and dropped. The sweep, restarts, repair and front
// collection are run_front_sweep's (front_sweep.hpp); this builder supplies the lattice and its
// subproblems.
//
// Example:
//   pkmopt::NbiOptions options;
//   options.points = 50;
//   pkmopt::FrontResult front = pkmopt::run_nbi(zdt2, options);
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

struct NbiOptions {
  std::size_t points = 21;     ///< >= 2, lattice size (see header comment)
  bool equality_form = false;  ///< Das & Dennis' equality constraints instead of the relaxed form
  IpoptOptions ipopt;          ///< for every subproblem
  std::vector<double> start;   ///< first start point; empty = default_start()
  std::size_t global_starts = 2;  ///< Latin-hypercube starts per restarted subproblem
  std::uint64_t seed = 1;         ///< seeds the Latin hypercubes (anchors and subproblems)

  std::optional<std::string> validate() const;
};

/// Das–Dennis weight vectors: all beta >= 0, sum beta = 1, entries multiples of 1/divisions,
/// in lexicographic order (the first weight decreasing).
std::vector<std::vector<double>> simplex_lattice(std::size_t dimensions, std::size_t divisions);

std::optional<std::string> nbi_explain_unsupported(const Problem& problem,
                                                   const NbiOptions& options);

/// Builds the front. Throws std::invalid_argument for bad options or an unsupported problem.
FrontResult run_nbi(const Problem& problem, const NbiOptions& options);

}  // namespace pkmopt
