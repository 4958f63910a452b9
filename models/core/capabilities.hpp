// The optional capabilities of a machine: what only some models have, asked for through the
// Machine's queries (models/core/machine.hpp) instead of casts to a model's type.
//
//   batch_analysis()     BatchAnalysis      many poses at once (the hexapod's SIMD kernel)
//   parasitic_motion()   ParasiticMotion    platforms whose other coordinates follow (3-PRS)
//   dynamics()           Dynamics           mass model, natural frequencies and modes, TCP mass
//                                           matrix, gravity and inertia wrench, inverse dynamics
//                                           (docs/dynamics.md); missing with a reason
//   translational_maps() TranslationalMaps  the TCP maps a hybrid machine needs of its module
//   all_forward_kinematics_solver()  AllForwardKinematics  every real forward-kinematics
//                                           solution (assembly mode) for given actuator values
//   jacobian_enclosure() JacobianEnclosure  an interval matrix holding the inverse Jacobian over
//                                           a box of poses (the proof that a region is free of
//                                           parallel singularities)
//
// A model offers a capability by implementing its interface and returning itself from the
// query:
//
//   class MyMachine : public Machine, public Dynamics { ...
//     Capability<Dynamics> dynamics() const override {
//       if (!masses_.present)
//         return Capability<Dynamics>::missing("the machine file has no 'masses'");
//       return this;
//     }
//   };
//
// and a caller asks for it:
//
//   const Capability<Dynamics> dynamics = machine.dynamics();
//   if (!dynamics) throw InputError("--mode-shapes needs a mass model: " + dynamics.reason());
//   dynamics->mode_shapes(data, pose, modes);
#pragma once

#include <Eigen/Core>
#include <array>
#include <cmath>
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "models/core/interval.hpp"
#include "models/core/machine.hpp"
#include "models/core/pose.hpp"
#include "models/core/pose_box.hpp"

namespace pkmopt {

struct MassModel;  // models/dynamics/mass_model.hpp

/// A capability (Machine::batch_analysis): a kernel that analyzes many poses at once, faster
/// than analyze pose by pose (the hexapod's SIMD path, models/hexapod/hexapod_batch.hpp). It needs
/// no MachineData and gives, for every pose, what analyze gives (compliance metrics included).
class BatchAnalysis {
 public:
  virtual ~BatchAnalysis() = default;
  /// Analyzes poses[0..count) under `wrench` into metrics[0..count) and, when `compliance` is
  /// given, the compliance matrices into compliance[0..count).
  virtual void analyze_batch(const Pose* poses, std::size_t count, const Wrench& wrench,
                             PoseMetrics* metrics, PoseCompliance* compliance) const = 0;
};

/// A capability (Machine::parasitic_motion): a platform with fewer than six degrees of freedom
/// whose remaining pose coordinates follow from the commanded ones (the parasitic x, y and rz of
/// a 3-PRS tripod, models/leg_chain/leg_chain.hpp). Machines that carry it (a hybrid machine's
/// axes) must move with the actual pose.
class ParasiticMotion {
 public:
  virtual ~ParasiticMotion() = default;
  /// The pose the platform takes when commanded to `pose`; nullopt when it cannot assemble.
  virtual std::optional<Pose> actual_pose(const Pose& pose) const = 0;
  /// T (6 x DOF): the TCP twist [v; omega] per rate of the platform's own coordinates, at the
  /// pose of the last analyze or twist_jacobian with `data` (made by this machine).
  virtual Eigen::MatrixXd twist_basis(const MachineData& data) const = 0;
};

/// The natural modes of one pose (Dynamics::mode_shapes).
struct PoseModes {
  Eigen::VectorXd frequencies;  ///< Hz, ascending: PoseMetrics::natural_frequencies
  /// Column k is mode k: the displacements of the serial axes of a hybrid machine (m, one row per
  /// axis, Dynamics::mode_axis_count), then the TCP twist [dp (m); dtheta (rad)] in base axes.
  /// Mass-normalised, x^T M x = 1 with M the mass matrix over the same coordinates (kg, kg*m^2);
  /// the sign makes the largest of the machine's DOF components positive.
  Eigen::MatrixXd shapes;
};

/// A capability (Machine::dynamics): the dynamics of a machine with a mass model
/// (docs/dynamics.md, models/dynamics/machine_dynamics.hpp).
class Dynamics {
 public:
  virtual ~Dynamics() = default;

  /// The machine's platform and leg masses (models/dynamics/mass_model.hpp).
  virtual const MassModel& mass_model() const = 0;
  /// The mass the drives move (kg): the platform and every leg's moving bodies
  /// (models/dynamics/leg_dynamics.hpp, moving_mass); a hybrid machine's serial carriages too.
  virtual double moving_mass() const = 0;
  /// How many natural frequencies analyze gives (the platform's DOF, and a hybrid machine's
  /// elastic axes).
  virtual int natural_frequency_count() const = 0;
  /// The natural frequencies and mode shapes at a pose (PoseModes; the frequencies are those
  /// of analyze). Returns false (out untouched) when the pose is unreachable or singular.
  virtual bool mode_shapes(MachineData& data, const Pose& pose, PoseModes& out) const = 0;
  /// How many serial-axis rows lead PoseModes::shapes (a hybrid machine's axes; else 0).
  virtual int mode_axis_count() const { return 0; }

  /// The TCP mass matrix M at a pose (6x6, base axes; kinetic energy 1/2 xi^T M xi of the
  /// platform and every leg body, models/dynamics/machine_dynamics.hpp). Returns false (M
  /// untouched) when a leg cannot close at the pose or the machine has no TCP mass matrix (a
  /// hybrid machine's is over its axes too).
  virtual bool mass_matrix(MachineData& /*data*/, const Pose& /*pose*/, Matrix6d& /*M*/) const {
    return false;
  }
  /// The wrench at the TCP equivalent, by virtual power, to gravity and to the inertia of the
  /// platform and every leg body when the TCP moves with the twist xi = [v; omega] and its rate
  /// xi_dot = [a; alpha] (m/s, rad/s, m/s^2, rad/s^2; base axes;
  /// models/dynamics/machine_dynamics.hpp). The actuators then carry the forces analyze gives for
  /// the wrench w + w_dyn (w the external wrench on the tool). Returns false (w_dyn untouched)
  /// when a leg cannot close at the pose or the machine has no such wrench (a hybrid machine).
  virtual bool dynamic_wrench(MachineData& /*data*/, const Pose& /*pose*/, const Vector6d& /*xi*/,
                              const Vector6d& /*xi_dot*/, Wrench& /*w_dyn*/) const {
    return false;
  }
  /// Inverse dynamics: the actuator forces (out.tau; the other metrics as analyze gives them
  /// under the wrench) that carry the external wrench on the tool, gravity and the inertia of
  /// every moving body when the TCP moves with the twist xi and its rate xi_dot. For a parallel
  /// machine the static solve under wrench + dynamic_wrench (static_inverse_dynamics below);
  /// machines whose actuators also move bodies that the TCP wrench does not see (serial axes)
  /// solve their own. Returns false when a leg cannot close (out unspecified).
  virtual bool inverse_dynamics(MachineData& data, const Pose& pose, const Vector6d& xi,
                                const Vector6d& xi_dot, const Wrench& wrench,
                                PoseMetrics& out) const = 0;
  /// For a machine carried on a translating base (the module of a hybrid machine): at `pose`
  /// relative to its base, moving with the relative twist xi and rate xi_dot under the effective
  /// gravity `gravity` (g minus the base's acceleration, base axes), the TCP wrench of gravity
  /// and inertia (as dynamic_wrench), the net force of gravity and inertia on all its bodies
  /// (models/dynamics/machine_dynamics.hpp, net_dynamic_force) and, when `kinetic` is given, the
  /// 9x9 kinetic-energy matrix over [base velocity; absolute twist] (carried_mass_matrix). Returns
  /// false when a leg cannot close or the machine cannot be carried.
  virtual bool carried_dynamics(MachineData& /*data*/, const Pose& /*pose*/, const Vector6d& /*xi*/,
                                const Vector6d& /*xi_dot*/, const Eigen::Vector3d& /*gravity*/,
                                Wrench& /*w_dyn*/, Eigen::Vector3d& /*net_force*/,
                                Eigen::Matrix<double, 9, 9>* /*kinetic*/) const {
    return false;
  }
};

/// Inverse dynamics of a parallel machine: analyze under wrench + dynamic_wrench (the actuators
/// move only bodies the TCP wrench sees). False when dynamic_wrench is.
inline bool static_inverse_dynamics(const Machine& machine, const Dynamics& dynamics,
                                    MachineData& data, const Pose& pose, const Vector6d& xi,
                                    const Vector6d& xi_dot, const Wrench& wrench,
                                    PoseMetrics& out) {
  Wrench w_dyn;
  if (!dynamics.dynamic_wrench(data, pose, xi, xi_dot, w_dyn)) return false;
  machine.analyze(data, pose, wrench + w_dyn, out);
  return true;
}

/// A capability (Machine::translational_maps): the translational maps at the TCP that a hybrid
/// machine (models/hybrid/hybrid_machine.hpp) needs to put this machine in series with serial
/// axes.
class TranslationalMaps {
 public:
  virtual ~TranslationalMaps() = default;
  /// analyze(data, pose, wrench, metrics), and with it, in base axes (both independent of the
  /// wrench):
  ///   compliance_tt (m/N): C_tt, the translational 3x3 block of the TCP compliance
  ///     (stiffness_min = 1 / lambda_max(C_tt));
  ///   error_map (3 x num_actuators, m): column j is the TCP position error when actuator j errs
  ///     by +actuator_error and the others are exact, so tcp_error_max = max over sign vectors
  ///     s in {-1, +1}^n of |error_map s|.
  /// `metrics` is filled in every case; returns false (maps unspecified) at a singular pose.
  virtual bool analyze_with_maps(MachineData& data, const Pose& pose, const Wrench& wrench,
                                 PoseMetrics& metrics, Eigen::Matrix3d& compliance_tt,
                                 Eigen::Matrix<double, 3, Eigen::Dynamic>& error_map) const = 0;
};

/// One real solution of the forward kinematics (AllForwardKinematics).
struct ForwardSolution {
  Pose pose;                          ///< the TCP pose
  double residual = 0.0;              ///< max |q(pose) - q| (actuator units)
  double jacobian_determinant = 0.0;  ///< det of the inverse Jacobian at the pose
  bool reachable = false;             ///< within the strokes and joint limits
  double nearest_other = INFINITY;    ///< pose distance to the nearest other real solution
  double to_reference = INFINITY;     ///< pose distance to the reference pose
};

/// Every assembly mode for one set of actuator values.
struct ForwardSolutions {
  std::vector<ForwardSolution> real;  ///< by increasing distance to the reference pose
  std::size_t complex_count = 0;      ///< solutions with imaginary parts
  std::size_t at_infinity = 0;        ///< paths that ran to infinity (a special geometry)
  std::size_t failed = 0;             ///< paths that failed (reported in `failures`)
  std::size_t paths = 0;
  std::vector<std::string> failures;
  /// The geometry is singular at every pose: the solutions are curves, not a finite set.
  bool architecture_singular = false;
  /// The length rho of the pose distance sqrt(|dp|^2 + (rho theta)^2), theta the angle of the
  /// relative rotation (m): how far a rotation moves the platform's joints.
  double distance_length = 0.0;
};

/// A capability (Machine::all_forward_kinematics_solver): all real forward-kinematics solutions
/// by a method that is complete for the general geometry (the hexapod's 40-path parameter
/// homotopy, models/hexapod/assembly_modes.hpp).
class AllForwardKinematics {
 public:
  virtual ~AllForwardKinematics() = default;
  /// The solutions for actuator values `q`, with their distances to `reference` (nullopt: the
  /// model's home pose, the default guess of forward_kinematics).
  virtual ForwardSolutions all_forward_kinematics(const Eigen::VectorXd& q,
                                                  const std::optional<Pose>& reference) const = 0;
};

using IntervalJacobian = std::array<std::array<Interval, 6>, 6>;
/// The partial derivatives of J_c with respect to the six coordinates of a box (p_x, p_y, p_z,
/// theta, phi, gamma; models/core/pose_box.hpp), each enclosed over the box.
using IntervalJacobianSlopes = std::array<IntervalJacobian, 6>;

/// A capability (Machine::jacobian_enclosure): the inverse Jacobian over a box of poses.
class JacobianEnclosure {
 public:
  virtual ~JacobianEnclosure() = default;
  /// rho (m): the length the Jacobian's angular columns are divided by, so that its entries
  /// have no unit (the hexapod: the mean distance of the platform joints from the TCP).
  virtual double enclosure_length() const = 0;
  /// An interval matrix holding, for every pose x of `box`, J_c(x): the inverse Jacobian
  /// (twist_jacobian, [v; omega] to actuator rates) with its angular columns divided by
  /// enclosure_length(). det J_c has the sign of det J. With `slopes`, also the derivatives of
  /// J_c over the box, for the mean-value form J_c(x) in J_c(x_mid) + sum_k slopes[k] (X_k -
  /// x_mid,k). False when the box holds a pose where J is not defined (a leg of length 0).
  virtual bool enclose_jacobian(const PoseBox& box, IntervalJacobian& J,
                                IntervalJacobianSlopes* slopes = nullptr) const = 0;
};

}  // namespace pkmopt
