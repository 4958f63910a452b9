// The population machinery shared by the evolutionary algorithms (NSGA-II, NSGA-III): an
// individual with its design, fitness and constraint violation; Deb's constraint-domination
// (Deb 2000: with violation V = sum max(|h| - tol_eq, 0) + sum max(g, 0), a feasible design beats
// an infeasible one, of two infeasible ones the smaller V wins, of two feasible ones Pareto
// dominance decides); the fast non-dominated sort (Deb et al. 2002); batch evaluation (in
// parallel when the problem allows, results in input order); the initial population.
#pragma once

#include <chrono>
#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "optimizer/front_result.hpp"
#include "optimizer/problem.hpp"
#include "optimizer/random.hpp"
#include "optimizer/variation.hpp"

namespace pkmopt {

struct Individual {
  std::vector<double> x;
  std::vector<double> fitness;
  double violation = 0.0;
  std::size_t rank = 0;
  double crowding = 0.0;
};

/// Deb's constraint-domination on the first m fitness values: true when a is better than b.
bool constrained_dominates(const Individual& a, const Individual& b, std::size_t m);

/// Fast non-dominated sort; sets rank, returns the fronts (indices in ascending order).
std::vector<std::vector<std::size_t>> sort_fronts(std::vector<Individual>& pop, std::size_t m);

/// Evaluates individuals[first..] by Problem::batch_fitness: fitness and violation; a design with
/// a non-finite objective counts as infeasible (the largest violation). Throws std::runtime_error
/// when the problem returns a fitness of the wrong size.
void evaluate_individuals(const Problem& problem, std::vector<Individual>& individuals,
                          std::size_t first, int threads, double equality_tolerance);

/// SBX crossover and polynomial mutation settings (optimizer/variation.hpp).
struct VariationSettings {
  double crossover_probability = 1.0;  ///< per pair
  double crossover_eta = 20.0;
  double mutation_probability = 0.0;  ///< per variable (resolved: never 0)
  double mutation_eta = 20.0;
};

/// The mutation probability per variable an option gives: `probability`, or 1/n when it is 0.
inline double resolved_mutation_probability(double probability, std::size_t n) {
  return probability > 0.0 ? probability : 1.0 / static_cast<double>(n);
}

/// Appends `count` children (count even) to `out`: two parents by `select()` (an index into
/// `parents`), SBX with the crossover probability, polynomial mutation of each; the random draws
/// in that order, from `rng`.
template <class Select>
void append_offspring(const std::vector<Individual>& parents, std::size_t count,
                      const Bounds& bounds, const VariationSettings& v, Select&& select,
                      Random& rng, std::vector<Individual>& out) {
  for (std::size_t k = 0; k < count / 2; ++k) {
    Individual child1, child2;
    child1.x = parents[select()].x;
    child2.x = parents[select()].x;
    if (rng.bernoulli(v.crossover_probability))
      sbx_crossover(child1.x, child2.x, bounds, v.crossover_eta, rng);
    polynomial_mutation(child1.x, bounds, v.mutation_probability, v.mutation_eta, rng);
    polynomial_mutation(child2.x, bounds, v.mutation_probability, v.mutation_eta, rng);
    out.push_back(std::move(child1));
    out.push_back(std::move(child2));
  }
}

/// Empty when the variation settings (mutation_probability 0 meaning 1/n), the equality tolerance
/// and the thread count are valid; otherwise "TYPE::KEY = VALUE. Violated constraint: RULE".
std::optional<std::string> check_evolution_options(std::string_view type,
                                                   const VariationSettings& v,
                                                   double equality_tolerance, int threads);

/// The result of a run: the feasible non-dominated part of the final population (make_front),
/// with the algorithm's name, the evaluation counts of `counted` and the time since `start`.
FrontResult population_front(const Problem& problem, const std::vector<Individual>& population,
                             double equality_tolerance, const std::string& algorithm,
                             const CountingProblem& counted,
                             std::chrono::steady_clock::time_point start);

/// `size` individuals: the given designs first (clamped into the bounds), the rest drawn uniformly
/// in the bounds from `rng`. Throws std::invalid_argument naming `algorithm` when a given design
/// has the wrong number of values.
std::vector<Individual> initial_individuals(const Problem& problem, std::size_t size,
                                            const std::vector<std::vector<double>>& given,
                                            Random& rng, const std::string& algorithm);

}  // namespace pkmopt
