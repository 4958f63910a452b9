// Tests of models/motion/trajectory: the angular velocity map against the derivative of the
// rotation, the helix formula and its derivative, q_dot = J xi against finite differences of the IK
// (hexapod and delta), sampled paths, and singular poses located where they are (Fichter's
// 90 deg yaw singularity, architecturally singular hexapods); the twist rate against
// differences of the twist; the inverse dynamics tau_dyn against finite differences of every
// body's momenta (an independent body model written here), its static limit against tau under
// gravity, and the power balance of a linear delta. `pkmopt trajectory` is tested in
// tests/app/trajectory_cli_test.cpp.
#include "models/motion/trajectory.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

#include "io/machine/machine_file.hpp"
#include "models/hexapod/hexapod.hpp"
#include "models/leg_chain/leg_chain.hpp"
#include "tests/models/dynamics/hexapod_bodies.hpp"
#include "tests/sample_machines.hpp"

namespace {

namespace fs = std::filesystem;
using namespace pkmopt;
using sample_machines::Uniform;
using namespace pkmopt::test_bodies;

constexpr double kPi = std::numbers::pi;

std::string source_path(const std::string& relative) {
  return (fs::path(PKMOPT_SOURCE_DIR) / relative).string();
}

// omega from the derivative of R: [omega]x = R_dot R^T, R_dot by central differences.
TEST(Trajectory, AngularVelocityMapMatchesTheDerivativeOfTheRotation) {
  const std::vector<Eigen::Vector3d> angle_set = {
      {0.3, -0.4, 1.1}, {-1.2, 0.9, -2.5}, {0.0, 1.3, 0.4}, {2.0, -0.1, 3.0}};
  const Eigen::Vector3d rates(0.7, -1.3, 0.4);
  const double h = 1e-6;
  for (const Eigen::Vector3d& a : angle_set) {
    const Eigen::Matrix3d R_dot =
        (rotation_zyx<double>(a + h * rates) - rotation_zyx<double>(a - h * rates)) / (2 * h);
    const Eigen::Matrix3d W = R_dot * rotation_zyx<double>(a).transpose();
    const Eigen::Vector3d omega_fd(W(2, 1), W(0, 2), W(1, 0));
    EXPECT_LT((angular_velocity_map(a) * rates - omega_fd).norm(), 1e-8) << a.transpose();
    EXPECT_LT((W + W.transpose()).norm(), 1e-8);  // skew: R_dot R^T is a cross-product matrix
  }
}

HelixParameters seeds_helix() {
  HelixParameters h;
  h.centre = {0.0, 0.0, 0.70};
  h.angle_amplitudes = deg_to_rad(Eigen::Vector3d(5, 5, 5));
  return h;
}

// amp = 0.01 + 0.02 t/2pi, x = amp cos t, y = amp sin t, z = 0.01 + 0.01 t^2/4pi^2 (seeds).
TEST(Trajectory, HelixFormulaAtPinnedTimes) {
  const HelixPath helix(seeds_helix());
  const struct {
    double t;
    Eigen::Vector3d offset;
  } cases[] = {
      {0.0, {0.01, 0.0, 0.01}},
      {kPi / 2, {0.0, 0.015, 0.01 + 0.01 / 16}},
      {kPi, {-0.02, 0.0, 0.0125}},
      {2 * kPi, {0.03, 0.0, 0.02}},
  };
  for (const auto& c : cases) {
    const PathPoint p = helix.at(c.t);
    EXPECT_LT((p.pose.position - Eigen::Vector3d(0, 0, 0.70) - c.offset).norm(), 1e-15) << c.t;
  }
  // rx = 5 sin t, ry = 5 cos t, rz = 5 sin 2t (deg) at t = pi/4: 5/sqrt2, 5/sqrt2, 5.
  const Eigen::Vector3d a = rad_to_deg(helix.at(kPi / 4).pose.angles);
  EXPECT_NEAR(a(0), 5 / std::sqrt(2.0), 1e-12);
  EXPECT_NEAR(a(1), 5 / std::sqrt(2.0), 1e-12);
  EXPECT_NEAR(a(2), 5.0, 1e-12);
  // The analytic rate against central differences, at w = 1 and w = 3.
  for (double w : {1.0, 3.0}) {
    HelixParameters hp = seeds_helix();
    hp.angular_frequency = w;
    const HelixPath path(hp);
    for (double t = 0.05; t < 6.3; t += 0.37) {
      const double h = 1e-6;
      const PathPoint p = path.at(t), plus = path.at(t + h), minus = path.at(t - h);
      Vector6d fd;
      fd << (plus.pose.position - minus.pose.position) / (2 * h),
          (plus.pose.angles - minus.pose.angles) / (2 * h);
      EXPECT_LT((p.pose_rate - fd).cwiseAbs().maxCoeff(), 1e-8) << "t " << t << " w " << w;
    }
  }
}

// Second-order differences are exact for quadratics, on uneven spacing too.
TEST(Trajectory, CentralDifferencesAreExactForQuadratics) {
  const std::vector<double> times = {0.0, 0.1, 0.35, 0.4, 0.9};
  std::vector<Eigen::VectorXd> values;
  for (double t : times) values.push_back(Eigen::Vector2d(3 * t * t - t + 2, -t * t));
  const auto rates = central_difference_rates(times, values);
  for (std::size_t k = 1; k + 1 < times.size(); ++k) {
    EXPECT_NEAR(rates[k](0), 6 * times[k] - 1, 1e-12);
    EXPECT_NEAR(rates[k](1), -2 * times[k], 1e-12);
  }
  EXPECT_THROW(central_difference_rates({0.0, 0.0}, {values[0], values[1]}), std::invalid_argument);
}

// q_dot = J xi against the central difference of the IK along the path (h = 1e-6 s), and the
// q_dot_fd column (neighbouring samples) against q_dot to O(dt^2).
void expect_rates_match_ik(const Machine& machine, const TcpPath& path, int samples,
                           double fd_tolerance, double sample_tolerance) {
  const std::vector<double> times = uniform_times(path.t_start(), path.t_end(), samples);
  const TrajectoryResult run = evaluate_trajectory(machine, path, times);
  ASSERT_EQ(run.samples.size(), times.size());
  const auto data = machine.make_data();
  PoseMetrics plus, minus;
  int checked = 0;
  for (std::size_t k = 0; k < run.samples.size(); ++k) {
    const TrajectorySample& s = run.samples[k];
    ASSERT_TRUE(s.jacobian_ok) << "t " << s.t;
    ASSERT_FALSE(s.metrics.singular) << "t " << s.t;
    const double h = 1e-6;
    machine.analyze(*data, path.at(s.t + h).pose, Wrench::Zero(), plus);
    machine.analyze(*data, path.at(s.t - h).pose, Wrench::Zero(), minus);
    const Eigen::VectorXd fd = (plus.q - minus.q) / (2 * h);
    const double scale = std::max(1e-3, fd.cwiseAbs().maxCoeff());
    EXPECT_LT((s.q_dot - fd).cwiseAbs().maxCoeff(), fd_tolerance * scale) << "t " << s.t;
    if (k > 0 && k + 1 < run.samples.size()) {
      EXPECT_LT((s.q_dot - s.q_dot_fd).cwiseAbs().maxCoeff(), sample_tolerance * scale)
          << "t " << s.t;
    }
    ++checked;
  }
  EXPECT_EQ(checked, samples);
}

TEST(Trajectory, HexapodLegRatesMatchDifferencesOfTheIkAlongTheHelix) {
  const auto machine =
      load_machine_file(source_path("studies/library/hexapod-450/hexapod-450.yaml"));
  HelixParameters hp = seeds_helix();
  hp.angle_amplitudes = deg_to_rad(Eigen::Vector3d(15, 10, 20));  // large angles: E(a) matters
  expect_rates_match_ik(*machine, HelixPath(hp), 401, 1e-7, 2e-3);
  // Leaving out E(a) (omega = angle rates) would be wrong by far more than the tolerance.
  const HelixPath helix(hp);
  const auto data = machine->make_data();
  Eigen::MatrixXd J;
  const PathPoint p = helix.at(1.0);
  ASSERT_TRUE(machine->twist_jacobian(*data, p.pose, J));
  Vector6d naive = p.pose_rate;
  const double h = 1e-6;
  PoseMetrics plus, minus;
  machine->analyze(*data, helix.at(1.0 + h).pose, Wrench::Zero(), plus);
  machine->analyze(*data, helix.at(1.0 - h).pose, Wrench::Zero(), minus);
  const Eigen::VectorXd fd = (plus.q - minus.q) / (2 * h);
  EXPECT_GT((J * naive - fd).cwiseAbs().maxCoeff(), 1e-3 * fd.cwiseAbs().maxCoeff());
}

TEST(Trajectory, DeltaDriveRatesMatchDifferencesOfTheIkAlongATranslationalHelix) {
  const auto machine = load_machine_file(source_path("examples/delta.yaml"));
  HelixParameters hp;
  hp.centre = {0.05, -0.03, -1.0};
  hp.radius_start = 0.1;
  hp.radius_growth = 0.1;
  hp.height_growth = 0.2;
  expect_rates_match_ik(*machine, HelixPath(hp), 81, 1e-7, 5e-3);
}

// A sampled path's rates are central differences: q_dot from them converges to the IK
// differences as the samples get denser.
TEST(Trajectory, SampledPathFollowsTheHelix) {
  const auto machine =
      load_machine_file(source_path("studies/library/hexapod-450/hexapod-450.yaml"));
  const HelixPath helix(seeds_helix());
  const std::vector<double> times = uniform_times(0.0, 2 * kPi, 401);
  std::vector<Pose> poses;
  for (double t : times) poses.push_back(helix.at(t).pose);
  const SampledPath sampled(times, poses);
  const TrajectoryResult a = evaluate_trajectory(*machine, helix, times);
  const TrajectoryResult b = evaluate_trajectory(*machine, sampled, times);
  double worst = 0.0, scale = 0.0;
  for (std::size_t k = 1; k + 1 < times.size(); ++k) {
    EXPECT_EQ(a.samples[k].metrics.q, b.samples[k].metrics.q);
    worst = std::max(worst, (a.samples[k].q_dot - b.samples[k].q_dot).cwiseAbs().maxCoeff());
    scale = std::max(scale, a.samples[k].q_dot.cwiseAbs().maxCoeff());
  }
  EXPECT_LT(worst, 1e-3 * scale);
  EXPECT_GT(scale, 1e-3);  // the legs do move (m/s)
  // Between samples the spline stays on the helix (O(h^4)), and its accelerations are the
  // helix's (O(h^2)).
  for (std::size_t k = 10; k < 400; k += 37) {
    const double t = 0.5 * (times[k] + times[k + 1]);
    const PathPoint mid = sampled.at(t), exact = helix.at(t);
    EXPECT_LT((mid.pose.position - exact.pose.position).norm(), 1e-9);
    EXPECT_LT((mid.pose_acceleration - exact.pose_acceleration).cwiseAbs().maxCoeff(),
              1e-3 * exact.pose_acceleration.cwiseAbs().maxCoeff());
  }
  EXPECT_THROW(SampledPath({0.0, 1.0, 1.0}, {poses[0], poses[1], poses[2]}), std::invalid_argument);
}

HexapodDesign fichter_design() {
  HexapodDesign d = semi_regular_hexapod(0.6, deg_to_rad(20), 0.3, deg_to_rad(20));
  d.min_length = 0.2;
  d.max_length = 2.0;
  d.stiffness.axial_stiffness = 1e8;
  return d;
}

// Fichter (1986, IJRR 5(2)): a semi-regular hexapod at its central position is singular when
// turned 90 deg about the vertical; det J changes sign there. A helix of zero radius turning
// rz = 90 + 10 sin 2t deg crosses it at t = pi/2, pi, 3pi/2; none of them is a sample.
TEST(Trajectory, FichterYawSingularityIsLocatedByBisection) {
  const Hexapod hexapod(fichter_design());
  HelixParameters hp;
  hp.centre = {0, 0, 0.8};
  hp.radius_start = hp.radius_growth = 0.0;
  hp.height_growth = 0.1;
  hp.nominal_angles = {0, 0, deg_to_rad(90)};
  hp.angle_amplitudes = {0, 0, deg_to_rad(10)};
  hp.t_start = 0.1;
  hp.t_end = 6.0;
  const TrajectoryResult run =
      evaluate_trajectory(hexapod, HelixPath(hp), uniform_times(hp.t_start, hp.t_end, 60));
  ASSERT_EQ(run.singular_poses.size(), 3u);
  const double expected[] = {kPi / 2, kPi, 3 * kPi / 2};
  for (int i = 0; i < 3; ++i) {
    const SingularPose& p = run.singular_poses[static_cast<std::size_t>(i)];
    EXPECT_EQ(p.kind, SingularPose::Kind::kDetSignChange);
    EXPECT_NEAR(p.t, expected[i], 1e-9);
    EXPECT_NEAR(rad_to_deg(p.pose.angles(2)), 90.0, 1e-7);
    EXPECT_EQ(p.singularity_margin, 0.0);
    EXPECT_LT(p.det_j_before * p.det_j_after, 0.0);
  }
  // No sample is singular, and away from 90 deg the margin is clearly positive.
  for (const TrajectorySample& s : run.samples) EXPECT_FALSE(s.metrics.singular) << s.t;

  // A sample exactly at the singular pose is reported as such, once.
  const std::vector<double> times = {0.0, 0.25, 0.5, 0.8, 1.0};
  std::vector<Pose> poses;
  for (double t : times) poses.push_back(Pose{{0, 0, 0.8}, {0, 0, deg_to_rad(80 + 20 * t)}});
  const TrajectoryResult at_sample = evaluate_trajectory(hexapod, SampledPath(times, poses), times);
  ASSERT_EQ(at_sample.singular_poses.size(), 1u);
  EXPECT_EQ(at_sample.singular_poses[0].kind, SingularPose::Kind::kSample);
  EXPECT_EQ(at_sample.singular_poses[0].t, 0.5);
  EXPECT_TRUE(at_sample.samples[2].metrics.singular);
}

// Similar base and platform hexagons are singular everywhere (Ma & Angeles 1991): every sample.
TEST(Trajectory, ArchitecturallySingularHexapodIsSingularAtEverySample) {
  HexapodDesign d = semi_regular_hexapod(0.6, deg_to_rad(20), 0.3, deg_to_rad(100));
  d.min_length = 0.2;
  d.max_length = 2.0;
  d.stiffness.axial_stiffness = 1e8;
  const Hexapod hexapod(d);
  HelixParameters hp = seeds_helix();
  hp.centre = {0, 0, 0.8};
  const TrajectoryResult run =
      evaluate_trajectory(hexapod, HelixPath(hp), uniform_times(0, 2 * kPi, 11));
  ASSERT_EQ(run.singular_poses.size(), 11u);
  for (const SingularPose& p : run.singular_poses) {
    EXPECT_EQ(p.kind, SingularPose::Kind::kSample);
  }
}

// stepped_times and summarize_trajectory on small hand-made inputs.
using pkmopt::TrajectoryResult;
using pkmopt::TrajectorySample;

// The helix's analytic second derivative against central differences of its first.
TEST(Trajectory, HelixAccelerationIsTheDerivativeOfItsRate) {
  HelixParameters hp = seeds_helix();
  hp.angle_amplitudes = deg_to_rad(Eigen::Vector3d(4, -3, 6));
  hp.angular_frequency = 2.5;
  const HelixPath helix(hp);
  const double h = 1e-5;
  for (double t : {0.0, 0.3, 1.1, 2.0, 2.4}) {
    const Vector6d fd = (helix.at(t + h).pose_rate - helix.at(t - h).pose_rate) / (2 * h);
    EXPECT_LT((fd - helix.at(t).pose_acceleration).cwiseAbs().maxCoeff(), 1e-7) << "t " << t;
  }
}

// A path whose angles all move: the twist rate [a; alpha] against central differences of the
// twist [v; omega].
TEST(Trajectory, TwistRateIsTheDerivativeOfTheTwist) {
  HelixParameters hp = seeds_helix();
  hp.nominal_angles = deg_to_rad(Eigen::Vector3d(10, -25, 40));
  hp.angle_amplitudes = deg_to_rad(Eigen::Vector3d(20, 15, 30));
  hp.angular_frequency = 1.7;
  const HelixPath helix(hp);
  const double h = 1e-5;
  for (double t : {0.1, 0.8, 1.9, 3.3, 5.0}) {
    const Vector6d fd =
        (twist_from_pose_rate(helix.at(t + h)) - twist_from_pose_rate(helix.at(t - h))) / (2 * h);
    EXPECT_LT((fd - twist_rate_from_path(helix.at(t))).cwiseAbs().maxCoeff(), 1e-7) << "t " << t;
  }
}

// Newton-Euler of every body by virtual power: for each unit twist e_j,
//   (J^T tau_dyn)_j = w_j + sum_b (m_b g - dp_b/dt) . dv_b/de_j - dH_b/dt . domega_b/de_j,
// with the momenta's rates from central differences in time along a fast helix.
TEST(TrajectoryDynamics, TauDynMatchesDifferencesOfTheBodiesMomenta) {
  Uniform u(71);
  for (int g = 0; g < 4; ++g) {
    HexapodDesign design = sample_machines::random_hexapod_design(u);
    design.masses = sample_machines::random_hexapod_masses(u);
    const Hexapod hexapod(design);
    HelixParameters hp;
    hp.centre = {u(-0.05, 0.05), u(-0.05, 0.05), u(0.7, 0.9)};
    hp.radius_start = 0.05;
    hp.radius_growth = 0.05;
    hp.height_growth = 0.05;
    hp.angle_amplitudes = deg_to_rad(Eigen::Vector3d(u(-10, 10), u(-10, 10), u(-15, 15)));
    hp.angular_frequency = u(2, 6);  // up to ~2 g at the rim
    const HelixPath helix(hp);
    const Wrench w =
        (Wrench() << u(-500, 500), u(-500, 500), u(-500, 500), u(-50, 50), u(-50, 50), u(-50, 50))
            .finished();
    const std::vector<double> times = {0.2, 0.9, 1.6};
    const TrajectoryResult run = evaluate_trajectory(hexapod, helix, times, w);
    const std::array<double, 13> mass = body_masses(design.masses);
    for (std::size_t k = 0; k < times.size(); ++k) {
      const TrajectorySample& s = run.samples[k];
      ASSERT_EQ(s.tau_dyn.size(), 6);
      ASSERT_TRUE(s.jacobian_ok);
      const double dt = 1e-4;
      const Momenta plus = momenta_at(design, helix, s.t + dt),
                    minus = momenta_at(design, helix, s.t - dt);
      const Vector6d lhs = s.J.transpose() * s.tau_dyn;
      Vector6d rhs = w;
      for (int j = 0; j < 6; ++j) {
        std::array<Eigen::Vector3d, 13> dv, dw;
        virtual_velocities(design, s.pose, j, dv, dw);
        for (int b = 0; b < 13; ++b) {
          const Eigen::Vector3d p_dot = (plus.linear[b] - minus.linear[b]) / (2 * dt);
          const Eigen::Vector3d H_dot = (plus.angular[b] - minus.angular[b]) / (2 * dt);
          rhs(j) += (mass[b] * design.masses.gravity - p_dot).dot(dv[b]) - H_dot.dot(dw[b]);
        }
      }
      EXPECT_LT((lhs - rhs).cwiseAbs().maxCoeff(), 1e-5 * (1.0 + rhs.cwiseAbs().maxCoeff()))
          << "design " << g << " sample " << k << "\n"
          << lhs.transpose() << "\n"
          << rhs.transpose();
      // The static forces under the wrench alone differ: gravity and inertia matter here.
      EXPECT_GT((s.tau_dyn - s.metrics.tau).cwiseAbs().maxCoeff(), 1.0);
    }
  }
}

// At rest (a path that does not move) tau_dyn is tau under the wrench plus the bodies' weights,
// which map to the TCP by virtual power: (w_g)_j = sum_b m_b g . dv_b/de_j.
TEST(TrajectoryDynamics, AtRestTauDynIsTauUnderTheWrenchAndGravity) {
  Uniform u(72);
  for (int g = 0; g < 4; ++g) {
    HexapodDesign design = sample_machines::random_hexapod_design(u);
    design.masses = sample_machines::random_hexapod_masses(u);
    const Hexapod hexapod(design);
    const Pose pose = sample_machines::random_pose(u);
    const SampledPath still({0.0, 0.5, 1.0, 1.5}, {pose, pose, pose, pose});
    const Wrench w =
        (Wrench() << u(-500, 500), u(-500, 500), u(-500, 500), u(-50, 50), u(-50, 50), u(-50, 50))
            .finished();
    const TrajectoryResult run = evaluate_trajectory(hexapod, still, {0.0, 0.7, 1.5}, w);
    const std::array<double, 13> mass = body_masses(design.masses);
    Wrench gravity = Wrench::Zero();
    for (int j = 0; j < 6; ++j) {
      std::array<Eigen::Vector3d, 13> dv, dw;
      virtual_velocities(design, pose, j, dv, dw);
      for (int b = 0; b < 13; ++b) gravity(j) += mass[b] * design.masses.gravity.dot(dv[b]);
    }
    PoseMetrics expected;
    const auto data = hexapod.make_data();
    hexapod.analyze(*data, pose, w + gravity, expected);
    for (const TrajectorySample& s : run.samples) {
      EXPECT_EQ(s.twist, Vector6d::Zero());
      EXPECT_EQ(s.twist_rate, Vector6d::Zero());
      EXPECT_LT((s.tau_dyn - expected.tau).cwiseAbs().maxCoeff(),
                1e-7 * (1.0 + expected.tau.cwiseAbs().maxCoeff()))
          << "design " << g;
    }
  }
}

// A linear delta along a translational helix: the actuators' power tau_dyn . q_dot equals the
// wrench's and gravity's power minus the rate of the kinetic energy 1/2 xi^T M xi (M from
// Machine::mass_matrix, checked against every body's kinetic energy in leg_chain_compliance_test).
TEST(TrajectoryDynamics, LinearDeltaPowerBalance) {
  const auto machine = load_machine_file(source_path("examples/linear_delta.yaml"));
  auto& delta = dynamic_cast<const LegChainMachine&>(*machine);
  LegChainDesign design = delta.design();
  sample_machines::add_linear_delta_masses(design);
  const LegChainMachine heavy(design);
  PoseMetrics home;
  const auto data = heavy.make_data();
  heavy.analyze(*data, design.home, Wrench::Zero(), home);
  ASSERT_TRUE(home.reachable);
  HelixParameters hp;
  hp.centre = design.home.position - Eigen::Vector3d(0, 0, 0.01);
  hp.radius_start = 0.02;
  hp.radius_growth = 0.04;
  hp.height_growth = 0.02;
  hp.angular_frequency = 12.0;  // up to 0.7 m/s and 8 m/s^2
  const HelixPath helix(hp);
  const Wrench w = (Wrench() << 40, -70, 120, 0, 0, 0).finished();
  const TrajectoryResult run = evaluate_trajectory(heavy, helix, {0.3, 0.7, 1.1}, w);
  for (const TrajectorySample& s : run.samples) {
    ASSERT_EQ(s.tau_dyn.size(), 3);
    ASSERT_TRUE(s.jacobian_ok);
    const double h = 1e-5;
    auto kinetic = [&](double t) {
      const PathPoint point = helix.at(t);
      Matrix6d M;
      EXPECT_TRUE(heavy.mass_matrix(*data, point.pose, M));
      const Vector6d xi = twist_from_pose_rate(point);
      return 0.5 * xi.dot(M * xi);
    };
    const double T_dot = (kinetic(s.t + h) - kinetic(s.t - h)) / (2 * h);
    Wrench gravity;
    ASSERT_TRUE(heavy.dynamic_wrench(*data, s.pose, Vector6d::Zero(), Vector6d::Zero(), gravity));
    const double power = s.tau_dyn.dot(s.q_dot);
    const double expected = (w + gravity).dot(s.twist) - T_dot;
    EXPECT_NEAR(power, expected, 1e-6 * (1.0 + std::abs(expected))) << "t " << s.t;
    EXPECT_GT(std::abs(T_dot), 1.0);  // the inertia does work here (W)
  }
}

TEST(SteppedTimes, KeepsTheStepAndEndsAtTEnd) {
  const auto t = pkmopt::stepped_times(0.0, 1.0, 0.3);
  ASSERT_EQ(t.size(), 5u);  // 0, 0.3, 0.6, 0.9 and a shorter last step to 1
  EXPECT_EQ(t[0], 0.0);
  EXPECT_DOUBLE_EQ(t[1], 0.3);
  EXPECT_DOUBLE_EQ(t[2], 0.6);
  EXPECT_DOUBLE_EQ(t[3], 0.9);
  EXPECT_EQ(t[4], 1.0);
  EXPECT_EQ(t[3], 0.0 + 3 * 0.3);  // k * dt, not a running sum
}

TEST(SteppedTimes, ADividingStepDoesNotRepeatTEnd) {
  const auto t = pkmopt::stepped_times(1.0, 2.0, 0.25);
  ASSERT_EQ(t.size(), 5u);
  EXPECT_EQ(t[3], 1.75);
  EXPECT_EQ(t[4], 2.0);
}

TEST(SteppedTimes, AStepLongerThanTheSpanGivesBothEnds) {
  // Once a single time (t_end): the tolerance was a billionth of the step, 1e6 s here.
  EXPECT_EQ(pkmopt::stepped_times(0.0, 6.25, 1e15), (std::vector<double>{0.0, 6.25}));
  EXPECT_EQ(pkmopt::stepped_times(2.0, 3.0, 1.0), (std::vector<double>{2.0, 3.0}));
}

TEST(SteppedTimes, RejectsBadSpansAndSteps) {
  EXPECT_THROW(pkmopt::stepped_times(0.0, 1.0, 0.0), std::invalid_argument);
  EXPECT_THROW(pkmopt::stepped_times(1.0, 1.0, 0.1), std::invalid_argument);
  EXPECT_THROW(pkmopt::stepped_times(0.0, std::nan(""), 0.1), std::invalid_argument);
}

TrajectorySample sample(double q1, double q2, double qd1, double qd2, double fd1, double fd2,
                        bool reachable, double margin, bool jacobian_ok) {
  TrajectorySample s;
  s.metrics.q = Eigen::Vector2d(q1, q2);
  s.q_dot = Eigen::Vector2d(qd1, qd2);
  s.q_dot_fd = Eigen::Vector2d(fd1, fd2);
  s.metrics.reachable = reachable;
  s.metrics.singularity_margin = margin;
  s.jacobian_ok = jacobian_ok;
  return s;
}

TEST(SummarizeTrajectory, RangesAndInteriorMismatch) {
  TrajectoryResult r;
  // The ends disagree by 10 (ignored: not interior); interior samples by 0.5 and 0.25; the
  // third sample's Jacobian failed, so its 7 does not count.
  r.samples.push_back(sample(1.0, -2.0, 0.1, -3.0, 10.1, -3.0, true, 0.4, true));
  r.samples.push_back(sample(1.5, -1.0, -0.6, 0.2, -0.1, 0.2, false, 0.2, true));
  r.samples.push_back(sample(0.5, -4.0, 0.0, 0.0, 7.0, 0.0, true, 0.3, false));
  r.samples.push_back(sample(2.0, -3.0, 0.5, 0.25, 0.5, 0.0, true, 0.6, true));
  r.samples.push_back(sample(1.0, -1.5, 0.0, 0.0, 0.0, 20.0, true, 0.9, true));
  const pkmopt::TrajectorySummary s = pkmopt::summarize_trajectory(r, 2);
  EXPECT_EQ(s.samples, 5u);
  EXPECT_EQ(s.reachable, 4u);
  EXPECT_EQ(s.singularity_margin_min, 0.2);
  EXPECT_EQ(s.q_min, Eigen::Vector2d(0.5, -4.0));
  EXPECT_EQ(s.q_max, Eigen::Vector2d(2.0, -1.0));
  EXPECT_EQ(s.q_dot_max, Eigen::Vector2d(0.6, 3.0));
  EXPECT_DOUBLE_EQ(s.q_dot_mismatch_max, 0.5);  // |-0.6 - (-0.1)| at sample 1
}

// Peak, RMS (trapezoidal in time) and peak power of tau_dyn.
TEST(SummarizeTrajectory, DynamicForcesPeakRmsAndPower) {
  TrajectoryResult r;
  const double times[] = {0.0, 1.0, 3.0};
  const double forces[] = {1.0, -3.0, 2.0};
  const double rates[] = {0.5, 2.0, -4.0};
  for (int k = 0; k < 3; ++k) {
    TrajectorySample s = sample(0.0, 0.0, rates[k], 0.0, rates[k], 0.0, true, 0.5, true);
    s.t = times[k];
    s.metrics.tau = Eigen::Vector2d(forces[k] / 2, 0.0);
    s.tau_dyn = Eigen::Vector2d(forces[k], 0.0);
    r.samples.push_back(s);
  }
  const pkmopt::TrajectorySummary s = pkmopt::summarize_trajectory(r, 2);
  ASSERT_TRUE(s.dynamics);
  EXPECT_EQ(s.tau_max, Eigen::Vector2d(1.5, 0.0));
  EXPECT_EQ(s.tau_dyn_max, Eigen::Vector2d(3.0, 0.0));
  // integral of tau^2: 1 * (1 + 9) / 2 + 2 * (9 + 4) / 2 = 18 over 3 s.
  EXPECT_DOUBLE_EQ(s.tau_dyn_rms(0), std::sqrt(18.0 / 3.0));
  EXPECT_EQ(s.tau_dyn_rms(1), 0.0);
  EXPECT_EQ(s.power_max, Eigen::Vector2d(8.0, 0.0));  // |2 * -4|
}

TEST(SummarizeTrajectory, NoSamples) {
  const pkmopt::TrajectorySummary s = pkmopt::summarize_trajectory(TrajectoryResult{}, 3);
  EXPECT_EQ(s.samples, 0u);
  EXPECT_EQ(s.q_min.size(), 3);
  EXPECT_TRUE(std::isinf(s.q_min(0)) && s.q_min(0) > 0);
  EXPECT_TRUE(std::isinf(s.q_max(2)) && s.q_max(2) < 0);
  EXPECT_EQ(s.q_dot_max, Eigen::Vector3d::Zero());
  EXPECT_EQ(s.q_dot_mismatch_max, 0.0);
}

}  // namespace
