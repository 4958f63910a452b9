// The generic leg-chain machine: design validation, per-leg IK, kinematics (A, B, T),
// Jacobians, reachability and the per-pose metrics (stiffness, singularity, forces, TCP error).
#include "models/leg_chain/leg_chain.hpp"

#include <Eigen/Eigenvalues>
#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "models/core/linalg.hpp"
#include "models/core/machine.hpp"
#include "models/core/require.hpp"
#include "models/leg_chain/leg_chain_detail.hpp"
#include "models/stiffness/compliance_metrics.hpp"

namespace pkmopt {
namespace {

using detail::angle_between;
using detail::kInf;
using detail::kPi;
using detail::Mat3M;
using detail::MatM;
using detail::reciprocal_condition;
using detail::VecM;
using detail::wrap_angle;

// A leg is serial-singular when |B_i| / scale_i is below this: near a branch point the closed-form
// IK (a square root of a difference) only gives B_i to about sqrt(eps).
constexpr double kSerialTolerance = 1e-7;

std::string fmt_double(double v) {
  std::ostringstream os;
  os.precision(17);
  os << v;
  return os.str();
}

// Rotation of v about the unit axis w by angle a (Rodrigues).
Eigen::Vector3d rotate_about(const Eigen::Vector3d& w, double a, const Eigen::Vector3d& v) {
  return std::cos(a) * v + std::sin(a) * w.cross(v) + (1.0 - std::cos(a)) * w.dot(v) * w;
}

}  // namespace

namespace {

// Checks leg i (0-based) of a design and normalises its axes and crank direction; throws
// std::invalid_argument naming the leg and the field.
void check_leg(LegChainLeg& leg, int i, PlatformMobility mobility) {
  const std::string name = "leg " + std::to_string(i + 1) + ": ";
  require(leg.base_point.allFinite() && leg.platform_point.allFinite() && leg.axis.allFinite() &&
              leg.crank_zero.allFinite(),
          name + "points and axes must be finite numbers");
  require(std::isfinite(leg.q_min) && std::isfinite(leg.q_max) && leg.q_min < leg.q_max,
          name + "the actuator range needs finite q_min < q_max, found [" + fmt_double(leg.q_min) +
              ", " + fmt_double(leg.q_max) + "]");
  require(leg.branch == 1 || leg.branch == -1, name + "branch must be +1 or -1");
  if (leg.kind == LegKind::kUPS) {
    require(leg.q_min > 0.0, name + "min_length must be > 0, found " + fmt_double(leg.q_min));
  } else {
    require(
        std::isfinite(leg.link_length) && leg.link_length > 0.0,
        name + "the link length must be a finite number > 0, found " + fmt_double(leg.link_length));
    require(leg.axis.norm() > 1e-12, name + "the guide / crank axis must be non-zero");
    leg.axis.normalize();
  }
  if (leg.kind == LegKind::kRUS) {
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
              std::isfinite(leg.E) && leg.E >= 0.0 && std::isfinite(leg.area) && leg.area >= 0.0 &&
              std::isfinite(leg.actuator_stiffness) && leg.actuator_stiffness >= 0.0 &&
              leg.rods >= 1,
          name + "stiffness values must be finite numbers >= 0 (rods >= 1)");
  require(leg.axial_stiffness > 0.0 || (leg.E > 0.0 && leg.area > 0.0) || leg.link_section,
          name +
              "a link stiffness is needed: axial_stiffness > 0, or E > 0 and area > 0, or a "
              "link_section");
  require(std::isfinite(leg.base_joint_stiffness) && leg.base_joint_stiffness >= 0.0 &&
              std::isfinite(leg.platform_joint_stiffness) && leg.platform_joint_stiffness >= 0.0,
          name + "joint stiffnesses must be finite numbers >= 0");
  check_screw_drive(leg.drive, name + "drive", leg.kind == LegKind::kRUS);
  require(!std::isnan(leg.base_max_angle) && leg.base_max_angle > 0.0 &&
              !std::isnan(leg.platform_max_angle) && leg.platform_max_angle > 0.0,
          name + "joint angle limits must be > 0");
  require(leg.base_axis.allFinite() && leg.base_axis.norm() > 1e-12 &&
              leg.platform_axis.allFinite() && leg.platform_axis.norm() > 1e-12,
          name + "joint axes must be non-zero finite vectors");
  leg.base_axis.normalize();
  leg.platform_axis.normalize();
  if (mobility == PlatformMobility::kPlanarLegs) {
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
  check_link_shapes(design_);
  require(
      std::isfinite(design_.actuator_error) && design_.actuator_error >= 0.0,
      "actuator_error must be a finite number >= 0, found " + fmt_double(design_.actuator_error));
  require(design_.home.position.allFinite() && design_.home.angles.allFinite(),
          "the home pose must be finite");
  int revolute = 0;
  for (int i = 0; i < n; ++i) {
    LegChainLeg& leg = design_.legs[static_cast<std::size_t>(i)];
    check_leg(leg, i, design_.mobility);
    if (leg.kind == LegKind::kRUS) ++revolute;
  }
  require(revolute == 0 || revolute == n, "legs must be all revolute or all prismatic");
  revolute_ = revolute == n;
  validate_link_compliance();
  if (design_.masses.present) check_mass_model(design_.masses, "masses.");

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
  auto d = new_data<LegChainData>();
  const int n = num_actuators();
  d->s.resize(3, n);
  d->r.resize(3, n);
  d->c.resize(3, n);
  d->q.resize(n);
  d->B.resize(n);
  d->A.resize(n, n);
  d->T.resize(6, n);
  d->k.resize(n);
  d->actuator_compliance.resize(n);
  d->link_compliance.resize(n);
  return d;
}

bool LegChainMachine::twist_jacobian(MachineData& data, const Pose& pose,
                                     Eigen::MatrixXd& J) const {
  auto& d = data_of<LegChainData>(data);
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
  auto& d = data_of<LegChainData>(*data);
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

std::optional<double> LegChainMachine::reach_excess(const Pose& pose) const {
  const std::optional<Eigen::VectorXd> q = inverse_kinematics(pose);
  if (!q) return std::nullopt;
  Eigen::VectorXd base_angles, platform_angles;
  joint_angles(pose, base_angles, platform_angles);
  double excess = 0.0;
  for (int i = 0; i < num_actuators(); ++i) {
    const LegChainLeg& leg = design_.legs[static_cast<std::size_t>(i)];
    excess = std::max({excess, leg.q_min - (*q)(i), (*q)(i)-leg.q_max});
    if (std::isfinite(leg.base_max_angle))
      excess = std::max(excess, base_angles(i) - leg.base_max_angle);
    if (std::isfinite(leg.platform_max_angle))
      excess = std::max(excess, platform_angles(i) - leg.platform_max_angle);
  }
  // The links' interference: how far they are closer than min_clearance (m).
  if (checks_leg_interference())
    excess = std::max(excess, design_.shapes.min_clearance - leg_clearance(pose).value);
  return excess;
}

Eigen::MatrixXd LegChainMachine::twist_basis(const MachineData& data) const {
  return data_of<LegChainData>(data).T;
}

bool LegChainMachine::reachable(MachineData& data, const Pose& pose) const {
  auto& d = data_of<LegChainData>(data);
  compute_kinematics(d, pose);
  return reachable_from_kinematics(d, pose) && (!design_.shapes.present() || links_apart(d));
}

void LegChainMachine::joint_angles(const Pose& pose, Eigen::VectorXd& base_angles,
                                   Eigen::VectorXd& platform_angles) const {
  const auto data = make_data();
  auto& d = data_of<LegChainData>(*data);
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
  auto& d = data_of<LegChainData>(data);
  const int n = num_actuators();
  compute_kinematics(d, pose);
  out.reachable = reachable_from_kinematics(d, pose);
  const Clearance clearance = clearance_from_kinematics(d);
  out.leg_clearance = clearance.value;
  out.clearance_first = clearance.first;
  out.clearance_second = clearance.second;
  if (design_.shapes.present())
    out.reachable = out.reachable && clearance.value >= design_.shapes.min_clearance;
  out.q = d.q;

  // Axial stiffness of every leg at its platform point: actuator and link in series.
  for (int i = 0; i < n; ++i) {
    const LegChainLeg& leg = design_.legs[static_cast<std::size_t>(i)];
    const double length = leg.kind == LegKind::kUPS ? d.q(i) : leg.link_length;
    double compliance = leg.link_section
                            ? length / (leg.link_section->E * leg.link_section->A * leg.rods)
                        : leg.axial_stiffness > 0.0 ? 1.0 / leg.axial_stiffness
                                                    : length / (leg.E * leg.area * leg.rods);
    double actuator = 0.0;  // in the actuator's own unit (m/N or rad/(N*m))
    if (leg.actuator_stiffness > 0.0) {
      actuator = 1.0 / leg.actuator_stiffness;
      compliance += d.B(i) * d.B(i) / leg.actuator_stiffness;
    }
    if (leg.drive.any()) {
      const double drive =
          drive_compliance(leg.drive, d.q(i), leg.q_min, leg.q_max, leg.kind == LegKind::kRUS);
      actuator += drive;
      compliance += d.B(i) * d.B(i) * drive;
    }
    if (leg.base_joint_stiffness > 0.0) compliance += 1.0 / (leg.base_joint_stiffness * leg.rods);
    if (leg.platform_joint_stiffness > 0.0)
      compliance += 1.0 / (leg.platform_joint_stiffness * leg.rods);
    d.actuator_compliance(i) = actuator;
    d.link_compliance(i) = compliance - d.B(i) * d.B(i) * actuator;
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
    if (d.compliance_metrics) {
      set_singular_compliance_metrics(out, d.matrices);
      if (design_.masses.present) out.natural_frequencies.setZero(n);
    }
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
  // tcp_error_max: dx = A^-1 B dq; the largest |position part| over the box vertices.
  const Mat3M E = P * d.B.asDiagonal();
  out.tcp_error_max = design_.actuator_error * max_norm_over_sign_vectors(E);
  d.error_map = design_.actuator_error * E;
  bool stiffness_ok = true;
  if (vjm_) {
    // The virtual-joint model (models/leg_chain/leg_chain_vjm.cpp): stiffness_min, compliance_tt
    // and the compliance metrics from the legs' 6x6 stiffness.
    stiffness_ok = compute_vjm_metrics(d, f, wrench, out);
  } else {
    const Mat3M Pk = P * d.k.cwiseInverse().asDiagonal();
    Mat3<double> Ctt = Pk * P.transpose();
    Eigen::SelfAdjointEigenSolver<Mat3<double>> eig3;
    eig3.computeDirect(Ctt, Eigen::EigenvaluesOnly);
    const double c_max = eig3.eigenvalues()(2);
    out.stiffness_min = c_max > 0.0 ? 1.0 / c_max : kInf;
    d.compliance_tt = Ctt;
  }
  if (!stiffness_ok || !std::isfinite(out.stiffness_min) || !out.tau.allFinite() ||
      !std::isfinite(out.tcp_error_max)) {
    out.singular = true;
    out.singularity_margin = 0.0;
    out.stiffness_min = 0.0;
    out.tau = VecM::Constant(n, kInf);
    out.tcp_error_max = kInf;
    if (d.compliance_metrics) {
      set_singular_compliance_metrics(out, d.matrices);
      if (design_.masses.present) out.natural_frequencies.setZero(n);
    }
    return;
  }
  if (d.compliance_metrics && !vjm_) compute_compliance_metrics(d, f, wrench, out);
  if (d.compliance_metrics && design_.masses.present) {
    out.natural_frequencies = natural_modes_of(d, false).frequencies;
  }
}

bool LegChainMachine::analyze_with_maps(MachineData& data, const Pose& pose, const Wrench& wrench,
                                        PoseMetrics& metrics, Eigen::Matrix3d& compliance_tt,
                                        Eigen::Matrix<double, 3, Eigen::Dynamic>& error_map) const {
  auto& d = data_of<LegChainData>(data);
  analyze(d, pose, wrench, metrics);
  if (metrics.singular) return false;
  compliance_tt = d.compliance_tt;
  error_map = d.error_map;
  return true;
}

std::unique_ptr<Machine> make_leg_chain_machine(const LegChainDesign& design) {
  return std::make_unique<LegChainMachine>(design);
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

namespace pkmopt {

bool LegChainMachine::sketch(MachineData& data, const Pose& pose, MachineSketch& out) const {
  if (!pose.position.allFinite() || !pose.angles.allFinite()) return false;
  auto& d = data_of<LegChainData>(data);
  compute_kinematics(d, pose);
  if (!d.ik_ok || !d.c.allFinite()) return false;
  out = MachineSketch{};
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  const int n = num_actuators();
  for (int i = 0; i < n; ++i) {
    const LegChainLeg& leg = design_.legs[static_cast<std::size_t>(i)];
    const Eigen::Vector3d c = d.c.col(i);
    const Eigen::Vector3d b = d.position + d.r.col(i);
    out.base_joints.push_back(leg.base_point);
    out.platform_joints.push_back(b);
    switch (leg.kind) {
      case LegKind::kUPS:  // the leg itself is actuated: base joint to platform joint
        out.lines.push_back({leg.base_point, b, MachineSketch::Part::kActuator, i});
        break;
      case LegKind::kPUS: {  // the guide over its travel, the carriage at c, the strut
        const Eigen::Vector3d u = leg.axis.normalized();
        out.lines.push_back({leg.base_point + leg.q_min * u, leg.base_point + leg.q_max * u,
                             MachineSketch::Part::kGuide, i});
        out.lines.push_back({leg.base_point, c, MachineSketch::Part::kActuator, i});
        out.lines.push_back({c, b, MachineSketch::Part::kLink, i});
        break;
      }
      case LegKind::kRUS:  // the crank from its pivot, the rod
        out.lines.push_back({leg.base_point, c, MachineSketch::Part::kActuator, i});
        out.lines.push_back({c, b, MachineSketch::Part::kLink, i});
        break;
    }
    centre += b / static_cast<double>(n);
  }
  out.lines.push_back({centre, d.position, MachineSketch::Part::kTool, -1});
  out.tcp = d.position;
  out.reachable =
      reachable_from_kinematics(d, pose) && (!design_.shapes.present() || links_apart(d));
  return true;
}

}  // namespace pkmopt
