// MOEA/D with differential evolution (MOEA/D-DE: Zhang & Li, IEEE TEVC 11(6), 2007; Li & Zhang,
// IEEE TEVC 13(2), 2009) and constraint handling: the front is decomposed into one scalar
// subproblem per weight vector, each solved by its own member with help from the members of its
// neighbouring weights.
//
// Weights: the Das–Dennis directions (optimizer/reference_directions.hpp: `divisions`, two layers
// with `inner_divisions`) or the given list; the population is one member per weight. The
// neighbourhood B(i) of weight i is its `neighbours` nearest weights (Euclidean, itself
// included; ties by index).
// Subproblem i: the Tchebycheff function g(x | w) = max_j w'_j |f^_j(x) - z^_j|, w'_j = max(w_j,
// 1e-6), in objectives normalised f^ = (f - z*) / (z_nad - z*) by the ideal point z* of every
// design evaluated so far and the nadir z_nad of the current population (a range of 0 counts as
// 1), so objectives of any units weigh alike (`normalize: false`: f^ = f - z*).
// Each generation, for the subproblems in a random order: the mating pool is B(i) with
// probability `neighbourhood_probability`, else the whole population; the child is
// DE/rand/1/bin, y_j = x_i,j + F (x_r1,j - x_r2,j) for a random j_rand and with probability CR
// for the others (x_i,j otherwise), r1 != r2 from the pool, values beyond a bound put at a random
// point between the parent's value and that bound, then polynomial mutation (optimizer/
// variation.hpp).
// Batch-parallel and reproducible: the children of one generation are all made first (every
// random draw on the calling thread), evaluated together (in parallel when the problem allows),
// then offered in the same order: each child replaces at most `max_replacements` members of its
// pool, visited in a random order, whose subproblem it solves at least as well.
// Constraints (what pymoo's MOEA/D lacks): Deb's rules inside the replacement (Jan & Zhang 2010):
// with violation V (optimizer/population.hpp), the smaller V wins; of equal V (two feasible
// designs) the smaller g. The ideal point and the nadir are taken over feasible designs once
// there are any.
// The result: the feasible non-dominated members of the last population.
//
// Example:
//   pkmopt::MoeadOptions options;
//   options.divisions = 12;       // 91 weights in 3 objectives: population 91
//   options.generations = 250;
//   pkmopt::FrontResult front = pkmopt::run_moead(dtlz2, options);
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "optimizer/front_result.hpp"
#include "optimizer/problem.hpp"

namespace pkmopt {

struct MoeadOptions {
  std::size_t generations = 250;
  std::size_t divisions = 12;       ///< H of the Das–Dennis weights (H1 with inner_divisions)
  std::size_t inner_divisions = 0;  ///< H2 of an inside layer; 0: one layer
  std::vector<std::vector<double>> weights;  ///< given: used instead (M each, >= 0, not all 0)
  std::size_t neighbours = 20;               ///< T, at least 2 (at most the population)
  double neighbourhood_probability = 0.9;    ///< delta
  std::size_t max_replacements = 2;          ///< n_r
  double differential_weight = 0.5;          ///< F
  double crossover_rate = 1.0;               ///< CR
  double mutation_probability = 0.0;         ///< 0 means 1/n
  double mutation_eta = 20.0;
  bool normalize = true;
  double equality_tolerance = 1e-4;
  std::uint64_t seed = 1;
  int threads = 0;
  std::vector<std::vector<double>> initial_population;

  std::optional<std::string> validate() const;
};

/// The weight vectors the options give for m objectives (throws std::invalid_argument for bad
/// given weights).
std::vector<std::vector<double>> moead_weights(const MoeadOptions& options, std::size_t m);

/// Runs MOEA/D (see the header comment). Evaluations: population * (generations + 1).
FrontResult run_moead(const Problem& problem, const MoeadOptions& options);

}  // namespace pkmopt
