// Platform mobility of the leg-chain machine: the pose the platform actually takes (Schoenflies
// swing-twist projection, planar-leg parasitic x, y, rz solve) and the planar legs' twist map.
#include <Eigen/Geometry>
#include <Eigen/LU>
#include <cmath>
#include <limits>
#include <optional>

#include "models/core/machine.hpp"
#include "models/leg_chain/leg_chain.hpp"
#include "models/leg_chain/leg_chain_detail.hpp"

namespace pkmopt {
namespace {

using detail::angle_between;
using detail::MatM;
using detail::reciprocal_condition;
using detail::wrap_angle;

// A Schoenflies pose is on the platform's rotation set when R e is within this (rad) of e.
constexpr double kRotationTolerance = 1e-9;

}  // namespace

bool LegChainMachine::resolve_pose(const Pose& pose, Eigen::Vector3d& p, Eigen::Matrix3d& R) const {
  p = pose.position;
  switch (design_.mobility) {
    case PlatformMobility::kSixDof:
      R = rotation_zyx<double>(pose.angles);
      return true;
    case PlatformMobility::kTranslational:
      R.setIdentity();
      return pose.angles.cwiseAbs().maxCoeff() <= 1e-12;
    case PlatformMobility::kSchoenflies: {
      // Swing-twist split of the given rotation: the twist about e is Rot(e, phi) with
      // phi = 2 atan2(q_vec . e, q_w); the swing turns e to R0 e.
      const Eigen::Vector3d& e = design_.rotation_axis;
      const Eigen::Matrix3d R0 = rotation_zyx<double>(pose.angles);
      const Eigen::Quaterniond quat(R0);
      const double phi = 2.0 * std::atan2(quat.vec().dot(e), quat.w());
      R = Eigen::AngleAxisd(std::isfinite(phi) ? phi : 0.0, e).toRotationMatrix();
      return angle_between(R0 * e, e) <= kRotationTolerance;
    }
    case PlatformMobility::kPlanarLegs: {
      // Parasitic x, y, rz from h_i = n_i . (p + Rz(rz) M rel_i - o_i) = 0, M = Ry(ry) Rx(rx);
      // Newton from the home pose's x, y, rz.
      const Eigen::Matrix3d M =
          rotation_zyx<double>(Eigen::Vector3d(pose.angles(0), pose.angles(1), 0.0));
      Eigen::Vector3d x(design_.home.position(0), design_.home.position(1), design_.home.angles(2));
      bool converged = false;
      double last_residual = std::numeric_limits<double>::infinity(), last_scale = 1.0;
      for (int iteration = 0; iteration < 50; ++iteration) {
        const Eigen::Matrix3d Rk = Eigen::AngleAxisd(x(2), Eigen::Vector3d::UnitZ()) * M;
        const Eigen::Vector3d pk(x(0), x(1), pose.position(2));
        Eigen::Vector3d h;
        Eigen::Matrix3d G;
        double scale = 1.0;
        for (int i = 0; i < 3; ++i) {
          const LegChainLeg& leg = design_.legs[static_cast<std::size_t>(i)];
          const Eigen::Vector3d ri = Rk * platform_rel_.col(i);
          h(i) = leg.plane_normal.dot(pk + ri - leg.base_point);
          G(i, 0) = leg.plane_normal(0);
          G(i, 1) = leg.plane_normal(1);
          G(i, 2) = leg.plane_normal.dot(Eigen::Vector3d::UnitZ().cross(ri));
          scale = std::max(scale, (pk - leg.base_point).norm() + ri.norm());
        }
        if (!h.allFinite()) break;
        last_residual = h.cwiseAbs().maxCoeff();
        last_scale = scale;
        if (last_residual <= 1e-15 * scale) {
          converged = true;
          break;
        }
        const Eigen::FullPivLU<Eigen::Matrix3d> lu(G);
        if (!lu.isInvertible()) break;
        const Eigen::Vector3d step = lu.solve(h);
        if (!step.allFinite()) break;
        x -= step;
        if (step.norm() <= 1e-15 * (1.0 + x.norm())) break;  // stalled at rounding level
      }
      // Stalled or out of iterations just above the strict tolerance: accept rounding-level
      // residuals (the last step only reduced them further).
      if (!converged && last_residual <= 1e-9 * last_scale) converged = true;
      if (converged && x.allFinite()) {
        p = Eigen::Vector3d(x(0), x(1), pose.position(2));
        R = Eigen::AngleAxisd(wrap_angle(x(2)), Eigen::Vector3d::UnitZ()) * M;
        return true;
      }
      R = rotation_zyx<double>(pose.angles);
      return false;
    }
  }
  R = rotation_zyx<double>(pose.angles);
  return true;
}

std::optional<Pose> LegChainMachine::actual_pose(const Pose& pose) const {
  Eigen::Vector3d p;
  Eigen::Matrix3d R;
  const bool ok = resolve_pose(pose, p, R);
  if (!ok && design_.mobility == PlatformMobility::kPlanarLegs) return std::nullopt;
  Pose out;
  out.position = p;
  out.angles = design_.mobility == PlatformMobility::kTranslational ? Eigen::Vector3d::Zero()
                                                                    : angles_from_rotation(R);
  if (design_.mobility == PlatformMobility::kPlanarLegs) {
    // Keep the given rx, ry exactly (R = Rz(rz) Ry(ry) Rx(rx) by construction).
    out.angles = Eigen::Vector3d(pose.angles(0), pose.angles(1), angles_from_rotation(R)(2));
  }
  return out;
}

bool LegChainMachine::planar_twist_map(const Eigen::Vector3d& /*p*/, const Eigen::Matrix3d& R,
                                       Eigen::Matrix<double, 6, Eigen::Dynamic, 0, 6, 6>& T) const {
  // G row i = [n_i^T, (r_i x n_i)^T]; parasitic columns (v_x, v_y, w_z), DOF (v_z, w_x, w_y).
  Eigen::Matrix3d Gp, Gd;
  for (int i = 0; i < 3; ++i) {
    const Eigen::Vector3d& n = design_.legs[static_cast<std::size_t>(i)].plane_normal;
    const Eigen::Vector3d rn = (R * platform_rel_.col(i)).cross(n);
    Gp.row(i) << n(0), n(1), rn(2);
    Gd.row(i) << n(2), rn(0), rn(1);
  }
  T.setZero(6, 3);
  T(2, 0) = 1.0;
  T(3, 1) = 1.0;
  T(4, 2) = 1.0;
  Eigen::Matrix3d Gp_h = Gp;
  Gp_h.col(2) /= characteristic_length_;
  MatM Gp_dyn = Gp_h;
  if (!(reciprocal_condition(Gp_dyn) >= kSingularRcond)) return false;
  const Eigen::Matrix3d X = -Gp.partialPivLu().solve(Gd);
  if (!X.allFinite()) return false;
  T.row(0) = X.row(0);
  T.row(1) = X.row(1);
  T.row(5) = X.row(2);
  return true;
}

}  // namespace pkmopt
