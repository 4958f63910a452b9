// The sweep-and-repair driver shared by the Ipopt front builders (epsilon-constraint in
// epsilon_constraint.hpp, Normal Boundary Intersection in nbi.hpp).
//
// A front builder cuts the front into K single-objective subproblems S_1..S_K, one per front
// point, from the anchors; the driver solves them. A builder plugs in only its scalarisation: a
// planner that, given the anchors, returns the subproblems in sweep order (FrontSubproblem: the
// problem Ipopt solves, its start from a design, and a score s_k(f) of a base fitness f, larger
// is better) and a few constants (SweepPlan). The driver then runs, on the counted problem:
//
//   1. Anchors: compute_anchors(problem, start, ipopt, 8 random starts, seed); the usable ones
//      are the first known points. tol_j = 1e-5 range_j (0 when every anchor failed).
//   2. Sweep: S_1..S_K in order, each started from the previous usable result (continuation;
//      S_1 from SweepPlan::first_x). Extra starts only when the solve fails, lands on a point f
//      a known point e weakly dominates within tol (e_j <= f_j + tol_j for all objectives), or
//      jumps (continuation_jumped(anchors, previous, f, jump_step, jump_max_steps)): 3 points on
//      the design-space segment from the previous result to the new one (at most 100 Ipopt
//      iterations each), the subproblem's restart anchors (full runs), `global_starts`
//      Latin-hypercube points (seeded by `seed`, at most 100 iterations), and, if the segment
//      was not tried yet and the best result so far jumps, the segment to it. A result replaces
//      the current one when usable with a subproblem objective lower by more than
//      1e-9 (1 + |current|).
//   3. Repair (at most 3 passes, until nothing changes): S_k is re-solved from the first known
//      point e it admits with the highest score above s_k(f_k) + repair_margin (f_k its
//      result; any admitted point when it failed), unless the last repair of S_k started from
//      that same point. A result scoring higher than e replaces f_k (and becomes a known point);
//      otherwise e itself becomes S_k's answer when keep_known_on_failed_repair.
//   4. Front: the anchors, then the results in order; a failed subproblem counts in
//      failed_subproblems, a result a kept point weakly dominates within tol in
//      dominated_subproblems, as do the points make_front drops. `subproblems` counts every
//      Ipopt solve (anchors included).
//
// Example (a weighted-sum toy scalarisation; see tests/optimizer/front_sweep_test.cpp):
//   pkmopt::FrontSweepOptions options;
//   options.algorithm = "weighted_sum";
//   pkmopt::FrontResult front = pkmopt::run_front_sweep(problem, options,
//       [](const pkmopt::Problem& counted, const pkmopt::AnchorSet& anchors,
//          const std::vector<double>& start) {
//         pkmopt::SweepPlan plan;
//         for (double w : {0.25, 0.5, 0.75})
//           plan.subproblems.push_back(std::make_unique<WeightedSum>(counted, w));
//         plan.first_x = anchors.points[0].x;
//         plan.first_f = anchors.points[0].fitness;
//         return plan;
//       });
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "optimizer/anchors.hpp"
#include "optimizer/front_result.hpp"
#include "optimizer/ipopt_solver.hpp"
#include "optimizer/problem.hpp"

namespace pkmopt {

/// One subproblem of a sweep: the single-objective problem whose solution is one front point.
class FrontSubproblem {
 public:
  virtual ~FrontSubproblem() = default;
  /// What Ipopt solves. Its first n variables are the design x; any after them (NBI's t) are
  /// the scalarisation's own and dropped from solutions.
  virtual const Problem& problem() const = 0;
  /// A start vector for problem() from the design x; fx is the base fitness at x, or empty when
  /// not known (an implementation that needs it evaluates it).
  virtual std::vector<double> start(const std::vector<double>& x,
                                    const std::vector<double>& fx) const = 0;
  /// How good a base fitness is for this subproblem (larger is better): what repair compares.
  virtual double score(const std::vector<double>& f) const = 0;
  /// Whether a known point of fitness f may answer this subproblem in repair.
  virtual bool admits(const std::vector<double>& /*f*/) const { return true; }
  /// Anchors (indices into AnchorSet::points, usable ones) to restart from, in order.
  virtual std::vector<std::size_t> restart_anchors() const = 0;
};

/// What a scalarisation gives the driver once the anchors are known.
struct SweepPlan {
  std::vector<std::unique_ptr<FrontSubproblem>> subproblems;  ///< in sweep order
  /// Why no subproblem could be built (the front's message); empty otherwise.
  std::string failure;
  std::vector<double> first_x;  ///< warm start of the first subproblem
  std::vector<double> first_f;  ///< its base fitness; empty when not known
  double jump_step = 1.0;       ///< continuation_jumped(..., jump_step, jump_max_steps)
  double jump_max_steps = 3.0;
  double repair_margin = 0.0;  ///< a known point must score this much above a result
  bool keep_known_on_failed_repair = true;
  /// The weak-dominance test as NBI has always written it, !(e_j > f_j + tol_j): a NaN entry
  /// then covers (the epsilon-constraint form e_j <= f_j + tol_j does not). Both agree on
  /// finite values; kept so each builder's results stay what they were.
  bool nan_covers = false;
};

/// Builds the plan from the counted problem (subproblems must evaluate through it), the
/// anchors and the resolved start point.
using SweepPlanner = std::function<SweepPlan(const Problem& counted, const AnchorSet& anchors,
                                             const std::vector<double>& start)>;

struct FrontSweepOptions {
  std::string algorithm;          ///< FrontResult::algorithm
  IpoptOptions ipopt;             ///< for every solve
  std::vector<double> start;      ///< first start point; empty = default_start()
  std::size_t global_starts = 2;  ///< Latin-hypercube starts per restarted subproblem
  std::uint64_t seed = 1;         ///< seeds the Latin hypercubes (anchors and subproblems)
};

/// Runs anchors, sweep, repair and front collection (see header comment). Never throws for
/// solver failure; options and problem are the caller's to check.
FrontResult run_front_sweep(const Problem& problem, const FrontSweepOptions& options,
                            const SweepPlanner& planner);

/// The checks every front builder makes: consistent bounds, at least two objectives (messages
/// name `algorithm`).
std::optional<std::string> front_problem_explain_unsupported(const Problem& problem,
                                                             std::string_view algorithm);
/// A start point of the wrong size (empty = default start, accepted).
std::optional<std::string> front_start_explain_unsupported(const Problem& problem,
                                                           std::string_view algorithm,
                                                           const std::vector<double>& start);

}  // namespace pkmopt
