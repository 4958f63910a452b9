// Link compliance of the legs of a parallel machine by the virtual-joint method (VJM):
// A. Pashkevich, D. Chablat, P. Wenger, "Stiffness analysis of overconstrained parallel
// manipulators", Mech. Mach. Theory 44 (2009); A. Klimchik, A. Pashkevich, D. Chablat,
// "Fundamentals of manipulator stiffness modeling using matrix structural analysis", Mech. Mach.
// Theory 133 (2019).
//
// Conventions (docs/conventions.md): SI units, base frame, twists [v; omega] (the velocity of the
// reference point, then the angular velocity, base axes), wrenches [f; m] (force, then moment
// about the reference point). A 6x6 stiffness K maps a small twist-displacement dx = [dp; dtheta]
// of the reference point to the wrench w = K dx that holds it; a compliance C maps w to dx. Units
// of K: N/m (force/translation), N/rad and N*m/m (coupling), N*m/rad (moment/rotation).
//
// Moving the reference point from a to b (d = b - a, [d]x the cross-product matrix):
//   twist   dx_b = X dx_a,  X = [I, -[d]x; 0, I]       (twist_transform(a, b))
//   wrench  w_b = X^-T w_a, X^-T = [I, 0; -[d]x, I]    (wrench_transform(a, b))
//   K_b = X^-T K_a X^-1 (move_stiffness),   C_b = X C_a X^T (move_compliance).
//
// Beam (Euler-Bernoulli, clamped at its start, loaded at its tip): local frame at the tip with
// x along the beam, y the given second axis, z = x cross y. Iy (Iz) is the second moment of area
// about y (z): Iz resists deflection along y, Iy along z. Tip compliance, local [u; theta]:
//   u_x = L/EA f_x,  theta_x = L/GJ m_x,
//   [u_y; theta_z] = [L^3/3EIz, L^2/2EIz; L^2/2EIz, L/EIz] [f_y; m_z],
//   [u_z; theta_y] = [L^3/3EIy, -L^2/2EIy; -L^2/2EIy, L/EIy] [f_z; m_y].
// In a leg the beam is replaced by six independent virtual springs (the same tip compliance):
// a translation along x (L/EA), a rotation about x (L/GJ), rotations about y and z through the
// mid-point (L/EIy, L/EIz) and translations along z and y (L^3/12EIy, L^3/12EIz).
//
// Leg (a serial chain from the base to the platform attachment, all at the current pose, base
// frame). The elements, in any order (only the geometry matters at one pose):
//   rigid link           nothing to add: the chain is given by the joints' points and axes;
//   elastic beam         add_beam: six virtual springs as above;
//   actuated joint       add_actuated_prismatic / add_actuated_revolute: one virtual spring with
//                        compliance 1/k along / about the joint axis (k = 0: rigid, no spring);
//   passive joint        add_prismatic, add_revolute, add_universal (2 revolutes), add_spherical
//                        (3 revolutes about the base axes through the centre);
//   elastic joint        add_elastic_joint: a 6x6 compliance at a point (e.g. ball_joint_compliance
//                        for a ball joint's own axial and radial stiffness);
//   two-force members    add_two_force_members: rods with ball joints at both ends between the
//                        previous body and the next (one rod, or the two parallel rods of a
//                        parallelogram). They carry only the axial forces f_j along their lines:
//                        the wrench is w = Z f (column j of Z: zeta_j = [s_j; (a_j - ref) x s_j]),
//                        elongation zeta_j^T dx = f_j / k_j; every twist with Z^T t = 0 is free.
// Each unit joint motion is a twist at the reference point: prismatic [u; 0], revolute about u
// through c [(c - ref) x u; u]. With J_theta (6 x n_theta) the virtual springs' twists,
// K_theta = diag(k) and J_q (6 x n_q) the passive joints' twists, the chain with its passive
// joints locked has the compliance
//   S = J_theta K_theta^-1 J_theta^T  (+ elastic joints and rod groups, moved to ref),
// and with them free (the kinetostatic model of Pashkevich 2009) [S, J_q; J_q^T, 0] [w; dq] =
// [dx; 0] (twist compatibility, and J_q^T w = 0: no passive joint loaded), so
//   K_leg = top-left 6x6 block of [S, J_q; J_q^T, 0]^-1.
// Computed stably without the block inverse: the leg transmits the wrenches w with J_q^T w = 0,
// i.e. w = N y with N an orthonormal basis of null(J_q^T) (Householder QR with column pivoting of
// J_q), and then N^T S N y = N^T dx, so
//   K_leg = N (N^T S N)^-1 N^T   (pivoted Cholesky of the small N^T S N; K_leg = Y Y^T is
//                                  symmetric positive semi-definite by construction).
// Dependent passive joints (J_q rank-deficient, where the block matrix is singular) are handled
// by the rank-revealing QR: a twist already spanned adds nothing (the joint motions are not
// unique but the wrench is). The computation runs in scaled units (translations divided by a
// characteristic length L, the largest distance of a joint point to ref) so that the rank
// decisions do not depend on the unit of length. When N^T S N is singular the chain has no
// compliance at all for some wrench it transmits (its elements are rigid along it): the stiffness
// is infinite there; `rigid` is set and `stiffness` holds N (N^T S N)^+ N^T (pseudo-inverse by an
// eigen-decomposition), the stiffness for the twists that do not deform the rigid directions (the
// reactions along those are undetermined). The caller must treat the rigid directions as
// kinematic constraints: `stiffness` alone understates the leg.
//
// The platform stiffness is the sum of the legs' stiffness at one reference point
// (platform_stiffness); a two-force member as a leg of its own (a hexapod's UPS leg, a rod
// between base and platform) contributes k zeta zeta^T (two_force_member_stiffness), and a UPS leg
// modelled as universal joint, actuator and elastic struts and spherical joint reduces exactly to
// it: the struts' bending compliance lies in directions the passive joints free.
//
// Known transmitted wrenches (stiffness_for_wrenches): when the leg's geometry gives a basis W
// (6 x m) of null(J_q^T) in closed form - e.g. a 3-PRS leg transmits the force along its strut and
// the force along its revolute axis, both through the spherical joint: W = [s, n; r x s, r x n]
// - the elimination needs no QR: the leg transmits w = W y, its elements deform by W^T S W y + O y
// (O: the compliance of elements acting on the coordinates y directly, e.g. rods whose lines are
// the columns of W, O = diag(1/k_j)), so K_leg = W (W^T S W + O)^-1 W^T, the same matrix for any
// basis of the same space. The passive joints and rod groups of the leg are then not used (the
// basis and O stand for them); the tests compare both evaluations.
//
// Speed: fixed capacities (kMaxSprings virtual springs, kMaxPassive passive twists, ...), no heap
// allocation; VjmLeg lives on the stack and is rebuilt per pose (clear(), add_*, stiffness()).
//
// Example, one leg of a 3-PRS tripod at a pose (slide along z, revolute axis n at the carriage c,
// steel tube strut from c to the platform point P, spherical joint at P; reference: the TCP):
//   pkmopt::VjmLeg leg;
//   const pkmopt::BeamSection tube = pkmopt::tube_section(2.1e11, 8.1e10, 0.06, 0.04);
//   leg.add_actuated_prismatic(c, Eigen::Vector3d::UnitZ(), 2.0e8);   // ball screw, N/m
//   leg.add_revolute(c, n);
//   leg.add_beam(tube, (P - c).norm(), c, P - c, n);                   // local y = the R axis
//   leg.add_spherical(P);
//   pkmopt::LegCompliance k1 = leg.stiffness(tcp);                     // rank 2
//   // ... the other legs; then
//   pkmopt::Matrix6d K = pkmopt::platform_stiffness(std::array{k1, k2, k3}, tcp);
// A RUS / delta leg: add_actuated_revolute(o, w, k_motor), add_beam(crank section, r, o, e - o, w),
// then add_two_force_members with the rod (or the parallelogram's two rods) from the elbow to the
// platform. A UPS leg: add_universal(a, w1, w2), add_actuated_prismatic(a, s, k_act), add_beam
// for the cylinder and the piston rod, add_spherical(P). A PUS leg: add_actuated_prismatic(c, u,
// k_act), add_universal(c, w1, w2), add_beam for the strut, add_spherical(P) (or, with a rigid-
// in-bending strut, add_two_force_member(c, P, E A / L) after the actuator).
#pragma once

#include <Eigen/Core>
#include <array>
#include <span>

#include "models/core/pose.hpp"

namespace pkmopt {

/// Cross section of a straight beam. E, G: Pa; A: m^2; Iy, Iz: m^4 (about the local y, z axes);
/// J: torsion constant, m^4 (the polar moment for a circular section).
struct BeamSection {
  double E = 0.0;
  double G = 0.0;
  double A = 0.0;
  double Iy = 0.0;
  double Iz = 0.0;
  double J = 0.0;
};

/// G = E / (2 (1 + poisson)) of an isotropic material (Pa).
double shear_modulus(double E, double poisson);

/// A circular tube of outer and inner diameter D, d (m; d = 0: a solid rod):
/// A = pi (D^2 - d^2) / 4, Iy = Iz = pi (D^4 - d^4) / 64, J = 2 Iy. Throws std::invalid_argument
/// unless E, G > 0 and 0 <= d < D.
BeamSection tube_section(double E, double G, double outer_diameter, double inner_diameter = 0.0);

/// The 6x6 tip compliance of a beam of the section and length clamped at its start (local frame
/// at the tip, x along the beam; see the header comment). m/N, 1/N, rad/(N*m).
Matrix6d beam_compliance(const BeamSection& section, double length);

/// [v]x: [v]x w = v x w.
Eigen::Matrix3d cross_product_matrix(const Eigen::Vector3d& v);
/// X with dx_to = X dx_from for the twist of one rigid body at two points.
Matrix6d twist_transform(const Eigen::Vector3d& from, const Eigen::Vector3d& to);
/// X^-T with w_to = X^-T w_from for the same wrench about two points.
Matrix6d wrench_transform(const Eigen::Vector3d& from, const Eigen::Vector3d& to);
/// A stiffness at `from` expressed at `to`: X^-T K X^-1.
Matrix6d move_stiffness(const Matrix6d& K, const Eigen::Vector3d& from, const Eigen::Vector3d& to);
/// A compliance at `from` expressed at `to`: X C X^T.
Matrix6d move_compliance(const Matrix6d& C, const Eigen::Vector3d& from, const Eigen::Vector3d& to);
/// A 6x6 stiffness or compliance given in axes R (columns: the frame's axes in base axes) turned
/// to base axes: diag(R, R) M diag(R, R)^T.
Matrix6d rotate_6x6(const Matrix6d& M, const Eigen::Matrix3d& R);

/// Compliance of a ball joint's own deformation (base axes, at its centre): translational block
/// 1/k_axial along the unit `axis` plus 1/k_radial across it (0: rigid that way), zero rotational
/// blocks (the rotations are the passive joint's: add_spherical at the same point).
Matrix6d ball_joint_compliance(const Eigen::Vector3d& axis, double axial_stiffness,
                               double radial_stiffness);

/// The compliance of a 6x6 stiffness by the Moore-Penrose pseudo-inverse: directions of zero
/// stiffness get zero compliance, so they must be freed by a passive joint of the chain. Uses an
/// eigen-decomposition: compute it once in the joint's own frame and rotate_6x6 it per pose.
Matrix6d compliance_from_stiffness(const Matrix6d& K);

/// k zeta zeta^T, zeta = [s; (b - ref) x s], s = (b - a)/|b - a|: a rod with ball joints at a and b
/// and axial stiffness k (N/m) between base and platform, at `reference`.
Matrix6d two_force_member_stiffness(const Eigen::Vector3d& a, const Eigen::Vector3d& b, double k,
                                    const Eigen::Vector3d& reference);

/// A rod with ball joints at both ends: a on the previous body, b on the next; stiffness N/m
/// (0: rigid).
struct TwoForceMember {
  Eigen::Vector3d a = Eigen::Vector3d::Zero();
  Eigen::Vector3d b = Eigen::Vector3d::UnitX();
  double stiffness = 0.0;
};

/// The wrenches a leg transmits, known from its geometry (VjmLeg::stiffness_for_wrenches).
struct TransmittedWrenches {
  /// 6 x m (m <= 6) independent wrenches at the reference point spanning the wrenches the passive
  /// joints and rod groups do not relieve; columns of one kind and scale (e.g. unit forces along
  /// lines: the rigid test compares their compliances).
  Eigen::Matrix<double, 6, Eigen::Dynamic, 0, 6, 6> basis;
  /// m x m compliance of the elements acting directly on the basis coordinates (a rod's axial
  /// compliance 1/k on the column of its line), or empty (none).
  Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, 6, 6> compliance;
};

/// The Cartesian stiffness of one leg at a reference point.
struct LegCompliance {
  Matrix6d stiffness = Matrix6d::Zero();  ///< K_leg at `reference`, base axes (N/m, N, N*m/rad)
  Eigen::Vector3d reference = Eigen::Vector3d::Zero();
  int constrained_dim = 0;  ///< dimension of the wrench space the leg transmits (rank of K_leg)
  bool rigid = false;       ///< some transmitted wrench meets no compliance (see header comment)
};

/// K_legs summed at `reference` (each moved from its own reference).
Matrix6d platform_stiffness(std::span<const LegCompliance> legs, const Eigen::Vector3d& reference);

/// A leg described element by element at one pose (base frame). Fixed capacity, no heap; the
/// add_* functions throw std::length_error when a capacity is exceeded and std::invalid_argument
/// on a zero axis, a non-positive length or section value, or a negative stiffness. Axes need not
/// be unit vectors.
class VjmLeg {
 public:
  static constexpr int kMaxSprings = 24;       ///< 1-DOF virtual springs (a beam uses 6)
  static constexpr int kMaxPassive = 12;       ///< passive joint axes (a spherical joint uses 3)
  static constexpr int kMaxElasticJoints = 3;  ///< 6x6 joint compliances
  static constexpr int kMaxRodGroups = 2;      ///< add_two_force_members calls
  static constexpr int kMaxRodsPerGroup = 4;   ///< rods in one group
  static constexpr int kMaxPassiveColumns = kMaxPassive + 5 * kMaxRodGroups;
  using PassiveTwists = Eigen::Matrix<double, 6, Eigen::Dynamic, 0, 6, kMaxPassiveColumns>;

  void clear();

  /// An elastic beam from `start` along `x_axis`; `y_axis` (made orthogonal to x) fixes the
  /// section's local y.
  void add_beam(const BeamSection& section, double length, const Eigen::Vector3d& start,
                const Eigen::Vector3d& x_axis, const Eigen::Vector3d& y_axis);
  /// A 1-DOF virtual spring: translation along `axis` (rotational = false) or rotation about the
  /// axis through `point`, compliance m/N or rad/(N*m).
  void add_spring(const Eigen::Vector3d& point, const Eigen::Vector3d& axis, bool rotational,
                  double compliance);
  /// Actuated joints with the drive's stiffness (N/m, N*m/rad; 0 = rigid).
  void add_actuated_prismatic(const Eigen::Vector3d& point, const Eigen::Vector3d& axis,
                              double stiffness);
  void add_actuated_revolute(const Eigen::Vector3d& point, const Eigen::Vector3d& axis,
                             double stiffness);
  /// Passive joints.
  void add_prismatic(const Eigen::Vector3d& point, const Eigen::Vector3d& axis);
  void add_revolute(const Eigen::Vector3d& point, const Eigen::Vector3d& axis);
  void add_universal(const Eigen::Vector3d& point, const Eigen::Vector3d& axis1,
                     const Eigen::Vector3d& axis2);
  void add_spherical(const Eigen::Vector3d& point);
  /// A joint's own 6x6 compliance at `point`, base axes (zero entries: rigid).
  void add_elastic_joint(const Eigen::Vector3d& point, const Matrix6d& compliance);
  /// Rods in parallel between the previous body and the next (at most kMaxRodsPerGroup, with
  /// independent lines: not two on one line).
  void add_two_force_members(std::span<const TwoForceMember> rods);
  void add_two_force_member(const Eigen::Vector3d& a, const Eigen::Vector3d& b, double stiffness);

  /// K_leg at `reference` with the passive joints eliminated. Throws std::domain_error when the
  /// rods of a group are (numerically) on dependent lines at this pose.
  LegCompliance stiffness(const Eigen::Vector3d& reference) const;
  /// K_leg = W (W^T S W + O)^-1 W^T from the caller's basis W and compliance O of the transmitted
  /// wrenches (see the header comment): the springs, beams and elastic joints are used, the
  /// passive joints and rod groups are not. When W^T S W + O is singular (a transmitted wrench
  /// meets no compliance) `rigid` is set and the stiffness left zero.
  LegCompliance stiffness_for_wrenches(const Eigen::Vector3d& reference,
                                       const TransmittedWrenches& wrenches) const;
  /// S: the chain's compliance at `reference` with the passive joints locked (m/N, ...).
  Matrix6d locked_compliance(const Eigen::Vector3d& reference) const;
  /// J_q at `reference` (the passive joints' unit twists, then for each rod group an orthonormal
  /// basis of the twists its rods let through): the J_q of the block formula with S above.
  void passive_twists(const Eigen::Vector3d& reference, PassiveTwists& Jq) const;

  int num_springs() const { return num_springs_; }
  int num_passive() const { return num_passive_; }

 private:
  struct Axis {
    Eigen::Vector3d point;
    Eigen::Vector3d axis;  // unit
    bool rotational;
    double compliance;  // springs only
  };
  struct ElasticJoint {
    Eigen::Vector3d point;
    Matrix6d compliance;
  };
  struct RodGroup {
    std::array<TwoForceMember, kMaxRodsPerGroup> rods;
    int count;
  };
  // S (scaled: translations / L) and the scaled, unit-norm passive twists at `reference`.
  void assemble(const Eigen::Vector3d& reference, double inv_length, Matrix6d& S,
                Eigen::Matrix<double, 6, kMaxPassiveColumns>& P, int& num_columns) const;
  double length_scale(const Eigen::Vector3d& reference) const;

  std::array<Axis, kMaxSprings> springs_;
  std::array<Axis, kMaxPassive> passive_;
  std::array<ElasticJoint, kMaxElasticJoints> elastic_;
  std::array<RodGroup, kMaxRodGroups> rod_groups_;
  int num_springs_ = 0;
  int num_passive_ = 0;
  int num_elastic_ = 0;
  int num_rod_groups_ = 0;
};

}  // namespace pkmopt
