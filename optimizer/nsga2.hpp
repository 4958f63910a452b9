// NSGA-II (Deb, Pratap, Agarwal & Meyarivan 2002) with Deb's constraint-domination.
//
// Each generation: binary tournaments on (rank, crowding distance) pick parents; simulated
// binary crossover (SBX, distribution index eta_c, each variable crossed with probability 1/2)
// and polynomial mutation (distribution index eta_m, probability p_m per variable), both in
// Deb's bounded form (optimizer/variation.hpp, checked against nsga2r), make `population`
// children; parents and children are merged, sorted into non-dominated fronts and truncated by
// crowding distance.
//
// Constraint-domination (Deb 2000): with violation V = sum max(|h| - tol_eq, 0) + sum max(g, 0),
// a feasible design beats an infeasible one; of two infeasible designs the one with smaller V
// wins; of two feasible ones Pareto dominance decides.
//
// Fitness is evaluated by Problem::batch_fitness, in parallel when the problem declares
// ThreadSafety::basic. Every random draw comes from one pkmopt::Random stream on the calling
// thread, so a seed gives bit-identical fronts for any number of threads.
// Evaluations: population * (generations + 1).
//
// Nsga2Search runs the same algorithm a few generations at a time (the architecture synthesis
// gives each structure generations in rounds): constructing it draws and evaluates the initial
// population, advance(g) runs g more generations, and after advance(a) then advance(b) the
// population is bit-identical to run_nsga2 with generations = a + b (options.generations is not
// read by the search).
//
// Example:
//   pkmopt::Nsga2Options options;
//   options.population = 100;
//   options.generations = 250;
//   options.seed = 1;
//   pkmopt::FrontResult front = pkmopt::run_nsga2(zdt1, options);
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "optimizer/front_result.hpp"
#include "optimizer/problem.hpp"

namespace pkmopt {

struct Nsga2Options {
  std::size_t population = 100;        ///< even, >= 4
  std::size_t generations = 250;       ///< >= 0
  double crossover_probability = 1.0;  ///< per pair, in [0, 1]
  double crossover_eta = 20.0;         ///< SBX distribution index, > 0 (Deb et al. 2002)
  double mutation_probability = 0.0;   ///< per variable in [0, 1]; 0 means 1/n
  double mutation_eta = 20.0;          ///< polynomial mutation distribution index, > 0
  double equality_tolerance = 1e-4;    ///< |h| below this counts as satisfied
  std::uint64_t seed = 1;
  int threads = 0;  ///< 0 = OpenMP's default
  /// Designs to start from (clamped into the bounds); the rest of the population is drawn
  /// uniformly in the bounds.
  std::vector<std::vector<double>> initial_population;

  std::optional<std::string> validate() const;
};

/// Why NSGA-II cannot take this problem (infinite bounds, inconsistent bounds), or empty.
std::optional<std::string> nsga2_explain_unsupported(const Problem& problem);

/// Runs NSGA-II. Throws std::invalid_argument for invalid options or an unsupported problem.
/// The result is the feasible non-dominated part of the final population (empty if no design
/// is feasible; `message` says so).
FrontResult run_nsga2(const Problem& problem, const Nsga2Options& options);

/// NSGA-II a few generations at a time (see the header comment). The problem must outlive the
/// search.
class Nsga2Search {
 public:
  /// Draws and evaluates the initial population. Throws std::invalid_argument as run_nsga2.
  Nsga2Search(const Problem& problem, const Nsga2Options& options);
  ~Nsga2Search();
  Nsga2Search(Nsga2Search&&) noexcept;
  Nsga2Search& operator=(Nsga2Search&&) noexcept;

  /// Runs `generations` more generations.
  void advance(std::size_t generations);
  /// Generations run so far (0 after construction).
  std::size_t generations() const;
  /// Fitness evaluations so far (population * (generations() + 1)).
  long long fitness_evaluations() const;
  /// The feasible non-dominated part of the current population, as run_nsga2 returns it.
  FrontResult front() const;

 private:
  struct State;
  std::unique_ptr<State> state_;
};

}  // namespace pkmopt
