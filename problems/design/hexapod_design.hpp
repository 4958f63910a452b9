// The hexapod design problem: a design vector -> a semi-regular Gough-Stewart hexapod -> metrics
// over a task -> [objectives | inequality constraints] for the pkmopt optimizers.
//
// Design parameters (internal units: m and rad; files give the separations in degrees):
//   base_radius r_b, platform_radius r_p (m), base_pair_separation alpha_b,
//   platform_pair_separation alpha_p (rad), min_length (m), stroke (m; max_length = min_length +
//   stroke), home_height h (m: the task region is lifted by h along base z).
// Each is fixed (lower == upper) or free within [lower, upper]; only free ones are variables.
// The rest of the machine (leg stiffness, joint limits, TCP, actuator error, characteristic
// length) comes from a fixed HexapodDesign template. Joints: docs/conventions.md (semi-regular).
//
// Task: N TCP poses (positions of a box or cylinder grid x orientations of a tilt cone x yaw
// range, sampled by sample_orientations of models/workspace), a constant wrench w at the TCP.
// Pose k: position p_k + (0, 0, h), angles of R_k.
//
// Metrics (user units and signs; see docs/conventions.md for the per-pose definitions):
//   stiffness_min       min_k stiffness_min(pose k)                    N/m
//   singularity_margin  min_k singularity_margin(pose k)               0..1
//   leg_force_max       max_k max_i |tau_i(pose k)| under w            N
//   tcp_error_max       max_k tcp_error_max(pose k)                    m
//   workspace_volume    workspace_volume(hexapod, task.workspace)     m^3 (constant orientation
//                       set of task.workspace; coarse resolution for speed)
//   conditioning_index  global conditioning index: the mean singularity margin over the inside
//                       grid nodes of the workspace (compute_workspace with maps, task.workspace
//                       orientations and resolution; each node's margin is the worst over
//                       the orientations)                              0..1
//   machine_size        pi r_b^2 max_length: the envelope cylinder of machine_envelope_volume
//                       (planar base joints)                           m^3
//   swept_volume        the convex hull of the base joints, the platform joints at every task
//                       pose and the solids (models/hexapod/swept_envelope.hpp)  m^3
//   footprint           the area of its projection on the base's x-y plane  m^2
//   task_singularity_free  singularity_free_share of the task region lifted by home_height
//                       (models/workspace/mode_certificate.hpp): 1 when it is proved free of
//                       parallel singularities with one working mode       0..1
//   actuator_cost       (spec.actuator_catalog set: the optimiser chooses the legs' actuator)
//                       the relative cost (actuator_costs: the catalog's costs, or the rank by
//                       force rating when it has none) of choose_actuator(catalog, {force =
//                       leg_force_max, stroke, peak_force = actuator_force_dynamic_max with a
//                       task a_max}), the cheapest entry that carries every leg over the task;
//                       when none does: twice the dearest entry's cost (a rank catalog:
//                       entries + 1), and actuator_overload > 0 says so   (relative)
//   actuator_overload   actuator_overload(catalog, that need): without a_max leg_force_max -
//                       actuator_force_capacity(catalog, stroke), the largest rating among
//                       entries at least as long as the stroke; <= 0 exactly when some entry
//                       carries the legs (the constraint "actuator_overload <= 0" is the catalog
//                       choice's feasibility)                                N
//   actuator_force_dynamic_max  (masses and a task a_max) max over the task of the forces with
//                       the TCP accelerating from rest with |a| <= a_max under the wrench and
//                       gravity (models/dynamics/acceleration_capability.hpp)         N
// An objective is minimised as f = metric, maximised as f = -metric. A constraint
// "metric <= b" gives g = metric - b <= 0, "metric >= b" gives g = b - metric <= 0.
// Task reachability (optional, default on), one row g_reach <= 0 with
//   g_reach = max over poses and legs of { min_length - q_i, q_i - max_length,
//             cos(base_limit) - s_i . a_axis, cos(platform_limit) + s_i . (R n_b) }
// (joint rows only for finite joint limits; lengths in m, cosines dimensionless).
//
// Formulations:
//   aggregate (derivative-free, for NSGA-II): rows as above, one per objective and constraint.
//   smooth (gradient solvers: Ipopt, NLopt, epsilon-constraint, NBI, hybrid): worst cases
//     become per-pose rows, every row scaled to O(1). Variables = free design parameters + one
//     epigraph variable per epigraph objective, in objective order:
//       minimize leg_force_max: t in kN (kEpigraphForceUnit), 0 <= t <= kEpigraphForceUpper;
//         objective row 1000 t (N); rows (+-tau_i(pose k) - 1000 t) / 1000 <= 0 (kN).
//       maximize stiffness_min: s in N/um (kEpigraphStiffnessUnit = 1e6 N/m),
//         0 <= s <= 6 k(min_length lower bound) (an upper bound of any stiffness_min);
//         objective row -1e6 s (N/m, the maximised metric's minimised sign); rows: with
//         M_k = I - 1e6 s C_tt(pose k) (C = K^-1, K = J^T diag(k) J), the 7 principal minors
//         of M_k (3 diagonal entries, 3 2x2 minors, det), each as -minor <= 0. Exact:
//         lambda_max(C_tt) <= 1/s_Nm <=> M_k is positive semidefinite <=> all principal
//         minors >= 0, and smooth where lambda_max is not (repeated top eigenvalues).
//     Constraints: leg_force_max <= b gives (+-tau_i(pose k) - b) / 1000 <= 0 (kN);
//     actuator_overload <= b (a fixed stroke only: the capacity F is then a constant) the
//     same rows with b + F;
//     stiffness_min >= b the 7 minor rows of I - b C_tt(pose k) per pose; machine_size <= / >= b
//     one row; reachability: the terms of g_reach, each its own row. Only these metrics are
//     smooth; other metrics are refused with a message. Gradients come from
//     hexapod_legs<ceres::Jet> and an LU solve of J^T in Jet arithmetic (forward-mode
//     autodiff over the 7 parameters and the epigraph variables). Every inequality row is
//     tightened by kSmoothRowMargin (1e-6 in its unit) so that solutions feasible to a solver's
//     tolerance are feasible in the aggregate metrics.
//
// Failures: a design the Hexapod constructor rejects, a singular task pose or any non-finite
// metric makes the evaluation fail: `DesignEvaluation::failure` says why, and every objective and
// constraint row of the fitness is kFailurePenalty (finite: the design is infeasible and
// dominated, never NaN).
//
// Metrics, objectives, constraints, the task and its sampling are shared with every design
// problem (problems/design/machine_design.hpp).
//
// Thread safety: basic. Every fitness call builds its own Hexapod and HexapodData, so
// batch_fitness evaluates designs in parallel (OpenMP) with one HexapodData per thread.
//
// Example:
//   HexapodDesignSpec spec;                       // defaults: the docs/conventions.md hexapod
//   spec.parameters[kBaseRadius] = {0.5, 0.7};    // free
//   spec.task = box_task({0, 0, 0.9}, {0.15, 0.15, 0.1}, {3, 3, 3}, deg_to_rad(20), 0);
//   spec.objectives = {{DesignMetric::stiffness_min, Sense::maximize},
//                      {DesignMetric::machine_size, Sense::minimize}};
//   HexapodDesignProblem problem(spec);
//   std::vector<double> f = problem.fitness({0.6});
#pragma once

#include <array>
#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "models/hexapod/hexapod.hpp"
#include "models/workspace/workspace.hpp"
#include "optimizer/problem.hpp"
#include "problems/design/actuator_catalog.hpp"
#include "problems/design/design_problem.hpp"
#include "problems/design/machine_design.hpp"

namespace pkmopt {

enum DesignParameterIndex : int {
  kBaseRadius = 0,
  kPlatformRadius,
  kBasePairSeparation,
  kPlatformPairSeparation,
  kMinLength,
  kStroke,
  kHomeHeight,
  kNumDesignParameters
};

/// The name of a design parameter in files ("base_radius", "base_pair_separation_deg", ...).
std::string_view design_parameter_name(int index);
/// True for the parameters given in degrees in files (the pair separations).
bool design_parameter_in_degrees(int index);

/// Everything that defines a hexapod design problem.
struct HexapodDesignSpec {
  std::string name = "hexapod-design";
  /// The fixed part of the machine (its joints and lengths are overwritten by the parameters).
  HexapodDesign machine_template;
  std::array<ParameterRange, kNumDesignParameters> parameters;
  DesignTask task;
  std::vector<DesignObjective> objectives;
  std::vector<DesignConstraint> constraints;
  bool require_reachable = true;
  DesignFormulation formulation = DesignFormulation::aggregate;
  /// The actuators to choose the legs from (actuator_cost, actuator_overload and the chosen
  /// entry of every evaluation); the stroke's upper bound must not exceed the longest entry.
  std::optional<ActuatorCatalog> actuator_catalog;
  /// The catalog prices the six legs as one group of alike drives (drive_cost = 6 x the entry's
  /// cost, drive_overload) instead of actuator_cost and actuator_overload.
  bool each_drive = false;

  /// The docs/conventions.md hexapod with every parameter fixed at its value.
  HexapodDesignSpec();
};

/// Upper bound (N) of the leg-force epigraph variable of the smooth formulation: finite so that
/// multi-start solvers can sample it; far above any actuator force.
inline constexpr double kEpigraphForceUpper = 1e8;
/// Unit of the leg-force epigraph variable and of the force rows (N per unit: kN).
inline constexpr double kEpigraphForceUnit = 1e3;
/// Unit of the stiffness epigraph variable (N/m per unit: N/um).
inline constexpr double kEpigraphStiffnessUnit = 1e6;
/// Every inequality row of the smooth formulation is g + kSmoothRowMargin <= 0 (rows in their
/// O(1) units: kN, m, cosines, dimensionless minors, m^3): solvers accept a constraint
/// violation of about 1e-8, and their solutions must pass the aggregate check g <= 0.
inline constexpr double kSmoothRowMargin = 1e-6;
/// Rows per task pose of a smooth stiffness_min objective or constraint (principal minors).
inline constexpr std::size_t kStiffnessRowsPerPose = 7;

/// Everything an evaluation measured, in user units and signs.
struct DesignEvaluation {
  std::array<double, kNumDesignParameters> parameters{};  ///< internal units (rad)
  std::array<double, kNumDesignMetrics> metrics{};        ///< by DesignMetric; only the needed ones
  bool reachable = false;                                 ///< every task pose reachable
  double reach_violation = 0.0;                           ///< g_reach (<= 0 when reachable)
  std::string failure;                                    ///< empty when the evaluation succeeded
  /// With an actuator catalog: the index of the chosen entry (the cheapest that carries the
  /// legs), -1 when none does or the design failed.
  int actuator = -1;
  /// each_drive: the legs as one group and the catalog's choice for it (measure() puts it in
  /// words, drive_choice_text).
  std::vector<DriveGroupNeed> drive_needs;
  DriveChoice drive_choice;
  bool ok() const { return failure.empty(); }
};

/// The machine of a parameter vector (internal units): the template with the parameters' joints
/// and leg lengths.
HexapodDesign hexapod_design_of(const HexapodDesign& machine_template,
                                const std::array<double, kNumDesignParameters>& parameters);

class HexapodDesignProblem final : public DesignProblem {
 public:
  /// Checks the spec; throws std::invalid_argument naming the field (empty task, no objective,
  /// lower > upper, a metric that has no smooth formulation in smooth mode...).
  explicit HexapodDesignProblem(HexapodDesignSpec spec);

  Bounds bounds() const override;
  std::size_t num_objectives() const override { return spec_.objectives.size(); }
  std::size_t num_inequality() const override { return num_inequality_; }
  std::vector<double> fitness(const std::vector<double>& x) const override;
  bool has_gradient() const override { return spec_.formulation == DesignFormulation::smooth; }
  /// Dense row-major Jacobian of the smooth fitness (smooth formulation only).
  std::vector<double> gradient(const std::vector<double>& x) const override;
  std::string name() const override { return spec_.name; }
  ThreadSafety thread_safety() const override { return ThreadSafety::basic; }

  const HexapodDesignSpec& spec() const { return spec_; }

  // DesignProblem (problems/design/design_problem.hpp).
  const DesignTask& task() const override { return spec_.task; }
  const std::vector<DesignObjective>& objectives() const override { return spec_.objectives; }
  const std::vector<DesignConstraint>& constraints() const override { return spec_.constraints; }
  bool require_reachable() const override { return spec_.require_reachable; }
  bool aggregate() const override { return spec_.formulation == DesignFormulation::aggregate; }
  /// Indices of the free parameters, in variable order.
  const std::vector<int>& free_parameters() const override { return free_; }
  std::vector<double> design_parameters(const std::vector<double>& x) const override;
  double home_height(const std::vector<double>& parameters) const override;
  DesignRecord measure(const std::vector<double>& x) const override;
  const ActuatorCatalog* actuator_catalog() const override {
    return spec_.actuator_catalog ? &*spec_.actuator_catalog : nullptr;
  }
  bool prices_each_drive() const override { return spec_.each_drive; }

  /// Number of epigraph variables (smooth formulation), after the free parameters (one per
  /// minimize leg_force_max / maximize stiffness_min objective, in objective order).
  std::size_t num_epigraph() const { return epigraph_objectives_.size(); }
  /// All parameters (internal units) for a variable vector.
  std::array<double, kNumDesignParameters> parameters_of(const std::vector<double>& x) const;
  /// The machine of a parameter vector (internal units).
  HexapodDesign design_of(const std::array<double, kNumDesignParameters>& parameters) const;
  /// Measures a design over the task (every metric the objectives and constraints need).
  DesignEvaluation evaluate(const std::vector<double>& x) const;
  /// Objective and constraint rows of the aggregate formulation from an evaluation.
  std::vector<double> aggregate_fitness(const DesignEvaluation& evaluation) const;

 private:
  void check_machine_for_goals(const std::string& where);
  void set_up_actuator_catalog(const std::string& where);
  void set_up_smooth_formulation(const std::string& where);
  std::size_t smooth_constraint_rows(const std::string& where, std::size_t poses) const;
  template <typename T>
  void smooth_rows(const std::array<T, kNumDesignParameters>& p, const std::vector<T>& epigraph,
                   std::vector<T>& rows) const;
  template <typename T>
  T reach_rows(const std::array<T, kNumDesignParameters>& p, std::vector<T>* rows) const;
  // The parts of evaluate: the obstacles in the reach terms, the pass over the lifted task poses
  // (worst cases, the accelerated force), the catalog's choice for the legs, and the region's
  // metrics (task_singularity_free, swept_volume, footprint, task_margin).
  void keep_out_of_obstacles(const Hexapod& hexapod, double h, DesignEvaluation& ev) const;
  void measure_task_poses(const Hexapod& hexapod, double h, DesignEvaluation& ev) const;
  void price_legs(double stroke, DesignEvaluation& ev) const;
  void measure_task_region(const Hexapod& hexapod, double h, DesignEvaluation& ev) const;

  HexapodDesignSpec spec_;
  std::vector<int> free_;
  std::vector<std::size_t> epigraph_objectives_;  // objective indices with an epigraph variable
  std::size_t num_inequality_ = 0;
  std::array<bool, kNumDesignMetrics> needed_{};
  double stiffness_upper_ = 0.0;  // bound of the stiffness epigraph variable (N/um)
  CatalogPricing pricing_;        // the catalog's entries' costs, and a design's that none carries
};

}  // namespace pkmopt
