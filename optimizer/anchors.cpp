#include "optimizer/anchors.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "optimizer/random.hpp"
#include "optimizer/scalarization.hpp"

namespace pkmopt {

std::vector<double> default_start(const Problem& problem) {
  const Bounds b = problem.bounds();
  std::vector<double> x(b.lower.size(), 0.0);
  for (std::size_t j = 0; j < x.size(); ++j) {
    const bool low = std::isfinite(b.lower[j]);
    const bool high = std::isfinite(b.upper[j]);
    x[j] = low && high ? 0.5 * (b.lower[j] + b.upper[j])
                       : (low ? b.lower[j] : (high ? b.upper[j] : 0.0));
  }
  return x;
}

std::vector<std::vector<double>> latin_hypercube(const Problem& problem, std::size_t count,
                                                 std::uint64_t seed,
                                                 const std::vector<double>& start) {
  const Bounds b = problem.bounds();
  const std::size_t n = b.lower.size();
  Random rng(seed);
  std::vector<std::vector<double>> lhs(count, std::vector<double>(n));
  std::vector<std::size_t> strata(count);
  for (std::size_t j = 0; j < n; ++j) {
    for (std::size_t k = 0; k < count; ++k) strata[k] = k;
    rng.shuffle(strata);
    const bool finite = std::isfinite(b.lower[j]) && std::isfinite(b.upper[j]);
    for (std::size_t k = 0; k < count; ++k) {
      const double u =
          (static_cast<double>(strata[k]) + rng.uniform01()) / static_cast<double>(count);
      lhs[k][j] = finite ? b.lower[j] + u * (b.upper[j] - b.lower[j]) : start[j];
    }
  }
  return lhs;
}

namespace {

// L-BFGS iterations a stage-1 solve gets before it switches to SR1 updates.
constexpr int kBfgsIterations = 30;

// A stage-1 solve. Its augmentation is concave wherever an f_j is (ZDT2's concave front): the
// L-BFGS updates of Ipopt are then skipped and it crawls with gradient-sized steps to the
// iteration limit (1000 iterations on ZDT2 from the centre). SR1 updates keep negative
// curvature (6 iterations there) but cost about twice as many iterations as BFGS on convex
// problems (ZDT1). So: BFGS for kBfgsIterations, then, if it has not converged, SR1 from where
// it stopped with the rest of the budget. An update type the caller set explicitly is kept.
SolveResult solve_stage1(const Problem& stage1, const std::vector<double>& x0,
                         const IpoptOptions& options) {
  const bool caller_chose =
      std::any_of(options.extra_options.begin(), options.extra_options.end(),
                  [](const auto& option) { return option.first == "limited_memory_update_type"; });
  if (caller_chose || options.max_iterations <= kBfgsIterations) {
    return solve_with_ipopt(stage1, x0, options);
  }
  IpoptOptions bfgs = options;
  bfgs.max_iterations = kBfgsIterations;
  SolveResult first = solve_with_ipopt(stage1, x0, bfgs);
  if (first.status != SolveStatus::max_iterations || first.x.empty()) return first;
  IpoptOptions sr1 = options;
  sr1.max_iterations = options.max_iterations - kBfgsIterations;
  sr1.extra_options.emplace_back("limited_memory_update_type", "sr1");
  SolveResult second = solve_with_ipopt(stage1, first.x, sr1);
  second.iterations += first.iterations;
  second.fitness_evaluations += first.fitness_evaluations;
  second.gradient_evaluations += first.gradient_evaluations;
  second.seconds += first.seconds;
  const bool second_ok = !second.fitness.empty() && second.constraint_violation <= 1e-6;
  return second_ok || first.fitness.empty() ? second : first;
}

}  // namespace

AnchorSet compute_anchors(const Problem& problem, const std::vector<double>& start,
                          const IpoptOptions& options, std::size_t random_starts,
                          std::uint64_t seed) {
  const std::size_t m = problem.num_objectives();
  AnchorSet set;
  set.points.resize(m);
  const std::vector<std::vector<double>> lhs = latin_hypercube(problem, random_starts, seed, start);
  for (std::size_t i = 0; i < m; ++i) {
    AnchorPoint& anchor = set.points[i];
    // Stage 1: min f_i + rho sum_{j != i} f_j / s_j (rho = 1e-3, s_j = max(1, |f_j(start)|)):
    // the small augmentation keeps the anchor off weakly dominated plateaus.
    const std::vector<double> at_start = checked_fitness(problem, start);
    std::vector<double> weights(m, 0.0);
    for (std::size_t j = 0; j < m; ++j)
      weights[j] = j == i ? 1.0 : 1e-3 / std::max(1.0, std::abs(at_start[j]));
    // Multi-start: `start`, then a Latin hypercube of `random_starts` points (each variable's
    // range cut into as many strata, one point per stratum), so a non-convex f_i (ZDT3's last
    // front piece) is minimised globally with good odds. The best usable result is kept.
    const ScalarizedProblem stage1(problem, weights, {});
    SolveResult first = solve_stage1(stage1, start, options);
    ++set.solves;
    IpoptOptions short_run = options;
    short_run.max_iterations = std::min(options.max_iterations, 100);
    for (std::size_t k = 0; k < lhs.size(); ++k) {
      SolveResult other = solve_stage1(stage1, lhs[k], short_run);
      ++set.solves;
      const bool other_ok = !other.fitness.empty() && other.constraint_violation <= 1e-6;
      const bool first_ok = !first.fitness.empty() && first.constraint_violation <= 1e-6;
      if (other_ok && (!first_ok || other.objective < first.objective)) first = std::move(other);
    }
    anchor.x = first.x;
    anchor.summary = first.summary();
    // Next to a steep objective (ZDT's sqrt(f_1) at f_1 = 0) Ipopt may stop without
    // converging at a point that is still feasible and good: such a point is kept.
    const bool feasible_point = !first.fitness.empty() && first.constraint_violation <= 1e-6;
    if (!first.usable() && !feasible_point) {
      ++set.failed;
      continue;
    }
    anchor.ok = true;
    anchor.fitness = checked_fitness(problem, anchor.x);
    const double best = anchor.fitness[i];
    std::vector<double> others(m, 0.0);
    for (std::size_t j = 0; j < m; ++j)
      if (j != i) others[j] = 1.0 / std::max(1.0, std::abs(anchor.fitness[j]));
    const double scale = std::max(1.0, std::abs(best));
    // Gradient-based NLP scaling would shrink this objective next to a steep f_i (ZDT's
    // sqrt(f_1) at f_1 = 0) and stop Ipopt early: the refinement runs unscaled.
    IpoptOptions unscaled = options;
    unscaled.extra_options.emplace_back("nlp_scaling_method", "none");
    const SolveResult refined = solve_with_ipopt(
        ScalarizedProblem(problem, others, {{i, best + 1e-7 * scale, scale}}), anchor.x, unscaled);
    ++set.solves;
    if (refined.usable()) {
      const std::vector<double> f = checked_fitness(problem, refined.x);
      if (f[i] <= best + 1e-7 * scale) {
        anchor.x = refined.x;
        anchor.fitness = f;
        anchor.summary = refined.summary();
      }
    }
  }
  set.ideal.assign(m, INFINITY);
  set.nadir.assign(m, -INFINITY);
  std::size_t good = 0;
  for (const AnchorPoint& anchor : set.points) {
    if (!anchor.ok) continue;
    ++good;
    for (std::size_t j = 0; j < m; ++j) {
      set.ideal[j] = std::min(set.ideal[j], anchor.fitness[j]);
      set.nadir[j] = std::max(set.nadir[j], anchor.fitness[j]);
    }
  }
  if (good == 0) return set;  // the caller reports it: failed == number of objectives
  set.range.resize(m);
  for (std::size_t j = 0; j < m; ++j) {
    const double range = set.nadir[j] - set.ideal[j];
    set.range[j] = range > 1e-12 ? range : 1.0;
  }
  return set;
}

std::vector<std::vector<double>> segment_starts(const std::vector<double>& a,
                                                const std::vector<double>& b) {
  std::vector<std::vector<double>> starts;
  for (double lambda : {0.25, 0.5, 0.75}) {
    std::vector<double> between(a.size());
    for (std::size_t i = 0; i < a.size(); ++i) between[i] = (1.0 - lambda) * a[i] + lambda * b[i];
    starts.push_back(std::move(between));
  }
  return starts;
}

bool continuation_jumped(const AnchorSet& anchors, const std::vector<double>& previous,
                         const std::vector<double>& f, double step, double max_steps) {
  if (previous.empty()) return false;
  double squared = 0.0;
  for (std::size_t j = 0; j < anchors.range.size(); ++j) {  // the objectives only
    const double d = (f[j] - previous[j]) / anchors.range[j];
    squared += d * d;
  }
  return std::sqrt(squared) > max_steps * step;
}

}  // namespace pkmopt
