// Anchor points of a front: for each objective i, a design minimising f_i (first solve:
// min f_i + 1e-3 sum_{j != i} f_j / max(1, |f_j(start)|), which avoids weakly dominated
// plateaus; L-BFGS for 30 iterations, then SR1 updates if it has not converged, because the
// augmentation is concave where an f_j is and L-BFGS stalls there), refined lexicographically when
// Ipopt manages it (second solve: minimise sum_{j != i} f_j / s_j subject to f_i <= f_i* + 1e-7
// max(1, |f_i*|), s_j = max(1, |f_j|)). The anchors give the ideal point (ideal_i = f_i(anchor_i)),
// the nadir estimate of the pay-off table (nadir_j = max_i f_j(anchor_i)) and the objective ranges
// used to scale the epsilon-constraint and NBI subproblems.
//
// Example:
//   pkmopt::AnchorSet anchors = pkmopt::compute_anchors(zdt1, start, ipopt_options);
//   // anchors.points[0].fitness ~ (0, 1), anchors.points[1].fitness ~ (1, 0)
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "optimizer/ipopt_solver.hpp"
#include "optimizer/problem.hpp"

namespace pkmopt {

struct AnchorPoint {
  std::vector<double> x;
  std::vector<double> fitness;  ///< full fitness of the base problem
  bool ok = false;              ///< both solves usable
  std::string summary;          ///< Ipopt's summary of the last solve
};

struct AnchorSet {
  std::vector<AnchorPoint> points;          ///< one per objective
  std::vector<double> ideal, nadir, range;  ///< range_i = nadir_i - ideal_i (1 if <= 1e-12)
  std::size_t solves = 0;
  std::size_t failed = 0;  ///< anchors whose first solve failed
};

/// A start point inside the bounds: the centre, or the finite bound, or 0.
std::vector<double> default_start(const Problem& problem);

/// `count` Latin-hypercube points in the bounds (each variable's range cut into `count`
/// strata, one point per stratum, strata shuffled per variable by a Random seeded with `seed`);
/// a variable with an infinite bound takes its value from `start` (size n).
std::vector<std::vector<double>> latin_hypercube(const Problem& problem, std::size_t count,
                                                 std::uint64_t seed,
                                                 const std::vector<double>& start);

/// The points 1/4, 1/2 and 3/4 of the way from a to b (design space): restart points for a
/// front builder whose continuation jumped from a to b over a piece of the front.
std::vector<std::vector<double>> segment_starts(const std::vector<double>& a,
                                                const std::vector<double>& b);

/// True when f lies more than `max_steps` steps (of size `step`, in objective space normalised
/// by the anchors' ranges; fitness rows, only their objective entries count) from `previous`:
/// the continuation jumped. False for an empty `previous`.
bool continuation_jumped(const AnchorSet& anchors, const std::vector<double>& previous,
                         const std::vector<double>& f, double step, double max_steps = 3.0);

/// Anchors of a multi-objective problem from `start` (see header comment). Never throws for
/// solver failure: a failed anchor has ok = false; if every anchor failed, failed == m and
/// range is left empty.
/// The first solve of each anchor also starts from `random_starts` Latin-hypercube points
/// (seeded by `seed`; finite bounds only) and keeps the best.
AnchorSet compute_anchors(const Problem& problem, const std::vector<double>& start,
                          const IpoptOptions& options, std::size_t random_starts = 8,
                          std::uint64_t seed = 1);

}  // namespace pkmopt
