#include "optimizer/population.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace pkmopt {

bool constrained_dominates(const Individual& a, const Individual& b, std::size_t m) {
  if (a.violation == 0.0 && b.violation > 0.0) return true;
  if (a.violation > 0.0 || b.violation > 0.0) return a.violation < b.violation;
  bool strictly = false;
  for (std::size_t i = 0; i < m; ++i) {
    if (a.fitness[i] > b.fitness[i]) return false;
    if (a.fitness[i] < b.fitness[i]) strictly = true;
  }
  return strictly;
}

std::vector<std::vector<std::size_t>> sort_fronts(std::vector<Individual>& pop, std::size_t m) {
  const std::size_t n = pop.size();
  std::vector<std::vector<std::size_t>> dominated(n);
  std::vector<std::size_t> domination_count(n, 0);
  std::vector<std::vector<std::size_t>> fronts(1);
  for (std::size_t p = 0; p < n; ++p) {
    for (std::size_t q = p + 1; q < n; ++q) {
      if (constrained_dominates(pop[p], pop[q], m)) {
        dominated[p].push_back(q);
        ++domination_count[q];
      } else if (constrained_dominates(pop[q], pop[p], m)) {
        dominated[q].push_back(p);
        ++domination_count[p];
      }
    }
  }
  for (std::size_t p = 0; p < n; ++p)
    if (domination_count[p] == 0) {
      pop[p].rank = 0;
      fronts[0].push_back(p);
    }
  for (std::size_t level = 0; !fronts[level].empty(); ++level) {
    std::vector<std::size_t> next;
    for (std::size_t p : fronts[level])
      for (std::size_t q : dominated[p])
        if (--domination_count[q] == 0) {
          pop[q].rank = level + 1;
          next.push_back(q);
        }
    std::sort(next.begin(), next.end());
    fronts.push_back(std::move(next));
  }
  fronts.pop_back();
  return fronts;
}

void evaluate_individuals(const Problem& problem, std::vector<Individual>& individuals,
                          std::size_t first, int threads, double equality_tolerance) {
  std::vector<std::vector<double>> xs;
  xs.reserve(individuals.size() - first);
  for (std::size_t k = first; k < individuals.size(); ++k) xs.push_back(individuals[k].x);
  std::vector<std::vector<double>> fitness = problem.batch_fitness(xs, threads);
  const std::size_t m = problem.num_objectives();
  for (std::size_t k = 0; k < fitness.size(); ++k) {
    Individual& ind = individuals[first + k];
    if (fitness[k].size() != problem.fitness_size())
      throw std::runtime_error(fmt::format("problem '{}': fitness returned {} values, expected {}",
                                           problem.name(), fitness[k].size(),
                                           problem.fitness_size()));
    ind.fitness = std::move(fitness[k]);
    // Non-finite objectives make a design useless: treat it as infeasible.
    bool finite = true;
    for (std::size_t i = 0; i < m; ++i) finite = finite && std::isfinite(ind.fitness[i]);
    ind.violation = constraint_violation(problem, ind.fitness, equality_tolerance, 0.0);
    if (!finite) ind.violation = std::numeric_limits<double>::max();
  }
}

std::vector<Individual> initial_individuals(const Problem& problem, std::size_t size,
                                            const std::vector<std::vector<double>>& given,
                                            Random& rng, const std::string& algorithm) {
  const Bounds bounds = problem.bounds();
  const std::size_t n = bounds.lower.size();
  std::vector<Individual> population(size);
  for (std::size_t k = 0; k < size; ++k) {
    std::vector<double>& x = population[k].x;
    if (k < given.size()) {
      x = given[k];
      if (x.size() != n)
        throw std::invalid_argument(
            fmt::format("{}: initial design {} has {} values, problem '{}' has {} variables",
                        algorithm, k + 1, x.size(), problem.name(), n));
      for (std::size_t j = 0; j < n; ++j) x[j] = std::clamp(x[j], bounds.lower[j], bounds.upper[j]);
    } else {
      x.resize(n);
      for (std::size_t j = 0; j < n; ++j) x[j] = rng.uniform(bounds.lower[j], bounds.upper[j]);
    }
  }
  return population;
}

FrontResult population_front(const Problem& problem, const std::vector<Individual>& population,
                             double equality_tolerance, const std::string& algorithm,
                             const CountingProblem& counted,
                             std::chrono::steady_clock::time_point start) {
  std::vector<std::vector<double>> xs, fitness;
  for (const Individual& ind : population) {
    xs.push_back(ind.x);
    fitness.push_back(ind.fitness);
  }
  FrontResult result = make_front(problem, xs, fitness, equality_tolerance, 0.0);
  result.algorithm = algorithm;
  result.fitness_evaluations = counted.fitness_evaluations();
  result.gradient_evaluations = counted.gradient_evaluations();
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (result.x.empty()) result.message = "no feasible design in the final population";
  return result;
}

std::optional<std::string> check_evolution_options(std::string_view type,
                                                   const VariationSettings& v,
                                                   double equality_tolerance, int threads) {
  auto violated = [&](const char* name, auto value, const char* rule) {
    return fmt::format("{}::{} = {}. Violated constraint: {}", type, name, value, rule);
  };
  if (!(v.crossover_probability >= 0.0 && v.crossover_probability <= 1.0))
    return violated("crossover_probability", v.crossover_probability,
                    "0 <= crossover_probability <= 1");
  if (!(v.crossover_eta > 0.0))
    return violated("crossover_eta", v.crossover_eta, "crossover_eta > 0");
  if (!(v.mutation_probability >= 0.0 && v.mutation_probability <= 1.0))
    return violated("mutation_probability", v.mutation_probability,
                    "0 <= mutation_probability <= 1");
  if (!(v.mutation_eta > 0.0)) return violated("mutation_eta", v.mutation_eta, "mutation_eta > 0");
  if (!(equality_tolerance >= 0.0))
    return violated("equality_tolerance", equality_tolerance, "equality_tolerance >= 0");
  if (threads < 0) return violated("threads", threads, "threads >= 0");
  return std::nullopt;
}

}  // namespace pkmopt
