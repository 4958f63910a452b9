#include "optimizer/nbi.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>

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

  std::vector<std::vector<double>> xs, fitness;
  std::size_t subproblems = 0, failed = 0, duplicates = 0;
  const AnchorSet anchors = compute_anchors(counted, start, options.ipopt, 8, options.seed);
  subproblems += anchors.solves;
  failed += anchors.failed;
  for (const AnchorPoint& anchor : anchors.points)
    if (anchor.ok) {
      xs.push_back(anchor.x);
      fitness.push_back(anchor.fitness);
    }

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
    const std::vector<std::vector<double>> global_starts =
        latin_hypercube(problem, options.global_starts, options.seed, start);
    IpoptOptions short_run = options.ipopt;
    short_run.max_iterations = std::min(options.ipopt.max_iterations, 100);
    std::vector<double> warm = anchors.points[0].x;
    for (const std::vector<double>& beta : simplex_lattice(m, divisions)) {
      if (std::count(beta.begin(), beta.end(), 1.0) == 1) continue;  // an anchor
      std::vector<double> chim(m, 0.0);
      for (std::size_t i = 0; i < m; ++i)
        for (std::size_t j = 0; j < m; ++j) chim[j] += beta[i] * phi[i][j];
      NbiProblem sub(counted, anchors.ideal, anchors.range, chim, normal, options.equality_form);
      std::vector<double> xt = warm;
      xt.push_back(sub.feasible_t(checked_fitness(counted, warm)));
      SolveResult solved = solve_with_ipopt(sub, xt, options.ipopt);
      ++subproblems;
      // A failed result is retried once from the anchor with the largest weight (continuation
      // can trap the local solver on one piece of a disconnected front).
      if (!solved.usable()) {
        const std::size_t nearest =
            static_cast<std::size_t>(std::max_element(beta.begin(), beta.end()) - beta.begin());
        std::vector<double> restart = anchors.points[nearest].x;
        restart.push_back(sub.feasible_t(anchors.points[nearest].fitness));
        solved = solve_with_ipopt(sub, restart, options.ipopt);
        ++subproblems;
      }
      // Multi-start: the same subproblem from each global start point; the usable optimum
      // with the largest t wins (a local solver otherwise stops on locally optimal pieces that
      // the global front dominates, as on ZDT3).
      for (const std::vector<double>& global_start : global_starts) {
        std::vector<double> from = global_start;
        from.push_back(sub.feasible_t(checked_fitness(counted, global_start)));
        SolveResult other = solve_with_ipopt(sub, from, short_run);
        ++subproblems;
        if (other.usable() &&
            (!solved.usable() ||
             other.objective < solved.objective - 1e-9 * (1.0 + std::abs(solved.objective))))
          solved = std::move(other);
      }
      if (!solved.usable()) {
        ++failed;
        continue;
      }
      warm.assign(solved.x.begin(), solved.x.end() - 1);
      // A result that an earlier one weakly dominates within 1e-5 of the objective ranges
      // (lattice points facing a gap of the front) adds nothing: dropped.
      std::vector<double> f = checked_fitness(counted, warm);
      const bool covered = std::any_of(fitness.begin(), fitness.end(), [&](const auto& e) {
        for (std::size_t j = 0; j < m; ++j)
          if (e[j] > f[j] + 1e-5 * anchors.range[j]) return false;
        return true;
      });
      if (covered) {
        ++duplicates;
        continue;
      }
      xs.push_back(warm);
      fitness.push_back(std::move(f));
    }
  }

  FrontResult front = make_front(problem, xs, fitness);
  front.algorithm = "nbi";
  front.subproblems = subproblems;
  front.failed_subproblems = failed;
  front.dominated_subproblems = duplicates + xs.size() - front.x.size();
  front.fitness_evaluations = counted.fitness_evaluations();
  front.gradient_evaluations = counted.gradient_evaluations();
  front.seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - clock_start).count();
  if (!all_anchors)
    front.message =
        fmt::format("{} anchor(s) failed, so NBI could not build its simplex", anchors.failed);
  else if (failed > 0)
    front.message = fmt::format("{} of {} subproblems failed", failed, subproblems);
  return front;
}

}  // namespace pkmopt
