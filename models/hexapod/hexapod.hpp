// The Gough-Stewart hexapod (6-UPS): six legs of variable length join base joints a_i to
// platform joints b_i.
//
// Frames and formulas (docs/conventions.md):
//   base joints a_i in the base frame, platform joints b_i and the TCP `tcp` in the platform
//   frame; for a TCP pose (p, R):   p0 = p - R tcp,   r_i = R (b_i - tcp),
//   leg vector  l_i = p + r_i - a_i,   length q_i = |l_i|,   unit vector s_i = l_i / q_i.
//   Inverse Jacobian (6x6, at the TCP, base axes): q_dot = J [v; omega],
//   row i = [s_i^T, (r_i x s_i)^T].
//   Leg forces for a wrench w at the TCP: J^T tau = w, tension positive.
//   Leg stiffness (the compliance chain, every term optional):
//     1/k_i = 1/k_strut_i + 1/actuator_stiffness + c_drive(q_i) + 1/k_base_joint +
//     1/k_platform_joint
//   k_strut_i the constant `axial_stiffness` or E * area / q_i; c_drive the ball screw (its free
//   length grows linearly with q_i from min to max length), nut, bearing and motor torsion
//   (models/stiffness/compliance_chain.hpp).
//   Stiffness matrix K = J^T diag(k) J; compliance C = K^-1;
//   stiffness_min = 1 / lambda_max(C_tt) (C_tt the translational 3x3 block of C).
//   singularity_margin = 1 / cond(J_h), J_h = J diag(1, 1, 1, 1/L, 1/L, 1/L).
//   tcp_error_max = max over |dq_i| <= actuator_error of |(J^-1 dq)_position| (at a vertex).
//   Base joint angle: angle(s_i, base_axis); platform joint angle: angle(-s_i, R platform_axis).
//   A pose is reachable when min_length <= q_i <= max_length, every joint angle is within
//   its limit and, with a leg shape, the legs' clearance is at least min_clearance
//   (leg_clearance over the 15 leg pairs, models/geometry/leg_interference.hpp).
//   Singular pose: 1 / cond(J_h) < kSingularRcond; then singularity_margin = 0,
//   stiffness_min = 0, tau_i = tcp_error_max = +inf.
//
// Units: metres, newtons, N/m, radians inside the code.
//
// The kinematic core (`hexapod_legs`) is templated on the scalar type so that ceres::Jet and
// Eigen::AutoDiffScalar differentiate through it; the metrics are computed in double.
//
// Example:
//   pkmopt::HexapodDesign design = pkmopt::semi_regular_hexapod(0.6, deg_to_rad(20),
//                                                               0.25, deg_to_rad(20));
//   design.min_length = 0.7; design.max_length = 1.15;
//   design.stiffness.E = 2.1e11; design.stiffness.area = 3e-4;
//   pkmopt::Hexapod hexapod(design);
//   pkmopt::HexapodData data(hexapod);
//   pkmopt::PoseMetrics m;
//   hexapod.analyze(data, pkmopt::Pose{{0, 0, 0.9}, {0, 0, 0}}, pkmopt::Wrench::Zero(), m);
#pragma once

#include <Eigen/Core>
#include <limits>
#include <memory>
#include <optional>
#include <string>

#include "models/core/capabilities.hpp"
#include "models/core/machine.hpp"
#include "models/core/pose.hpp"
#include "models/dynamics/leg_dynamics.hpp"
#include "models/dynamics/mass_model.hpp"
#include "models/geometry/joint_layout.hpp"
#include "models/geometry/leg_interference.hpp"
#include "models/geometry/solid_bodies.hpp"
#include "models/stiffness/compliance_chain.hpp"

namespace pkmopt {

/// How stiff each leg is along its axis: the compliance chain strut + actuator + drive train +
/// joints in series (every element optional, at least one given).
struct LegStiffness {
  /// Constant axial stiffness of the strut (N/m); used when > 0, instead of E * area / q.
  double axial_stiffness = 0.0;
  double E = 0.0;                   ///< Young's modulus of the strut (Pa)
  double area = 0.0;                ///< cross-section of the strut (m^2)
  double actuator_stiffness = 0.0;  ///< lumped actuator, in series (N/m); 0 = absent (rigid)
  /// Ball screw (free length growing with the leg length between min and max_length), nut,
  /// bearing and motor torsion (models/stiffness/compliance_chain.hpp).
  ScrewDrive drive{};
  double base_joint_stiffness = 0.0;      ///< axial stiffness of the base joint (N/m); 0 = rigid
  double platform_joint_stiffness = 0.0;  ///< axial stiffness of the platform joint (N/m)
};

/// Universal / spherical joint limits. An angle limit of +inf means unlimited.
struct HexapodJointLimits {
  double base_max_angle = std::numeric_limits<double>::infinity();      ///< rad
  double platform_max_angle = std::numeric_limits<double>::infinity();  ///< rad
  Eigen::Vector3d base_axis{0, 0, 1};       ///< base joint axis, base frame (unit)
  Eigen::Vector3d platform_axis{0, 0, -1};  ///< platform joint axis, platform frame (unit)
};

/// Everything that defines a hexapod. Validated by the Hexapod constructor.
struct HexapodDesign {
  Eigen::Matrix<double, 3, 6> base_joints;      ///< a_i, base frame (m)
  Eigen::Matrix<double, 3, 6> platform_joints;  ///< b_i, platform frame (m)
  double min_length = 0.0;                      ///< shortest leg (m)
  double max_length = 0.0;                      ///< longest leg (m)
  LegStiffness stiffness;
  HexapodJointLimits joints;
  Eigen::Vector3d tcp = Eigen::Vector3d::Zero();  ///< TCP in the platform frame (m)
  /// L in J_h; when empty, the mean distance from the TCP to the platform joints.
  std::optional<double> characteristic_length;
  double actuator_error = 1e-5;  ///< m, half-width of the actuator error box
  /// Platform and leg masses (models/dynamics/mass_model.hpp; UPS cylinder and rod); `present`
  /// false: none (no natural frequencies).
  MassModel masses;
  /// The legs' outer shape (models/geometry/leg_interference.hpp); not given: no interference
  /// check.
  LegShape leg_shape;
  /// m: with a leg shape, a pose is reachable only when leg_clearance >= min_clearance.
  double min_clearance = 0.0;
  /// Platform and base plates and the tool, checked against the legs
  /// (models/geometry/solid_bodies.hpp); they need a leg shape.
  MachineBodies bodies;
};

/// A design with semi-regular base and platform; lengths, stiffness and limits left to fill in.
HexapodDesign semi_regular_hexapod(double base_radius, double base_pair_separation,
                                   double platform_radius, double platform_pair_separation);

/// Leg lengths and (optionally) the inverse Jacobian at a TCP pose, for any scalar type.
///   base: a_i (3x6), platform_rel: b_i - tcp (3x6), position/angles: the TCP pose (rad).
///   q: leg lengths (out); J: inverse Jacobian (out, may be null); s: unit leg vectors (out,
///   may be null); r: R (b_i - tcp) (out, may be null).
template <typename T>
void hexapod_legs(const Eigen::Matrix<T, 3, 6>& base, const Eigen::Matrix<T, 3, 6>& platform_rel,
                  const Vec3<T>& position, const Vec3<T>& angles, Vec6<T>* q, Mat6<T>* J = nullptr,
                  Eigen::Matrix<T, 3, 6>* s = nullptr, Eigen::Matrix<T, 3, 6>* r = nullptr) {
  using std::sqrt;
  const Mat3<T> R = rotation_zyx<T>(angles);
  for (int i = 0; i < 6; ++i) {
    const Vec3<T> ri = R * platform_rel.col(i);
    const Vec3<T> li = position + ri - base.col(i);
    const T length = sqrt(li.squaredNorm());
    if (q) (*q)(i) = length;
    if (J || s) {
      const Vec3<T> si = li / length;
      if (s) s->col(i) = si;
      if (J) {
        J->template block<1, 3>(i, 0) = si.transpose();
        J->template block<1, 3>(i, 3) = ri.cross(si).transpose();
      }
    }
    if (r) r->col(i) = ri;
  }
}

/// Per-thread scratch space and last results of a hexapod.
class HexapodData : public MachineData {
 public:
  HexapodData() = default;
  /// A data of `hexapod` (what hexapod.make_data() makes).
  explicit HexapodData(const class Hexapod& hexapod);

  Vec6<double> q;                 ///< leg lengths (m)
  Eigen::Matrix<double, 3, 6> s;  ///< unit leg vectors, base frame
  Eigen::Matrix<double, 3, 6> r;  ///< R (b_i - tcp), base frame
  Matrix6d J;                     ///< inverse Jacobian
  Vec6<double> leg_stiffness;     ///< k_i (N/m)
  Mat3<double> compliance_tt;     ///< C_tt of the last compute_metrics (m/N; not if singular)
  /// TCP position error per actuator error of the last compute_metrics (m; not if singular):
  /// actuator_error times the translational rows of J^-1.
  Eigen::Matrix<double, 3, 6> error_map;
};

/// The hexapod's `model:` name in machine and study files.
inline constexpr std::string_view kHexapodModel = "hexapod";

/// A Gough-Stewart hexapod. Immutable; share it between threads, give each a HexapodData.
class Hexapod final : public Machine,
                      public BatchAnalysis,
                      public Dynamics,
                      public TranslationalMaps,
                      public AllForwardKinematics,
                      public JacobianEnclosure {
 public:
  /// Validates the design; throws std::invalid_argument naming the offending field.
  explicit Hexapod(const HexapodDesign& design);

  const HexapodDesign& design() const { return design_; }
  /// b_i - tcp (3x6), platform frame.
  const Eigen::Matrix<double, 3, 6>& platform_rel_tcp() const { return platform_rel_; }
  /// The characteristic length L (m) used in J_h.
  double characteristic_length() const { return characteristic_length_; }

  std::string_view model() const override { return kHexapodModel; }
  int num_actuators() const override { return 6; }
  bool revolute_actuators() const override { return false; }
  std::optional<double> actuator_stroke(int i) const override {
    if (i < 0 || i >= 6) return std::nullopt;
    return design_.max_length - design_.min_length;
  }
  std::unique_ptr<MachineData> make_data() const override;

  void analyze(MachineData& data, const Pose& pose, const Wrench& wrench,
               PoseMetrics& out) const override;
  bool reachable(MachineData& data, const Pose& pose) const override;
  bool checks_leg_interference() const override { return design_.leg_shape.present(); }
  /// The legs' clearance at a pose (+inf without a leg shape).
  Clearance leg_clearance(const Pose& pose) const;
  /// `legs` (the legs' own clearance at `pose`) lowered by the solids' (design().bodies).
  Clearance with_solid_bodies(const Pose& pose, Clearance legs) const;
  FkResult forward_kinematics(const Eigen::VectorXd& q, const std::optional<Pose>& guess,
                              const FkOptions& options = {}) const override;
  /// Leg i puts the TCP in the ball of radius max_length about c_i = a_i - R (b_i - tcp); with
  /// a base joint limit beta < 90 deg about +z the leg also keeps min_length cos(beta) <= l_z
  /// and |l_xy| <= max_length sin(beta). The box is the intersection over legs, united over the
  /// orientations. Empty box: nothing is reachable.
  std::optional<Eigen::AlignedBox3d> workspace_search_box(
      const std::vector<Eigen::Matrix3d>& orientations) const override;
  /// The vertical cylinder about the centroid of the base joints whose radius is the largest
  /// horizontal distance of a base joint from that axis and whose height is the z extent of the
  /// base joints plus max_length (the legs standing straight up at full stroke).
  std::optional<double> envelope_volume() const override;
  std::string actuator_coordinates_requirement(const Eigen::VectorXd& q) const override;
  /// The SIMD batch kernel (analyze_hexapod_batch, models/hexapod/hexapod_batch.hpp, automatic
  /// kernel).
  const BatchAnalysis* batch_analysis() const override { return this; }
  void analyze_batch(const Pose* poses, std::size_t count, const Wrench& wrench,
                     PoseMetrics* metrics, PoseCompliance* compliance) const override;
  /// Legs from the base joints a_i to the platform joints at the pose, and the tool.
  bool sketch(MachineData& data, const Pose& pose, MachineSketch& out) const override;
  /// Present with a mass model (the machine file's `masses`).
  Capability<AllForwardKinematics> all_forward_kinematics_solver() const override { return this; }
  /// Every assembly mode (models/hexapod/assembly_modes.hpp); rho of the pose distance is the
  /// mean distance of the platform joints from the TCP.
  ForwardSolutions all_forward_kinematics(const Eigen::VectorXd& q,
                                          const std::optional<Pose>& reference) const override;
  Capability<JacobianEnclosure> jacobian_enclosure() const override { return this; }
  /// rho: the mean distance of the platform joints from the TCP (m).
  double enclosure_length() const override;
  /// Row i: [s_i^T, (r_i x s_i)^T / rho], s_i = l_i / |l_i|, l_i = p + r_i - a_i, r_i = R (b_i -
  /// tcp); with r_i x l_i = r_i x (p - a_i) for the moment (models/hexapod/hexapod_enclosure.cpp).
  bool enclose_jacobian(const PoseBox& box, IntervalJacobian& J,
                        IntervalJacobianSlopes* slopes = nullptr) const override;
  Capability<Dynamics> dynamics() const override {
    if (!design_.masses.present)
      return Capability<Dynamics>::missing("the machine file has no 'masses'");
    return this;
  }
  int natural_frequency_count() const override { return design_.masses.present ? 6 : 0; }
  const MassModel& mass_model() const override { return design_.masses; }
  double moving_mass() const override {
    return pkmopt::moving_mass(design_.masses,
                               std::vector<LegBodyKind>(6, LegBodyKind::kTelescopic));
  }
  bool mass_matrix(MachineData& data, const Pose& pose, Matrix6d& M) const override;
  bool mode_shapes(MachineData& data, const Pose& pose, PoseModes& out) const override;
  bool dynamic_wrench(MachineData& data, const Pose& pose, const Vector6d& xi,
                      const Vector6d& xi_dot, Wrench& w_dyn) const override;
  bool carried_dynamics(MachineData& data, const Pose& pose, const Vector6d& xi,
                        const Vector6d& xi_dot, const Eigen::Vector3d& gravity, Wrench& w_dyn,
                        Eigen::Vector3d& net_force,
                        Eigen::Matrix<double, 9, 9>* kinetic) const override;
  bool inverse_dynamics(MachineData& data, const Pose& pose, const Vector6d& xi,
                        const Vector6d& xi_dot, const Wrench& wrench,
                        PoseMetrics& out) const override {
    return static_inverse_dynamics(*this, *this, data, pose, xi, xi_dot, wrench, out);
  }
  bool twist_jacobian(MachineData& data, const Pose& pose, Eigen::MatrixXd& J) const override;
  /// C_tt and actuator_error * (translational rows of J^-1), from compute_metrics.
  const TranslationalMaps* translational_maps() const override { return this; }
  bool analyze_with_maps(MachineData& data, const Pose& pose, const Wrench& wrench,
                         PoseMetrics& metrics, Eigen::Matrix3d& compliance_tt,
                         Eigen::Matrix<double, 3, Eigen::Dynamic>& error_map) const override;

  /// Leg lengths at a pose.
  Vec6<double> inverse_kinematics(const Pose& pose) const;
  /// The inverse Jacobian at a pose.
  Matrix6d inverse_jacobian(const Pose& pose) const;
  /// The 6x6 stiffness matrix K = J^T diag(k) J at a pose (N/m, N, N*m/rad blocks).
  Matrix6d stiffness_matrix(const Pose& pose) const;
  /// Leg stiffness k_i for a leg of length q (N/m).
  double leg_stiffness(double q) const;
  /// The legs' joint points at a pose (telescopic: base joint a_i, platform joint P_i).
  std::vector<LegPoints> leg_points(const Pose& pose) const;
  /// The TCP mass matrix at a pose (models/dynamics/machine_dynamics.hpp; needs design().masses).
  Matrix6d mass_matrix(const Pose& pose) const;
  /// Base and platform joint angles (rad) of every leg at a pose.
  void joint_angles(const Pose& pose, Vec6<double>& base_angles,
                    Vec6<double>& platform_angles) const;
  /// The home pose used as the default FK guess: x = y = 0, no rotation, and the height at
  /// which the mean leg length equals the mean of q.
  Pose home_pose_for(const Vec6<double>& q) const;

  /// Kinematics only (q, s, r, J) into data; returns false when a leg has zero length.
  bool compute_kinematics(HexapodData& data, const Pose& pose) const;
  /// The same with R = rotation_zyx(pose.angles) already computed.
  bool compute_kinematics(HexapodData& data, const Pose& pose, const Mat3<double>& R) const;
  /// Full metric set (the fast path behind analyze).
  void compute_metrics(HexapodData& data, const Pose& pose, const Wrench& wrench,
                       PoseMetrics& out) const;

 private:
  bool reachable_from_kinematics(const HexapodData& data, const Mat3<double>& R) const;
  /// The legs' bodies of the last compute_kinematics (a_i to a_i + q_i s_i); returns how many.
  int bodies_from_kinematics(const HexapodData& data, Capsule (&bodies)[12]) const;
  /// The clearance of the legs (with each other and with the solids) of the last
  /// compute_kinematics at `pose`, R its rotation.
  Clearance clearance_from_kinematics(const HexapodData& data, const Pose& pose,
                                      const Mat3<double>& R) const;
  /// compliance (into data.matrices), tcp_deflection, tcp_rotation_deflection,
  /// stiffness_min_direction, stiffness_min_loaded and (with masses) natural_frequencies of a
  /// non-singular pose (after
  /// compute_metrics' kinematics and tau).
  void compute_compliance_metrics(HexapodData& data, const Pose& pose,
                                  const Vec6<double>& compliance, const Wrench& wrench,
                                  PoseMetrics& out) const;

  /// The assembly-mode solver of this geometry (AssemblyModeSolver), made on the first
  /// all_forward_kinematics and shared by copies.
  struct AssemblyModeCache;
  static std::shared_ptr<AssemblyModeCache> new_assembly_mode_cache();

  HexapodDesign design_;
  Eigen::Matrix<double, 3, 6> platform_rel_;
  std::shared_ptr<AssemblyModeCache> assembly_modes_ = new_assembly_mode_cache();
  double characteristic_length_ = 1.0;
  double cos_base_limit_ = -2.0;      // cos of the base joint limit (-2: unlimited)
  double cos_platform_limit_ = -2.0;  // cos of the platform joint limit
};

}  // namespace pkmopt
