// Serial 5-axis machines as machines: a coordinate-code chain (models/serial/serial_chain.hpp) of
// two rotary and three linear feed axes and optionally a spindle, with each feed axis's range,
// stiffness and positioning error (models/serial/serial_axis.hpp).
//
// Frames. The chain runs from the workpiece to the tool (r_0 = T(q) r_tool), so frame 0 is the
// workpiece's (the table's at zero axis values): a pose is the tool's pose seen from the
// workpiece, as a hexapod's TCP pose is seen from its base, and the same task file serves both.
//
// Pose and the free rotation. A 5-axis machine sets the tool point and the tool axis, five
// coordinates; the rotation of the tool about its own axis is the spindle's. A pose (p, R) asks
// for the tool point p and the tool axis a_0 = R e_z; how R turns about a_0 (the pose's rz when
// rx = ry = 0) is not commanded and does not change q or any metric. Forward kinematics returns
// the orientation the chain gives: R_chain(q) R_a, R_a the smallest rotation taking e_z to the
// tool axis a_tool of the last frame (the identity for the usual a_tool = e_z).
//
// Inverse kinematics: five_axis_inverse_kinematics (models/serial/five_axis_ik.hpp), every
// branch in closed form; each rotary value is moved by whole turns to the one nearest the middle
// of its range. The branch used: of those within every range, the one whose second rotary axis
// (in chain order) is nearest the middle of its range, on a tie (1e-9 rad) the larger value (the
// tilt of a table-table machine keeps its side along a path). Without a branch in range the pose
// is unreachable and the metrics are those of the branch least beyond its ranges. At a pose
// where the first rotary axis does not move the tool axis (A = 0 on the 641236 table: the tool
// axis along C) that axis is free and takes the middle of its range.
//
// Metrics (docs/conventions.md; W = [f; m] at the tool point, base axes = workpiece frame):
//   J_f       the tool's twist per feed-axis rate (6 x 5, SerialChain::twist_jacobian);
//   M         [J_f, s], s = [0; a_0] the spin about the tool axis: the twist of the tool for
//             [q_dot; spin]; the inverse Jacobian of Machine::twist_jacobian is J = the feed rows
//             of M^-1 (q_dot = J xi, whatever the twist's spin about a_0).
//   det_j     det M (sign changes where a path crosses a singular pose);
//   singularity_margin  1 / cond(M_h), M_h = diag(I, L I) M diag(c), c_i = 1 for a linear axis
//             and 1/L for a rotary one and the spin (L = characteristic_length): the rotary
//             columns become [omega x d / L; omega]. singular when 1 / cond < kSingularRcond.
//   tau       the load of each drive, tau = J_f^T W: a linear axis carries the force along it
//             (N), a rotary one the moment about it (N*m), positive when the wrench pushes the axis
//             towards +q; the moment about the tool axis goes into the spindle. Finite at singular
//             poses: a serial singularity loses a motion, not the statics.
//   compliance  C = J_f D J_f^T (6 x 6), D = diag(1 / k_i) (0 for a rigid axis): the drives in
//             series. stiffness_min = 1 / lambda_max(C_tt); +inf when every axis is rigid.
//   stiffness_min_loaded  with the change of the drive loads as the axes yield: tau(q + dq) =
//             J_f(q + dq)^T W gives K_g = d(J_f^T W)/dq (in closed form: an axis k before axis
//             j turns column j with it, d col_j = [u_k x v_j; u_k x omega_j] for a rotary k; an
//             axis at or after j moves the tool point only, dv_j = omega_j x v_k for a rotary j),
//             the axes yield by dq = D (K_g dq + J_f^T dW), so C_T = J_f (I - D K_g)^-1 D J_f^T
//             (the conservative congruence transformation of Chen & Kao, IJRR 19(9), 2000, in
//             compliance form). 0 (unstable) when K - K_g on the elastic axes is not positive
//             definite; +inf when every axis is rigid.
//   tcp_error_max  max over |dq_i| <= e_i of |J_f,t dq| (the translational rows), exact (a vertex
//             of the box).
//   Natural frequencies: none (no mass model).
// envelope_volume: the box of the three linear travels grown by the tool's reach |r_tool| (from
// the last frame's origin to the tool point) on every side, prod_i (max_i - min_i + 2 |r_tool|)
// over the linear feed axes: the space the tool sweeps, a lower bound of the machine's frame.
//
// Units: m, rad, N, N*m inside; the machine file gives rotary values in degrees.
//
// Example:
//   pkmopt::SerialDesign design;
//   design.chain = pkmopt::SerialChain::from_code("641236");
//   design.spindle = 5;                                   // S, the sixth variable
//   design.axes = {...};                                  // C, A, X, Y, Z
//   design.tool_point = {0, 0, 0.1};
//   pkmopt::SerialMachine machine(design);
//   auto data = machine.make_data();
//   pkmopt::PoseMetrics m;
//   machine.analyze(*data, pose, wrench, m);              // m.q = [C, A, X, Y, Z]
#pragma once

#include <Eigen/Core>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "models/core/machine.hpp"
#include "models/core/pose.hpp"
#include "models/serial/five_axis_ik.hpp"
#include "models/serial/serial_axis.hpp"
#include "models/serial/serial_chain.hpp"
#include "models/serial/serial_statics.hpp"

namespace pkmopt {

/// Everything that defines a serial 5-axis machine. Validated by the SerialMachine constructor.
struct SerialDesign {
  SerialChain chain;  ///< two rotary and three linear feed axes, optionally a spindle (m, rad)
  int spindle = -1;   ///< the spindle's index among the chain's variables, -1 for none
  std::vector<SerialAxis> axes;  ///< one per feed axis (the variables without the spindle)
  Eigen::Vector3d tool_point = Eigen::Vector3d::Zero();  ///< r_tool, last frame (m)
  Eigen::Vector3d tool_axis = Eigen::Vector3d::UnitZ();  ///< a_tool, last frame (unit)
  double characteristic_length = 0.1;                    ///< L of singularity_margin (m)
};

/// Per-thread data of a serial machine (its analysis keeps no scratch state of its own).
class SerialData : public MachineData {};

class SerialMachine final : public Machine {
 public:
  /// Validates the design; throws std::invalid_argument naming the offending field.
  explicit SerialMachine(SerialDesign design);

  const SerialDesign& design() const { return design_; }

  std::string_view model() const override { return "serial"; }
  int num_actuators() const override { return static_cast<int>(feed_.size()); }
  bool revolute_actuators() const override { return false; }
  bool revolute_actuator(int i) const override;
  std::optional<double> actuator_stroke(int i) const override {
    if (i < 0 || i >= num_actuators()) return std::nullopt;
    const SerialAxis& a = design_.axes[static_cast<std::size_t>(i)];
    return a.max - a.min;
  }
  /// Every axis is a drive of its own.
  int drive_group(int i) const override { return i; }
  std::unique_ptr<MachineData> make_data() const override;
  void analyze(MachineData& data, const Pose& pose, const Wrench& wrench,
               PoseMetrics& out) const override;
  bool reachable(MachineData& data, const Pose& pose) const override;
  /// Exact: the chain's transform (converged, no iterations); q must be finite.
  FkResult forward_kinematics(const Eigen::VectorXd& q, const std::optional<Pose>& guess,
                              const FkOptions& options = {}) const override;
  /// A box holding the tool point for every axis value within its range (interval bounds of the
  /// chain's elements from the tool back to the workpiece), whatever the orientation.
  std::optional<Eigen::AlignedBox3d> workspace_search_box(
      const std::vector<Eigen::Matrix3d>& orientations) const override;
  std::string actuator_coordinates_requirement(const Eigen::VectorXd& q) const override;
  std::optional<double> envelope_volume() const override;
  /// The feed rows of M^-1 (see the header comment); false at a singular pose or when the tool
  /// axis cannot be reached.
  bool twist_jacobian(MachineData& data, const Pose& pose, Eigen::MatrixXd& J) const override;
  /// The largest excess of an axis over its range of the branch used; nullopt when the tool axis
  /// cannot be reached.
  std::optional<double> reach_excess(const Pose& pose) const override;
  /// The chain drawn from the workpiece to the tool: one guide line per element that moves the
  /// origin, the tool from its point back along its axis.
  bool sketch(MachineData& data, const Pose& pose, MachineSketch& out) const override;

  /// The branch used at a pose (see the header comment): the feed values (size
  /// num_actuators()) and whether every one is in range; nullopt when no branch reaches the tool
  /// axis.
  struct Branch {
    Eigen::VectorXd q;  ///< feed axes (m, rad)
    bool in_range = false;
    bool singular = false;  ///< the first rotary axis was free
    double excess = 0.0;    ///< largest excess over a range (m or rad), 0 in range
  };
  std::optional<Branch> inverse_kinematics(const Pose& pose) const;

  /// The chain's variables (spindle 0) for feed values q.
  Eigen::VectorXd full_coordinates(const Eigen::VectorXd& q) const;
  /// The tool axis a_0 and tool point r_0 of feed values q.
  Eigen::Vector3d tool_axis_at(const Eigen::VectorXd& q) const;
  /// J_f at feed values q (6 x num_actuators()).
  FeedJacobian feed_jacobian(const Eigen::VectorXd& q) const;
  /// K_g = d(J_f^T W)/dq at the configuration of J_f (see the header comment).
  Eigen::MatrixXd geometric_stiffness(const FeedJacobian& Jf, const Wrench& wrench) const;

 private:
  /// det_j, singularity_margin and singular from J_f and the tool axis a0 (see the header).
  void conditioning(const FeedJacobian& Jf, const Eigen::Vector3d& a0, PoseMetrics& out) const;
  /// stiffness_min_loaded and matrices.loaded_compliance_tt under `wrench` (see the header).
  void loaded_compliance(const FeedJacobian& Jf, const Wrench& wrench, PoseMetrics& out,
                         PoseCompliance& matrices) const;

  SerialDesign design_;
  std::vector<int> feed_;     // the chain variable index of each feed axis
  std::vector<bool> rotary_;  // per feed axis
  int second_rotary_ = -1;    // feed index of the second rotary axis
  int first_rotary_ = -1;     // feed index of the first rotary axis
  Eigen::Matrix3d tool_align_ = Eigen::Matrix3d::Identity();  // R_a: e_z -> a_tool
};

}  // namespace pkmopt
