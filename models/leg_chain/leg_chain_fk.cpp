// Forward kinematics of the leg-chain machine: Levenberg-Marquardt on the leg closure errors
// (with the Schoenflies / planar-leg mobility equations appended) and its default start pose.
#include <optional>
#include <string>

#include "models/core/pose_solver.hpp"
#include "models/leg_chain/leg_chain.hpp"
#include "models/leg_chain/leg_chain_detail.hpp"

namespace pkmopt {
namespace {

using detail::kInf;
using detail::Mat3M;
using detail::MatM;
using detail::VecM;

}  // namespace

FkResult LegChainMachine::forward_kinematics(const Eigen::VectorXd& q_target,
                                             const std::optional<Pose>& guess,
                                             const FkOptions& options) const {
  FkResult result;
  const int n = num_actuators();
  if (q_target.size() != n || !q_target.allFinite()) {
    result.message = "actuator coordinates must be " + std::to_string(n) + " finite numbers";
    result.residual = kInf;
    result.pose = design_.home;
    return result;
  }
  for (int i = 0; i < n; ++i) {
    if (design_.legs[static_cast<std::size_t>(i)].kind == LegKind::kUPS && !(q_target(i) > 0.0)) {
      result.message = "leg lengths must be > 0";
      result.residual = kInf;
      result.pose = design_.home;
      return result;
    }
  }
  Pose start = guess ? *guess : default_fk_start(q_target);
  if (!start.position.allFinite() || !start.angles.allFinite()) {
    result.message = "the guess must be finite";
    result.residual = kInf;
    result.pose = design_.home;
    return result;
  }
  Eigen::Vector3d start_p;
  Eigen::Matrix3d start_R;
  resolve_pose(start, start_p, start_R);
  if (design_.mobility == PlatformMobility::kTranslational) start.angles.setZero();

  // The actuated points and link lengths are fixed by q.
  Mat3M c(3, n);
  VecM L(n);
  for (int i = 0; i < n; ++i) {
    Eigen::Vector3d ci, dci;
    actuated_point(i, q_target(i), ci, dci);
    c.col(i) = ci;
    const LegChainLeg& leg = design_.legs[static_cast<std::size_t>(i)];
    L(i) = leg.kind == LegKind::kUPS ? q_target(i) : leg.link_length;
  }
  // Levenberg-Marquardt on the closure errors g_i = |P_i - c_i| - L_i; their Jacobian with
  // respect to the full twist has rows [s_i^T, (r_i x s_i)^T]. 6-DOF and translational platforms
  // solve on their DOF directly. Schoenflies and planar-leg platforms solve on the full twist
  // with the mobility's own equations appended (6 x 6, all in m):
  //   Schoenflies: L_c e1 . (R e) = 0, L_c e2 . (R e) = 0 (R keeps e; e1, e2 orthogonal to e);
  //   planar legs: h_i = n_i . (P_i - base_point_i) = 0.
  auto closure_rows = [&](const Eigen::Vector3d& p, const Eigen::Matrix3d& R, VecM& g, MatM& jac,
                          bool full) {
    for (int i = 0; i < n; ++i) {
      const Eigen::Vector3d ri = R * platform_rel_.col(i);
      const Eigen::Vector3d l = p + ri - c.col(i);
      const double len = l.norm();
      g(i) = len - L(i);
      const Eigen::Vector3d si = len > 0.0 ? Eigen::Vector3d(l / len) : Eigen::Vector3d::Zero();
      jac.block(i, 0, 1, 3) = si.transpose();
      if (full) jac.block(i, 3, 1, 3) = ri.cross(si).transpose();
    }
  };
  if (design_.mobility == PlatformMobility::kSixDof ||
      design_.mobility == PlatformMobility::kTranslational) {
    const bool rotates = dof_ == 6;
    auto evaluate = [&](const Eigen::Vector3d& p, const Eigen::Matrix3d& R, VecM& g, MatM& jac) {
      closure_rows(p, R, g, jac, rotates);
    };
    const PoseClosureSolve<VecM> solve =
        solve_pose_closure<VecM, MatM>(start_p, start_R, rotates, n, options, evaluate);
    return fk_result(solve, start, rotates, "leg closure error");
  }
  const double Lc = characteristic_length_;
  const Eigen::Vector3d& e = design_.rotation_axis;
  const Eigen::Vector3d e1 = e.unitOrthogonal();
  const Eigen::Vector3d e2 = e.cross(e1);
  auto evaluate = [&](const Eigen::Vector3d& p, const Eigen::Matrix3d& R, VecM& g, MatM& jac) {
    jac.setZero();
    closure_rows(p, R, g, jac, true);
    if (design_.mobility == PlatformMobility::kSchoenflies) {
      // d(R e) = omega x (R e): d(e_k . R e) = omega . ((R e) x e_k).
      const Eigen::Vector3d Re = R * e;
      g(4) = Lc * e1.dot(Re);
      g(5) = Lc * e2.dot(Re);
      jac.block(4, 3, 1, 3) = Lc * Re.cross(e1).transpose();
      jac.block(5, 3, 1, 3) = Lc * Re.cross(e2).transpose();
    } else {
      for (int i = 0; i < 3; ++i) {
        const LegChainLeg& leg = design_.legs[static_cast<std::size_t>(i)];
        const Eigen::Vector3d ri = R * platform_rel_.col(i);
        g(3 + i) = leg.plane_normal.dot(p + ri - leg.base_point);
        jac.block(3 + i, 0, 1, 3) = leg.plane_normal.transpose();
        jac.block(3 + i, 3, 1, 3) = ri.cross(leg.plane_normal).transpose();
      }
    }
  };
  const PoseClosureSolve<VecM> solve =
      solve_pose_closure<VecM, MatM>(start_p, start_R, true, 6, options, evaluate);
  FkResult full = fk_result(solve, start, true, "leg closure error");
  if (design_.mobility == PlatformMobility::kSchoenflies && full.converged) {
    // Report the rotation about e exactly (the solve keeps R e = e to its tolerance).
    if (const auto exact = actual_pose(full.pose)) full.pose.angles = exact->angles;
  }
  return full;
}

Pose LegChainMachine::default_fk_start(const Eigen::VectorXd& q) const {
  Pose start = design_.home;
  if (!home_ik_ok_) return start;
  Eigen::Vector3d home_p;
  Eigen::Matrix3d R;
  resolve_pose(design_.home, home_p, R);
  Eigen::Vector3d p = home_leg_offset_;
  for (int i = 0; i < num_actuators(); ++i) {
    Eigen::Vector3d c, dc;
    actuated_point(i, q(i), c, dc);
    p += (c - R * platform_rel_.col(i)) / num_actuators();
  }
  if (p.allFinite()) start.position = p;
  return start;
}

}  // namespace pkmopt
