// Architecture synthesis studies: one task, every candidate kinematic structure dimensioned for
// it, one merged Pareto front. A study file is a synthesis study when it has a `candidates:` key.
//
//   study: milling-synthesis
//   description: "..."
//   candidates: auto                # every structure pkmopt offers for the task's motion type
//   # or a list; each entry a model name (its design space scaled from the task) or a map:
//   #   - hexapod
//   #   - {name: wide-hexaglide, task_centre: [0, 0, 0.5],
//   #      machine: {model: hexaglide, parameters: {...}, struts: {...}}}
//   task:                           # as in a design study; the region's centre is an offset
//     region: {shape: box, centre: [0, 0, 0], size: [0.3, 0.3, 0.2], points: [3, 3, 3]}
//     orientations: {tilt_deg: 20, step_deg: 10}
//     wrench: [300, 300, -1000, 0, 0, 0]
//   objectives: [...]               # as in a design study, the same for every structure
//   constraints: [...]
//   optimizer: {algorithm: nsga2, population: 40, generations: 60, seed: 1}
//   allocation: {rule: successive_halving, floor_generations: 15}
//   output: {designs: true}
//
// Candidates. A model offers its structures through the registry (ModelEntry::synthesis,
// io/machine/model_registry.hpp): a study machine section whose design space is scaled from the
// task's size, and where the task sits in the model's frame (task_centre). The task region's
// `centre` is added to it, and each structure's home_height moves it along z as in a design
// study. A list entry that is a map gives its own machine section (a design study's `machine:`)
// and task_centre (default: the model's).
//
// Mobility filter, before any evaluation. The task needs the translations along which its region
// extends (x, y, z) and the rotations of its orientations (tilt: about x and y; yaw: about z),
// its motion type nTmR. Rules first: a model's platform degrees of freedom (PlatformDofs, by
// pkmopt's conventions: 1 translation is z, 1 rotation is the yaw about z, 2 rotations are the
// tilts about x and y) must hold every needed motion. Then a numeric check: the structure's
// middle design (every free parameter at the middle of its range) at up to 9 task poses spread
// over the task; where the inverse Jacobian J (Machine::twist_jacobian) exists, J S (S: the
// needed unit twists) must have full column rank (smallest singular value above 1e-9 of the
// largest). A structure whose J S is rank deficient at every checked pose is dropped with its
// rank. Each dropped candidate carries its reason.
//
// Search (studies/synthesis_run.hpp): one NSGA-II per structure, the budget moving between
// structures by successive halving with a floor.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "io/format/yaml_reader.hpp"
#include "studies/design_study.hpp"

namespace pkmopt {

/// The motions a task needs: translations x, y, z and rotations about x, y, z (base axes).
struct TaskMotion {
  std::array<bool, 6> needed{};
  /// "3T2R": needed translations and rotations.
  std::string type() const;
  /// The needed motions in words: "x, y, z, tilt about x, tilt about y".
  std::string words() const;
};

/// One candidate structure of a synthesis.
struct SynthesisCandidate {
  std::string name;       ///< unique in the study
  std::string model;      ///< its registry model
  std::string structure;  ///< in words ("Gough–Stewart hexapod (6-UPS)")
  std::string origin;     ///< "scaled from the task" or "the study file"
  std::array<double, 3> task_centre{};  ///< m, the model's place for the task (before offset)
  bool searched = false;                ///< passed the mobility filter
  std::string dropped;                  ///< why it is not searched (empty when searched)
  std::string mobility;                 ///< what the numeric check found
  std::uint64_t seed = 0;               ///< its NSGA-II seed (from the study's seed and name)
  /// Its design study (searched candidates; the optimizer section is the synthesis's).
  std::shared_ptr<DesignStudy> study;
};

/// How the evaluation budget moves between structures.
struct SynthesisAllocation {
  std::string rule = "successive_halving";  ///< or "equal": every structure the same budget
  std::size_t floor_generations = 0;        ///< generations each structure runs before any drop
};

struct SynthesisStudy {
  std::string name;
  std::string description;
  TaskMotion motion;
  std::vector<SynthesisCandidate> candidates;  ///< every candidate, searched or dropped
  Nsga2Options nsga2;                          ///< population, generations, seed, variation
  SynthesisAllocation allocation;
  bool write_designs = true;
  std::size_t front_size = 0;  ///< the merged front thinned to this many designs; 0: not
  std::string resolved_yaml;   ///< study.resolved.yaml (a valid synthesis study file)

  /// The searched candidates' indices, in study order.
  std::vector<std::size_t> searched() const;
};

/// True when the file's root map has a `candidates:` key.
bool is_synthesis_study(const YamlValue& root);

/// Loads a synthesis study, generates its candidates and runs the mobility filter (throws
/// InputError naming file, line, column and key; a candidate's generated section is named
/// "candidate NAME (scaled from the task)").
SynthesisStudy load_synthesis_study(const YamlValue& root);

/// A candidate's NSGA-II seed: SplitMix64 of the study's seed and the FNV-1a hash of its name,
/// so a structure's search does not depend on the other candidates or their order.
std::uint64_t candidate_seed(std::uint64_t study_seed, const std::string& name);

/// The docs table of a synthesis section ("allocation").
std::string synthesis_fields_markdown(std::string_view section);

}  // namespace pkmopt
