#include "optimizer/front_sweep.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <utility>

namespace pkmopt {

FrontResult run_front_sweep(const Problem& problem, const FrontSweepOptions& options,
                            const SweepPlanner& planner) {
  const auto clock_start = std::chrono::steady_clock::now();
  CountingProblem counted(problem);
  const std::size_t m = problem.num_objectives();
  const std::size_t n = problem.num_variables();
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
  std::vector<double> tolerance(m, 0.0);
  for (std::size_t j = 0; j < m && !anchors.range.empty(); ++j)
    tolerance[j] = 1e-5 * anchors.range[j];

  const SweepPlan plan = planner(counted, anchors, start);
  // True when one of `points` weakly dominates f within `tolerance`.
  auto covered = [&](const std::vector<std::vector<double>>& points, const std::vector<double>& f) {
    return std::any_of(points.begin(), points.end(), [&](const std::vector<double>& e) {
      for (std::size_t j = 0; j < m; ++j)
        if (plan.nan_covers ? e[j] > f[j] + tolerance[j] : !(e[j] <= f[j] + tolerance[j]))
          return false;
      return true;
    });
  };

  // The best result of each subproblem so far.
  struct Slot {
    std::vector<double> x, f;              // empty while no usable result is known
    std::size_t repaired_from = SIZE_MAX;  // known point the last repair started from
  };
  std::vector<Slot> slots(plan.subproblems.size());

  if (!slots.empty()) {
    const std::vector<std::vector<double>> global_starts =
        latin_hypercube(problem, options.global_starts, options.seed, start);
    IpoptOptions short_run = options.ipopt;
    short_run.max_iterations = std::min(options.ipopt.max_iterations, 100);
    // Solves a subproblem from the design x (base fitness fx, or empty) and keeps the design
    // part of a usable solution.
    auto solve = [&](const FrontSubproblem& sub, const std::vector<double>& x,
                     const std::vector<double>& fx, const IpoptOptions& ipopt) {
      SolveResult result = solve_with_ipopt(sub.problem(), sub.start(x, fx), ipopt);
      ++solves;
      if (result.usable()) result.x.resize(n);
      return result;
    };
    // a replaces b when usable with a lower subproblem objective (beyond rounding).
    auto better = [](const SolveResult& a, const SolveResult& b) {
      return a.usable() &&
             (!b.usable() || a.objective < b.objective - 1e-9 * (1.0 + std::abs(b.objective)));
    };

    std::vector<double> warm = plan.first_x;
    std::vector<double> warm_f = plan.first_f;
    // Continuation jumped: the result is far from the previous one (in objectives scaled by
    // their ranges), as when the front has a gap here, or when the local solver skipped over a
    // piece of a disconnected front.
    auto jumped = [&](const std::vector<double>& f) {
      return continuation_jumped(anchors, warm_f, f, plan.jump_step, plan.jump_max_steps);
    };
    for (std::size_t k = 0; k < slots.size(); ++k) {
      const FrontSubproblem& sub = *plan.subproblems[k];
      Slot& slot = slots[k];
      SolveResult solved = solve(sub, warm, warm_f, options.ipopt);
      std::vector<double> f =
          solved.usable() ? checked_fitness(counted, solved.x) : std::vector<double>{};
      // Extra starts only when the warm-started solve failed, landed on a point a known one
      // weakly dominates, or jumped (continuation trapped on, or skipping, pieces of a
      // disconnected front).
      if (!solved.usable() || covered(known_f, f) || jumped(f)) {
        ++retried;
        auto try_from = [&](const std::vector<double>& x, const std::vector<double>& fx,
                            bool is_short) {
          SolveResult other = solve(sub, x, fx, is_short ? short_run : options.ipopt);
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
            try_from(between, {}, true);
        };
        if (solved.usable()) bridge();
        for (std::size_t i : sub.restart_anchors())
          try_from(anchors.points[i].x, anchors.points[i].fitness, false);
        for (const std::vector<double>& x : global_starts) try_from(x, {}, true);
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

    // Repair: a subproblem whose result (or failure) a known point beats, typically its
    // neighbour's solution, is re-solved from that point. On a disconnected front this moves
    // results stuck on a dominated piece to the global one, and gives failed subproblems a
    // feasible start. If Ipopt still does no better, the known point itself may be the
    // subproblem's answer (a repeat, dropped below).
    for (int pass = 0; pass < 3; ++pass) {
      bool changed = false;
      for (std::size_t k = 0; k < slots.size(); ++k) {
        const FrontSubproblem& sub = *plan.subproblems[k];
        Slot& slot = slots[k];
        std::size_t best = known_f.size();
        double best_score = slot.f.empty() ? -INFINITY : sub.score(slot.f) + plan.repair_margin;
        for (std::size_t j = 0; j < known_f.size(); ++j) {
          if (!sub.admits(known_f[j])) continue;
          const double score = sub.score(known_f[j]);
          if (score > best_score) {
            best_score = score;
            best = j;
          }
        }
        if (best == known_f.size() || best == slot.repaired_from) continue;
        slot.repaired_from = best;
        ++repaired;
        changed = true;
        SolveResult solved = solve(sub, known_x[best], known_f[best], options.ipopt);
        std::vector<double> f =
            solved.usable() ? checked_fitness(counted, solved.x) : std::vector<double>{};
        if (!f.empty() && sub.score(f) > best_score) {
          slot.x = solved.x;
          slot.f = f;
          known_x.push_back(std::move(solved.x));
          known_f.push_back(std::move(f));
        } else if (plan.keep_known_on_failed_repair) {
          slot.x = known_x[best];
          slot.f = known_f[best];
        }
      }
      if (!changed) break;
    }
  }

  // The front: anchors, then the subproblem results in order; a result that a kept one weakly
  // dominates within 1e-5 of the objective ranges (a subproblem facing a gap of the front, or
  // with inactive bounds), or that any other result dominates, adds nothing and is dropped.
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
    if (covered(fitness, slot.f)) {
      ++dominated;
      continue;
    }
    xs.push_back(slot.x);
    fitness.push_back(slot.f);
  }

  FrontResult front = make_front(problem, xs, fitness);
  front.algorithm = options.algorithm;
  front.subproblems = solves;
  front.failed_subproblems = failed;
  front.dominated_subproblems = dominated + xs.size() - front.x.size();
  front.fitness_evaluations = counted.fitness_evaluations();
  front.gradient_evaluations = counted.gradient_evaluations();
  front.seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - clock_start).count();
  if (!plan.failure.empty())
    front.message = plan.failure;
  else if (failed > 0)
    front.message = fmt::format("{} of {} subproblems failed", failed, slots.size());
  if (retried > 0 || repaired > 0)
    front.message += fmt::format("{}{} subproblem(s) restarted, {} repaired from a neighbour",
                                 front.message.empty() ? "" : "; ", retried, repaired);
  return front;
}

std::optional<std::string> front_problem_explain_unsupported(const Problem& problem,
                                                             std::string_view algorithm) {
  try {
    check_bounds(problem);
  } catch (const std::invalid_argument& e) {
    return std::string(e.what());
  }
  if (problem.num_objectives() < 2)
    return fmt::format("{} builds fronts, but the problem named '{}' has one objective (use ipopt)",
                       algorithm, problem.name());
  return std::nullopt;
}

std::optional<std::string> front_start_explain_unsupported(const Problem& problem,
                                                           std::string_view algorithm,
                                                           const std::vector<double>& start) {
  if (!start.empty() && start.size() != problem.num_variables())
    return fmt::format("{}: start has {} values, the problem has {} variables", algorithm,
                       start.size(), problem.num_variables());
  return std::nullopt;
}

}  // namespace pkmopt
