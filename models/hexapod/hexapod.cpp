#include "models/hexapod/hexapod.hpp"

#include <Eigen/Eigenvalues>
#include <Eigen/SVD>
#include <algorithm>
#include <bit>
#include <cmath>
#include <numbers>
#include <sstream>
#include <stdexcept>
#include <string>

#include "models/core/linalg.hpp"
#include "models/core/pose_solver.hpp"
#include "models/core/require.hpp"
#include "models/dynamics/machine_dynamics.hpp"
#include "models/hexapod/hexapod_batch.hpp"
#include "models/stiffness/compliance_metrics.hpp"

namespace pkmopt {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// Below this reciprocal condition number the eigenvalues of J_h^T J_h lose too many digits
// (lambda_min has a relative error ~ eps * cond^2, so the margin ~ eps * cond^2 / 2: 1e-12 at
// 1e-2, 1e-10 at 1e-3) and the margin is taken from an SVD of J_h instead.
constexpr double kRcondSvdFallback = 1e-2;

std::string fmt_double(double v) {
  std::ostringstream os;
  os.precision(17);
  os << v;
  return os.str();
}

// 1 / k_i of a leg of length q (m/N): the compliance chain in series (models/hexapod/hexapod.hpp).
double leg_compliance(const LegStiffness& k, double q, double q_min, double q_max) {
  double compliance = 0.0;
  if (k.axial_stiffness > 0.0)
    compliance = 1.0 / k.axial_stiffness;
  else if (k.E > 0.0 && k.area > 0.0)
    compliance = q / (k.E * k.area);
  if (k.actuator_stiffness > 0.0) compliance += 1.0 / k.actuator_stiffness;
  if (k.drive.any()) compliance += drive_compliance(k.drive, q, q_min, q_max, false);
  if (k.base_joint_stiffness > 0.0) compliance += 1.0 / k.base_joint_stiffness;
  if (k.platform_joint_stiffness > 0.0) compliance += 1.0 / k.platform_joint_stiffness;
  return compliance;
}

}  // namespace

HexapodDesign semi_regular_hexapod(double base_radius, double base_pair_separation,
                                   double platform_radius, double platform_pair_separation) {
  HexapodDesign design;
  design.base_joints = semi_regular_base_joints(base_radius, base_pair_separation);
  design.platform_joints = semi_regular_platform_joints(platform_radius, platform_pair_separation);
  return design;
}

Hexapod::Hexapod(const HexapodDesign& design) : design_(design) {
  require(design_.base_joints.allFinite(), "base joints must be finite numbers");
  require(design_.platform_joints.allFinite(), "platform joints must be finite numbers");
  require(design_.tcp.allFinite(), "tool.tcp must be finite numbers");
  require(std::isfinite(design_.min_length) && design_.min_length > 0.0,
          "legs.min_length must be a finite number > 0, found " + fmt_double(design_.min_length));
  require(std::isfinite(design_.max_length) && design_.max_length > design_.min_length,
          "legs.max_length must be finite and > legs.min_length (" +
              fmt_double(design_.min_length) + "), found " + fmt_double(design_.max_length));
  const LegStiffness& k = design_.stiffness;
  require(
      std::isfinite(k.axial_stiffness) && k.axial_stiffness >= 0.0,
      "legs.axial_stiffness must be a finite number >= 0, found " + fmt_double(k.axial_stiffness));
  require(std::isfinite(k.E) && k.E >= 0.0,
          "legs.E must be a finite number >= 0, found " + fmt_double(k.E));
  require(std::isfinite(k.area) && k.area >= 0.0,
          "legs.area must be a finite number >= 0, found " + fmt_double(k.area));
  require(std::isfinite(k.actuator_stiffness) && k.actuator_stiffness >= 0.0,
          "legs.actuator_stiffness must be a finite number >= 0, found " +
              fmt_double(k.actuator_stiffness));
  require(std::isfinite(k.base_joint_stiffness) && k.base_joint_stiffness >= 0.0,
          "legs.base_joint_stiffness must be a finite number >= 0, found " +
              fmt_double(k.base_joint_stiffness));
  require(std::isfinite(k.platform_joint_stiffness) && k.platform_joint_stiffness >= 0.0,
          "legs.platform_joint_stiffness must be a finite number >= 0, found " +
              fmt_double(k.platform_joint_stiffness));
  check_screw_drive(k.drive, "legs.drive", false);
  if (design_.masses.present) check_mass_model(design_.masses, "masses.");
  check_leg_shape(design_.leg_shape, design_.min_clearance);
  check_hexapod_bodies(design_.leg_shape, design_.bodies);
  require(k.axial_stiffness > 0.0 || (k.E > 0.0) == (k.area > 0.0),
          "legs: the strut needs both E and area (or axial_stiffness)");
  require(k.axial_stiffness > 0.0 || (k.E > 0.0 && k.area > 0.0) || k.actuator_stiffness > 0.0 ||
              k.drive.any() || k.base_joint_stiffness > 0.0 || k.platform_joint_stiffness > 0.0,
          "legs need a stiffness: axial_stiffness > 0, or E > 0 and area > 0, or a drive, "
          "actuator or joint stiffness");
  const HexapodJointLimits& j = design_.joints;
  require(!std::isnan(j.base_max_angle) && j.base_max_angle > 0.0,
          "joints.base_max_angle_deg must be > 0");
  require(!std::isnan(j.platform_max_angle) && j.platform_max_angle > 0.0,
          "joints.platform_max_angle_deg must be > 0");
  require(j.base_axis.allFinite() && j.base_axis.norm() > 1e-12,
          "joints.base_axis must be a non-zero finite vector");
  require(j.platform_axis.allFinite() && j.platform_axis.norm() > 1e-12,
          "joints.platform_axis must be a non-zero finite vector");
  design_.joints.base_axis.normalize();
  design_.joints.platform_axis.normalize();
  require(
      std::isfinite(design_.actuator_error) && design_.actuator_error >= 0.0,
      "actuator_error must be a finite number >= 0, found " + fmt_double(design_.actuator_error));

  platform_rel_ = design_.platform_joints.colwise() - design_.tcp;
  if (design_.characteristic_length) {
    const double L = *design_.characteristic_length;
    require(std::isfinite(L) && L > 0.0,
            "characteristic_length must be a finite number > 0, found " + fmt_double(L));
    characteristic_length_ = L;
  } else {
    characteristic_length_ = platform_rel_.colwise().norm().mean();
    require(characteristic_length_ > 0.0,
            "the platform joints all sit at the TCP; give characteristic_length");
  }
  cos_base_limit_ = j.base_max_angle >= std::numbers::pi ? -2.0 : std::cos(j.base_max_angle);
  cos_platform_limit_ =
      j.platform_max_angle >= std::numbers::pi ? -2.0 : std::cos(j.platform_max_angle);
}

HexapodData::HexapodData(const Hexapod& hexapod) : MachineData(&hexapod) {}

void Hexapod::analyze_batch(const Pose* poses, std::size_t count, const Wrench& wrench,
                            PoseMetrics* metrics, PoseCompliance* compliance) const {
  analyze_hexapod_batch(*this, poses, count, wrench, metrics, HexapodBatchKernel::automatic,
                        compliance);
}

std::unique_ptr<MachineData> Hexapod::make_data() const { return new_data<HexapodData>(*this); }

double Hexapod::leg_stiffness(double q) const {
  return 1.0 / leg_compliance(design_.stiffness, q, design_.min_length, design_.max_length);
}

bool Hexapod::compute_kinematics(HexapodData& d, const Pose& pose) const {
  return compute_kinematics(d, pose, rotation_zyx<double>(pose.angles));
}

bool Hexapod::compute_kinematics(HexapodData& d, const Pose& pose, const Mat3<double>& R) const {
  bool ok = true;
  for (int i = 0; i < 6; ++i) {
    const Eigen::Vector3d ri = R * platform_rel_.col(i);
    const Eigen::Vector3d li = pose.position + ri - design_.base_joints.col(i);
    const double length = li.norm();
    d.q(i) = length;
    d.r.col(i) = ri;
    if (length > 0.0) {
      d.s.col(i) = li / length;
    } else {
      d.s.col(i).setZero();
      ok = false;
    }
    d.J.block<1, 3>(i, 0) = d.s.col(i).transpose();
    d.J.block<1, 3>(i, 3) = ri.cross(d.s.col(i)).transpose();
  }
  return ok;
}

bool Hexapod::reachable_from_kinematics(const HexapodData& d, const Mat3<double>& R) const {
  const Eigen::Vector3d platform_axis = R * design_.joints.platform_axis;
  for (int i = 0; i < 6; ++i) {
    if (!(d.q(i) >= design_.min_length && d.q(i) <= design_.max_length)) return false;
    if (d.s.col(i).dot(design_.joints.base_axis) < cos_base_limit_) return false;
    if (-d.s.col(i).dot(platform_axis) < cos_platform_limit_) return false;
  }
  return true;
}

int Hexapod::bodies_from_kinematics(const HexapodData& d, Capsule (&bodies)[12]) const {
  int n = 0;
  for (int i = 0; i < 6; ++i) {
    const Eigen::Vector3d a = design_.base_joints.col(i);
    n += leg_bodies(design_.leg_shape, a, a + d.q(i) * d.s.col(i), i, bodies + n);
  }
  return n;
}

Clearance Hexapod::clearance_from_kinematics(const HexapodData& d, const Pose& pose,
                                             const Mat3<double>& R) const {
  Capsule bodies[12];
  const int n = bodies_from_kinematics(d, bodies);
  const std::span<const Capsule> legs(bodies, static_cast<std::size_t>(n));
  Clearance c = pkmopt::leg_clearance(legs);
  if (design_.bodies.present())
    body_clearance(legs, design_.bodies, R, pose.position - R * design_.tcp, c);
  return c;
}

Clearance Hexapod::leg_clearance(const Pose& pose) const {
  if (!design_.leg_shape.present()) return {};
  HexapodData d;
  const Mat3<double> R = rotation_zyx<double>(pose.angles);
  compute_kinematics(d, pose, R);
  return clearance_from_kinematics(d, pose, R);
}

Clearance Hexapod::with_solid_bodies(const Pose& pose, Clearance legs) const {
  if (!design_.bodies.present() || !design_.leg_shape.present()) return legs;
  const Mat3<double> R = rotation_zyx<double>(pose.angles);
  Capsule bodies[12];
  int n = 0;
  for (int i = 0; i < 6; ++i) {
    const Eigen::Vector3d p = pose.position + R * platform_rel_.col(i);
    n += leg_bodies(design_.leg_shape, design_.base_joints.col(i), p, i, bodies + n);
  }
  body_clearance(std::span<const Capsule>(bodies, static_cast<std::size_t>(n)), design_.bodies, R,
                 pose.position - R * design_.tcp, legs);
  return legs;
}

bool Hexapod::reachable(MachineData& data, const Pose& pose) const {
  auto& d = data_of<HexapodData>(data);
  const Mat3<double> R = rotation_zyx<double>(pose.angles);
  if (!compute_kinematics(d, pose, R)) return false;
  if (!reachable_from_kinematics(d, R)) return false;
  if (!design_.leg_shape.present()) return true;
  Capsule bodies[12];
  const int n = bodies_from_kinematics(d, bodies);
  const std::span<const Capsule> legs(bodies, static_cast<std::size_t>(n));
  return legs_apart(legs, design_.min_clearance) &&
         (!design_.bodies.present() ||
          bodies_apart(legs, design_.bodies, R, pose.position - R * design_.tcp,
                       design_.min_clearance));
}

void Hexapod::compute_metrics(HexapodData& d, const Pose& pose, const Wrench& wrench,
                              PoseMetrics& out) const {
  const Mat3<double> R = rotation_zyx<double>(pose.angles);
  const bool legs_ok = compute_kinematics(d, pose, R);
  out.reachable = legs_ok && reachable_from_kinematics(d, R);
  if (design_.leg_shape.present()) {
    const Clearance c = clearance_from_kinematics(d, pose, R);
    out.leg_clearance = c.value;
    out.clearance_first = c.first;
    out.clearance_second = c.second;
    out.reachable = out.reachable && c.value >= design_.min_clearance;
  } else {
    out.leg_clearance = std::numeric_limits<double>::infinity();
    out.clearance_first = out.clearance_second = -1;
  }
  out.q = d.q;
  Vec6<double> compliance;  // 1 / k_i
  for (int i = 0; i < 6; ++i) {
    compliance(i) =
        leg_compliance(design_.stiffness, d.q(i), design_.min_length, design_.max_length);
    d.leg_stiffness(i) = 1.0 / compliance(i);
  }

  // singularity_margin = 1 / cond(J_h) from the eigenvalues of J_h^T J_h.
  Matrix6d Jh = d.J;
  Jh.rightCols<3>() *= 1.0 / characteristic_length_;
  Matrix6d gram;
  gram.noalias() = Jh.transpose().lazyProduct(Jh);
  Vec6<double> lambda;
  symmetric_eigenvalues6(gram, lambda);
  const double lambda_max = lambda(5);
  const double lambda_min = std::max(lambda(0), 0.0);
  double rcond = lambda_max > 0.0 ? std::sqrt(lambda_min / lambda_max) : 0.0;
  if (rcond < kRcondSvdFallback && lambda_max > 0.0) {
    Eigen::JacobiSVD<Matrix6d> svd(Jh);
    const auto& sv = svd.singularValues();
    rcond = sv(0) > 0.0 ? sv(5) / sv(0) : 0.0;
  }

  // One elimination on J^T gives det J, the leg forces tau = J^-T w and the translational rows
  // P of J^-1 (J^T x = e_k gives row k of J^-1).
  Eigen::Matrix<double, 6, 4> rhs = Eigen::Matrix<double, 6, 4>::Zero();
  rhs(0, 0) = rhs(1, 1) = rhs(2, 2) = 1.0;
  rhs.col(3) = wrench;
  Eigen::Matrix<double, 6, 4> solution;
  double det = 0.0;
  const bool invertible = solve_transposed6x4(d.J, rhs, solution, det);
  out.det_j = std::isfinite(det) ? det : 0.0;

  out.singular = !legs_ok || !invertible || !(rcond >= kSingularRcond);
  if (out.singular) {
    out.singularity_margin = 0.0;
    out.stiffness_min = 0.0;
    out.tau = Vec6<double>::Constant(kInf);
    out.tcp_error_max = kInf;
    if (d.compliance_metrics) {
      set_singular_compliance_metrics(out, d.matrices);
      if (design_.masses.present) out.natural_frequencies.setZero(6);
    }
    return;
  }
  out.singularity_margin = rcond;
  out.tau = solution.col(3);

  // C_tt = P diag(1/k) P^T with P the translational rows of J^-1 (C = J^-1 diag(1/k) J^-T).
  const Eigen::Matrix<double, 6, 3> Pt = solution.leftCols<3>();  // P^T
  Mat3<double> Ctt;
  for (int a = 0; a < 3; ++a) {
    for (int b = 0; b <= a; ++b) {
      double sum = 0.0;
      for (int i = 0; i < 6; ++i) sum += Pt(i, a) * compliance(i) * Pt(i, b);
      Ctt(a, b) = Ctt(b, a) = sum;
    }
  }
  Eigen::Vector3d c_eigenvalues;
  symmetric_eigenvalues3(Ctt, c_eigenvalues);
  const double c_max = c_eigenvalues(2);
  out.stiffness_min = c_max > 0.0 ? 1.0 / c_max : 0.0;
  d.compliance_tt = Ctt;
  d.error_map = design_.actuator_error * Pt.transpose();

  // tcp_error_max: the largest |P s| over the 32 sign vectors s with s_0 = +1, as the sums of
  // p_0 +- p_1 +- p_2 (4 vectors) and +- p_3 +- p_4 +- p_5 (8 vectors), p_j the columns of P.
  double head[3][4], tail[3][8];
  for (int c = 0; c < 3; ++c) {
    for (int m = 0; m < 4; ++m) {
      head[c][m] = Pt(0, c) + ((m & 1) ? -Pt(1, c) : Pt(1, c)) + ((m & 2) ? -Pt(2, c) : Pt(2, c));
    }
    for (int m = 0; m < 8; ++m) {
      tail[c][m] = ((m & 1) ? -Pt(3, c) : Pt(3, c)) + ((m & 2) ? -Pt(4, c) : Pt(4, c)) +
                   ((m & 4) ? -Pt(5, c) : Pt(5, c));
    }
  }
  double best[8] = {0, 0, 0, 0, 0, 0, 0, 0};
  for (int h = 0; h < 4; ++h) {
    for (int m = 0; m < 8; ++m) {
      const double x = head[0][h] + tail[0][m];
      const double y = head[1][h] + tail[1][m];
      const double z = head[2][h] + tail[2][m];
      const double norm2 = x * x + y * y + z * z;
      best[m] = norm2 > best[m] ? norm2 : best[m];
    }
  }
  const double best_norm2 = *std::max_element(best, best + 8);
  out.tcp_error_max = design_.actuator_error * std::sqrt(best_norm2);
  if (d.compliance_metrics) compute_compliance_metrics(d, pose, compliance, wrench, out);
}

void Hexapod::compute_compliance_metrics(HexapodData& d, const Pose& pose,
                                         const Vec6<double>& compliance, const Wrench& wrench,
                                         PoseMetrics& out) const {
  // C = J^-1 diag(1/k) J^-T; the loaded stiffness adds each leg's geometric term under its
  // force tau_i (models/stiffness/compliance_metrics.hpp).
  const Eigen::PartialPivLU<Matrix6d> lu(d.J);
  const Matrix6d Jinv = lu.inverse();
  const Matrix6d C = Jinv * compliance.asDiagonal() * Jinv.transpose();
  fill_compliance_metrics(C, wrench, out, d.matrices);
  Matrix6d G = Matrix6d::Zero();
  for (int i = 0; i < 6; ++i) G += geometric_stiffness(out.tau(i), d.s.col(i), d.r.col(i), d.q(i));
  out.stiffness_min_loaded = loaded_stiffness_min(C, G, &d.matrices.loaded_compliance_tt);
  if (design_.masses.present) {
    const NaturalModes modes = natural_frequencies6(C, mass_matrix(pose));
    out.natural_frequencies = modes.frequencies;
  }
}

void Hexapod::analyze(MachineData& data, const Pose& pose, const Wrench& wrench,
                      PoseMetrics& out) const {
  compute_metrics(data_of<HexapodData>(data), pose, wrench, out);
}

bool Hexapod::analyze_with_maps(MachineData& data, const Pose& pose, const Wrench& wrench,
                                PoseMetrics& metrics, Eigen::Matrix3d& compliance_tt,
                                Eigen::Matrix<double, 3, Eigen::Dynamic>& error_map) const {
  auto& d = data_of<HexapodData>(data);
  compute_metrics(d, pose, wrench, metrics);
  if (metrics.singular) return false;
  compliance_tt = d.compliance_tt;
  error_map = d.error_map;
  return true;
}

Vec6<double> Hexapod::inverse_kinematics(const Pose& pose) const {
  Vec6<double> q;
  hexapod_legs<double>(design_.base_joints, platform_rel_, pose.position, pose.angles, &q);
  return q;
}

Matrix6d Hexapod::inverse_jacobian(const Pose& pose) const {
  Vec6<double> q;
  Matrix6d J;
  hexapod_legs<double>(design_.base_joints, platform_rel_, pose.position, pose.angles, &q, &J);
  return J;
}

bool Hexapod::twist_jacobian(MachineData& /*data*/, const Pose& pose, Eigen::MatrixXd& J) const {
  const Matrix6d Jp = inverse_jacobian(pose);
  if (!Jp.allFinite()) return false;
  J = Jp;
  return true;
}

Matrix6d Hexapod::stiffness_matrix(const Pose& pose) const {
  Vec6<double> q;
  Matrix6d J;
  hexapod_legs<double>(design_.base_joints, platform_rel_, pose.position, pose.angles, &q, &J);
  Vec6<double> k;
  for (int i = 0; i < 6; ++i) k(i) = leg_stiffness(q(i));
  return J.transpose() * k.asDiagonal() * J;
}

void Hexapod::joint_angles(const Pose& pose, Vec6<double>& base_angles,
                           Vec6<double>& platform_angles) const {
  HexapodData d;
  compute_kinematics(d, pose);
  const Eigen::Vector3d platform_axis =
      rotation_zyx<double>(pose.angles) * design_.joints.platform_axis;
  for (int i = 0; i < 6; ++i) {
    const Eigen::Vector3d si = d.s.col(i);
    // atan2 of |cross| and dot is accurate at every angle, unlike acos near 0 and pi.
    base_angles(i) =
        std::atan2(si.cross(design_.joints.base_axis).norm(), si.dot(design_.joints.base_axis));
    platform_angles(i) = std::atan2(si.cross(platform_axis).norm(), -si.dot(platform_axis));
  }
}

Pose Hexapod::home_pose_for(const Vec6<double>& q) const {
  // Mean leg length at (0, 0, z) with R = I; increasing in z once z is above every joint pair.
  const double target = q.mean();
  Eigen::Matrix<double, 3, 6> offset = platform_rel_ - design_.base_joints;
  auto mean_length = [&](double z) {
    double sum = 0.0;
    for (int i = 0; i < 6; ++i) sum += std::hypot(offset(0, i), offset(1, i), offset(2, i) + z);
    return sum / 6.0;
  };
  double lo = -offset.row(2).minCoeff();
  // Grow the step, not lo + step: with a far-off TCP, lo + small step rounds back to lo.
  double step = std::max(target, 1e-3);
  while (mean_length(lo + step) < target && step < 1e12) step *= 2.0;
  double hi = lo + step;
  if (mean_length(lo) < target) {
    for (int it = 0; it < 200 && hi - lo > 1e-15 * (1.0 + std::abs(hi)); ++it) {
      const double mid = 0.5 * (lo + hi);
      (mean_length(mid) < target ? lo : hi) = mid;
    }
  }
  Pose home;
  home.position = {0.0, 0.0, 0.5 * (lo + hi)};
  return home;
}

FkResult Hexapod::forward_kinematics(const Eigen::VectorXd& q_target,
                                     const std::optional<Pose>& guess,
                                     const FkOptions& options) const {
  FkResult result;
  if (q_target.size() != 6 || !q_target.allFinite() || (q_target.array() <= 0.0).any()) {
    result.message = "leg lengths must be 6 finite numbers > 0";
    result.residual = kInf;
    return result;
  }
  const Vec6<double> q_goal = q_target;
  const Pose start = guess ? *guess : home_pose_for(q_goal);
  if (!start.position.allFinite() || !start.angles.allFinite()) {
    result.message = "the guess must be finite";
    result.residual = kInf;
    return result;
  }

  // Levenberg-Marquardt on the TCP twist: the Jacobian of q(pose) with respect to a small
  // twist [v; omega] (omega about base axes, R <- exp(omega) R) is exactly J.
  Eigen::Vector3d p = start.position;
  Eigen::Matrix3d R = rotation_zyx<double>(start.angles);
  auto evaluate = [&](const Eigen::Vector3d& pos, const Eigen::Matrix3d& rot, Vec6<double>& res,
                      Matrix6d& jac) {
    for (int i = 0; i < 6; ++i) {
      const Eigen::Vector3d ri = rot * platform_rel_.col(i);
      const Eigen::Vector3d li = pos + ri - design_.base_joints.col(i);
      const double length = li.norm();
      res(i) = length - q_goal(i);
      const Eigen::Vector3d si =
          length > 0.0 ? Eigen::Vector3d(li / length) : Eigen::Vector3d::Zero();
      jac.block<1, 3>(i, 0) = si.transpose();
      jac.block<1, 3>(i, 3) = ri.cross(si).transpose();
    }
  };
  const PoseClosureSolve<Vec6<double>> solve =
      solve_pose_closure<Vec6<double>, Matrix6d>(p, R, true, 6, options, evaluate);
  return fk_result(solve, start, true, "leg length error");
}

std::optional<Eigen::AlignedBox3d> Hexapod::workspace_search_box(
    const std::vector<Eigen::Matrix3d>& orientations) const {
  const double beta = design_.joints.base_max_angle;
  const bool axis_is_z = (design_.joints.base_axis - Eigen::Vector3d::UnitZ()).norm() < 1e-12;
  const bool cone = axis_is_z && beta < std::numbers::pi / 2;
  Eigen::AlignedBox3d united;  // empty
  for (const Eigen::Matrix3d& R : orientations) {
    Eigen::AlignedBox3d box(Eigen::Vector3d::Constant(-kInf), Eigen::Vector3d::Constant(kInf));
    for (int i = 0; i < 6; ++i) {
      const Eigen::Vector3d centre = design_.base_joints.col(i) - R * platform_rel_.col(i);
      const double L = design_.max_length;
      Eigen::Vector3d low = centre - Eigen::Vector3d::Constant(L);
      Eigen::Vector3d high = centre + Eigen::Vector3d::Constant(L);
      if (cone) {
        const double radial = L * std::sin(beta);
        low = centre + Eigen::Vector3d(-radial, -radial, design_.min_length * std::cos(beta));
        high = centre + Eigen::Vector3d(radial, radial, L);
      }
      box = box.intersection(Eigen::AlignedBox3d(low, high));
    }
    if (!box.isEmpty()) united.extend(box);
  }
  return united;
}

std::optional<double> Hexapod::envelope_volume() const {
  const Eigen::Vector3d centroid = design_.base_joints.rowwise().mean();
  double radius = 0.0;
  for (int i = 0; i < 6; ++i) {
    radius = std::max(radius, (design_.base_joints.col(i) - centroid).head<2>().norm());
  }
  const double height = design_.base_joints.row(2).maxCoeff() -
                        design_.base_joints.row(2).minCoeff() + design_.max_length;
  return std::numbers::pi * radius * radius * height;
}

std::string Hexapod::actuator_coordinates_requirement(const Eigen::VectorXd& q) const {
  if ((q.array() > 0.0).all()) return {};
  return "6 leg lengths > 0 (m)";
}

}  // namespace pkmopt

namespace pkmopt {

bool Hexapod::sketch(MachineData& data, const Pose& pose, MachineSketch& out) const {
  if (!pose.position.allFinite() || !pose.angles.allFinite()) return false;
  const Mat3<double> R = rotation_zyx<double>(pose.angles);
  out = MachineSketch{};
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  for (int i = 0; i < 6; ++i) {
    const Eigen::Vector3d a = design_.base_joints.col(i);
    const Eigen::Vector3d b = pose.position + R * platform_rel_.col(i);
    out.base_joints.push_back(a);
    out.platform_joints.push_back(b);
    out.lines.push_back({a, b, MachineSketch::Part::kActuator, i});
    centre += b / 6.0;
  }
  out.lines.push_back({centre, pose.position, MachineSketch::Part::kTool, -1});
  out.tcp = pose.position;
  out.reachable = reachable(data, pose);
  return true;
}

}  // namespace pkmopt
