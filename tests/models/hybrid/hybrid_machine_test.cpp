// Tests of models/hybrid/hybrid_machine: zero travel reduces to the module, the mount transform,
// IK/FK round trips, the twist Jacobian against finite differences, statics, compliances in series
// against an independent computation, tcp_error_max against brute force, the workspace of a long
// axis carrying a hexapod, and the machine files (CLI, bad files exit 2 naming the key).
#include "models/hybrid/hybrid_machine.hpp"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <Eigen/LU>
#include <Eigen/SVD>
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "io/format/input_error.hpp"
#include "io/machine/machine_file.hpp"
#include "models/hexapod/hexapod.hpp"
#include "models/leg_chain/leg_chain.hpp"
#include "models/workspace/workspace.hpp"
#include "tests/cli_runner.hpp"
#include "tests/sample_machines.hpp"
#include "tests/scratch_dir.hpp"

namespace pkmopt {
namespace {

using sample_machines::Uniform;

std::shared_ptr<const Machine> conventions_hexapod() {
  return std::make_shared<Hexapod>(sample_machines::conventions_hexapod_design());
}

HybridMachine make_hybrid(const std::string& code, const std::vector<HybridAxis>& axes,
                          std::shared_ptr<const Machine> module, const Eigen::Vector3d& home) {
  HybridDesign d;
  d.chain = SerialChain::from_code(code);
  d.axes = axes;
  d.module = std::move(module);
  d.home = home;
  return HybridMachine(d);
}

// The pose moved by the twist h [v; omega] (omega about base axes through the TCP).
Pose moved(const Pose& pose, const Vector6d& twist, double h) {
  Pose out = pose;
  out.position += h * twist.head<3>();
  out.angles = angles_from_rotation(rotation_from_vector(h * twist.tail<3>()) *
                                    rotation_zyx<double>(pose.angles));
  return out;
}

// The world pose of a module-local pose, computed independently of the machine: T_chain(q_s)
// times the local pose.
Pose world_of(const SerialChain& chain, const Eigen::VectorXd& q_serial, const Pose& local) {
  const Eigen::Matrix4d T = chain.transform(q_serial);
  Pose world;
  world.position = T.topLeftCorner<3, 3>() * local.position + T.topRightCorner<3, 1>();
  world.angles = angles_from_rotation(T.topLeftCorner<3, 3>() * rotation_zyx<double>(local.angles));
  return world;
}

void expect_same_pose(const Pose& a, const Pose& b, double tol) {
  EXPECT_LE((a.position - b.position).norm(), tol);
  const Eigen::Matrix3d dR =
      rotation_zyx<double>(a.angles) * rotation_zyx<double>(b.angles).transpose();
  EXPECT_LE(rotation_vector(dR).norm(), tol);
}

// With no travel and rigid, exact axes the hybrid is its module moved by the mount.
TEST(HybridMachine, ZeroTravelEqualsTheModule) {
  Uniform u(11);
  std::vector<std::shared_ptr<const Machine>> modules = {
      conventions_hexapod(), std::make_shared<Hexapod>(sample_machines::random_hexapod_design(u)),
      make_hexaglide(HexaglideDesign{}), make_linear_delta(LinearDeltaDesign{})};
  for (const auto& module : modules) {
    // Identity mount, then a tilted and offset one (constant elements, radians in code strings).
    for (const std::string code : {"1 2 3", "3:0.4 1 5:0.3 2 4:-0.2 3 6:0.5"}) {
      const HybridMachine hybrid = make_hybrid(code, {{0, 0}, {0, 0}, {0, 0}}, module, {0, 0, 1});
      const Eigen::Matrix4d T = hybrid.design().chain.transform(Eigen::Vector3d::Zero());
      const Eigen::Matrix3d R0 = T.topLeftCorner<3, 3>();
      auto hybrid_data = hybrid.make_data();
      auto module_data = module->make_data();
      int compared = 0;
      for (int k = 0; k < 40; ++k) {
        Pose local;
        if (const auto* chain = dynamic_cast<const LegChainMachine*>(module.get())) {
          local.position = chain->design().home.position +
                           Eigen::Vector3d(u(-0.05, 0.05), u(-0.05, 0.05), u(-0.05, 0.05));
        } else {
          local = sample_machines::random_pose(u);
          if (module.get() == modules[0].get()) local.position(2) = u(0.75, 1.0);
        }
        local.angles = deg_to_rad(Eigen::Vector3d(u(-10, 10), u(-10, 10), u(-10, 10)));
        if (module->model() == "linear_delta") local.angles.setZero();  // translational platform
        const Pose world = world_of(hybrid.design().chain, Eigen::Vector3d::Zero(), local);
        Wrench w;
        for (int i = 0; i < 6; ++i) w(i) = u(-500, 500);
        Wrench w_local;
        w_local << R0.transpose() * w.head<3>(), R0.transpose() * w.tail<3>();
        PoseMetrics mh, mm;
        hybrid.analyze(*hybrid_data, world, w, mh);
        module->analyze(*module_data, local, w_local, mm);
        EXPECT_EQ(mh.singular, mm.singular);
        if (mm.singular) {
          EXPECT_TRUE(std::isinf(mh.tcp_error_max));
          continue;
        }
        compared += mm.reachable;
        EXPECT_EQ(mh.reachable, mm.reachable);
        EXPECT_EQ(hybrid.reachable(*hybrid_data, world), mm.reachable);
        ASSERT_EQ(mh.q.size(), 3 + mm.q.size());
        EXPECT_LE(mh.q.head(3).cwiseAbs().maxCoeff(), 0.0);
        EXPECT_LE((mh.q.tail(mm.q.size()) - mm.q).cwiseAbs().maxCoeff(), 1e-12);
        const double tau_scale = 1.0 + mm.tau.cwiseAbs().maxCoeff();
        EXPECT_LE((mh.tau.tail(mm.tau.size()) - mm.tau).cwiseAbs().maxCoeff(), 1e-9 * tau_scale);
        EXPECT_NEAR(mh.stiffness_min, mm.stiffness_min, 1e-9 * mm.stiffness_min);
        EXPECT_NEAR(mh.singularity_margin, mm.singularity_margin, 1e-12);
        EXPECT_NEAR(mh.det_j, mm.det_j, 1e-12 * std::abs(mm.det_j));
        EXPECT_NEAR(mh.tcp_error_max, mm.tcp_error_max, 1e-12 * mm.tcp_error_max);
      }
      EXPECT_GT(compared, 5) << module->model();
    }
  }
}

TEST(HybridMachine, RefusesRotaryAxesDependentAxesAndBadRanges) {
  const auto hexapod = conventions_hexapod();
  EXPECT_THROW(make_hybrid("14", {{0, 1}, {0, 1}}, hexapod, {0, 0, 1}), std::invalid_argument);
  EXPECT_THROW(make_hybrid("1 6:0 1", {{0, 1}, {0, 1}}, hexapod, {0, 0, 1}),
               std::invalid_argument);  // two parallel x axes
  EXPECT_THROW(make_hybrid("1", {{1, 0}}, hexapod, {0, 0, 1}), std::invalid_argument);
  EXPECT_THROW(make_hybrid("12", {{0, 1}}, hexapod, {0, 0, 1}), std::invalid_argument);
  EXPECT_THROW(make_hybrid("1", {{0, 1, -1.0}}, hexapod, {0, 0, 1}), std::invalid_argument);
  EXPECT_THROW(make_hybrid("1", {{0, 1}}, make_delta(DeltaDesign{}), {0, 0, -0.9}),
               std::invalid_argument);  // revolute drives
}

// A hybrid machine has dynamics when its module has; without, it says why, in the module's words.
TEST(HybridMachine, DynamicsComeFromTheModule) {
  const HybridMachine bare = make_hybrid("1", {{-1.0, 1.0}}, conventions_hexapod(), {0, 0, 0.9});
  EXPECT_FALSE(bare.dynamics());
  EXPECT_EQ(bare.dynamics().reason(),
            "its parallel module has no mass model (the machine file has no 'masses')");
  EXPECT_EQ(bare.translational_maps(), nullptr);
}

// The follow rule: q_s = clamp(A^+ (p - t0 - R0 h)), here with one x axis.
TEST(HybridMachine, FollowRuleAndRoundTrip) {
  const HybridMachine hybrid = make_hybrid("1", {{-1.0, 1.0}}, conventions_hexapod(), {0, 0, 0.9});
  auto data = hybrid.make_data();
  PoseMetrics m;
  hybrid.analyze(*data, Pose{{0.7, 0.05, 0.9}, {0, 0, 0}}, Wrench::Zero(), m);
  EXPECT_DOUBLE_EQ(m.q(0), 0.7);
  hybrid.analyze(*data, Pose{{1.1, 0.0, 0.9}, {0, 0, 0}}, Wrench::Zero(), m);
  EXPECT_DOUBLE_EQ(m.q(0), 1.0);  // clamped; the hexapod takes the remaining 0.1 m
  EXPECT_TRUE(m.reachable);

  Uniform u(5);
  int reachable = 0;
  for (int k = 0; k < 60; ++k) {
    const Pose pose{{u(-1.2, 1.2), u(-0.1, 0.1), u(0.8, 1.0)},
                    deg_to_rad(Eigen::Vector3d(u(-10, 10), u(-10, 10), u(-20, 20)))};
    hybrid.analyze(*data, pose, Wrench::Zero(), m);
    if (!m.reachable) continue;
    ++reachable;
    const FkResult fk = hybrid.forward_kinematics(m.q, std::nullopt);
    ASSERT_TRUE(fk.converged) << fk.message;
    expect_same_pose(fk.pose, pose, 1e-9);
    // From a guess 2 cm and 2 deg away as well.
    const FkResult fk_guess =
        hybrid.forward_kinematics(m.q, Pose{pose.position + Eigen::Vector3d(0.02, -0.02, 0.01),
                                            pose.angles + deg_to_rad(Eigen::Vector3d(2, -2, 2))});
    ASSERT_TRUE(fk_guess.converged);
    expect_same_pose(fk_guess.pose, pose, 1e-9);
  }
  EXPECT_GT(reachable, 15);
}

// The drives bought as one entry: each serial axis alone (even at equal travels), the module's
// alike legs together; a hexapod module's six legs are one group.
TEST(HybridMachine, DriveGroupsAreEachAxisAndTheModulesLegs) {
  const HybridMachine gantry = make_hybrid("12", {{-1.0, 1.0}, {-1.0, 1.0}},
                                           make_tripod_3prs(Tripod3PrsDesign{}), {0, 0, 1.2});
  const std::vector<int> expected = {0, 1, 2, 2, 2};
  for (int i = 0; i < gantry.num_actuators(); ++i)
    EXPECT_EQ(gantry.drive_group(i), expected[static_cast<std::size_t>(i)]) << i;
  const HybridMachine long_axis =
      make_hybrid("1", {{-1.0, 1.0}}, conventions_hexapod(), {0, 0, 0.9});
  EXPECT_EQ(long_axis.drive_group(0), 0);
  for (int i = 1; i < 7; ++i) EXPECT_EQ(long_axis.drive_group(i), 1) << i;
}

// A gantry X/Y carrying a 3-PRS head: the axes compensate the head's parasitic x, y.
TEST(HybridMachine, GantryOverATripodRoundTrip) {
  const std::shared_ptr<const Machine> tripod = make_tripod_3prs(Tripod3PrsDesign{});
  const HybridMachine hybrid = make_hybrid("12", {{-1.5, 1.5}, {-1.0, 1.0}}, tripod, {0, 0, 1.2});
  auto data = hybrid.make_data();
  Uniform u(9);
  int checked = 0;
  for (int k = 0; k < 30; ++k) {
    Eigen::VectorXd q(5);
    q << u(-1.2, 1.2), u(-0.8, 0.8), u(0.4, 0.55), u(0.4, 0.55), u(0.4, 0.55);
    const FkResult fk = hybrid.forward_kinematics(q, std::nullopt);
    if (!fk.converged) continue;
    PoseMetrics m;
    hybrid.analyze(*data, fk.pose, Wrench::Zero(), m);
    if (!m.reachable) continue;
    ++checked;
    EXPECT_LE((m.q - q).cwiseAbs().maxCoeff(), 1e-9);
    // Beyond the Y range the parasitic motion can no longer be compensated.
    Pose far = fk.pose;
    far.position(1) = 1.5;
    EXPECT_FALSE(hybrid.reachable(*data, far));
  }
  EXPECT_GT(checked, 15);
}

// d q / d(pose) along every unit twist against central differences of q(pose).
TEST(HybridMachine, TwistJacobianMatchesFiniteDifferences) {
  const HybridMachine hybrid = make_hybrid("1 3:0.1 6:0.4 2 5:0.2", {{-1.0, 1.0}, {-0.5, 0.5}},
                                           conventions_hexapod(), {0.02, -0.01, 0.9});
  auto data = hybrid.make_data();
  const Eigen::Matrix3d R0 = hybrid.mount_rotation();
  Uniform u(21);
  int checked = 0;
  for (int k = 0; k < 20; ++k) {
    // Local pose near home, serial axes inside (first 14 poses) or beyond their ranges.
    const bool beyond = k >= 14;
    Eigen::Vector2d qs(u(-0.8, 0.8), beyond ? 0.8 : u(-0.4, 0.4));
    Pose local{{u(-0.05, 0.05), u(-0.05, 0.05), u(0.85, 0.95)},
               deg_to_rad(Eigen::Vector3d(u(-8, 8), u(-8, 8), u(-8, 8)))};
    const Pose pose = world_of(hybrid.design().chain, qs, local);
    Eigen::MatrixXd J;
    ASSERT_TRUE(hybrid.twist_jacobian(*data, pose, J));
    ASSERT_EQ(J.rows(), 8);
    PoseMetrics m;
    for (int j = 0; j < 6; ++j) {
      Vector6d twist = Vector6d::Zero();
      twist(j) = 1.0;
      const double h = 1e-6;
      hybrid.analyze(*data, moved(pose, twist, h), Wrench::Zero(), m);
      const Eigen::VectorXd q_plus = m.q;
      hybrid.analyze(*data, moved(pose, twist, -h), Wrench::Zero(), m);
      const Eigen::VectorXd fd = (q_plus - m.q) / (2 * h);
      EXPECT_LE((J.col(j) - fd).cwiseAbs().maxCoeff(), 1e-6) << "pose " << k << " twist " << j;
    }
    if (beyond) {
      EXPECT_LE(J.row(1).cwiseAbs().maxCoeff(), 0.0);  // the clamped Y stands still
    }
    ++checked;
  }
  EXPECT_EQ(checked, 20);
  (void)R0;
}

// Parasitic module: J times the twist made by a small change of q_k gives e_k.
TEST(HybridMachine, TwistJacobianOfTheGantryTripodInvertsForwardKinematics) {
  const std::shared_ptr<const Machine> tripod = make_tripod_3prs(Tripod3PrsDesign{});
  const HybridMachine hybrid = make_hybrid("12", {{-1.5, 1.5}, {-1.0, 1.0}}, tripod, {0, 0, 1.2});
  auto data = hybrid.make_data();
  Uniform u(4);
  for (int k = 0; k < 10; ++k) {
    Eigen::VectorXd q(5);
    q << u(-1.0, 1.0), u(-0.6, 0.6), u(0.4, 0.55), u(0.4, 0.55), u(0.4, 0.55);
    const FkResult fk = hybrid.forward_kinematics(q, std::nullopt);
    ASSERT_TRUE(fk.converged);
    Eigen::MatrixXd J;
    ASSERT_TRUE(hybrid.twist_jacobian(*data, fk.pose, J));
    for (int j = 0; j < 5; ++j) {
      const double h = 1e-6;
      Eigen::VectorXd qp = q, qm = q;
      qp(j) += h;
      qm(j) -= h;
      const Pose pp = hybrid.forward_kinematics(qp, fk.pose).pose;
      const Pose pm = hybrid.forward_kinematics(qm, fk.pose).pose;
      Vector6d twist;
      twist.head<3>() = (pp.position - pm.position) / (2 * h);
      twist.tail<3>() = rotation_vector(rotation_zyx<double>(pp.angles) *
                                        rotation_zyx<double>(pm.angles).transpose()) /
                        (2 * h);
      const Eigen::VectorXd rate = J * twist;
      EXPECT_LE((rate - Eigen::VectorXd::Unit(5, j)).cwiseAbs().maxCoeff(), 1e-6)
          << "q " << k << " actuator " << j;
    }
  }
}

// tau_s = A^T f and the module's equilibrium J_p^T tau_p = local wrench, with non-orthogonal axes
// and a tilted mount.
TEST(HybridMachine, Statics) {
  const HybridMachine hybrid = make_hybrid("1 6:0.5 1 4:0.3 3", {{-1, 1}, {-1, 1}, {-0.3, 0.3}},
                                           conventions_hexapod(), {0, 0, 0.9});
  const Eigen::MatrixXd A = hybrid.axis_directions();
  EXPECT_NEAR(A.col(0).dot(A.col(1)), std::cos(0.5), 1e-15);  // not orthogonal
  const Eigen::Matrix3d R0 = hybrid.mount_rotation();
  auto data = hybrid.make_data();
  Uniform u(8);
  for (int k = 0; k < 10; ++k) {
    const Pose pose{{u(-0.5, 0.5), u(-0.3, 0.3), u(0.6, 0.9)},
                    deg_to_rad(Eigen::Vector3d(u(-10, 10), u(-10, 10), u(-10, 10)))};
    Wrench w;
    for (int i = 0; i < 6; ++i) w(i) = u(-1000, 1000);
    PoseMetrics m;
    hybrid.analyze(*data, pose, w, m);
    ASSERT_FALSE(m.singular);
    for (int i = 0; i < 3; ++i) EXPECT_NEAR(m.tau(i), A.col(i).dot(w.head<3>()), 1e-9);
    const HybridSplit s = hybrid.split(pose);
    Eigen::MatrixXd Jp;
    auto module_data = hybrid.module().make_data();
    ASSERT_TRUE(hybrid.module().twist_jacobian(*module_data, s.local, Jp));
    Wrench w_local;
    w_local << R0.transpose() * w.head<3>(), R0.transpose() * w.tail<3>();
    EXPECT_LE((Jp.transpose() * m.tau.tail(6) - w_local).cwiseAbs().maxCoeff(), 1e-8);
  }
}

// Compliances in series against the hexapod's own stiffness matrix: stiffness_min, the 6x6
// compliance (the module's turned by R0 plus the axes), the deflection under a wrench, and the
// loaded stiffness (the module's loaded translational block at the local wrench, turned, plus the
// axes).
TEST(HybridMachine, StiffnessOfAxesAndModuleInSeries) {
  const auto hexapod = conventions_hexapod();
  const Hexapod& hex = static_cast<const Hexapod&>(*hexapod);
  const HybridMachine hybrid =
      make_hybrid("1 5:0.25 2", {{-1, 1, 1.5e8}, {-1, 1, 8e7}}, hexapod, {0, 0, 0.9});
  const Eigen::Matrix3d R0 = hybrid.mount_rotation();
  const Eigen::MatrixXd A = hybrid.axis_directions();
  auto data = hybrid.make_data();
  Uniform u(3);
  for (int k = 0; k < 10; ++k) {
    const Pose pose{{u(-0.5, 0.5), u(-0.3, 0.3), u(0.7, 1.0)},
                    deg_to_rad(Eigen::Vector3d(u(-10, 10), u(-10, 10), u(-10, 10)))};
    Wrench w;
    w << u(-3e3, 3e3), u(-3e3, 3e3), u(-3e4, 0), u(-100, 100), u(-100, 100), u(-100, 100);
    PoseMetrics m;
    hybrid.analyze(*data, pose, w, m);
    const HybridSplit s = hybrid.split(pose);
    const Matrix6d C = hex.stiffness_matrix(s.local).inverse();
    const Eigen::Matrix3d axes =
        A.col(0) * A.col(0).transpose() / 1.5e8 + A.col(1) * A.col(1).transpose() / 8e7;
    const Eigen::Matrix3d Ctt = R0 * C.topLeftCorner<3, 3>() * R0.transpose() + axes;
    const double expected =
        1.0 / Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(Ctt).eigenvalues().maxCoeff();
    EXPECT_NEAR(m.stiffness_min, expected, 1e-8 * expected);
    Matrix6d turn = Matrix6d::Zero();
    turn.topLeftCorner<3, 3>() = turn.bottomRightCorner<3, 3>() = R0;
    Matrix6d C6 = turn * C * turn.transpose();
    C6.topLeftCorner<3, 3>() += axes;
    EXPECT_LT((data->matrices.compliance - C6).norm(), 1e-9 * C6.norm());
    const Vec6<double> dx = C6 * w;
    EXPECT_NEAR(m.tcp_deflection, dx.head<3>().norm(), 1e-9 * dx.head<3>().norm());
    EXPECT_NEAR(m.tcp_rotation_deflection, dx.tail<3>().norm(), 1e-9 * dx.tail<3>().norm());
    Wrench local;
    local << R0.transpose() * w.head<3>(), R0.transpose() * w.tail<3>();
    PoseMetrics module;
    const auto module_data = hex.make_data();
    hex.analyze(*module_data, s.local, local, module);
    const Eigen::Matrix3d loaded =
        R0 * module_data->matrices.loaded_compliance_tt * R0.transpose() + axes;
    const double loaded_expected =
        1.0 / Eigen::JacobiSVD<Eigen::Matrix3d>(loaded).singularValues()(0);
    EXPECT_NEAR(m.stiffness_min_loaded, loaded_expected, 1e-9 * loaded_expected);
    EXPECT_NE(m.stiffness_min_loaded, m.stiffness_min);
  }
  // Nearly rigid hexapod: the stiffness along the soft axis is the axis stiffness.
  HexapodDesign stiff = sample_machines::conventions_hexapod_design();
  stiff.stiffness = LegStiffness{};
  stiff.stiffness.axial_stiffness = 1e16;
  const HybridMachine soft_axis =
      make_hybrid("1", {{-1, 1, 2e7}}, std::make_shared<Hexapod>(stiff), {0, 0, 0.9});
  auto soft_data = soft_axis.make_data();
  PoseMetrics m;
  soft_axis.analyze(*soft_data, Pose{{0.3, 0, 0.9}, {0, 0, 0}}, Wrench::Zero(), m);
  EXPECT_NEAR(m.stiffness_min, 2e7, 2e7 * 1e-6);
}

// tcp_error_max: no sample of the box exceeds it and a vertex attains it (independent map from
// the hexapod's inverse Jacobian).
TEST(HybridMachine, TcpErrorMaxIsTheBoxMaximum) {
  const auto hexapod = conventions_hexapod();
  const Hexapod& hex = static_cast<const Hexapod&>(*hexapod);
  const HybridMachine hybrid =
      make_hybrid("1 6:0.7 2", {{-1, 1, 0, 2e-5}, {-1, 1, 0, 7e-6}}, hexapod, {0, 0, 0.9});
  const Eigen::Matrix3d R0 = hybrid.mount_rotation();
  const Eigen::MatrixXd A = hybrid.axis_directions();
  auto data = hybrid.make_data();
  Uniform u(17);
  const Pose pose{{0.3, 0.1, 0.85}, deg_to_rad(Eigen::Vector3d(5, -3, 10))};
  PoseMetrics m;
  hybrid.analyze(*data, pose, Wrench::Zero(), m);
  const HybridSplit s = hybrid.split(pose);
  const Matrix6d Jinv = hex.inverse_jacobian(s.local).inverse();
  Eigen::Matrix<double, 3, 8> E;
  E.col(0) = 2e-5 * A.col(0);
  E.col(1) = 7e-6 * A.col(1);
  E.rightCols<6>() = R0 * Jinv.topRows<3>() * hex.design().actuator_error;
  double vertex_max = 0.0;
  for (unsigned g = 0; g < 256; ++g) {
    Eigen::Matrix<double, 8, 1> sign;
    for (int j = 0; j < 8; ++j) sign(j) = (g >> j) & 1u ? 1.0 : -1.0;
    vertex_max = std::max(vertex_max, (E * sign).norm());
  }
  EXPECT_NEAR(m.tcp_error_max, vertex_max, 1e-12 * vertex_max);
  double sampled = 0.0;
  for (int k = 0; k < 4000; ++k) {
    Eigen::Matrix<double, 8, 1> x;
    for (int j = 0; j < 8; ++j) x(j) = u(-1, 1);
    sampled = std::max(sampled, (E * x).norm());
  }
  EXPECT_LE(sampled, m.tcp_error_max * (1 + 1e-12));
  EXPECT_GT(m.tcp_error_max, hex.design().actuator_error);
}

// The module maps behind the series formulas: the hexapod's against its stiffness matrix and
// inverse Jacobian, the 3-PRS head's error map against central differences of its FK.
TEST(HybridMachine, ModuleTranslationalMaps) {
  const Hexapod hexapod(sample_machines::conventions_hexapod_design());
  auto hex_data = hexapod.make_data();
  const Pose pose{{0.05, -0.03, 0.88}, deg_to_rad(Eigen::Vector3d(4, -6, 9))};
  Eigen::Matrix3d C;
  Eigen::Matrix<double, 3, Eigen::Dynamic> E;
  PoseMetrics metrics, reference;
  const Wrench w = (Wrench() << 300, -200, -900, 10, 0, -20).finished();
  ASSERT_TRUE(hexapod.analyze_with_maps(*hex_data, pose, w, metrics, C, E));
  hexapod.analyze(*hexapod.make_data(), pose, w, reference);  // the same analyze
  EXPECT_EQ(metrics.tau, reference.tau);
  EXPECT_EQ(metrics.stiffness_min, reference.stiffness_min);
  EXPECT_EQ(metrics.tcp_error_max, reference.tcp_error_max);
  const Eigen::Matrix3d C_ref = hexapod.stiffness_matrix(pose).inverse().topLeftCorner<3, 3>();
  EXPECT_LE((C - C_ref).cwiseAbs().maxCoeff(), 1e-9 * C_ref.cwiseAbs().maxCoeff());
  const Eigen::Matrix<double, 3, 6> E_ref =
      hexapod.design().actuator_error * hexapod.inverse_jacobian(pose).inverse().topRows<3>();
  EXPECT_LE((E - E_ref).cwiseAbs().maxCoeff(), 1e-12 * E_ref.cwiseAbs().maxCoeff());

  const auto tripod = make_tripod_3prs(Tripod3PrsDesign{});
  auto tripod_data = tripod->make_data();
  const Eigen::Vector3d q(0.45, 0.52, 0.40);
  const FkResult fk = tripod->forward_kinematics(q, std::nullopt);
  ASSERT_TRUE(fk.converged);
  ASSERT_NE(tripod->translational_maps(), nullptr);
  ASSERT_TRUE(
      tripod->translational_maps()->analyze_with_maps(*tripod_data, fk.pose, w, metrics, C, E));
  tripod->analyze(*tripod->make_data(), fk.pose, w, reference);
  EXPECT_EQ(metrics.tau, reference.tau);
  EXPECT_EQ(metrics.stiffness_min, reference.stiffness_min);
  const double error = static_cast<const LegChainMachine&>(*tripod).design().actuator_error;
  for (int j = 0; j < 3; ++j) {
    const double h = 1e-6;
    const Eigen::Vector3d step = h * Eigen::Vector3d::Unit(j);
    const Eigen::Vector3d fd = (tripod->forward_kinematics(q + step, fk.pose).pose.position -
                                tripod->forward_kinematics(q - step, fk.pose).pose.position) /
                               (2 * h) * error;
    EXPECT_LE((E.col(j) - fd).norm(), 1e-6 * error) << "actuator " << j;
  }
  EXPECT_GT(C.trace(), 0.0);
}

TEST(HybridMachine, SingularModulePoseGivesInfNotNan) {
  // Platform in the base plane with the TCP at the platform origin: every leg horizontal.
  HexapodDesign flat = sample_machines::conventions_hexapod_design();
  flat.tcp = Eigen::Vector3d::Zero();
  const HybridMachine hybrid =
      make_hybrid("1", {{-1, 1, 1e8, 1e-6}}, std::make_shared<Hexapod>(flat), {0, 0, 0.0});
  auto data = hybrid.make_data();
  PoseMetrics m;
  hybrid.analyze(*data, Pose{{0.2, 0, 0}, {0, 0, 0}}, Wrench::Zero(), m);
  EXPECT_TRUE(m.singular);
  EXPECT_EQ(m.stiffness_min, 0.0);
  EXPECT_EQ(m.singularity_margin, 0.0);
  EXPECT_TRUE(std::isinf(m.tcp_error_max));
  EXPECT_TRUE((m.tau.array() == std::numeric_limits<double>::infinity()).all());
}

// Long X axis with travel [-1, 1] carrying a hexapod, follow rule about h = (0, 0, h_z): a
// position is reachable iff the module reaches (x - clamp(x, -1, 1), y, z). So the hybrid's X
// extent is the module's plus 2 m, and V_hybrid = V_module + 2 * A0 with A0 the area of the
// module's workspace section at x = 0.
TEST(HybridMachine, WorkspaceOfALongAxisCarryingAHexapod) {
  const auto hexapod = conventions_hexapod();
  const HybridMachine hybrid = make_hybrid("1", {{-1, 1}}, hexapod, {0, 0, 0.9});
  WorkspaceOptions options;
  options.resolution = 0.04;
  options.compute_hull = false;
  options.compute_maps = false;
  const WorkspaceResult bare = compute_workspace(*hexapod, options);
  const WorkspaceResult ws = compute_workspace(hybrid, options);
  EXPECT_FALSE(ws.touches_search_box);
  EXPECT_NEAR(ws.bounding_box.min()(0), bare.bounding_box.min()(0) - 1.0, 1e-6);
  EXPECT_NEAR(ws.bounding_box.max()(0), bare.bounding_box.max()(0) + 1.0, 1e-6);

  // A0 by a fine grid (2 mm) on the section x = 0 of the module's search box.
  const Eigen::AlignedBox3d box = *hexapod->workspace_search_box({Eigen::Matrix3d::Identity()});
  auto data = hexapod->make_data();
  const double step = 0.002;
  double area = 0.0;
  for (double y = box.min()(1) + step / 2; y < box.max()(1); y += step) {
    for (double z = box.min()(2) + step / 2; z < box.max()(2); z += step) {
      if (hexapod->reachable(*data, Pose{{0, y, z}, {0, 0, 0}})) area += step * step;
    }
  }
  EXPECT_NEAR(ws.volume - bare.volume, 2.0 * area, 0.01 * 2.0 * area);
  EXPECT_GT(ws.volume, 4.0 * bare.volume);
}

// A gantry X/Y carrying a 3-PRS head at identity orientation: the head has no parasitic x, y
// there, so the workspace is the X x Y travel times the head's Z stroke (q in [0, 0.95]).
TEST(HybridMachine, WorkspaceOfAGantryCarryingATripod) {
  const std::shared_ptr<const Machine> tripod = make_tripod_3prs(Tripod3PrsDesign{});
  const HybridMachine hybrid = make_hybrid("12", {{-1.5, 1.5}, {-1.0, 1.0}}, tripod, {0, 0, 1.2});
  WorkspaceOptions options;
  options.resolution = 0.05;
  options.compute_hull = false;
  options.compute_maps = false;
  const WorkspaceResult ws = compute_workspace(hybrid, options);
  EXPECT_NEAR(ws.volume, 3.0 * 2.0 * 0.95, 1e-3 * 3.0 * 2.0 * 0.95);
  EXPECT_NEAR(ws.bounding_box.min()(0), -1.5, 1e-3);
  EXPECT_NEAR(ws.bounding_box.max()(1), 1.0, 1e-3);
}

// ------------------------------------------------------------------------------------------
// Machine files and the CLI.

class HybridFiles : public scratch::ScratchDirTest {
 protected:
  void SetUp() override {
    std::filesystem::copy_file(examples_ / "hexapod.yaml", dir_ / "hexapod.yaml");
  }
  // The message of loading a hybrid file with the given serial and parallel sections.
  std::string error_of(const std::string& text) {
    try {
      load_machine_file(write("m.yaml", text));
    } catch (const InputError& e) {
      return e.what();
    }
    return "no error";
  }
  const std::filesystem::path examples_ = std::filesystem::path(PKMOPT_SOURCE_DIR) / "examples";
};

TEST_F(HybridFiles, ExamplesLoadAndDescribe) {
  const auto hexamech = load_machine_file((examples_ / "hybrid_long_axis_hexapod.yaml").string());
  EXPECT_EQ(hexamech->model(), "hybrid");
  EXPECT_EQ(hexamech->num_actuators(), 7);
  const auto gantry = load_machine_file((examples_ / "hybrid_gantry_3prs.yaml").string());
  EXPECT_EQ(gantry->num_actuators(), 5);
  cli_runner::CliRun run =
      run_cli("describe " + (examples_ / "hybrid_long_axis_hexapod.yaml").string());
  EXPECT_EQ(run.status, 0) << run.err;
  EXPECT_NE(run.out.find("structure_class: P1З6"), std::string::npos) << run.out;
  run = run_cli("describe " + (examples_ / "hybrid_gantry_3prs.yaml").string());
  EXPECT_EQ(run.status, 0) << run.err;
  EXPECT_NE(run.out.find("structure_class: P2З3"), std::string::npos) << run.out;
}

TEST_F(HybridFiles, AnalyzeFkAndWorkspaceOnTheLongAxis) {
  const std::string machine = (examples_ / "hybrid_long_axis_hexapod.yaml").string();
  const std::string poses = write("p.csv", "x,y,z,rx,ry,rz\n0.7,0,0.9,0,0,0\n1.1,0,0.9,0,0,0\n");
  cli_runner::CliRun run =
      run_cli("analyze " + machine + " --poses " + poses + " --wrench 0,0,-1000,0,0,0");
  ASSERT_EQ(run.status, 0) << run.err;
  EXPECT_NE(run.out.find("q_7,tau_1"), std::string::npos);
  // X at 0.7, then clamped at 1.0; the X drive carries no part of a vertical load.
  EXPECT_NE(run.out.find("\n0.7,0,0.9,0,0,0,1,0.7,"), std::string::npos) << run.out;
  EXPECT_NE(run.out.find("\n1.1,0,0.9,0,0,0,1,1,"), std::string::npos) << run.out;
  run = run_cli("fk " + machine +
                " --q 0.7,1.0921019490250472,1.0921019490250472,"
                "1.0921019490250472,1.0921019490250472,1.0921019490250472,"
                "1.0921019490250472");
  ASSERT_EQ(run.status, 0) << run.err;
  const std::size_t line = run.out.find('\n');
  ASSERT_NE(line, std::string::npos);
  EXPECT_NEAR(std::stod(run.out.substr(line + 1)), 0.7, 1e-12) << run.out;
  run = run_cli("workspace " + machine + " --resolution 0.05");
  EXPECT_EQ(run.status, 0) << run.err;
  EXPECT_NE(run.out.find("workspace (constant_orientation): volume"), std::string::npos);
}

// pkmopt trajectory: the rates from the hybrid's twist Jacobian agree with central differences of
// its IK along the seeds' helix (second-order differences: ~2e-7 m/s at 2001 samples).
TEST_F(HybridFiles, TrajectoryRatesMatchDifferencesOfTheIk) {
  const cli_runner::CliRun run = cli_runner::run_cli(
      dir_,
      "trajectory " + (examples_ / "hybrid_long_axis_hexapod.yaml").string() +
          " --helix --helix-centre 0.3,0.05,0.85 --helix-angles 10,10,5 --samples 2001 --out " +
          (dir_ / "t.csv").string());
  ASSERT_EQ(run.status, 0) << run.err;
  const std::string key = "max |q_dot - q_dot_fd| ";
  const std::size_t at = run.out.find(key);
  ASSERT_NE(at, std::string::npos) << run.out;
  EXPECT_LT(std::stod(run.out.substr(at + key.size())), 1e-3) << run.out;  // mm/s
  EXPECT_NE(run.out.find(" mm/s (interior samples)"), std::string::npos) << run.out;
  EXPECT_NE(run.out.find("2001 reachable"), std::string::npos) << run.out;
}

TEST_F(HybridFiles, BadFilesNameTheKey) {
  const std::string par = "parallel: {file: hexapod.yaml, home: [0, 0, 0.9]}\n";
  EXPECT_NE(error_of("model: hybrid\nserial: {code: \"1\", range: [[-1, 1]], speed: 1}\n" + par)
                .find("serial.speed"),
            std::string::npos);
  EXPECT_NE(error_of("model: hybrid\nserial: {code: \"12\", range: [[-1, 1]]}\n" + par)
                .find("serial.range: expected a list of 2, found a list of 1"),
            std::string::npos);
  EXPECT_NE(error_of("model: hybrid\nserial: {code: \"1\", range: [[1, -1]]}\n" + par)
                .find("serial.range[0]: expected [min, max] with min <= max (m), found [1, -1]"),
            std::string::npos);
  EXPECT_NE(error_of("model: hybrid\nserial: {code: \"14\", range: [[-1, 1], [0, 1]]}\n" + par)
                .find("serial.code: expected variable axes that are translations"),
            std::string::npos);
  EXPECT_NE(error_of("model: hybrid\nserial: {code: \"1 6:0 1\", range: [[-1, 1], [0, 1]]}\n" + par)
                .find("serial.code: hybrid: the 2 serial axes are linearly dependent"),
            std::string::npos);
  EXPECT_NE(error_of("model: hybrid\nserial: {code: \"1\"}\n" + par)
                .find("serial: missing required key 'range'"),
            std::string::npos);
  EXPECT_NE(error_of("model: hybrid\nserial: {code: \"1\", range: [[-1, 1]]}\n"
                     "parallel: {file: hexapod.yaml}\n")
                .find("parallel: missing required key 'home'"),
            std::string::npos);
  EXPECT_NE(error_of("model: hybrid\nserial: {code: \"1\", range: [[-1, 1]]}\n"
                     "parallel: {file: none.yaml, home: [0, 0, 1]}\n")
                .find("parallel.file: expected an existing machine file"),
            std::string::npos);
  write("inner.yaml", "model: hybrid\nserial: {code: \"1\", range: [[-1, 1]]}\n" + par);
  EXPECT_NE(error_of("model: hybrid\nserial: {code: \"2\", range: [[-1, 1]]}\n"
                     "parallel: {file: inner.yaml, home: [0, 0, 1]}\n")
                .find("parallel.file: expected a parallel machine file"),
            std::string::npos);
  EXPECT_NE(
      error_of("model: hybrid\nserial: {code: \"1\", range: [[-1, 1]], stiffness: [-2]}\n" + par)
          .find("serial.stiffness[0]: expected a number >= 0"),
      std::string::npos);
  EXPECT_NE(
      error_of("model: hybrid\nserial: {code: \"12\", axes: [X, X], range: [[-1, 1], [0, 1]]}\n" +
               par)
          .find("serial.axes: expected distinct axis names"),
      std::string::npos);
  std::filesystem::copy_file(examples_ / "delta.yaml", dir_ / "delta.yaml");
  EXPECT_NE(error_of("model: hybrid\nserial: {code: \"1\", range: [[-1, 1]]}\n"
                     "parallel: {file: delta.yaml, home: [0, 0, -0.9]}\n")
                .find("parallel.file: expected a parallel machine with prismatic actuators"),
            std::string::npos);
  // The CLI exits 2 and names the key.
  const cli_runner::CliRun run =
      run_cli("analyze " +
              write("bad.yaml",
                    "model: hybrid\nserial: {code: \"1\", range: [[-1, 1]], "
                    "error: [1e-6, 2e-6]}\n" +
                        par) +
              " --poses " + write("p.csv", "x,y,z\n0,0,0.9\n"));
  EXPECT_EQ(run.status, 2);
  EXPECT_NE(run.err.find("serial.error: expected a list of 1, found a list of 2"),
            std::string::npos)
      << run.err;
}

}  // namespace
}  // namespace pkmopt
