#include "models/hexapod.hpp"

#include <Eigen/Eigenvalues>
#include <Eigen/SVD>
#include <algorithm>
#include <bit>
#include <cmath>
#include <numbers>
#include <sstream>
#include <stdexcept>
#include <string>

#include "models/linalg.hpp"

namespace pkmopt {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// Below this reciprocal condition number the eigenvalues of J_h J_h^T lose too many digits
// (relative error ~ eps * cond^2) and the margin is taken from an SVD of J_h instead.
constexpr double kRcondSvdFallback = 1e-3;

std::string fmt_double(double v) {
  std::ostringstream os;
  os.precision(17);
  os << v;
  return os.str();
}

void require(bool condition, const std::string& message) {
  if (!condition) throw std::invalid_argument(message);
}

Eigen::Matrix<double, 3, 6> hexagon(double radius, const double (&angles_deg)[6]) {
  Eigen::Matrix<double, 3, 6> joints;
  for (int i = 0; i < 6; ++i) {
    const double theta = deg_to_rad(angles_deg[i]);
    joints.col(i) << radius * std::cos(theta), radius * std::sin(theta), 0.0;
  }
  return joints;
}

}  // namespace

Eigen::Matrix<double, 3, 6> semi_regular_base_joints(double radius, double pair_separation) {
  const double half = rad_to_deg(pair_separation) / 2.0;
  double angles[6];
  for (int i = 0; i < 6; ++i) {
    const double k = i / 2;
    angles[i] = 120.0 * k + (i % 2 == 0 ? -half : half);
  }
  return hexagon(radius, angles);
}

Eigen::Matrix<double, 3, 6> semi_regular_platform_joints(double radius, double pair_separation) {
  const double half = rad_to_deg(pair_separation) / 2.0;
  double angles[6];
  for (int i = 0; i < 6; ++i) {
    const double k = i / 2;
    angles[i] = i % 2 == 0 ? 120.0 * k - 60.0 + half : 120.0 * k + 60.0 - half;
  }
  return hexagon(radius, angles);
}

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
  require(k.axial_stiffness > 0.0 || (k.E > 0.0 && k.area > 0.0),
          "legs need a stiffness: axial_stiffness > 0, or E > 0 and area > 0");
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

std::unique_ptr<MachineData> Hexapod::make_data() const {
  return std::make_unique<HexapodData>(*this);
}

double Hexapod::leg_stiffness(double q) const {
  const LegStiffness& k = design_.stiffness;
  double compliance = k.axial_stiffness > 0.0 ? 1.0 / k.axial_stiffness : q / (k.E * k.area);
  if (k.actuator_stiffness > 0.0) compliance += 1.0 / k.actuator_stiffness;
  return 1.0 / compliance;
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

bool Hexapod::reachable(MachineData& data, const Pose& pose) const {
  auto& d = static_cast<HexapodData&>(data);
  const Mat3<double> R = rotation_zyx<double>(pose.angles);
  if (!compute_kinematics(d, pose, R)) return false;
  return reachable_from_kinematics(d, R);
}

void Hexapod::compute_metrics(HexapodData& d, const Pose& pose, const Wrench& wrench,
                              PoseMetrics& out) const {
  const Mat3<double> R = rotation_zyx<double>(pose.angles);
  const bool legs_ok = compute_kinematics(d, pose, R);
  out.reachable = legs_ok && reachable_from_kinematics(d, R);
  out.q = d.q;
  for (int i = 0; i < 6; ++i) d.leg_stiffness(i) = leg_stiffness(d.q(i));

  // singularity_margin = 1 / cond(J_h) from the eigenvalues of J_h J_h^T.
  Matrix6d Jh = d.J;
  Jh.rightCols<3>() /= characteristic_length_;
  Matrix6d gram;
  gram.noalias() = Jh.lazyProduct(Jh.transpose());
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
  const Lu6 lu(d.J);
  out.det_j = std::isfinite(lu.determinant()) ? lu.determinant() : 0.0;

  out.singular = !legs_ok || lu.exactly_singular() || !(rcond >= kSingularRcond);
  if (out.singular) {
    out.singularity_margin = 0.0;
    out.stiffness_min = 0.0;
    out.tau = Vec6<double>::Constant(kInf);
    out.tcp_error_max = kInf;
    return;
  }
  out.singularity_margin = rcond;
  // Transposed solves with one LU: J^T x = e_k gives row k of J^-1; tau = J^-T w.
  out.tau = lu.solve_transposed(wrench);
  Eigen::Matrix<double, 3, 6> P;
  for (int k = 0; k < 3; ++k) P.row(k) = lu.solve_transposed(Vec6<double>::Unit(k)).transpose();

  // C_tt = P diag(1/k) P^T with P the translational rows of J^-1 (C = J^-1 diag(1/k) J^-T).
  const Eigen::Matrix<double, 3, 6> Pk = P * d.leg_stiffness.cwiseInverse().asDiagonal();
  Mat3<double> Ctt;
  Ctt.noalias() = Pk.lazyProduct(P.transpose());
  Eigen::SelfAdjointEigenSolver<Mat3<double>> eig3;
  eig3.computeDirect(Ctt, Eigen::EigenvaluesOnly);
  const double c_max = eig3.eigenvalues()(2);
  out.stiffness_min = c_max > 0.0 ? 1.0 / c_max : 0.0;

  // tcp_error_max: the largest |P s| over the 32 sign vectors s with s_0 = +1 (Gray code).
  Eigen::Vector3d v = P.rowwise().sum();
  double best = v.squaredNorm();
  double sign[6] = {1, 1, 1, 1, 1, 1};
  for (unsigned g = 1; g < 32; ++g) {
    const int col = std::countr_zero(g) + 1;
    sign[col] = -sign[col];
    v += (2.0 * sign[col]) * P.col(col);
    best = std::max(best, v.squaredNorm());
  }
  out.tcp_error_max = design_.actuator_error * std::sqrt(best);
}

void Hexapod::analyze(MachineData& data, const Pose& pose, const Wrench& wrench,
                      PoseMetrics& out) const {
  compute_metrics(static_cast<HexapodData&>(data), pose, wrench, out);
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
  double hi = lo + std::max(target, 1e-3);
  while (mean_length(hi) < target && hi < 1e12) hi = lo + 2.0 * (hi - lo);
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
  Vec6<double> res;
  Matrix6d J;
  evaluate(p, R, res, J);
  double cost = res.squaredNorm();
  double lambda = options.initial_damping;
  int iterations = 0;
  bool converged = res.cwiseAbs().maxCoeff() <= options.tolerance;
  int polish_steps = 0;
  while (iterations < options.max_iterations) {
    if (converged) {
      // One or two Gauss-Newton steps past the tolerance take the pose to machine precision.
      if (polish_steps >= 2) break;
      ++polish_steps;
    }
    ++iterations;
    const Matrix6d JtJ = J.transpose() * J;
    const Vec6<double> g = J.transpose() * res;
    Matrix6d A = JtJ;
    const double damping = converged ? 0.0 : lambda;
    for (int i = 0; i < 6; ++i) A(i, i) += damping * (JtJ(i, i) + 1e-12);
    const Vec6<double> step = -A.ldlt().solve(g);
    if (!step.allFinite()) {
      if (converged) break;
      lambda *= 10.0;
      if (lambda > 1e16) break;
      continue;
    }
    const Eigen::Vector3d p_trial = p + step.head<3>();
    const Eigen::Matrix3d R_trial = rotation_from_vector(step.tail<3>()) * R;
    Vec6<double> res_trial;
    Matrix6d J_trial;
    evaluate(p_trial, R_trial, res_trial, J_trial);
    const double cost_trial = res_trial.squaredNorm();
    if (std::isfinite(cost_trial) && cost_trial < cost) {
      p = p_trial;
      R = R_trial;
      res = res_trial;
      J = J_trial;
      cost = cost_trial;
      lambda = std::max(lambda / 5.0, 1e-15);
      converged = converged || res.cwiseAbs().maxCoeff() <= options.tolerance;
    } else {
      if (converged) break;  // the polish step cannot improve: done
      lambda *= 5.0;
      if (lambda > 1e16) break;
    }
  }
  // Re-orthonormalise (the updates keep R a rotation up to rounding).
  Eigen::JacobiSVD<Eigen::Matrix3d> svd(R, Eigen::ComputeFullU | Eigen::ComputeFullV);
  R = svd.matrixU() * svd.matrixV().transpose();

  result.pose.position = p;
  result.pose.angles = angles_from_rotation(R);
  result.iterations = iterations;
  result.residual = res.cwiseAbs().maxCoeff();
  result.converged = converged && result.pose.position.allFinite();
  if (!result.pose.position.allFinite() || !result.pose.angles.allFinite()) {
    result.pose = start;
    result.residual = kInf;
    result.converged = false;
  }
  if (result.converged) {
    result.message = "converged";
  } else {
    std::ostringstream os;
    os << "did not converge: max leg length error " << result.residual << " m after " << iterations
       << " iterations";
    result.message = os.str();
  }
  return result;
}

}  // namespace pkmopt
