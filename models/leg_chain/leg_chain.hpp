// The leg-chain family of parallel machines, and its named members (delta, linear_delta,
// hexaglide, tripod_3prs, tripod_3rps).
//
// Every leg closes one distance constraint between an actuated point c_i(q_i) on the base side
// and a platform point P_i = p + R (b_i - tcp) (p, R: the TCP pose; b_i in the platform frame):
//     |P_i - c_i(q_i)| = L_i(q_i)
// with the leg kinds
//   UPS  fixed base joint c_i = a_i, variable length L_i = q_i (m)             (hexapod legs);
//   PUS  carriage on a guide line c_i = g_i + q_i u_i (m), constant strut L_i  (PUU: the same);
//   RUS  crank of length r_i turning about the axis w_i through the pivot o_i,
//        elbow c_i = o_i + r_i (cos q_i d_i + sin q_i (w_i x d_i)) (q_i in rad), constant rod L_i.
// Unit leg vector s_i = (P_i - c_i) / |P_i - c_i| (from the actuated side to the platform).
//
// Platform mobility (the m platform degrees of freedom, m = number of legs):
//   kSixDof        6 legs, the platform moves freely; DOF twist [v; omega] (base axes, at the TCP).
//   kTranslational 3 legs, the orientation is held at R = I by parallelogram rods (deltas,
//                  linear deltas); DOF twist v. A pose with a rotation is not reachable.
//   kSchoenflies   4 legs (3T1R), the platform turns only about the fixed unit axis e
//                  (`rotation_axis`, base frame): R = Rot(e, phi), the other two rotations held by
//                  parallelogram strut pairs whose bars are parallel to e. DOF twist (v, omega_e).
//                  A pose is reachable only if its R is a rotation about e (within 1e-9 rad);
//                  phi is the twist angle of R about e (swing-twist split), and the metrics of a
//                  pose off that set are those of R = Rot(e, phi).
//   kPlanarLegs    3 legs, each kept in a plane by a revolute joint (3-PRS / 3-RPS tripod heads):
//                  the platform point stays in the plane through base_point with normal
//                  plane_normal_i (a plane that contains the actuated point's path):
//                      h_i = n_i . (p + R (b_i - tcp) - base_point_i) = 0.
//                  DOF (z, rx, ry) of the TCP pose, DOF twist (v_z, omega_x, omega_y); the
//                  parasitic x, y, rz follow from h = 0 (Newton, from the home pose's x, y, rz).
//                  The x, y, rz of a given pose are ignored: the machine is at its parasitic ones
//                  (actual_pose()). The planes must fix x, y, rz (G_p below invertible).
// The full twist is T xi: T = I (6-DOF), [I; 0] (translational), [I 0; 0 e] (6x4, Schoenflies),
// and for planar legs, with G (3x6) row i = [n_i^T, (r_i x n_i)^T] the plane constraints' twist
// Jacobian split into the parasitic columns G_p (v_x, v_y, omega_z) and the DOF columns G_d
// (v_z, omega_x, omega_y): T = identity on the DOF rows and -G_p^-1 G_d on the parasitic rows.
// G_p singular is reported as a parallel (constraint) singularity.
//
// Velocity equations: differentiating the constraints,  A xi = B q_dot  with
//   A (m x m): row i = [s_i^T, (r_i x s_i)^T] T,  r_i = R (b_i - tcp);
//   B = diag(B_i): B_i = 1 (UPS), s_i . u_i (PUS), s_i . (w_i x (c_i - o_i)) (RUS),
// and the inverse Jacobian J = B^-1 A (q_dot = J xi). det B = 0 is a serial singularity (a leg's
// actuator cannot move the platform point along its rod, e.g. a delta's arm and rod aligned);
// det A = 0 a parallel singularity (the platform gains a motion with the actuators locked).
//
// IK is closed form per leg. The two solutions of PUS and RUS legs are told apart by the sign of
// B_i: branch +1 takes B_i > 0, branch -1 takes B_i < 0 (B_i = 0 is the serial singularity
// between them). For the delta (docs/conventions.md) branch +1 is the elbow-out solution.
// FK: Levenberg-Marquardt (models/core/pose_solver.hpp) on the closure errors |P_i - c_i| - L_i;
// 6-DOF and translational platforms solve on their DOF; Schoenflies and planar-leg platforms on
// the full twist with their mobility equations appended (6 x 6, all in m): L e1 . (R e) = 0 and
// L e2 . (R e) = 0 (e1, e2 orthogonal to e), resp. h_i = 0.
//
// Metrics (same names and meanings as the hexapod, docs/conventions.md):
//   q_i: m (UPS, PUS), rad (RUS; degrees in files).
//   tau: J^T tau = T^T w, the actuator forces (N) / torques (N*m) balancing the wrench w at the
//     TCP; for platforms with fewer than 6 DOF only the components T^T w of w along the platform
//     DOF load the actuators (the rest is taken by the passive constraints: parallelograms,
//     the tripod's revolute joints). Equivalently the rod forces are
//     f = A^-T T^T w (tension positive) and tau_i = B_i f_i.
//   Axial stiffness of leg i, seen at the platform point along s_i:
//     k_i = 1 / (B_i^2 c_act_i + 1 / k_link_i + (1/k_base_joint + 1/k_platform_joint) / rods),
//     c_act_i = 1/actuator_stiffness + the drive train's compliance at q_i (ball screw, nut,
//     bearing, motor torsion; models/stiffness/compliance_chain.hpp), in m/N or rad/(N*m) for RUS;
//     every
//     term optional (0 = rigid). k_link_i the link's axial stiffness: axial_stiffness, or
//     E * area * rods / length (length q_i for UPS, the constant strut/rod length otherwise;
//     `rods` = 2 for a parallelogram pair).
//     K = A^T diag(k) A on the platform DOF; C = K^-1; C_tt the translational 3x3 block of
//     T C T^T; stiffness_min = 1 / lambda_max(C_tt) (N/m). (The passive constraints - parallelogram
//     bars, the tripod's revolute joints - are taken as rigid.)
//   Link compliance (models/leg_chain/leg_chain_vjm.cpp, docs/stiffness.md): when some leg has a
//     link_section, a crank_section or a parallelogram_width, the 6x6 stiffness at the TCP is the
//     virtual-joint model (models/stiffness/virtual_joint.hpp) of the legs at the pose, summed:
//     actuator
//     spring (c_act_i) -> crank beam (RUS) -> link -> passive joints -> platform, the link a beam
//     with the revolute joint about n_i at its foot (planar legs), a beam between a universal and
//     a spherical joint (other single links with a section: bending cannot enter), two rods with
//     ball ends parallelogram_width apart (pairs), or a two-force member. C = K^-1, now finite in
//     every direction (translational / Schoenflies machines without widths: C = T (T^T K T)^-1
//     T^T, the orientation still held rigidly). The section gives the link's axial stiffness
//     (axial_stiffness, E and area are then not used).
//   singularity_margin = 1 / cond(J_h), J_h = J diag(1 for translational DOF, 1/L for rotational
//     DOF), 0 at a serial or a parallel singularity.
//   det_j = det J.
//   tcp_error_max: max over |dq_i| <= actuator_error of |(T J^-1 dq)_position| (at a vertex).
//   Reachable: every leg's IK exists on its branch, q_i within [q_min, q_max] (the crank range
//     for RUS), every joint angle within its limit, and the pose's rotation is one the platform
//     can take (R = I translational, R = Rot(e, phi) Schoenflies; planar legs: the parasitic
//     solve converged).
//     Base-side joint angle: angle(s_i, base_axis_i), base_axis_i fixed in the base for UPS and
//     PUS and carried by the crank for RUS (given at q = 0); platform joint angle:
//     angle(-s_i, R platform_axis_i).
//   At a singular pose (serial: |B_i| < 1e-7 scale_i with scale_i = 1 for UPS/PUS and r_i for
//   RUS; parallel: 1/cond(A_h) < kSingularRcond; or a leg that cannot close):
//     singularity_margin = 0, stiffness_min = 0, tau_i = tcp_error_max = +inf. Never NaN.
//
// Units: metres, radians, newtons, N/m, N*m/rad inside the code.
//
// Examples:
//   pkmopt::DeltaDesign d;           // an ABB IRB 360-like delta, see DeltaDesign
//   auto machine = pkmopt::make_delta(d);
//   auto data = machine->make_data();
//   pkmopt::PoseMetrics m;
//   machine->analyze(*data, pkmopt::Pose{{0, 0, -0.9}, {0, 0, 0}}, pkmopt::Wrench::Zero(), m);
//   // m.q: drive angles (rad), m.tau: torques (N*m)
//   auto tripod = pkmopt::make_tripod_3prs(pkmopt::Tripod3PrsDesign{});   // Sprint Z3-like
//   // pose z = 1.2 m, rx = 30 deg, ry = -20 deg; its x, y, rz are replaced by the parasitic ones
//   pkmopt::Pose pose{{0, 0, 1.2}, pkmopt::deg_to_rad(Eigen::Vector3d(30, -20, 0))};
//   tripod->analyze(*tripod->make_data(), pose, pkmopt::Wrench::Zero(), m);   // m.q: slides (m)
//   pkmopt::Tripod3PrsDesign z3;     // steel tube struts: their bending and torsion enter (VJM)
//   z3.stiffness.section = pkmopt::tube_section(2.1e11, 8.1e10, 0.08, 0.06);
//   auto head = pkmopt::make_tripod_3prs(z3);
//   head->analyze(*head->make_data(), pose, pkmopt::Wrench::Zero(), m);  //
//   data.matrices.compliance: finite
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "models/core/capabilities.hpp"
#include "models/core/machine.hpp"
#include "models/core/pose.hpp"
#include "models/dynamics/leg_dynamics.hpp"
#include "models/dynamics/machine_dynamics.hpp"
#include "models/dynamics/mass_model.hpp"
#include "models/geometry/leg_interference.hpp"
#include "models/geometry/solid_bodies.hpp"
#include "models/stiffness/compliance_chain.hpp"
#include "models/stiffness/virtual_joint.hpp"

namespace pkmopt {

enum class LegKind { kUPS, kPUS, kRUS };
enum class PlatformMobility { kSixDof, kTranslational, kSchoenflies, kPlanarLegs };

/// One leg of a leg-chain machine. Units: m, rad, N/m, Pa, m^2.
struct LegChainLeg {
  LegKind kind = LegKind::kUPS;
  /// UPS: the base joint a_i; PUS: the guide point g_i (carriage joint at q = 0); RUS: the crank
  /// pivot o_i. Base frame.
  Eigen::Vector3d base_point = Eigen::Vector3d::Zero();
  /// PUS: guide direction u_i; RUS: crank axis w_i. Normalised by the machine.
  Eigen::Vector3d axis = Eigen::Vector3d::UnitZ();
  /// RUS: crank direction d_i at q = 0 (made orthogonal to the axis and normalised).
  Eigen::Vector3d crank_zero = Eigen::Vector3d::UnitX();
  double crank_length = 0.0;  ///< RUS: r_i (m)
  double link_length = 0.0;   ///< PUS, RUS: constant strut / rod length L_i (m)
  Eigen::Vector3d platform_point = Eigen::Vector3d::Zero();  ///< b_i, platform frame (m)
  double q_min = 0.0;  ///< actuator range: leg length (UPS), carriage travel (PUS), angle (RUS)
  double q_max = 0.0;
  int branch = 1;  ///< +1: the IK solution with B_i > 0; -1: B_i < 0 (PUS, RUS)

  // Stiffness: link axial stiffness (axial_stiffness > 0, else E * area * rods / length) in
  // series with the actuator (0 = rigid actuator; N/m, or N*m/rad for RUS).
  double axial_stiffness = 0.0;
  double E = 0.0;
  double area = 0.0;
  int rods = 1;  ///< parallel rods of the link (2 for a parallelogram pair)
  double actuator_stiffness = 0.0;
  /// The actuator's drive train in series with actuator_stiffness
  /// (models/stiffness/compliance_chain.hpp): ball screw (free length linear in q over [q_min,
  /// q_max]), nut, bearing and motor torsion (N·m/rad through the lead); a revolute actuator takes
  /// the torsion only.
  ScrewDrive drive{};
  double base_joint_stiffness = 0.0;      ///< axial stiffness of each rod's base-side joint (N/m)
  double platform_joint_stiffness = 0.0;  ///< ... of each rod's platform joint (N/m)

  // Link compliance beyond the axial model (docs/stiffness.md, "Link compliance"); any of these
  // switches the machine to the virtual-joint model. Local beam axes: x along the link, y = the
  // plane normal (planar legs) or the crank axis (crank); for U-S links the bending cannot enter.
  /// Section of one strut / rod (`rods` equal links on one line share the load); its E * A
  /// replaces axial_stiffness, E and area.
  std::optional<BeamSection> link_section{};
  /// RUS: section of the crank (from the pivot to the elbow); unset: a rigid crank.
  std::optional<BeamSection> crank_section{};
  /// rods == 2 (PUS, RUS legs of translational or Schoenflies platforms): the distance between
  /// the two rods of the pair along the bars (m); 0: the pair acts on one line (the axial model).
  double parallelogram_width = 0.0;
  /// Direction of the pair's bars (base frame; the platform bar stays parallel). Zero: the crank
  /// axis (RUS), the rotation axis (Schoenflies); PUS legs of translational platforms give it.
  Eigen::Vector3d parallelogram_axis = Eigen::Vector3d::Zero();

  // Joint limits (+inf: unlimited). base_axis: base frame (UPS, PUS), crank frame at q = 0 (RUS).
  double base_max_angle = std::numeric_limits<double>::infinity();
  double platform_max_angle = std::numeric_limits<double>::infinity();
  Eigen::Vector3d base_axis = Eigen::Vector3d::UnitZ();
  Eigen::Vector3d platform_axis = -Eigen::Vector3d::UnitZ();

  /// kPlanarLegs: normal n_i of the leg's plane (the axis of its passive revolute joint), base
  /// frame; the plane passes through base_point. Normalised by the machine; the actuated point's
  /// path must lie in the plane (PUS: axis . n = 0; RUS: crank axis parallel to n).
  Eigen::Vector3d plane_normal = Eigen::Vector3d::UnitY();
};

/// The links' outer shape and the solids for the interference check
/// (models/geometry/leg_interference.hpp, models/geometry/solid_bodies.hpp). Every link is a
/// capsule from joint centre to joint centre; links of one leg are not checked against each other;
/// carriages and guides are not checked. No diameter given: not checked.
struct LinkShapes {
  /// Each strut or rod (each rod of a parallelogram pair, parallelogram_width apart) and each
  /// UPS leg (m); 0: not given.
  double link_diameter = 0.0;
  double crank_diameter = 0.0;  ///< RUS: the crank from its pivot to the elbow (m); 0: not given
  /// m: with a shape, a pose is reachable only when leg_clearance >= min_clearance.
  double min_clearance = 0.0;
  MachineBodies bodies;  ///< platform and base plates, tool; need a link shape
  bool present() const { return link_diameter > 0.0 || crank_diameter > 0.0; }
};

/// Everything that defines a leg-chain machine. Validated by the LegChainMachine constructor.
struct LegChainDesign {
  std::string model = "leg_chain";  ///< reported by Machine::model()
  PlatformMobility mobility = PlatformMobility::kSixDof;
  /// 6 (kSixDof), 3 (kTranslational, kPlanarLegs) or 4 (kSchoenflies)
  std::vector<LegChainLeg> legs;
  /// kSchoenflies: the platform's rotation axis e, base frame (normalised by the machine).
  Eigen::Vector3d rotation_axis = Eigen::Vector3d::UnitZ();
  Eigen::Vector3d tcp = Eigen::Vector3d::Zero();  ///< TCP in the platform frame (m)
  /// L in J_h; when empty, the mean distance from the TCP to the platform points.
  std::optional<double> characteristic_length;
  /// Half-width of the actuator error box (m, or rad for RUS legs).
  double actuator_error = 1e-5;
  /// Default FK start (and the pose the named models are built around).
  Pose home;
  /// Platform and leg masses (models/dynamics/mass_model.hpp: UPS cylinder and rod, PUS carriage
  /// and link, RUS crank and link); `present` false: none (no natural frequencies).
  MassModel
      masses;  /// The links' shape and the solids for the interference check; none: not checked.
  LinkShapes shapes;
};

/// Throws std::invalid_argument naming the key unless the link diameters and min_clearance are
/// finite and >= 0, a crank diameter has a RUS leg, and the solids are valid and have a link
/// shape to be checked against.
void check_link_shapes(const LegChainDesign& design);

/// Per-thread scratch space and the last results of a leg-chain machine.
class LegChainData : public MachineData {
 public:
  Eigen::Matrix<double, 3, Eigen::Dynamic, 0, 3, 6> s;  ///< unit leg vectors, base frame
  Eigen::Matrix<double, 3, Eigen::Dynamic, 0, 3, 6> r;  ///< R (b_i - tcp)
  Eigen::Matrix<double, 3, Eigen::Dynamic, 0, 3, 6> c;  ///< actuated points c_i(q_i)
  Eigen::Matrix<double, Eigen::Dynamic, 1, 0, 6, 1> q;  ///< actuator coordinates
  Eigen::Matrix<double, Eigen::Dynamic, 1, 0, 6, 1> B;  ///< diag of B
  Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, 6, 6> A;  ///< m x m
  Eigen::Matrix<double, 6, Eigen::Dynamic, 0, 6, 6> T;  ///< full twist = T * DOF twist (6 x m)
  Eigen::Matrix<double, Eigen::Dynamic, 1, 0, 6, 1> k;  ///< axial leg stiffness (N/m)
  /// The actuator side of each leg's compliance chain (m/N, rad/(N*m) for RUS; 0 = rigid) ...
  Eigen::Matrix<double, Eigen::Dynamic, 1, 0, 6, 1> actuator_compliance;
  /// ... and the link side (rods and joints, m/N, along s_i).
  Eigen::Matrix<double, Eigen::Dynamic, 1, 0, 6, 1> link_compliance;
  Eigen::Vector3d position = Eigen::Vector3d::Zero();      ///< TCP position actually used
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();  ///< platform rotation actually used
  bool pose_ok = true;  ///< the given rotation is one the platform can take (parasitic solved)
  bool constraint_singular = false;  ///< planar legs: G_p singular (T undefined)
  bool ik_ok = true;                 ///< every leg's IK exists
  bool serial_singular = false;      ///< some |B_i| numerically 0
  bool parallel_singular = false;    ///< A numerically singular
  double det_a = 0.0;
  double det_b = 0.0;
  Eigen::Matrix3d compliance_tt = Eigen::Matrix3d::Zero();  ///< C_tt of the last analyze (m/N)
  /// TCP position error per actuator error of the last analyze (3 x m, m): actuator_error times
  /// the position rows of T J^-1.
  Eigen::Matrix<double, 3, Eigen::Dynamic, 0, 3, 6> error_map;
};

/// A leg-chain machine. Immutable; share it between threads, give each a LegChainData.
class LegChainMachine final : public Machine,
                              public ParasiticMotion,
                              public Dynamics,
                              public TranslationalMaps {
 public:
  /// Validates the design; throws std::invalid_argument naming the offending field.
  explicit LegChainMachine(const LegChainDesign& design);

  const LegChainDesign& design() const { return design_; }
  int dof() const { return dof_; }
  double characteristic_length() const { return characteristic_length_; }

  std::string_view model() const override { return design_.model; }
  int num_actuators() const override { return static_cast<int>(design_.legs.size()); }
  bool revolute_actuators() const override { return revolute_; }
  std::optional<double> actuator_stroke(int i) const override {
    if (i < 0 || i >= num_actuators()) return std::nullopt;
    const LegChainLeg& leg = design_.legs[static_cast<std::size_t>(i)];
    return leg.q_max - leg.q_min;
  }
  std::unique_ptr<MachineData> make_data() const override;
  void analyze(MachineData& data, const Pose& pose, const Wrench& wrench,
               PoseMetrics& out) const override;
  bool reachable(MachineData& data, const Pose& pose) const override;
  FkResult forward_kinematics(const Eigen::VectorXd& q, const std::optional<Pose>& guess,
                              const FkOptions& options = {}) const override;
  std::optional<Eigen::AlignedBox3d> workspace_search_box(
      const std::vector<Eigen::Matrix3d>& orientations) const override;
  std::optional<double> envelope_volume() const override;
  std::string actuator_coordinates_requirement(const Eigen::VectorXd& q) const override;
  /// Each leg at the pose: a PUS guide over its travel and the carriage, a RUS crank, a UPS
  /// leg from its base joint, then the link to the platform joint; the tool.
  bool sketch(MachineData& data, const Pose& pose, MachineSketch& out) const override;
  bool checks_leg_interference() const override { return design_.shapes.present(); }
  /// The largest excess over an actuator range, a joint-angle limit or the links' minimum
  /// clearance at (the actual pose of) a pose (models/core/machine.hpp).
  std::optional<double> reach_excess(const Pose& pose) const override;
  /// This machine when its legs are planar (parasitic x, y, rz), else null.
  const ParasiticMotion* parasitic_motion() const override {
    return design_.mobility == PlatformMobility::kPlanarLegs ? this : nullptr;
  }
  /// T of the last analyze or twist_jacobian with `data` (the DOF twist columns).
  Eigen::MatrixXd twist_basis(const MachineData& data) const override;
  /// The links' clearance at a pose (with each other and with the solids; +inf without a link
  /// shape or where a leg cannot close).
  Clearance leg_clearance(const Pose& pose) const;
  /// ... from the kinematics in `data` (compute_kinematics).
  Clearance clearance_from_kinematics(const LegChainData& data) const;
  /// Whether the links keep min_clearance, decided faster than clearance_from_kinematics.
  bool links_apart(const LegChainData& data) const;
  /// Present with a mass model (the machine file's `masses`).
  Capability<Dynamics> dynamics() const override {
    if (!design_.masses.present)
      return Capability<Dynamics>::missing("the machine file has no 'masses'");
    return this;
  }
  int natural_frequency_count() const override {
    return design_.masses.present ? num_actuators() : 0;
  }
  const MassModel& mass_model() const override { return design_.masses; }
  double moving_mass() const override;
  /// The full-twist TCP mass matrix at actual_pose(pose); only its restriction T^T M T to the
  /// platform's own twists is meaningful.
  bool mass_matrix(MachineData& data, const Pose& pose, Matrix6d& M) const override;
  bool mode_shapes(MachineData& data, const Pose& pose, PoseModes& out) const override;
  /// At actual_pose(pose), with xi and xi_dot projected on the platform's own twists (T T^+);
  /// for planar legs (3-PRS) the rate of T (the parasitic motion's own acceleration) is not
  /// included (docs/dynamics.md).
  bool dynamic_wrench(MachineData& data, const Pose& pose, const Vector6d& xi,
                      const Vector6d& xi_dot, Wrench& w_dyn) const override;
  /// As dynamic_wrench (projected on the platform's own twists).
  bool carried_dynamics(MachineData& data, const Pose& pose, const Vector6d& xi,
                        const Vector6d& xi_dot, const Eigen::Vector3d& gravity, Wrench& w_dyn,
                        Eigen::Vector3d& net_force,
                        Eigen::Matrix<double, 9, 9>* kinetic) const override;
  bool inverse_dynamics(MachineData& data, const Pose& pose, const Vector6d& xi,
                        const Vector6d& xi_dot, const Wrench& wrench,
                        PoseMetrics& out) const override {
    return static_inverse_dynamics(*this, *this, data, pose, xi, xi_dot, wrench, out);
  }
  /// Row i: [s_i^T, (r_i x s_i)^T] / B_i at actual_pose(pose) (false when a leg cannot close or
  /// some B_i = 0). Along the platform's own twists xi = T eta it gives q_dot = J eta.
  bool twist_jacobian(MachineData& data, const Pose& pose, Eigen::MatrixXd& J) const override;
  /// C_tt and actuator_error * (position rows of T J^-1), from analyze.
  const TranslationalMaps* translational_maps() const override { return this; }
  bool analyze_with_maps(MachineData& data, const Pose& pose, const Wrench& wrench,
                         PoseMetrics& metrics, Eigen::Matrix3d& compliance_tt,
                         Eigen::Matrix<double, 3, Eigen::Dynamic>& error_map) const override;

  /// Closed-form IK of every leg on its branch (at actual_pose(pose)); nullopt when a leg cannot
  /// close or the parasitic motion cannot be solved.
  std::optional<Eigen::VectorXd> inverse_kinematics(const Pose& pose) const;
  /// The TCP pose the platform takes when asked for `pose`: unchanged (6-DOF), R = I
  /// (translational), R = Rot(e, phi) with phi the twist of R about e (Schoenflies), the
  /// parasitic x, y, rz solved from z, rx, ry (planar legs). nullopt when the parasitic solve
  /// fails.
  std::optional<Pose> actual_pose(const Pose& pose) const override;
  /// Index of the first rotational platform DOF (DOF twist columns from there on are angular
  /// velocities): 3 (6-DOF, Schoenflies), dof() (translational: none), 1 (planar legs).
  int first_rotational_dof() const { return first_rotational_dof_; }
  /// The actuated point c_i(q) and its derivative dc_i/dq.
  void actuated_point(int leg, double q, Eigen::Vector3d& c, Eigen::Vector3d& dc) const;
  /// Kinematics at a pose into data (q by IK, s, r, c, A, B, singularity flags); returns the
  /// platform rotation used. Joint limits and ranges are not checked.
  void compute_kinematics(LegChainData& data, const Pose& pose) const;
  /// The m x m matrices A and B = diag(B_i) and J = B^-1 A at a pose (empty J if det B = 0).
  void jacobians(const Pose& pose, Eigen::MatrixXd& A, Eigen::MatrixXd& B,
                 Eigen::MatrixXd& J) const;
  /// The 6 x m map T from the DOF twist to the full TCP twist at (the actual pose of) a pose.
  Eigen::MatrixXd twist_map(const Pose& pose) const;
  /// Reachability from computed kinematics (ranges, IK existence, joint limits, orientation).
  bool reachable_from_kinematics(const LegChainData& data, const Pose& pose) const;
  /// Base-side and platform joint angles (rad) of every leg at a pose.
  void joint_angles(const Pose& pose, Eigen::VectorXd& base_angles,
                    Eigen::VectorXd& platform_angles) const;

  /// Whether analyze uses the virtual-joint model (some leg has a section or a pair width).
  bool link_compliance_model() const { return vjm_; }
  /// ... and whether its stiffness holds all six directions (else the mobility's T holds the
  /// orientation: translational and Schoenflies machines without parallelogram widths).
  bool link_compliance_full() const { return vjm_full_; }
  /// The virtual-joint description of leg i at the kinematics in `data` (compute_kinematics and
  /// the actuator compliance of analyze): its springs and beams, with `passive_joints` its
  /// passive joints and rod groups (for VjmLeg::stiffness), and the wrenches it transmits (for
  /// VjmLeg::stiffness_for_wrenches, the closed-form elimination analyze uses). Throws
  /// std::invalid_argument on a degenerate leg geometry.
  void vjm_leg(const LegChainData& data, int leg, VjmLeg& out, TransmittedWrenches& wrenches,
               bool passive_joints = true) const;
  /// The sum of the legs' VJM stiffness at the TCP (6x6, base axes) at the kinematics in `data`;
  /// false when a leg's geometry is degenerate or a leg is rigid along a wrench it carries.
  bool vjm_stiffness(const LegChainData& data, Matrix6d& K) const;

 private:
  /// The actual TCP position and platform rotation of a pose; false when the pose's rotation is
  /// not one the platform can take (it is projected) or the parasitic solve failed.
  bool resolve_pose(const Pose& pose, Eigen::Vector3d& position, Eigen::Matrix3d& R) const;
  /// Plane constraint residuals h_i and the 6 x m twist map at a platform pose (planar legs);
  /// false when G_p is singular.
  bool planar_twist_map(const Eigen::Vector3d& p, const Eigen::Matrix3d& R,
                        Eigen::Matrix<double, 6, Eigen::Dynamic, 0, 6, 6>& T) const;
  /// The home pose moved by the mean displacement of the actuated points from home to q.
  Pose default_fk_start(const Eigen::VectorXd& q) const;
  double leg_ik(int leg, const Eigen::Vector3d& platform_point, bool& ok) const;
  /// The legs' joint points at the kinematics in `d` (models/leg_chain/leg_chain_dynamics.cpp).
  std::vector<LegPoints> leg_points(const LegChainData& d) const;
  /// With masses: the natural modes from d.matrices.compliance on the DOF (models/
  /// leg_chain_dynamics.cpp); the shapes (DOF coordinates) only when `shapes` is set.
  NaturalModes natural_modes_of(const LegChainData& d, bool shapes) const;
  /// compliance (into d.matrices), tcp_deflection, tcp_rotation_deflection,
  /// stiffness_min_direction and stiffness_min_loaded of a non-singular pose, from the rod forces
  /// f (models/leg_chain/leg_chain_compliance.cpp).
  void compute_compliance_metrics(LegChainData& d,
                                  const Eigen::Matrix<double, Eigen::Dynamic, 1, 0, 6, 1>& f,
                                  const Wrench& wrench, PoseMetrics& out) const;
  /// The geometric stiffness on the full twist of the rod forces f (every leg, its actuated point
  /// fixed) and, for planar legs, of the plane constraints' reactions (models/
  /// leg_chain_compliance.cpp).
  Matrix6d full_twist_geometric_stiffness(
      const LegChainData& d, const Eigen::Matrix<double, Eigen::Dynamic, 1, 0, 6, 1>& f,
      const Wrench& wrench) const;
  /// The VJM step of analyze (models/leg_chain/leg_chain_vjm.cpp): stiffness_min, d.compliance_tt
  /// and, with d.compliance_metrics, the compliance metrics; false when the stiffness is not
  /// positive definite.
  bool compute_vjm_metrics(LegChainData& d,
                           const Eigen::Matrix<double, Eigen::Dynamic, 1, 0, 6, 1>& f,
                           const Wrench& wrench, PoseMetrics& out) const;
  /// Checks the link sections and parallelogram widths of the design and sets vjm_, vjm_full_
  /// (models/leg_chain/leg_chain_vjm.cpp).
  void validate_link_compliance();

  LegChainDesign design_;
  int dof_ = 6;
  int first_rotational_dof_ = 3;
  bool revolute_ = false;
  double characteristic_length_ = 1.0;
  Eigen::Matrix<double, 3, Eigen::Dynamic> platform_rel_;  // b_i - tcp
  Eigen::Vector3d home_leg_offset_ = Eigen::Vector3d::Zero();
  bool home_ik_ok_ = false;
  bool vjm_ = false;
  bool vjm_full_ = false;
};

/// Builds the machine of a design (a factory for design studies). Throws std::invalid_argument.
std::unique_ptr<Machine> make_leg_chain_machine(const LegChainDesign& design);

// ---------------------------------------------------------------------------------------------
// Named models. Each parametric struct documents its parameters; `*_design` turns it into a
// LegChainDesign, `make_*` into a machine. docs/machines.md has sketches.

/// Stiffness data shared by the named models.
struct LinkStiffness {
  double axial_stiffness = 0.0;           ///< N/m per link (used when > 0)
  double E = 2.1e11;                      ///< Pa
  double area = 1.0e-4;                   ///< m^2 per rod
  double actuator_stiffness = 0.0;        ///< N/m (prismatic) or N*m/rad (revolute); 0 = rigid
  ScrewDrive drive{};                     ///< the actuator's drive train (LegChainLeg::drive)
  double base_joint_stiffness = 0.0;      ///< N/m per rod; 0 = rigid
  double platform_joint_stiffness = 0.0;  ///< N/m per rod; 0 = rigid
  /// Section of one link (LegChainLeg::link_section): its E * A replaces axial_stiffness, E and
  /// area; bending enters the tripod's struts (the others are U-S or S-S links).
  std::optional<BeamSection> section{};
  double parallelogram_width = 0.0;  ///< m, deltas' rod pairs (LegChainLeg::parallelogram_width)
};

/// Rotary (Clavel) delta, docs/conventions.md: pivots at base_radius, azimuth -90+120(i-1) deg,
/// cranks of length upper_arm in the vertical plane through the centre, theta = 0 horizontal
/// outwards, positive theta lowers the elbow; parallelogram rods of length rod to platform
/// points at platform_radius on the same azimuth; platform below the base (z < 0).
/// The defaults are the ABB IRB 360 dimensions used by R. L. Williams II, "The Delta Parallel
/// Robot: Kinematics Solutions" (2015): wB = 0.164, uP = 0.044, L = 0.524, l = 1.244 m.
struct DeltaDesign {
  double base_radius = 0.164;            ///< m, centre to each drive pivot
  double platform_radius = 0.044;        ///< m, TCP to each rod-pair centre on the platform
  double upper_arm = 0.524;              ///< m, crank length
  double rod = 1.244;                    ///< m, parallelogram rod length
  double theta_min = -60.0 * kDegToRad;  ///< rad, drive range
  double theta_max = 100.0 * kDegToRad;
  int branch = 1;                                        ///< +1 elbow-out (default), -1 elbow-in
  LinkStiffness stiffness{.E = 7.0e10, .area = 5.0e-5};  ///< rods: 2 per parallelogram
  std::optional<BeamSection> crank_section{};            ///< the upper arm; unset: rigid
  double elbow_max_angle = std::numeric_limits<double>::infinity();     ///< rad
  double platform_max_angle = std::numeric_limits<double>::infinity();  ///< rad
  Eigen::Vector3d tcp = Eigen::Vector3d::Zero();
  std::optional<double> characteristic_length;
  double actuator_error = 1e-3 * kDegToRad;  ///< rad
  MassModel masses;                          ///< platform and leg masses (LegChainDesign::masses)
  LinkShapes shapes;                         ///< interference check (LegChainDesign::shapes)
};
LegChainDesign delta_design(const DeltaDesign& d);
std::unique_ptr<Machine> make_delta(const DeltaDesign& d);

/// Linear delta: three carriages on guides at azimuths -90 + 120 (i - 1) deg, each guide in the
/// vertical plane through the centre, passing through (guide_radius, azimuth, 0) and inclined
/// by `inclination` from the vertical towards the centre (0 = vertical guides, a Kossel-type
/// printer); q_i = carriage travel along the guide (m, upwards positive from z = 0).
/// Parallelogram rods of length rod join each carriage to the platform at platform_radius;
/// the platform hangs below the carriages.
struct LinearDeltaDesign {
  double guide_radius = 0.25;     ///< m
  double platform_radius = 0.04;  ///< m
  double rod = 0.35;              ///< m
  double inclination = 0.0;       ///< rad, guide tilt towards the centre
  double q_min = 0.0;             ///< m, carriage stroke
  double q_max = 0.6;
  LinkStiffness stiffness{.E = 7.0e10, .area = 3.0e-5, .actuator_stiffness = 2.0e7};
  double carriage_max_angle = std::numeric_limits<double>::infinity();  ///< rad
  double platform_max_angle = std::numeric_limits<double>::infinity();  ///< rad
  Eigen::Vector3d tcp = Eigen::Vector3d::Zero();
  std::optional<double> characteristic_length;
  double actuator_error = 1e-5;  ///< m
  MassModel masses;              ///< platform and leg masses (LegChainDesign::masses)
  LinkShapes shapes;             ///< interference check (LegChainDesign::shapes)
};
LegChainDesign linear_delta_design(const LinearDeltaDesign& d);
std::unique_ptr<Machine> make_linear_delta(const LinearDeltaDesign& d);

/// Hexaglide (6-PUS): six carriages on guides parallel to the base x axis (optionally inclined
/// by `inclination` about the y axis), guide i at lateral position guide_y[i], height
/// guide_z[i]; struts of length strut join carriage i to platform joint b_i. Carriage i sits on
/// the -x side of its platform joint for b_i.x < 0 and on the +x side otherwise (splayed
/// struts). q_i = carriage position along the guide (m, from x = 0).
/// Defaults: b_i = the semi-regular hexagon of docs/conventions.md (radius 0.25, pair separation
/// 20 deg) turned by 90 deg about z (three joints on each side of x = 0), guide_y[i] =
/// b_i.y +- 0.3 (outwards). (Guides with guide_y proportional to b_i.y are singular: a turn about
/// x with a y translation keeps every strut length.)
struct HexaglideDesign {
  std::array<double, 6> guide_y{};
  std::array<double, 6> guide_z{0, 0, 0, 0, 0, 0};
  double inclination = 0.0;  ///< rad
  double strut = 0.8;        ///< m
  Eigen::Matrix<double, 3, 6> platform_joints;
  double q_min = -1.2;  ///< m
  double q_max = 1.2;
  LinkStiffness stiffness{.E = 2.1e11, .area = 3.0e-4, .actuator_stiffness = 2.0e8};
  double carriage_max_angle = std::numeric_limits<double>::infinity();  ///< rad
  double platform_max_angle = std::numeric_limits<double>::infinity();  ///< rad
  Eigen::Vector3d tcp = Eigen::Vector3d::Zero();
  std::optional<double> characteristic_length;
  double actuator_error = 1e-5;  ///< m
  double home_height = 0.6;      ///< m, z of the home pose (FK start)
  HexaglideDesign();
  MassModel masses;   ///< platform and leg masses (LegChainDesign::masses)
  LinkShapes shapes;  ///< interference check (LegChainDesign::shapes)
};
LegChainDesign hexaglide_design(const HexaglideDesign& d);
std::unique_ptr<Machine> make_hexaglide(const HexaglideDesign& d);

/// 3-PRS tripod head like the DS Technologie Sprint Z3: three slides parallel to the head axis
/// at base_radius, azimuths -90 + 120 (i - 1) deg; each carriage carries a revolute joint whose
/// axis is horizontal and tangential (n_i = (-sin a_i, cos a_i, 0)), so strut i (constant length
/// `strut`) stays in the vertical plane through the head axis and slide i; a spherical joint at
/// platform_radius joins it to the platform. Base frame (docs/conventions.md, tripods): z along the
/// slides from the base towards the platform (for a head hanging from a gantry z points down,
/// towards the workpiece); q_i = carriage position along +z (m). The platform is on the +z side of
/// the carriages (branch +1); the TCP is tool_length beyond the platform centre along the
/// platform's +z (tcp = (0, 0, tool_length)). DOF (z, rx, ry); x, y, rz parasitic
/// (kPlanarLegs). Defaults: base_radius 0.30, platform_radius 0.15, strut 0.55, stroke
/// [0, 0.95] m, tool_length 0.20 m - they reach rx, ry within +-40 deg over a Z travel of more
/// than 670 mm (docs/machines.md gives the figures).
struct Tripod3PrsDesign {
  double base_radius = 0.30;      ///< m, head axis to each slide
  double platform_radius = 0.15;  ///< m, platform centre to each spherical joint
  double strut = 0.55;            ///< m
  double q_min = 0.0;             ///< m, slide stroke
  double q_max = 0.95;
  double tool_length = 0.20;                     ///< m, TCP beyond the platform centre
  double revolute_max_angle = 50.0 * kDegToRad;  ///< rad, strut from the slide's +z
  double platform_max_angle = 70.0 * kDegToRad;  ///< rad, strut from the platform normal
  LinkStiffness stiffness{.E = 2.1e11,
                          .area = 6.0e-4,
                          .actuator_stiffness = 2.0e8};  ///< struts (steel), ball-screw drives
  std::optional<double> characteristic_length;
  double actuator_error = 1e-5;  ///< m
  MassModel masses;              ///< platform and leg masses (LegChainDesign::masses)
  LinkShapes shapes;             ///< interference check (LegChainDesign::shapes)
};
LegChainDesign tripod_3prs_design(const Tripod3PrsDesign& d);
std::unique_ptr<Machine> make_tripod_3prs(const Tripod3PrsDesign& d);

/// 3-RPS tripod head like the A3 head: the 3-PRS head's joints in the other order. Three
/// revolute joints fixed in the base at base_radius, azimuths -90 + 120 (i - 1) deg, their axes
/// horizontal and tangential (n_i = (-sin a_i, cos a_i, 0)), each carrying a telescopic leg of
/// length q_i in [min_length, max_length] (the actuator) that stays in the vertical plane through
/// the head axis and its joint; a spherical joint at platform_radius joins it to the platform.
/// Same base frame, TCP and parasitic motion as the 3-PRS head (a platform point in a vertical
/// plane through the head axis: x, y, rz follow from z, rx, ry alone, as Carretero, Podhorodeski,
/// Nahon & Gosselin, J. Mech. Design 122(1), 2000, give for the 3-RPS): DOF (z, rx, ry)
/// (kPlanarLegs, UPS legs). Defaults: the 3-PRS head's radii and tool, legs 0.55-1.35 m.
struct Tripod3RpsDesign {
  double base_radius = 0.30;      ///< m, head axis to each base revolute joint
  double platform_radius = 0.15;  ///< m, platform centre to each spherical joint
  double q_min = 0.55;            ///< m, leg length range
  double q_max = 1.35;
  double tool_length = 0.20;                     ///< m, TCP beyond the platform centre
  double revolute_max_angle = 50.0 * kDegToRad;  ///< rad, leg from the base's +z
  double platform_max_angle = 70.0 * kDegToRad;  ///< rad, leg from the platform normal
  LinkStiffness stiffness{.E = 2.1e11,
                          .area = 6.0e-4,
                          .actuator_stiffness = 2.0e8};  ///< legs (steel), ball-screw drives
  std::optional<double> characteristic_length;
  double actuator_error = 1e-5;  ///< m
  MassModel masses;              ///< platform and leg masses (LegChainDesign::masses)
  LinkShapes shapes;             ///< interference check (LegChainDesign::shapes)
};
LegChainDesign tripod_3rps_design(const Tripod3RpsDesign& d);
std::unique_ptr<Machine> make_tripod_3rps(const Tripod3RpsDesign& d);

}  // namespace pkmopt
