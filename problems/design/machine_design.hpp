// Design problems for any Machine: a design family (named parameters -> a machine), a task, and
// the metrics every design study uses, measured through the generic Machine interface.
//
// The vocabulary shared with the hexapod design problem (metrics, objectives, constraints, the
// task) is in problems/design/design_metrics.hpp; what the study engine reads of any design problem
// in problems/design/design_problem.hpp.
//
// Design family: parameters p_1..p_n, each with a name as in study files ("rod",
// "inclination_deg"), a unit ("m" or "deg"; angles are radians inside the code), a default
// value, and the machine-file keys it sets; a builder p -> std::unique_ptr<Machine>; a
// machine_size(p) (m^3); and a machine-file writer (YAML that `pkmopt analyze` loads). Every
// family has the parameter `home_height` (m): the task region is lifted by h along base z
// (the task centre of the study is at centre + (0, 0, h) in the machine frame), as for the
// hexapod. The families of the models are beside them (the leg chains' in
// problems/design/leg_chain_design.hpp, the lathe's in problems/design/lathe_design.hpp).
// Each parameter is fixed (lower == upper) or free within [lower, upper]; only free ones are
// variables. Everything else (link stiffness, joint limits, TCP, actuator error, branch) comes from
// the family's template design.
//
// Metrics (same names and meanings as the hexapod problem; per-pose definitions in
// docs/conventions.md and models/core/machine.hpp), over the task poses k lifted by home_height:
//   stiffness_min       min_k stiffness_min(pose k)                       N/m
//   singularity_margin  min_k singularity_margin(pose k)                  0..1
//   leg_force_max       max_k max_i |tau_i(pose k)| under w               N (N*m for rotary drives)
//   tcp_error_max       max_k tcp_error_max(pose k)                       m
//   tcp_deflection_max  max_k tcp_deflection(pose k) under w              m
//   stiffness_min_loaded  min_k stiffness_min_loaded(pose k) under w      N/m
//   natural_frequency_min min_k natural_frequency_1(pose k) (needs masses)  Hz
//   moving_mass         platform plus every leg's moving bodies (needs masses)  kg
//   leg_clearance_min   min_k leg_clearance(pose k) (needs the legs' shape)   m
//   swept_volume, footprint   the convex hull of the machine's drawing over the task and its
//                       area seen from above (models/geometry/sketch_envelope.hpp)  m^3, m^2
//   task_margin         how far the task could grow and stay reachable (design_metrics.hpp)  m
//   task_singularity_free     hexapod studies only (hexapod_design.hpp)      0..1
//   workspace_volume    workspace_volume(machine, task.workspace)        m^3
//   conditioning_index  mean singularity margin over the workspace grid  0..1
//   machine_size        the family's machine_size (above)                m^3
//   actuator_cost, actuator_overload  with an actuator catalog (families with linear drives:
//                       the lathe's cylinders, a hexaglide's or linear delta's carriages as
//                       linear motors or screws): the cheapest entry that carries every drive,
//                       need = {force: the largest |tau_i| over the task, stroke: the longest
//                       actuator_stroke, both over the chosen drives (actuator_drives, default
//                       every drive)}, as for the hexapod (problems/design/hexapod_design.hpp): its
//                       relative cost (twice the dearest entry's, or entries + 1 for a rank
//                       catalog, when none carries) and the overload of the best long-enough
//                       entry (N; <= 0 exactly when some entry carries the drives)
// Reduced over the poses where the machine can be analysed: a pose that is unreachable and
// singular (typically a leg that cannot close at all) has no metrics and only counts in the
// reachability row. A reachable singular pose makes the evaluation fail (as for the hexapod)
// when its statics blow up (stiffness_min 0 or a force without bound, as at a parallel
// machine's singularity); a serial machine's free rotary axis (the tool along the C axis) keeps
// finite statics and is measured, with singularity_margin 0.
// Task reachability (optional, default on) is one row, the mean over the N task poses
//   g_reach = (1/N) sum_k v_k,  v_k = 0 for a reachable pose (Machine::reachable: actuator
//   ranges, joint limits, no rotation of a translational platform), else
//   v_k = min(1, e_k) with e_k the largest excess of pose k over an actuator range (m or rad)
//   or a joint-angle limit (rad) of a leg-chain machine, and v_k = 1 when the legs cannot close,
//   when no excess explains it, or for machines that are not leg chains. With an installation
//   space (task.installation_space), v_k also gains min(1, o_k) for o_k > 0, how far the
//   machine drawn at pose k sticks out of it (models/geometry/sketch_envelope.hpp,
//   sketch_excess).
// So g_reach <= 0 <=> the whole task is reachable, and g_reach in (0, 1] says how far off it
// is (the fraction of unreachable poses when each misses by 1 or more).
//
// Formulation: aggregate only (derivative-free: NSGA-II, derivative-free NLopt algorithms):
// one row per objective (f = metric, or -metric when maximised), per constraint
// (metric - b <= 0 for max, b - metric <= 0 for min) and the reachability row.
//
// Failures: a design the family's builder rejects, no analysable task pose, a reachable
// singular task pose or any non-finite needed metric: `failure` says why and every row is
// kFailurePenalty (finite: never NaN).
//
// Thread safety: basic. Every evaluation builds its own machine and MachineData, so batches run
// in parallel (OpenMP) and give bit-identical results for any thread count.
//
// Example:
//   MachineDesignSpec spec;
//   spec.family = linear_delta_family(LinearDeltaDesign{});   // leg_chain_design.hpp
//   spec.parameters = default_ranges(spec.family);
//   spec.parameters[spec.family.index_of("rod")] = {0.5, 0.9};
//   spec.task.poses = box_task_poses({0, 0, -0.6}, {0.15, 0.15, 0.1}, {3, 3, 3}, 0, 0);
//   spec.objectives = {{DesignMetric::stiffness_min, Sense::maximize},
//                      {DesignMetric::machine_size, Sense::minimize}};
//   MachineDesignProblem problem(spec);
//   std::vector<double> f = problem.fitness({0.7});
#pragma once

#include <array>
#include <cstddef>
#include <functional>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "models/core/machine.hpp"
#include "models/geometry/installation_space.hpp"
#include "models/workspace/workspace.hpp"
#include "optimizer/problem.hpp"
#include "problems/design/actuator_catalog.hpp"
#include "problems/design/design_metrics.hpp"
#include "problems/design/design_problem.hpp"

namespace pkmopt {

// ---------------------------------------------------------------------------------------------
// Design families.

/// Writes a model's design as its machine file (the model's io/ reader reads it back).
template <class Design>
using DesignWriter = std::function<std::string(const Design&)>;

/// One named design parameter of a family.
struct FamilyParameter {
  std::string name;      ///< as in study files: "rod", "inclination_deg"
  std::string unit;      ///< "m" or "deg" (file unit; "deg" parameters are rad inside)
  std::string doc;       ///< one line for the docs: what the parameter sets
  double default_value;  ///< file units
  bool may_be_negative;  ///< otherwise values must be >= 0 ...
  bool may_be_zero;      ///< ... and > 0 unless this is set
  double max_abs = std::numeric_limits<double>::infinity();  ///< |file value| <= max_abs
  bool in_degrees() const { return unit == "deg"; }
  /// Internal value (rad for degrees) of a file value.
  double to_internal(double file_value) const;
  /// File value of an internal value.
  double to_file(double internal_value) const;
};

/// A family of machines described by a few parameters (see the header comment).
struct DesignFamily {
  std::string model;  ///< the `model:` name of the machine files
  std::vector<FamilyParameter> parameters;
  /// Machine-file keys computed from the parameters (a study's machine section may not set them).
  std::vector<std::string> parameter_keys;
  /// The machine of a parameter vector (internal units; one value per parameter). Throws
  /// std::invalid_argument for an impossible machine.
  std::function<std::unique_ptr<Machine>(const std::vector<double>&)> build;
  /// The machine_size metric of a built design (m^3).
  std::function<double(const Machine&, const std::vector<double>&)> machine_size;
  /// The platform keeps its orientation (task poses must not rotate).
  bool translational = false;
  /// The machine file of a parameter vector (internal units), from the writer the family was
  /// made with (the model's registry entry gives its io/ writer; io/machine/model_registry.hpp);
  /// empty when it was made without one.
  std::function<std::string(const std::vector<double>&)> machine_file;

  /// Index of a parameter by name; -1 if there is none.
  int index_of(std::string_view name) const;
  /// The default parameter vector (internal units).
  std::vector<double> default_parameters() const;
};

/// machine_size as Machine::envelope_volume (models/workspace: machine_envelope_volume).
double envelope_machine_size(const Machine& machine, const std::vector<double>& parameters);

/// v_k of g_reach for a pose the machine does not reach (see the header comment), in (0, 1].
double pose_reach_violation(const Machine& machine, const Pose& pose);

// ---------------------------------------------------------------------------------------------
// The problem.

/// Everything that defines a machine design problem.
struct MachineDesignSpec {
  std::string name = "machine-design";
  DesignFamily family;
  std::vector<ParameterRange> parameters;  ///< one per family parameter, internal units
  DesignTask task;
  std::vector<DesignObjective> objectives;
  std::vector<DesignConstraint> constraints;
  bool require_reachable = true;
  /// The linear drives to choose every design's actuators from (actuator_cost,
  /// actuator_overload; see the header comment); none when absent.
  std::optional<ActuatorCatalog> actuator_catalog;
  /// The drives (0-based) the catalog entry is chosen for; empty: every drive.
  std::vector<int> actuator_drives;
  /// Every drive priced from the catalog, linear and rotary (drive_cost, drive_overload;
  /// Machine::drive_group gives the alike drives), instead of one entry for the chosen drives.
  bool each_drive = false;
};

/// The machine's drives in groups of alike drives (Machine::drive_group, in order of their first
/// drive): their kind, count, largest |drive_force| and longest stroke (linear drives).
std::vector<DriveGroupNeed> drive_group_needs(const Machine& machine,
                                              const Eigen::VectorXd& drive_force);

/// Every parameter of a family fixed at its default.
std::vector<ParameterRange> default_ranges(const DesignFamily& family);

/// Everything an evaluation measured, in user units and signs.
struct MachineDesignEvaluation {
  std::vector<double> parameters;  ///< every family parameter, internal units
  DesignMetrics metrics{};         ///< by DesignMetric; only the needed ones
  bool reachable = false;          ///< every task pose reachable
  double reach_violation = 0.0;    ///< g_reach (0 when reachable, else in (0, 1])
  std::size_t analysed_poses = 0;  ///< poses the metrics were reduced over
  int actuator = -1;               ///< with a catalog: the chosen entry, -1 when none carries
  /// each_drive: the groups of drives and the catalog's choice for them (measure() puts it in
  /// words, drive_choice_text; the search needs only the metrics).
  std::vector<DriveGroupNeed> drive_needs;
  DriveChoice drive_choice;
  std::string failure;  ///< empty when the evaluation succeeded
  bool ok() const { return failure.empty(); }
};

class MachineDesignProblem final : public DesignProblem {
 public:
  /// Checks the spec; throws std::invalid_argument naming the field.
  explicit MachineDesignProblem(MachineDesignSpec spec);

  Bounds bounds() const override;
  std::size_t num_objectives() const override { return spec_.objectives.size(); }
  std::size_t num_inequality() const override {
    return spec_.constraints.size() + (spec_.require_reachable ? 1 : 0);
  }
  std::vector<double> fitness(const std::vector<double>& x) const override;
  std::string name() const override { return spec_.name; }
  ThreadSafety thread_safety() const override { return ThreadSafety::basic; }

  const MachineDesignSpec& spec() const { return spec_; }
  const DesignFamily& family() const { return spec_.family; }

  // DesignProblem (problems/design/design_problem.hpp); the formulation is aggregate.
  const DesignTask& task() const override { return spec_.task; }
  const std::vector<DesignObjective>& objectives() const override { return spec_.objectives; }
  const std::vector<DesignConstraint>& constraints() const override { return spec_.constraints; }
  bool require_reachable() const override { return spec_.require_reachable; }
  bool aggregate() const override { return true; }
  const ActuatorCatalog* actuator_catalog() const override {
    return spec_.actuator_catalog ? &*spec_.actuator_catalog : nullptr;
  }
  bool prices_each_drive() const override { return spec_.each_drive; }
  /// Indices of the free parameters, in variable order.
  const std::vector<int>& free_parameters() const override { return free_; }
  std::vector<double> design_parameters(const std::vector<double>& x) const override {
    return parameters_of(x);
  }
  double home_height(const std::vector<double>& parameters) const override {
    return home_height_of(parameters);
  }
  DesignRecord measure(const std::vector<double>& x) const override;
  /// All parameters (internal units) for a variable vector.
  std::vector<double> parameters_of(const std::vector<double>& x) const;
  /// The task lift (m) of a parameter vector (0 when the family has no home_height).
  double home_height_of(const std::vector<double>& parameters) const;
  /// Measures a design over the task (every metric the objectives and constraints need).
  MachineDesignEvaluation evaluate(const std::vector<double>& x) const;
  /// Objective and constraint rows from an evaluation.
  std::vector<double> aggregate_fitness(const MachineDesignEvaluation& evaluation) const;

 private:
  /// Checks the catalog and the family's drives; the costs by which designs choose.
  void set_up_actuator_catalog(const std::string& where);
  /// Refuses mass metrics without a mass model and leg_clearance_min without the links' shape,
  /// from the family's template machine.
  void check_template_machine(const std::string& where) const;
  /// The pass over the lifted task poses: the worst-case metrics, reachability (with the
  /// installation space and the obstacles) and a failure; returns each drive's largest |tau|.
  Eigen::VectorXd measure_task_poses(const Machine& machine, double h,
                                     MachineDesignEvaluation& ev) const;
  /// task_margin, swept_volume and footprint over the lifted task, when needed.
  void measure_envelope(const Machine& machine, double h, MachineDesignEvaluation& ev) const;
  /// The catalog's choice for the drives' largest loads: one entry, or every drive priced.
  void price_drives(const Machine& machine, const Eigen::VectorXd& drive_force,
                    MachineDesignEvaluation& ev) const;
  MachineDesignSpec spec_;
  std::vector<int> free_;
  NeededMetrics needed_{};
  int home_height_ = -1;
  CatalogPricing pricing_;  // with a catalog: the entries' costs, and a design's none carries
};

}  // namespace pkmopt
