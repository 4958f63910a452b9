// Design problems for any Machine: a design family (named parameters -> a machine), a task, and
// the metrics every design study uses, measured through the generic Machine interface.
//
// This header also holds the vocabulary shared with the hexapod design problem
// (problems/hexapod_design.hpp): metrics, senses, objectives, constraints, the task and its pose
// sampling, the worst-case reduction over the task and the aggregate fitness rows.
//
// Design family: parameters p_1..p_n, each with a name as in study files ("rod",
// "inclination_deg"), a unit ("m" or "deg"; angles are radians inside the code), a default
// value, and the machine-file keys it sets; a builder p -> std::unique_ptr<Machine>; a
// machine_size(p) (m^3); and a machine-file writer (YAML that `pkmopt analyze` loads). Every
// family has the parameter `home_height` (m): the task region is lifted by h along base z
// (the task centre of the study is at centre + (0, 0, h) in the machine frame), as for the
// hexapod. The families (docs/design-studies.md has their parameter tables):
//   delta        base_radius, platform_radius, upper_arm, rod (m), drive_min_deg, drive_max_deg
//                (deg, the drive range), home_height (m);
//                machine_size = envelope_volume = pi (r_b + r_a)^2 (2 r_a + l)
//                (r_b base radius, r_a upper arm, l rod: the cylinder swept by the cranks,
//                extended down by a rod length).
//   linear_delta guide_radius, platform_radius, rod, stroke (m; carriage travel q in
//                [0, stroke] along each guide from z = 0), inclination_deg (deg), home_height;
//                machine_size = envelope_volume = pi rho^2 (s cos(i) + l),
//                rho = max(r_g, |r_g - s sin(i)|) (the cylinder about the guide segments,
//                extended down by a rod length).
//   hexaglide    platform_radius (m), pair_separation_deg (deg; the semi-regular platform
//                turned 90 deg about z, as models/leg_chain.hpp), guide_offset (m: guide i
//                lies at y = b_i.y + guide_offset outwards), strut, stroke (m: carriages travel
//                q in [-stroke/2, stroke/2] along x), inclination_deg (deg), home_height (m);
//                machine_size = envelope_volume = pi rho^2 (s |sin(i)| + L),
//                rho = max_i sqrt((s/2 cos(i))^2 + (y_i - y_mean)^2), y_i the guide positions.
//   tripod_3prs  base_radius, platform_radius, strut, stroke (m: slide travel q in
//                [q_min, q_min + stroke], q_min from the template), home_height (m);
//                machine_size = envelope_volume (the cylinder about the slides' travel,
//                extended by a strut length). The head's inputs are z and the two tilts: the
//                task's x, y and rz are replaced by the parasitic ones (models/leg_chain.hpp),
//                so a tripod task is a column of z values times a tilt cone.
// Each is fixed (lower == upper) or free within [lower, upper]; only free ones are variables.
// Everything else (link stiffness, joint limits, TCP, actuator error, branch) comes from the
// family's template design.
//
// Metrics (same names and meanings as the hexapod problem; per-pose definitions in
// docs/conventions.md and models/machine.hpp), over the task poses k lifted by home_height:
//   stiffness_min       min_k stiffness_min(pose k)                       N/m
//   singularity_margin  min_k singularity_margin(pose k)                  0..1
//   leg_force_max       max_k max_i |tau_i(pose k)| under w               N (N*m for rotary drives)
//   tcp_error_max       max_k tcp_error_max(pose k)                       m
//   tcp_deflection_max  max_k tcp_deflection(pose k) under w              m
//   stiffness_min_loaded  min_k stiffness_min_loaded(pose k) under w      N/m
//   natural_frequency_min min_k natural_frequency_1(pose k) (needs masses)  Hz
//   moving_mass         platform plus every leg's moving bodies (needs masses)  kg
//   leg_clearance_min   min_k leg_clearance(pose k) (needs the legs' shape)   m
//   swept_volume, footprint   hexapod studies only (hexapod_design.hpp)      m^3, m^2
//   workspace_volume    workspace_volume(machine, task.workspace)        m^3
//   conditioning_index  mean singularity margin over the workspace grid  0..1
//   machine_size        the family's machine_size (above)                m^3
// Reduced over the poses where the machine can be analysed: a pose that is unreachable and
// singular (typically a leg that cannot close at all) has no metrics and only counts in the
// reachability row. A reachable singular pose makes the evaluation fail (as for the hexapod).
// Task reachability (optional, default on) is one row, the mean over the N task poses
//   g_reach = (1/N) sum_k v_k,  v_k = 0 for a reachable pose (Machine::reachable: actuator
//   ranges, joint limits, no rotation of a translational platform), else
//   v_k = min(1, e_k) with e_k the largest excess of pose k over an actuator range (m or rad)
//   or a joint-angle limit (rad) of a leg-chain machine, and v_k = 1 when the legs cannot close,
//   when no excess explains it, or for machines that are not leg chains.
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
//   spec.family = linear_delta_family(LinearDeltaDesign{});
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
#include <variant>
#include <vector>

#include "models/installation_space.hpp"
#include "models/lathe_conversion.hpp"
#include "models/leg_chain.hpp"
#include "models/machine.hpp"
#include "models/workspace/workspace.hpp"
#include "optimizer/problem.hpp"

namespace pkmopt {

// ---------------------------------------------------------------------------------------------
// Vocabulary shared by every design problem.

/// A parameter's range in internal units; fixed when lower == upper.
struct ParameterRange {
  double lower = 0.0;
  double upper = 0.0;
  bool fixed() const { return lower == upper; }
};

enum class DesignMetric {
  stiffness_min,
  singularity_margin,
  leg_force_max,
  tcp_error_max,
  workspace_volume,
  conditioning_index,
  machine_size,
  /// The relative cost of the cheapest catalog actuator that carries the legs (hexapod studies
  /// with an actuator catalog to choose from; see hexapod_design.hpp).
  actuator_cost,
  /// leg_force_max minus the largest force rating among the catalog entries whose stroke
  /// covers the design's stroke (N); <= 0 exactly when some entry carries the legs.
  actuator_overload,
  /// max over the task of the TCP deflection under the task wrench, |(C w)_t| (m).
  tcp_deflection_max,
  /// min over the task of the loaded stiffness (N/m; models/machine.hpp).
  stiffness_min_loaded,
  /// min over the task of the first natural frequency (Hz; needs the machine's masses,
  /// docs/dynamics.md).
  natural_frequency_min,
  /// The mass in motion: the platform's and every leg's moving bodies (kg; needs the masses).
  moving_mass,
  /// max over the task and the actuators of the force when the TCP, at rest, accelerates in any
  /// direction with |a| <= the task's a_max under the task wrench and gravity (N; needs the
  /// masses; models/acceleration_capability.hpp).
  actuator_force_dynamic_max,
  /// min over the task of the legs' clearance (m; needs the legs' shape, models/
  /// leg_interference.hpp; negative when legs intersect).
  leg_clearance_min,
  /// The volume of the convex hull of the machine over the task (m^3; hexapod studies;
  /// models/swept_envelope.hpp): base joints, platform joints and the solids at every task pose.
  swept_volume,
  /// The area of that hull's projection on the base's x-y plane (m^2; hexapod studies).
  footprint
};
inline constexpr int kNumDesignMetrics = 17;
/// True for the metrics that need the compliance matrix at every task pose.
bool is_compliance_metric(DesignMetric metric);
/// True for the metrics that need an actuator catalog (actuator_cost, actuator_overload).
bool is_actuator_metric(DesignMetric metric);
std::string_view design_metric_name(DesignMetric metric);
/// The metric named `name`, nullopt if none is.
std::optional<DesignMetric> design_metric_from_name(std::string_view name);

enum class Sense { minimize, maximize };
enum class Relation { less_equal, greater_equal };

struct DesignObjective {
  DesignMetric metric = DesignMetric::stiffness_min;
  Sense sense = Sense::minimize;
};

struct DesignConstraint {
  DesignMetric metric = DesignMetric::leg_force_max;
  Relation relation = Relation::less_equal;
  double bound = 0.0;  ///< in the metric's unit
};

/// The poses and load the machine must handle.
struct DesignTask {
  std::vector<Pose> poses;         ///< TCP poses before the home_height lift (rad)
  Wrench wrench = Wrench::Zero();  ///< at the TCP, base axes (N, N*m)
  /// a_max (m/s^2): the TCP acceleration the drives are sized for (actuator_force_dynamic_max and
  /// an actuator catalog's choice); 0 = none.
  double acceleration_max = 0.0;
  /// For workspace_volume and conditioning_index (hull off; maps only for the index).
  WorkspaceOptions workspace;
  /// The space the whole machine must fit in at every task pose (hexapod problems: legs with
  /// their shape, base and platform joints; models/installation_space.hpp); part of the
  /// reachability row.
  InstallationSpace installation_space;
};

/// Positions on an n_x x n_y x n_z grid of the box centre +- half_extents (a count of 1 puts the
/// points on the centre plane), times the orientations of a cone of half-angle `tilt` and a yaw
/// range +-yaw (rad) sampled with `orientation_step` (sample_orientations, R0 = I).
std::vector<Pose> box_task_poses(const Eigen::Vector3d& centre, const Eigen::Vector3d& half_extents,
                                 const Eigen::Vector3i& counts, double tilt, double yaw,
                                 double orientation_step = 10.0 * kDegToRad);
/// Positions on a cylinder about the vertical axis through `centre`: the axis point and
/// `rings` rings (radius radius*j/rings) of `per_ring` points each, on `layers` planes spanning
/// centre.z +- height/2, times the orientations as in box_task_poses.
std::vector<Pose> cylinder_task_poses(const Eigen::Vector3d& centre, double radius, double height,
                                      int rings, int per_ring, int layers, double tilt, double yaw,
                                      double orientation_step = 10.0 * kDegToRad);

/// Objective and constraint rows of a failed design (finite: never NaN in outputs).
inline constexpr double kFailurePenalty = 1e20;

/// Metric values by DesignMetric index (user units and signs).
using DesignMetrics = std::array<double, kNumDesignMetrics>;
/// Which metrics the objectives and constraints need, by DesignMetric index.
using NeededMetrics = std::array<bool, kNumDesignMetrics>;

/// Checks the goals and the task of a design problem (`where` names it in messages: at least one
/// objective and one pose, finite constraint bounds, valid workspace options when needed) and
/// prepares task.workspace (maps only for the conditioning index, no hull, no points). Returns
/// the metrics the goals need. Throws std::invalid_argument.
NeededMetrics check_design_goals(const std::string& where,
                                 const std::vector<DesignObjective>& objectives,
                                 const std::vector<DesignConstraint>& constraints,
                                 DesignTask& task);

/// The worst cases of the per-pose metrics over a task.
struct TaskWorstCase {
  double stiffness_min = std::numeric_limits<double>::infinity();
  double singularity_margin = std::numeric_limits<double>::infinity();
  double leg_force_max = 0.0;  ///< max_i |tau_i|
  double tcp_error_max = 0.0;
  double tcp_deflection_max = 0.0;
  double stiffness_min_loaded = std::numeric_limits<double>::infinity();
  double natural_frequency_min = std::numeric_limits<double>::infinity();
  double leg_clearance_min = std::numeric_limits<double>::infinity();
  void add(const PoseMetrics& metrics);
  /// Writes the worst cases into their slots of `metrics`.
  void store(DesignMetrics& metrics) const;
};

/// workspace_volume and conditioning_index of a machine (only those `needed`) into `metrics`;
/// a workspace error or an empty workspace (for the index) sets `failure` when it is empty.
void measure_workspace_metrics(const Machine& machine, const WorkspaceOptions& options,
                               const NeededMetrics& needed, DesignMetrics& metrics,
                               std::string& failure);

/// Replaces every non-finite needed metric by kFailurePenalty; the first one sets `failure` when
/// it is empty ("stiffness_min is not finite").
void check_finite_metrics(const NeededMetrics& needed, DesignMetrics& metrics,
                          std::string& failure);

/// The aggregate rows [objectives | constraints | reachability (if required)] of a measured
/// design; every row is kFailurePenalty when `failed`.
std::vector<double> aggregate_design_rows(const std::vector<DesignObjective>& objectives,
                                          const std::vector<DesignConstraint>& constraints,
                                          bool require_reachable, const DesignMetrics& metrics,
                                          double reach_violation, bool failed);

// ---------------------------------------------------------------------------------------------
// Design families.

/// The design of a family's machine: the design struct of its model.
using FamilyDesign = std::variant<DeltaDesign, LinearDeltaDesign, HexaglideDesign, Tripod3PrsDesign,
                                  Lathe16k20f3Design>;

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
  /// The model's design of a parameter vector (internal units); io/machine_file_writer.hpp
  /// writes it as a machine file.
  std::function<FamilyDesign(const std::vector<double>&)> design;
  /// The machine_size metric of a built design (m^3).
  std::function<double(const Machine&, const std::vector<double>&)> machine_size;
  /// The platform keeps its orientation (task poses must not rotate).
  bool translational = false;

  /// Index of a parameter by name; -1 if there is none.
  int index_of(std::string_view name) const;
  /// The default parameter vector (internal units).
  std::vector<double> default_parameters() const;
};

/// machine_size as Machine::envelope_volume (models/workspace: machine_envelope_volume).
double envelope_machine_size(const Machine& machine, const std::vector<double>& parameters);

/// v_k of g_reach for a pose the machine does not reach (see the header comment), in (0, 1].
double pose_reach_violation(const Machine& machine, const Pose& pose);

/// The families of the leg-chain models; the template supplies everything the parameters do
/// not set (its geometric fields are the parameter defaults).
DesignFamily delta_family(const DeltaDesign& design_template);
DesignFamily linear_delta_family(const LinearDeltaDesign& design_template);
DesignFamily hexaglide_family(const HexaglideDesign& design_template);
DesignFamily tripod_3prs_family(const Tripod3PrsDesign& design_template);

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

  /// Coarse workspace options for speed (resolution 0.05 m, 4 bisections), as the hexapod's.
  MachineDesignSpec();
};

/// Every parameter of a family fixed at its default.
std::vector<ParameterRange> default_ranges(const DesignFamily& family);

/// Everything an evaluation measured, in user units and signs.
struct MachineDesignEvaluation {
  std::vector<double> parameters;  ///< every family parameter, internal units
  DesignMetrics metrics{};         ///< by DesignMetric; only the needed ones
  bool reachable = false;          ///< every task pose reachable
  double reach_violation = 0.0;    ///< g_reach (0 when reachable, else in (0, 1])
  std::size_t analysed_poses = 0;  ///< poses the metrics were reduced over
  std::string failure;             ///< empty when the evaluation succeeded
  bool ok() const { return failure.empty(); }
};

class MachineDesignProblem final : public Problem {
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
  /// Indices of the free parameters, in variable order.
  const std::vector<int>& free_parameters() const { return free_; }
  /// All parameters (internal units) for a variable vector.
  std::vector<double> parameters_of(const std::vector<double>& x) const;
  /// The task lift (m) of a parameter vector (0 when the family has no home_height).
  double home_height_of(const std::vector<double>& parameters) const;
  /// Measures a design over the task (every metric the objectives and constraints need).
  MachineDesignEvaluation evaluate(const std::vector<double>& x) const;
  /// Objective and constraint rows from an evaluation.
  std::vector<double> aggregate_fitness(const MachineDesignEvaluation& evaluation) const;

 private:
  MachineDesignSpec spec_;
  std::vector<int> free_;
  NeededMetrics needed_{};
  int home_height_ = -1;
};

}  // namespace pkmopt
