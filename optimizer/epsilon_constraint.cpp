#include "optimizer/epsilon_constraint.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <vector>

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

  std::size_t solves = 0, failed = 0, retried = 0, repaired = 0;
  const AnchorSet anchors = compute_anchors(counted, start, options.ipopt, 8, options.seed);
  solves += anchors.solves;
  failed += anchors.failed;
  // Every point found so far (anchors, then subproblem results): x and full fitness.
  std::vector<std::vector<double>> known_x, known_f;
  for (const AnchorPoint& anchor : anchors.points)
    if (anchor.ok) {
      known_x.push_back(anchor.x);
      known_f.push_back(anchor.fitness);
    }
  const std::size_t anchor_count = known_x.size();

  // One epsilon-constraint subproblem and its best result so far.
  struct Slot {
    std::vector<ObjectiveBound> bounds;
    std::vector<double> x, f;              // empty while no feasible point is known
    std::size_t repaired_from = SIZE_MAX;  // known point the last repair started from
  };
  std::vector<Slot> slots;
  std::vector<double> tolerance(m, 0.0);

  if (!anchors.range.empty()) {
    // The other objectives and their epsilon values.
    std::vector<std::size_t> others;
    for (std::size_t j = 0; j < m; ++j)
      if (j != p) others.push_back(j);
    std::vector<double> fractions;
    double grid_step;  // between neighbouring levels, as a fraction of the objective ranges
    if (m == 2) {
      const std::size_t per_axis = options.points - 2;
      for (std::size_t k = per_axis; k >= 1; --k)  // from the primary anchor's side
        fractions.push_back(static_cast<double>(k) / static_cast<double>(per_axis + 1));
      grid_step = 1.0 / static_cast<double>(per_axis + 1);
    } else {
      const std::size_t per_axis = std::max<std::size_t>(
          2, static_cast<std::size_t>(std::floor(
                 std::pow(static_cast<double>(options.points), 1.0 / static_cast<double>(m - 1)) +
                 1e-9)));
      for (std::size_t k = per_axis; k >= 1; --k)
        fractions.push_back(static_cast<double>(k) / static_cast<double>(per_axis));
      grid_step = 1.0 / static_cast<double>(per_axis);
    }
    // Serpentine walk over the grid: axis 0 runs fastest and reverses direction each time a
    // slower axis moves, so consecutive subproblems are neighbours.
    const std::size_t total =
        fractions.empty()
            ? 0
            : static_cast<std::size_t>(std::llround(std::pow(static_cast<double>(fractions.size()),
                                                             static_cast<double>(others.size()))));
    for (std::size_t step = 0; step < total; ++step) {
      Slot slot;
      std::size_t stride = 1;
      for (std::size_t a = 0; a < others.size(); ++a) {
        const std::size_t level = (step / stride) % fractions.size();
        const bool reversed = ((step / (stride * fractions.size())) % 2) == 1;
        const std::size_t k = reversed ? fractions.size() - 1 - level : level;
        stride *= fractions.size();
        const std::size_t j = others[a];
        slot.bounds.push_back(
            {j, anchors.ideal[j] + fractions[k] * anchors.range[j], anchors.range[j]});
      }
      slots.push_back(std::move(slot));
    }

    // Fallback starts, used only when the warm-started solve fails, lands on a point that a
    // known one weakly dominates, or jumps (see `jumped`): the primary anchor, the anchors of the
    // other objectives (each satisfies its own epsilon bound whatever its value, so narrow feasible
    // sets stay reachable), then `global_starts` Latin-hypercube points (at most 100 iterations
    // each).
    struct Start {
      std::vector<double> x;
      bool short_run;
    };
    std::vector<Start> fallback;
    if (anchors.points[p].ok) fallback.push_back({anchors.points[p].x, false});
    for (std::size_t j = 0; j < m; ++j)
      if (j != p && anchors.points[j].ok) fallback.push_back({anchors.points[j].x, false});
    for (std::vector<double>& point :
         latin_hypercube(problem, options.global_starts, options.seed, start))
      fallback.push_back({std::move(point), true});
    IpoptOptions short_run = options.ipopt;
    short_run.max_iterations = std::min(options.ipopt.max_iterations, 100);
    for (std::size_t j = 0; j < m; ++j) tolerance[j] = 1e-5 * anchors.range[j];
    std::vector<double> weights(m, 0.0);
    weights[p] = 1.0 / anchors.range[p];
    // a replaces b when usable and lower in the primary objective (beyond rounding).
    auto better = [](const SolveResult& a, const SolveResult& b) {
      return a.usable() &&
             (!b.usable() || a.objective < b.objective - 1e-9 * (1.0 + std::abs(b.objective)));
    };

    std::vector<double> warm = anchors.points[p].ok ? anchors.points[p].x : start;
    std::vector<double> warm_f =
        anchors.points[p].ok ? anchors.points[p].fitness : std::vector<double>{};
    // Continuation jumped: the result is farther from the previous one than 3 grid steps (in
    // objectives scaled by their ranges), as when the front has a gap here, or when the local
    // solver skipped over a piece of a disconnected front.
    auto jumped = [&](const std::vector<double>& f) {
      return continuation_jumped(anchors, warm_f, f, grid_step);
    };
    for (Slot& slot : slots) {
      const ScalarizedProblem sub(counted, weights, slot.bounds);
      SolveResult solved = solve_with_ipopt(sub, warm, options.ipopt);
      ++solves;
      std::vector<double> f =
          solved.usable() ? checked_fitness(counted, solved.x) : std::vector<double>{};
      if (!solved.usable() || dominated_by_any(known_f, f, m, tolerance) || jumped(f)) {
        ++retried;
        auto try_from = [&](const std::vector<double>& from, bool is_short) {
          SolveResult other = solve_with_ipopt(sub, from, is_short ? short_run : options.ipopt);
          ++solves;
          if (better(other, solved)) {
            solved = std::move(other);
            f = checked_fitness(counted, solved.x);
          }
        };
        // After a jump, a piece of the front the continuation skipped lies between the
        // previous result and this one: starts on the segment joining them in design space.
        bool bridged = false;
        auto bridge = [&]() {
          bridged = true;
          for (const std::vector<double>& between : segment_starts(warm, solved.x))
            try_from(between, true);
        };
        if (solved.usable()) bridge();
        for (const Start& from : fallback) try_from(from.x, from.short_run);
        if (!bridged && solved.usable() && jumped(f)) bridge();
      }
      if (!solved.usable()) continue;  // retried from its neighbours below
      warm = solved.x;
      warm_f = f;
      slot.x = solved.x;
      slot.f = f;
      known_x.push_back(std::move(solved.x));
      known_f.push_back(std::move(f));
    }

    // Repair: a subproblem whose result (or failure) is beaten by a known point that satisfies
    // its epsilon bounds with a lower primary objective, typically the solution of its
    // neighbour with tighter bounds, is re-solved from that point. On a disconnected front this
    // moves results stuck on a dominated piece to the global one, and gives failed subproblems
    // a feasible start. If Ipopt still fails, the known point itself is the subproblem's
    // best answer (a repeat, dropped below).
    for (int pass = 0; pass < 3; ++pass) {
      bool changed = false;
      for (Slot& slot : slots) {
        const double current = slot.f.empty() ? INFINITY : slot.f[p] - tolerance[p];
        std::size_t best = known_f.size();
        for (std::size_t k = 0; k < known_f.size(); ++k) {
          const std::vector<double>& g = known_f[k];
          if (!(g[p] < current) || (best < known_f.size() && !(g[p] < known_f[best][p]))) continue;
          bool satisfies = true;
          for (const ObjectiveBound& b : slot.bounds)
            satisfies = satisfies && g[b.objective] <= b.epsilon + 1e-8 * b.scale;
          if (satisfies) best = k;
        }
        if (best == known_f.size() || best == slot.repaired_from) continue;
        slot.repaired_from = best;
        ++repaired;
        changed = true;
        const ScalarizedProblem sub(counted, weights, slot.bounds);
        SolveResult solved = solve_with_ipopt(sub, known_x[best], options.ipopt);
        ++solves;
        std::vector<double> f =
            solved.usable() ? checked_fitness(counted, solved.x) : std::vector<double>{};
        if (f.empty() || !(f[p] < known_f[best][p])) {
          slot.x = known_x[best];
          slot.f = known_f[best];
        } else {
          slot.x = solved.x;
          slot.f = f;
          known_x.push_back(std::move(solved.x));
          known_f.push_back(std::move(f));
        }
      }
      if (!changed) break;
    }
  }

  // The front: anchors, then the subproblem results in order; a result that a kept one weakly
  // dominates within 1e-5 of the objective ranges (epsilon bounds in a gap of the front, or
  // inactive ones), or that any other result dominates, adds nothing and is dropped.
  std::vector<std::vector<double>> xs(known_x.begin(),
                                      known_x.begin() + static_cast<std::ptrdiff_t>(anchor_count));
  std::vector<std::vector<double>> fitness(
      known_f.begin(), known_f.begin() + static_cast<std::ptrdiff_t>(anchor_count));
  std::size_t dominated = 0;
  for (const Slot& slot : slots) {
    if (slot.f.empty()) {
      ++failed;
      continue;
    }
    if (dominated_by_any(fitness, slot.f, m, tolerance)) {
      ++dominated;
      continue;
    }
    xs.push_back(slot.x);
    fitness.push_back(slot.f);
  }

  FrontResult front = make_front(problem, xs, fitness);
  front.algorithm = "epsilon_constraint";
  front.subproblems = solves;
  front.failed_subproblems = failed;
  front.dominated_subproblems = dominated + xs.size() - front.x.size();
  front.fitness_evaluations = counted.fitness_evaluations();
  front.gradient_evaluations = counted.gradient_evaluations();
  front.seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - clock_start).count();
  if (anchors.range.empty())
    front.message = "every anchor solve failed: " + anchors.points.front().summary;
  else if (front.failed_subproblems > 0)
    front.message =
        fmt::format("{} of {} subproblems failed", front.failed_subproblems, slots.size());
  if (retried > 0 || repaired > 0)
    front.message += fmt::format("{}{} subproblem(s) restarted, {} repaired from a neighbour",
                                 front.message.empty() ? "" : "; ", retried, repaired);
  return front;
}

}  // namespace pkmopt
