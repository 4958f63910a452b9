// The search of an architecture synthesis (studies/synthesis_study.hpp): one NSGA-II per
// candidate structure, all feeding one archive, the budget moving toward the structures that
// make the merged front.
//
// Budget. With n structures, population P and G generations in the optimizer section, the
// synthesis spends at most what n separate runs would: B = n P (G + 1) evaluations.
//   equal               every structure runs G generations.
//   successive_halving  round 0 (the floor): every structure runs F generations
//                       (allocation.floor_generations). Then rounds 1..K keep the better half
//                       (rounded up) of the structures of the round before until one is left;
//                       the rest of the budget, B - n P (F + 1), is split evenly over the rounds
//                       and, within a round, over its structures (whole generations, rounded
//                       down). A structure continues its own population: its search after g
//                       generations in all is the search a separate run of g generations makes.
// Ranking after each round: by the structure's exclusive share of the merged front (the merged
// front's hypervolume less the hypervolume without the structure's designs), then by the
// hypervolume of its own front, then by its feasible evaluations, then in study order. The
// hypervolumes are taken in objectives normalised to the merged front (its ideal 0, its nadir 1)
// with the reference point 1.1 in each; a structure dropped keeps its designs in the merged
// front.
//
// Every structure's NSGA-II has its own seed (candidate_seed) and runs on `threads` threads, the
// structures one after another, so a seed gives the same result for any thread count.
//
// Example:
//   SynthesisStudy study = load_synthesis_study(YamlValue::load_file("study.yaml"));
//   const AllocationPlan plan = plan_allocation(study.searched().size(), 40, 60,
//                                               study.allocation);
#pragma once

#include <chrono>
#include <cstddef>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "io/format/yaml_reader.hpp"
#include "optimizer/problem.hpp"
#include "studies/journal.hpp"
#include "studies/run_study.hpp"
#include "studies/synthesis_study.hpp"

namespace pkmopt {

/// The rounds of a synthesis (see the header comment).
struct AllocationPlan {
  std::vector<std::size_t> structures;   ///< structures running in round r
  std::vector<std::size_t> generations;  ///< generations each of them runs in round r
  std::size_t population = 0;            ///< P
  long long budget = 0;                  ///< B = n P (G + 1)
  /// Evaluations the plan spends: P per structure for its first population, then P per
  /// generation.
  long long planned() const;
};

/// The plan for n structures (n >= 1), population P and G generations.
AllocationPlan plan_allocation(std::size_t n, std::size_t population, std::size_t generations,
                               const SynthesisAllocation& allocation);

/// One structure's feasible non-dominated designs (objective vectors, minimised).
using StructureFront = std::vector<std::vector<double>>;

/// The ranking scores of structures from their fronts (see the header comment): each one's
/// exclusive hypervolume share of the merged front and its own front's hypervolume, normalised.
struct StructureScores {
  std::vector<double> exclusive;
  std::vector<double> own;
};
StructureScores score_structures(const std::vector<StructureFront>& fronts);

/// What the search did with one searched structure.
struct StructureRun {
  std::size_t candidate = 0;  ///< index into SynthesisStudy::candidates
  std::size_t generations = 0;
  long long evaluations = 0;        ///< fitness requests of its NSGA-II
  std::size_t rounds = 0;           ///< rounds it ran in
  bool kept = true;                 ///< ran in the last round
  std::vector<double> exclusive;    ///< its exclusive share after each round (normalised HV)
  FrontResult front;                ///< its NSGA-II's last population front
};

struct SynthesisSearch {
  AllocationPlan plan;
  std::vector<StructureRun> runs;  ///< in study order of the searched candidates
  double seconds = 0.0;
};

/// Runs the search on the searched candidates' problems (problems[k] for study.searched()[k]:
/// their design problems, or journaled ones). `log` gets one line per round (may be empty).
SynthesisSearch search_structures(const SynthesisStudy& study,
                                  const std::vector<const Problem*>& problems, int threads,
                                  const std::function<void(const std::string&)>& log);

/// `pkmopt run` of a synthesis study (studies/run_study.hpp calls it): the result folder, one
/// journal per structure in candidates/NAME/, the search, and the result files
/// (studies/synthesis_outputs.hpp). Throws InputError.
StudyRunResult run_synthesis_study(const YamlValue& root, const StudyRunOptions& options,
                                   std::chrono::steady_clock::time_point wall_start);

}  // namespace pkmopt
