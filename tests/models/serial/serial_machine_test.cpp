// Tests of models/serial/serial_machine: a 641236 table-table machine and a head-head machine as
// Machines. Each metric against an independent computation from the chain's forward kinematics:
// round trips pose -> q -> pose, the inverse Jacobian against central differences of the IK
// along a twist, the drive loads by virtual work, the compliance against the tool's motion when
// each drive yields by its load over its stiffness, the loaded compliance against the solved
// nonlinear equilibrium, tcp_error_max against all box vertices, the singular A = 0 and the
// search box against sampled axis values.
#include "models/serial/serial_machine.hpp"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <Eigen/SVD>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include "tests/sample_machines.hpp"

namespace pkmopt {
namespace {

using sample_machines::Uniform;

constexpr double kPi = std::numbers::pi;
constexpr double kDeg = kPi / 180.0;

// 641236: C (unlimited), A tilting to one side, X, Y, Z; the spindle S.
SerialDesign table_table(double stiffness_scale = 1.0) {
  SerialDesign d;
  d.chain = SerialChain::from_code("641236");
  d.spindle = 5;
  d.axes = {{-360 * kDeg, 360 * kDeg, 2e5 * stiffness_scale, 2e-5 * kDeg},
            {-110 * kDeg, 0.0, 3e5 * stiffness_scale, 3e-5 * kDeg},
            {-0.5, 0.5, 1.5e8 * stiffness_scale, 5e-6},
            {-0.4, 0.4, 1.2e8 * stiffness_scale, 6e-6},
            {-0.3, 0.6, 1.0e8 * stiffness_scale, 4e-6}};
  d.tool_point = {0.0, 0.0, 0.15};
  return d;
}

// Head-head: X, Y, Z, then C and A on the head, no spindle axis in the chain.
SerialDesign head_head() {
  SerialDesign d;
  d.chain = SerialChain::from_code("12364");
  d.axes = {{-1, 1, 1e8, 5e-6},
            {-1, 1, 1e8, 5e-6},
            {-1, 1, 1e8, 5e-6},
            {-200 * kDeg, 200 * kDeg, 4e5, 1e-5},
            {2 * kDeg, 100 * kDeg, 4e5, 1e-5}};
  d.tool_point = {0.0, 0.0, -0.2};
  d.tool_axis = {0.0, 0.0, -1.0};
  return d;
}

Eigen::VectorXd random_in_range(const SerialDesign& d, Uniform& u) {
  Eigen::VectorXd q(5);
  for (int i = 0; i < 5; ++i) {
    const SerialAxis& a = d.axes[static_cast<std::size_t>(i)];
    q(i) = u(a.min + 0.02 * (a.max - a.min), a.max - 0.02 * (a.max - a.min));
  }
  return q;
}

Eigen::Vector3d tool_axis_of(const Pose& p) { return rotation_zyx<double>(p.angles).col(2); }

// The pose moved by a small twist [v; omega] for time t.
Pose moved(const Pose& p, const Vector6d& xi, double t) {
  Pose out;
  out.position = p.position + t * xi.head<3>();
  const Eigen::AngleAxisd turn(t * xi.tail<3>().norm(), xi.tail<3>().normalized());
  out.angles = angles_from_rotation(Eigen::Matrix3d(turn * rotation_zyx<double>(p.angles)));
  return out;
}

TEST(SerialMachine, PoseToAxesToPoseRoundTrips) {
  for (const SerialDesign& d : {table_table(), head_head()}) {
    const SerialMachine machine(d);
    auto data = machine.make_data();
    Uniform u(3);
    for (int trial = 0; trial < 40; ++trial) {
      const Eigen::VectorXd q = random_in_range(d, u);
      const FkResult fk = machine.forward_kinematics(q, std::nullopt);
      ASSERT_TRUE(fk.converged);
      PoseMetrics m;
      machine.analyze(*data, fk.pose, Wrench::Zero(), m);
      ASSERT_TRUE(m.reachable) << trial;
      // One-sided tilt ranges: the branch is unique, so the axis values themselves return
      // (the rotary ones up to whole turns).
      for (int i = 0; i < 5; ++i) {
        const double gap =
            machine.revolute_actuator(i) ? std::remainder(m.q(i) - q(i), 2.0 * kPi) : m.q(i) - q(i);
        EXPECT_NEAR(gap, 0.0, 1e-9) << d.chain.code() << " trial " << trial << " axis " << i;
      }
      const FkResult back = machine.forward_kinematics(m.q, std::nullopt);
      EXPECT_LT((back.pose.position - fk.pose.position).norm(), 1e-12);
      EXPECT_LT((tool_axis_of(back.pose) - tool_axis_of(fk.pose)).norm(), 1e-12);
    }
  }
}

TEST(SerialMachine, HeadHeadToolAxisIsTheChainsAxis) {
  const SerialMachine machine(head_head());
  Eigen::VectorXd q(5);
  q << 0.1, -0.2, 0.3, 0.0, 0.0;
  const FkResult fk = machine.forward_kinematics(q, std::nullopt);
  // C = A = 0: the tool hangs down, 0.2 m below the head's point.
  EXPECT_LT((fk.pose.position - Eigen::Vector3d(0.1, -0.2, 0.1)).norm(), 1e-15);
  EXPECT_LT((tool_axis_of(fk.pose) - Eigen::Vector3d(0, 0, -1)).norm(), 1e-15);
}

TEST(SerialMachine, InverseJacobianMatchesCentralDifferencesAndIgnoresTheSpin) {
  for (const SerialDesign& d : {table_table(), head_head()}) {
    const SerialMachine machine(d);
    auto data = machine.make_data();
    Uniform u(5);
    for (int trial = 0; trial < 20; ++trial) {
      const Pose pose = machine.forward_kinematics(random_in_range(d, u), std::nullopt).pose;
      Eigen::MatrixXd J;
      ASSERT_TRUE(machine.twist_jacobian(*data, pose, J));
      ASSERT_EQ(J.rows(), 5);
      Vector6d xi;
      for (int k = 0; k < 6; ++k) xi(k) = u(-1.0, 1.0);
      const double h = 1e-6;
      PoseMetrics plus, minus;
      machine.analyze(*data, moved(pose, xi, h), Wrench::Zero(), plus);
      machine.analyze(*data, moved(pose, xi, -h), Wrench::Zero(), minus);
      const Eigen::VectorXd fd = (plus.q - minus.q) / (2 * h);
      EXPECT_LT((J * xi - fd).cwiseAbs().maxCoeff(), 1e-6 * (1 + fd.norm())) << trial;
      Vector6d spin = Vector6d::Zero();
      spin.tail<3>() = tool_axis_of(pose);
      EXPECT_LT((J * spin).cwiseAbs().maxCoeff(), 1e-12);
    }
  }
}

// Every axis is a drive of its own, even where two have the same kind and travel (X, Y, Z here;
// a parallel machine's alike legs share one group: HybridMachine.DriveGroups...).
TEST(SerialMachine, EveryAxisIsADriveGroupOfItsOwn) {
  const SerialMachine machine(head_head());
  for (int i = 0; i < machine.num_actuators(); ++i) EXPECT_EQ(machine.drive_group(i), i);
}

TEST(SerialMachine, DriveLoadsDoTheWrenchsVirtualWork) {
  const SerialDesign d = table_table();
  const SerialMachine machine(d);
  auto data = machine.make_data();
  Uniform u(11);
  for (int trial = 0; trial < 20; ++trial) {
    const Eigen::VectorXd q = random_in_range(d, u);
    const Pose pose = machine.forward_kinematics(q, std::nullopt).pose;
    Wrench w;
    for (int k = 0; k < 6; ++k) w(k) = u(-500.0, 500.0);
    PoseMetrics m;
    machine.analyze(*data, pose, w, m);
    // tau_i = W . (the tool's twist when axis i moves), the twist from the chain's own product.
    for (int i = 0; i < 5; ++i) {
      const double h = 1e-6;
      Eigen::VectorXd qp = m.q, qm = m.q;
      qp(i) += h;
      qm(i) -= h;
      const Eigen::Matrix4d Tp = d.chain.transform(machine.full_coordinates(qp));
      const Eigen::Matrix4d Tm = d.chain.transform(machine.full_coordinates(qm));
      const Eigen::Vector3d v =
          (Tp.topLeftCorner<3, 3>() * d.tool_point + Tp.topRightCorner<3, 1>() -
           Tm.topLeftCorner<3, 3>() * d.tool_point - Tm.topRightCorner<3, 1>()) /
          (2 * h);
      const Eigen::Matrix3d dR = (Tp.topLeftCorner<3, 3>() - Tm.topLeftCorner<3, 3>()) / (2 * h);
      const Eigen::Matrix3d W = dR * Tp.topLeftCorner<3, 3>().transpose();  // [omega]x
      const Eigen::Vector3d omega(W(2, 1), W(0, 2), W(1, 0));
      const double work = w.head<3>().dot(v) + w.tail<3>().dot(omega);
      EXPECT_NEAR(m.tau(i), work, 1e-5 * (1 + std::abs(work))) << trial << " axis " << i;
    }
  }
}

TEST(SerialMachine, ComplianceIsTheToolsMotionWhenEachDriveYields) {
  const SerialDesign d = table_table();
  const SerialMachine machine(d);
  auto data = machine.make_data();
  Uniform u(13);
  for (int trial = 0; trial < 10; ++trial) {
    const Pose pose = machine.forward_kinematics(random_in_range(d, u), std::nullopt).pose;
    Wrench w;
    for (int k = 0; k < 6; ++k) w(k) = u(-0.01, 0.01);  // small: the motion is linear in it
    PoseMetrics m;
    machine.analyze(*data, pose, w, m);
    // Each drive yields by tau_i / k_i: the tool point moves by C_t w (linear in the small w).
    Eigen::VectorXd dq(5);
    for (int i = 0; i < 5; ++i) dq(i) = m.tau(i) / d.axes[static_cast<std::size_t>(i)].stiffness;
    const Eigen::Vector3d moved_point =
        machine.forward_kinematics(m.q + dq, std::nullopt).pose.position;
    const Eigen::Vector3d dp = data->matrices.compliance.topRows<3>() * w;
    EXPECT_LT((moved_point - pose.position - dp).norm(), 1e-6 * dp.norm() + 1e-15) << trial;
    // stiffness_min from the translational block.
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(
        data->matrices.compliance.topLeftCorner<3, 3>());
    EXPECT_NEAR(m.stiffness_min, 1.0 / eig.eigenvalues()(2), 1e-9 * m.stiffness_min);
    EXPECT_NEAR(m.tcp_deflection, dp.norm(), 1e-12 * (1 + dp.norm()));
  }
}

TEST(SerialMachine, LoadedComplianceIsTheTangentOfTheNonlinearEquilibrium) {
  // Soft drives and a large wrench, so that the change of the loads as the axes yield matters.
  const SerialDesign d = table_table(1e-3);
  const SerialMachine machine(d);
  auto data = machine.make_data();
  Uniform u(17);
  Eigen::VectorXd D(5);
  for (int i = 0; i < 5; ++i) D(i) = 1.0 / d.axes[static_cast<std::size_t>(i)].stiffness;
  for (int trial = 0; trial < 6; ++trial) {
    const Eigen::VectorXd q0 = random_in_range(d, u);
    Wrench w;
    for (int k = 0; k < 3; ++k) w(k) = u(-300.0, 300.0);
    for (int k = 3; k < 6; ++k) w(k) = u(-30.0, 30.0);
    // The drives' springs hold the axes at q0 unloaded; under W they yield to the equilibrium
    // q = q0 + D J_f(q)^T W (fixed-point iteration), the tool point moving with them.
    auto equilibrium = [&](const Wrench& load) {
      Eigen::VectorXd q = q0;
      for (int it = 0; it < 300; ++it)
        q = q0 + D.cwiseProduct(machine.feed_jacobian(q).transpose() * load);
      return q;
    };
    auto tool_under = [&](const Wrench& load) {
      return machine.forward_kinematics(equilibrium(load), std::nullopt).pose.position;
    };
    // The tangent compliance depends on the configuration and the load only: analyze at the
    // loaded configuration under W gives it.
    const Pose loaded_pose = machine.forward_kinematics(equilibrium(w), std::nullopt).pose;
    PoseMetrics m;
    machine.analyze(*data, loaded_pose, w, m);
    const Eigen::Matrix3d loaded = data->matrices.loaded_compliance_tt;
    const double h = 1e-2;
    Eigen::Matrix3d fd;
    for (int k = 0; k < 3; ++k) {
      Wrench plus = w, minus = w;
      plus(k) += h;
      minus(k) -= h;
      fd.col(k) = (tool_under(plus) - tool_under(minus)) / (2 * h);
    }
    EXPECT_LT((loaded - fd).norm(), 1e-6 * fd.norm()) << trial << "\n" << loaded << "\n" << fd;
    // The load matters here: the unloaded compliance differs.
    EXPECT_GT((data->matrices.compliance.topLeftCorner<3, 3>() - fd).norm(), 1e-4 * fd.norm());
    EXPECT_NEAR(m.stiffness_min_loaded, 1.0 / loaded.jacobiSvd().singularValues()(0),
                1e-12 * m.stiffness_min_loaded);
  }
}

TEST(SerialMachine, GeometricStiffnessMatchesCentralDifferencesOfTheDriveLoads) {
  for (const SerialDesign& d : {table_table(), head_head()}) {
    const SerialMachine machine(d);
    Uniform u(29);
    for (int trial = 0; trial < 10; ++trial) {
      const Eigen::VectorXd q = random_in_range(d, u);
      Wrench w;
      for (int k = 0; k < 6; ++k) w(k) = u(-100.0, 100.0);
      const Eigen::MatrixXd Kg = machine.geometric_stiffness(machine.feed_jacobian(q), w);
      const double h = 1e-6;
      for (int k = 0; k < 5; ++k) {
        Eigen::VectorXd plus = q, minus = q;
        plus(k) += h;
        minus(k) -= h;
        const Eigen::VectorXd fd = (machine.feed_jacobian(plus).transpose() * w -
                                    machine.feed_jacobian(minus).transpose() * w) /
                                   (2 * h);
        EXPECT_LT((Kg.col(k) - fd).cwiseAbs().maxCoeff(), 1e-6 * (1 + fd.norm()))
            << d.chain.code() << " trial " << trial << " column " << k;
      }
    }
  }
}

TEST(SerialMachine, TcpErrorMaxIsTheWorstVertexOfTheErrorBox) {
  const SerialDesign d = table_table();
  const SerialMachine machine(d);
  auto data = machine.make_data();
  Uniform u(19);
  for (int trial = 0; trial < 10; ++trial) {
    const Pose pose = machine.forward_kinematics(random_in_range(d, u), std::nullopt).pose;
    PoseMetrics m;
    machine.analyze(*data, pose, Wrench::Zero(), m);
    double worst = 0.0;
    for (int s = 0; s < 32; ++s) {
      Eigen::VectorXd dq(5);
      for (int i = 0; i < 5; ++i)
        dq(i) = ((s >> i) & 1 ? 1.0 : -1.0) * d.axes[static_cast<std::size_t>(i)].error;
      const Eigen::Vector3d p = machine.forward_kinematics(m.q + dq, std::nullopt).pose.position;
      worst = std::max(worst, (p - pose.position).norm());
    }
    EXPECT_NEAR(m.tcp_error_max, worst, 1e-4 * worst) << trial;
  }
}

TEST(SerialMachine, VerticalToolOnTheTiltingTableIsSingularButKeepsItsStatics) {
  SerialDesign d = table_table();
  d.axes[1] = {-110 * kDeg, 110 * kDeg, 3e5, 0.0};
  const SerialMachine machine(d);
  auto data = machine.make_data();
  const Pose vertical{{0.1, 0.05, 0.2}, {0, 0, 0}};
  PoseMetrics m;
  Wrench w;
  w << 100, -200, 300, 1, 2, 3;
  machine.analyze(*data, vertical, w, m);
  EXPECT_TRUE(m.reachable);
  EXPECT_TRUE(m.singular);
  EXPECT_EQ(m.singularity_margin, 0.0);
  EXPECT_NEAR(m.q(1), 0.0, 1e-12);  // A = 0, C free at the middle of its range (0)
  EXPECT_NEAR(m.q(0), 0.0, 1e-12);
  EXPECT_TRUE(m.tau.allFinite());
  EXPECT_GT(m.stiffness_min, 0.0);
  EXPECT_TRUE(std::isfinite(m.stiffness_min));
  Eigen::MatrixXd J;
  EXPECT_FALSE(machine.twist_jacobian(*data, vertical, J));
  // Tilted by 0.1 degree: regular, and tilting the tool sideways there needs C to turn about
  // 1 / sin(0.1 deg) = 573 times as fast as the tool axis turns.
  const Pose tilted{{0.1, 0.05, 0.2}, {0.1 * kDeg, 0, 0}};
  machine.analyze(*data, tilted, w, m);
  EXPECT_FALSE(m.singular);
  EXPECT_GT(m.singularity_margin, 0.0);
  ASSERT_TRUE(machine.twist_jacobian(*data, tilted, J));
  Vector6d sideways = Vector6d::Zero();
  sideways(4) = 1.0;  // omega about y: the axis (near z, tilted about x) turns sideways
  EXPECT_NEAR(std::abs((J * sideways)(0)), 1.0 / std::sin(0.1 * kDeg), 1e-3 / std::sin(0.1 * kDeg));
  // The two branches (C, A) and (C + 180, -A): the tie of |A| goes to the larger A, on both
  // sides of the vertical (C turns over instead of A passing through 0).
  EXPECT_NEAR(m.q(1), 0.1 * kDeg, 1e-12);
  PoseMetrics other;
  machine.analyze(*data, Pose{{0.1, 0.05, 0.2}, {-0.1 * kDeg, 0, 0}}, w, other);
  EXPECT_NEAR(other.q(1), 0.1 * kDeg, 1e-12);
  EXPECT_NEAR(std::abs(std::remainder(other.q(0) - m.q(0), 2 * kPi)), kPi, 1e-12);
  // det M = 0 at A = 0 and grows with |A|: the same at +-0.1 degrees.
  EXPECT_NEAR(other.det_j, m.det_j, 1e-9 * std::abs(m.det_j));
  PoseMetrics at_pole;
  machine.analyze(*data, vertical, w, at_pole);
  EXPECT_LT(std::abs(at_pole.det_j), 1e-12 * std::abs(m.det_j) / std::sin(0.1 * kDeg));
}

TEST(SerialMachine, OutOfRangeAndOutOfReachPoses) {
  const SerialMachine machine(table_table());
  auto data = machine.make_data();
  PoseMetrics m;
  // X beyond its 0.5 m: the branch is found, out of range by the excess.
  machine.analyze(*data, Pose{{0.8, 0, 0.2}, {0, 0, 0}}, Wrench::Zero(), m);
  EXPECT_FALSE(m.reachable);
  EXPECT_NEAR(*machine.reach_excess(Pose{{0.8, 0, 0.2}, {0, 0, 0}}), 0.3, 1e-12);
  EXPECT_FALSE(machine.reachable(*data, Pose{{0.8, 0, 0.2}, {0, 0, 0}}));
  EXPECT_TRUE(machine.reachable(*data, Pose{{0.3, 0, 0.2}, {0, 0, 0}}));
  // A tilted by 120 degrees: beyond A's 110.
  EXPECT_FALSE(machine.reachable(*data, Pose{{0.1, 0, 0.2}, {120 * kDeg, 0, 0}}));
  // Not finite: no branch.
  EXPECT_FALSE(machine.reach_excess(Pose{{NAN, 0, 0}, {0, 0, 0}}));
  machine.analyze(*data, Pose{{NAN, 0, 0}, {0, 0, 0}}, Wrench::Zero(), m);
  EXPECT_FALSE(m.reachable);
  EXPECT_TRUE(m.q.allFinite());
}

TEST(SerialMachine, SearchBoxHoldsEveryToolPoint) {
  for (const SerialDesign& d : {table_table(), head_head()}) {
    const SerialMachine machine(d);
    const auto box = machine.workspace_search_box({Eigen::Matrix3d::Identity()});
    ASSERT_TRUE(box);
    Uniform u(23);
    for (int trial = 0; trial < 2000; ++trial) {
      Eigen::VectorXd q(5);
      for (int i = 0; i < 5; ++i) {
        const SerialAxis& a = d.axes[static_cast<std::size_t>(i)];
        q(i) = trial % 2 ? u(a.min, a.max) : (u(0, 1) < 0.5 ? a.min : a.max);
      }
      const Eigen::Vector3d p = machine.forward_kinematics(q, std::nullopt).pose.position;
      EXPECT_TRUE(box->exteriorDistance(p) <= 1e-12) << p.transpose();
    }
  }
}

TEST(SerialMachine, UnitsPerAxisAndRefusals) {
  const SerialMachine machine(table_table());
  EXPECT_EQ(machine.num_actuators(), 5);
  EXPECT_TRUE(machine.revolute_actuator(0));
  EXPECT_TRUE(machine.revolute_actuator(1));
  EXPECT_FALSE(machine.revolute_actuator(2));
  EXPECT_TRUE(machine.any_revolute_actuator());
  EXPECT_FALSE(machine.revolute_actuators());
  SerialDesign four = table_table();
  four.chain = SerialChain::from_code("61236");
  four.axes.pop_back();
  EXPECT_THROW(SerialMachine{four}, std::invalid_argument);
  SerialDesign missing = table_table();
  missing.axes.pop_back();
  EXPECT_THROW(SerialMachine{missing}, std::invalid_argument);
  SerialDesign reversed = table_table();
  reversed.axes[2] = {0.5, -0.5, 0, 0};
  EXPECT_THROW(SerialMachine{reversed}, std::invalid_argument);
  const FkResult bad = machine.forward_kinematics(Eigen::VectorXd::Constant(4, 0.0), std::nullopt);
  EXPECT_FALSE(bad.converged);
}

}  // namespace
}  // namespace pkmopt
