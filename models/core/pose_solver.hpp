// The forward-kinematics solve shared by the parallel machine models: Levenberg-Marquardt on
// the platform pose for n closure equations g(p, R) = 0 (leg length errors, m).
//
// The unknowns are a twist of the platform: a translation of the TCP and, when `rotates`, a
// rotation vector omega about the base axes (R <- exp(omega) R); the caller's `evaluate(p, R,
// g, jac)` fills the residuals g (n) and their Jacobian with respect to that twist (n x n: the
// machine's A or J). Steps solve (J^T J + lambda diag(J^T J)) dx = -J^T g; lambda shrinks by 5
// after a successful step and grows by 5 (10 for a non-finite step) otherwise. Once
// max |g| <= tolerance, up to two undamped Gauss-Newton steps polish the pose to machine
// precision. Never loops forever (max_iterations) and never returns a non-orthonormal R.
//
//   auto solve = solve_pose_closure<Vec6, Mat6>(p0, R0, true, 6, options,
//       [&](const Eigen::Vector3d& p, const Eigen::Matrix3d& R, Vec& g, Mat& jac) {...});
//   if (solve.converged) ... solve.position, solve.rotation, solve.residual
#pragma once

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <Eigen/SVD>
#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <string>

#include "models/core/machine.hpp"
#include "models/core/pose.hpp"

namespace pkmopt {

template <typename Vec>
struct PoseClosureSolve {
  Eigen::Vector3d position;
  Eigen::Matrix3d rotation;
  Vec residual;  ///< g at the returned pose
  int iterations = 0;
  bool converged = false;  ///< max |g| <= tolerance reached
};

/// Vec, Mat: the residual vector and Jacobian types (fixed or dynamic size; n equations).
template <typename Vec, typename Mat, typename Evaluate>
PoseClosureSolve<Vec> solve_pose_closure(const Eigen::Vector3d& start_position,
                                         const Eigen::Matrix3d& start_rotation, bool rotates, int n,
                                         const FkOptions& options, Evaluate&& evaluate) {
  Eigen::Vector3d p = start_position;
  Eigen::Matrix3d R = start_rotation;
  Vec g(n);
  Mat jac(n, n);
  evaluate(p, R, g, jac);
  double cost = g.squaredNorm();
  double lambda = options.initial_damping;
  int iterations = 0;
  bool converged = g.cwiseAbs().maxCoeff() <= options.tolerance;
  int polish_steps = 0;
  while (iterations < options.max_iterations) {
    if (converged) {
      // One or two Gauss-Newton steps past the tolerance take the pose to machine precision.
      if (polish_steps >= 2) break;
      ++polish_steps;
    }
    ++iterations;
    const Mat JtJ = jac.transpose() * jac;
    const Vec grad = jac.transpose() * g;
    Mat H = JtJ;
    const double damping = converged ? 0.0 : lambda;
    for (int i = 0; i < n; ++i) H(i, i) += damping * (JtJ(i, i) + 1e-12);
    const Vec step = -H.ldlt().solve(grad);
    if (!step.allFinite()) {
      if (converged) break;
      lambda *= 10.0;
      if (lambda > 1e16) break;
      continue;
    }
    const Eigen::Vector3d p_trial = p + step.template head<3>();
    const Eigen::Matrix3d R_trial =
        rotates
            ? Eigen::Matrix3d(rotation_from_vector(Eigen::Vector3d(step.template tail<3>())) * R)
            : R;
    Vec g_trial(n);
    Mat jac_trial(n, n);
    evaluate(p_trial, R_trial, g_trial, jac_trial);
    const double cost_trial = g_trial.squaredNorm();
    if (std::isfinite(cost_trial) && cost_trial < cost) {
      p = p_trial;
      R = R_trial;
      g = g_trial;
      jac = jac_trial;
      cost = cost_trial;
      lambda = std::max(lambda / 5.0, 1e-15);
      converged = converged || g.cwiseAbs().maxCoeff() <= options.tolerance;
    } else {
      if (converged) break;  // the polish step cannot improve: done
      lambda *= 5.0;
      if (lambda > 1e16) break;
    }
  }
  // Re-orthonormalise (the updates keep R a rotation up to rounding).
  Eigen::JacobiSVD<Eigen::Matrix3d> svd(R, Eigen::ComputeFullU | Eigen::ComputeFullV);
  PoseClosureSolve<Vec> result;
  result.position = p;
  result.rotation = svd.matrixU() * svd.matrixV().transpose();
  result.residual = g;
  result.iterations = iterations;
  result.converged = converged;
  return result;
}

/// The FkResult of a solve: the pose (angles zero when the platform does not rotate), the
/// largest residual, and "converged" or "did not converge: max <what> <residual> m after <n>
/// iterations". A non-finite pose or residual gives back `start`, residual inf, not converged.
template <typename Vec>
FkResult fk_result(const PoseClosureSolve<Vec>& solve, const Pose& start, bool rotates,
                   const std::string& what) {
  FkResult result;
  result.pose.position = solve.position;
  result.pose.angles = rotates ? angles_from_rotation(solve.rotation) : Eigen::Vector3d::Zero();
  result.iterations = solve.iterations;
  result.residual = solve.residual.cwiseAbs().maxCoeff();
  result.converged = solve.converged && solve.position.allFinite();
  if (!result.pose.position.allFinite() || !result.pose.angles.allFinite() ||
      !std::isfinite(result.residual)) {
    result.pose = start;
    result.residual = std::numeric_limits<double>::infinity();
    result.converged = false;
  }
  if (result.converged) {
    result.message = "converged";
  } else {
    std::ostringstream os;
    os << "did not converge: max " << what << " " << result.residual << " m after "
       << solve.iterations << " iterations";
    result.message = os.str();
  }
  return result;
}

}  // namespace pkmopt
