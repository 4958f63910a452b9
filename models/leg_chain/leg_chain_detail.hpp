// Internal helpers shared by the leg-chain sources (models/leg_chain/leg_chain*.cpp):
// dimension-capped matrix types, angle helpers and the reciprocal condition number. Not part of the
// public API.
#pragma once

#include <Eigen/Core>
#include <Eigen/Eigenvalues>
#include <Eigen/SVD>
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "models/core/pose.hpp"

namespace pkmopt::detail {

inline constexpr double kInf = std::numeric_limits<double>::infinity();
inline constexpr double kPi = std::numbers::pi;

using MatM = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, 6, 6>;
using VecM = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, 6, 1>;
using Mat3M = Eigen::Matrix<double, 3, Eigen::Dynamic, 0, 3, 6>;

// Angle wrapped to (-pi, pi].
inline double wrap_angle(double a) {
  a = std::remainder(a, 2.0 * kPi);
  return a <= -kPi ? a + 2.0 * kPi : a;
}

inline double angle_between(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return std::atan2(a.cross(b).norm(), a.dot(b));
}

// 1 / cond(M) = sigma_min / sigma_max (0 if not finite). 3x3: from the eigenvalues of M^T M
// (closed form), with an SVD when the ratio is below 1e-3 (the squared matrix loses digits there,
// relative error ~ eps cond^2); other sizes: SVD.
inline double reciprocal_condition(const MatM& M) {
  if (!M.allFinite()) return 0.0;
  if (M.rows() == 3) {
    const Mat3<double> gram = M.transpose() * M;
    Eigen::SelfAdjointEigenSolver<Mat3<double>> eig;
    eig.computeDirect(gram, Eigen::EigenvaluesOnly);
    const double lambda_max = eig.eigenvalues()(2);
    const double lambda_min = std::max(eig.eigenvalues()(0), 0.0);
    const double rcond = lambda_max > 0.0 ? std::sqrt(lambda_min / lambda_max) : 0.0;
    if (rcond >= 1e-3) return rcond;
  }
  Eigen::JacobiSVD<MatM> svd(M);
  const auto& sv = svd.singularValues();
  const double rcond = sv(0) > 0.0 ? sv(M.rows() - 1) / sv(0) : 0.0;
  return std::isfinite(rcond) ? rcond : 0.0;
}

}  // namespace pkmopt::detail
