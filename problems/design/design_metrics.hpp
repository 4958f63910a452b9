// The vocabulary of design problems, shared by every model: metrics, senses, objectives,
// constraints, the task and its pose sampling, the worst-case reduction over a task and the
// aggregate fitness rows. The metrics' definitions and units are in
// problems/design/machine_design.hpp (any machine) and problems/design/hexapod_design.hpp
// (hexapod-only metrics), per-pose metrics in docs/conventions.md and models/core/machine.hpp.
#pragma once

#include <array>
#include <cstddef>
#include <limits>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "models/core/machine.hpp"
#include "models/core/pose_box.hpp"
#include "models/geometry/installation_space.hpp"
#include "models/geometry/obstacle.hpp"
#include "models/workspace/workspace.hpp"

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
  /// min over the task of the loaded stiffness (N/m; models/core/machine.hpp).
  stiffness_min_loaded,
  /// min over the task of the first natural frequency (Hz; needs the machine's masses,
  /// docs/dynamics.md).
  natural_frequency_min,
  /// The mass in motion: the platform's and every leg's moving bodies (kg; needs the masses).
  moving_mass,
  /// max over the task and the actuators of the force when the TCP, at rest, accelerates in any
  /// direction with |a| <= the task's a_max under the task wrench and gravity (N; needs the
  /// masses; models/dynamics/acceleration_capability.hpp).
  actuator_force_dynamic_max,
  /// min over the task of the legs' clearance (m; needs the legs' shape, models/
  /// leg_interference.hpp; negative when legs intersect).
  leg_clearance_min,
  /// The volume of the convex hull of the machine over the task (m^3): the hexapod's base joints,
  /// platform joints and solids at every task pose (models/hexapod/swept_envelope.hpp), other
  /// models' drawings (models/geometry/sketch_envelope.hpp).
  swept_volume,
  /// The area of that hull's projection on the base's x-y plane (m^2).
  footprint,
  /// The share of the task region proved free of parallel singularities with one working mode
  /// (0..1; 1: certified; hexapod studies with a box or cylinder task;
  /// models/workspace/mode_certificate.hpp).
  task_singularity_free,
  /// How far the task could grow and stay reachable (m; task_margin below): the workspace
  /// margin around the task, for any model.
  task_margin,
  /// Every drive priced ({actuator: cheapest, catalog: FILE, each_drive: true}): the sum over the
  /// groups of alike drives of count x the cost of the cheapest catalog entry of their kind that
  /// carries the group (problems/design/actuator_catalog.hpp choose_drives; relative cost).
  drive_cost,
  /// The largest relative shortfall over those groups (dimensionless, choose_drives); <= 0
  /// exactly when every drive is carried by some entry.
  drive_overload
};
inline constexpr int kNumDesignMetrics = 21;
/// True for the metrics that need the compliance matrix at every task pose.
bool is_compliance_metric(DesignMetric metric);
/// True for the metrics that need an actuator catalog (actuator_cost, actuator_overload,
/// drive_cost, drive_overload).
bool is_actuator_metric(DesignMetric metric);
/// True for the metrics of a catalog that prices every drive (drive_cost, drive_overload).
bool is_drive_metric(DesignMetric metric);
/// Why a design problem with a catalog (each_drive or not) cannot measure the needed metrics:
/// the one-entry metrics with each_drive, the every-drive ones without; empty when it can.
std::string actuator_metric_mismatch(const std::array<bool, kNumDesignMetrics>& needed,
                                     bool each_drive);
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

/// The workspace options design problems start from: a 0.05 m grid, 4 bisection steps.
inline WorkspaceOptions coarse_design_workspace() {
  WorkspaceOptions options;
  options.resolution = 0.05;
  options.bisection_steps = 4;
  return options;
}

/// The poses and load the machine must handle.
struct DesignTask {
  std::vector<Pose> poses;         ///< TCP poses before the home_height lift (rad)
  Wrench wrench = Wrench::Zero();  ///< at the TCP, base axes (N, N*m)
  /// a_max (m/s^2): the TCP acceleration the drives are sized for (actuator_force_dynamic_max and
  /// an actuator catalog's choice); 0 = none.
  double acceleration_max = 0.0;
  /// For workspace_volume and conditioning_index (hull off; maps only for the index); coarse
  /// for speed by default: 0.05 m and 4 bisections of the boundary cells.
  WorkspaceOptions workspace = coarse_design_workspace();
  /// The task as a region of poses (box or cylinder tasks: the positions' bounding box times the
  /// orientation set, before the home_height lift), for task_singularity_free.
  std::optional<PoseBox> region;
  /// The space the whole machine must fit in at every task pose (hexapod problems: legs with
  /// their shape, base and platform joints; models/geometry/installation_space.hpp); part of the
  /// reachability row.
  InstallationSpace installation_space;
  /// Fixed bodies the machine must keep out of at every task pose (base frame: its drawing's lines
  /// and joints, not the tool; models/geometry/sketch_envelope.hpp sketch_intrusion); part of the
  /// reachability row.
  std::vector<ObstacleBox> obstacles;
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

/// task_margin (m): the largest d in [0, d_max] such that every task pose moved outwards by d
/// along each base axis on which it lies off the centre of the poses' bounding box (the pose
/// keeps its orientation; a coordinate at the centre stays) is reachable (Machine::reachable);
/// bisected to d_max / 2^16. 0 when a task pose itself is unreachable; d_max when every pose
/// moved by d_max is reachable. `poses` are the task poses after the home_height lift.
double task_margin(const Machine& machine, const std::vector<Pose>& poses, double d_max);
/// The d_max of design studies: the largest extent of the task's positions, at least 0.1 m.
double task_margin_limit(const std::vector<Pose>& poses);

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

}  // namespace pkmopt
