// Tests of models/hexapod/hexapod: every formula of docs/conventions.md checked independently,
// derivatives against finite differences, IK/FK round trips, equilibrium, published singular cases
// and Dietmaier's 40 real assembly modes.
#include "models/hexapod/hexapod.hpp"

#include <ceres/jet.h>
#include <gtest/gtest.h>
#include <omp.h>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <Eigen/LU>
#include <Eigen/SVD>
#include <cmath>
#include <limits>
#include <numbers>
#include <string>
#include <unsupported/Eigen/AutoDiff>
#include <vector>

#include "tests/hexapod_reference.hpp"
#include "tests/sample_machines.hpp"

namespace pkmopt {
namespace {

using sample_machines::Uniform;

using hexapod_reference::random_wrench;
using hexapod_reference::reference_metrics;
using hexapod_reference::ReferenceMetrics;
// An independent rotation: fixed-axis x, then y, then z.
constexpr auto reference_rotation = hexapod_reference::rotation;

// Leg lengths for an explicit platform rotation R (no Euler angles involved).
Vec6<double> legs_at(const HexapodDesign& d, const Eigen::Vector3d& p, const Eigen::Matrix3d& R) {
  Vec6<double> q;
  for (int i = 0; i < 6; ++i) {
    q(i) = (p + R * (d.platform_joints.col(i) - d.tcp) - d.base_joints.col(i)).norm();
  }
  return q;
}

TEST(Hexapod, InverseKinematicsMatchesDefinition) {
  Uniform u(1);
  for (int g = 0; g < 20; ++g) {
    const HexapodDesign d = sample_machines::random_hexapod_design(u);
    const Hexapod hexapod(d);
    for (int k = 0; k < 10; ++k) {
      const Pose pose = sample_machines::random_pose(u);
      const Vec6<double> expected = legs_at(d, pose.position, reference_rotation(pose.angles));
      const Vec6<double> q = hexapod.inverse_kinematics(pose);
      for (int i = 0; i < 6; ++i) EXPECT_NEAR(q(i), expected(i), 1e-14 * expected(i));
    }
  }
}

// Column j of J is d q / d twist_j: translate the TCP along base axis j (j < 3) or rotate the
// platform about base axis j - 3 through the TCP (R <- exp(h e) R).
TEST(Hexapod, InverseJacobianMatchesFiniteDifferences) {
  Uniform u(2);
  const double h = 1e-6;
  for (int g = 0; g < 20; ++g) {
    const HexapodDesign d = sample_machines::random_hexapod_design(u);
    const Hexapod hexapod(d);
    for (int k = 0; k < 5; ++k) {
      const Pose pose = sample_machines::random_pose(u);
      const Matrix6d J = hexapod.inverse_jacobian(pose);
      // The Machine interface gives the same matrix.
      auto data = hexapod.make_data();
      Eigen::MatrixXd J_machine;
      ASSERT_TRUE(static_cast<const Machine&>(hexapod).twist_jacobian(*data, pose, J_machine));
      EXPECT_EQ((J_machine - J).cwiseAbs().maxCoeff(), 0.0);
      const Eigen::Matrix3d R = rotation_zyx<double>(pose.angles);
      for (int j = 0; j < 6; ++j) {
        Eigen::Vector3d dp = Eigen::Vector3d::Zero(), dw = Eigen::Vector3d::Zero();
        (j < 3 ? dp : dw)(j % 3) = h;
        const Vec6<double> plus = legs_at(d, pose.position + dp, rotation_from_vector(dw) * R);
        const Vec6<double> minus = legs_at(d, pose.position - dp, rotation_from_vector(-dw) * R);
        const Vec6<double> fd = (plus - minus) / (2 * h);
        for (int i = 0; i < 6; ++i) {
          EXPECT_NEAR(J(i, j), fd(i), 1e-8) << "geometry " << g << " column " << j;
        }
      }
    }
  }
}

// The templated core differentiates with ceres::Jet (w.r.t. the pose parameters and the
// geometry) and with Eigen::AutoDiffScalar; both agree with finite differences.
TEST(Hexapod, TemplatedCoreDifferentiatesWithJetAndAutoDiff) {
  Uniform u(3);
  const HexapodDesign d = sample_machines::random_hexapod_design(u);
  const Hexapod hexapod(d);
  const Pose pose = sample_machines::random_pose(u);
  const Eigen::Matrix<double, 3, 6> rel = hexapod.platform_rel_tcp();

  // Jet over the 6 pose parameters plus the x coordinate of base joint 2.
  using Jet = ceres::Jet<double, 7>;
  Eigen::Matrix<Jet, 3, 6> base_j = d.base_joints.cast<Jet>();
  base_j(0, 2).v[6] = 1.0;
  Vec3<Jet> p_j, a_j;
  for (int k = 0; k < 3; ++k) {
    p_j(k) = Jet(pose.position(k), k);
    a_j(k) = Jet(pose.angles(k), 3 + k);
  }
  Vec6<Jet> q_j;
  Mat6<Jet> J_j;
  hexapod_legs<Jet>(base_j, rel.cast<Jet>(), p_j, a_j, &q_j, &J_j);

  using AD = Eigen::AutoDiffScalar<Eigen::Matrix<double, 6, 1>>;
  Vec3<AD> p_ad, a_ad;
  for (int k = 0; k < 3; ++k) {
    p_ad(k) = AD(pose.position(k), 6, k);
    a_ad(k) = AD(pose.angles(k), 6, 3 + k);
  }
  Vec6<AD> q_ad;
  hexapod_legs<AD>(d.base_joints.cast<AD>(), rel.cast<AD>(), p_ad, a_ad, &q_ad);

  const double h = 1e-6;
  auto q_at = [&](const Eigen::Matrix<double, 3, 6>& base, Vec3<double> p, Vec3<double> a) {
    Vec6<double> q;
    hexapod_legs<double>(base, rel, p, a, &q);
    return q;
  };
  for (int j = 0; j < 7; ++j) {
    Eigen::Matrix<double, 3, 6> bp = d.base_joints, bm = d.base_joints;
    Vec3<double> pp = pose.position, pm = pose.position, ap = pose.angles, am = pose.angles;
    if (j < 3) {
      pp(j) += h;
      pm(j) -= h;
    } else if (j < 6) {
      ap(j - 3) += h;
      am(j - 3) -= h;
    } else {
      bp(0, 2) += h;
      bm(0, 2) -= h;
    }
    const Vec6<double> fd = (q_at(bp, pp, ap) - q_at(bm, pm, am)) / (2 * h);
    for (int i = 0; i < 6; ++i) {
      EXPECT_NEAR(q_j(i).v[j], fd(i), 1e-8);
      if (j < 6) {
        EXPECT_NEAR(q_ad(i).derivatives()(j), fd(i), 1e-8);
      }
    }
  }
  // d q / d position is the translational block of J.
  const Matrix6d J = hexapod.inverse_jacobian(pose);
  for (int i = 0; i < 6; ++i) {
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(q_j(i).v[k], J(i, k), 1e-14);
  }
  // Jet also differentiates J itself: d J / d x against finite differences.
  auto J_at = [&](double dx) {
    Pose shifted = pose;
    shifted.position(0) += dx;
    return hexapod.inverse_jacobian(shifted);
  };
  const Matrix6d dJ = (J_at(h) - J_at(-h)) / (2 * h);
  for (int i = 0; i < 6; ++i) {
    for (int k = 0; k < 6; ++k) EXPECT_NEAR(J_j(i, k).v[0], dJ(i, k), 1e-7);
  }
}

TEST(Hexapod, ForwardKinematicsRoundTripFromNearbyGuess) {
  Uniform u(4);
  for (int g = 0; g < 30; ++g) {
    const Hexapod hexapod(sample_machines::random_hexapod_design(u));
    for (int k = 0; k < 10; ++k) {
      const Pose pose = sample_machines::random_pose(u);
      Pose guess = pose;
      guess.position += Eigen::Vector3d(u(-0.03, 0.03), u(-0.03, 0.03), u(-0.03, 0.03));
      guess.angles += deg_to_rad(Eigen::Vector3d(u(-5, 5), u(-5, 5), u(-5, 5)));
      const FkResult r = hexapod.forward_kinematics(hexapod.inverse_kinematics(pose), guess);
      ASSERT_TRUE(r.converged) << r.message;
      EXPECT_LE(r.residual, 1e-12);
      EXPECT_LT((r.pose.position - pose.position).norm(), 1e-10);
      EXPECT_LT((rotation_zyx<double>(r.pose.angles) - rotation_zyx<double>(pose.angles)).norm(),
                1e-10);
      EXPECT_LT((r.pose.angles - pose.angles).norm(), 1e-10);
      EXPECT_LE(r.iterations, 10);
    }
  }
}

TEST(Hexapod, ForwardKinematicsFromDefaultHomeGuess) {
  const Hexapod hexapod(sample_machines::conventions_hexapod_design());
  for (double x : {-0.15, 0.0, 0.15}) {
    for (double z : {0.75, 0.85, 0.95}) {
      for (double tilt : {-15.0, 0.0, 15.0}) {
        const Pose pose{{x, -0.5 * x, z}, deg_to_rad(Eigen::Vector3d(tilt, 0.5 * tilt, 10))};
        const FkResult r = hexapod.forward_kinematics(hexapod.inverse_kinematics(pose), {});
        ASSERT_TRUE(r.converged) << r.message;
        EXPECT_LT((r.pose.position - pose.position).norm(), 1e-10);
        EXPECT_LT((r.pose.angles - pose.angles).norm(), 1e-10);
      }
    }
  }
}

TEST(Hexapod, ForwardKinematicsReportsImpossibleLengthsWithoutNan) {
  const Hexapod hexapod(sample_machines::conventions_hexapod_design());
  // Every base joint is >= 0.35 m from every platform joint's circle: 1 cm legs cannot close.
  const FkResult r = hexapod.forward_kinematics(Vec6<double>::Constant(0.01), {});
  EXPECT_FALSE(r.converged);
  EXPECT_FALSE(r.message.empty());
  EXPECT_TRUE(r.pose.position.allFinite());
  EXPECT_TRUE(r.pose.angles.allFinite());
  EXPECT_FALSE(std::isnan(r.residual));
  EXPECT_LE(r.iterations, FkOptions{}.max_iterations);
  // Bad input is a reported failure as well.
  Eigen::VectorXd bad = Vec6<double>::Constant(1.0);
  bad(3) = std::nan("");
  EXPECT_FALSE(hexapod.forward_kinematics(bad, {}).converged);
  EXPECT_FALSE(hexapod.forward_kinematics(Eigen::VectorXd::Ones(5), {}).converged);
}

// Dietmaier (1998) showed a general Gough-Stewart platform with 40 real assembly modes for one
// set of leg lengths. Multi-start FK must find exactly 40 distinct real postures.
TEST(Hexapod, DietmaierPlatformHasFortyRealAssemblyModes) {
  const Hexapod hexapod(sample_machines::dietmaier_design());
  const Vec6<double> q = sample_machines::dietmaier_legs();
  Uniform u(5);
  std::vector<Eigen::Matrix<double, 12, 1>> solutions;
  for (int start = 0; start < 20000; ++start) {
    Pose guess;
    guess.position = {u(-2, 2), u(-2, 2), u(-2, 2)};
    guess.angles = {u(-M_PI, M_PI), u(-M_PI / 2, M_PI / 2), u(-M_PI, M_PI)};
    const FkResult r = hexapod.forward_kinematics(q, guess);
    if (!r.converged) continue;
    const Eigen::Matrix3d R = rotation_zyx<double>(r.pose.angles);
    ASSERT_LT((legs_at(hexapod.design(), r.pose.position, R) - q).cwiseAbs().maxCoeff(), 1e-11);
    Eigen::Matrix<double, 12, 1> key;
    key << r.pose.position, Eigen::Map<const Eigen::Matrix<double, 9, 1>>(R.data());
    bool known = false;
    for (const auto& s : solutions) known = known || (s - key).norm() < 1e-6;
    if (!known) solutions.push_back(key);
  }
  EXPECT_EQ(solutions.size(), 40u);
}

TEST(Hexapod, LegForcesBalanceTheWrench) {
  Uniform u(6);
  for (int g = 0; g < 20; ++g) {
    const Hexapod hexapod(sample_machines::random_hexapod_design(u));
    HexapodData data(hexapod);
    PoseMetrics m;
    for (int k = 0; k < 5; ++k) {
      const Pose pose = sample_machines::random_pose(u);
      Wrench w;
      for (int i = 0; i < 6; ++i) w(i) = u(-1000, 1000);
      hexapod.analyze(data, pose, w, m);
      ASSERT_FALSE(m.singular);
      // Independent statics: sum of leg forces along s_i, and their moments about the TCP.
      const Eigen::Matrix3d R = reference_rotation(pose.angles);
      Eigen::Vector3d force = Eigen::Vector3d::Zero(), moment = Eigen::Vector3d::Zero();
      for (int i = 0; i < 6; ++i) {
        const Eigen::Vector3d r =
            R * (hexapod.design().platform_joints.col(i) - hexapod.design().tcp);
        const Eigen::Vector3d l = pose.position + r - hexapod.design().base_joints.col(i);
        const Eigen::Vector3d s = l.normalized();
        force += m.tau(i) * s;
        moment += r.cross(m.tau(i) * s);
      }
      EXPECT_LT((force - w.head<3>()).norm(), 1e-9 * (1 + w.norm()));
      EXPECT_LT((moment - w.tail<3>()).norm(), 1e-9 * (1 + w.norm()));
    }
  }
}

TEST(Hexapod, DownwardLoadCompressesTheLegs) {
  const Hexapod hexapod(sample_machines::conventions_hexapod_design());
  HexapodData data(hexapod);
  PoseMetrics m;
  hexapod.analyze(data, Pose{{0, 0, 0.9}, {0, 0, 0}}, (Wrench() << 0, 0, -1000, 0, 0, 0).finished(),
                  m);
  // Symmetric pose: each leg carries 1000 N / (6 cos beta), cos beta = vertical / length.
  const Vec6<double> q = m.q;
  const double vertical = 1.0;  // TCP at 0.9, platform joints 0.10 above it, base at 0
  for (int i = 0; i < 6; ++i) EXPECT_NEAR(m.tau(i), -1000.0 / (6.0 * vertical / q(i)), 1e-9);
}

TEST(Hexapod, LegStiffnessFormula) {
  HexapodDesign d = sample_machines::conventions_hexapod_design();
  const Hexapod series(d);
  EXPECT_DOUBLE_EQ(series.leg_stiffness(1.0), 1.0 / (1.0 / (2.1e11 * 3e-4) + 1.0 / 2e8));
  d.stiffness.actuator_stiffness = 0;
  EXPECT_DOUBLE_EQ(Hexapod(d).leg_stiffness(0.9), 2.1e11 * 3e-4 / 0.9);
  d.stiffness = LegStiffness{};
  d.stiffness.axial_stiffness = 5e7;
  EXPECT_DOUBLE_EQ(Hexapod(d).leg_stiffness(0.9), 5e7);
}

// K from virtual work: a small twist stretches each leg by dq (from exact IK), the legs push
// back with -k dq, and the resultant wrench (summed geometrically) is -K dx to first order.
TEST(Hexapod, StiffnessMatrixMatchesLegSpringsUnderSmallDisplacement) {
  Uniform u(7);
  for (int g = 0; g < 10; ++g) {
    const Hexapod hexapod(sample_machines::random_hexapod_design(u));
    const HexapodDesign& d = hexapod.design();
    const Pose pose = sample_machines::random_pose(u);
    const Matrix6d K = hexapod.stiffness_matrix(pose);
    const Eigen::Matrix3d R = rotation_zyx<double>(pose.angles);
    const Vec6<double> q0 = legs_at(d, pose.position, R);
    for (int trial = 0; trial < 3; ++trial) {
      Vec6<double> dx;
      for (int i = 0; i < 6; ++i) dx(i) = u(-1, 1) * 1e-7;
      const Vec6<double> q1 =
          legs_at(d, pose.position + dx.head<3>(), rotation_from_vector(dx.tail<3>()) * R);
      Vec6<double> wrench = Vec6<double>::Zero();
      for (int i = 0; i < 6; ++i) {
        const double k = hexapod.leg_stiffness(q0(i));
        const Eigen::Vector3d r = R * (d.platform_joints.col(i) - d.tcp);
        const Eigen::Vector3d s = (pose.position + r - d.base_joints.col(i)).normalized();
        const double tension = -k * (q1(i) - q0(i));
        wrench.head<3>() += tension * s;
        wrench.tail<3>() += r.cross(tension * s);
      }
      const Vec6<double> expected = -K * dx;
      EXPECT_LT((wrench - expected).norm(), 1e-5 * expected.norm());
    }
  }
}

TEST(Hexapod, StiffnessMinIsWorstDirectionOfComplianceBlock) {
  Uniform u(8);
  for (int g = 0; g < 10; ++g) {
    const Hexapod hexapod(sample_machines::random_hexapod_design(u));
    HexapodData data(hexapod);
    PoseMetrics m;
    const Pose pose = sample_machines::random_pose(u);
    hexapod.analyze(data, pose, Wrench::Zero(), m);
    const Matrix6d K = hexapod.stiffness_matrix(pose);
    const Matrix6d C = K.inverse();
    // K dx = w for the displacement under a random wrench.
    Wrench w;
    for (int i = 0; i < 6; ++i) w(i) = u(-100, 100);
    EXPECT_LT((K * (C * w) - w).norm(), 1e-9 * w.norm());
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(C.topLeftCorner<3, 3>());
    const double expected = 1.0 / eig.eigenvalues()(2);
    EXPECT_NEAR(m.stiffness_min, expected, 1e-9 * expected);
    // A pure force along the worst direction moves the TCP by |f| / stiffness_min; any other
    // direction moves it less.
    const Eigen::Vector3d worst = eig.eigenvectors().col(2);
    Wrench f = Wrench::Zero();
    f.head<3>() = worst;
    EXPECT_NEAR((C * f).head<3>().norm(), 1.0 / m.stiffness_min, 1e-9 / m.stiffness_min);
    for (int t = 0; t < 20; ++t) {
      f.head<3>() = Eigen::Vector3d(u(-1, 1), u(-1, 1), u(-1, 1)).normalized();
      EXPECT_LE((C * f).head<3>().norm(), (1.0 + 1e-12) / m.stiffness_min);
    }
  }
}

TEST(Hexapod, SingularityMarginIsInverseConditionOfScaledJacobian) {
  Uniform u(9);
  for (int g = 0; g < 20; ++g) {
    HexapodDesign d = sample_machines::random_hexapod_design(u);
    if (g % 2) d.characteristic_length = u(0.1, 0.5);
    const Hexapod hexapod(d);
    const double L = d.characteristic_length
                         ? *d.characteristic_length
                         : (d.platform_joints.colwise() - d.tcp).colwise().norm().mean();
    EXPECT_DOUBLE_EQ(hexapod.characteristic_length(), L);
    HexapodData data(hexapod);
    PoseMetrics m;
    const Pose pose = sample_machines::random_pose(u);
    hexapod.analyze(data, pose, Wrench::Zero(), m);
    Matrix6d Jh = hexapod.inverse_jacobian(pose);
    Jh.rightCols<3>() /= L;
    Eigen::JacobiSVD<Matrix6d> svd(Jh);
    const double expected = svd.singularValues()(5) / svd.singularValues()(0);
    EXPECT_NEAR(m.singularity_margin, expected, 1e-12 * expected);
    EXPECT_NEAR(m.det_j, hexapod.inverse_jacobian(pose).determinant(), 1e-12);
  }
}

// Similar semi-regular base and platform hexagons (platform pair separation 120 deg - base
// separation, so platform joint i sits at the azimuth of base joint i) are architecturally
// singular: singular at every pose (Ma & Angeles, "Architecture singularities of platform
// manipulators", ICRA 1991; Karger 2003). The regular case is 60/60.
TEST(Hexapod, SimilarHexagonsAreSingularEverywhere) {
  Uniform u(10);
  for (double base_sep : {60.0, 20.0, 45.0}) {
    HexapodDesign d =
        semi_regular_hexapod(0.6, deg_to_rad(base_sep), 0.3, deg_to_rad(120.0 - base_sep));
    d.min_length = 0.2;
    d.max_length = 2.0;
    d.stiffness.axial_stiffness = 1e8;
    const Hexapod hexapod(d);
    HexapodData data(hexapod);
    PoseMetrics m;
    for (int k = 0; k < 20; ++k) {
      const Pose pose = sample_machines::random_pose(u);
      hexapod.analyze(data, pose, Wrench::Constant(10.0), m);
      EXPECT_TRUE(m.singular);
      EXPECT_EQ(m.singularity_margin, 0.0);
      EXPECT_EQ(m.stiffness_min, 0.0);
      EXPECT_TRUE(std::isinf(m.tcp_error_max));
      for (int i = 0; i < 6; ++i) EXPECT_TRUE(std::isinf(m.tau(i)));
      EXPECT_FALSE(std::isnan(m.det_j));
      EXPECT_LT(std::abs(m.det_j), 1e-12);
    }
  }
}

// Fichter (1986, "A Stewart platform-based manipulator: general theory and practical
// construction", IJRR 5(2)): a semi-regular hexapod at its central position is singular when
// the platform is turned 90 deg about the vertical axis; det J changes sign there.
TEST(Hexapod, FichterYawSingularityAtNinetyDegrees) {
  HexapodDesign d = semi_regular_hexapod(0.6, deg_to_rad(20), 0.3, deg_to_rad(20));
  d.min_length = 0.2;
  d.max_length = 2.0;
  d.stiffness.axial_stiffness = 1e8;
  const Hexapod hexapod(d);
  HexapodData data(hexapod);
  PoseMetrics below, at, above;
  for (double z : {0.5, 0.8, 1.2}) {
    for (double yaw : {90.0, -90.0}) {
      hexapod.analyze(data, Pose{{0, 0, z}, {0, 0, deg_to_rad(yaw - 1)}}, Wrench::Zero(), below);
      hexapod.analyze(data, Pose{{0, 0, z}, {0, 0, deg_to_rad(yaw)}}, Wrench::Zero(), at);
      hexapod.analyze(data, Pose{{0, 0, z}, {0, 0, deg_to_rad(yaw + 1)}}, Wrench::Zero(), above);
      EXPECT_LT(below.det_j * above.det_j, 0.0) << "z " << z << " yaw " << yaw;
      EXPECT_EQ(at.singularity_margin, 0.0);
      EXPECT_GT(below.singularity_margin, 1e-3);
      EXPECT_GT(above.singularity_margin, 1e-3);
    }
  }
}

TEST(Hexapod, TcpErrorMaxIsTheMaximumOverTheErrorBox) {
  Uniform u(11);
  for (int g = 0; g < 10; ++g) {
    const Hexapod hexapod(sample_machines::random_hexapod_design(u));
    const double eps = hexapod.design().actuator_error;
    HexapodData data(hexapod);
    PoseMetrics m;
    const Pose pose = sample_machines::random_pose(u);
    hexapod.analyze(data, pose, Wrench::Zero(), m);
    const Matrix6d Jinv = hexapod.inverse_jacobian(pose).inverse();
    double brute = 0.0;
    for (int mask = 0; mask < 64; ++mask) {
      Vec6<double> dq;
      for (int i = 0; i < 6; ++i) dq(i) = (mask >> i & 1) ? eps : -eps;
      brute = std::max(brute, (Jinv * dq).head<3>().norm());
    }
    EXPECT_NEAR(m.tcp_error_max, brute, 1e-12 * brute);
    for (int t = 0; t < 100; ++t) {
      Vec6<double> dq;
      for (int i = 0; i < 6; ++i) dq(i) = u(-eps, eps);
      EXPECT_LE((Jinv * dq).head<3>().norm(), m.tcp_error_max * (1 + 1e-12));
    }
  }
}

TEST(Hexapod, ReachabilityFollowsStrokeAndJointLimits) {
  HexapodDesign d = sample_machines::conventions_hexapod_design();
  d.joints.base_axis = Eigen::Vector3d(0.1, 0, 1).normalized();
  const Hexapod hexapod(d);
  HexapodData data(hexapod);
  PoseMetrics m;
  Uniform u(12);
  int reachable = 0, unreachable = 0;
  for (int k = 0; k < 2000; ++k) {
    const Pose pose{{u(-0.3, 0.3), u(-0.3, 0.3), u(0.6, 1.2)},
                    deg_to_rad(Eigen::Vector3d(u(-25, 25), u(-25, 25), u(-40, 40)))};
    hexapod.analyze(data, pose, Wrench::Zero(), m);
    const Eigen::Matrix3d R = reference_rotation(pose.angles);
    bool expected = true;
    for (int i = 0; i < 6; ++i) {
      const Eigen::Vector3d l =
          pose.position + R * (d.platform_joints.col(i) - d.tcp) - d.base_joints.col(i);
      const Eigen::Vector3d s = l.normalized();
      const double base_angle =
          std::acos(std::clamp(s.dot(d.joints.base_axis.normalized()), -1.0, 1.0));
      const double platform_angle =
          std::acos(std::clamp(-s.dot(R * d.joints.platform_axis), -1.0, 1.0));
      expected = expected && l.norm() >= d.min_length && l.norm() <= d.max_length &&
                 base_angle <= d.joints.base_max_angle &&
                 platform_angle <= d.joints.platform_max_angle;
    }
    EXPECT_EQ(m.reachable, expected) << "pose " << k;
    EXPECT_EQ(hexapod.reachable(data, pose), expected);
    (expected ? reachable : unreachable)++;
  }
  EXPECT_GT(reachable, 100);
  EXPECT_GT(unreachable, 100);
  Vec6<double> base_angles, platform_angles;
  hexapod.joint_angles(Pose{{0, 0, 0.9}, {0, 0, 0}}, base_angles, platform_angles);
  EXPECT_GT(base_angles.minCoeff(), 0.0);
  EXPECT_LT(platform_angles.maxCoeff(), deg_to_rad(45));
}

TEST(Hexapod, ConstructorRejectsImpossibleDesigns) {
  const HexapodDesign good = sample_machines::conventions_hexapod_design();
  EXPECT_NO_THROW(Hexapod{good});
  auto expect_rejected = [](HexapodDesign d) { EXPECT_THROW(Hexapod{d}, std::invalid_argument); };
  HexapodDesign d = good;
  d.max_length = d.min_length;
  expect_rejected(d);
  d = good;
  d.min_length = -0.1;
  expect_rejected(d);
  d = good;
  d.stiffness.E = -1;
  expect_rejected(d);
  d = good;
  d.stiffness = LegStiffness{};
  expect_rejected(d);
  d = good;
  d.base_joints(1, 3) = std::nan("");
  expect_rejected(d);
  d = good;
  d.characteristic_length = 0.0;
  expect_rejected(d);
  d = good;
  d.actuator_error = std::numeric_limits<double>::infinity();
  expect_rejected(d);
}

TEST(Hexapod, ParallelBatchEqualsSerial) {
  const Hexapod hexapod(sample_machines::conventions_hexapod_design());
  Uniform u(13);
  std::vector<Pose> poses(2000);
  for (auto& p : poses) {
    p = Pose{{u(-0.2, 0.2), u(-0.2, 0.2), u(0.7, 1.0)},
             deg_to_rad(Eigen::Vector3d(u(-20, 20), u(-20, 20), u(-20, 20)))};
  }
  const Wrench w = Wrench::Constant(50.0);
  std::vector<PoseMetrics> serial(poses.size()), parallel(poses.size());
  HexapodData data(hexapod);
  for (std::size_t i = 0; i < poses.size(); ++i) hexapod.analyze(data, poses[i], w, serial[i]);
#pragma omp parallel num_threads(2)
  {
    HexapodData local(hexapod);
#pragma omp for
    for (std::size_t i = 0; i < poses.size(); ++i) hexapod.analyze(local, poses[i], w, parallel[i]);
  }
  for (std::size_t i = 0; i < poses.size(); ++i) {
    EXPECT_EQ(serial[i].q, parallel[i].q);
    EXPECT_EQ(serial[i].tau, parallel[i].tau);
    EXPECT_EQ(serial[i].stiffness_min, parallel[i].stiffness_min);
    EXPECT_EQ(serial[i].singularity_margin, parallel[i].singularity_margin);
    EXPECT_EQ(serial[i].tcp_error_max, parallel[i].tcp_error_max);
  }
}

// ---- Regression harness of the fast metric path ------------------------------------------------
// Compares analyze with the plain reference of tests/hexapod_reference.hpp (Eigen's general
// solvers; 1e-10 relative, or 64 eps cond(J)); returns 1 when the pose was checked as
// non-singular.
int expect_matches_reference(const Hexapod& hexapod, const Pose& pose, const Wrench& w,
                             const std::string& where) {
  HexapodData data(hexapod);
  PoseMetrics m;
  hexapod.analyze(data, pose, w, m);
  return hexapod_reference::expect_metrics_match_reference(m, reference_metrics(hexapod, pose, w),
                                                           where);
}

TEST(HexapodFastPath, MatchesReferenceOnRandomGeometriesAndPoses) {
  Uniform u(21);
  int checked = 0;
  for (int g = 0; g < 300; ++g) {
    const Hexapod hexapod(sample_machines::random_hexapod_design(u));
    for (int k = 0; k < 10; ++k) {
      checked += expect_matches_reference(hexapod, sample_machines::random_pose(u),
                                          random_wrench(u), "geometry " + std::to_string(g));
    }
  }
  EXPECT_GT(checked, 2900);
}

// Symmetric poses of semi-regular designs (repeated eigenvalues of J_h J_h^T and of C_tt).
TEST(HexapodFastPath, MatchesReferenceAtSymmetricPoses) {
  Uniform u(22);
  for (int g = 0; g < 100; ++g) {
    HexapodDesign d =
        semi_regular_hexapod(u(0.4, 0.9), deg_to_rad(u(5, 50)), u(0.15, 0.4), deg_to_rad(u(5, 50)));
    d.min_length = 0.3;
    d.max_length = 2.0;
    d.stiffness.axial_stiffness = u(1e7, 1e8);
    if (g % 2) d.tcp = {0, 0, u(-0.2, 0.0)};
    if (g % 3 == 0) d.characteristic_length = u(0.1, 0.6);
    const Hexapod hexapod(d);
    for (int k = 0; k < 10; ++k) {
      // Centre poses with a yaw that is a multiple of 60 deg keep the 3-fold symmetry.
      const Pose pose{{0, 0, u(0.5, 1.2)}, {0, 0, deg_to_rad(60.0 * (k % 3))}};
      expect_matches_reference(hexapod, pose, random_wrench(u), "geometry " + std::to_string(g));
    }
  }
}

// Near-singular poses: similar hexagons (architecturally singular) with their joints moved by
// 1e-9 .. 1e-2 m, and Fichter's yaw singularity approached to 1e-10 .. 1e-2 rad.
TEST(HexapodFastPath, MatchesReferenceNearSingularities) {
  Uniform u(23);
  int near_singular = 0;
  for (int g = 0; g < 200; ++g) {
    const Hexapod hexapod(hexapod_reference::near_similar_hexapod(u, g % 2 == 1));
    for (int k = 0; k < 5; ++k) {
      const Pose pose = sample_machines::random_pose(u);
      if (reference_metrics(hexapod, pose, Wrench::Zero()).rcond < 1e-4) ++near_singular;
      expect_matches_reference(hexapod, pose, random_wrench(u), "similar " + std::to_string(g));
    }
  }
  for (int g = 0; g < 200; ++g) {
    HexapodDesign d =
        semi_regular_hexapod(u(0.4, 0.9), deg_to_rad(u(5, 50)), u(0.15, 0.4), deg_to_rad(u(5, 50)));
    d.min_length = 0.2;
    d.max_length = 2.0;
    d.stiffness.axial_stiffness = 1e8;
    const Hexapod hexapod(d);
    const double offset = (g % 2 ? 1.0 : -1.0) * std::pow(10.0, u(-10, -2));
    const Pose pose{{0, 0, u(0.5, 1.2)}, {0, 0, deg_to_rad(g % 4 < 2 ? 90.0 : -90.0) + offset}};
    if (reference_metrics(hexapod, pose, Wrench::Zero()).rcond < 1e-4) ++near_singular;
    expect_matches_reference(hexapod, pose, random_wrench(u), "fichter " + std::to_string(g));
  }
  EXPECT_GT(near_singular, 300);
}

// ---------------------------------------------------------------------------------------------
// The compliance chain, the compliance, the deflection under the wrench and the loaded stiffness.

TEST(HexapodCompliance, ChainElementsAddInSeries) {
  HexapodDesign d = sample_machines::conventions_hexapod_design();
  const double q = 0.9;
  const double before = 1.0 / Hexapod(d).leg_stiffness(q);
  d.stiffness.drive = ScrewDrive{.E = 2.1e11,
                                 .root_diameter = 0.025,
                                 .free_length_at_min = 0.1,
                                 .free_length_at_max = 0.55,
                                 .nut_stiffness = 6e8,
                                 .bearing_stiffness = 9e8,
                                 .torsional_stiffness = 3000,
                                 .lead = 0.01};
  d.stiffness.base_joint_stiffness = 4e8;
  d.stiffness.platform_joint_stiffness = 5e8;
  // Hand sum: q = 0.9 of [0.7, 1.15] puts the nut at 0.1 + 0.45 * 0.2 / 0.45 = 0.3 m.
  const double screw = 0.3 / (2.1e11 * std::numbers::pi * 0.025 * 0.025 / 4);
  const double torsion = std::pow(0.01 / (2 * std::numbers::pi), 2) / 3000;
  const double expected = before + screw + 1 / 6e8 + 1 / 9e8 + torsion + 1 / 4e8 + 1 / 5e8;
  EXPECT_NEAR(1.0 / Hexapod(d).leg_stiffness(q), expected, 1e-14);
  // A leg of drive and joints only (no strut term) is allowed; nothing at all is not.
  d.stiffness.E = d.stiffness.area = d.stiffness.actuator_stiffness = 0.0;
  EXPECT_NO_THROW(Hexapod{d});
  d.stiffness = LegStiffness{};
  EXPECT_THROW(Hexapod{d}, std::invalid_argument);
}

// The twist displacement dx = [dp; dtheta] applied to a pose (rotation exp([dtheta]x) R).
Pose displaced(const Pose& pose, const Vec6<double>& dx) {
  const Eigen::Matrix3d R = rotation_from_vector(dx.tail<3>()) * rotation_zyx<double>(pose.angles);
  return Pose{pose.position + dx.head<3>(), angles_from_rotation(R)};
}

TEST(HexapodCompliance, ComplianceIsTheInverseOfTheStiffnessAndGivesTheDeflection) {
  Uniform u(31);
  for (int g = 0; g < 10; ++g) {
    const Hexapod hexapod(sample_machines::random_hexapod_design(u));
    const Pose pose = sample_machines::random_pose(u);
    const Wrench w = random_wrench(u);
    HexapodData data(hexapod);
    PoseMetrics m;
    hexapod.analyze(data, pose, w, m);
    if (m.singular) continue;
    const Matrix6d K = hexapod.stiffness_matrix(pose);
    EXPECT_LT((data.matrices.compliance * K - Matrix6d::Identity()).norm(), 1e-8);
    const Vec6<double> dx = K.lu().solve(w);
    EXPECT_NEAR(m.tcp_deflection, dx.head<3>().norm(), 1e-9 * dx.head<3>().norm());
    EXPECT_NEAR(m.tcp_rotation_deflection, dx.tail<3>().norm(), 1e-9 * dx.tail<3>().norm());
    // The worst direction: the force along it gives exactly 1/stiffness_min of displacement
    // along it.
    const Eigen::Vector3d v = m.stiffness_min_direction;
    EXPECT_NEAR(v.dot(data.matrices.compliance.topLeftCorner<3, 3>() * v), 1.0 / m.stiffness_min,
                1e-9 / m.stiffness_min);
  }
}

// The wrench the legs need from outside at a displaced pose when each leg's tension changes by
// k_i (q_i - q_i0) from tau0 (the leg springs), J(x)^T tau(x).
Wrench spring_wrench(const Hexapod& hexapod, const Pose& pose, const Vec6<double>& tau0,
                     const Vec6<double>& q0, const Vec6<double>& dx) {
  const Pose moved = displaced(pose, dx);
  const Vec6<double> q = hexapod.inverse_kinematics(moved);
  Vec6<double> tau;
  for (int i = 0; i < 6; ++i) tau(i) = tau0(i) + hexapod.leg_stiffness(q0(i)) * (q(i) - q0(i));
  return hexapod.inverse_jacobian(moved).transpose() * tau;
}

TEST(HexapodCompliance, LoadedStiffnessMatchesFiniteDifferencesOfTheLoadedEquilibrium) {
  Uniform u(32);
  int checked = 0;
  for (int g = 0; g < 12; ++g) {
    const Hexapod hexapod(sample_machines::random_hexapod_design(u));
    const Pose pose = sample_machines::random_pose(u);
    // A heavy wrench, so that the geometric term shows: 50 kN and 5 kN m.
    Wrench w = random_wrench(u);
    w.head<3>() *= 5e4 / w.head<3>().norm();
    w.tail<3>() *= 5e3 / w.tail<3>().norm();
    HexapodData data(hexapod);
    PoseMetrics m;
    hexapod.analyze(data, pose, w, m);
    if (m.singular || m.singularity_margin < 1e-3) continue;
    const Vec6<double> q0 = hexapod.inverse_kinematics(pose);
    Matrix6d KT;
    const double h = 1e-7;
    for (int j = 0; j < 6; ++j) {
      Vec6<double> dx = Vec6<double>::Zero();
      dx(j) = h;
      KT.col(j) = (spring_wrench(hexapod, pose, m.tau, q0, dx) -
                   spring_wrench(hexapod, pose, m.tau, q0, -dx)) /
                  (2 * h);
    }
    // The finite-difference tangent reduces to the unloaded stiffness without load ...
    const Matrix6d K = hexapod.stiffness_matrix(pose);
    EXPECT_GT((KT - K).norm(), 1e-6 * K.norm()) << "the load must change the stiffness";
    // ... and gives the loaded metric by its definition: 1 / sigma_max of (K_T^-1)_tt.
    const Eigen::Matrix3d CTtt = KT.inverse().topLeftCorner<3, 3>();
    const double expected = 1.0 / Eigen::JacobiSVD<Eigen::Matrix3d>(CTtt).singularValues()(0);
    EXPECT_NEAR(m.stiffness_min_loaded, expected, 1e-5 * expected);
    ++checked;
  }
  EXPECT_GE(checked, 6);
}

TEST(HexapodCompliance, LoadedEqualsUnloadedWithoutLoadAndFallsUnderCompression) {
  const Hexapod hexapod(sample_machines::conventions_hexapod_design());
  const Pose pose{{0, 0, 0.9}, {0, 0, 0}};
  HexapodData data(hexapod);
  PoseMetrics free, pressed;
  hexapod.analyze(data, pose, Wrench::Zero(), free);
  EXPECT_NEAR(free.stiffness_min_loaded, free.stiffness_min, 1e-9 * free.stiffness_min);
  EXPECT_EQ(free.tcp_deflection, 0.0);
  // A downward force compresses every leg (tau < 0): compressed legs lose lateral stiffness
  // (the geometric term -|tau| Pi / q), so the loaded stiffness is the lower one.
  Wrench down = Wrench::Zero();
  down(2) = -2e5;
  hexapod.analyze(data, pose, down, pressed);
  ASSERT_TRUE((pressed.tau.array() < 0).all());
  EXPECT_LT(pressed.stiffness_min_loaded, pressed.stiffness_min);
}

TEST(HexapodCompliance, DeflectionIsTheDisplacementOfTheLoadedEquilibriumFoundByTheFk) {
  // The legs stretch by tau_i / k_i under the wrench; the FK of the stretched lengths is the
  // loaded pose. For a small wrench its displacement is C w to first order.
  Uniform u(33);
  for (int g = 0; g < 6; ++g) {
    const Hexapod hexapod(sample_machines::random_hexapod_design(u));
    const Pose pose = sample_machines::random_pose(u);
    Wrench w = random_wrench(u);
    w *= 10.0 / w.head<3>().norm();  // 10 N: deflections of micrometres
    HexapodData data(hexapod);
    PoseMetrics m;
    hexapod.analyze(data, pose, w, m);
    if (m.singular || m.singularity_margin < 1e-2) continue;
    const Vec6<double> q0 = hexapod.inverse_kinematics(pose);
    Pose loaded = pose;
    for (int iteration = 0; iteration < 20; ++iteration) {
      // Equilibrium at the loaded pose: tau = J(x)^-T w, legs at q0 + tau / k.
      const Vec6<double> tau =
          hexapod.inverse_jacobian(loaded).transpose().fullPivLu().solve(Vec6<double>(w));
      Eigen::VectorXd q(6);
      for (int i = 0; i < 6; ++i) q(i) = q0(i) + tau(i) / hexapod.leg_stiffness(q0(i));
      const FkResult fk = hexapod.forward_kinematics(q, loaded, FkOptions{.tolerance = 1e-15});
      ASSERT_TRUE(fk.converged) << fk.message;
      loaded = fk.pose;
    }
    const double moved = (loaded.position - pose.position).norm();
    EXPECT_NEAR(m.tcp_deflection, moved, 1e-4 * moved) << "design " << g;
  }
}

// Published case: the cubic (orthogonal) Gough-Stewart platform of Geng & Haynes, "Six
// degree-of-freedom active vibration control using the Stewart platforms", IEEE Trans. Control
// Systems Technology 2(1), 1994, and Preumont et al., "A six-axis single-stage active vibration
// isolator based on Stewart platform", J. Sound and Vibration 300, 2007: with the legs along the
// edges of a cube whose main diagonal is vertical, K = k diag(2, 2, 2, 1.5 Hc^2, 1.5 Hc^2, 6 Hc^2)
// at the cube's centre (Hc the height of the legs' span). The numbers of T. Dehaeze's
// stewart-simscape tables (org/cubic-configuration.org, Hc = 100 mm, k = 1 N/m): diag 2, 2, 2,
// 0.015, 0.015, 0.06 at the centre; with the TCP 70 mm above it K15 = -0.14, K24 = 0.14 and
// K44 = K55 = 0.025 (printed to two digits).
TEST(HexapodCompliance, CubicConfigurationHasThePublishedStiffness) {
  const double Hc = 0.1;
  for (const double d : {0.0, 0.07}) {
    HexapodDesign design =
        sample_machines::cubic_hexapod_design(Hc, 1.0);  // k = 1 N/m, as in the tables
    design.tcp = Eigen::Vector3d(0, 0, d);
    const Hexapod hexapod(design);
    const Matrix6d K = hexapod.stiffness_matrix(Pose{{0, 0, d}, {0, 0, 0}});
    Matrix6d expected = Matrix6d::Zero();
    expected.diagonal() << 2, 2, 2, 1.5 * Hc * Hc + 2 * d * d, 1.5 * Hc * Hc + 2 * d * d,
        6 * Hc * Hc;
    expected(0, 4) = expected(4, 0) = -2 * d;
    expected(1, 3) = expected(3, 1) = 2 * d;
    EXPECT_LT((K - expected).norm(), 1e-12) << K;
    if (d == 0.0) {
      EXPECT_NEAR(K(3, 3), 0.015, 5e-4);
      EXPECT_NEAR(K(5, 5), 0.06, 5e-3);
    } else {
      EXPECT_NEAR(K(0, 4), -0.14, 5e-3);
      EXPECT_NEAR(K(1, 3), 0.14, 5e-3);
      EXPECT_NEAR(K(3, 3), 0.025, 5e-4);
    }
    // Uniform translational stiffness 2k at the centre: stiffness_min = 2 N/m.
    HexapodData data(hexapod);
    PoseMetrics m;
    hexapod.analyze(data, Pose{{0, 0, d}, {0, 0, 0}}, Wrench::Zero(), m);
    if (d == 0.0) {
      EXPECT_NEAR(m.stiffness_min, 2.0, 1e-12);
    }
  }
}

// The hexapod offers its SIMD kernel as a capability: the batch gives what analyze gives.
TEST(HexapodCapabilities, BatchAnalysisGivesWhatAnalyzeGives) {
  const Hexapod hexapod(sample_machines::conventions_hexapod_design());
  const BatchAnalysis* batch = hexapod.batch_analysis();
  ASSERT_NE(batch, nullptr);
  EXPECT_EQ(hexapod.parasitic_motion(), nullptr);
  const std::vector<Pose> poses = {Pose{{0.0, 0.0, 0.9}, {0, 0, 0}},
                                   Pose{{0.05, -0.03, 0.95}, {0.1, -0.05, 0.2}}};
  const Wrench w = (Wrench() << 100, 200, -3000, 10, -20, 5).finished();
  std::vector<PoseMetrics> metrics(poses.size());
  batch->analyze_batch(poses.data(), poses.size(), w, metrics.data(), nullptr);
  auto data = hexapod.make_data();
  for (std::size_t k = 0; k < poses.size(); ++k) {
    PoseMetrics m;
    hexapod.analyze(*data, poses[k], w, m);
    EXPECT_EQ(metrics[k].reachable, m.reachable);
    EXPECT_LT((metrics[k].q - m.q).norm(), 1e-12);
    EXPECT_LT((metrics[k].tau - m.tau).norm(), 1e-9 * m.tau.norm());
    EXPECT_NEAR(metrics[k].stiffness_min / m.stiffness_min, 1.0, 1e-10);
  }
}

// The hexapod's dynamics is a capability it has with masses: missing, with the reason a command
// prints, without them; present, the machine's own mass model, with them. The static inverse
// dynamics is analyze under the wrench plus the gravity and inertia wrench.
TEST(HexapodCapabilities, DynamicsWithMassesOnlyAndSaysWhyNot) {
  const Hexapod bare(sample_machines::conventions_hexapod_design());
  const Capability<Dynamics> none = bare.dynamics();
  EXPECT_FALSE(none);
  EXPECT_EQ(none.get(), nullptr);
  EXPECT_EQ(none.reason(), "the machine file has no 'masses'");
  EXPECT_NE(bare.translational_maps(), nullptr);

  sample_machines::Uniform u(7);
  HexapodDesign design = sample_machines::conventions_hexapod_design();
  design.masses = sample_machines::random_hexapod_masses(u);
  const Hexapod heavy(design);
  const Capability<Dynamics> dynamics = heavy.dynamics();
  ASSERT_TRUE(dynamics);
  EXPECT_EQ(dynamics.reason(), "");
  EXPECT_EQ(&dynamics->mass_model(), &heavy.design().masses);
  EXPECT_EQ(dynamics->natural_frequency_count(), 6);
  EXPECT_EQ(dynamics->mode_axis_count(), 0);
  const Pose pose{{0.02, -0.01, 0.9}, deg_to_rad(Eigen::Vector3d(3, -2, 5))};
  Vector6d xi, xi_dot;
  xi << 0.1, -0.2, 0.05, 0.3, 0.1, -0.2;
  xi_dot << 1.0, 0.5, -2.0, 0.4, -0.3, 0.8;
  const Wrench w = (Wrench() << 100, -50, -800, 5, 0, -10).finished();
  auto data = heavy.make_data();
  Wrench w_dyn;
  ASSERT_TRUE(dynamics->dynamic_wrench(*data, pose, xi, xi_dot, w_dyn));
  PoseMetrics expected, found;
  heavy.analyze(*data, pose, w + w_dyn, expected);
  ASSERT_TRUE(dynamics->inverse_dynamics(*data, pose, xi, xi_dot, w, found));
  EXPECT_EQ(found.tau, expected.tau);
}

// A MachineData remembers the machine that made it: another machine's data, or one made outside
// make_data(), is refused with a message instead of being read as the wrong type.
TEST(HexapodCapabilities, RefusesAnotherMachinesData) {
  const Hexapod hexapod(sample_machines::conventions_hexapod_design());
  const Hexapod other(sample_machines::conventions_hexapod_design());
  const Pose pose{{0.0, 0.0, 0.9}, {0, 0, 0}};
  PoseMetrics m;
  auto own = hexapod.make_data();
  EXPECT_EQ(own->made_by(), &hexapod);
  EXPECT_NO_THROW(hexapod.analyze(*own, pose, Wrench::Zero(), m));
  auto foreign = other.make_data();
  EXPECT_THROW(hexapod.analyze(*foreign, pose, Wrench::Zero(), m), std::invalid_argument);
  MachineData bare;
  EXPECT_THROW(hexapod.analyze(bare, pose, Wrench::Zero(), m), std::invalid_argument);
  HexapodData constructed(hexapod);  // what make_data() makes
  EXPECT_NO_THROW(hexapod.analyze(constructed, pose, Wrench::Zero(), m));
}

}  // namespace
}  // namespace pkmopt
