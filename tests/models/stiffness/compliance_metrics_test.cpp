// Tests of models/stiffness/compliance_metrics: the geometric stiffness of a leg force and of a
// constraint force against finite differences of their wrenches, the deflection and worst
// direction, and the loaded stiffness's definition (unloaded limit, instability).
#include "models/stiffness/compliance_metrics.hpp"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <Eigen/LU>
#include <cmath>
#include <random>

namespace pkmopt {
namespace {

Eigen::Vector3d random_vector(std::mt19937& rng, double scale) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  return scale * Eigen::Vector3d(u(rng), u(rng), u(rng));
}

// The wrench f [s; r x s] a leg from the fixed point a needs at the platform point p + r, after a
// small platform displacement [dp; dtheta] (r turned by exp([dtheta]x)).
Vec6<double> leg_wrench(double f, const Eigen::Vector3d& a, const Eigen::Vector3d& p,
                        const Eigen::Vector3d& r, const Vec6<double>& dx) {
  const Eigen::Vector3d r1 = rotation_from_vector(dx.tail<3>()) * r;
  const Eigen::Vector3d s = (p + dx.head<3>() + r1 - a).normalized();
  Vec6<double> w;
  w << f * s, f * r1.cross(s);
  return w;
}

TEST(GeometricStiffness, MatchesFiniteDifferencesOfTheLegWrench) {
  std::mt19937 rng(11);
  for (int trial = 0; trial < 20; ++trial) {
    const Eigen::Vector3d a = random_vector(rng, 0.6),
                          p = random_vector(rng, 0.3) + Eigen::Vector3d(0, 0, 0.9);
    const Eigen::Vector3d r = random_vector(rng, 0.25);
    const double f = 1000.0 * (trial % 2 == 0 ? 1.0 : -2.5);
    const Eigen::Vector3d l = p + r - a;
    const Matrix6d K = geometric_stiffness(f, l.normalized(), r, l.norm());
    const double h = 1e-6;
    for (int j = 0; j < 6; ++j) {
      Vec6<double> dx = Vec6<double>::Zero();
      dx(j) = h;
      const Vec6<double> fd = (leg_wrench(f, a, p, r, dx) - leg_wrench(f, a, p, r, -dx)) / (2 * h);
      EXPECT_LT((fd - K.col(j)).norm(), 1e-6 * (1.0 + K.col(j).norm())) << "column " << j;
    }
  }
}

TEST(GeometricStiffness, ConstraintForceOfFixedDirectionTurnsOnlyItsLeverArm) {
  std::mt19937 rng(12);
  const Eigen::Vector3d n = random_vector(rng, 1.0).normalized(), r = random_vector(rng, 0.2);
  const double f = 750.0;
  const Matrix6d K = constraint_geometric_stiffness(f, n, r);
  auto wrench = [&](const Vec6<double>& dx) {
    const Eigen::Vector3d r1 = rotation_from_vector(dx.tail<3>()) * r;
    Vec6<double> w;
    w << f * n, f * r1.cross(n);
    return w;
  };
  const double h = 1e-6;
  for (int j = 0; j < 6; ++j) {
    Vec6<double> dx = Vec6<double>::Zero();
    dx(j) = h;
    const Vec6<double> fd = (wrench(dx) - wrench(-dx)) / (2 * h);
    EXPECT_LT((fd - K.col(j)).norm(), 1e-6 * (1.0 + K.col(j).norm()));
  }
}

TEST(GeometricStiffness, AntisymmetricPartIsHalfTheMomentOfTheWrench) {
  // Summed over legs, K_g - K_g^T = -[m]x with m the moment of the legs' wrench about the TCP.
  std::mt19937 rng(13);
  Matrix6d K = Matrix6d::Zero();
  Eigen::Vector3d m = Eigen::Vector3d::Zero();
  for (int i = 0; i < 6; ++i) {
    const Eigen::Vector3d a = random_vector(rng, 0.6), r = random_vector(rng, 0.25);
    const Eigen::Vector3d l = Eigen::Vector3d(0, 0, 0.9) + r - a;
    const double f = 100.0 * (i + 1) * (i % 2 ? -1 : 1);
    K += geometric_stiffness(f, l.normalized(), r, l.norm());
    m += f * r.cross(l.normalized());
  }
  const Eigen::Matrix3d skew =
      K.bottomRightCorner<3, 3>() - K.bottomRightCorner<3, 3>().transpose();
  Eigen::Matrix3d mx;
  mx << 0, -m.z(), m.y(), m.z(), 0, -m.x(), -m.y(), m.x(), 0;
  EXPECT_LT((skew + mx).norm(), 1e-9 * m.norm());
  EXPECT_LT((K.topLeftCorner<3, 3>() - K.topLeftCorner<3, 3>().transpose()).norm(), 1e-12);
  EXPECT_LT((K.topRightCorner<3, 3>() - K.bottomLeftCorner<3, 3>().transpose()).norm(), 1e-9);
}

Matrix6d random_compliance(std::mt19937& rng) {
  Matrix6d M;
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int i = 0; i < 6; ++i)
    for (int j = 0; j < 6; ++j) M(i, j) = u(rng);
  return 1e-8 * (M * M.transpose() + 0.5 * Matrix6d::Identity());
}

TEST(ComplianceMetrics, DeflectionAndWorstDirection) {
  std::mt19937 rng(14);
  const Matrix6d C = random_compliance(rng);
  Wrench w;
  w << 100, -200, 300, 5, -6, 7;
  PoseMetrics m;
  PoseCompliance matrices;
  fill_compliance_metrics(C, w, m, matrices);
  EXPECT_EQ(matrices.compliance, C);
  EXPECT_DOUBLE_EQ(m.tcp_deflection, (C * w).head<3>().norm());
  EXPECT_DOUBLE_EQ(m.tcp_rotation_deflection, (C * w).tail<3>().norm());
  const Eigen::Matrix3d Ctt = C.topLeftCorner<3, 3>();
  const double lambda_max = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(Ctt).eigenvalues()(2);
  const Eigen::Vector3d v = m.stiffness_min_direction;
  EXPECT_NEAR(v.norm(), 1.0, 1e-12);
  EXPECT_LT((Ctt * v - lambda_max * v).norm(), 1e-9 * lambda_max);
  Eigen::Index largest = 0;
  v.cwiseAbs().maxCoeff(&largest);
  EXPECT_GT(v(largest), 0.0);
}

TEST(ComplianceMetrics, LoadedStiffnessWithoutLoadIsTheUnloadedOne) {
  std::mt19937 rng(15);
  const Matrix6d C = random_compliance(rng);
  const double lambda_max =
      Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(C.topLeftCorner<3, 3>()).eigenvalues()(2);
  const double loaded = loaded_stiffness_min(DofMatrix(C), DofMatrix(Matrix6d::Zero()),
                                             TwistMap(Matrix6d::Identity()));
  EXPECT_NEAR(loaded, 1.0 / lambda_max, 1e-10 / lambda_max);
}

TEST(ComplianceMetrics, LoadedStiffnessIsTheInverseOfTheTangentCompliance) {
  std::mt19937 rng(16);
  const Matrix6d C = random_compliance(rng);
  Matrix6d G = 1e6 * random_compliance(rng) * 1e8;  // a positive geometric term (1e6 N/m scale)
  G(0, 4) += 3e5;                                   // and an antisymmetric part
  const Matrix6d KT = C.inverse() + G;
  const Eigen::Matrix3d CTtt = KT.inverse().topLeftCorner<3, 3>();
  const double expected = 1.0 / Eigen::JacobiSVD<Eigen::Matrix3d>(CTtt).singularValues()(0);
  EXPECT_NEAR(loaded_stiffness_min(DofMatrix(C), DofMatrix(G), TwistMap(Matrix6d::Identity())),
              expected, 1e-9 * expected);
  // A compressive load that makes K_T indefinite: the loaded mechanism is unstable, 0.
  const Matrix6d unstable = -2.0 * C.inverse();
  EXPECT_EQ(loaded_stiffness_min(DofMatrix(C), DofMatrix(unstable), TwistMap(Matrix6d::Identity())),
            0.0);
}

TEST(ComplianceMetrics, SingularPoseHasInfiniteDeflectionAndNoDirection) {
  PoseMetrics m;
  PoseCompliance matrices;
  set_singular_compliance_metrics(m, matrices);
  EXPECT_TRUE(std::isinf(matrices.compliance(0, 0)));
  EXPECT_TRUE(std::isinf(matrices.loaded_compliance_tt(2, 2)));
  EXPECT_TRUE(std::isinf(m.tcp_deflection));
  EXPECT_TRUE(std::isinf(m.tcp_rotation_deflection));
  EXPECT_EQ(m.stiffness_min_loaded, 0.0);
  EXPECT_EQ(m.stiffness_min_direction, Eigen::Vector3d::Zero());
}

}  // namespace
}  // namespace pkmopt
