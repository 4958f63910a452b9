#include "models/leg_chain.hpp"

#include <Eigen/Eigenvalues>
#include <Eigen/LU>
#include <Eigen/SVD>
#include <algorithm>
#include <bit>
#include <cmath>
#include <numbers>
#include <sstream>
#include <stdexcept>

#include "models/hexapod.hpp"  // kSingularRcond, semi_regular_platform_joints
#include "models/linalg.hpp"
#include "models/pose_solver.hpp"
#include "models/require.hpp"

namespace pkmopt {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kPi = std::numbers::pi;
// A leg is serial-singular when |B_i| / scale_i is below this: near a branch point the closed-form
// IK (a square root of a difference) only gives B_i to about sqrt(eps).
constexpr double kSerialTolerance = 1e-7;
// A Schoenflies pose is on the platform's rotation set when R e is within this (rad) of e.
constexpr double kRotationTolerance = 1e-9;

using MatM = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, 6, 6>;
using VecM = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, 6, 1>;
using Mat3M = Eigen::Matrix<double, 3, Eigen::Dynamic, 0, 3, 6>;

std::string fmt_double(double v) {
  std::ostringstream os;
  os.precision(17);
  os << v;
  return os.str();
}

// Angle wrapped to (-pi, pi].
double wrap_angle(double a) {
  a = std::remainder(a, 2.0 * kPi);
  return a <= -kPi ? a + 2.0 * kPi : a;
}

double angle_between(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return std::atan2(a.cross(b).norm(), a.dot(b));
}

// Rotation of v about the unit axis w by angle a (Rodrigues).
Eigen::Vector3d rotate_about(const Eigen::Vector3d& w, double a, const Eigen::Vector3d& v) {
  return std::cos(a) * v + std::sin(a) * w.cross(v) + (1.0 - std::cos(a)) * w.dot(v) * w;
}

// 1 / cond(M) = sigma_min / sigma_max (0 if not finite). 3x3: from the eigenvalues of M^T M
// (closed form), with an SVD when the ratio is below 1e-3 (the squared matrix loses digits there,
// relative error ~ eps cond^2); other sizes: SVD.
double reciprocal_condition(const MatM& M) {
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

// Azimuth unit vector (cos phi, sin phi, 0).
Eigen::Vector3d radial(double phi) { return {std::cos(phi), std::sin(phi), 0.0}; }

}  // namespace

LegChainMachine::LegChainMachine(const LegChainDesign& design) : design_(design) {
  const int n = static_cast<int>(design_.legs.size());
  switch (design_.mobility) {
    case PlatformMobility::kSixDof:
      require(n == 6, "a 6-DOF leg-chain machine needs 6 legs, found " + std::to_string(n));
      dof_ = 6;
      first_rotational_dof_ = 3;
      break;
    case PlatformMobility::kTranslational:
      require(n == 3,
              "a 3-DOF translational leg-chain machine needs 3 legs, found " + std::to_string(n));
      dof_ = 3;
      first_rotational_dof_ = 3;
      break;
    case PlatformMobility::kSchoenflies:
      require(n == 4,
              "a Schoenflies (3T1R) leg-chain machine needs 4 legs, found " + std::to_string(n));
      require(design_.rotation_axis.allFinite() && design_.rotation_axis.norm() > 1e-12,
              "rotation_axis must be a non-zero finite vector");
      design_.rotation_axis.normalize();
      dof_ = 4;
      first_rotational_dof_ = 3;
      break;
    case PlatformMobility::kPlanarLegs:
      require(n == 3,
              "a planar-leg (3-PRS) leg-chain machine needs 3 legs, found " + std::to_string(n));
      dof_ = 3;
      first_rotational_dof_ = 1;
      break;
  }
  require(design_.tcp.allFinite(), "tool.tcp must be finite numbers");
  require(
      std::isfinite(design_.actuator_error) && design_.actuator_error >= 0.0,
      "actuator_error must be a finite number >= 0, found " + fmt_double(design_.actuator_error));
  require(design_.home.position.allFinite() && design_.home.angles.allFinite(),
          "the home pose must be finite");
  int revolute = 0;
  for (int i = 0; i < n; ++i) {
    LegChainLeg& leg = design_.legs[static_cast<std::size_t>(i)];
    const std::string name = "leg " + std::to_string(i + 1) + ": ";
    require(leg.base_point.allFinite() && leg.platform_point.allFinite() && leg.axis.allFinite() &&
                leg.crank_zero.allFinite(),
            name + "points and axes must be finite numbers");
    require(std::isfinite(leg.q_min) && std::isfinite(leg.q_max) && leg.q_min < leg.q_max,
            name + "the actuator range needs finite q_min < q_max, found [" +
                fmt_double(leg.q_min) + ", " + fmt_double(leg.q_max) + "]");
    require(leg.branch == 1 || leg.branch == -1, name + "branch must be +1 or -1");
    if (leg.kind == LegKind::kUPS) {
      require(leg.q_min > 0.0, name + "min_length must be > 0, found " + fmt_double(leg.q_min));
    } else {
      require(std::isfinite(leg.link_length) && leg.link_length > 0.0,
              name + "the link length must be a finite number > 0, found " +
                  fmt_double(leg.link_length));
      require(leg.axis.norm() > 1e-12, name + "the guide / crank axis must be non-zero");
      leg.axis.normalize();
    }
    if (leg.kind == LegKind::kRUS) {
      ++revolute;
      require(std::isfinite(leg.crank_length) && leg.crank_length > 0.0,
              name + "the crank length must be a finite number > 0, found " +
                  fmt_double(leg.crank_length));
      leg.crank_zero -= leg.crank_zero.dot(leg.axis) * leg.axis;
      require(leg.crank_zero.norm() > 1e-12,
              name + "the crank direction at q = 0 must not be along the crank axis");
      leg.crank_zero.normalize();
      require(leg.q_max - leg.q_min <= 2.0 * kPi + 1e-12,
              name + "the crank range must not exceed 360 degrees");
    }
    require(std::isfinite(leg.axial_stiffness) && leg.axial_stiffness >= 0.0 &&
                std::isfinite(leg.E) && leg.E >= 0.0 && std::isfinite(leg.area) &&
                leg.area >= 0.0 && std::isfinite(leg.actuator_stiffness) &&
                leg.actuator_stiffness >= 0.0 && leg.rods >= 1,
            name + "stiffness values must be finite numbers >= 0 (rods >= 1)");
    require(leg.axial_stiffness > 0.0 || (leg.E > 0.0 && leg.area > 0.0),
            name + "a link stiffness is needed: axial_stiffness > 0, or E > 0 and area > 0");
    require(!std::isnan(leg.base_max_angle) && leg.base_max_angle > 0.0 &&
                !std::isnan(leg.platform_max_angle) && leg.platform_max_angle > 0.0,
            name + "joint angle limits must be > 0");
    require(leg.base_axis.allFinite() && leg.base_axis.norm() > 1e-12 &&
                leg.platform_axis.allFinite() && leg.platform_axis.norm() > 1e-12,
            name + "joint axes must be non-zero finite vectors");
    leg.base_axis.normalize();
    leg.platform_axis.normalize();
    if (design_.mobility == PlatformMobility::kPlanarLegs) {
      require(leg.plane_normal.allFinite() && leg.plane_normal.norm() > 1e-12,
              name + "plane_normal must be a non-zero finite vector");
      leg.plane_normal.normalize();
      // The actuated point must move within the leg's plane.
      if (leg.kind == LegKind::kPUS) {
        require(std::abs(leg.plane_normal.dot(leg.axis)) <= 1e-9,
                name + "the guide axis must lie in the leg's plane (axis . plane_normal = 0)");
      } else if (leg.kind == LegKind::kRUS) {
        require(leg.plane_normal.cross(leg.axis).norm() <= 1e-9,
                name + "the crank axis must be parallel to plane_normal");
      }
    }
  }
  require(revolute == 0 || revolute == n, "legs must be all revolute or all prismatic");
  revolute_ = revolute == n;

  platform_rel_.resize(3, n);
  for (int i = 0; i < n; ++i) {
    platform_rel_.col(i) = design_.legs[static_cast<std::size_t>(i)].platform_point - design_.tcp;
  }
  // Mean leg vector at the home pose: the default FK start follows the actuated points.
  home_leg_offset_.setZero();
  Eigen::Vector3d home_p;
  Eigen::Matrix3d home_R;
  resolve_pose(design_.home, home_p, home_R);
  if (const auto q_home = inverse_kinematics(design_.home)) {
    for (int i = 0; i < n; ++i) {
      Eigen::Vector3d c, dc;
      actuated_point(i, (*q_home)(i), c, dc);
      home_leg_offset_ += home_p + home_R * platform_rel_.col(i) - c;
    }
    home_leg_offset_ /= n;
    home_ik_ok_ = true;
  }
  if (design_.characteristic_length) {
    const double L = *design_.characteristic_length;
    require(std::isfinite(L) && L > 0.0,
            "characteristic_length must be a finite number > 0, found " + fmt_double(L));
    characteristic_length_ = L;
  } else {
    characteristic_length_ = platform_rel_.colwise().norm().mean();
    if (first_rotational_dof_ < dof_) {
      require(characteristic_length_ > 0.0,
              "the platform joints all sit at the TCP; give characteristic_length");
    } else if (!(characteristic_length_ > 0.0)) {
      characteristic_length_ = 1.0;  // unused: no rotational DOF
    }
  }
}

std::unique_ptr<MachineData> LegChainMachine::make_data() const {
  auto d = std::make_unique<LegChainData>();
  const int n = num_actuators();
  d->s.resize(3, n);
  d->r.resize(3, n);
  d->c.resize(3, n);
  d->q.resize(n);
  d->B.resize(n);
  d->A.resize(n, n);
  d->T.resize(6, n);
  d->k.resize(n);
  return d;
}

bool LegChainMachine::twist_jacobian(MachineData& data, const Pose& pose,
                                     Eigen::MatrixXd& J) const {
  auto& d = static_cast<LegChainData&>(data);
  compute_kinematics(d, pose);
  const int n = num_actuators();
  if (!d.ik_ok || (d.B.array() == 0.0).any()) return false;
  J.resize(n, 6);
  for (int i = 0; i < n; ++i) {
    J.row(i).head<3>() = d.s.col(i).transpose() / d.B(i);
    J.row(i).tail<3>() = d.r.col(i).cross(d.s.col(i)).transpose() / d.B(i);
  }
  return J.allFinite();
}

void LegChainMachine::actuated_point(int i, double q, Eigen::Vector3d& c,
                                     Eigen::Vector3d& dc) const {
  const LegChainLeg& leg = design_.legs[static_cast<std::size_t>(i)];
  switch (leg.kind) {
    case LegKind::kUPS:
      c = leg.base_point;
      dc.setZero();
      break;
    case LegKind::kPUS:
      c = leg.base_point + q * leg.axis;
      dc = leg.axis;
      break;
    case LegKind::kRUS: {
      const Eigen::Vector3d n0 = leg.axis.cross(leg.crank_zero);
      const Eigen::Vector3d crank =
          leg.crank_length * (std::cos(q) * leg.crank_zero + std::sin(q) * n0);
      c = leg.base_point + crank;
      dc = leg.axis.cross(crank);
      break;
    }
  }
}

double LegChainMachine::leg_ik(int i, const Eigen::Vector3d& P, bool& ok) const {
  const LegChainLeg& leg = design_.legs[static_cast<std::size_t>(i)];
  const Eigen::Vector3d d = P - leg.base_point;
  const double L = leg.link_length;
  ok = true;
  switch (leg.kind) {
    case LegKind::kUPS:
      return d.norm();
    case LegKind::kPUS: {
      // |d - q u| = L:  q = t -+ sqrt(t^2 - |d|^2 + L^2), t = u.d; B = s.u = (t - q) / L.
      const double t = leg.axis.dot(d);
      const double disc = t * t - d.squaredNorm() + L * L;
      if (!(disc >= 0.0)) {
        ok = false;
        return std::isfinite(t) ? t : 0.0;
      }
      return t - leg.branch * std::sqrt(disc);
    }
    case LegKind::kRUS: {
      // E cos q + F sin q = G with E = d.d0, F = d.n0, G = (|d|^2 + r^2 - L^2) / (2 r);
      // q = phi -+ acos(G / hypot(E, F)), phi = atan2(F, E); B = -r hypot(E,F) sin(q - phi).
      const Eigen::Vector3d n0 = leg.axis.cross(leg.crank_zero);
      const double E = d.dot(leg.crank_zero);
      const double F = d.dot(n0);
      const double r = leg.crank_length;
      const double G = (d.squaredNorm() + r * r - L * L) / (2.0 * r);
      const double H = std::hypot(E, F);
      const double phi = std::atan2(F, E);
      double ratio = H > 0.0 ? G / H : (G >= 0.0 ? kInf : -kInf);
      if (!(ratio >= -1.0 && ratio <= 1.0)) {
        ok = false;
        ratio = ratio > 1.0 ? 1.0 : -1.0;  // the closest the elbow gets
      }
      const double q = wrap_angle(phi - leg.branch * std::acos(ratio));
      return std::isfinite(q) ? q : 0.0;
    }
  }
  return 0.0;
}

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

void LegChainMachine::compute_kinematics(LegChainData& d, const Pose& pose) const {
  const int n = num_actuators();
  Eigen::Vector3d position;
  Eigen::Matrix3d R;
  d.pose_ok = resolve_pose(pose, position, R);
  d.position = position;
  d.rotation = R;
  d.ik_ok = d.pose_ok || design_.mobility != PlatformMobility::kPlanarLegs;
  d.constraint_singular = false;
  Eigen::Matrix<double, Eigen::Dynamic, 6, 0, 6, 6> a_full(n, 6);
  for (int i = 0; i < n; ++i) {
    const Eigen::Vector3d ri = R * platform_rel_.col(i);
    const Eigen::Vector3d P = position + ri;
    bool ok = true;
    const double qi = leg_ik(i, P, ok);
    d.ik_ok = d.ik_ok && ok;
    Eigen::Vector3d c, dc;
    actuated_point(i, qi, c, dc);
    const Eigen::Vector3d l = P - c;
    const double len = l.norm();
    const Eigen::Vector3d si = len > 0.0 ? Eigen::Vector3d(l / len) : Eigen::Vector3d::Zero();
    if (!(len > 0.0)) d.ik_ok = false;
    d.q(i) = qi;
    d.r.col(i) = ri;
    d.c.col(i) = c;
    d.s.col(i) = si;
    const LegChainLeg& leg = design_.legs[static_cast<std::size_t>(i)];
    d.B(i) = leg.kind == LegKind::kUPS ? 1.0 : si.dot(dc);
    a_full.block(i, 0, 1, 3) = si.transpose();
    a_full.block(i, 3, 1, 3) = ri.cross(si).transpose();
  }
  // A = a_full T on the platform DOF.
  switch (design_.mobility) {
    case PlatformMobility::kSixDof:
      d.T.setIdentity(6, 6);
      d.A = a_full;
      break;
    case PlatformMobility::kTranslational:
      d.T.setZero(6, 3);
      d.T.topRows(3).setIdentity();
      d.A = a_full.leftCols(3);
      break;
    case PlatformMobility::kSchoenflies:
      d.T.setZero(6, 4);
      d.T.topLeftCorner(3, 3).setIdentity();
      d.T.block(3, 3, 3, 1) = design_.rotation_axis;
      d.A.leftCols(3) = a_full.leftCols(3);
      d.A.col(3) = a_full.rightCols(3) * design_.rotation_axis;
      break;
    case PlatformMobility::kPlanarLegs:
      if (!planar_twist_map(position, R, d.T)) {
        d.constraint_singular = true;
        d.T.setZero(6, 3);
        d.T(2, 0) = d.T(3, 1) = d.T(4, 2) = 1.0;
      }
      d.A = a_full * d.T;
      break;
  }
  // Serial singularity: |B_i| small relative to its scale (1 for UPS/PUS, r_i for RUS).
  d.serial_singular = false;
  d.det_b = 1.0;
  for (int i = 0; i < n; ++i) {
    const LegChainLeg& leg = design_.legs[static_cast<std::size_t>(i)];
    const double scale = leg.kind == LegKind::kRUS ? leg.crank_length : 1.0;
    if (!(std::abs(d.B(i)) >= kSerialTolerance * scale)) d.serial_singular = true;
    d.det_b *= d.B(i);
  }
}

Eigen::MatrixXd LegChainMachine::twist_map(const Pose& pose) const {
  const auto data = make_data();
  auto& d = static_cast<LegChainData&>(*data);
  compute_kinematics(d, pose);
  return d.T;
}

void LegChainMachine::jacobians(const Pose& pose, Eigen::MatrixXd& A, Eigen::MatrixXd& B,
                                Eigen::MatrixXd& J) const {
  LegChainData d;
  const int n = num_actuators();
  d.s.resize(3, n);
  d.r.resize(3, n);
  d.c.resize(3, n);
  d.q.resize(n);
  d.B.resize(n);
  d.A.resize(n, n);
  d.T.resize(6, n);
  d.k.resize(n);
  compute_kinematics(d, pose);
  A = d.A;
  B = d.B.asDiagonal();
  if ((d.B.array() == 0.0).any()) {
    J.resize(0, 0);
  } else {
    J = d.B.cwiseInverse().asDiagonal() * d.A;
  }
}

bool LegChainMachine::reachable_from_kinematics(const LegChainData& d, const Pose& /*pose*/) const {
  if (!d.ik_ok || !d.pose_ok) return false;
  const Eigen::Matrix3d& R = d.rotation;
  for (int i = 0; i < num_actuators(); ++i) {
    const LegChainLeg& leg = design_.legs[static_cast<std::size_t>(i)];
    if (!(d.q(i) >= leg.q_min && d.q(i) <= leg.q_max)) return false;
    if (std::isfinite(leg.base_max_angle)) {
      const Eigen::Vector3d axis =
          leg.kind == LegKind::kRUS ? rotate_about(leg.axis, d.q(i), leg.base_axis) : leg.base_axis;
      if (angle_between(d.s.col(i), axis) > leg.base_max_angle) return false;
    }
    if (std::isfinite(leg.platform_max_angle) &&
        angle_between(-d.s.col(i), R * leg.platform_axis) > leg.platform_max_angle) {
      return false;
    }
  }
  return true;
}

bool LegChainMachine::reachable(MachineData& data, const Pose& pose) const {
  auto& d = static_cast<LegChainData&>(data);
  compute_kinematics(d, pose);
  return reachable_from_kinematics(d, pose);
}

void LegChainMachine::joint_angles(const Pose& pose, Eigen::VectorXd& base_angles,
                                   Eigen::VectorXd& platform_angles) const {
  const auto data = make_data();
  auto& d = static_cast<LegChainData&>(*data);
  compute_kinematics(d, pose);
  const Eigen::Matrix3d R = d.rotation;
  const int n = num_actuators();
  base_angles.resize(n);
  platform_angles.resize(n);
  for (int i = 0; i < n; ++i) {
    const LegChainLeg& leg = design_.legs[static_cast<std::size_t>(i)];
    const Eigen::Vector3d axis =
        leg.kind == LegKind::kRUS ? rotate_about(leg.axis, d.q(i), leg.base_axis) : leg.base_axis;
    base_angles(i) = angle_between(d.s.col(i), axis);
    platform_angles(i) = angle_between(-d.s.col(i), R * leg.platform_axis);
  }
}

std::optional<Eigen::VectorXd> LegChainMachine::inverse_kinematics(const Pose& pose) const {
  Eigen::Vector3d p;
  Eigen::Matrix3d R;
  if (!resolve_pose(pose, p, R) && design_.mobility == PlatformMobility::kPlanarLegs) {
    return std::nullopt;
  }
  Eigen::VectorXd q(num_actuators());
  for (int i = 0; i < num_actuators(); ++i) {
    bool ok = true;
    q(i) = leg_ik(i, p + R * platform_rel_.col(i), ok);
    if (!ok) return std::nullopt;
  }
  return q;
}

void LegChainMachine::analyze(MachineData& data, const Pose& pose, const Wrench& wrench,
                              PoseMetrics& out) const {
  auto& d = static_cast<LegChainData&>(data);
  const int n = num_actuators();
  compute_kinematics(d, pose);
  out.reachable = reachable_from_kinematics(d, pose);
  out.q = d.q;

  // Axial stiffness of every leg at its platform point: actuator and link in series.
  for (int i = 0; i < n; ++i) {
    const LegChainLeg& leg = design_.legs[static_cast<std::size_t>(i)];
    const double length = leg.kind == LegKind::kUPS ? d.q(i) : leg.link_length;
    double compliance = leg.axial_stiffness > 0.0 ? 1.0 / leg.axial_stiffness
                                                  : length / (leg.E * leg.area * leg.rods);
    if (leg.actuator_stiffness > 0.0) compliance += d.B(i) * d.B(i) / leg.actuator_stiffness;
    d.k(i) = compliance > 0.0 ? 1.0 / compliance : kInf;
  }

  // Parallel singularity from the conditioning of A_h = A diag(1, 1/L) (the part of J_h that
  // does not depend on the actuators).
  MatM Ah = d.A;
  Ah.rightCols(n - first_rotational_dof_) /= characteristic_length_;
  const Eigen::PartialPivLU<MatM> lu_a(d.A);
  d.det_a = std::isfinite(lu_a.determinant()) ? lu_a.determinant() : 0.0;
  const double rcond_a = reciprocal_condition(Ah);
  d.parallel_singular = !(rcond_a >= kSingularRcond) || d.det_a == 0.0 || d.constraint_singular;

  double rcond = 0.0;
  if (!d.serial_singular && !d.parallel_singular) {
    const MatM Jh = d.B.cwiseInverse().asDiagonal() * Ah;
    rcond = reciprocal_condition(Jh);
  }
  const double det_j = d.det_b != 0.0 ? d.det_a / d.det_b : 0.0;
  out.det_j = std::isfinite(det_j) ? det_j : 0.0;
  out.singular = d.serial_singular || d.parallel_singular || !(rcond >= kSingularRcond) || !d.ik_ok;
  if (out.singular) {
    out.singularity_margin = 0.0;
    out.stiffness_min = 0.0;
    out.tau = VecM::Constant(n, kInf);
    out.tcp_error_max = kInf;
    return;
  }
  out.singularity_margin = rcond;

  // Generalised force on the platform DOF: T^T w.
  VecM w_dof(n);
  if (design_.mobility == PlatformMobility::kSixDof ||
      design_.mobility == PlatformMobility::kTranslational) {
    w_dof = wrench.head(n);
  } else {
    w_dof = d.T.transpose() * wrench;
  }
  // Rod forces f = A^-T w_dof; tau_i = B_i f_i.
  const VecM f = lu_a.transpose().solve(w_dof);
  out.tau = d.B.cwiseProduct(f).array() + 0.0;  // + 0.0: no negative zeros in files

  // T_t A^-1 (T_t: the translational rows of T) gives the TCP displacement per unit axial
  // displacement.
  const MatM Ainv = lu_a.inverse();
  Eigen::Matrix<double, 3, Eigen::Dynamic, 0, 3, 6> P(3, n);
  if (design_.mobility == PlatformMobility::kPlanarLegs) {
    P = d.T.topRows(3) * Ainv;
  } else {
    P = Ainv.topRows(3);
  }
  const Mat3M Pk = P * d.k.cwiseInverse().asDiagonal();
  Mat3<double> Ctt = Pk * P.transpose();
  Eigen::SelfAdjointEigenSolver<Mat3<double>> eig3;
  eig3.computeDirect(Ctt, Eigen::EigenvaluesOnly);
  const double c_max = eig3.eigenvalues()(2);
  out.stiffness_min = c_max > 0.0 ? 1.0 / c_max : kInf;

  // tcp_error_max: dx = A^-1 B dq; the largest |position part| over the box vertices.
  const Mat3M E = P * d.B.asDiagonal();
  out.tcp_error_max = design_.actuator_error * max_norm_over_sign_vectors(E);
  d.compliance_tt = Ctt;
  d.error_map = design_.actuator_error * E;
  if (!std::isfinite(out.stiffness_min) || !out.tau.allFinite() ||
      !std::isfinite(out.tcp_error_max)) {
    out.singular = true;
    out.singularity_margin = 0.0;
    out.stiffness_min = 0.0;
    out.tau = VecM::Constant(n, kInf);
    out.tcp_error_max = kInf;
  }
}

bool LegChainMachine::translational_maps(
    MachineData& data, const Pose& pose, const Wrench& wrench, PoseMetrics& metrics,
    Eigen::Matrix3d& compliance_tt, Eigen::Matrix<double, 3, Eigen::Dynamic>& error_map) const {
  auto& d = static_cast<LegChainData&>(data);
  analyze(d, pose, wrench, metrics);
  if (metrics.singular) return false;
  compliance_tt = d.compliance_tt;
  error_map = d.error_map;
  return true;
}

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

std::optional<Eigen::AlignedBox3d> LegChainMachine::workspace_search_box(
    const std::vector<Eigen::Matrix3d>& orientations) const {
  // Leg i keeps its platform point P_i within reach of the set of its actuated points:
  //   UPS: ball of radius q_max about a_i; PUS: within L_i of the guide segment;
  //   RUS: within r_i + L_i of the pivot. The TCP is P_i - R (b_i - tcp).
  Eigen::AlignedBox3d united;
  const int n = num_actuators();
  for (const Eigen::Matrix3d& R_in : orientations) {
    // The rotation the platform takes for R_in (projected for 3- and 4-DOF platforms).
    Pose asked{Eigen::Vector3d::Zero(), angles_from_rotation(R_in)};
    Eigen::Vector3d p_actual;
    Eigen::Matrix3d R;
    if (!resolve_pose(asked, p_actual, R) && design_.mobility == PlatformMobility::kPlanarLegs) {
      continue;
    }
    Eigen::AlignedBox3d box(Eigen::Vector3d::Constant(-kInf), Eigen::Vector3d::Constant(kInf));
    for (int i = 0; i < n; ++i) {
      const LegChainLeg& leg = design_.legs[static_cast<std::size_t>(i)];
      const Eigen::Vector3d offset = -R * platform_rel_.col(i);
      Eigen::AlignedBox3d leg_box;
      switch (leg.kind) {
        case LegKind::kUPS: {
          const Eigen::Vector3d reach = Eigen::Vector3d::Constant(leg.q_max);
          leg_box = Eigen::AlignedBox3d(leg.base_point - reach, leg.base_point + reach);
          break;
        }
        case LegKind::kPUS: {
          const Eigen::Vector3d reach = Eigen::Vector3d::Constant(leg.link_length);
          const Eigen::Vector3d a = leg.base_point + leg.q_min * leg.axis;
          const Eigen::Vector3d b = leg.base_point + leg.q_max * leg.axis;
          leg_box = Eigen::AlignedBox3d(a.cwiseMin(b) - reach, a.cwiseMax(b) + reach);
          break;
        }
        case LegKind::kRUS: {
          const Eigen::Vector3d reach =
              Eigen::Vector3d::Constant(leg.crank_length + leg.link_length);
          leg_box = Eigen::AlignedBox3d(leg.base_point - reach, leg.base_point + reach);
          break;
        }
      }
      leg_box.translate(offset);
      box = box.intersection(leg_box);
    }
    if (design_.mobility == PlatformMobility::kPlanarLegs && !box.isEmpty()) {
      // x and y are parasitic (the given ones are ignored): the box is the parasitic x, y at the
      // ends of the z range (one point for vertical leg planes).
      Eigen::AlignedBox3d planar;
      for (const double z : {box.min().z(), box.max().z()}) {
        asked.position.z() = z;
        if (resolve_pose(asked, p_actual, R)) planar.extend(p_actual);
      }
      if (planar.isEmpty()) continue;
      box.min().head<2>() = planar.min().head<2>();
      box.max().head<2>() = planar.max().head<2>();
    }
    if (!box.isEmpty()) united.extend(box);
    if (design_.mobility == PlatformMobility::kTranslational) break;
  }
  return united;
}

std::optional<double> LegChainMachine::envelope_volume() const {
  // Vertical cylinder about the centroid of the actuated points' reach: radius the largest
  // horizontal distance an actuated point reaches (stroke ends, crank circle), height the z
  // extent of those points plus the longest link (UPS: max_length).
  std::vector<Eigen::Vector3d> points;
  double link = 0.0;
  for (const LegChainLeg& leg : design_.legs) {
    switch (leg.kind) {
      case LegKind::kUPS:
        points.push_back(leg.base_point);
        link = std::max(link, leg.q_max);
        break;
      case LegKind::kPUS:
        points.push_back(leg.base_point + leg.q_min * leg.axis);
        points.push_back(leg.base_point + leg.q_max * leg.axis);
        link = std::max(link, leg.link_length);
        break;
      case LegKind::kRUS: {
        const Eigen::Vector3d n0 = leg.axis.cross(leg.crank_zero);
        for (int k = 0; k < 72; ++k) {
          const double a = 2.0 * kPi * k / 72.0;
          points.push_back(leg.base_point +
                           leg.crank_length * (std::cos(a) * leg.crank_zero + std::sin(a) * n0));
        }
        link = std::max(link, leg.link_length);
        break;
      }
    }
  }
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  for (const auto& p : points) centroid += p;
  centroid /= static_cast<double>(points.size());
  double radius = 0.0, zmin = kInf, zmax = -kInf;
  for (const auto& p : points) {
    radius = std::max(radius, (p - centroid).head<2>().norm());
    zmin = std::min(zmin, p.z());
    zmax = std::max(zmax, p.z());
  }
  return kPi * radius * radius * (zmax - zmin + link);
}

std::unique_ptr<Machine> make_leg_chain_machine(const LegChainDesign& design) {
  return std::make_unique<LegChainMachine>(design);
}

// ------------------------------------------------------------------------------------------
// Named models.

namespace {

void apply_stiffness(LegChainLeg& leg, const LinkStiffness& k, int rods) {
  leg.axial_stiffness = k.axial_stiffness;
  leg.E = k.E;
  leg.area = k.area;
  leg.rods = rods;
  leg.actuator_stiffness = k.actuator_stiffness;
}

}  // namespace

LegChainDesign delta_design(const DeltaDesign& p) {
  require(std::isfinite(p.base_radius) && p.base_radius >= 0.0,
          "base_radius must be a finite number >= 0");
  require(std::isfinite(p.platform_radius) && p.platform_radius >= 0.0,
          "platform_radius must be a finite number >= 0");
  LegChainDesign d;
  d.model = "delta";
  d.mobility = PlatformMobility::kTranslational;
  for (int i = 0; i < 3; ++i) {
    const double phi = deg_to_rad(-90.0 + 120.0 * i);
    const Eigen::Vector3d u = radial(phi);
    LegChainLeg leg;
    leg.kind = LegKind::kRUS;
    leg.base_point = p.base_radius * u;
    leg.crank_zero = u;
    // n0 = w x d0 must be -z (positive theta lowers the elbow): w = d0 x n0 = u x (-z).
    leg.axis = u.cross(-Eigen::Vector3d::UnitZ());
    leg.crank_length = p.upper_arm;
    leg.link_length = p.rod;
    leg.platform_point = p.platform_radius * u;
    leg.q_min = p.theta_min;
    leg.q_max = p.theta_max;
    leg.branch = p.branch;
    apply_stiffness(leg, p.stiffness, 2);
    leg.base_max_angle = p.elbow_max_angle;
    leg.platform_max_angle = p.platform_max_angle;
    leg.base_axis = -Eigen::Vector3d::UnitZ();     // crank frame at theta = 0: down
    leg.platform_axis = Eigen::Vector3d::UnitZ();  // -s_i points up at the platform
    d.legs.push_back(leg);
  }
  d.tcp = p.tcp;
  d.characteristic_length = p.characteristic_length;
  d.actuator_error = p.actuator_error;
  // Home: the platform straight below with the cranks horizontal (if the rods reach).
  const double dr = p.base_radius + p.upper_arm - p.platform_radius;
  const double h2 = p.rod * p.rod - dr * dr;
  d.home.position = Eigen::Vector3d(0, 0, -(h2 > 0.0 ? std::sqrt(h2) : p.rod)) + p.tcp;
  return d;
}

std::unique_ptr<Machine> make_delta(const DeltaDesign& d) {
  return make_leg_chain_machine(delta_design(d));
}

LegChainDesign linear_delta_design(const LinearDeltaDesign& p) {
  require(std::isfinite(p.inclination) && std::abs(p.inclination) < kPi / 2,
          "the guide inclination must be within (-90, 90) degrees");
  LegChainDesign d;
  d.model = "linear_delta";
  d.mobility = PlatformMobility::kTranslational;
  for (int i = 0; i < 3; ++i) {
    const double phi = deg_to_rad(-90.0 + 120.0 * i);
    const Eigen::Vector3d u = radial(phi);
    LegChainLeg leg;
    leg.kind = LegKind::kPUS;
    leg.base_point = p.guide_radius * u;
    // Upwards along the guide, leaning towards the centre by the inclination.
    leg.axis = std::cos(p.inclination) * Eigen::Vector3d::UnitZ() - std::sin(p.inclination) * u;
    leg.link_length = p.rod;
    leg.platform_point = p.platform_radius * u;
    leg.q_min = p.q_min;
    leg.q_max = p.q_max;
    leg.branch = -1;  // carriage above the platform point: q > u.d, B_i < 0
    apply_stiffness(leg, p.stiffness, 2);
    leg.base_max_angle = p.carriage_max_angle;
    leg.platform_max_angle = p.platform_max_angle;
    leg.base_axis = -Eigen::Vector3d::UnitZ();
    leg.platform_axis = Eigen::Vector3d::UnitZ();
    d.legs.push_back(leg);
  }
  d.tcp = p.tcp;
  d.characteristic_length = p.characteristic_length;
  d.actuator_error = p.actuator_error;
  // Home: the carriages at mid-stroke, platform straight below them.
  const double qm = 0.5 * (p.q_min + p.q_max);
  const Eigen::Vector3d carriage = d.legs[0].base_point + qm * d.legs[0].axis;
  const double dr = carriage.head<2>().norm() - p.platform_radius;
  const double h2 = p.rod * p.rod - dr * dr;
  d.home.position =
      Eigen::Vector3d(0, 0, carriage.z() - (h2 > 0.0 ? std::sqrt(h2) : p.rod)) + p.tcp;
  return d;
}

std::unique_ptr<Machine> make_linear_delta(const LinearDeltaDesign& d) {
  return make_leg_chain_machine(linear_delta_design(d));
}

HexaglideDesign::HexaglideDesign()
    : platform_joints(Eigen::AngleAxisd(kPi / 2, Eigen::Vector3d::UnitZ()).toRotationMatrix() *
                      semi_regular_platform_joints(0.25, 20.0 * kDegToRad)) {
  for (int i = 0; i < 6; ++i) {
    const double y = platform_joints(1, i);
    guide_y[static_cast<std::size_t>(i)] = y + (y >= 0.0 ? 0.3 : -0.3);
  }
}

LegChainDesign hexaglide_design(const HexaglideDesign& p) {
  require(std::isfinite(p.inclination) && std::abs(p.inclination) < kPi / 2,
          "the guide inclination must be within (-90, 90) degrees");
  LegChainDesign d;
  d.model = "hexaglide";
  d.mobility = PlatformMobility::kSixDof;
  const Eigen::Vector3d u(std::cos(p.inclination), 0.0, std::sin(p.inclination));
  for (int i = 0; i < 6; ++i) {
    LegChainLeg leg;
    leg.kind = LegKind::kPUS;
    leg.base_point = Eigen::Vector3d(0.0, p.guide_y[static_cast<std::size_t>(i)],
                                     p.guide_z[static_cast<std::size_t>(i)]);
    leg.axis = u;
    leg.link_length = p.strut;
    leg.platform_point = p.platform_joints.col(i);
    leg.q_min = p.q_min;
    leg.q_max = p.q_max;
    // Carriage on the far side of its platform joint: x_c < x_P (q < u.d, B > 0) for b.x < 0.
    leg.branch = p.platform_joints(0, i) < 0.0 ? 1 : -1;
    apply_stiffness(leg, p.stiffness, 1);
    leg.base_max_angle = p.carriage_max_angle;
    leg.platform_max_angle = p.platform_max_angle;
    leg.base_axis = Eigen::Vector3d::UnitZ();
    leg.platform_axis = -Eigen::Vector3d::UnitZ();
    d.legs.push_back(leg);
  }
  d.tcp = p.tcp;
  d.characteristic_length = p.characteristic_length;
  d.actuator_error = p.actuator_error;
  d.home.position = Eigen::Vector3d(0, 0, p.home_height);
  return d;
}

std::unique_ptr<Machine> make_hexaglide(const HexaglideDesign& d) {
  return make_leg_chain_machine(hexaglide_design(d));
}

LegChainDesign tripod_3prs_design(const Tripod3PrsDesign& p) {
  require(std::isfinite(p.base_radius) && p.base_radius > 0.0,
          "base_radius must be a finite number > 0");
  require(std::isfinite(p.platform_radius) && p.platform_radius > 0.0,
          "platform_radius must be a finite number > 0");
  require(std::isfinite(p.tool_length), "tool_length must be a finite number");
  LegChainDesign d;
  d.model = "tripod_3prs";
  d.mobility = PlatformMobility::kPlanarLegs;
  for (int i = 0; i < 3; ++i) {
    const double phi = deg_to_rad(-90.0 + 120.0 * i);
    const Eigen::Vector3d u = radial(phi);
    LegChainLeg leg;
    leg.kind = LegKind::kPUS;
    leg.base_point = p.base_radius * u;
    leg.axis = Eigen::Vector3d::UnitZ();
    leg.link_length = p.strut;
    leg.platform_point = p.platform_radius * u;
    leg.q_min = p.q_min;
    leg.q_max = p.q_max;
    leg.branch = 1;  // platform point on the +z side of the carriage: B_i = s_i . z > 0
    apply_stiffness(leg, p.stiffness, 1);
    leg.base_max_angle = p.revolute_max_angle;
    leg.platform_max_angle = p.platform_max_angle;
    leg.base_axis = Eigen::Vector3d::UnitZ();
    leg.platform_axis = -Eigen::Vector3d::UnitZ();
    leg.plane_normal = Eigen::Vector3d::UnitZ().cross(u);  // tangential
    d.legs.push_back(leg);
  }
  d.tcp = Eigen::Vector3d(0, 0, p.tool_length);
  d.characteristic_length = p.characteristic_length;
  d.actuator_error = p.actuator_error;
  // Home: level platform, carriages at mid-stroke.
  const double dr = p.base_radius - p.platform_radius;
  const double h2 = p.strut * p.strut - dr * dr;
  d.home.position =
      Eigen::Vector3d(0, 0, 0.5 * (p.q_min + p.q_max) + (h2 > 0.0 ? std::sqrt(h2) : p.strut)) +
      d.tcp;
  return d;
}

std::unique_ptr<Machine> make_tripod_3prs(const Tripod3PrsDesign& d) {
  return make_leg_chain_machine(tripod_3prs_design(d));
}

std::string LegChainMachine::actuator_coordinates_requirement(const Eigen::VectorXd& q) const {
  // Carriage positions and crank angles may take any sign; UPS legs are lengths.
  for (int i = 0; i < num_actuators() && i < q.size(); ++i) {
    if (design_.legs[static_cast<std::size_t>(i)].kind == LegKind::kUPS && !(q(i) > 0.0))
      return "leg lengths > 0 (m) for the UPS legs";
  }
  return {};
}

}  // namespace pkmopt
