#include "optimizer/hybrid.hpp"

#include <fmt/format.h>

#include <chrono>
#include <stdexcept>

#include "optimizer/scalarization.hpp"

namespace pkmopt {

std::optional<std::string> HybridOptions::validate() const {
  if (auto error = nsga2.validate()) return error;
  return ipopt.validate();
}

FrontResult run_hybrid(const Problem& problem, const HybridOptions& options) {
  if (auto error = options.validate()) throw std::invalid_argument(*error);
  if (problem.num_objectives() < 2)
    throw std::invalid_argument(fmt::format(
        "hybrid builds fronts, but the problem named '{}' has one objective (use ipopt)",
        problem.name()));
  const auto clock_start = std::chrono::steady_clock::now();
  CountingProblem counted(problem);
  const FrontResult explored = run_nsga2(counted, options.nsga2);
  const std::size_t m = problem.num_objectives();

  std::vector<std::vector<double>> xs = explored.x;
  std::vector<std::vector<double>> fitness = explored.fitness;
  std::size_t failed = 0;
  if (!explored.x.empty()) {
    const ObjectiveSet objectives = explored.objectives();
    const std::vector<double> ideal = ideal_point(objectives);
    const std::vector<double> nadir = nadir_point(objectives);
    std::vector<double> scale(m);
    for (std::size_t j = 0; j < m; ++j)
      scale[j] = nadir[j] - ideal[j] > 1e-12 ? nadir[j] - ideal[j] : 1.0;
    std::vector<double> weights(m, 0.0);
    weights[0] = 1.0 / scale[0];
    for (std::size_t k = 0; k < explored.x.size(); ++k) {
      std::vector<ObjectiveBound> bounds;
      for (std::size_t j = 1; j < m; ++j) bounds.push_back({j, objectives[k][j], scale[j]});
      const SolveResult polished = solve_with_ipopt(ScalarizedProblem(counted, weights, bounds),
                                                    explored.x[k], options.ipopt);
      if (!polished.usable()) {
        ++failed;
        continue;
      }
      xs.push_back(polished.x);
      fitness.push_back(checked_fitness(counted, polished.x));
    }
  }
  FrontResult front = make_front(problem, xs, fitness, options.nsga2.equality_tolerance, 1e-6);
  front.algorithm = "hybrid";
  front.subproblems = explored.x.size();
  front.failed_subproblems = failed;
  front.dominated_subproblems = 0;
  front.fitness_evaluations = counted.fitness_evaluations();
  front.gradient_evaluations = counted.gradient_evaluations();
  front.seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - clock_start).count();
  front.message = explored.message;
  if (failed > 0)
    front.message += fmt::format("{}{} of {} polish solves failed (originals kept)",
                                 front.message.empty() ? "" : "; ", failed, explored.x.size());
  return front;
}

}  // namespace pkmopt
