// Tests of models/leg_chain/leg_chain_compliance.cpp: the compliance and TCP deflection of every
// leg-chain model, and the loaded stiffness against finite differences of an independent
// loaded-equilibrium model written here (each rod a spring between its actuated point and the
// platform, each actuator a spring in its own coordinate, the actuator's balance solved by Newton
// per leg).
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <Eigen/LU>
#include <Eigen/SVD>
#include <cmath>
#include <memory>
#include <numbers>
#include <string>
#include <vector>

#include "models/leg_chain/leg_chain.hpp"

namespace pkmopt {
namespace {

struct Case {
  std::string name;
  LegChainDesign design;
  Pose pose;
};

std::vector<Case> cases() {
  std::vector<Case> out;
  DeltaDesign delta;
  delta.stiffness.actuator_stiffness = 2e4;  // N m/rad at the crank
  delta.stiffness.drive.torsional_stiffness = 5e4;
  out.push_back({"delta", delta_design(delta), Pose{{0.05, -0.08, -1.1}, {0, 0, 0}}});
  LinearDeltaDesign linear;
  linear.inclination = 0.3;
  linear.stiffness.drive = ScrewDrive{.E = 2.1e11,
                                      .root_diameter = 0.016,
                                      .free_length_at_min = 0.05,
                                      .free_length_at_max = 0.65,
                                      .nut_stiffness = 3e8};
  out.push_back({"linear_delta", linear_delta_design(linear), Pose{{0.03, 0.02, 0.25}, {0, 0, 0}}});
  HexaglideDesign hexaglide;
  out.push_back(
      {"hexaglide", hexaglide_design(hexaglide), Pose{{0.05, 0.02, 0.62}, {0.05, -0.04, 0.1}}});
  Tripod3PrsDesign tripod;
  tripod.stiffness.base_joint_stiffness = 5e8;
  out.push_back({"tripod_3prs", tripod_3prs_design(tripod), Pose{{0, 0, 1.2}, {0.2, -0.15, 0}}});
  return out;
}

Pose displaced(const Pose& pose, const Vec6<double>& dx) {
  const Eigen::Matrix3d R = rotation_from_vector(dx.tail<3>()) * rotation_zyx<double>(pose.angles);
  return Pose{pose.position + dx.head<3>(), angles_from_rotation(R)};
}

// The independent model of the loaded machine around its equilibrium at `pose` under `wrench`.
struct LoadedModel {
  const LegChainMachine& m;
  Pose pose;  // the actual pose (parasitic motion resolved)
  Wrench wrench;
  Eigen::VectorXd q0, f0, B0, l0;

  LoadedModel(const LegChainMachine& machine, const Pose& given, const Wrench& w)
      : m(machine), pose(*machine.actual_pose(given)), wrench(w) {
    auto data = m.make_data();
    PoseMetrics metrics;
    m.analyze(*data, pose, w, metrics);
    const int n = m.num_actuators();
    q0 = *m.inverse_kinematics(pose);
    f0.resize(n);
    B0.resize(n);
    l0.resize(n);
    for (int i = 0; i < n; ++i) {
      Eigen::Vector3d c, dc;
      m.actuated_point(i, q0(i), c, dc);
      const Eigen::Vector3d P = platform_point(pose, i);
      l0(i) = (P - c).norm();
      B0(i) = (P - c).normalized().dot(dc);
      f0(i) = metrics.tau(i) / B0(i);  // tau_i = B_i f_i
    }
  }

  Eigen::Vector3d platform_point(const Pose& p, int i) const {
    const LegChainLeg& leg = m.design().legs[static_cast<std::size_t>(i)];
    return p.position + rotation_zyx<double>(p.angles) * (leg.platform_point - m.design().tcp);
  }
  // The rod's spring (link and joints, along the rod) and the actuator's (its coordinate).
  double rod_stiffness(int i) const {
    const LegChainLeg& leg = m.design().legs[static_cast<std::size_t>(i)];
    double c = leg.link_length / (leg.E * leg.area * leg.rods);
    if (leg.base_joint_stiffness > 0) c += 1 / (leg.base_joint_stiffness * leg.rods);
    if (leg.platform_joint_stiffness > 0) c += 1 / (leg.platform_joint_stiffness * leg.rods);
    return 1 / c;
  }
  double actuator_compliance(int i, double q) const {
    const LegChainLeg& leg = m.design().legs[static_cast<std::size_t>(i)];
    double c = leg.actuator_stiffness > 0 ? 1 / leg.actuator_stiffness : 0.0;
    return c + drive_compliance(leg.drive, q, leg.q_min, leg.q_max, leg.kind == LegKind::kRUS);
  }

  // The DOF generalised force T^T (rod wrench - w) at the pose displaced by the full twist dx.
  Eigen::VectorXd net_force(const Vec6<double>& dx) const {
    const Pose moved = *m.actual_pose(displaced(pose, dx));
    const int n = m.num_actuators();
    Vec6<double> rods = Vec6<double>::Zero();
    for (int i = 0; i < n; ++i) {
      const Eigen::Vector3d P = platform_point(moved, i);
      const double kr = rod_stiffness(i), ca = actuator_compliance(i, q0(i));
      auto state = [&](double q, double& f, double& B, Eigen::Vector3d& s) {
        Eigen::Vector3d c, dc;
        m.actuated_point(i, q, c, dc);
        s = (P - c).normalized();
        f = f0(i) + kr * ((P - c).norm() - l0(i));
        B = s.dot(dc);
      };
      // Actuator balance: (q - q0) = ca (f B - f0 B0), by Newton with a numeric derivative.
      double q = q0(i), f = 0, B = 0;
      Eigen::Vector3d s;
      for (int it = 0; it < 50 && ca > 0; ++it) {
        state(q, f, B, s);
        const double r = (q - q0(i)) - ca * (f * B - f0(i) * B0(i));
        double f2, B2;
        Eigen::Vector3d s2;
        const double h = 1e-9;
        state(q + h, f2, B2, s2);
        const double r2 = (q + h - q0(i)) - ca * (f2 * B2 - f0(i) * B0(i));
        const double step = r / ((r2 - r) / h);
        q -= step;
        if (std::abs(step) < 1e-15) break;
      }
      state(q, f, B, s);
      rods.head<3>() += f * s;
      rods.tail<3>() += f * (P - moved.position).cross(s);
    }
    return m.twist_map(moved).transpose() * (rods - wrench);
  }
};

TEST(LegChainCompliance, ComplianceMapsTheWrenchToTheDeflection) {
  for (const Case& c : cases()) {
    const LegChainMachine m(c.design);
    auto data = m.make_data();
    Wrench w;
    w << 120, -80, 300, 4, -6, 9;
    PoseMetrics metrics;
    m.analyze(*data, c.pose, w, metrics);
    ASSERT_FALSE(metrics.singular) << c.name;
    const Eigen::MatrixXd T = m.twist_map(c.pose);
    Eigen::MatrixXd A, B, J;
    m.jacobians(c.pose, A, B, J);
    // Independent: K on the DOF from the legs' series springs, C6 = T K^-1 T^T.
    const LoadedModel model(m, c.pose, w);
    Eigen::VectorXd k(m.num_actuators());
    for (int i = 0; i < m.num_actuators(); ++i)
      k(i) = 1 / (1 / model.rod_stiffness(i) +
                  model.B0(i) * model.B0(i) * model.actuator_compliance(i, model.q0(i)));
    const Eigen::MatrixXd K = A.transpose() * k.asDiagonal() * A;
    const Eigen::MatrixXd C6 = T * K.inverse() * T.transpose();
    EXPECT_LT((data->matrices.compliance - C6).norm(), 1e-9 * C6.norm()) << c.name;
    const Vec6<double> dx = C6 * w;
    EXPECT_NEAR(metrics.tcp_deflection, dx.head<3>().norm(), 1e-9 * dx.head<3>().norm()) << c.name;
    EXPECT_NEAR(metrics.tcp_rotation_deflection, dx.tail<3>().norm(),
                1e-9 * dx.tail<3>().norm() + 1e-18)
        << c.name;
  }
}

TEST(LegChainCompliance, LoadedStiffnessMatchesFiniteDifferencesOfTheLoadedEquilibrium) {
  for (const Case& c : cases()) {
    const LegChainMachine m(c.design);
    auto data = m.make_data();
    // A heavy load: 20 kN and 2 kN m (the geometric term must show).
    Wrench w;
    w << 8e3, -5e3, -2e4, 1.5e3, -1e3, 2e3;
    PoseMetrics metrics;
    m.analyze(*data, c.pose, w, metrics);
    ASSERT_FALSE(metrics.singular) << c.name;
    const LoadedModel model(m, c.pose, w);
    const Eigen::MatrixXd T = m.twist_map(model.pose);
    const int dof = static_cast<int>(T.cols());
    Eigen::MatrixXd KT(dof, dof);
    const double h = 1e-7;
    for (int j = 0; j < dof; ++j) {
      const Vec6<double> dx = h * T.col(j);
      // K_T = d/dx [T^T (rod wrench - w)]: the wrench needed from outside per displacement.
      KT.col(j) = (model.net_force(dx) - model.net_force(-dx)) / (2 * h);
    }
    const Eigen::MatrixXd CT = KT.inverse();
    const Eigen::Matrix3d CTtt = T.topRows(3) * CT * T.topRows(3).transpose();
    const double expected = 1.0 / Eigen::JacobiSVD<Eigen::Matrix3d>(CTtt).singularValues()(0);
    EXPECT_NEAR(metrics.stiffness_min_loaded, expected, 1e-5 * expected)
        << c.name << ": unloaded " << metrics.stiffness_min;
    EXPECT_GT(std::abs(metrics.stiffness_min_loaded - metrics.stiffness_min),
              1e-7 * metrics.stiffness_min)
        << c.name << ": the load must change the stiffness";
  }
}

TEST(LegChainCompliance, DriveTrainEntersThroughTheTransmission) {
  // A linear delta's carriage drive: k_i = 1 / (L/(E A rods) + B_i^2 c_drive(q_i)).
  LinearDeltaDesign d;
  d.stiffness.actuator_stiffness = 0.0;
  const LegChainMachine rigid(linear_delta_design(d));
  d.stiffness.drive = ScrewDrive{.nut_stiffness = 2e8, .bearing_stiffness = 4e8};
  const LegChainMachine driven(linear_delta_design(d));
  const Pose pose{{0.02, 0.01, 0.3}, {0, 0, 0}};
  auto d1 = rigid.make_data();
  auto d2 = driven.make_data();
  PoseMetrics m1, m2;
  rigid.analyze(*d1, pose, Wrench::Zero(), m1);
  driven.analyze(*d2, pose, Wrench::Zero(), m2);
  EXPECT_LT(m2.stiffness_min, m1.stiffness_min);
  Eigen::MatrixXd A, B, J;
  driven.jacobians(pose, A, B, J);
  const LegChainLeg& leg = driven.design().legs[0];
  Eigen::VectorXd k(3);
  for (int i = 0; i < 3; ++i)
    k(i) = 1 / (leg.link_length / (leg.E * leg.area * leg.rods) +
                B(i, i) * B(i, i) * (1 / 2e8 + 1 / 4e8));
  const Eigen::Matrix3d C = (A.transpose() * k.asDiagonal() * A).inverse();
  EXPECT_NEAR(m2.stiffness_min,
              1 / Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(C).eigenvalues()(2),
              1e-9 * m2.stiffness_min);
}

// Natural frequencies of a linear delta with masses: the DOF mass matrix built here from the
// kinetic energy of every body (platform, carriages from the IK's carriage positions, links
// from their ends), differentiated numerically, and the DOF stiffness from the compliance give
// the frequencies analyze reports (Eigen's generalized eigensolver) and the mode shapes
// mode_shapes reports. Leg masses lower the frequencies.
TEST(LegChainCompliance, NaturalFrequenciesFromTheBodiesKineticEnergy) {
  LinearDeltaDesign p;
  p.masses.present = true;
  p.masses.platform.mass = 2.0;
  p.masses.platform.inertia = Eigen::Vector3d(0.01, 0.01, 0.02).asDiagonal();
  p.masses.legs.carriage = 1.5;
  p.masses.legs.link = {.mass = 0.4, .centre = 0.12, .inertia = 0.004};
  const LegChainDesign design = linear_delta_design(p);
  const LegChainMachine machine(design);
  ASSERT_EQ(machine.natural_frequency_count(), 3);
  const auto data = machine.make_data();
  const double h = 1e-6;
  for (const Eigen::Vector3d& position :
       {Eigen::Vector3d(0, 0, 0.05), Eigen::Vector3d(0.05, -0.03, 0.08)}) {
    const Pose pose{position, Eigen::Vector3d::Zero()};
    PoseMetrics m;
    machine.analyze(*data, pose, Wrench::Zero(), m);
    ASSERT_FALSE(m.singular);
    ASSERT_EQ(m.natural_frequencies.size(), 3);
    // Body positions at a platform position x: carriages c_i = base_i + q_i axis_i, links from
    // c_i to the platform joint P_i, centre at c_i + e s_i.
    struct Bodies {
      std::vector<Eigen::Vector3d> carriage, link_centre, link_dir;
    };
    auto bodies = [&](const Eigen::Vector3d& x) {
      Bodies b;
      const Eigen::VectorXd q = *machine.inverse_kinematics(Pose{x, Eigen::Vector3d::Zero()});
      for (std::size_t i = 0; i < 3; ++i) {
        const LegChainLeg& leg = design.legs[i];
        const Eigen::Vector3d c = leg.base_point + q(static_cast<int>(i)) * leg.axis.normalized();
        const Eigen::Vector3d P = x + leg.platform_point - design.tcp;
        const Eigen::Vector3d s = (P - c).normalized();
        b.carriage.push_back(c);
        b.link_centre.push_back(c + p.masses.legs.link.centre * s);
        b.link_dir.push_back(s);
      }
      return b;
    };
    auto energy = [&](const Eigen::Vector3d& v) {
      const Bodies plus = bodies(position + h * v), minus = bodies(position - h * v);
      double T = 0.5 * p.masses.platform.mass * v.squaredNorm();
      for (std::size_t i = 0; i < 3; ++i) {
        T += 0.5 * p.masses.legs.carriage *
             ((plus.carriage[i] - minus.carriage[i]) / (2 * h)).squaredNorm();
        T += 0.5 * p.masses.legs.link.mass *
             ((plus.link_centre[i] - minus.link_centre[i]) / (2 * h)).squaredNorm();
        const Eigen::Vector3d s = bodies(position).link_dir[i];
        const Eigen::Vector3d omega = s.cross((plus.link_dir[i] - minus.link_dir[i]) / (2 * h));
        T += 0.5 * p.masses.legs.link.inertia * omega.squaredNorm();
      }
      return T;
    };
    Eigen::Matrix3d M;
    for (int a = 0; a < 3; ++a) {
      for (int b = 0; b < 3; ++b) {
        const Eigen::Vector3d ea = Eigen::Vector3d::Unit(a), eb = Eigen::Vector3d::Unit(b);
        M(a, b) = energy(ea + eb) - energy(ea) - energy(eb);  // polarisation of 1/2 v^T M v
      }
    }
    const Eigen::Matrix3d K = data->matrices.compliance.topLeftCorner<3, 3>().inverse();
    const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::Matrix3d> ges(K,
                                                                        0.5 * (M + M.transpose()));
    for (int j = 0; j < 3; ++j) {
      const double f = std::sqrt(ges.eigenvalues()(j)) / (2 * std::numbers::pi);
      EXPECT_NEAR(m.natural_frequencies(j), f, 1e-6 * f) << j;
    }
    // The mode shapes (TCP displacements, no platform rotation) solve K x = omega^2 M x with
    // this test's K and M and are M-orthonormal (equal frequencies, as at the centre, leave the
    // shapes free within their plane, so the eigenvectors themselves are not compared).
    PoseModes modes;
    ASSERT_TRUE(machine.mode_shapes(*data, pose, modes));
    ASSERT_EQ(modes.shapes.rows(), 6);
    ASSERT_EQ(modes.shapes.cols(), 3);
    const Eigen::Matrix3d X = modes.shapes.topRows<3>();
    EXPECT_LT((X.transpose() * M * X - Eigen::Matrix3d::Identity()).norm(), 1e-6);
    for (int j = 0; j < 3; ++j) {
      EXPECT_NEAR(modes.frequencies(j), m.natural_frequencies(j), 1e-12 * m.natural_frequencies(j));
      const double omega = 2 * std::numbers::pi * modes.frequencies(j);
      const Eigen::Vector3d x = X.col(j);
      EXPECT_LT((K * x - omega * omega * M * x).norm(), 1e-6 * (K * x).norm()) << j;
      EXPECT_LT(modes.shapes.col(j).tail<3>().norm(), 1e-12 * x.norm()) << j;
    }
    // Massless legs: higher frequencies.
    LinearDeltaDesign light = p;
    light.masses.legs = LegMasses{};
    const LegChainMachine light_machine(linear_delta_design(light));
    PoseMetrics ml;
    light_machine.analyze(*light_machine.make_data(), pose, Wrench::Zero(), ml);
    for (int j = 0; j < 3; ++j) EXPECT_GT(ml.natural_frequencies(j), m.natural_frequencies(j));
  }
}

}  // namespace
}  // namespace pkmopt
