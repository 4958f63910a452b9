// The interface every machine model offers to workspaces, problems and the CLI.
//
// A Machine is immutable once built and may be shared between threads. Every per-pose
// algorithm takes a MachineData made by the same machine (`make_data()`), which holds the
// scratch space and results of one thread (the Model/Data split of Pinocchio):
//
//   auto data = machine.make_data();
//   pkmopt::PoseMetrics metrics;
//   machine.analyze(*data, pose, wrench, metrics);
//
// The meaning of every metric is fixed by docs/conventions.md:
//   q             actuator coordinates (m for prismatic actuators, rad for revolute ones;
//                 files show revolute coordinates in degrees)
//   tau           actuator forces (N) or torques (N*m) balancing the wrench, J^T tau = w,
//                 tension positive; +inf at a singular pose
//   stiffness_min the TCP stiffness in the worst direction of a pure force (N/m), 0 if singular
//   singularity_margin  1 / cond(J_h), 0..1, 0 if singular
//   det_j         det of the inverse Jacobian J
//   tcp_error_max the largest TCP position error (m) for actuator errors within the box
//                 |dq_i| <= actuator_error; +inf if singular
//   tcp_deflection           |(C w)_t| (m): how far the TCP moves under the analysed wrench
//   tcp_rotation_deflection  |(C w)_r| (rad): how far the tool turns under it
//   stiffness_min_direction  the unit force direction of stiffness_min (the eigenvector of C_tt
//                 for its largest eigenvalue; sign: largest component positive)
//   natural_frequencies      with a mass model: det(K - omega^2 M) = 0 on the platform DOF, Hz
//   leg_clearance            with a leg shape: the smallest gap between the surfaces of two legs
//                 (m, negative when they intersect; models/geometry/leg_interference.hpp), +inf
//                 without
//   stiffness_min_loaded     1 / sigma_max(C_T,tt), C_T = K_T^-1 the loaded (tangent) compliance
//                 with the geometric term of the leg forces under the wrench; 0 when K_T is
//                 not positive definite (the loaded mechanism is unstable)
//   All of them +inf (stiffness: 0, direction: 0) at a singular pose.
// The matrices behind them (PoseCompliance) stay in the MachineData of the call
// (data.matrices), so that a list of PoseMetrics stays small:
//   compliance    C = K^-1 (6x6, twist [dp; dtheta] per wrench [f; m] at the TCP, base axes);
//                 for platforms with fewer than 6 DOF the directions the passive constraints
//                 hold are rigid (zero rows and columns) unless link compliance is modelled
//   loaded_compliance_tt  the translational block of C_T (m/N)
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "models/core/machine_sketch.hpp"
#include "models/core/pose.hpp"

namespace pkmopt {

/// Below this reciprocal condition number of a machine's Jacobian (J_h of the hexapod, A_h of the
/// leg chains) a pose counts as singular.
inline constexpr double kSingularRcond = 1e-12;

/// Everything `analyze` computes at one pose.
struct PoseMetrics {
  bool reachable = false;
  Eigen::VectorXd q;    ///< actuator coordinates (dim num_actuators)
  Eigen::VectorXd tau;  ///< actuator forces / torques (dim num_actuators)
  double stiffness_min = 0.0;
  double singularity_margin = 0.0;
  double det_j = 0.0;
  double tcp_error_max = 0.0;
  bool singular = false;        ///< J numerically singular (see the model's header for the test)
  double tcp_deflection = 0.0;  ///< m, |(C w)_t| under the analysed wrench
  double tcp_rotation_deflection = 0.0;  ///< rad, |(C w)_r|
  double stiffness_min_loaded = 0.0;     ///< N/m, with the legs' loads (geometric term)
  Eigen::Vector3d stiffness_min_direction = Eigen::Vector3d::Zero();  ///< unit, base axes
  /// Hz, ascending, one per platform DOF: the undamped natural frequencies of the platform on the
  /// elastic mechanism (models/dynamics/machine_dynamics.hpp); empty when the machine has no mass
  /// model or the compliance metrics are off; 0 at a singular pose.
  Eigen::VectorXd natural_frequencies;
  /// m: the smallest clearance between the surfaces of two legs
  /// (models/geometry/leg_interference.hpp), negative when they intersect; +inf when the machine
  /// has no leg shape.
  double leg_clearance = std::numeric_limits<double>::infinity();
  int clearance_first = -1, clearance_second = -1;  ///< the closest pair (0-based legs)
};

/// The compliance matrices of one analyzed pose (see the header comment).
struct PoseCompliance {
  Matrix6d compliance = Matrix6d::Zero();  ///< C = K^-1 at the TCP (twist per wrench)
  /// The translational block of the loaded compliance K_T^-1 (m/N), whose largest singular value
  /// gives stiffness_min_loaded; +inf entries when the loaded machine is unstable.
  Eigen::Matrix3d loaded_compliance_tt = Eigen::Matrix3d::Zero();
};

/// Options of the forward kinematics solve.
struct FkOptions {
  int max_iterations = 100;       ///< Newton / Levenberg-Marquardt iterations at most
  double tolerance = 1e-12;       ///< converged when max |q(pose) - q| <= tolerance (q units)
  double initial_damping = 1e-6;  ///< Levenberg-Marquardt damping relative to diag(J^T J)
};

/// Result of a forward kinematics solve. Never contains NaN; on failure `converged` is false,
/// `pose` is the best pose found and `message` says why.
struct FkResult {
  Pose pose;
  bool converged = false;
  int iterations = 0;
  double residual = 0.0;  ///< max |q(pose) - q| at the returned pose
  std::string message;
};

class Machine;

/// Per-thread scratch space of a machine. Made by Machine::make_data(); a machine's per-pose
/// functions accept only the data it made (std::invalid_argument otherwise).
class MachineData {
 public:
  virtual ~MachineData() = default;
  /// The machine that made this data (null for a data made outside make_data).
  const Machine* made_by() const { return made_by_; }
  /// analyze fills compliance, tcp_deflection, tcp_rotation_deflection,
  /// stiffness_min_direction and stiffness_min_loaded only when this is set (a caller that
  /// needs none of them, e.g. a design problem, saves their cost; they are then left as zeros).
  bool compliance_metrics = true;
  /// The compliance matrices of the last analyze (with compliance_metrics set).
  PoseCompliance matrices;

  MachineData() = default;

 protected:
  /// A data of `made_by` (a model's data type constructed from its machine).
  explicit MachineData(const Machine* made_by) : made_by_(made_by) {}

 private:
  friend class Machine;
  const Machine* made_by_ = nullptr;
};

class BatchAnalysis;
class ParasiticMotion;
class Dynamics;
class TranslationalMaps;
class AllForwardKinematics;
class JacobianEnclosure;

/// What a query for an optional capability answers (models/core/capabilities.hpp): the
/// capability, or why the machine does not have it, in words a user can act on ("the machine
/// file has no 'masses'").
template <class T>
class Capability {
 public:
  /// The machine has it.
  Capability(const T* capability) : capability_(capability) {}  // NOLINT: implicit on purpose
  /// The machine does not have it, because of `reason`.
  static Capability missing(std::string reason) {
    Capability c(nullptr);
    c.reason_ = std::move(reason);
    return c;
  }
  explicit operator bool() const { return capability_ != nullptr; }
  const T* get() const { return capability_; }
  const T* operator->() const { return capability_; }
  /// Why the machine has no such capability; empty when it has.
  const std::string& reason() const { return reason_; }

 private:
  const T* capability_ = nullptr;
  std::string reason_;
};

class Machine {
 public:
  virtual ~Machine() = default;

  /// The `model:` name in machine files ("hexapod", ...).
  virtual std::string_view model() const = 0;
  /// Number of actuators (dimension of q and tau).
  virtual int num_actuators() const = 0;
  /// True when every actuator is revolute (q in rad inside, degrees in files).
  virtual bool revolute_actuators() const = 0;
  /// True when actuator i (0-based) is revolute: its q in rad inside and degrees in files, its
  /// tau in N*m. Machines that mix linear and rotary drives (a serial 5-axis machine) override
  /// it; the others' drives are all of one kind.
  virtual bool revolute_actuator(int /*i*/) const { return revolute_actuators(); }
  /// The travel of actuator i (0-based): the width of its range, m (rad for a revolute one);
  /// nullopt when the model does not give one.
  virtual std::optional<double> actuator_stroke(int /*i*/) const { return std::nullopt; }
  /// Drives bought as one catalog entry share a group, numbered by its first drive: by default
  /// the alike drives of a parallel machine (same kind, same stroke), so a hexapod's six legs are
  /// one group. A serial machine's axes are groups of their own.
  virtual int drive_group(int i) const {
    const std::optional<double> stroke = actuator_stroke(i);
    for (int j = 0; j < i; ++j) {
      if (revolute_actuator(j) != revolute_actuator(i)) continue;
      const std::optional<double> other = actuator_stroke(j);
      if (stroke.has_value() != other.has_value()) continue;
      if (!stroke || std::abs(*stroke - *other) <= 1e-9 * std::max(1.0, std::abs(*stroke)))
        return j;
    }
    return i;
  }
  /// True when any actuator is revolute.
  bool any_revolute_actuator() const {
    for (int i = 0; i < num_actuators(); ++i)
      if (revolute_actuator(i)) return true;
    return false;
  }

  virtual std::unique_ptr<MachineData> make_data() const = 0;

  /// Every metric at a TCP pose under an external wrench at the TCP (base axes).
  virtual void analyze(MachineData& data, const Pose& pose, const Wrench& wrench,
                       PoseMetrics& out) const = 0;

  /// Reachability only (actuator ranges and joint limits); cheaper than analyze.
  virtual bool reachable(MachineData& data, const Pose& pose) const = 0;

  /// Forward kinematics: the TCP pose for actuator coordinates q, from a guess
  /// (a model-chosen home pose when none is given).
  virtual FkResult forward_kinematics(const Eigen::VectorXd& q, const std::optional<Pose>& guess,
                                      const FkOptions& options = {}) const = 0;

  /// A box containing every reachable TCP position for the given platform orientations, from
  /// the geometry (used by the workspace search); nullopt when the model does not know one.
  virtual std::optional<Eigen::AlignedBox3d> workspace_search_box(
      const std::vector<Eigen::Matrix3d>& /*orientations*/) const {
    return std::nullopt;
  }
  /// True when the machine file gives the legs' shape: analyze fills leg_clearance and a pose is
  /// reachable only with leg_clearance >= min_clearance (models/geometry/leg_interference.hpp).
  virtual bool checks_leg_interference() const { return false; }
  /// The volume of the machine's envelope (m^3, see the model's header); nullopt if unknown.
  virtual std::optional<double> envelope_volume() const { return std::nullopt; }

  /// Empty when q (size num_actuators(), internal units) can be actuator coordinates of this
  /// machine; otherwise what is expected ("6 leg lengths > 0 (m)"). Range limits do not count:
  /// this only rejects values that mean nothing (a leg length <= 0).
  virtual std::string actuator_coordinates_requirement(const Eigen::VectorXd& /*q*/) const {
    return {};
  }

  /// The inverse Jacobian on the full TCP twist at a pose: q_dot = J xi with xi = [v; omega]
  /// (m/s, rad/s; base axes, at the TCP) and J of size num_actuators x 6 (rows in m or rad per
  /// unit twist). For platforms with fewer than six degrees of freedom only the twists the
  /// platform can make are meaningful. Returns false (J untouched) when a leg cannot close at
  /// the pose or J is unbounded (a serial singularity) or the model does not provide it.
  virtual bool twist_jacobian(MachineData& /*data*/, const Pose& /*pose*/,
                              Eigen::MatrixXd& /*J*/) const {
    return false;
  }

  /// How far a pose lies beyond the machine's limits: the largest excess of an actuator
  /// coordinate over its range (m or rad), of a joint angle over its limit (rad), or of the
  /// legs' clearance below its minimum (m); 0 when no limit is exceeded (the pose may still be
  /// unreachable for a reason these terms do not see). nullopt when a leg cannot close at the
  /// pose or the model does not measure it.
  virtual std::optional<double> reach_excess(const Pose& /*pose*/) const { return std::nullopt; }

  // Optional capabilities (models/core/capabilities.hpp): null when the machine has none.

  /// The batch kernel of the machine (BatchAnalysis); null when it has none.
  virtual const BatchAnalysis* batch_analysis() const { return nullptr; }
  /// The parasitic motion of the platform (ParasiticMotion); null when every pose coordinate is
  /// commanded.
  virtual const ParasiticMotion* parasitic_motion() const { return nullptr; }
  /// The machine's dynamics (Dynamics: its mass model, natural frequencies and modes, mass
  /// matrix, inverse dynamics); missing, with the reason, when it has no mass model.
  virtual Capability<Dynamics> dynamics() const {
    return Capability<Dynamics>::missing(std::string(model()) + " machines have no mass model");
  }
  /// Every real forward-kinematics solution (AllForwardKinematics); missing, with the reason,
  /// for models without a complete solver.
  virtual Capability<AllForwardKinematics> all_forward_kinematics_solver() const {
    return Capability<AllForwardKinematics>::missing(
        std::string(model()) +
        " machines: all forward-kinematics solutions are computed for the hexapod (the 6-6 "
        "Gough–Stewart platform) only");
  }
  /// An interval enclosure of the inverse Jacobian over a box of poses (JacobianEnclosure);
  /// missing, with the reason, for models without one.
  virtual Capability<JacobianEnclosure> jacobian_enclosure() const {
    return Capability<JacobianEnclosure>::missing(
        std::string(model()) +
        " machines: the Jacobian is enclosed over boxes of poses for the hexapod only");
  }
  /// The translational maps at the TCP that put the machine in series with serial axes
  /// (TranslationalMaps, the module of a hybrid machine); null when the model has none.
  virtual const TranslationalMaps* translational_maps() const { return nullptr; }

  /// The machine drawn as lines at a pose (models/core/machine_sketch.hpp). Returns false (out
  /// unspecified) when the legs cannot assemble at the pose or the model cannot draw itself.
  virtual bool sketch(MachineData& /*data*/, const Pose& /*pose*/, MachineSketch& /*out*/) const {
    return false;
  }

 protected:
  /// A new data of type D (a MachineData) marked as this machine's: make_data() returns one.
  template <class D, class... Args>
  std::unique_ptr<D> new_data(Args&&... args) const {
    auto data = std::make_unique<D>(std::forward<Args>(args)...);
    data->made_by_ = this;
    return data;
  }
  /// `data` as this machine's data type D; throws std::invalid_argument when another machine
  /// made it (a data is made by make_data() of the machine it is used with).
  template <class D>
  D& data_of(MachineData& data) const {
    if (data.made_by_ != this) throw_foreign_data();
    return static_cast<D&>(data);
  }
  template <class D>
  const D& data_of(const MachineData& data) const {
    if (data.made_by_ != this) throw_foreign_data();
    return static_cast<const D&>(data);
  }

 private:
  [[noreturn]] void throw_foreign_data() const {
    throw std::invalid_argument(std::string(model()) +
                                ": a MachineData made by another machine (each machine takes the "
                                "data its make_data() made)");
  }
};

}  // namespace pkmopt
