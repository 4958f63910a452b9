#include "optimizer/epsilon_constraint.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>

#include "optimizer/anchors.hpp"
#include "optimizer/scalarization.hpp"

namespace pkmopt {
namespace {

// True when an earlier result weakly dominates the objectives of f (first m entries) within
// `tolerance` (one entry per objective).
bool dominated_by_any(const std::vector<std::vector<double>>& earlier, const std::vector<double>& f,
                      std::size_t m, const std::vector<double>& tolerance) {
  if (f.empty()) return false;
  for (const auto& e : earlier) {
    bool covers = true;
    for (std::size_t i = 0; i < m && covers; ++i) covers = e[i] <= f[i] + tolerance[i];
    if (covers) return true;
  }
  return false;
}

}  // namespace

std::optional<std::string> EpsilonConstraintOptions::validate() const {
  if (points < 2)
    return fmt::format("EpsilonConstraintOptions::points = {}. Violated constraint: points >= 2",
                       points);
  if (!start.empty())
    for (double v : start)
      if (!std::isfinite(v))
        return std::string("EpsilonConstraintOptions::start has a non-finite value");
  return ipopt.validate();
}

std::optional<std::string> epsilon_constraint_explain_unsupported(
    const Problem& problem, const EpsilonConstraintOptions& options) {
  try {
    check_bounds(problem);
  } catch (const std::invalid_argument& e) {
    return std::string(e.what());
  }
  if (problem.num_objectives() < 2)
    return fmt::format(
        "epsilon_constraint builds fronts, but the problem named '{}' has one "
        "objective (use ipopt)",
        problem.name());
  if (options.primary_objective >= problem.num_objectives())
    return fmt::format("epsilon_constraint: primary objective {} out of range (the problem has {})",
                       options.primary_objective + 1, problem.num_objectives());
  if (!options.start.empty() && options.start.size() != problem.num_variables())
    return fmt::format("epsilon_constraint: start has {} values, the problem has {} variables",
                       options.start.size(), problem.num_variables());
  return std::nullopt;
}

FrontResult run_epsilon_constraint(const Problem& problem,
                                   const EpsilonConstraintOptions& options) {
  if (auto error = options.validate()) throw std::invalid_argument(*error);
  if (auto reason = epsilon_constraint_explain_unsupported(problem, options))
    throw std::invalid_argument(*reason);
  const auto clock_start = std::chrono::steady_clock::now();
  CountingProblem counted(problem);
  const std::size_t m = problem.num_objectives();
  const std::size_t p = options.primary_objective;
  const std::vector<double> start = options.start.empty() ? default_start(problem) : options.start;

  std::vector<std::vector<double>> xs, fitness;
  FrontResult result;
  std::size_t duplicates = 0;
  std::vector<double> tolerance(m, 0.0);
  const AnchorSet anchors = compute_anchors(counted, start, options.ipopt, 8, options.seed);
  result.subproblems += anchors.solves;
  result.failed_subproblems += anchors.failed;
  for (const AnchorPoint& anchor : anchors.points)
    if (anchor.ok) {
      xs.push_back(anchor.x);
      fitness.push_back(anchor.fitness);
    }

  if (!anchors.range.empty()) {
    // The other objectives and their epsilon values.
    std::vector<std::size_t> others;
    for (std::size_t j = 0; j < m; ++j)
      if (j != p) others.push_back(j);
    std::size_t per_axis;
    std::vector<double> fractions;
    if (m == 2) {
      per_axis = options.points >= 2 ? options.points - 2 : 0;
      for (std::size_t k = per_axis; k >= 1; --k)  // from the primary anchor's side
        fractions.push_back(static_cast<double>(k) / static_cast<double>(per_axis + 1));
    } else {
      per_axis = std::max<std::size_t>(
          2, static_cast<std::size_t>(std::floor(
                 std::pow(static_cast<double>(options.points), 1.0 / static_cast<double>(m - 1)) +
                 1e-9)));
      for (std::size_t k = per_axis; k >= 1; --k)
        fractions.push_back(static_cast<double>(k) / static_cast<double>(per_axis));
    }
    std::vector<double> warm = anchors.points[p].ok ? anchors.points[p].x : start;
    // Serpentine walk over the grid: axis 0 runs fastest and reverses direction each time a
    // slower axis moves, so consecutive subproblems are neighbours.
    std::vector<std::size_t> counter(others.size(), 0);
    const std::size_t total =
        fractions.empty()
            ? 0
            : static_cast<std::size_t>(std::llround(std::pow(static_cast<double>(fractions.size()),
                                                             static_cast<double>(others.size()))));
    // Global starts: the anchors of the other objectives (each satisfies its own epsilon
    // bound whatever its value, so narrow feasible sets stay reachable), then a Latin hypercube.
    std::vector<std::vector<double>> global_starts;
    for (std::size_t j = 0; j < m; ++j)
      if (j != p && anchors.points[j].ok) global_starts.push_back(anchors.points[j].x);
    for (std::vector<double>& point :
         latin_hypercube(problem, options.global_starts, options.seed, start))
      global_starts.push_back(std::move(point));
    IpoptOptions short_run = options.ipopt;
    short_run.max_iterations = std::min(options.ipopt.max_iterations, 100);
    for (std::size_t j = 0; j < m; ++j) tolerance[j] = 1e-5 * anchors.range[j];
    const double primary_scale = anchors.range[p];
    std::vector<double> weights(m, 0.0);
    weights[p] = 1.0 / primary_scale;
    for (std::size_t step = 0; step < total; ++step) {
      std::vector<ObjectiveBound> bounds;
      std::size_t stride = 1;
      for (std::size_t a = 0; a < others.size(); ++a) {
        const std::size_t level = (step / stride) % fractions.size();
        const bool reversed = ((step / (stride * fractions.size())) % 2) == 1;
        const std::size_t k = reversed ? fractions.size() - 1 - level : level;
        stride *= fractions.size();
        const std::size_t j = others[a];
        bounds.push_back({j, anchors.ideal[j] + fractions[k] * anchors.range[j], anchors.range[j]});
      }
      const ScalarizedProblem sub(counted, weights, bounds);
      SolveResult solved = solve_with_ipopt(sub, warm, options.ipopt);
      ++result.subproblems;
      std::vector<double> f =
          solved.usable() ? checked_fitness(counted, solved.x) : std::vector<double>{};
      // Continuation can trap the local solver on one piece of a disconnected front: a failed
      // or dominated result is retried once from the primary anchor.
      if ((!solved.usable() || dominated_by_any(fitness, f, m, tolerance)) &&
          anchors.points[p].ok) {
        SolveResult retry = solve_with_ipopt(sub, anchors.points[p].x, options.ipopt);
        ++result.subproblems;
        if (retry.usable()) {
          std::vector<double> g = checked_fitness(counted, retry.x);
          if (f.empty() || !dominated_by_any(fitness, g, m, tolerance)) {
            solved = std::move(retry);
            f = std::move(g);
          }
        }
      }
      // Multi-start: the same subproblem from each global start point; the usable optimum
      // with the lowest primary objective wins (a local solver otherwise stops on locally
      // optimal pieces that the global front dominates, as on ZDT3).
      for (const std::vector<double>& global_start : global_starts) {
        SolveResult other = solve_with_ipopt(sub, global_start, short_run);
        ++result.subproblems;
        if (other.usable() &&
            (!solved.usable() ||
             other.objective < solved.objective - 1e-9 * (1.0 + std::abs(solved.objective)))) {
          solved = std::move(other);
          f = checked_fitness(counted, solved.x);
        }
      }
      if (!solved.usable()) {
        ++result.failed_subproblems;
        continue;
      }
      warm = solved.x;
      // A result that an earlier one weakly dominates within 1e-5 of the objective ranges
      // (epsilon bounds in a gap of the front, or inactive ones) adds nothing: dropped.
      if (dominated_by_any(fitness, f, m, tolerance)) {
        ++duplicates;
        continue;
      }
      xs.push_back(solved.x);
      fitness.push_back(std::move(f));
    }
  }

  FrontResult front = make_front(problem, xs, fitness);
  front.algorithm = "epsilon_constraint";
  front.subproblems = result.subproblems;
  front.failed_subproblems = result.failed_subproblems;
  front.dominated_subproblems = duplicates + xs.size() - front.x.size();
  front.fitness_evaluations = counted.fitness_evaluations();
  front.gradient_evaluations = counted.gradient_evaluations();
  front.seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - clock_start).count();
  if (anchors.range.empty())
    front.message = "every anchor solve failed: " + anchors.points.front().summary;
  else if (front.failed_subproblems > 0)
    front.message =
        fmt::format("{} of {} subproblems failed", front.failed_subproblems, front.subproblems);
  return front;
}

}  // namespace pkmopt
