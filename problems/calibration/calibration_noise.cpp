// The noise of a calibration's measurements estimated from its residuals: the squared whitened
// residuals and the redundancy of each noise group (variance-component estimation).
//
// Groups: 0 instrument position (rows 6..8 of a pose), 1 instrument orientation (rows 9..11),
// 2 actuator readings (rows 0..5). At a least-squares solution of the whitened problem with
// Jacobian J = [A | B] (A: the free machine and frame parameters, B: the pose unknowns), the
// residual r = (I - H) e with H = J (J^T J)^+ J^T the hat matrix, so E[sum_{i in g} r_i^2] =
// s_g^2 sum_{i in g} (1 - H_ii) when the errors e of group g have variance s_g^2 (in units of
// the sigma used to whiten). The group's redundancy r_g = sum_{i in g} (1 - H_ii) sums to the
// degrees of freedom 6 N - n_free, and s_g^2 = Omega_g / r_g (Omega_g = sum r_i^2) is the
// variance-component estimate (Foerstner 1979; Koch, Parameter Estimation and Hypothesis Testing
// in Linear Models, 1999): the sigma of group g is too small by the factor s_g.
// Per pose k, with U_k (6 x 12) an orthonormal basis of the rows orthogonal to range(B_k) and
// R_k = U_k A_k its reduced rows (J_id = [R_1; ...; R_N], M = J_id^T J_id):
//   1 - H_ii = [U_k^T (I - R_k M^+ R_k^T) U_k]_ii          (row i of pose k)
// because the pose unknowns are eliminated exactly by U_k.
#include <Eigen/Core>
#include <Eigen/LU>
#include <Eigen/QR>
#include <Eigen/SVD>
#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "problems/calibration/calibration_detail.hpp"

namespace pkmopt::detail {

NoiseGroups noise_groups(const CalibrationVector& x, const Eigen::Vector3d& tcp,
                         const std::vector<CalibrationMeasurement>& measurements,
                         const std::vector<Vec6<double>>& poses, const std::vector<int>& active,
                         const CalibrationOptions& options) {
  static constexpr int kGroupOfRow[12] = {2, 2, 2, 2, 2, 2, 0, 0, 0, 1, 1, 1};
  const std::vector<int> free = free_indices_of(options.free);
  // The campaigns' leg zero shifts are unknowns too: 6 columns per campaign c >= 1 that has
  // poses here, each the offset column of leg i on that campaign's poses.
  int campaigns = 1;
  for (int k : active)
    campaigns = std::max(campaigns, measurements[static_cast<std::size_t>(k)].campaign + 1);
  const Eigen::Index n_machine = static_cast<Eigen::Index>(free.size());
  const Eigen::Index n = n_machine + 6 * (campaigns - 1);
  const std::size_t count = active.size();
  using Matrix12 = Eigen::Matrix<double, 12, 12>;
  std::vector<Matrix12> P(count);         // projection onto the pose directions of pose k
  std::vector<Eigen::MatrixXd> A(count);  // (I - P_k) A_k: the parameter columns, poses removed
  std::vector<Eigen::Matrix<double, 12, 1>> residuals(count);
  Eigen::MatrixXd M = Eigen::MatrixXd::Zero(n, n);
  std::array<Eigen::MatrixXd, 3> C;  // sum_k A_k^T S_g A_k
  for (auto& c : C) c = Eigen::MatrixXd::Zero(n, n);
  for (std::size_t k = 0; k < count; ++k) {
    const auto& m = measurements[static_cast<std::size_t>(active[k])];
    const Pose pose = pose_from_vector(poses[static_cast<std::size_t>(active[k])]);
    const Eigen::Matrix<double, 12, 66> J = calibration_jacobian(x, tcp, m, pose, options);
    const Eigen::HouseholderQR<Eigen::Matrix<double, 12, 6>> qr(J.rightCols<6>().eval());
    const Matrix12 Q = qr.householderQ();
    const Eigen::Matrix<double, 6, 12> U = Q.rightCols<6>().transpose();
    P[k] = Matrix12::Identity() - U.transpose() * U;
    A[k] = Eigen::MatrixXd::Zero(12, n);
    for (Eigen::Index j = 0; j < n_machine; ++j)
      A[k].col(j) = J.col(free[static_cast<std::size_t>(j)]);
    if (m.campaign > 0)
      for (int i = 0; i < 6; ++i)
        A[k].col(n_machine + 6 * (m.campaign - 1) + i) = J.col(kCalibrationLegParameters * i + 6);
    A[k] = (U.transpose() * U * A[k]).eval();
    M.noalias() += A[k].transpose() * A[k];
    for (int i = 0; i < 12; ++i)
      C[static_cast<std::size_t>(kGroupOfRow[i])].noalias() +=
          A[k].row(i).transpose() * A[k].row(i);
    residuals[k] = calibration_residuals(x, tcp, m, pose, options);
  }
  // M^+ (M is positive definite when the free parameters are identifiable; the pseudo-inverse
  // keeps the redundancy right when a direction is not).
  Eigen::MatrixXd M_inverse = Eigen::MatrixXd::Zero(n, n);
  if (n > 0) M_inverse = Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd>(M).pseudoInverse();
  NoiseGroups groups;
  // T_gh = sum_{i in g, j in h} R_ij^2 with R = I - P - Q, P = blockdiag(P_k), Q = A M^+ A^T
  // (P Q = 0): delta_gh (n_g - 2 sum_{i in g} H_ii) + sum_{i in g, j in h} (P_ij^2 + 2 P_ij Q_ij)
  // (within a pose) + tr(M^+ C_h M^+ C_g).
  Eigen::Matrix3d T = Eigen::Matrix3d::Zero();
  for (std::size_t k = 0; k < count; ++k) {
    const Matrix12 Qk = A[k] * M_inverse * A[k].transpose();
    for (int i = 0; i < 12; ++i) {
      const int g = kGroupOfRow[i];
      const double h = P[k](i, i) + Qk(i, i);
      groups.omega(g) += residuals[k](i) * residuals[k](i);
      groups.redundancy(g) += 1.0 - h;
      groups.rows(g) += 1;
      groups.residuals[static_cast<std::size_t>(g)].push_back(residuals[k](i));
      T(g, g) += 1.0 - 2.0 * h;
      for (int j = 0; j < 12; ++j) {
        T(g, kGroupOfRow[j]) += P[k](i, j) * P[k](i, j) + 2.0 * P[k](i, j) * Qk(i, j);
      }
    }
  }
  std::array<Eigen::MatrixXd, 3> MC;
  for (int g = 0; g < 3; ++g)
    MC[static_cast<std::size_t>(g)] = M_inverse * C[static_cast<std::size_t>(g)];
  for (int g = 0; g < 3; ++g)
    for (int h = 0; h < 3; ++h)
      T(g, h) += (MC[static_cast<std::size_t>(h)].cwiseProduct(
                      MC[static_cast<std::size_t>(g)].transpose()))
                     .sum();
  groups.T = T;
  return groups;
}

NoiseGroups robust_noise_groups(const NoiseGroups& groups) {
  NoiseGroups robust = groups;
  for (int g = 0; g < 3; ++g) {
    std::vector<double> squares;
    for (double r : groups.residuals[static_cast<std::size_t>(g)]) squares.push_back(r * r);
    if (squares.empty()) continue;
    const std::size_t middle = squares.size() / 2;
    std::nth_element(squares.begin(), squares.begin() + static_cast<std::ptrdiff_t>(middle),
                     squares.end());
    // The median of chi^2 with one degree of freedom is 0.454936.
    robust.omega(g) = static_cast<double>(squares.size()) * squares[middle] / 0.4549364231195724;
  }
  return robust;
}

Eigen::Vector3d helmert_factors(const NoiseGroups& groups, std::array<bool, 3>& resolved,
                                const Eigen::Vector3d& max_relative_sd,
                                Eigen::Vector3d* relative_sd) {
  // E[Omega] = T s^2 (Helmert). At the solution the estimate's covariance is 2 T^-1 (normal
  // errors), so sqrt(2 (T^-1)_gg) is the relative standard deviation of s_g^2: a group above
  // its max_relative_sd is not resolved by the data and is held at s_g = 1 (the worst first),
  // and the others are solved again without it.
  Eigen::Vector3d s2 = Eigen::Vector3d::Ones();
  Eigen::Vector3d sd = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
  for (int pass = 0; pass < 3; ++pass) {
    std::vector<int> unknown;
    for (int g = 0; g < 3; ++g)
      if (resolved[static_cast<std::size_t>(g)]) unknown.push_back(g);
    if (unknown.empty()) break;
    const Eigen::Index u = static_cast<Eigen::Index>(unknown.size());
    Eigen::MatrixXd T(u, u);
    Eigen::VectorXd rhs(u);
    for (Eigen::Index a = 0; a < u; ++a) {
      const int g = unknown[static_cast<std::size_t>(a)];
      rhs(a) = groups.omega(g);
      for (int h = 0; h < 3; ++h)
        if (!resolved[static_cast<std::size_t>(h)]) rhs(a) -= groups.T(g, h);
      for (Eigen::Index b = 0; b < u; ++b)
        T(a, b) = groups.T(g, unknown[static_cast<std::size_t>(b)]);
    }
    const Eigen::FullPivLU<Eigen::MatrixXd> lu(T);
    int worst = -1;
    double worst_excess = 1.0;
    Eigen::VectorXd solution, pass_sd(u);
    if (lu.isInvertible()) {
      solution = lu.solve(rhs);
      const Eigen::MatrixXd inverse = lu.inverse();
      for (Eigen::Index a = 0; a < u; ++a) {
        const double v = 2.0 * inverse(a, a);
        pass_sd(a) = v > 0.0 ? std::sqrt(v) : std::numeric_limits<double>::infinity();
        if (!(solution(a) > 0.0) || !std::isfinite(solution(a)))
          pass_sd(a) = std::numeric_limits<double>::infinity();
        const int g = unknown[static_cast<std::size_t>(a)];
        if (pass_sd(a) / max_relative_sd(g) > worst_excess) {
          worst_excess = pass_sd(a) / max_relative_sd(g);
          worst = g;
        }
      }
    } else {
      worst = unknown.back();  // singular: drop the last (actuator before orientation, position)
    }
    if (worst < 0) {
      for (Eigen::Index a = 0; a < u; ++a) {
        s2(unknown[static_cast<std::size_t>(a)]) = solution(a);
        sd(unknown[static_cast<std::size_t>(a)]) = pass_sd(a);
      }
      break;
    }
    resolved[static_cast<std::size_t>(worst)] = false;
  }
  if (relative_sd) *relative_sd = sd;
  return s2.cwiseSqrt();
}

}  // namespace pkmopt::detail
