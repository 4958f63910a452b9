// Design study files for `pkmopt run`: a machine with free parameters, a task, objectives,
// constraints, an optimizer and output options -> a HexapodDesignProblem, its Pareto front and
// the result folder. A study file is a design study when it has a `machine:` key.
//
//   study: hexapod-quick                      # name, required
//   description: "..."                        # optional
//   machine:
//     model: hexapod                          # or a leg-chain model, see below
//     parameters:                             # every key optional; a number = fixed,
//       base_radius: {min: 0.45, max: 0.75}   #   {min, max} = free (m; *_deg in degrees)
//       platform_radius: 0.25
//       base_pair_separation_deg: 20
//       platform_pair_separation_deg: {min: 10, max: 40}
//       min_length: 0.70
//       stroke: 0.45
//       home_height: 0.0                      # lifts the task region along z (m)
//     legs: {E: 2.1e11, area: 3.0e-4, actuator_stiffness: 2.0e8}   # or {axial_stiffness: k}
//     joints: {base_max_angle_deg: 45, platform_max_angle_deg: 45} # optional
//     tool: {tcp: [0, 0, -0.10]}                                    # optional
//     actuator_error: 1.0e-5                                        # optional (m)
//   task:
//     region: {shape: box, centre: [0, 0, 0.9], size: [0.3, 0.3, 0.2], points: [3, 3, 3]}
//          #  {shape: cylinder, centre: [...], radius: r, height: h, rings: 2, per_ring: 6,
//          #   layers: 3}
//     orientations: {tilt_deg: 20, yaw_deg: 0, step_deg: 10}         # optional
//     wrench: [fx, fy, fz, mx, my, mz]                                # N, N*m; optional
//     workspace: {resolution: 0.05, tilt_deg: 0, yaw_deg: 0, step_deg: 5}  # optional
//   objectives:                               # list, at least one
//     - maximize: stiffness_min
//     - minimize: machine_size
//   constraints:                              # optional list
//     - {metric: leg_force_max, max: 10500}   # metric <= 10500
//     - {metric: singularity_margin, min: 0.05}
//     - task_reachable
//     - task_singularity_free                 # the task region proved free of parallel
//                                             # singularities (hexapod; = {metric:
//                                             # task_singularity_free, min: 1})
//   optimizer: {algorithm: nsga2, population: 24, generations: 20, seed: 1}
//   output: {designs: true}                   # optional: write designs/<id>.yaml
//
// nsga2 uses the aggregate (derivative-free) formulation; every other algorithm the smooth one
// (see problems/design/hexapod_design.hpp).
//
// The machine section is read by the model it names (io/design/study_machine.hpp,
// io/machine/model_registry.hpp); the hexapod's is above (io/design/hexapod_study_machine.hpp). A
// model with a design family (problems/design/machine_design.hpp) loads into a
// MachineDesignProblem: `parameters:` takes the family's parameters (number = fixed, {min, max} =
// free), and every other key of the model's machine file may follow except the keys the parameters
// set:
//   machine:
//     model: linear_delta
//     parameters: {guide_radius: {min: 0.3, max: 0.6}, rod: {min: 0.5, max: 1.0}, stroke: 0.6,
//                  platform_radius: 0.05, inclination_deg: 0, home_height: 0}
//     rods: {E: 7.0e10, area: 3.0e-5}
//     carriage_stiffness: 2.0e7
//     joints: {carriage_max_angle_deg: 40, platform_max_angle_deg: 40}
// They take nsga2 or a derivative-free nlopt algorithm (aggregate formulation only) unless the
// model has a smooth formulation; actuator catalog constraints need a model that chooses
// actuators; translational platforms need a task without tilt or yaw.
//
// Outputs in DIR (docs/design-studies.md lists every column and unit): study.resolved.yaml
// (this schema with every default filled in; it loads to the same problem), journal.txt and
// evaluations.csv (every evaluation as it happens, studies/journal.hpp), pareto.csv and
// pareto.json (the front; pareto.json follows the pkmopt-pareto-1 format), summary.json, and
// designs/<id>.yaml (machine files for `pkmopt analyze` and `pkmopt workspace`).
//
// Example:
//   DesignStudy study = load_design_study("studies/library/hexapod-quick.yaml");
//   JournalOptions journal = design_journal_options(study);
//   journal.directory = "out";
//   journal.study_hash = study_hash(study.resolved_yaml);
//   JournaledProblem journaled(study.optimization_problem(), journal);
//   RunOutcome outcome = run_optimizer(journaled, study.optimizer, 0);
//   write_design_outputs("out", study, outcome, {.threads = 0});
// (studies/run_study.hpp does all of this, with the result folder's checks.)
#pragma once

#include <array>
#include <memory>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "io/design/study_machine.hpp"
#include "io/format/output_file.hpp"
#include "problems/design/design_problem.hpp"
#include "studies/journal.hpp"
#include "studies/optimizer_spec.hpp"

namespace pkmopt {

struct DesignStudy {
  std::string name;
  std::string description;
  /// The machine model (`machine.model`, io/machine/model_registry.hpp).
  std::string model;
  /// The model's part of the study: its parameters, capabilities and machine files.
  std::shared_ptr<const StudyMachine> machine;
  /// The design problem the optimizer runs.
  std::unique_ptr<DesignProblem> problem;
  OptimizerSpec optimizer;
  bool write_designs = true;
  /// output.front_size: the front is thinned to this many designs; 0: not thinned.
  std::size_t front_size = 0;
  std::array<double, 3> task_centre{};  ///< m, before the home_height lift
  double task_tilt_deg = 0.0;
  double task_yaw_deg = 0.0;
  std::size_t task_positions = 0;   ///< positions of the region (times orientations = poses)
  std::string task_region = "box";  ///< "box" or "cylinder"
  /// Where the task wrench comes from: "as typed", the cutting model's summary, or "" (none).
  std::string task_wrench_origin;
  /// study.resolved.yaml: the study with every default filled in (a valid study file).
  std::string resolved_yaml;
  /// Every parameter of the model in problem order (the free ones are the variables, in order).
  std::vector<StudyParameter> parameters;

  /// The problem the optimizer runs.
  const Problem& optimization_problem() const { return *problem; }
  const std::vector<DesignObjective>& objectives() const { return problem->objectives(); }
  const std::vector<DesignConstraint>& constraints() const { return problem->constraints(); }
  bool require_reachable() const { return problem->require_reachable(); }
  const DesignTask& task() const { return problem->task(); }
  /// True for the aggregate (derivative-free) formulation.
  bool aggregate() const { return problem->aggregate(); }
};

/// True when the file's root map has a `machine:` key (throws InputError for a bad file).
bool is_design_study_file(const std::string& path);

/// Loads and validates a design study (throws InputError naming file, line, column and key).
DesignStudy load_design_study(const std::string& path);
/// The same from a parsed study (relative paths inside it, e.g. an actuator catalog, are taken
/// relative to the folder of root.file(); a study built in memory names no folder, so they are
/// taken relative to the working directory).
DesignStudy load_design_study(const YamlValue& root);
/// One machine's design study from a study's shared sections (root: task, objectives,
/// constraints, optimizer, output; its other keys are not read): named `name`, the machine of
/// `machine_section`, the task region's centre moved by `placement` (m). The architecture
/// synthesis (studies/synthesis_study.hpp) makes one per candidate structure.
DesignStudy load_design_study_part(const YamlValue& root, const std::string& name,
                                   const YamlValue& machine_section,
                                   const std::array<double, 3>& placement);

/// The unit of a metric in outputs ("N/m", "m^3", "" for the dimensionless ones).
std::string_view design_metric_unit(DesignMetric metric);

/// Journal options for a design study: the evaluator with failure reasons and the
/// evaluations.csv header and rows (directory, hash and progress are left to the caller).
JournalOptions design_journal_options(const DesignStudy& study);

/// Extra facts for summary.json.
struct DesignRunFacts {
  int threads = 0;
  int mpi_ranks = 1;  ///< processes of the run: 1, or N under mpirun -np N
  double wall_seconds = 0.0;
  bool resumed = false;
  const JournaledProblem* journal = nullptr;  ///< evaluation counts (may be null)
};

/// What write_design_outputs wrote.
struct DesignOutputSummary {
  std::size_t designs = 0;    ///< designs on the front
  std::string status;         ///< summary.json's status (no_feasible_design for an empty front)
  std::string infeasibility;  ///< for an empty front: the most frequent causes, in words
};

/// Writes pareto.csv, pareto.json, summary.json and designs/<id>.yaml into `directory`, together
/// with the files `also` names, all or none (io/format/output_file.hpp, write_files_together).
DesignOutputSummary write_design_outputs(const std::string& directory, const DesignStudy& study,
                                         const RunOutcome& outcome, const DesignRunFacts& facts,
                                         const OutputFiles& also = {});

/// The docs table of a study section described by a field list, from the same list its reader
/// and the resolved writer use: "machine hexapod", "machine.parameters MODEL" (a leg-chain
/// model), "task.region box", "task.region cylinder", "task.orientations", "task.workspace",
/// "objectives[]", "constraints[]", "constraints[] actuator", "output".
std::string design_study_fields_markdown(std::string_view section);

}  // namespace pkmopt
