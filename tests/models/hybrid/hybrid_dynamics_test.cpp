// Tests of models/hybrid/hybrid_dynamics (the dynamics of a hybrid machine,
// models/hybrid/hybrid_machine.hpp): rigid axes give the module's own frequencies; a very stiff
// module on a soft axis is the mass of carriage and module (the machine's moving mass) on the axis
// spring; a stiff axis gives the module's frequencies back; at rest the axis drive carries the
// tool's force and every weight; along a fast path the actuators' power balances the wrench's and
// gravity's power and the rate of the kinetic energy of every body, all computed here from the
// bodies' positions (carriage, platform, cylinders and rods on the moving base) by finite
// differences.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <memory>
#include <numbers>
#include <vector>

#include "models/hexapod/hexapod.hpp"
#include "models/hybrid/hybrid_machine.hpp"
#include "models/leg_chain/leg_chain.hpp"
#include "models/motion/trajectory.hpp"
#include "tests/models/dynamics/hexapod_bodies.hpp"
#include "tests/sample_machines.hpp"

namespace pkmopt {
namespace {

using namespace pkmopt::test_bodies;

HexapodDesign module_design(double axial_stiffness) {
  HexapodDesign d = sample_machines::conventions_hexapod_design();
  d.stiffness = LegStiffness{};
  d.stiffness.axial_stiffness = axial_stiffness;
  d.masses = sample_machines::milling_hexapod_masses();
  // Off-axis centre of mass and unequal inertias: no symmetry to hide an error.
  d.masses.platform.centre_of_mass = {0.01, -0.02, -0.04};
  d.masses.platform.inertia(1, 1) = 1.4;
  return d;
}

HybridMachine hybrid(const std::string& code, double axis_stiffness, double carriage_mass,
                     const HexapodDesign& module) {
  HybridDesign d;
  d.chain = SerialChain::from_code(code);
  d.axes = {
      {.min = -1.0, .max = 1.0, .stiffness = axis_stiffness, .error = 0.0, .mass = carriage_mass}};
  d.module = std::make_shared<Hexapod>(module);
  d.home = {0.0, 0.0, 0.9};
  return HybridMachine(d);
}

PoseMetrics analyzed(const Machine& machine, const Pose& pose) {
  const auto data = machine.make_data();
  PoseMetrics m;
  machine.analyze(*data, pose, Wrench::Zero(), m);
  return m;
}

// Modules with parasitic motion (a 3-PRS head) take no masses in a hybrid, which says so.
TEST(HybridDynamics, AParasiticModuleWithMassesIsRefused) {
  Tripod3PrsDesign head;
  head.masses.present = true;
  head.masses.platform.mass = 30.0;
  head.masses.platform.inertia = Eigen::Vector3d(0.5, 0.5, 0.8).asDiagonal();
  HybridDesign d;
  d.chain = SerialChain::from_code("1 2");
  d.axes = {{.min = -1, .max = 1}, {.min = -1, .max = 1}};
  d.module = make_tripod_3prs(head);
  d.home = Eigen::Vector3d(0, 0, 1.2);
  EXPECT_THROW(HybridMachine{d}, std::invalid_argument);
  head.masses = MassModel{};
  d.module = make_tripod_3prs(head);
  const HybridMachine machine(d);
  EXPECT_EQ(machine.dynamics().reason(),
            "its parallel module has parasitic motion (planar legs), whose dynamics on moving axes "
            "are not modelled");
}

TEST(HybridDynamics, RigidAxesGiveTheModuleFrequencies) {
  const HexapodDesign module = module_design(2e7);
  const HybridMachine machine = hybrid("1", 0.0, 80.0, module);
  ASSERT_EQ(machine.natural_frequency_count(), 6);
  const Pose pose{{0.4, 0.05, 0.88}, deg_to_rad(Eigen::Vector3d(4, -3, 10))};
  const PoseMetrics m = analyzed(machine, pose);
  const PoseMetrics alone = analyzed(Hexapod(module), machine.split(pose).local);
  ASSERT_EQ(m.natural_frequencies.size(), 6);
  for (int k = 0; k < 6; ++k) {
    EXPECT_NEAR(m.natural_frequencies(k), alone.natural_frequencies(k),
                1e-9 * alone.natural_frequencies(k));
  }
  // The shapes too: the axis does not move, the TCP twist is the module's (base axes aligned).
  PoseModes modes, module_modes;
  ASSERT_TRUE(machine.mode_shapes(*machine.make_data(), pose, modes));
  const Hexapod alone_module(module);
  ASSERT_TRUE(
      alone_module.mode_shapes(*alone_module.make_data(), machine.split(pose).local, module_modes));
  ASSERT_EQ(modes.shapes.rows(), 7);
  for (int k = 0; k < 6; ++k) {
    EXPECT_LT(std::abs(modes.shapes(0, k)), 1e-12);
    const Vector6d x = modes.shapes.col(k).tail<6>(), y = module_modes.shapes.col(k);
    EXPECT_LT((x - y).norm(), 1e-7 * y.norm())
        << k << ": " << x.transpose() << " / " << y.transpose();
  }
}

// Legs 10^6 times stiffer than the axis: the lowest mode is carriage and module moving together
// on the axis drive, f = sqrt(k / (m_carriage + m_module)) / 2 pi; the other six are the
// module's. An axis 10^6 times stiffer than the legs: the module's six frequencies and a seventh
// very high one.
TEST(HybridDynamics, SoftAxisCarriesTheWholeMassAndAStiffOneGivesTheModuleBack) {
  const double k_axis = 1.0e6, m_carriage = 80.0;
  const HexapodDesign stiff_legs = module_design(1e12);
  const HybridMachine soft = hybrid("1", k_axis, m_carriage, stiff_legs);
  ASSERT_EQ(soft.natural_frequency_count(), 7);
  const double m_module = 45.0 + 6 * (6.0 + 3.0);
  const Pose pose{{0.3, 0.0, 0.9}, {0, 0, 0}};
  const PoseMetrics m = analyzed(soft, pose);
  ASSERT_EQ(m.natural_frequencies.size(), 7);
  const double expected = std::sqrt(k_axis / (m_carriage + m_module)) / (2 * std::numbers::pi);
  EXPECT_NEAR(m.natural_frequencies(0), expected, 1e-5 * expected);
  // The mass that mode moves is the machine's moving mass: the carriage, the platform and the
  // legs' cylinders and rods.
  EXPECT_DOUBLE_EQ(soft.moving_mass(), m_carriage + m_module);
  EXPECT_DOUBLE_EQ(Hexapod(stiff_legs).moving_mass(), m_module);
  // Its shape: the axis and the TCP move together along x by 1 / sqrt(m_carriage + m_module)
  // (mass-normalised), nothing else moves.
  PoseModes modes;
  ASSERT_TRUE(soft.mode_shapes(*soft.make_data(), pose, modes));
  ASSERT_EQ(soft.mode_axis_count(), 1);
  ASSERT_EQ(modes.shapes.rows(), 7);
  ASSERT_EQ(modes.shapes.cols(), 7);
  Eigen::VectorXd rigid_body = Eigen::VectorXd::Zero(7);
  rigid_body(0) = rigid_body(1) = 1.0 / std::sqrt(m_carriage + m_module);
  EXPECT_LT((modes.shapes.col(0) - rigid_body).norm(), 1e-5 * rigid_body.norm())
      << modes.shapes.col(0).transpose();
  for (int k = 0; k < 7; ++k) EXPECT_EQ(modes.frequencies(k), m.natural_frequencies(k));

  const HexapodDesign legs = module_design(2e7);
  const HybridMachine stiff = hybrid("1", 1e13, m_carriage, legs);
  const PoseMetrics s = analyzed(stiff, pose);
  const PoseMetrics alone = analyzed(Hexapod(legs), stiff.split(pose).local);
  for (int k = 0; k < 6; ++k) {
    EXPECT_NEAR(s.natural_frequencies(k), alone.natural_frequencies(k),
                1e-5 * alone.natural_frequencies(k));
  }
  EXPECT_GT(s.natural_frequencies(6), 10 * alone.natural_frequencies(5));
}

// A vertical axis (code "3") at rest: it carries the tool's force along z and every weight.
TEST(HybridDynamics, AtRestTheAxisCarriesTheForceAndEveryWeight) {
  const HybridMachine machine = hybrid("3", 2e8, 80.0, module_design(2e7));
  const auto data = machine.make_data();
  const Pose pose{{0.02, -0.01, 1.2}, deg_to_rad(Eigen::Vector3d(3, 2, -5))};
  const Wrench w = (Wrench() << 300, -200, -1500, 20, -10, 5).finished();
  PoseMetrics m;
  ASSERT_TRUE(machine.inverse_dynamics(*data, pose, Vector6d::Zero(), Vector6d::Zero(), w, m));
  const double total = 80.0 + 45.0 + 6 * 9.0;
  EXPECT_NEAR(m.tau(0), -1500 - total * 9.81, 1e-9 * total * 9.81);
  // The module's legs: as the hexapod alone at the local pose under the wrench and its weight.
  const Hexapod alone(module_design(2e7));
  const auto alone_data = alone.make_data();
  PoseMetrics a;
  ASSERT_TRUE(alone.inverse_dynamics(*alone_data, machine.split(pose).local, Vector6d::Zero(),
                                     Vector6d::Zero(), w, a));
  for (int i = 0; i < 6; ++i) EXPECT_NEAR(m.tau(1 + i), a.tau(i), 1e-9 * a.tau.norm());
}

// The bodies of the hybrid at time t along a path: the carriage on the X axis at u(t) and the
// module's bodies on the base shifted by a u(t).
struct World {
  double u = 0.0;
  HexapodBodies module;
};

World world_at(const HybridMachine& machine, const HexapodDesign& module, const TcpPath& path,
               double t) {
  const Pose pose = path.at(t).pose;
  World w;
  w.u = machine.split(pose).serial(0);
  HexapodDesign shifted = module;
  for (int i = 0; i < 6; ++i) shifted.base_joints.col(i) += machine.axis_directions().col(0) * w.u;
  w.module = bodies_at(shifted, pose);
  return w;
}

// Kinetic and potential energy of every body at t (central differences of the positions).
void energies(const HybridMachine& machine, const HexapodDesign& module, double m_carriage,
              const TcpPath& path, double t, double& T, double& V) {
  const double h = 1e-6;
  const World now = world_at(machine, module, path, t),
              plus = world_at(machine, module, path, t + h),
              minus = world_at(machine, module, path, t - h);
  const MassModel& m = module.masses;
  const Eigen::Vector3d g(0, 0, -9.81);
  const Eigen::Vector3d axis = machine.axis_directions().col(0);
  const double u_dot = (plus.u - minus.u) / (2 * h);
  T = 0.5 * m_carriage * u_dot * u_dot;
  V = -m_carriage * g.dot(axis * now.u);
  const Eigen::Vector3d v_c =
      (plus.module.platform_centre - minus.module.platform_centre) / (2 * h);
  const Eigen::Matrix3d W = (plus.module.R - minus.module.R) / (2 * h) * now.module.R.transpose();
  const Eigen::Vector3d omega(W(2, 1), W(0, 2), W(1, 0));
  T += 0.5 * m.platform.mass * v_c.squaredNorm() +
       0.5 * omega.dot(now.module.R * m.platform.inertia * now.module.R.transpose() * omega);
  V -= m.platform.mass * g.dot(now.module.platform_centre);
  for (int i = 0; i < 6; ++i) {
    const Eigen::Vector3d v1 = (plus.module.cylinder[i] - minus.module.cylinder[i]) / (2 * h);
    const Eigen::Vector3d v2 = (plus.module.rod[i] - minus.module.rod[i]) / (2 * h);
    const Eigen::Vector3d s_dot = (plus.module.s[i] - minus.module.s[i]) / (2 * h);
    const Eigen::Vector3d w = now.module.s[i].cross(s_dot);
    T += 0.5 * m.legs.cylinder.mass * v1.squaredNorm() + 0.5 * m.legs.rod.mass * v2.squaredNorm() +
         0.5 * (m.legs.cylinder.inertia + m.legs.rod.inertia) * w.squaredNorm();
    V -= m.legs.cylinder.mass * g.dot(now.module.cylinder[i]) +
         m.legs.rod.mass * g.dot(now.module.rod[i]);
  }
}

// Along a fast helix (the X axis follows the TCP over 0.3 m): sum tau q_dot = w . xi - dV/dt -
// dT/dt, the energies of every body from the test's own body model.
TEST(HybridDynamics, ActuatorPowerBalancesTheEnergyOfEveryBody) {
  const HexapodDesign module = module_design(2e7);
  const double m_carriage = 120.0;
  const HybridMachine machine = hybrid("1", 1.5e8, m_carriage, module);
  HelixParameters hp;
  hp.centre = {0.0, 0.0, 0.88};
  hp.radius_start = 0.15;
  hp.radius_growth = 0.05;
  hp.height_growth = 0.03;
  hp.angle_amplitudes = deg_to_rad(Eigen::Vector3d(5, -4, 8));
  hp.angular_frequency = 3.0;
  const HelixPath helix(hp);
  const Wrench w = (Wrench() << 300, -200, -800, 10, -20, 5).finished();
  const TrajectoryResult run = evaluate_trajectory(machine, helix, {0.2, 0.7, 1.3}, w);
  for (const TrajectorySample& s : run.samples) {
    ASSERT_EQ(s.tau_dyn.size(), 7);
    ASSERT_TRUE(s.jacobian_ok);
    const double dt = 1e-4;
    double T1, V1, T0, V0;
    energies(machine, module, m_carriage, helix, s.t + dt, T1, V1);
    energies(machine, module, m_carriage, helix, s.t - dt, T0, V0);
    const double power = s.tau_dyn.dot(s.q_dot);
    const double expected = w.dot(s.twist) - (V1 - V0) / (2 * dt) - (T1 - T0) / (2 * dt);
    EXPECT_NEAR(power, expected, 1e-5 * (1.0 + std::abs(expected))) << "t " << s.t;
    EXPECT_GT(std::abs(s.q_dot(0)), 0.1);             // the axis does move (m/s)
    EXPECT_GT(std::abs((T1 - T0) / (2 * dt)), 10.0);  // and the inertia does work (W)
  }
}

}  // namespace
}  // namespace pkmopt
