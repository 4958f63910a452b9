// Tests of models/stiffness/virtual_joint: beam and tube formulas against hand values; the VJM leg
// stiffness against an independent finite-element frame model written here (3-PRS tripod leg and
// tripod, delta with parallelogram rods, a cantilever), the UPS leg's exact reduction to k zeta
// zeta^T, the literal block-inverse formula of Pashkevich (2009), dependent passive joints, and
// the transformations between reference points.
#include "models/stiffness/virtual_joint.hpp"

#include <gtest/gtest.h>

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <Eigen/LU>
#include <Eigen/QR>
#include <array>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <utility>
#include <vector>

#include "tests/models/stiffness/frame_fe.hpp"

namespace pkmopt {
namespace {

using frame_fe::fe_beam;
using frame_fe::fe_rod;
using frame_fe::FrameModel;
using frame_fe::rel_diff;

using Eigen::Vector3d;
constexpr double kPi = std::numbers::pi;
constexpr double kSteelE = 2.1e11, kSteelG = 8.1e10, kAluE = 7.0e10, kAluG = 2.6e10;

Vector3d polar(double radius, double deg, double z = 0.0) {
  return {radius * std::cos(deg * kPi / 180), radius * std::sin(deg * kPi / 180), z};
}

// ---------------------------------------------------------------------------------------------
// 3-PRS tripod (Sprint Z3-like, models/leg_chain/leg_chain.hpp): slides along z at radius 0.30,
// struts of
// 0.55 m, platform joints at radius 0.15, TCP 0.20 m beyond the platform centre. A non-symmetric
// pose; each revolute axis is the slide's tangential direction made orthogonal to its strut (the
// comparison needs one consistent geometry, not the parasitic motion).
struct PrsLeg {
  Vector3d c, n, P;
};
struct Tripod {
  std::array<PrsLeg, 3> legs;
  Vector3d tcp;
  BeamSection strut = tube_section(kSteelE, kSteelG, 0.06, 0.045);
  double k_act = 2.0e8;  // ball screw, N/m
};

Tripod make_tripod() {
  Tripod t;
  const Eigen::Matrix3d R =
      (Eigen::AngleAxisd(0.05, Vector3d::UnitZ()) * Eigen::AngleAxisd(-0.14, Vector3d::UnitY()) *
       Eigen::AngleAxisd(0.21, Vector3d::UnitX()))
          .toRotationMatrix();
  const Vector3d p0(0.013, -0.021, 0.9);
  t.tcp = p0 + R * Vector3d(0, 0, 0.2);
  for (int i = 0; i < 3; ++i) {
    const double az = -90.0 + 120.0 * i;
    PrsLeg& leg = t.legs[static_cast<std::size_t>(i)];
    leg.P = p0 + R * polar(0.15, az);
    const Vector3d g = polar(0.30, az);
    const double h2 = (leg.P - g).head<2>().squaredNorm();
    leg.c = g + Vector3d(0, 0, leg.P.z() - std::sqrt(0.55 * 0.55 - h2));
    const Vector3d s = (leg.P - leg.c).normalized(), tang = polar(1.0, az + 90.0);
    leg.n = (tang - tang.dot(s) * s).normalized();
  }
  return t;
}

void vjm_prs_leg(const Tripod& t, const PrsLeg& l, VjmLeg& leg) {
  leg.clear();
  leg.add_actuated_prismatic(l.c, Vector3d::UnitZ(), t.k_act);
  leg.add_revolute(l.c, l.n);
  leg.add_beam(t.strut, (l.P - l.c).norm(), l.c, l.P - l.c, l.n);
  leg.add_spherical(l.P);
}

// FE of one PRS leg up to its platform point node (returned); `ball`: an elastic ball joint's
// translational stiffness between the strut end and the platform point (zero: rigid ball).
int fe_prs_leg(FrameModel& fe, const Tripod& t, const PrsLeg& l,
               const Eigen::Matrix3d& ball = Eigen::Matrix3d::Zero()) {
  const int carriage = fe.node(l.c);
  for (int k = 0; k < 3; ++k) fe.fix_along(carriage, true, Vector3d::Unit(k));
  fe.fix_along(carriage, false, Vector3d::UnitX());
  fe.fix_along(carriage, false, Vector3d::UnitY());
  Matrix6d ks = Matrix6d::Zero();
  ks(2, 2) = t.k_act;
  fe.spring(carriage, FrameModel::kGround, ks);
  const int s0 = fe.node(l.c);
  fe.revolute(carriage, s0, l.n);
  const int s_end = fe_beam(fe, s0, l.P, 3, t.strut, l.n);
  const int p = fe.node(l.P);
  if (ball.isZero()) {
    fe.tie_translations(s_end, p);
  } else {
    Matrix6d kb = Matrix6d::Zero();
    kb.topLeftCorner<3, 3>() = ball;
    fe.spring(s_end, p, kb);
  }
  return p;
}

TEST(VirtualJoint, TubeSectionAndShearModulusAgainstHandValues) {
  const BeamSection t = tube_section(kSteelE, kSteelG, 0.06, 0.045);
  EXPECT_NEAR(t.A, 1.237002107350981e-3, 1e-18);   // pi (D^2 - d^2) / 4
  EXPECT_NEAR(t.Iy, 4.348835533655792e-7, 1e-21);  // pi (D^4 - d^4) / 64
  EXPECT_DOUBLE_EQ(t.Iz, t.Iy);
  EXPECT_DOUBLE_EQ(t.J, 2.0 * t.Iy);
  EXPECT_DOUBLE_EQ(t.E, kSteelE);
  EXPECT_DOUBLE_EQ(t.G, kSteelG);
  const BeamSection rod = tube_section(kAluE, kAluG, 0.02);
  EXPECT_NEAR(rod.A, 3.141592653589793e-4, 1e-19);
  EXPECT_NEAR(rod.Iz, 7.853981633974483e-9, 1e-23);
  EXPECT_NEAR(shear_modulus(2.1e11, 0.3), 80769230769.23077, 1e-3);
  EXPECT_THROW(tube_section(kSteelE, kSteelG, 0.04, 0.05), std::invalid_argument);
  EXPECT_THROW(tube_section(0.0, kSteelG, 0.04, 0.0), std::invalid_argument);
}

TEST(VirtualJoint, BeamComplianceIsTheCantileverFormulas) {
  BeamSection s{kAluE, kAluG, 6e-4, 1.2e-7, 3.0e-7, 2.0e-7};
  const double L = 0.524, P = 100.0, M = 7.0;
  const Matrix6d C = beam_compliance(s, L);
  auto tip = [&C](double fx, double fy, double fz, double mx, double my, double mz) {
    return Vector6d(C * (Vector6d() << fx, fy, fz, mx, my, mz).finished());
  };
  Vector6d u = tip(0, P, 0, 0, 0, 0);  // tip force along y: bending with Iz
  EXPECT_NEAR(u(1), P * L * L * L / (3 * s.E * s.Iz), 1e-15);
  EXPECT_NEAR(u(5), P * L * L / (2 * s.E * s.Iz), 1e-15);  // slope dy/dx = rotation about +z
  EXPECT_EQ(u(2), 0.0);
  u = tip(0, 0, P, 0, 0, 0);  // along z: Iy, and the tip turns about -y
  EXPECT_NEAR(u(2), P * L * L * L / (3 * s.E * s.Iy), 1e-15);
  EXPECT_NEAR(u(4), -P * L * L / (2 * s.E * s.Iy), 1e-15);
  u = tip(P, 0, 0, M, 0, 0);  // axial force and torsion
  EXPECT_NEAR(u(0), P * L / (s.E * s.A), 1e-18);
  EXPECT_NEAR(u(3), M * L / (s.G * s.J), 1e-15);
  u = tip(0, 0, 0, 0, M, M);  // tip moments
  EXPECT_NEAR(u(4), M * L / (s.E * s.Iy), 1e-15);
  EXPECT_NEAR(u(2), -M * L * L / (2 * s.E * s.Iy), 1e-15);
  EXPECT_NEAR(u(1), M * L * L / (2 * s.E * s.Iz), 1e-15);
  EXPECT_EQ(C, C.transpose());
  // The six virtual springs of a beam give the same tip compliance (in base axes).
  const Vector3d a(0.1, -0.2, 0.3), x = Vector3d(1, 2, -0.5).normalized();
  const Vector3d y = Vector3d(0, 0.2, 1).cross(x).normalized();
  VjmLeg leg;
  leg.add_beam(s, L, a, 3 * x, y + 0.4 * x);  // axes not unit, y not orthogonal: normalised
  Eigen::Matrix3d R;
  R << x, y, x.cross(y);
  EXPECT_LT(rel_diff(leg.locked_compliance(a + L * x), rotate_6x6(C, R), true), 1e-13);
}

TEST(VirtualJoint, CantileverMatchesTheFrameModelAtAnOffsetPoint) {
  const BeamSection s{kSteelE, kSteelG, 8e-4, 2.5e-7, 1.1e-7, 1.6e-7};
  const Vector3d a(0.2, 0.1, -0.3), b(0.6, -0.15, 0.05), y(0.3, 1, 0.2), ref(0.7, 0.2, 0.3);
  FrameModel fe;
  const int base = fe.node(a);
  for (int k = 0; k < 6; ++k) fe.fix_along(base, k >= 3, Vector3d::Unit(k % 3));
  const int tip = fe_beam(fe, base, b, 4, s, y);
  const int r = fe.node(ref);
  fe.rigid(tip, r);
  const Matrix6d C_fe = fe.compliance(r);
  VjmLeg leg;
  leg.add_beam(s, (b - a).norm(), a, b - a, y);
  const LegCompliance k = leg.stiffness(ref);
  EXPECT_EQ(k.constrained_dim, 6);
  EXPECT_FALSE(k.rigid);
  EXPECT_LT(rel_diff(k.stiffness.inverse(), C_fe, true), 1e-9);
  Eigen::Matrix3d R;
  const Vector3d x = (b - a).normalized(), yy = (y - y.dot(x) * x).normalized();
  R << x, yy, x.cross(yy);
  const Matrix6d C_moved =
      move_compliance(rotate_6x6(beam_compliance(s, (b - a).norm()), R), b, ref);
  EXPECT_LT(rel_diff(C_moved, C_fe, true), 1e-9);
}

// (a) One PRS leg alone has a rank-2 stiffness (it transmits the force along its strut and the
// constraint force along its revolute axis; the other four twists are free), so the FE model of
// the leg alone is a mechanism. A well-posed comparison: the leg in parallel with an arbitrary
// positive definite fixture stiffness K_f at the platform point, in both models; then
// K_leg(FE) = C_FE^-1 - K_f must equal the VJM K_leg in all 36 entries. The ball joint at the
// platform is elastic here (ball_joint_compliance vs a translational spring in the FE).
TEST(VirtualJoint, PrsLegMatchesTheFrameModel) {
  const Tripod t = make_tripod();
  const PrsLeg& l = t.legs[1];
  const Vector3d ball_axis = Vector3d(0.1, -0.2, 1).normalized();
  const double k_axial = 4e8, k_radial = 2.5e8;
  Matrix6d G;
  for (int i = 0; i < 36; ++i) G.data()[i] = std::sin(1.0 + 7.3 * i);  // fixed "random" entries
  const Vector6d d = (Vector6d() << 1, 1, 1, 0.5, 0.5, 0.5).finished();
  const Matrix6d K_f =
      d.asDiagonal() * (2e6 * (G * G.transpose() + 0.5 * Matrix6d::Identity())) * d.asDiagonal();

  VjmLeg leg;
  vjm_prs_leg(t, l, leg);
  leg.add_elastic_joint(l.P, ball_joint_compliance(ball_axis, k_axial, k_radial));
  const LegCompliance k = leg.stiffness(l.P);
  EXPECT_EQ(k.constrained_dim, 2);
  EXPECT_FALSE(k.rigid);

  FrameModel fe;
  const Eigen::Matrix3d ball =
      k_axial * ball_axis * ball_axis.transpose() +
      k_radial * (Eigen::Matrix3d::Identity() - ball_axis * ball_axis.transpose());
  const int p = fe_prs_leg(fe, t, l, ball);
  fe.spring(p, FrameModel::kGround, K_f);
  const Matrix6d K_leg_fe = Matrix6d(fe.compliance(p).inverse()) - K_f;
  EXPECT_LT(rel_diff(k.stiffness, K_leg_fe, false), 1e-6) << k.stiffness << "\n\n" << K_leg_fe;
  // The leg is much stiffer than the fixture along the strut: the comparison is not the fixture's.
  const Vector3d s = (l.P - l.c).normalized();
  Vector6d t_axial;
  t_axial << s, Vector3d::Zero();
  EXPECT_GT(t_axial.dot(k.stiffness * t_axial), 10 * t_axial.dot(K_f * t_axial));
}

// (a) The complete tripod (three PRS legs, rigid platform, rigid ball joints): its 6x6 stiffness
// at the TCP is full rank; compare the compliance with the FE model loaded at the TCP.
TEST(VirtualJoint, TripodMatchesTheFrameModel) {
  const Tripod t = make_tripod();
  std::array<LegCompliance, 3> legs;
  VjmLeg leg;
  for (std::size_t i = 0; i < 3; ++i) {
    vjm_prs_leg(t, t.legs[i], leg);
    legs[i] = leg.stiffness(t.legs[i].P);
  }
  const Matrix6d K = platform_stiffness(legs, t.tcp);
  FrameModel fe;
  const int tcp = fe.node(t.tcp);
  for (const PrsLeg& l : t.legs) fe.rigid(tcp, fe_prs_leg(fe, t, l));
  const Matrix6d C_fe = fe.compliance(tcp);
  EXPECT_LT(rel_diff(Matrix6d(K.inverse()), C_fe, true), 1e-6);
  EXPECT_LT(rel_diff(K, Matrix6d(C_fe.inverse()), false), 1e-6);
}

// (b) A delta (ABB IRB 360-like dimensions, docs/conventions.md section 4) with elastic cranks
// (aluminium box section, Iy != Iz), motor torsion springs and parallelogram rod pairs (two-force
// members, rod frame elements with ball joints at both ends in the FE), non-symmetric pose.
TEST(VirtualJoint, DeltaMatchesTheFrameModel) {
  const double base_radius = 0.164, platform_radius = 0.044, arm = 0.524, rod = 1.244;
  const double half_width = 0.05, k_motor = 1.5e5;
  const BeamSection crank{kAluE, kAluG, 6e-4, 1.2e-7, 3.0e-7, 2.0e-7};
  const BeamSection rod_section = tube_section(kAluE, kAluG, 0.016, 0.012);
  const double k_rod = kAluE * rod_section.A / rod;
  const Vector3d tcp(0.07, -0.04, -1.2);
  std::array<LegCompliance, 3> legs;
  FrameModel fe;
  const int t = fe.node(tcp);
  VjmLeg leg;
  for (int i = 0; i < 3; ++i) {
    const double phi = -90.0 + 120.0 * i;
    const Vector3d d = polar(1.0, phi), w = polar(1.0, phi + 90.0), o = base_radius * d;
    const Vector3d P = tcp + platform_radius * d, q = P - o;
    // elbow e = o + arm (cos th d - sin th z) with |P - e| = rod: A cos th + B sin th = C
    const double A = 2 * arm * q.dot(d), B = -2 * arm * q.z(),
                 Cc = q.squaredNorm() + arm * arm - rod * rod;
    const double th = std::atan2(B, A) - std::acos(Cc / std::hypot(A, B));
    const Vector3d e = o + arm * (std::cos(th) * d - std::sin(th) * Vector3d::UnitZ());
    ASSERT_NEAR((P - e).norm(), rod, 1e-12);
    ASSERT_GT(th, 0.0);  // elbow below the pivot, arm outwards
    const std::array<TwoForceMember, 2> rods{
        TwoForceMember{e + half_width * w, P + half_width * w, k_rod},
        TwoForceMember{e - half_width * w, P - half_width * w, k_rod}};
    leg.clear();
    leg.add_actuated_revolute(o, w, k_motor);
    leg.add_beam(crank, arm, o, e - o, w);
    leg.add_two_force_members(rods);
    legs[static_cast<std::size_t>(i)] = leg.stiffness(tcp);
    EXPECT_EQ(legs[static_cast<std::size_t>(i)].constrained_dim, 2);

    const int m = fe.node(o);
    for (int k = 0; k < 3; ++k) fe.fix_along(m, false, Vector3d::Unit(k));
    fe.fix_along(m, true, w.unitOrthogonal());
    fe.fix_along(m, true, w.cross(w.unitOrthogonal()));
    Matrix6d motor = Matrix6d::Zero();
    motor.bottomRightCorner<3, 3>() = k_motor * w * w.transpose();
    fe.spring(m, FrameModel::kGround, motor);
    const int elbow = fe_beam(fe, m, e, 3, crank, w);
    for (const TwoForceMember& r : rods) {
      const int a = fe.node(r.a), b = fe.node(r.b);
      fe.rigid(elbow, a);  // the crossbar of the parallelogram, rigid
      fe.rigid(t, b);      // the platform, rigid
      fe_rod(fe, a, b, rod_section);
    }
  }
  const Matrix6d K = platform_stiffness(legs, tcp);
  const Matrix6d C_fe = fe.compliance(t);
  EXPECT_LT(rel_diff(K, Matrix6d(C_fe.inverse()), false), 1e-6);
  EXPECT_LT(rel_diff(Matrix6d(K.inverse()), C_fe, true), 1e-6);
  // The rotational stiffness is finite and positive (not the translational-only model's zero).
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> rot(K.bottomRightCorner<3, 3>());
  EXPECT_GT(rot.eigenvalues()(0), 1e2);  // N*m/rad
}

// A UPS leg modelled with its full bending (universal joint, actuator, cylinder and piston rod as
// beams, spherical joint) is exactly the two-force member k zeta zeta^T.
TEST(VirtualJoint, UpsLegReducesExactlyToTheAxialModel) {
  const Vector3d a(0.55, -0.12, 0.0), P(0.21, 0.09, 0.93), tcp(0.02, 0.03, 1.05);
  const Vector3d s = (P - a).normalized();
  const BeamSection cylinder = tube_section(kSteelE, kSteelG, 0.08, 0.06);
  const BeamSection piston = tube_section(kSteelE, kSteelG, 0.04);
  const double q = (P - a).norm(), l1 = 0.45, l2 = q - l1, k_act = 2e8;
  const double k = 1.0 / (1.0 / k_act + l1 / (kSteelE * cylinder.A) + l2 / (kSteelE * piston.A));
  const Matrix6d K_axial = two_force_member_stiffness(a, P, k, tcp);
  Vector6d zeta;
  zeta << s, (P - tcp).cross(s);
  EXPECT_LT(rel_diff(K_axial, k * zeta * zeta.transpose(), false), 1e-15);
  const Vector3d w1 = Vector3d::UnitZ().cross(s).normalized(), w2 = s.cross(w1);
  for (int variant = 0; variant < 3; ++variant) {
    VjmLeg leg;
    leg.add_universal(a, w1, w2);
    leg.add_actuated_prismatic(a, s, k_act);
    leg.add_beam(cylinder, l1, a, s, w1);
    leg.add_beam(piston, l2, a + l1 * s, s, w2);
    leg.add_spherical(P);
    if (variant == 1) leg.add_revolute(a, s);  // dependent passive joint (leg spin twice)
    if (variant == 2) leg.add_revolute(P + 0.3 * s, s);
    const LegCompliance r = leg.stiffness(tcp);
    EXPECT_EQ(r.constrained_dim, 1);
    EXPECT_LT(rel_diff(r.stiffness, K_axial, false), 1e-12) << "variant " << variant;
  }
  // The same rod as a group of one two-force member in a chain.
  VjmLeg rod;
  rod.add_two_force_member(a, P, k);
  EXPECT_LT(rel_diff(rod.stiffness(tcp).stiffness, K_axial, false), 1e-12);
}

// PUS and RUS legs (models/leg_chain/leg_chain.hpp) with elastic struts reduce to leg_chain's axial
// model K = k zeta zeta^T, 1/k = B^2 / k_act + L / (E A): B = s . u (PUS), s . (w x (c - o)) (RUS).
TEST(VirtualJoint, PusAndRusLegsGiveTheLegChainAxialModel) {
  const BeamSection strut = tube_section(kSteelE, kSteelG, 0.05, 0.035);
  const Vector3d P(0.12, 0.3, 0.85), tcp(0.0, 0.1, 1.0), o(0.4, 0.2, 0.1);
  const Vector3d u = Vector3d(0.3, -0.1, 1).normalized(), w = Vector3d(-0.2, 1, 0.1).normalized();
  for (const bool rus : {false, true}) {
    const double k_act = rus ? 3e5 : 1.5e8;  // N*m/rad, N/m
    const Vector3d c = rus ? Vector3d(o + 0.3 * w.unitOrthogonal()) : Vector3d(o + 0.2 * u);
    const Vector3d s = (P - c).normalized();
    const double B = rus ? s.dot(w.cross(c - o)) : s.dot(u), L = (P - c).norm();
    const double k = 1.0 / (B * B / k_act + L / (kSteelE * strut.A));
    VjmLeg leg;
    if (rus) {
      leg.add_actuated_revolute(o, w, k_act);  // rigid crank
    } else {
      leg.add_actuated_prismatic(c, u, k_act);
    }
    const Vector3d w1 = s.unitOrthogonal();
    leg.add_universal(c, w1, s.cross(w1));
    leg.add_beam(strut, L, c, s, w1);
    leg.add_spherical(P);
    EXPECT_LT(
        rel_diff(leg.stiffness(tcp).stiffness, two_force_member_stiffness(c, P, k, tcp), false),
        1e-12)
        << (rus ? "RUS" : "PUS");
  }
}

// The literal formula K = top-left block of [S, J_q; J_q^T, 0]^-1 (Pashkevich 2009), where the
// block matrix is invertible; and with a dependent passive joint, where it is singular.
TEST(VirtualJoint, AgreesWithTheBlockInverseAndHandlesDependentJoints) {
  const Tripod t = make_tripod();
  const PrsLeg& l = t.legs[0];
  VjmLeg leg;
  vjm_prs_leg(t, l, leg);
  const LegCompliance k = leg.stiffness(t.tcp);
  const Matrix6d S = leg.locked_compliance(t.tcp);
  VjmLeg::PassiveTwists Jq;
  leg.passive_twists(t.tcp, Jq);
  ASSERT_EQ(Jq.cols(), 4);
  auto block = [&S](const VjmLeg::PassiveTwists& J) {
    Eigen::MatrixXd B = Eigen::MatrixXd::Zero(6 + J.cols(), 6 + J.cols());
    B << S, J, J.transpose(), Eigen::MatrixXd::Zero(J.cols(), J.cols());
    return Eigen::FullPivLU<Eigen::MatrixXd>(B);
  };
  ASSERT_TRUE(block(Jq).isInvertible());
  const Matrix6d K_block = block(Jq).inverse().topLeftCorner(6, 6);
  EXPECT_LT(rel_diff(k.stiffness, K_block, false), 1e-8);
  // A second revolute on the same axis: J_q has rank 4 of 5 columns, the block matrix is singular,
  // the stiffness is unchanged.
  leg.add_revolute(l.c + 0.1 * l.n, 2.0 * l.n);
  leg.passive_twists(t.tcp, Jq);
  ASSERT_EQ(Jq.cols(), 5);
  EXPECT_FALSE(block(Jq).isInvertible());
  const LegCompliance k2 = leg.stiffness(t.tcp);
  EXPECT_EQ(k2.constrained_dim, 2);
  EXPECT_LT(rel_diff(k2.stiffness, k.stiffness, false), 1e-12);
}

TEST(VirtualJoint, SymmetricPositiveSemiDefiniteAndMovesBetweenPoints) {
  const Tripod t = make_tripod();
  const Vector3d p1 = t.tcp, p2 = t.tcp + Vector3d(0.3, -0.2, 0.4);
  VjmLeg leg;
  std::array<LegCompliance, 3> at1, at2;
  for (std::size_t i = 0; i < 3; ++i) {
    vjm_prs_leg(t, t.legs[i], leg);
    at1[i] = leg.stiffness(p1);
    at2[i] = leg.stiffness(p2);
    const Matrix6d& K = at1[i].stiffness;
    EXPECT_EQ(K, K.transpose());
    const Vector6d d = (Vector6d() << 1, 1, 1, 2, 2, 2).finished();  // rotations / L, L = 0.5
    const Vector6d lambda =
        Eigen::SelfAdjointEigenSolver<Matrix6d>(d.asDiagonal() * K * d.asDiagonal()).eigenvalues();
    EXPECT_GT(lambda(0), -1e-12 * lambda(5));
    EXPECT_GT(lambda(4), 1e-6 * lambda(5));  // rank 2
    EXPECT_LT(lambda(3), 1e-12 * lambda(5));
    EXPECT_LT(rel_diff(move_stiffness(K, p1, p2), at2[i].stiffness, false), 1e-12);
  }
  // The platform sum at p2 from the legs at p1, and the compliance moved, against direct values.
  const Matrix6d K2 = platform_stiffness(at1, p2);
  EXPECT_LT(rel_diff(K2, platform_stiffness(at2, p2), false), 1e-12);
  const Matrix6d C1 = platform_stiffness(at1, p1).inverse();
  EXPECT_LT(rel_diff(move_compliance(C1, p1, p2), Matrix6d(K2.inverse()), true), 1e-10);
  // Power is the same at both points: w_b^T t_b = w_a^T t_a; the transforms are inverse-transposes.
  const Vector6d tw = (Vector6d() << 0.1, -0.4, 0.2, 0.7, 0.3, -0.5).finished();
  const Vector6d wr = (Vector6d() << 3, 1, -2, 0.4, -0.6, 0.9).finished();
  const double power = wr.dot(tw);
  EXPECT_NEAR((wrench_transform(p1, p2) * wr).dot(twist_transform(p1, p2) * tw), power, 1e-14);
  EXPECT_LT((wrench_transform(p1, p2).transpose() * twist_transform(p1, p2) - Matrix6d::Identity())
                .norm(),
            1e-15);
  // The twist of a rigid body: v_2 = v_1 + omega x (p2 - p1).
  const Vector6d t2 = twist_transform(p1, p2) * tw;
  EXPECT_LT((t2.head<3>() - (tw.head<3>() + tw.tail<3>().cross(p2 - p1))).norm(), 1e-15);
}

TEST(VirtualJoint, RigidChainsAndErrors) {
  VjmLeg leg;
  leg.add_universal(Vector3d::Zero(), Vector3d::UnitX(), Vector3d::UnitY());
  leg.add_spherical(Vector3d(0, 0, 1));
  LegCompliance k = leg.stiffness(Vector3d(0, 0, 1));
  EXPECT_TRUE(k.rigid);  // nothing compliant along the leg: infinitely stiff there
  EXPECT_EQ(k.constrained_dim, 1);
  EXPECT_TRUE(k.stiffness.isZero());
  leg.add_actuated_prismatic(Vector3d::Zero(), Vector3d::UnitZ(), 1e7);
  k = leg.stiffness(Vector3d(0, 0, 1));
  EXPECT_FALSE(k.rigid);
  EXPECT_NEAR(k.stiffness(2, 2), 1e7, 1e-6);
  EXPECT_NEAR(k.stiffness.norm(), 1e7, 1e-6);
  // Partly rigid: a ball joint at P transmits any force, only the one along u meets a spring. The
  // compliant part is k u u^T (basis independent), the other two force directions are rigid.
  VjmLeg partly;
  const Vector3d P(0.3, -0.2, 0.8), u = Vector3d(1, 2, 2) / 3.0;
  partly.add_spherical(P);
  partly.add_actuated_prismatic(Vector3d::Zero(), u, 3e6);
  k = partly.stiffness(P);
  EXPECT_TRUE(k.rigid);
  EXPECT_EQ(k.constrained_dim, 3);
  Matrix6d expected = Matrix6d::Zero();
  expected.topLeftCorner<3, 3>() = 3e6 * u * u.transpose();
  EXPECT_LT(rel_diff(k.stiffness, expected, false), 1e-12);
  // A clamped chain compliant in 1 of its 6 directions only.
  VjmLeg clamped;
  clamped.add_actuated_revolute(Vector3d::Zero(), Vector3d::UnitZ(), 1e4);
  EXPECT_TRUE(clamped.stiffness(Vector3d::UnitX()).rigid);
  EXPECT_THROW(clamped.add_beam(tube_section(kSteelE, kSteelG, 0.02), 0.0, Vector3d::Zero(),
                                Vector3d::UnitX(), Vector3d::UnitY()),
               std::invalid_argument);
  EXPECT_THROW(clamped.add_beam(tube_section(kSteelE, kSteelG, 0.02), 1.0, Vector3d::Zero(),
                                Vector3d::UnitX(), Vector3d::UnitX()),
               std::invalid_argument);
  EXPECT_THROW(clamped.add_revolute(Vector3d::Zero(), Vector3d::Zero()), std::invalid_argument);
  EXPECT_THROW(clamped.add_actuated_prismatic(Vector3d::Zero(), Vector3d::UnitX(), -1.0),
               std::invalid_argument);
  leg.clear();
  for (int i = 0; i < VjmLeg::kMaxPassive; ++i)
    leg.add_revolute(Vector3d::Zero(), Vector3d::UnitX());
  EXPECT_THROW(leg.add_revolute(Vector3d::Zero(), Vector3d::UnitX()), std::length_error);
  VjmLeg rods;  // two rods on one line cannot share a load statically determinately
  const std::array<TwoForceMember, 2> same_line{
      TwoForceMember{Vector3d::Zero(), Vector3d::UnitZ(), 1e6},
      TwoForceMember{Vector3d::UnitZ(), Vector3d(0, 0, 2), 1e6}};
  rods.add_two_force_members(same_line);
  EXPECT_THROW(rods.stiffness(Vector3d::Zero()), std::domain_error);
}

}  // namespace
}  // namespace pkmopt
