#include "optimizer/nbi.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <utility>
#include <vector>

#include "optimizer/anchors.hpp"
#include "optimizer/scalarization.hpp"

namespace pkmopt {
namespace {

void lattice(std::size_t dimensions, std::size_t divisions, std::size_t index, std::size_t left,
             std::vector<double>& current, std::vector<std::vector<double>>& out) {
  if (index + 1 == dimensions) {
    current[index] = static_cast<double>(left) / static_cast<double>(divisions);
    out.push_back(current);
    return;
  }
  for (std::size_t k = left + 1; k-- > 0;) {
    current[index] = static_cast<double>(k) / static_cast<double>(divisions);
    lattice(dimensions, divisions, index + 1, left - k, current, out);
  }
}

}  // namespace

std::vector<std::vector<double>> simplex_lattice(std::size_t dimensions, std::size_t divisions) {
  std::vector<std::vector<double>> out;
  if (dimensions == 0 || divisions == 0) return out;
  std::vector<double> current(dimensions, 0.0);
  lattice(dimensions, divisions, 0, divisions, current, out);
  return out;
}

std::optional<std::string> NbiOptions::validate() const {
  if (points < 2)
    return fmt::format("NbiOptions::points = {}. Violated constraint: points >= 2", points);
  for (double v : start)
    if (!std::isfinite(v)) return std::string("NbiOptions::start has a non-finite value");
  return ipopt.validate();
}

std::optional<std::string> nbi_explain_unsupported(const Problem& problem,
                                                   const NbiOptions& options) {
  try {
    check_bounds(problem);
  } catch (const std::invalid_argument& e) {
    return std::string(e.what());
  }
  if (problem.num_objectives() < 2)
    return fmt::format(
        "nbi builds fronts, but the problem named '{}' has one objective (use ipopt)",
        problem.name());
  if (!options.start.empty() && options.start.size() != problem.num_variables())
    return fmt::format("nbi: start has {} values, the problem has {} variables",
                       options.start.size(), problem.num_variables());
  return std::nullopt;
}

FrontResult run_nbi(const Problem& problem, const NbiOptions& options) {
  if (auto error = options.validate()) throw std::invalid_argument(*error);
  if (auto reason = nbi_explain_unsupported(problem, options)) throw std::invalid_argument(*reason);
  const auto clock_start = std::chrono::steady_clock::now();
  CountingProblem counted(problem);
  const std::size_t m = problem.num_objectives();
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
  // True when a known point weakly dominates f within `tolerance`.
  auto covered = [&](const std::vector<std::vector<double>>& points, const std::vector<double>& f) {
    return std::any_of(points.begin(), points.end(), [&](const auto& e) {
      for (std::size_t j = 0; j < m; ++j)
        if (e[j] > f[j] + tolerance[j]) return false;
      return true;
    });
  };

  // One lattice point: its subproblem and best result so far.
  struct Slot {
    std::vector<double> beta, chim;
    std::vector<double> x, f;              // empty while no usable result is known
    std::size_t repaired_from = SIZE_MAX;  // known point the last repair started from
  };
  std::vector<Slot> slots;

  const bool all_anchors = anchors.failed == 0;
  if (all_anchors) {
    // Normalised pay-off matrix and quasi-normal.
    std::vector<std::vector<double>> phi(m, std::vector<double>(m));
    std::vector<double> normal(m, 0.0);
    for (std::size_t i = 0; i < m; ++i)
      for (std::size_t j = 0; j < m; ++j) {
        phi[i][j] = (anchors.points[i].fitness[j] - anchors.ideal[j]) / anchors.range[j];
        normal[j] -= phi[i][j];
      }
    double norm = 0.0;
    for (double v : normal) norm += v * v;
    norm = std::sqrt(norm);
    for (double& v : normal) v = norm > 0.0 ? v / norm : -1.0 / std::sqrt(static_cast<double>(m));

    std::size_t divisions = 1;
    if (m == 2) {
      divisions = options.points - 1;
    } else {
      while (simplex_lattice(m, divisions).size() < options.points) ++divisions;
    }
    for (const std::vector<double>& beta : simplex_lattice(m, divisions)) {
      if (std::count(beta.begin(), beta.end(), 1.0) == 1) continue;  // an anchor
      Slot slot;
      slot.beta = beta;
      slot.chim.assign(m, 0.0);
      for (std::size_t i = 0; i < m; ++i)
        for (std::size_t j = 0; j < m; ++j) slot.chim[j] += beta[i] * phi[i][j];
      slots.push_back(std::move(slot));
    }
    const std::vector<std::vector<double>> global_starts =
        latin_hypercube(problem, options.global_starts, options.seed, start);
    IpoptOptions short_run = options.ipopt;
    short_run.max_iterations = std::min(options.ipopt.max_iterations, 100);
    auto subproblem = [&](const Slot& slot) {
      return NbiProblem(counted, anchors.ideal, anchors.range, slot.chim, normal,
                        options.equality_form);
    };
    // The design x with t set to its largest feasible value for this subproblem.
    auto with_t = [&](const NbiProblem& sub, const std::vector<double>& x,
                      const std::vector<double>& f) {
      std::vector<double> xt = x;
      xt.push_back(sub.feasible_t(f));
      return xt;
    };
    // a replaces b when usable with a larger t (objective -t lower beyond rounding).
    auto better = [](const SolveResult& a, const SolveResult& b) {
      return a.usable() &&
             (!b.usable() || a.objective < b.objective - 1e-9 * (1.0 + std::abs(b.objective)));
    };

    std::vector<double> warm = anchors.points[0].x;
    std::vector<double> warm_f = anchors.points[0].fitness;
    // Continuation jumped: the result is farther from the previous one than 3 lattice steps
    // (1 / divisions, in objectives scaled by their ranges), as when the front has a gap here,
    // or when the local solver skipped over a piece of a disconnected front.
    auto jumped = [&](const std::vector<double>& f) {
      return continuation_jumped(anchors, warm_f, f, 3.0 / static_cast<double>(divisions), 1.0);
    };
    for (Slot& slot : slots) {
      const NbiProblem sub = subproblem(slot);
      SolveResult solved = solve_with_ipopt(sub, with_t(sub, warm, warm_f), options.ipopt);
      ++solves;
      std::vector<double> f;
      if (solved.usable()) {
        solved.x.pop_back();
        f = checked_fitness(counted, solved.x);
      }
      // Extra starts only when the warm-started solve failed, landed on a point a known one
      // weakly dominates, or jumped (continuation trapped on, or skipping, pieces of a
      // disconnected front): the anchors, nearest (largest weight) first, then `global_starts`
      // Latin-hypercube points (at most 100 iterations each); the largest t wins.
      if (!solved.usable() || covered(known_f, f) || jumped(f)) {
        ++retried;
        auto try_from = [&](const std::vector<double>& x, const std::vector<double>& fx,
                            bool is_short) {
          SolveResult other =
              solve_with_ipopt(sub, with_t(sub, x, fx), is_short ? short_run : options.ipopt);
          ++solves;
          if (other.usable()) other.x.pop_back();
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
            try_from(between, checked_fitness(counted, between), true);
        };
        if (solved.usable()) bridge();
        std::vector<std::size_t> order(m);
        for (std::size_t i = 0; i < m; ++i) order[i] = i;
        std::stable_sort(order.begin(), order.end(),
                         [&](std::size_t a, std::size_t b) { return slot.beta[a] > slot.beta[b]; });
        for (std::size_t i : order) try_from(anchors.points[i].x, anchors.points[i].fitness, false);
        for (const std::vector<double>& x : global_starts)
          try_from(x, checked_fitness(counted, x), true);
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

    // Repair: a lattice point whose result (or failure) is beaten by a known point reaching a
    // larger t on its line (typically a neighbour's solution) is re-solved from that point.
    // On a disconnected front this moves results stuck on a dominated piece to the global one.
    // In the relaxed form the known point is itself feasible, so if Ipopt still fails it is
    // the lattice point's best answer (a repeat, dropped below).
    for (int pass = 0; pass < 3; ++pass) {
      bool changed = false;
      for (Slot& slot : slots) {
        const NbiProblem sub = subproblem(slot);
        const double current = slot.f.empty() ? -INFINITY : sub.feasible_t(slot.f) + 1e-5;
        std::size_t best = known_f.size();
        double best_t = current;
        for (std::size_t k = 0; k < known_f.size(); ++k) {
          const double t = sub.feasible_t(known_f[k]);
          if (t > best_t) {
            best_t = t;
            best = k;
          }
        }
        if (best == known_f.size() || best == slot.repaired_from) continue;
        slot.repaired_from = best;
        ++repaired;
        changed = true;
        SolveResult solved =
            solve_with_ipopt(sub, with_t(sub, known_x[best], known_f[best]), options.ipopt);
        ++solves;
        std::vector<double> f;
        if (solved.usable()) {
          solved.x.pop_back();
          f = checked_fitness(counted, solved.x);
        }
        if (!f.empty() && sub.feasible_t(f) > best_t) {
          slot.x = solved.x;
          slot.f = f;
          known_x.push_back(std::move(solved.x));
          known_f.push_back(std::move(f));
        } else if (!options.equality_form) {
          slot.x = known_x[best];
          slot.f = known_f[best];
        }
      }
      if (!changed) break;
    }
  }

  // The front: anchors, then the lattice results in order; a result that a kept one weakly
  // dominates within 1e-5 of the objective ranges (lattice points facing a gap of the front),
  // or that any other result dominates, adds nothing and is dropped.
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
  front.algorithm = "nbi";
  front.subproblems = solves;
  front.failed_subproblems = failed;
  front.dominated_subproblems = dominated + xs.size() - front.x.size();
  front.fitness_evaluations = counted.fitness_evaluations();
  front.gradient_evaluations = counted.gradient_evaluations();
  front.seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - clock_start).count();
  if (!all_anchors)
    front.message =
        fmt::format("{} anchor(s) failed, so NBI could not build its simplex", anchors.failed);
  else if (failed > 0)
    front.message = fmt::format("{} of {} subproblems failed", failed, slots.size());
  if (retried > 0 || repaired > 0)
    front.message += fmt::format("{}{} subproblem(s) restarted, {} repaired from a neighbour",
                                 front.message.empty() ? "" : "; ", retried, repaired);
  return front;
}

}  // namespace pkmopt
