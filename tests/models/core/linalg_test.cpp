// Tests of models/core/linalg: the fast 6x6 and 3x3 symmetric eigenvalues against Eigen's solver
// and exact spectra, including repeated, clustered and zero eigenvalues; the LU solves.
#include "models/core/linalg.hpp"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <Eigen/QR>
#include <cmath>

#include "tests/sample_machines.hpp"

namespace pkmopt {
namespace {

using Matrix6 = Eigen::Matrix<double, 6, 6>;
using Vector6 = Eigen::Matrix<double, 6, 1>;

// Q diag(lambda) Q^T with a random orthogonal Q.
Matrix6 with_spectrum(const Vector6& lambda, sample_machines::Uniform& u) {
  Matrix6 M;
  for (int i = 0; i < 36; ++i) M.data()[i] = u(-1, 1);
  const Matrix6 Q = Eigen::HouseholderQR<Matrix6>(M).householderQ();
  return Q * lambda.asDiagonal() * Q.transpose();
}

TEST(Linalg, EigenvaluesOfRandomSymmetricMatrices) {
  sample_machines::Uniform u(1);
  for (int k = 0; k < 500; ++k) {
    Matrix6 M;
    for (int i = 0; i < 36; ++i) M.data()[i] = u(-1, 1);
    const Matrix6 A = M * M.transpose() + (k % 2 ? Matrix6::Zero() : Matrix6(M + M.transpose()));
    Vector6 fast;
    symmetric_eigenvalues6(A, fast);
    const Vector6 ref = Eigen::SelfAdjointEigenSolver<Matrix6>(A).eigenvalues();
    const double scale = ref.cwiseAbs().maxCoeff();
    for (int i = 0; i < 6; ++i) EXPECT_NEAR(fast(i), ref(i), 1e-14 * scale);
  }
}

TEST(Linalg, KnownSpectraWithRepeatedAndZeroEigenvalues) {
  sample_machines::Uniform u(2);
  const Vector6 spectra[] = {
      (Vector6() << 1, 1, 1, 1, 1, 1).finished(),
      (Vector6() << 0.5, 0.5, 2, 2, 3, 3).finished(),
      (Vector6() << 0, 0, 1e-3, 1, 1, 7).finished(),
      (Vector6() << 1e-8, 1e-4, 1e-2, 1, 1e2, 1e4).finished(),
      (Vector6() << -3, -1, 0, 0, 2, 5).finished(),
  };
  for (const Vector6& lambda : spectra) {
    for (int rep = 0; rep < 20; ++rep) {
      Vector6 fast;
      symmetric_eigenvalues6(with_spectrum(lambda, u), fast);
      const double scale = lambda.cwiseAbs().maxCoeff();
      for (int i = 0; i < 6; ++i) EXPECT_NEAR(fast(i), lambda(i), 1e-14 * scale);
    }
  }
  // Already diagonal (the tridiagonal form splits at once) and zero.
  Vector6 fast;
  symmetric_eigenvalues6(Vector6(6, 5, 4, 3, 2, 1).asDiagonal().toDenseMatrix(), fast);
  EXPECT_EQ(fast, (Vector6() << 1, 2, 3, 4, 5, 6).finished());
  symmetric_eigenvalues6(Matrix6::Zero(), fast);
  EXPECT_EQ(fast, Vector6::Zero());
}

TEST(Linalg, Lu6SolvesAndDeterminantMatchEigen) {
  sample_machines::Uniform u(3);
  for (int k = 0; k < 200; ++k) {
    Matrix6 J;
    for (int i = 0; i < 36; ++i) J.data()[i] = u(-1, 1);
    Vector6 b;
    for (int i = 0; i < 6; ++i) b(i) = u(-1, 1);
    const Lu6 lu(J);
    EXPECT_FALSE(lu.exactly_singular());
    EXPECT_NEAR(lu.determinant(), J.determinant(), 1e-12 * std::abs(J.determinant()) + 1e-15);
    EXPECT_LT((J * lu.solve(b) - b).norm(), 1e-10 * b.norm());
    EXPECT_LT((J.transpose() * lu.solve_transposed(b) - b).norm(), 1e-10 * b.norm());
  }
  Matrix6 singular = Matrix6::Identity();
  singular(3, 3) = 0.0;
  const Lu6 lu(singular);
  EXPECT_TRUE(lu.exactly_singular());
  EXPECT_EQ(lu.determinant(), 0.0);
}

TEST(Linalg, ThreeByThreeEigenvaluesIncludingClusters) {
  sample_machines::Uniform u(4);
  using Matrix3 = Eigen::Matrix3d;
  for (int k = 0; k < 500; ++k) {
    Matrix3 M;
    for (int i = 0; i < 9; ++i) M.data()[i] = u(-1, 1);
    const Matrix3 A = M * M.transpose();
    Eigen::Vector3d fast;
    symmetric_eigenvalues3(A, fast);
    const Eigen::Vector3d ref = Eigen::SelfAdjointEigenSolver<Matrix3>(A).eigenvalues();
    for (int i = 0; i < 3; ++i) EXPECT_NEAR(fast(i), ref(i), 1e-14 * ref(2));
  }
  // Two largest eigenvalues equal or within 1e-9 (the case a closed-form cubic solution gets
  // wrong to ~1e-8): Q diag(lambda) Q^T with a random rotation Q.
  for (const double gap : {0.0, 1e-12, 1e-9, 1e-6}) {
    for (int rep = 0; rep < 50; ++rep) {
      Matrix3 M;
      for (int i = 0; i < 9; ++i) M.data()[i] = u(-1, 1);
      const Matrix3 Q = Eigen::HouseholderQR<Matrix3>(M).householderQ();
      const Eigen::Vector3d lambda(0.3e-8, 1e-8, (1.0 + gap) * 1e-8);
      Eigen::Vector3d fast;
      symmetric_eigenvalues3(Q * lambda.asDiagonal() * Q.transpose(), fast);
      for (int i = 0; i < 3; ++i) EXPECT_NEAR(fast(i), lambda(i), 1e-15 * 1e-8);
    }
  }
  Eigen::Vector3d fast;
  symmetric_eigenvalues3(Eigen::Vector3d(3, 1, 2).asDiagonal().toDenseMatrix(), fast);
  EXPECT_EQ(fast, Eigen::Vector3d(1, 2, 3));
}

TEST(Linalg, TransposedSolveWithFourRightHandSides) {
  sample_machines::Uniform u(5);
  for (int k = 0; k < 200; ++k) {
    Matrix6 J;
    for (int i = 0; i < 36; ++i) J.data()[i] = u(-1, 1);
    Eigen::Matrix<double, 6, 4> B, X;
    for (int i = 0; i < 24; ++i) B.data()[i] = u(-1, 1);
    double det = 0.0;
    ASSERT_TRUE(solve_transposed6x4(J, B, X, det));
    EXPECT_NEAR(det, J.determinant(), 1e-12 * std::abs(J.determinant()) + 1e-15);
    for (int c = 0; c < 4; ++c) {
      EXPECT_LT((J.transpose() * X.col(c) - B.col(c)).norm(), 1e-10 * B.col(c).norm());
    }
  }
  Matrix6 singular = Matrix6::Identity();
  singular(2, 2) = 0.0;
  Eigen::Matrix<double, 6, 4> X;
  double det = 1.0;
  EXPECT_FALSE(solve_transposed6x4(singular, Eigen::Matrix<double, 6, 4>::Ones(), X, det));
  EXPECT_EQ(det, 0.0);
  // A row permutation: pivoting flips the sign of the determinant.
  Matrix6 swapped = Matrix6::Identity();
  swapped.row(0).swap(swapped.row(4));
  ASSERT_TRUE(solve_transposed6x4(swapped, Eigen::Matrix<double, 6, 4>::Ones(), X, det));
  EXPECT_EQ(det, -1.0);
}

}  // namespace
// The box maximum against every one of the 2^n sign vectors (both signs of s_0) and against
// random interior points of the box, which never exceed it; a known case by hand.
TEST(Linalg, MaxNormOverSignVectorsIsTheLargestBoxVertex) {
  EXPECT_EQ(max_norm_over_sign_vectors(Eigen::Matrix<double, 3, Eigen::Dynamic>(3, 0)), 0.0);
  Eigen::Matrix<double, 3, 2> two;
  two << 1, 0, 0, 2, 0, 0;  // columns (1, 0, 0) and (0, 2, 0): |(+-1, +-2, 0)| = sqrt(5)
  EXPECT_DOUBLE_EQ(max_norm_over_sign_vectors(two), std::sqrt(5.0));
  sample_machines::Uniform uniform(5);
  for (int n = 1; n <= 9; ++n) {
    Eigen::Matrix<double, 3, Eigen::Dynamic> c(3, n);
    for (int j = 0; j < n; ++j)
      for (int a = 0; a < 3; ++a) c(a, j) = uniform(-1.0, 1.0);
    const double max = max_norm_over_sign_vectors(c);
    double brute = 0.0;
    for (unsigned g = 0; g < (1u << n); ++g) {
      Eigen::VectorXd s(n);
      for (int j = 0; j < n; ++j) s(j) = (g >> j) & 1u ? -1.0 : 1.0;
      brute = std::max(brute, (c * s).norm());
    }
    EXPECT_NEAR(max, brute, 1e-14 * brute) << n;
    for (int k = 0; k < 2000; ++k) {
      Eigen::VectorXd s(n);
      for (int j = 0; j < n; ++j) s(j) = uniform(-1.0, 1.0);
      EXPECT_LE((c * s).norm(), max * (1.0 + 1e-14)) << n;
    }
  }
}

}  // namespace pkmopt
