// The population machinery shared by the evolutionary algorithms (NSGA-II, NSGA-III): an
// individual with its design, fitness and constraint violation; Deb's constraint-domination
// (Deb 2000: with violation V = sum max(|h| - tol_eq, 0) + sum max(g, 0), a feasible design beats
// an infeasible one, of two infeasible ones the smaller V wins, of two feasible ones Pareto
// dominance decides); the fast non-dominated sort (Deb et al. 2002); batch evaluation (in
// parallel when the problem allows, results in input order); the initial population.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "optimizer/problem.hpp"
#include "optimizer/random.hpp"

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

/// `size` individuals: the given designs first (clamped into the bounds), the rest drawn uniformly
/// in the bounds from `rng`. Throws std::invalid_argument naming `algorithm` when a given design
/// has the wrong number of values.
std::vector<Individual> initial_individuals(const Problem& problem, std::size_t size,
                                            const std::vector<std::vector<double>>& given,
                                            Random& rng, const std::string& algorithm);

}  // namespace pkmopt
