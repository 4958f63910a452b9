// NSGA-III (Deb & Jain, IEEE TEVC 18(4), 2014; constraint handling of Jain & Deb, Part II, IEEE
// TEVC 18(4), 2014) with NSGA-II's variation (SBX and polynomial mutation, optimizer/variation.hpp)
// and Deb's constraint-domination (optimizer/population.hpp).
//
// Each generation: parents by binary tournament on constraint violation (of two feasible designs
// one at random, as NSGA-III selects feasible parents at random), `population` children, parents
// and children merged and sorted into non-dominated fronts. Whole fronts are kept while they
// fit; the front that fits only partly is thinned by reference directions
// (optimizer/nsga3_selection.hpp): the objectives of the kept members and that front are
// normalised (ideal point, the extreme points' hyperplane; both remembered across generations as
// Blank, Deb & Roy 2019 advise), every member is associated with its
// nearest reference line, and the places left go niche by niche to the least crowded directions.
// A partly fitting front of infeasible designs is thinned by violation instead (the smallest
// first, ties by index).
//
// Reference directions: the given list, or Das–Dennis with `divisions` (one layer) or two layers
// (`inner_divisions` > 0; optimizer/reference_directions.hpp). The population defaults to the
// smallest multiple of 4 at least the number of directions (Deb & Jain 2014).
//
// Aspiration points (R-NSGA-III, optimizer/aspiration_directions.hpp): with
// `aspiration_points` (objective units, minimised) the directions are instead, each generation,
// small Das–Dennis sets around the aspiration points normalised by that generation's ideal point
// and intercepts, plus the axis directions; the front gathers where the decision maker asked.
// The population then defaults to the number of these directions rounded up to a multiple of 4.
//
// Every random draw comes from one pkmopt::Random stream on the calling thread: a seed gives
// bit-identical fronts for any number of threads. Evaluations: population * (generations + 1).
//
// Example:
//   pkmopt::Nsga3Options options;
//   options.divisions = 12;                  // 91 directions in 3 objectives, population 92
//   options.generations = 250;
//   pkmopt::FrontResult front = pkmopt::run_nsga3(dtlz2, options);
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "optimizer/front_result.hpp"
#include "optimizer/problem.hpp"

namespace pkmopt {

struct Nsga3Options {
  std::size_t population = 0;  ///< 0: the smallest multiple of 4 >= the directions; else even >= 4
  std::size_t generations = 250;
  std::size_t divisions = 12;       ///< H (H1 with two layers), >= 1, when no directions are given
  std::size_t inner_divisions = 0;  ///< H2 of the inside layer; 0: one layer
  std::vector<std::vector<double>> reference_directions;  ///< given: used instead (M each, >= 0)
  double crossover_probability = 1.0;
  double crossover_eta = 30.0;        ///< Deb & Jain 2014 use 30
  double mutation_probability = 0.0;  ///< 0 means 1/n
  double mutation_eta = 20.0;
  double equality_tolerance = 1e-4;
  std::uint64_t seed = 1;
  int threads = 0;
  std::vector<std::vector<double>> initial_population;
  /// Aspiration points in objective units (minimised), each of M values; empty: none.
  std::vector<std::vector<double>> aspiration_points;
  std::size_t aspiration_divisions = 0;  ///< H of each local set; 0: default_aspiration_divisions
  double aspiration_spread = 0.1;        ///< the local sets' size on the normalised simplex, (0, 1]

  std::optional<std::string> validate() const;
};

/// The reference directions the options give for m objectives (with aspiration points: those of
/// the points taken as already normalised, for their count).
std::vector<std::vector<double>> nsga3_directions(const Nsga3Options& options, std::size_t m);

/// Runs NSGA-III. Throws std::invalid_argument for invalid options or an unsupported problem
/// (nsga2_explain_unsupported). The result is the feasible non-dominated part of the final
/// population (empty with a message when none is feasible).
FrontResult run_nsga3(const Problem& problem, const Nsga3Options& options);

}  // namespace pkmopt
