// Hybrid machines: serial translational axes carrying a parallel module (a long X axis carrying
// a hexapod like Hexamech-1, structure class P1З6; a gantry X/Y carrying a 3-PRS head like the
// Ecospeed / Sprint Z3, P2З3).
//
// Model. The serial carrier is a coordinate-code chain (models/serial/serial_chain.hpp) whose
// VARIABLE elements are translations (motions 1, 2, 3); constant elements may be translations or
// rotations (a mount offset or tilt). Its transform at axis values q_s is therefore
//     T_chain(q_s) = [R0, t0 + A q_s; 0, 1]
// with R0 the constant mount rotation, t0 the constant offset and A (3 x n_s) the world
// directions of the axes (unit, constant because no variable element rotates). The module's base
// frame is T_chain(q_s): a TCP pose (p, R) of the machine (world) is the module-local pose
//     p_local = R0^T (p - t0 - A q_s),   R_local = R0^T R.
// Variable rotary axes are refused (their directions would depend on q_s); describe accepts them.
//
// Redundancy rule ("follow"): the serial axes take the coarse travel so that the module's TCP
// stays as close as possible to the module's reference point h (module-local, `home`):
//     q_s = clamp(A^+ (p - t0 - R0 h), [min_i, max_i])   componentwise,
// A^+ = (A^T A)^-1 A^T (A must have full column rank). A long axis carrying a hexapod thus does
// the macro motion and the hexapod the micro motion about h. Modules with parasitic motion
// (planar-leg 3-PRS heads, whose x, y follow from z, rx, ry) cannot choose their local x, y: the
// serial axes then compensate the module's actual position a(p_local) instead of h,
//     q_s = clamp(A^+ (p - t0 - R0 a)),   solved by fixed-point iteration,
// and a pose is attained only when t0 + A q_s + R0 a = p (within 1e-9 m); the module's local rz
// is its parasitic one (as for the bare module, the requested rz is not honoured).
//
// Actuator coordinates q = [q_s; q_p] (n_s + n_p): the serial axis positions (m) first, then the
// module's (m). Modules with revolute actuators (a delta) are refused: the CLI scales every q of
// a machine by one unit (m, or rad shown as degrees), so q would mix units.
//
// Metrics at a pose under a wrench w = [f; m] at the TCP (base axes):
//   reachable   module reachable at the local pose (the serial axes are clamped to their range,
//               so they are always in range) and, with a parasitic module, the pose attained.
//   (The serial axes' statics, compliance and error columns are those of serial machines,
//   models/serial/serial_statics.hpp, with the axes' twists J_f = [A; 0].)
//   tau         serial axis i: tau_s,i = a_i . f (N; the statics of a serial chain, tau_s = A^T f:
//               each prismatic drive carries the force component along its axis, moments go into
//               the guides); module: the module's tau under the local wrench [R0^T f; R0^T m]
//               (the wrench acts at the TCP, so no moment transfer).
//   stiffness_min  1 / lambda_max(C_tt), the serial and parallel compliances in series:
//               C_tt = R0 C_tt,module R0^T + sum_i a_i a_i^T / k_i (k_i the axis stiffness, N/m,
//               absent = rigid).
//   compliance  the module's 6x6 compliance turned by R0 plus sum_i [a_i a_i^T / k_i, 0; 0, 0]
//               (serial axes in series); tcp_deflection etc. from it (models/core/machine.hpp).
//   stiffness_min_loaded  from R0 C_T,tt,module R0^T + sum_i a_i a_i^T / k_i: the serial axes'
//               directions are fixed, so the load adds no geometric term of theirs; 0 when the
//               module's loaded stiffness is 0 (unstable).
//   singularity_margin, det_j, singular: the module's at the local pose.
//   tcp_error_max  max over |ds_i| <= e_i (axis errors, m) and |dq_j| <= module actuator error of
//               |sum_i a_i ds_i + R0 P dq| (P the module's TCP position error map), exact: the
//               maximum of a convex function over a box is at a vertex; all 2^(n-1) sign
//               vectors are enumerated (n <= 9: at most 3 independent axes and 6 module drives).
//   At a singular module pose: singularity_margin = stiffness_min = 0, every tau_i and
//   tcp_error_max = +inf (docs/conventions.md). Never NaN.
//
// Dynamics (a module with masses; models/hybrid/hybrid_dynamics.cpp, docs/dynamics.md). Coordinates
// z = [u; xi]: the axis displacements u (carriage i moves with sum_{j <= i} a_j u_dot_j: an axis
// carries the ones after it in the chain and the module) and the platform's absolute twist xi.
// The module's base translates with d = A u_dot; its bodies' kinetic energy is
// 1/2 [d; xi]^T Q [d; xi] (Machine::carried_dynamics), so the mass matrix is
//   M_z = [A^T Q_dd A + M_carriages, A^T Q_dxi; Q_dxi^T A, Q_xixi].
// The axis drives (compliance 1 / k_i) and the module (compliance C_m, world axes) in series:
// with D = diag(1 / k_i) and B = [A; 0] (6 x n_s), the compliance on z is
//   C_z = [D, D B^T; B D, B D B^T + C_m]      (K_z = L^T diag(k, K_m) L, L = [I, 0; -B, I]).
// Natural frequencies: the positive eigenvalues mu = 1 / omega^2 of Lc^T M_z Lc with
// C_z = Lc Lc^T (its eigen decomposition; rigid axes and the module's rigid directions give
// mu = 0, a massless direction too), f = 1 / (2 pi sqrt(mu)) ascending: natural_frequency_count
// = the module's count plus one per elastic axis (k_i > 0), padded with +inf where a direction
// carries no mass.
// Inverse dynamics: with the follow rule, u_dot = D_free A^+ v and u_ddot = D_free A^+ a (axes
// clamped at a limit stand still); the module moves relative to its base with
// [v - A u_dot; omega], [a - A u_ddot; alpha] under the effective gravity g - A u_ddot (the base
// translates without turning), which gives its actuator forces and the net force F_m of gravity
// and inertia on its bodies; axis i then carries
//   tau_s,i = a_i . (f + F_m + sum_{j >= i} m_j (g - a_carriage,j)),
// f the tool's external force (the static tau_s = A^T f with no masses). Modules with parasitic
// motion (planar-leg heads) take no masses.
// Forward kinematics: T_chain(q_s) composed with the module FK of q_p (the world guess is taken
// to the local frame at q_s). Twist Jacobian: q_s_dot = A^+ v for an axis strictly inside its
// range (0 for an axis clamped at a limit: the follow rule holds it there), module rows from the
// module's twist Jacobian on the local twist [R0^T (v - A q_s_dot); R0^T omega]. Parasitic
// modules: the serial and module DOF rates solve [A, R0 T_v; 0, R0 T_w] [q_s_dot; eta] = xi in
// the least-squares sense (T the module's 6 x 3 DOF-to-twist map): exact along the twists the
// machine can make; a twist with another rz rate than the head's parasitic one is projected.
// Workspace search box: the module's box for the local orientations R0^T R, moved by R0, t0 and
// every vertex of the serial range box (the bounding box of the transformed corners).
// envelope_volume: the module's envelope swept over the axes' travel, with the module's envelope
// taken as the cube of its volume V: prod_k (V^(1/3) + L_k) over the world axes k, L_k =
// sum_i (max_i - min_i) |A_ki| (the travel box's extent along k); nullopt when the module has
// no envelope.
//
// Units: m, rad, N, N/m inside the code.
//
// Example:
//   pkmopt::HybridDesign design;
//   design.chain = pkmopt::SerialChain::from_code("1");      // one X axis
//   design.axes = {{-1.0, 1.0, 2.0e8, 5e-6}};                  // range (m), stiffness, error
//   design.module = std::make_shared<pkmopt::Hexapod>(hexapod_design);
//   design.home = {0.0, 0.0, 0.9};                              // module-local reference point
//   pkmopt::HybridMachine machine(design);
//   auto data = machine.make_data();
//   pkmopt::PoseMetrics m;
//   machine.analyze(*data, pkmopt::Pose{{0.7, 0.0, 0.9}, {0, 0, 0}}, pkmopt::Wrench::Zero(), m);
//   // m.q = [0.7 (X), six leg lengths of the hexapod at its home]
#pragma once

#include <Eigen/Core>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "models/core/capabilities.hpp"
#include "models/core/machine.hpp"
#include "models/core/pose.hpp"
#include "models/serial/serial_axis.hpp"
#include "models/serial/serial_chain.hpp"
#include "models/serial/serial_statics.hpp"

namespace pkmopt {

/// One serial axis of a hybrid machine (a translation: m, N/m).
using HybridAxis = SerialAxis;

/// Everything that defines a hybrid machine. Validated by the HybridMachine constructor.
struct HybridDesign {
  SerialChain chain;                      ///< variable elements: translations only (m, rad)
  std::vector<HybridAxis> axes;           ///< one per variable element, in chain order
  std::shared_ptr<const Machine> module;  ///< the parallel module (not itself hybrid)
  Eigen::Vector3d home = Eigen::Vector3d::Zero();  ///< h, module-local reference point (m)
  /// World frame (m/s^2), for the dynamics with a module that has masses (the module file's own
  /// gravity is not used).
  Eigen::Vector3d gravity{0.0, 0.0, -9.81};
};

/// Per-thread scratch space of a hybrid machine: the module's data and last results.
class HybridData : public MachineData {
 public:
  std::unique_ptr<MachineData> module;
  PoseMetrics module_metrics;
  Eigen::Matrix3d module_compliance = Eigen::Matrix3d::Zero();
  Eigen::Matrix<double, 3, Eigen::Dynamic> module_error_map;
  Eigen::MatrixXd module_jacobian;
  bool want_mode_shapes = false;  ///< analyze also fills mode_shapes (Machine::mode_shapes)
  Eigen::MatrixXd mode_shapes;    ///< PoseModes::shapes of the last analyze with want_mode_shapes
};

/// The split of a world TCP pose between the serial axes and the module (the follow rule).
struct HybridSplit {
  Eigen::VectorXd serial;     ///< q_s, clamped to the ranges (m)
  Eigen::VectorXd unclamped;  ///< A^+ (p - t0 - R0 h) before clamping (m)
  Pose local;                 ///< the module-local TCP pose
  bool attained = true;       ///< parasitic modules: the world position is reached
};

/// A hybrid machine. Immutable; share it between threads, give each a HybridData.
class HybridMachine final : public Machine, public Dynamics {
 public:
  /// Validates the design; throws std::invalid_argument naming the offending field.
  explicit HybridMachine(HybridDesign design);

  const HybridDesign& design() const { return design_; }
  const Machine& module() const { return *design_.module; }
  int num_serial() const { return num_serial_; }
  const Eigen::Matrix3d& mount_rotation() const { return R0_; }  ///< R0
  const Eigen::Vector3d& mount_offset() const { return t0_; }    ///< t0 (m)
  const Eigen::Matrix<double, 3, Eigen::Dynamic>& axis_directions() const { return A_; }  ///< A

  std::string_view model() const override { return "hybrid"; }
  int num_actuators() const override { return num_serial_ + design_.module->num_actuators(); }
  bool revolute_actuators() const override { return false; }  ///< modules are prismatic
  /// The serial axes' travels, then the module's strokes.
  std::optional<double> actuator_stroke(int i) const override {
    if (i < 0 || i >= num_actuators()) return std::nullopt;
    if (i < num_serial_) {
      const HybridAxis& a = design_.axes[static_cast<std::size_t>(i)];
      return a.max - a.min;
    }
    return design_.module->actuator_stroke(i - num_serial_);
  }
  /// Each serial axis its own group; the module's drives grouped as the module groups them.
  int drive_group(int i) const override {
    if (i < num_serial_) return i;
    return num_serial_ + design_.module->drive_group(i - num_serial_);
  }
  /// The module's interference check; clearance_pair numbers its legs as their actuators.
  bool checks_leg_interference() const override {
    return design_.module->checks_leg_interference();
  }
  std::unique_ptr<MachineData> make_data() const override;
  void analyze(MachineData& data, const Pose& pose, const Wrench& wrench,
               PoseMetrics& out) const override;
  bool reachable(MachineData& data, const Pose& pose) const override;
  FkResult forward_kinematics(const Eigen::VectorXd& q, const std::optional<Pose>& guess,
                              const FkOptions& options = {}) const override;
  std::optional<Eigen::AlignedBox3d> workspace_search_box(
      const std::vector<Eigen::Matrix3d>& orientations) const override;
  std::string actuator_coordinates_requirement(const Eigen::VectorXd& q) const override;
  bool twist_jacobian(MachineData& data, const Pose& pose, Eigen::MatrixXd& J) const override;
  std::optional<double> envelope_volume() const override;
  /// The module's sketch at the split's local pose carried by the axes, each axis's travel a
  /// guide line from the mount.
  bool sketch(MachineData& data, const Pose& pose, MachineSketch& out) const override;
  /// The module's masses (with the axes' in design().axes); null when the module has none.
  /// Present when the module has a mass model.
  Capability<Dynamics> dynamics() const override {
    if (parasitic_module_ != nullptr)
      return Capability<Dynamics>::missing(
          "its parallel module has parasitic motion (planar legs), whose dynamics on moving axes "
          "are not modelled");
    if (module_dynamics_ == nullptr)
      return Capability<Dynamics>::missing("its parallel module has no mass model (" +
                                           design_.module->dynamics().reason() + ")");
    return this;
  }
  const MassModel& mass_model() const override { return module_dynamics_->mass_model(); }
  /// The module's moving mass and every axis's carriage (HybridAxis::mass).
  double moving_mass() const override;
  int natural_frequency_count() const override;
  bool mode_shapes(MachineData& data, const Pose& pose, PoseModes& out) const override;
  int mode_axis_count() const override { return num_serial_; }
  /// See the header comment (Dynamics).
  bool inverse_dynamics(MachineData& data, const Pose& pose, const Vector6d& xi,
                        const Vector6d& xi_dot, const Wrench& wrench,
                        PoseMetrics& out) const override;

  /// The follow rule at a world pose (see the header comment).
  HybridSplit split(const Pose& pose) const;
  /// The world pose of a module-local pose with the serial axes at q_s.
  Pose world_pose(const Eigen::VectorXd& q_serial, const Pose& local) const;

 private:
  /// With masses: the natural frequencies at the split `s` from the module compliance (world
  /// axes) of the last analyze, and the mode shapes into d.mode_shapes when d.want_mode_shapes
  /// (models/hybrid/hybrid_dynamics.cpp).
  void compute_natural_frequencies(HybridData& d, const HybridSplit& s, const Matrix6d& C_module,
                                   PoseMetrics& out) const;
  /// 1 for the axes strictly inside their range at the split (they follow), 0 for clamped ones.
  Eigen::VectorXd free_axes(const HybridSplit& s) const;

  HybridDesign design_;
  int num_serial_ = 0;
  Eigen::Matrix3d R0_ = Eigen::Matrix3d::Identity();
  Eigen::Vector3d t0_ = Eigen::Vector3d::Zero();
  Eigen::Matrix<double, 3, Eigen::Dynamic> A_;
  Eigen::Matrix<double, Eigen::Dynamic, 3> A_pinv_;
  FeedJacobian Jf_;  // [A; 0]: the axes' twists, for the statics shared with serial machines
  const ParasiticMotion* parasitic_module_ = nullptr;  // planar-leg module, else null
  const Dynamics* module_dynamics_ = nullptr;          // module with masses, else null
  const TranslationalMaps* module_maps_ = nullptr;     // the module's maps, null without
};

}  // namespace pkmopt
