// Tests of models/leg_chain/leg_chain_vjm.cpp, the link compliance of the leg-chain machines by the
// virtual-joint method: the 6x6 compliance of a 3-PRS tripod with elastic struts and of a delta
// with elastic cranks and parallelogram rod pairs against the independent finite-element frame
// model of tests/models/stiffness/frame_fe.hpp (several non-symmetric poses, the machines' own
// kinematics); very stiff links give back the axial model with rigid constraints; UPS and U-S
// links, which carry only axial forces, give the axial model exactly; the loaded stiffness is the
// VJM stiffness plus the geometric terms of the rod forces and plane reactions, here by finite
// differences; and the design checks.
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <Eigen/LU>
#include <Eigen/SVD>
#include <array>
#include <cmath>
#include <cstddef>
#include <stdexcept>
#include <string>
#include <vector>

#include "models/hexapod/hexapod.hpp"  // semi_regular_platform_joints
#include "models/leg_chain/leg_chain.hpp"
#include "tests/models/stiffness/frame_fe.hpp"

#if defined(__SANITIZE_ADDRESS__)
#define PKMOPT_TEST_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define PKMOPT_TEST_ASAN 1
#endif
#endif
#if defined(PKMOPT_TEST_ASAN)
#include <sanitizer/allocator_interface.h>
#endif

namespace pkmopt {
namespace {

using Eigen::Vector3d;
using frame_fe::fe_axial_joint;
using frame_fe::fe_beam;
using frame_fe::fe_rod;
using frame_fe::FrameModel;
using frame_fe::rel_diff;

constexpr double kSteelE = 2.1e11, kSteelG = 8.1e10, kAluE = 7.0e10, kAluG = 2.6e10;

// The metrics of a pose with the compliance matrices analyze leaves in its data.
struct Analyzed : PoseMetrics {
  Matrix6d compliance;
  Eigen::Matrix3d loaded_compliance_tt;
};

Analyzed analyze(const LegChainMachine& m, const Pose& pose, const Wrench& w) {
  auto data = m.make_data();
  Analyzed metrics;
  m.analyze(*data, pose, w, metrics);
  metrics.compliance = data->matrices.compliance;
  metrics.loaded_compliance_tt = data->matrices.loaded_compliance_tt;
  return metrics;
}

Pose pose_deg(double x, double y, double z, double rx, double ry, double rz = 0.0) {
  return Pose{{x, y, z}, deg_to_rad(Eigen::Vector3d(rx, ry, rz))};
}

// The kinematics of a leg at the actual pose: actuated point c, platform point P, unit rod s.
struct LegGeometry {
  Vector3d c, dc, P, s;
};

std::vector<LegGeometry> leg_geometry(const LegChainMachine& m, const Pose& actual) {
  const Eigen::VectorXd q = *m.inverse_kinematics(actual);
  const Eigen::Matrix3d R = rotation_zyx<double>(actual.angles);
  std::vector<LegGeometry> legs;
  for (int i = 0; i < m.num_actuators(); ++i) {
    const LegChainLeg& leg = m.design().legs[static_cast<std::size_t>(i)];
    LegGeometry g;
    m.actuated_point(i, q(i), g.c, g.dc);
    g.P = actual.position + R * (leg.platform_point - m.design().tcp);
    g.s = (g.P - g.c).normalized();
    legs.push_back(g);
  }
  return legs;
}

// ---------------------------------------------------------------------------------------------
// 3-PRS tripod (Sprint Z3-like defaults) with steel tube struts, ball-screw slides (slide and nut
// in series) and an elastic revolute joint along the strut.
Tripod3PrsDesign tube_tripod() {
  Tripod3PrsDesign t;
  t.stiffness.section = tube_section(kSteelE, kSteelG, 0.08, 0.06);
  t.stiffness.actuator_stiffness = 2.0e8;
  t.stiffness.drive.nut_stiffness = 5.0e8;
  t.stiffness.base_joint_stiffness = 8.0e8;
  return t;
}

// The FE frame model of the tripod at the machine's actual pose, loaded at the TCP.
Matrix6d tripod_fe_compliance(const LegChainMachine& m, const Pose& actual,
                              const Tripod3PrsDesign& t) {
  const double k_slide =
      1.0 / (1.0 / t.stiffness.actuator_stiffness + 1.0 / t.stiffness.drive.nut_stiffness);
  FrameModel fe;
  const int tcp = fe.node(actual.position);
  const std::vector<LegGeometry> legs = leg_geometry(m, actual);
  for (std::size_t i = 0; i < legs.size(); ++i) {
    const LegGeometry& g = legs[i];
    const Vector3d n = m.design().legs[i].plane_normal;
    const int carriage = fe.node(g.c);  // on the slide (z): only its travel is free
    for (int k = 0; k < 3; ++k) fe.fix_along(carriage, true, Vector3d::Unit(k));
    fe.fix_along(carriage, false, Vector3d::UnitX());
    fe.fix_along(carriage, false, Vector3d::UnitY());
    Matrix6d drive = Matrix6d::Zero();
    drive(2, 2) = k_slide;
    fe.spring(carriage, FrameModel::kGround, drive);
    const int foot = fe.node(g.c);  // the revolute joint, axial spring along the strut
    fe_axial_joint(fe, carriage, foot, g.s, t.stiffness.base_joint_stiffness);
    const Vector3d n1 = n.unitOrthogonal(), n2 = n.cross(n1);
    fe.tie_along(carriage, foot, true, n1);
    fe.tie_along(carriage, foot, true, n2);
    const int end = fe_beam(fe, foot, g.P, 3, *t.stiffness.section, n);
    const int p = fe.node(g.P);
    fe.tie_translations(end, p);  // spherical joint
    fe.rigid(tcp, p);             // the platform
  }
  return fe.compliance(tcp);
}

// (a) The VJM compliance of the machine equals the FE frame model's at non-symmetric poses.
TEST(LegChainVjm, TripodMatchesTheFrameModelAtNonSymmetricPoses) {
  const Tripod3PrsDesign t = tube_tripod();
  const LegChainMachine m(tripod_3prs_design(t));
  ASSERT_TRUE(m.link_compliance_model());
  ASSERT_TRUE(m.link_compliance_full());
  Tripod3PrsDesign axial_design = t;
  axial_design.stiffness.section.reset();
  axial_design.stiffness.E = t.stiffness.section->E;
  axial_design.stiffness.area = t.stiffness.section->A;
  const LegChainMachine axial(tripod_3prs_design(axial_design));
  ASSERT_FALSE(axial.link_compliance_model());
  const Wrench w = (Wrench() << 900, -400, -2500, 60, -40, 25).finished();
  for (const Pose& pose : {pose_deg(0, 0, 1.1, 12, -7), pose_deg(0, 0, 1.3, -25, 18),
                           pose_deg(0, 0, 0.95, 5, 33), pose_deg(0, 0, 1.2, -31, -22)}) {
    const Analyzed metrics = analyze(m, pose, w);
    ASSERT_FALSE(metrics.singular);
    const Pose actual = *m.actual_pose(pose);
    const Matrix6d C_fe = tripod_fe_compliance(m, actual, t);
    EXPECT_LT(rel_diff(metrics.compliance, C_fe, true), 1e-6) << metrics.compliance << "\n\n"
                                                              << C_fe;
    // Every direction is compliant now (the axial model's constrained ones are rigid), and the
    // metrics follow from C: stiffness_min, the deflection.
    const Eigen::SelfAdjointEigenSolver<Matrix6d> eig(metrics.compliance);
    EXPECT_GT(eig.eigenvalues()(0), 0.0);
    const Eigen::Matrix3d Ctt = C_fe.topLeftCorner<3, 3>();
    const double fe_min =
        1.0 / Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(Ctt).eigenvalues()(2);
    EXPECT_NEAR(metrics.stiffness_min, fe_min, 1e-6 * fe_min);
    const Vec6<double> dx = C_fe * w;
    EXPECT_NEAR(metrics.tcp_deflection, dx.head<3>().norm(), 1e-6 * dx.head<3>().norm());
    // Bending lowers the stiffness below the axial bound with the same E * A.
    const Analyzed bound = analyze(axial, pose, w);
    EXPECT_LT(metrics.stiffness_min, 0.99 * bound.stiffness_min);
    EXPECT_EQ(metrics.tau, bound.tau);  // the statics do not change
    EXPECT_EQ(metrics.tcp_error_max, bound.tcp_error_max);
  }
}

// (b) A delta (ABB IRB 360-like) with aluminium box-section cranks (Iy != Iz), motor torsion and
// parallelogram rod pairs 0.1 m wide.
DeltaDesign wide_delta() {
  DeltaDesign d;
  d.crank_section = BeamSection{kAluE, kAluG, 6e-4, 1.2e-7, 3.0e-7, 2.0e-7};
  d.stiffness.E = kAluE;
  d.stiffness.area = tube_section(kAluE, kAluG, 0.016, 0.012).A;
  d.stiffness.parallelogram_width = 0.1;
  d.stiffness.actuator_stiffness = 1.5e5;
  return d;
}

Matrix6d delta_fe_compliance(const LegChainMachine& m, const Vector3d& tcp_position,
                             const DeltaDesign& d) {
  const BeamSection rod_section = tube_section(kAluE, kAluG, 0.016, 0.012);
  const Pose actual{tcp_position, Vector3d::Zero()};
  FrameModel fe;
  const int t = fe.node(tcp_position);
  const std::vector<LegGeometry> legs = leg_geometry(m, actual);
  for (std::size_t i = 0; i < legs.size(); ++i) {
    const LegChainLeg& leg = m.design().legs[i];
    const Vector3d w = leg.axis, o = leg.base_point, e = legs[i].c;
    const int pivot = fe.node(o);  // the motor: turns about w against its spring
    for (int k = 0; k < 3; ++k) fe.fix_along(pivot, false, Vector3d::Unit(k));
    fe.fix_along(pivot, true, w.unitOrthogonal());
    fe.fix_along(pivot, true, w.cross(w.unitOrthogonal()));
    Matrix6d motor = Matrix6d::Zero();
    motor.bottomRightCorner<3, 3>() = d.stiffness.actuator_stiffness * w * w.transpose();
    fe.spring(pivot, FrameModel::kGround, motor);
    const int elbow = fe_beam(fe, pivot, e, 3, *d.crank_section, w);
    const Vector3d h = 0.5 * d.stiffness.parallelogram_width * w;
    for (const double side : {1.0, -1.0}) {
      const int a = fe.node(e + side * h), b = fe.node(legs[i].P + side * h);
      fe.rigid(elbow, a);  // the elbow bar
      fe.rigid(t, b);      // the platform
      fe_rod(fe, a, b, rod_section);
    }
  }
  return fe.compliance(t);
}

TEST(LegChainVjm, DeltaMatchesTheFrameModelAtNonSymmetricPoses) {
  const DeltaDesign d = wide_delta();
  const LegChainMachine m(delta_design(d));
  ASSERT_TRUE(m.link_compliance_full());
  const Wrench w = (Wrench() << 20, -35, -60, 1.5, -0.8, 2.0).finished();
  for (const Vector3d& p : {Vector3d(0.07, -0.04, -1.2), Vector3d(-0.15, 0.1, -1.0),
                            Vector3d(0.2, 0.18, -1.1), Vector3d(-0.05, -0.25, -0.95)}) {
    const Analyzed metrics = analyze(m, Pose{p, Vector3d::Zero()}, w);
    ASSERT_FALSE(metrics.singular);
    const Matrix6d C_fe = delta_fe_compliance(m, p, d);
    EXPECT_LT(rel_diff(metrics.compliance, C_fe, true), 1e-6) << metrics.compliance << "\n\n"
                                                              << C_fe;
    // The pairs hold the orientation elastically: a finite rotational compliance.
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> rot(
        metrics.compliance.bottomRightCorner<3, 3>());
    EXPECT_GT(rot.eigenvalues()(0), 0.0);
    EXPECT_LT(rot.eigenvalues()(2), 1e-2);  // rad/(N*m)
  }
}

// (c) Links very stiff in bending and torsion (the same E * A): the axial model's compliance T C
// T^T, and almost no compliance for the wrenches the constraints take (T^T w = 0).
TEST(LegChainVjm, VeryStiffLinksGiveTheAxialModelWithRigidConstraints) {
  Tripod3PrsDesign t;
  t.stiffness.actuator_stiffness = 2.0e8;
  const LegChainMachine axial(tripod_3prs_design(t));
  // E * A as the axial model's; I and J 1e8 times a 80/60 mm tube's.
  BeamSection stiff{t.stiffness.E,  kSteelG,        t.stiffness.area,
                    1e8 * 1.374e-6, 1e8 * 1.374e-6, 2e8 * 1.374e-6};
  Tripod3PrsDesign s = t;
  s.stiffness.section = stiff;
  const LegChainMachine vjm(tripod_3prs_design(s));
  Tripod3PrsDesign tube = t;
  tube.stiffness.section = tube_section(kSteelE, kSteelG, 0.08, 0.06);
  tube.stiffness.section->A = t.stiffness.area;
  const LegChainMachine realistic(tripod_3prs_design(tube));
  for (const Pose& pose : {pose_deg(0, 0, 1.15, 14, -9), pose_deg(0, 0, 1.35, -20, 26)}) {
    const Analyzed a = analyze(axial, pose, Wrench::Zero());
    const Analyzed v = analyze(vjm, pose, Wrench::Zero());
    const Analyzed r = analyze(realistic, pose, Wrench::Zero());
    ASSERT_FALSE(v.singular);
    EXPECT_LT(rel_diff(v.compliance, a.compliance, true), 1e-6);
    EXPECT_NEAR(v.stiffness_min, a.stiffness_min, 1e-6 * a.stiffness_min);
    EXPECT_GT(rel_diff(r.compliance, a.compliance, true), 1e-2);  // a real tube is not rigid
    // The plane constraints' wrenches [n_j; r_j x n_j] do no work on T: almost no deflection.
    const Pose actual = *vjm.actual_pose(pose);
    const std::vector<LegGeometry> legs = leg_geometry(vjm, actual);
    for (std::size_t j = 0; j < legs.size(); ++j) {
      const Vector3d n = vjm.design().legs[j].plane_normal;
      Wrench wc;
      wc << n, (legs[j].P - actual.position).cross(n);
      const double scale = a.compliance.norm() * wc.norm();
      EXPECT_LT((v.compliance * wc).norm(), 1e-6 * scale) << "constraint " << j;
      EXPECT_GT((r.compliance * wc).norm(), 1e-3 * scale) << "constraint " << j;
      EXPECT_LT((a.compliance * wc).norm(), 1e-12 * scale) << "constraint " << j;
    }
  }
  // A delta whose cranks are very stiff (no pair widths: the orientation stays rigid).
  DeltaDesign d;
  d.stiffness.actuator_stiffness = 1.5e5;
  const LegChainMachine delta_axial(delta_design(d));
  d.crank_section = BeamSection{kAluE, kAluG, 1e6 * 6e-4, 1e8 * 1.2e-7, 1e8 * 3.0e-7, 1e8 * 2.0e-7};
  const LegChainMachine delta_vjm(delta_design(d));
  ASSERT_TRUE(delta_vjm.link_compliance_model());
  ASSERT_FALSE(delta_vjm.link_compliance_full());
  const Pose p{{0.1, -0.05, -1.05}, Vector3d::Zero()};
  const Analyzed a = analyze(delta_axial, p, Wrench::Zero());
  const Analyzed v = analyze(delta_vjm, p, Wrench::Zero());
  EXPECT_LT(rel_diff(v.compliance, a.compliance, true), 1e-6);
  const Eigen::Matrix3d rotational = v.compliance.bottomRightCorner<3, 3>();
  EXPECT_TRUE(rotational.isZero(0.0));
}

// (d) A generic 6-UPS leg chain (a hexapod written leg by leg) with telescopic legs as beams:
// bending cannot enter a link between a universal and a spherical joint, the VJM is the axial
// model exactly, the loaded stiffness too.
LegChainDesign ups_chain(bool sections) {
  const Eigen::Matrix<double, 3, 6> base = semi_regular_base_joints(0.6, deg_to_rad(20.0));
  const Eigen::Matrix<double, 3, 6> top = semi_regular_platform_joints(0.25, deg_to_rad(20.0));
  LegChainDesign d;
  d.mobility = PlatformMobility::kSixDof;
  d.tcp = Vector3d(0.01, -0.02, -0.1);
  d.home.position = Vector3d(0, 0, 0.85);
  const BeamSection cylinder = tube_section(kSteelE, kSteelG, 0.07, 0.05);
  for (int i = 0; i < 6; ++i) {
    LegChainLeg leg;
    leg.kind = LegKind::kUPS;
    leg.base_point = base.col(i);
    leg.platform_point = top.col(i);
    leg.q_min = 0.6;
    leg.q_max = 1.3;
    if (sections) {
      leg.link_section = cylinder;
    } else {
      leg.E = cylinder.E;
      leg.area = cylinder.A;
    }
    leg.actuator_stiffness = 2.0e8;
    leg.drive = ScrewDrive{
        .E = 2.1e11, .root_diameter = 0.02, .free_length_at_min = 0.1, .free_length_at_max = 0.6};
    leg.base_joint_stiffness = 6e8;
    leg.platform_joint_stiffness = 9e8;
    d.legs.push_back(leg);
  }
  return d;
}

TEST(LegChainVjm, UpsLegsWithSectionsAreTheAxialModelExactly) {
  const LegChainMachine vjm(ups_chain(true)), axial(ups_chain(false));
  ASSERT_TRUE(vjm.link_compliance_model());
  ASSERT_FALSE(axial.link_compliance_model());
  const Wrench w = (Wrench() << 4e3, -2e3, -9e3, 300, -500, 200).finished();
  for (const Pose& pose :
       {pose_deg(0.02, -0.03, 0.9, 4, -3, 6), pose_deg(-0.08, 0.05, 1.0, -7, 9, -12)}) {
    const Analyzed v = analyze(vjm, pose, w), a = analyze(axial, pose, w);
    ASSERT_FALSE(a.singular);
    ASSERT_FALSE(v.singular);
    EXPECT_LT(rel_diff(v.compliance, a.compliance, true), 1e-12);
    EXPECT_NEAR(v.stiffness_min, a.stiffness_min, 1e-12 * a.stiffness_min);
    EXPECT_NEAR(v.tcp_deflection, a.tcp_deflection, 1e-12 * a.tcp_deflection);
    EXPECT_NEAR(v.tcp_rotation_deflection, a.tcp_rotation_deflection,
                1e-12 * a.tcp_rotation_deflection);
    EXPECT_NEAR(v.stiffness_min_loaded, a.stiffness_min_loaded, 1e-12 * a.stiffness_min_loaded);
    EXPECT_NE(v.stiffness_min_loaded, v.stiffness_min);  // the load shows
  }
  // The hexaglide's struts (universal joint at the carriage, spherical at the platform) with a
  // section: the axial model with the section's E * A.
  HexaglideDesign g;
  g.stiffness.section = tube_section(kSteelE, kSteelG, 0.05, 0.04);
  const LegChainMachine glide_vjm(hexaglide_design(g));
  g.stiffness.section.reset();
  g.stiffness.area = tube_section(kSteelE, kSteelG, 0.05, 0.04).A;
  g.stiffness.E = kSteelE;
  const LegChainMachine glide_axial(hexaglide_design(g));
  const Pose pose = pose_deg(0.05, 0.02, 0.62, 3, -2, 5);
  const Analyzed v = analyze(glide_vjm, pose, w), a = analyze(glide_axial, pose, w);
  EXPECT_LT(rel_diff(v.compliance, a.compliance, true), 1e-12);
}

// The loaded stiffness with link compliance: K_T = C^-1 + the geometric terms of the rod forces
// (actuated points fixed) and of the plane constraints' reactions (fixed normals), computed here
// by central differences of that wrench at constant forces.
double expected_loaded_min(const LegChainMachine& m, const Pose& pose, const Wrench& w,
                           const Analyzed& metrics) {
  const Pose actual = *m.actual_pose(pose);
  const std::vector<LegGeometry> legs = leg_geometry(m, actual);
  const int n = m.num_actuators();
  const bool planar = m.design().mobility == PlatformMobility::kPlanarLegs;
  Eigen::VectorXd f(n);
  Eigen::MatrixXd Z(6, planar ? 2 * n : n);
  for (int i = 0; i < n; ++i) {
    const LegGeometry& g = legs[static_cast<std::size_t>(i)];
    f(i) = metrics.tau(i) / g.s.dot(g.dc);  // tau_i = B_i f_i
    Z.col(i) << g.s, (g.P - actual.position).cross(g.s);
    if (planar) {
      const Vector3d nj = m.design().legs[static_cast<std::size_t>(i)].plane_normal;
      Z.col(n + i) << nj, (g.P - actual.position).cross(nj);
    }
  }
  Eigen::VectorXd lambda = Eigen::VectorXd::Zero(n);
  if (planar) lambda = Eigen::MatrixXd(Z).fullPivLu().solve(w).tail(n);
  auto held = [&](const Vec6<double>& dx) {
    const Eigen::Matrix3d dR = rotation_from_vector(Vector3d(dx.tail<3>()));
    Vec6<double> total = Vec6<double>::Zero();
    for (int i = 0; i < n; ++i) {
      const LegGeometry& g = legs[static_cast<std::size_t>(i)];
      const Vector3d r = dR * (g.P - actual.position), P = actual.position + dx.head<3>() + r;
      const Vector3d s = (P - g.c).normalized();
      total.head<3>() += f(i) * s;
      total.tail<3>() += f(i) * r.cross(s);
      if (planar) {
        const Vector3d nj = m.design().legs[static_cast<std::size_t>(i)].plane_normal;
        total.head<3>() += lambda(i) * nj;
        total.tail<3>() += lambda(i) * r.cross(nj);
      }
    }
    return total;
  };
  Matrix6d G;
  const double h = 1e-7;
  for (int j = 0; j < 6; ++j) {
    const Vec6<double> dx = h * Vec6<double>::Unit(j);
    G.col(j) = (held(dx) - held(-dx)) / (2 * h);
  }
  const Matrix6d KT = Matrix6d(metrics.compliance.inverse()) + G;
  const Eigen::Matrix3d CTtt = Matrix6d(KT.inverse()).topLeftCorner<3, 3>();
  return 1.0 / Eigen::JacobiSVD<Eigen::Matrix3d>(CTtt).singularValues()(0);
}

TEST(LegChainVjm, LoadedStiffnessAddsTheGeometricTermsOfRodsAndConstraints) {
  const LegChainMachine tripod(tripod_3prs_design(tube_tripod()));
  const LegChainMachine delta(delta_design(wide_delta()));
  const Wrench heavy = (Wrench() << 8e3, -5e3, -2e4, 1.5e3, -1e3, 2e3).finished();
  const Wrench light = (Wrench() << 60, -40, -150, 4, -3, 5).finished();
  struct Run {
    const LegChainMachine* m;
    Pose pose;
    Wrench w;
  };
  for (const Run& run : {Run{&tripod, pose_deg(0, 0, 1.2, 15, -10), heavy},
                         Run{&tripod, pose_deg(0, 0, 1.05, -28, 20), heavy},
                         Run{&delta, Pose{{0.1, -0.15, -1.1}, Vector3d::Zero()}, light}}) {
    const Analyzed metrics = analyze(*run.m, run.pose, run.w);
    ASSERT_FALSE(metrics.singular);
    const double expected = expected_loaded_min(*run.m, run.pose, run.w, metrics);
    EXPECT_NEAR(metrics.stiffness_min_loaded, expected, 1e-6 * expected);
    EXPECT_GT(std::abs(metrics.stiffness_min_loaded - metrics.stiffness_min),
              1e-6 * metrics.stiffness_min)
        << "the load must change the stiffness";
  }
}

// A Schoenflies machine (examples/schoenflies_4pus.yaml) whose parallelogram pairs are 0.05 m wide:
// the bars along the rotation axis hold the two other rotations elastically.
LegChainDesign schoenflies_pairs() {
  LegChainDesign d;
  d.mobility = PlatformMobility::kSchoenflies;
  d.tcp = Vector3d(0, 0, -0.05);
  const std::array<Vector3d, 4> guides{Vector3d(0.4, 0, 0), Vector3d(0, 0.4, 0),
                                       Vector3d(-0.4, 0, 0), Vector3d(0, -0.4, 0)};
  const std::array<Vector3d, 4> joints{Vector3d(0.06, 0.103923, 0), Vector3d(0.103923, 0.06, 0),
                                       Vector3d(-0.06, -0.103923, 0),
                                       Vector3d(-0.103923, -0.06, 0)};
  for (std::size_t i = 0; i < 4; ++i) {
    LegChainLeg leg;
    leg.kind = LegKind::kPUS;
    leg.base_point = guides[i];
    leg.axis = Vector3d::UnitZ();
    leg.link_length = 0.5;
    leg.platform_point = joints[i];
    leg.q_min = -0.5;
    leg.q_max = 1.0;
    leg.branch = -1;
    leg.E = kAluE;
    leg.area = 3.0e-5;
    leg.rods = 2;
    leg.actuator_stiffness = 2.0e7;
    leg.parallelogram_width = 0.05;
    d.legs.push_back(leg);
  }
  return d;
}

// analyze eliminates the passive joints in closed form (the wrenches each leg transmits, from its
// geometry); VjmLeg::stiffness eliminates them by the QR of their twists: the same stiffness for
// every kind of leg.
TEST(LegChainVjm, ClosedFormEliminationIsTheGeneralOne) {
  DeltaDesign cranks_only;
  cranks_only.crank_section = wide_delta().crank_section;
  cranks_only.stiffness.actuator_stiffness = 1.5e5;
  cranks_only.stiffness.base_joint_stiffness = 4e7;
  HexaglideDesign glide;
  glide.stiffness.section = tube_section(kSteelE, kSteelG, 0.05, 0.04);
  glide.stiffness.platform_joint_stiffness = 7e8;
  LinearDeltaDesign linear;
  linear.inclination = 0.2;
  linear.stiffness.section = tube_section(kAluE, kAluG, 0.012, 0.008);
  linear.stiffness.parallelogram_width = 0.06;
  struct Case {
    std::string name;
    LegChainDesign design;
    Pose pose;
    bool full;
  };
  for (const Case& c :
       {Case{"tripod", tripod_3prs_design(tube_tripod()), pose_deg(0, 0, 1.2, 18, -11), true},
        Case{"delta", delta_design(wide_delta()), Pose{{0.1, -0.2, -1.05}, Vector3d::Zero()}, true},
        Case{"delta_cranks", delta_design(cranks_only), Pose{{-0.1, 0.15, -1.0}, Vector3d::Zero()},
             false},
        Case{"ups", ups_chain(true), pose_deg(0.02, -0.03, 0.9, 4, -3, 6), true},
        Case{"hexaglide", hexaglide_design(glide), pose_deg(0.05, 0.02, 0.62, 3, -2, 5), true},
        Case{"linear_delta", linear_delta_design(linear), Pose{{0.03, 0.02, 0.2}, Vector3d::Zero()},
             true},
        Case{"schoenflies", schoenflies_pairs(), pose_deg(0.01, 0.02, -0.03, 0, 0, 10), true}}) {
    const LegChainMachine m(c.design);
    ASSERT_TRUE(m.link_compliance_model()) << c.name;
    EXPECT_EQ(m.link_compliance_full(), c.full) << c.name;
    auto data = m.make_data();
    auto& d = static_cast<LegChainData&>(*data);
    PoseMetrics metrics;
    m.analyze(d, c.pose, Wrench::Zero(), metrics);
    ASSERT_FALSE(metrics.singular) << c.name;
    Matrix6d K_sum = Matrix6d::Zero();
    for (int i = 0; i < m.num_actuators(); ++i) {
      VjmLeg leg;
      TransmittedWrenches wrenches;
      m.vjm_leg(d, i, leg, wrenches);
      const LegCompliance general = leg.stiffness(d.position);
      const LegCompliance closed = leg.stiffness_for_wrenches(d.position, wrenches);
      EXPECT_FALSE(general.rigid) << c.name << " leg " << i;
      EXPECT_FALSE(closed.rigid) << c.name << " leg " << i;
      EXPECT_EQ(closed.constrained_dim, general.constrained_dim) << c.name << " leg " << i;
      EXPECT_LT(rel_diff(closed.stiffness, general.stiffness, false), 1e-9)
          << c.name << " leg " << i;
      K_sum += general.stiffness;
    }
    Matrix6d K;
    ASSERT_TRUE(m.vjm_stiffness(d, K));
    EXPECT_LT(rel_diff(K, K_sum, false), 1e-9) << c.name;
    if (c.full) {
      EXPECT_LT(rel_diff(d.matrices.compliance, Matrix6d(K_sum.inverse()), true), 1e-9) << c.name;
    }
  }
}

#if defined(__GLIBC__) || defined(PKMOPT_TEST_ASAN)
}  // namespace
}  // namespace pkmopt

// Counts the heap allocations (malloc: operator new and Eigen's allocations) while enabled.
// Under AddressSanitizer, which owns malloc and free, through its allocation hook; otherwise by
// replacing glibc's malloc (replacing it under ASan would pair glibc's malloc with ASan's free).
namespace {
bool g_count_allocations = false;
long g_allocations = 0;
}  // namespace
#if defined(PKMOPT_TEST_ASAN)
namespace {
void count_allocation(const volatile void*, std::size_t) {
  if (g_count_allocations) ++g_allocations;
}
void ignore_free(const volatile void*) {}
const int g_hooks_installed =
    __sanitizer_install_malloc_and_free_hooks(count_allocation, ignore_free);
}  // namespace
#else
extern "C" void* __libc_malloc(std::size_t size);
extern "C" void* malloc(std::size_t size) {
  if (g_count_allocations) ++g_allocations;
  return __libc_malloc(size);
}
#endif

namespace pkmopt {
namespace {

// The per-pose VJM path allocates nothing (after the first call has sized the outputs).
TEST(LegChainVjm, AnalyzeAllocatesNothingPerPose) {
  DeltaDesign cranks_only;
  cranks_only.crank_section = wide_delta().crank_section;
  for (const LegChainDesign& design :
       {tripod_3prs_design(tube_tripod()), delta_design(wide_delta()), delta_design(cranks_only)}) {
    const LegChainMachine m(design);
    auto data = m.make_data();
    PoseMetrics metrics;
    const Wrench w = (Wrench() << 100, -50, -300, 5, -4, 3).finished();
    const bool tripod = m.design().mobility == PlatformMobility::kPlanarLegs;
    const Pose first = tripod ? pose_deg(0, 0, 1.2, 10, 5) : Pose{{0, 0, -1.0}, Vector3d::Zero()};
    m.analyze(*data, first, w, metrics);
#if defined(PKMOPT_TEST_ASAN)
    ASSERT_NE(g_hooks_installed, 0);
#endif
    g_allocations = 0;
    g_count_allocations = true;
    for (int k = 0; k < 20; ++k) {
      const double a = 0.05 * k;
      const Pose pose =
          tripod ? pose_deg(0, 0, 1.0 + 0.02 * k, 25 * std::sin(a), -20 * std::cos(a))
                 : Pose{{0.1 * std::sin(a), -0.1 * std::cos(a), -1.1 + 0.01 * k}, Vector3d::Zero()};
      m.analyze(*data, pose, w, metrics);
    }
    g_count_allocations = false;
    EXPECT_EQ(g_allocations, 0) << m.design().model;
    EXPECT_TRUE(data->matrices.compliance.allFinite());
  }
}
#endif

// Without a wrench, at the home pose and with the design metrics off, the stiffness is the same.
TEST(LegChainVjm, StiffnessMinDoesNotNeedTheComplianceMetrics) {
  const LegChainMachine m(tripod_3prs_design(tube_tripod()));
  const Pose pose = pose_deg(0, 0, 1.2, 20, -15);
  auto data = m.make_data();
  PoseMetrics full, lean;
  m.analyze(*data, pose, Wrench::Zero(), full);
  const Matrix6d full_compliance = data->matrices.compliance;
  data->compliance_metrics = false;
  m.analyze(*data, pose, Wrench::Zero(), lean);
  EXPECT_EQ(lean.stiffness_min, full.stiffness_min);
  Eigen::Matrix3d Ctt;
  Eigen::Matrix<double, 3, Eigen::Dynamic> error_map;
  ASSERT_TRUE(m.analyze_with_maps(*data, pose, Wrench::Zero(), lean, Ctt, error_map));
  const Eigen::Matrix3d full_tt = full_compliance.topLeftCorner<3, 3>();
  EXPECT_EQ(Ctt, full_tt);
}

TEST(LegChainVjm, DesignChecksNameTheLeg) {
  auto message = [](const LegChainDesign& d) {
    try {
      const LegChainMachine m(d);
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  LegChainDesign tripod = tripod_3prs_design(tube_tripod());
  tripod.legs[1].link_section.reset();
  EXPECT_EQ(message(tripod),
            "planar legs with link compliance: every leg needs a link_section (the strut's "
            "bending carries its revolute joint's constraint)");
  tripod = tripod_3prs_design(tube_tripod());
  tripod.legs[2].link_section->Iz = 0.0;
  EXPECT_EQ(message(tripod),
            "leg 3: link_section: E, G, A, Iy, Iz and J must be finite numbers > 0");
  tripod = tripod_3prs_design(tube_tripod());
  tripod.legs[0].crank_section = tube_section(kSteelE, kSteelG, 0.05);
  EXPECT_EQ(message(tripod), "leg 1: a crank_section needs a RUS leg");
  LegChainDesign delta = delta_design(wide_delta());
  delta.legs[1].parallelogram_width = 0.0;
  EXPECT_EQ(message(delta), "parallelogram_width: on every leg or on none");
  delta = delta_design(wide_delta());
  delta.legs[0].rods = 1;
  EXPECT_EQ(message(delta), "leg 1: parallelogram_width needs rods = 2 (a parallelogram pair)");
  delta = delta_design(wide_delta());
  delta.legs[2].parallelogram_axis = Vector3d(0, 0, 1);
  EXPECT_EQ(message(delta), "leg 3: parallelogram_axis must be parallel to the crank axis");
  LinearDeltaDesign linear;
  linear.stiffness.parallelogram_width = 0.06;
  LegChainDesign pus = linear_delta_design(linear);
  EXPECT_EQ(message(pus), "no error");
  pus.legs[0].parallelogram_axis.setZero();
  EXPECT_EQ(message(pus),
            "leg 1: parallelogram_axis is needed: the direction of the pair's bars (base frame)");
  LegChainDesign hexapod = ups_chain(true);
  hexapod.legs[4].rods = 2;
  hexapod.legs[4].parallelogram_width = 0.05;
  EXPECT_EQ(message(hexapod), "leg 5: parallelogram_width needs a PUS or RUS leg");
}

}  // namespace
}  // namespace pkmopt
