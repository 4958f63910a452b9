// The dynamics of a hybrid machine (models/hybrid/hybrid_machine.hpp, "Dynamics";
// docs/dynamics.md): natural frequencies of the serial carriages and the module on the axis drives
// and the module's legs in series, and the inverse dynamics of the axes and the module along a
// motion.
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

#include "models/hybrid/hybrid_machine.hpp"

namespace pkmopt {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// blockdiag(R, R): turns twists and wrenches from the module's base axes to the world's.
Matrix6d turn6(const Eigen::Matrix3d& R) {
  Matrix6d T = Matrix6d::Zero();
  T.topLeftCorner<3, 3>() = T.bottomRightCorner<3, 3>() = R;
  return T;
}

}  // namespace

double HybridMachine::moving_mass() const {
  double total = module_dynamics_ == nullptr ? 0.0 : module_dynamics_->moving_mass();
  for (const HybridAxis& a : design_.axes) total += a.mass;
  return total;
}

int HybridMachine::natural_frequency_count() const {
  if (module_dynamics_ == nullptr) return 0;
  int elastic = 0;
  for (const HybridAxis& a : design_.axes) elastic += a.stiffness > 0.0 ? 1 : 0;
  return module_dynamics_->natural_frequency_count() + elastic;
}

void HybridMachine::compute_natural_frequencies(HybridData& d, const HybridSplit& s,
                                                const Matrix6d& C_module, PoseMetrics& out) const {
  const int ns = num_serial_, n = ns + 6;
  const int count = natural_frequency_count();
  out.natural_frequencies = Eigen::VectorXd::Zero(count);
  Wrench w_dyn;
  Eigen::Vector3d net;
  Eigen::Matrix<double, 9, 9> Q;
  if (!module_dynamics_->carried_dynamics(*d.module, s.local, Vector6d::Zero(), Vector6d::Zero(),
                                          R0_.transpose() * design_.gravity, w_dyn, net, &Q)) {
    return;  // a leg cannot close: 0, as at a singular pose
  }
  // The module's kinetic energy in world axes: d_local = R0^T d, xi_local = turn^T xi.
  Eigen::Matrix<double, 9, 9> turn9 = Eigen::Matrix<double, 9, 9>::Zero();
  turn9.topLeftCorner<3, 3>() = R0_;
  turn9.bottomRightCorner<6, 6>() = turn6(R0_);
  const Eigen::Matrix<double, 9, 9> Qw = turn9 * Q * turn9.transpose();
  // M_z over [u_dot; xi].
  Eigen::MatrixXd M = Eigen::MatrixXd::Zero(n, n);
  M.topLeftCorner(ns, ns) = A_.transpose() * Qw.topLeftCorner<3, 3>() * A_;
  for (int j = 0; j < ns; ++j) {  // carriage j moves with sum_{l <= j} a_l u_dot_l
    const double m = design_.axes[static_cast<std::size_t>(j)].mass;
    for (int l = 0; l <= j; ++l) {
      for (int k = 0; k <= j; ++k) M(l, k) += m * A_.col(l).dot(A_.col(k));
    }
  }
  M.topRightCorner(ns, 6) = A_.transpose() * Qw.topRightCorner<3, 6>();
  M.bottomLeftCorner(6, ns) = M.topRightCorner(ns, 6).transpose();
  M.bottomRightCorner<6, 6>() = Qw.bottomRightCorner<6, 6>();
  // C_z = [D, D B^T; B D, B D B^T + C_m], B = [A; 0].
  Eigen::MatrixXd B = Eigen::MatrixXd::Zero(6, ns);
  B.topRows(3) = A_;
  Eigen::VectorXd D(ns);
  for (int i = 0; i < ns; ++i) {
    const double k = design_.axes[static_cast<std::size_t>(i)].stiffness;
    D(i) = k > 0.0 ? 1.0 / k : 0.0;
  }
  Eigen::MatrixXd C = Eigen::MatrixXd::Zero(n, n);
  C.topLeftCorner(ns, ns) = D.asDiagonal();
  C.topRightCorner(ns, 6) = D.asDiagonal() * B.transpose();
  C.bottomLeftCorner(6, ns) = B * D.asDiagonal();
  C.bottomRightCorner<6, 6>() = B * D.asDiagonal() * B.transpose() + C_module;
  C = (0.5 * (C + C.transpose())).eval();
  M = (0.5 * (M + M.transpose())).eval();
  if (!C.allFinite() || !M.allFinite()) return;
  // mu = eigenvalues of Lc^T M Lc with C = Lc Lc^T (C = V L V^T, Lc = V L^1/2).
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> c_eig(C);
  if (c_eig.info() != Eigen::Success) return;
  const Eigen::VectorXd lambda = c_eig.eigenvalues().cwiseMax(0.0);
  const Eigen::MatrixXd Lc = c_eig.eigenvectors() * lambda.cwiseSqrt().asDiagonal();
  Eigen::MatrixXd S = Lc.transpose() * M * Lc;
  S = (0.5 * (S + S.transpose())).eval();
  const bool shapes = d.want_mode_shapes;
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> s_eig(
      S, shapes ? Eigen::ComputeEigenvectors : Eigen::EigenvaluesOnly);
  if (s_eig.info() != Eigen::Success) return;
  const Eigen::VectorXd mu = s_eig.eigenvalues();  // ascending: frequencies descend
  const double scale = mu.cwiseAbs().maxCoeff();
  std::vector<double> frequencies;
  if (shapes) d.mode_shapes = Eigen::MatrixXd::Zero(n, count);
  for (Eigen::Index k = mu.size() - 1; k >= 0; --k) {
    if (mu(k) > 1e-12 * scale && static_cast<int>(frequencies.size()) < count) {
      if (shapes) {
        // z = Lc y / sqrt(mu): z^T M z = y^T S y / mu = 1.
        Eigen::VectorXd z = Lc * s_eig.eigenvectors().col(k) / std::sqrt(mu(k));
        Eigen::Index lead = 0;
        z.cwiseAbs().maxCoeff(&lead);
        if (z(lead) < 0.0) z = -z;
        d.mode_shapes.col(static_cast<Eigen::Index>(frequencies.size())) = z;
      }
      frequencies.push_back(1.0 / (2.0 * std::numbers::pi * std::sqrt(mu(k))));
    }
  }
  for (int k = 0; k < count; ++k) {
    out.natural_frequencies(k) =
        k < static_cast<int>(frequencies.size()) ? frequencies[static_cast<std::size_t>(k)] : kInf;
  }
}

bool HybridMachine::mode_shapes(MachineData& data, const Pose& pose, PoseModes& out) const {
  if (module_dynamics_ == nullptr) return false;
  auto& d = data_of<HybridData>(data);
  const bool compliance_metrics = d.compliance_metrics;
  d.compliance_metrics = true;
  d.want_mode_shapes = true;
  d.mode_shapes.resize(0, 0);
  PoseMetrics metrics;
  analyze(d, pose, Wrench::Zero(), metrics);
  d.compliance_metrics = compliance_metrics;
  d.want_mode_shapes = false;
  if (!metrics.reachable || metrics.singular || d.mode_shapes.cols() == 0) return false;
  out.frequencies = metrics.natural_frequencies;
  out.shapes = d.mode_shapes;
  return true;
}

bool HybridMachine::inverse_dynamics(MachineData& data, const Pose& pose, const Vector6d& xi,
                                     const Vector6d& xi_dot, const Wrench& wrench,
                                     PoseMetrics& out) const {
  if (module_dynamics_ == nullptr) return false;
  auto& d = data_of<HybridData>(data);
  analyze(data, pose, wrench, out);  // every other metric under the wrench
  const HybridSplit s = split(pose);
  const Eigen::VectorXd free = free_axes(s);
  const Eigen::VectorXd u_dot = free.asDiagonal() * (A_pinv_ * xi.head<3>());
  const Eigen::VectorXd u_ddot = free.asDiagonal() * (A_pinv_ * xi_dot.head<3>());
  const Eigen::Vector3d base_acceleration = A_ * u_ddot;
  // The module relative to its translating base, in its own axes.
  Vector6d xi_rel, xi_dot_rel;
  xi_rel << R0_.transpose() * (xi.head<3>() - A_ * u_dot), R0_.transpose() * xi.tail<3>();
  xi_dot_rel << R0_.transpose() * (xi_dot.head<3>() - base_acceleration),
      R0_.transpose() * xi_dot.tail<3>();
  const Eigen::Vector3d g_local = R0_.transpose() * (design_.gravity - base_acceleration);
  Wrench w_dyn;
  Eigen::Vector3d net;
  if (!module_dynamics_->carried_dynamics(*d.module, s.local, xi_rel, xi_dot_rel, g_local, w_dyn,
                                          net, nullptr)) {
    return false;
  }
  Wrench local_wrench;
  local_wrench << R0_.transpose() * wrench.head<3>(), R0_.transpose() * wrench.tail<3>();
  const bool compliance = d.module->compliance_metrics;
  d.module->compliance_metrics = false;
  PoseMetrics module_metrics;
  design_.module->analyze(*d.module, s.local, local_wrench + w_dyn, module_metrics);
  d.module->compliance_metrics = compliance;
  const int n = num_actuators();
  if (module_metrics.singular || out.singular) {
    out.tau = Eigen::VectorXd::Constant(n, kInf);
    return true;
  }
  // Axis i carries the force on everything after it: the tool's force, the module's gravity and
  // inertia, and the carriages from i on.
  const Eigen::Vector3d module_force = R0_ * net;
  Eigen::Vector3d carried = wrench.head<3>() + module_force;
  Eigen::VectorXd tau_serial(num_serial_);
  std::vector<Eigen::Vector3d> carriage_acceleration(static_cast<std::size_t>(num_serial_));
  Eigen::Vector3d acc = Eigen::Vector3d::Zero();
  for (int j = 0; j < num_serial_; ++j) {
    acc += A_.col(j) * u_ddot(j);
    carriage_acceleration[static_cast<std::size_t>(j)] = acc;
  }
  for (int i = num_serial_ - 1; i >= 0; --i) {
    const double m = design_.axes[static_cast<std::size_t>(i)].mass;
    carried += m * (design_.gravity - carriage_acceleration[static_cast<std::size_t>(i)]);
    tau_serial(i) = A_.col(i).dot(carried);
  }
  out.tau.resize(n);
  out.tau << tau_serial, module_metrics.tau;
  if (!out.tau.allFinite()) out.tau.setConstant(kInf);
  return true;
}

}  // namespace pkmopt
