// Tests of models/dynamics/machine_dynamics on hexapods: the TCP mass matrix against the kinetic
// energy of every body computed here from the bodies' positions along a motion (finite
// differences), the gravity and inertia wrench against the energy balance, the natural modes
// against K x = omega^2 M x, the cubic Gough-Stewart platform's closed-form frequencies, leg masses
// lowering every frequency, and the mode shapes of Machine::mode_shapes.
#include "models/dynamics/machine_dynamics.hpp"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

#include "models/hexapod/hexapod.hpp"
#include "tests/models/dynamics/hexapod_bodies.hpp"
#include "tests/sample_machines.hpp"

namespace pkmopt {
namespace {

using sample_machines::Uniform;

// The pose reached from `pose` along the twist [v; omega] (base axes, at the TCP) and its rate
// [a; alpha] after time t, to O(t^3): position p + v t + a t^2 / 2, rotation
// exp([omega t + alpha t^2 / 2]x) R.
Pose moved(const Pose& pose, const Vector6d& xi, const Vector6d& xi_dot, double t) {
  const Eigen::Vector3d turn = xi.tail<3>() * t + 0.5 * xi_dot.tail<3>() * t * t;
  Eigen::Matrix3d R = rotation_zyx<double>(pose.angles);
  if (turn.norm() > 0) R = Eigen::AngleAxisd(turn.norm(), turn.normalized()).toRotationMatrix() * R;
  return Pose{pose.position + xi.head<3>() * t + 0.5 * xi_dot.head<3>() * t * t,
              angles_from_rotation(R)};
}

// The kinetic energy of every body at the pose, from central differences of the bodies' centres
// and directions along the twist (the test's own model of the bodies).
double kinetic_energy(const Hexapod& hexapod, const Pose& pose, const Vector6d& xi) {
  const double h = 1e-6;
  const HexapodDesign& d = hexapod.design();
  const MassModel& m = d.masses;
  const Pose plus = moved(pose, xi, Vector6d::Zero(), h),
             minus = moved(pose, xi, Vector6d::Zero(), -h);
  const Eigen::Matrix3d R = rotation_zyx<double>(pose.angles);
  auto centre = [&](const Pose& p) {
    return Eigen::Vector3d(p.position +
                           rotation_zyx<double>(p.angles) * (m.platform.centre_of_mass - d.tcp));
  };
  const Eigen::Vector3d v_c = (centre(plus) - centre(minus)) / (2 * h);
  const Eigen::Vector3d omega = xi.tail<3>();
  double T = 0.5 * m.platform.mass * v_c.squaredNorm() +
             0.5 * omega.dot(R * m.platform.inertia * R.transpose() * omega);
  auto joints = [&](const Pose& p, int i) {
    return Eigen::Vector3d(p.position +
                           rotation_zyx<double>(p.angles) * (d.platform_joints.col(i) - d.tcp));
  };
  for (int i = 0; i < 6; ++i) {
    const Eigen::Vector3d a = d.base_joints.col(i);
    auto s_of = [&](const Pose& p) { return Eigen::Vector3d((joints(p, i) - a).normalized()); };
    const Eigen::Vector3d s = s_of(pose), s_dot = (s_of(plus) - s_of(minus)) / (2 * h);
    const Eigen::Vector3d c1_dot = m.legs.cylinder.centre * s_dot;
    const Eigen::Vector3d c2_dot = ((joints(plus, i) - m.legs.rod.centre * s_of(plus)) -
                                    (joints(minus, i) - m.legs.rod.centre * s_of(minus))) /
                                   (2 * h);
    const Eigen::Vector3d w = s.cross(s_dot);
    T += 0.5 * m.legs.cylinder.mass * c1_dot.squaredNorm() +
         0.5 * m.legs.rod.mass * c2_dot.squaredNorm() +
         0.5 * (m.legs.cylinder.inertia + m.legs.rod.inertia) * w.squaredNorm();
  }
  return T;
}

Vector6d random_twist(Uniform& u) {
  Vector6d xi;
  xi << u(-1, 1), u(-1, 1), u(-1, 1), u(-2, 2), u(-2, 2), u(-2, 2);
  return xi;
}

TEST(MachineDynamics, MassMatrixGivesTheKineticEnergyOfEveryBody) {
  Uniform u(41);
  for (int g = 0; g < 8; ++g) {
    HexapodDesign design = sample_machines::random_hexapod_design(u);
    design.masses = sample_machines::random_hexapod_masses(u);
    const Hexapod hexapod(design);
    for (int k = 0; k < 4; ++k) {
      const Pose pose = sample_machines::random_pose(u);
      const Matrix6d M = hexapod.mass_matrix(pose);
      EXPECT_LE((M - M.transpose()).norm(), 1e-12 * M.norm());
      EXPECT_GT(Eigen::SelfAdjointEigenSolver<Matrix6d>(M).eigenvalues().minCoeff(), 0.0);
      const Vector6d xi = random_twist(u);
      const double T = kinetic_energy(hexapod, pose, xi);
      EXPECT_NEAR(0.5 * xi.dot(M * xi), T, 1e-7 * T) << "design " << g << " pose " << k;
    }
  }
}

// The power of the inertia wrench (no gravity) is -dT/dt along a motion with twist xi and twist
// rate xi_dot, T(t) = 1/2 xi(t)^T M(x(t)) xi(t); the gravity wrench's power is the rate of the
// bodies' potential energy (checked per leg in leg_dynamics_test; here the platform's).
TEST(MachineDynamics, DynamicWrenchMatchesTheEnergyBalance) {
  Uniform u(42);
  for (int g = 0; g < 6; ++g) {
    HexapodDesign design = sample_machines::random_hexapod_design(u);
    design.masses = sample_machines::random_hexapod_masses(u);
    const Eigen::Vector3d gravity = design.masses.gravity;
    const Hexapod hexapod(design);
    const Pose pose = sample_machines::random_pose(u);
    const Vector6d xi = random_twist(u), xi_dot = 10.0 * random_twist(u);
    const double h = 1e-5;
    auto energy = [&](double t) {
      const Vector6d x = xi + xi_dot * t;
      return 0.5 * x.dot(hexapod.mass_matrix(moved(pose, xi, xi_dot, t)) * x);
    };
    const double dT = (energy(h) - energy(-h)) / (2 * h);
    MassModel no_gravity = design.masses;
    no_gravity.gravity.setZero();
    const Eigen::Matrix3d R = rotation_zyx<double>(pose.angles);
    const std::vector<LegPoints> legs = hexapod.leg_points(pose);
    const Wrench inertia =
        dynamic_wrench(no_gravity, R, design.tcp, legs, pose.position, xi, xi_dot);
    EXPECT_NEAR(inertia.dot(xi), -dT, 1e-6 * (1 + std::abs(dT))) << "design " << g;
    // Zero motion: the gravity wrench; its power along xi is d/dt of m g . c summed over bodies.
    const Wrench static_w = dynamic_wrench(design.masses, R, design.tcp, legs, pose.position,
                                           Vector6d::Zero(), Vector6d::Zero());
    auto potential = [&](double t) {
      const Pose p = moved(pose, xi, Vector6d::Zero(), t);
      double V = design.masses.platform.mass *
                 gravity.dot(p.position + rotation_zyx<double>(p.angles) *
                                              (design.masses.platform.centre_of_mass - design.tcp));
      for (const LegPoints& leg : hexapod.leg_points(p)) {
        const Eigen::Vector3d s = (leg.platform - leg.joint).normalized();
        V += design.masses.legs.cylinder.mass *
             gravity.dot(leg.joint + design.masses.legs.cylinder.centre * s);
        V += design.masses.legs.rod.mass *
             gravity.dot(leg.platform - design.masses.legs.rod.centre * s);
      }
      return V;
    };
    const double dV = (potential(h) - potential(-h)) / (2 * h);
    EXPECT_NEAR(static_w.dot(xi), dV, 1e-6 * (1 + std::abs(dV))) << "design " << g;
  }
}

TEST(MachineDynamics, NaturalModesSolveTheGeneralizedEigenproblem) {
  Uniform u(43);
  HexapodDesign design = sample_machines::random_hexapod_design(u);
  design.masses = sample_machines::random_hexapod_masses(u);
  const Hexapod hexapod(design);
  const Pose pose = sample_machines::random_pose(u);
  const Matrix6d K = hexapod.stiffness_matrix(pose);
  const Matrix6d M = hexapod.mass_matrix(pose);
  const NaturalModes modes = natural_modes(Eigen::MatrixXd(K.inverse()), Eigen::MatrixXd(M), true);
  ASSERT_TRUE(modes.ok);
  for (int k = 0; k < 6; ++k) {
    if (k > 0) {
      EXPECT_GE(modes.frequencies(k), modes.frequencies(k - 1));
    }
    const double w2 = std::pow(2 * std::numbers::pi * modes.frequencies(k), 2);
    const Vector6d x = modes.shapes.col(k);
    EXPECT_LE((K * x - w2 * M * x).norm(), 1e-8 * (K * x).norm()) << k;
    EXPECT_NEAR(x.dot(M * x), 1.0, 1e-10);
  }
  // Against Eigen's generalized solver; the fixed-size path gives the same.
  const Eigen::GeneralizedSelfAdjointEigenSolver<Matrix6d> ges(K, M);
  const NaturalModes fixed = natural_frequencies6(K.inverse(), M);
  ASSERT_TRUE(fixed.ok);
  for (int k = 0; k < 6; ++k) {
    const double f = std::sqrt(ges.eigenvalues()(k)) / (2 * std::numbers::pi);
    EXPECT_NEAR(modes.frequencies(k), f, 1e-9 * f);
    EXPECT_NEAR(fixed.frequencies(k), f, 1e-9 * f);
  }
  // A rigid direction (zero compliance) has no finite frequency; a mass matrix that is not
  // positive definite is refused.
  Eigen::MatrixXd C = Eigen::MatrixXd::Identity(2, 2);
  C(1, 1) = 0.0;
  const NaturalModes rigid = natural_modes(C, Eigen::MatrixXd::Identity(2, 2), false);
  EXPECT_TRUE(rigid.ok);
  EXPECT_NEAR(rigid.frequencies(0), 1 / (2 * std::numbers::pi), 1e-15);
  EXPECT_TRUE(std::isinf(rigid.frequencies(1)));
  EXPECT_FALSE(natural_modes(C, Eigen::MatrixXd::Zero(2, 2), false).ok);
}

// The cubic Gough-Stewart platform (Geng & Haynes 1994; K = k diag(2, 2, 2, 3/2 Hc^2, 3/2 Hc^2,
// 6 Hc^2) at the cube centre, hexapod_test's published case) with massless legs and the centre
// of mass at the TCP: M = diag(m, m, m, Ixx, Iyy, Izz) and f_j = sqrt(K_jj / M_jj) / 2 pi. Leg
// masses then lower every frequency.
TEST(MachineDynamics, CubicHexapodHasTheClosedFormFrequencies) {
  const double Hc = 0.1, k = 2.0e7;
  HexapodDesign design = sample_machines::cubic_hexapod_design(Hc, k);
  design.masses.present = true;
  design.masses.platform.mass = 12.0;
  design.masses.platform.inertia = Eigen::Vector3d(0.11, 0.13, 0.2).asDiagonal();
  const Hexapod hexapod(design);
  HexapodData data(hexapod);
  PoseMetrics m;
  const Pose centre{{0, 0, 0}, {0, 0, 0}};
  hexapod.analyze(data, centre, Wrench::Zero(), m);
  ASSERT_EQ(m.natural_frequencies.size(), 6);
  const double K[6] = {2 * k, 2 * k, 2 * k, 1.5 * Hc * Hc * k, 1.5 * Hc * Hc * k, 6 * Hc * Hc * k};
  const double Mass[6] = {12, 12, 12, 0.11, 0.13, 0.2};
  std::vector<double> expected;
  for (int j = 0; j < 6; ++j)
    expected.push_back(std::sqrt(K[j] / Mass[j]) / (2 * std::numbers::pi));
  std::sort(expected.begin(), expected.end());
  for (int j = 0; j < 6; ++j) {
    EXPECT_NEAR(m.natural_frequencies(j), expected[static_cast<std::size_t>(j)],
                1e-9 * expected[static_cast<std::size_t>(j)])
        << j;
  }
  // Leg masses lower every frequency.
  HexapodDesign heavy = design;
  heavy.masses.legs.cylinder = {.mass = 2.0, .centre = 0.03, .inertia = 0.002};
  heavy.masses.legs.rod = {.mass = 1.0, .centre = 0.04, .inertia = 0.001};
  const Hexapod heavy_hexapod(heavy);
  PoseMetrics mh;
  heavy_hexapod.analyze(*heavy_hexapod.make_data(), centre, Wrench::Zero(), mh);
  for (int j = 0; j < 6; ++j) EXPECT_LT(mh.natural_frequencies(j), m.natural_frequencies(j)) << j;
}

// A hexapod on a base translating with velocity d: 1/2 [d; xi]^T Q [d; xi] (carried_mass_matrix)
// is the kinetic energy of every body computed from their positions on the moving base
// (tests/models/dynamics/hexapod_bodies.hpp) by central differences; the net force of gravity and
// inertia at rest is the total weight.
TEST(MachineDynamics, CarriedMassMatrixGivesTheKineticEnergyOnAMovingBase) {
  Uniform u(43);
  for (int g = 0; g < 6; ++g) {
    HexapodDesign design = sample_machines::random_hexapod_design(u);
    design.masses = sample_machines::random_hexapod_masses(u);
    const Hexapod hexapod(design);
    const auto data = hexapod.make_data();
    const Pose pose = sample_machines::random_pose(u);
    const Vector6d xi = random_twist(u);
    const Eigen::Vector3d d(u(-1, 1), u(-1, 1), u(-1, 1));
    Wrench w_dyn;
    Eigen::Vector3d net;
    Eigen::Matrix<double, 9, 9> Q;
    ASSERT_TRUE(hexapod.carried_dynamics(*data, pose, Vector6d::Zero(), Vector6d::Zero(),
                                         design.masses.gravity, w_dyn, net, &Q));
    const double total = design.masses.platform.mass +
                         6 * (design.masses.legs.cylinder.mass + design.masses.legs.rod.mass);
    EXPECT_LT((net - total * design.masses.gravity).norm(), 1e-10 * total * 9.81);
    EXPECT_LE((Q - Q.transpose()).norm(), 1e-12 * Q.norm());
    const double h = 1e-6;
    auto bodies = [&](double t) {
      HexapodDesign shifted = design;
      for (int i = 0; i < 6; ++i) shifted.base_joints.col(i) += d * t;
      return test_bodies::bodies_at(shifted, moved(pose, xi, Vector6d::Zero(), t));
    };
    const test_bodies::HexapodBodies b = bodies(0), plus = bodies(h), minus = bodies(-h);
    const MassModel& m = design.masses;
    const Eigen::Vector3d v_c = (plus.platform_centre - minus.platform_centre) / (2 * h);
    const Eigen::Vector3d omega = xi.tail<3>();
    double T = 0.5 * m.platform.mass * v_c.squaredNorm() +
               0.5 * omega.dot(b.R * m.platform.inertia * b.R.transpose() * omega);
    for (int i = 0; i < 6; ++i) {
      const Eigen::Vector3d v1 = (plus.cylinder[i] - minus.cylinder[i]) / (2 * h);
      const Eigen::Vector3d v2 = (plus.rod[i] - minus.rod[i]) / (2 * h);
      const Eigen::Vector3d w = b.s[i].cross((plus.s[i] - minus.s[i]) / (2 * h));
      T += 0.5 * m.legs.cylinder.mass * v1.squaredNorm() +
           0.5 * m.legs.rod.mass * v2.squaredNorm() +
           0.5 * (m.legs.cylinder.inertia + m.legs.rod.inertia) * w.squaredNorm();
    }
    Eigen::Matrix<double, 9, 1> z;
    z << d, xi;
    EXPECT_NEAR(0.5 * z.dot(Q * z), T, 1e-7 * T) << "design " << g;
  }
}

// A semi-regular hexapod at its home pose (three-fold and mirror symmetric), massless legs, the
// centre of mass at the TCP on the axis: the vertical translation and the yaw decouple from the
// other four directions, so two of the six frequencies are sqrt(K_zz / m) / 2 pi and
// sqrt(K_yaw / I_zz) / 2 pi with K = J^T diag(k) J, and the other four come in equal pairs (x
// with ry, y with rx).
TEST(MachineDynamics, SymmetricHexapodHasDecoupledVerticalAndYawModes) {
  HexapodDesign design = sample_machines::conventions_hexapod_design();
  design.tcp = {0, 0, -0.1};
  design.masses.present = true;
  design.masses.platform = sample_machines::milling_hexapod_masses().platform;
  design.masses.platform.centre_of_mass = design.tcp;  // massless legs, centre of mass at the TCP
  const Hexapod hexapod(design);
  const Pose home{{0, 0, 0.9}, {0, 0, 0}};
  HexapodData data(hexapod);
  PoseMetrics m;
  hexapod.analyze(data, home, Wrench::Zero(), m);
  ASSERT_EQ(m.natural_frequencies.size(), 6);
  const Matrix6d K = hexapod.stiffness_matrix(home);
  const double f_z = std::sqrt(K(2, 2) / 45.0) / (2 * std::numbers::pi);
  const double f_yaw = std::sqrt(K(5, 5) / 2.0) / (2 * std::numbers::pi);
  auto found = [&](double f) {
    double nearest = std::numeric_limits<double>::infinity();
    for (int j = 0; j < 6; ++j) nearest = std::min(nearest, std::abs(m.natural_frequencies(j) - f));
    return nearest;
  };
  EXPECT_LT(found(f_z), 1e-9 * f_z) << m.natural_frequencies.transpose() << " f_z " << f_z;
  EXPECT_LT(found(f_yaw), 1e-9 * f_yaw) << m.natural_frequencies.transpose() << " f_yaw " << f_yaw;
  // The four others: two equal pairs.
  std::vector<double> rest;
  for (int j = 0; j < 6; ++j) {
    const double f = m.natural_frequencies(j);
    if (std::abs(f - f_z) > 1e-6 * f_z && std::abs(f - f_yaw) > 1e-6 * f_yaw) rest.push_back(f);
  }
  ASSERT_EQ(rest.size(), 4u);
  EXPECT_NEAR(rest[0], rest[1], 1e-9 * rest[1]);
  EXPECT_NEAR(rest[2], rest[3], 1e-9 * rest[3]);
  // The vertical mode is a pure z translation and the yaw mode a pure turn about z,
  // mass-normalised: 1 / sqrt(m) and 1 / sqrt(I_zz).
  PoseModes modes;
  ASSERT_TRUE(hexapod.mode_shapes(data, home, modes));
  for (int j = 0; j < 6; ++j) {
    const Vector6d x = modes.shapes.col(j);
    if (std::abs(modes.frequencies(j) - f_z) < 1e-6 * f_z) {
      EXPECT_LT((x - Vector6d::Unit(2) / std::sqrt(45.0)).norm(), 1e-9) << x.transpose();
    } else if (std::abs(modes.frequencies(j) - f_yaw) < 1e-6 * f_yaw) {
      EXPECT_LT((x - Vector6d::Unit(5) / std::sqrt(2.0)).norm(), 1e-9) << x.transpose();
    }
  }
}

// The mode shapes of random hexapods with leg masses at random poses solve
// K x = omega^2 M x with K = J^T diag(k) J (Hexapod::stiffness_matrix, not the compliance the
// frequencies come from) and M the TCP mass matrix; they are M-orthonormal, carry the
// frequencies analyze reports, and the largest component is positive.
TEST(MachineDynamics, ModeShapesSolveTheEigenproblemAtRandomPoses) {
  Uniform u(47);
  for (int g = 0; g < 8; ++g) {
    HexapodDesign design = sample_machines::random_hexapod_design(u);
    design.masses = sample_machines::random_hexapod_masses(u);
    const Hexapod hexapod(design);
    const auto data = hexapod.make_data();
    const Pose pose = sample_machines::random_pose(u);
    PoseMetrics m;
    hexapod.analyze(*data, pose, Wrench::Zero(), m);
    if (!m.reachable || m.singular) continue;
    PoseModes modes;
    ASSERT_TRUE(hexapod.mode_shapes(*data, pose, modes));
    Matrix6d M;
    ASSERT_TRUE(hexapod.mass_matrix(*data, pose, M));
    const Matrix6d K = hexapod.stiffness_matrix(pose);
    ASSERT_EQ(modes.shapes.rows(), 6);
    ASSERT_EQ(modes.shapes.cols(), 6);
    const Matrix6d X = modes.shapes;
    EXPECT_LT((X.transpose() * M * X - Matrix6d::Identity()).norm(), 1e-9) << "design " << g;
    for (int j = 0; j < 6; ++j) {
      EXPECT_NEAR(modes.frequencies(j), m.natural_frequencies(j), 1e-9 * m.natural_frequencies(j));
      const double omega = 2 * std::numbers::pi * modes.frequencies(j);
      const Vector6d x = X.col(j);
      EXPECT_LT((K * x - omega * omega * M * x).norm(), 1e-8 * (K * x).norm()) << g << " " << j;
      Eigen::Index lead = 0;
      x.cwiseAbs().maxCoeff(&lead);
      EXPECT_GT(x(lead), 0.0);
    }
  }
}

// Without masses there are no modes; an unreachable pose has none either.
TEST(MachineDynamics, NoModesWithoutMassesOrOutsideTheWorkspace) {
  HexapodDesign design = sample_machines::conventions_hexapod_design();
  PoseModes modes;
  const Hexapod bare(design);
  EXPECT_FALSE(bare.mode_shapes(*bare.make_data(), Pose{{0, 0, 0.9}, {0, 0, 0}}, modes));
  design.masses = sample_machines::milling_hexapod_masses();
  const Hexapod heavy(design);
  EXPECT_FALSE(heavy.mode_shapes(*heavy.make_data(), Pose{{0, 0, 5.0}, {0, 0, 0}}, modes));
  EXPECT_EQ(modes.shapes.size(), 0);
}

}  // namespace
}  // namespace pkmopt
