#include "models/hybrid/hybrid_machine.hpp"

#include <fmt/format.h>

#include <Eigen/Eigenvalues>
#include <Eigen/QR>
#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <utility>

#include "models/core/linalg.hpp"
#include "models/core/require.hpp"
#include "models/geometry/leg_interference.hpp"
#include "models/serial/serial_statics.hpp"
#include "models/stiffness/compliance_metrics.hpp"

namespace pkmopt {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
// A parasitic module's pose counts as attained when the world TCP is within this (m).
constexpr double kAttainedTolerance = 1e-9;

}  // namespace

HybridMachine::HybridMachine(HybridDesign design) : design_(std::move(design)) {
  require(design_.module != nullptr, "hybrid: the parallel module is missing");
  require(design_.module->model() != "hybrid", "hybrid: the module must be a parallel machine");
  require(!design_.module->revolute_actuators(),
          "hybrid: modules with revolute actuators (a delta) are not supported: q would mix the "
          "axes' metres with the module's angles; use a module with prismatic actuators");
  num_serial_ = design_.chain.num_variables();
  require(num_serial_ >= 1, "hybrid: the serial chain needs at least one variable axis");
  require(design_.chain.num_rotations() == 0,
          "hybrid: variable rotary axes (motions 4, 5, 6) are not computable; use translations "
          "(1, 2, 3) and constant rotations");
  require(
      static_cast<int>(design_.axes.size()) == num_serial_,
      fmt::format("hybrid: {} axis ranges for {} serial axes", design_.axes.size(), num_serial_));
  for (std::size_t i = 0; i < design_.axes.size(); ++i) {
    const HybridAxis& a = design_.axes[i];
    require(std::isfinite(a.min) && std::isfinite(a.max) && a.min <= a.max,
            fmt::format("hybrid: axis {} range must be finite with min <= max, found [{}, {}]",
                        i + 1, a.min, a.max));
    require(std::isfinite(a.stiffness) && a.stiffness >= 0.0,
            fmt::format("hybrid: axis {} stiffness must be >= 0, found {}", i + 1, a.stiffness));
    require(std::isfinite(a.error) && a.error >= 0.0,
            fmt::format("hybrid: axis {} error must be >= 0, found {}", i + 1, a.error));
    require(std::isfinite(a.mass) && a.mass >= 0.0,
            fmt::format("hybrid: axis {} mass must be >= 0, found {}", i + 1, a.mass));
  }
  require(design_.gravity.allFinite(), "hybrid: gravity must be finite");
  require(design_.home.allFinite(), "hybrid: the module's home point must be finite");

  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(num_serial_);
  const Eigen::Matrix4d T0 = design_.chain.transform(zero);
  R0_ = T0.topLeftCorner<3, 3>();
  t0_ = T0.topRightCorner<3, 1>();
  A_ = design_.chain.tool_point_jacobian(zero, Eigen::Vector3d::Zero());
  const Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(A_);
  require(qr.rank() == num_serial_,
          fmt::format("hybrid: the {} serial axes are linearly dependent (rank {}); give "
                      "independent translation axes",
                      num_serial_, qr.rank()));
  A_pinv_ = (A_.transpose() * A_).ldlt().solve(A_.transpose());
  Jf_ = FeedJacobian::Zero(6, num_serial_);
  Jf_.topRows<3>() = A_;

  parasitic_module_ = design_.module->parasitic_motion();
  module_dynamics_ = design_.module->dynamics().get();
  module_maps_ = design_.module->translational_maps();
  require(parasitic_module_ == nullptr || module_dynamics_ == nullptr,
          "hybrid: a module with parasitic motion (planar legs) takes no masses in a hybrid "
          "machine: its dynamics on moving axes are not modelled");
}

std::unique_ptr<MachineData> HybridMachine::make_data() const {
  auto d = new_data<HybridData>();
  d->module = design_.module->make_data();
  return d;
}

Pose HybridMachine::world_pose(const Eigen::VectorXd& q_serial, const Pose& local) const {
  Pose world;
  world.position = t0_ + A_ * q_serial + R0_ * local.position;
  world.angles = angles_from_rotation(R0_ * rotation_zyx<double>(local.angles));
  return world;
}

HybridSplit HybridMachine::split(const Pose& pose) const {
  HybridSplit s;
  auto clamp = [&](const Eigen::VectorXd& u) {
    Eigen::VectorXd q(num_serial_);
    for (int i = 0; i < num_serial_; ++i) {
      const HybridAxis& a = design_.axes[static_cast<std::size_t>(i)];
      q(i) = std::clamp(u(i), a.min, a.max);
    }
    return q;
  };
  const Eigen::Vector3d local_angles =
      angles_from_rotation(R0_.transpose() * rotation_zyx<double>(pose.angles));
  auto local_at = [&](const Eigen::VectorXd& q) {
    Pose local;
    local.position = R0_.transpose() * (pose.position - t0_ - A_ * q);
    local.angles = local_angles;
    return local;
  };
  s.unclamped = A_pinv_ * (pose.position - t0_ - R0_ * design_.home);
  s.serial = clamp(s.unclamped);
  s.local = local_at(s.serial);
  if (parasitic_module_ == nullptr) return s;

  // The module fixes its own local x, y (and rz): the serial axes carry it to the world point.
  s.attained = false;
  for (int iteration = 0; iteration < 50; ++iteration) {
    const std::optional<Pose> actual = parasitic_module_->actual_pose(s.local);
    if (!actual) return s;
    s.unclamped = A_pinv_ * (pose.position - t0_ - R0_ * actual->position);
    const Eigen::VectorXd next = clamp(s.unclamped);
    const double step = (next - s.serial).cwiseAbs().maxCoeff();
    s.serial = next;
    s.local = local_at(s.serial);
    if (step <= 1e-14 * (1.0 + s.serial.cwiseAbs().maxCoeff())) break;
  }
  const std::optional<Pose> actual = parasitic_module_->actual_pose(s.local);
  if (!actual) return s;
  const Eigen::Vector3d reached = t0_ + A_ * s.serial + R0_ * actual->position;
  s.attained = (reached - pose.position).norm() <= kAttainedTolerance;
  return s;
}

void HybridMachine::analyze(MachineData& data, const Pose& pose, const Wrench& wrench,
                            PoseMetrics& out) const {
  auto& d = data_of<HybridData>(data);
  const int n = num_actuators();
  const HybridSplit s = split(pose);
  Wrench local_wrench;
  local_wrench.head<3>() = R0_.transpose() * wrench.head<3>();
  local_wrench.tail<3>() = R0_.transpose() * wrench.tail<3>();
  PoseMetrics& m = d.module_metrics;
  d.module->compliance_metrics = d.compliance_metrics;
  bool maps = false;
  if (module_maps_ != nullptr)
    maps = module_maps_->analyze_with_maps(*d.module, s.local, local_wrench, m, d.module_compliance,
                                           d.module_error_map);
  else
    design_.module->analyze(*d.module, s.local, local_wrench, m);

  out.reachable = m.reachable && s.attained;
  // The module's legs are numbered as their actuators: after the serial axes.
  out.leg_clearance = m.leg_clearance;
  out.clearance_first = m.clearance_first < 0 ? -1 : m.clearance_first + num_serial_;
  out.clearance_second = m.clearance_second < 0 || m.clearance_second >= kPlatformBody
                             ? m.clearance_second
                             : m.clearance_second + num_serial_;
  out.natural_frequencies.resize(0);  // set below with masses and the compliance metrics
  out.q.resize(n);
  out.q << s.serial, m.q;
  out.tau.resize(n);
  out.tau.head(num_serial_) = serial_drive_loads(Jf_, wrench);
  out.tau.tail(n - num_serial_) = m.tau;
  out.singular = m.singular;
  out.singularity_margin = m.singularity_margin;
  out.det_j = m.det_j;
  if (m.singular || !maps) {
    out.singular = true;
    set_singular_metrics(out, d.compliance_metrics, d.matrices);
    if (d.compliance_metrics && module_dynamics_ != nullptr)
      out.natural_frequencies.setZero(natural_frequency_count());
    return;
  }

  // Serial and parallel compliances in series.
  Matrix6d in_series = Matrix6d::Zero();
  in_series.topLeftCorner<3, 3>() = R0_ * d.module_compliance * R0_.transpose();
  add_serial_compliance(Jf_, design_.axes, in_series);
  const Eigen::Matrix3d compliance = in_series.topLeftCorner<3, 3>();
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig;
  eig.computeDirect(compliance, Eigen::EigenvaluesOnly);
  const double c_max = eig.eigenvalues()(2);
  out.stiffness_min = c_max > 0.0 ? 1.0 / c_max : 0.0;
  if (d.compliance_metrics) {
    // The 6x6 compliance: the module's turned by R0, the serial axes' along their directions
    // (in series); loaded: the module's loaded block plus the serial axes (fixed directions, no
    // geometric term).
    Matrix6d turn = Matrix6d::Zero();
    turn.topLeftCorner<3, 3>() = turn.bottomRightCorner<3, 3>() = R0_;
    Matrix6d C = turn * d.module->matrices.compliance * turn.transpose();
    add_serial_compliance(Jf_, design_.axes, C);
    Matrix6d loaded_in_series = Matrix6d::Zero();
    loaded_in_series.topLeftCorner<3, 3>() =
        R0_ * d.module->matrices.loaded_compliance_tt * R0_.transpose();
    add_serial_compliance(Jf_, design_.axes, loaded_in_series);
    const Eigen::Matrix3d loaded = loaded_in_series.topLeftCorner<3, 3>();
    const Matrix6d C_module = turn * d.module->matrices.compliance * turn.transpose();
    fill_compliance_metrics(C, wrench, out, d.matrices);
    d.matrices.loaded_compliance_tt = loaded;
    out.stiffness_min_loaded = m.stiffness_min_loaded > 0.0 ? loaded_stiffness_of(loaded) : 0.0;
    if (module_dynamics_ != nullptr) compute_natural_frequencies(d, s, C_module, out);
  }

  // tcp_error_max over the vertices of the combined error box (zero columns skipped).
  Eigen::Matrix<double, 3, Eigen::Dynamic, 0, 3, 16> columns(3, n);
  int used = 0;
  append_serial_error_columns(Jf_, design_.axes, columns, used);
  for (int j = 0; j < d.module_error_map.cols(); ++j) {
    if (d.module_error_map.col(j).squaredNorm() > 0.0) {
      columns.col(used++) = R0_ * d.module_error_map.col(j);
    }
  }
  out.tcp_error_max = max_norm_over_sign_vectors(columns.leftCols(used));
  if (!out.tau.allFinite() || !std::isfinite(out.tcp_error_max) ||
      !std::isfinite(out.stiffness_min)) {
    out.singular = true;
    set_singular_metrics(out, d.compliance_metrics, d.matrices);
    if (d.compliance_metrics && module_dynamics_ != nullptr)
      out.natural_frequencies.setZero(natural_frequency_count());
  }
}

bool HybridMachine::reachable(MachineData& data, const Pose& pose) const {
  auto& d = data_of<HybridData>(data);
  const HybridSplit s = split(pose);
  return s.attained && design_.module->reachable(*d.module, s.local);
}

FkResult HybridMachine::forward_kinematics(const Eigen::VectorXd& q,
                                           const std::optional<Pose>& guess,
                                           const FkOptions& options) const {
  FkResult result;
  if (q.size() != num_actuators() || !q.head(num_serial_).allFinite()) {
    result.message = fmt::format("{} actuator coordinates expected, the first {} finite",
                                 num_actuators(), num_serial_);
    result.residual = kInf;
    return result;
  }
  const Eigen::VectorXd q_serial = q.head(num_serial_);
  std::optional<Pose> local_guess;
  if (guess) {
    local_guess = Pose{};
    local_guess->position = R0_.transpose() * (guess->position - t0_ - A_ * q_serial);
    local_guess->angles =
        angles_from_rotation(R0_.transpose() * rotation_zyx<double>(guess->angles));
  }
  result = design_.module->forward_kinematics(q.tail(num_actuators() - num_serial_), local_guess,
                                              options);
  result.pose = world_pose(q_serial, result.pose);
  return result;
}

std::optional<Eigen::AlignedBox3d> HybridMachine::workspace_search_box(
    const std::vector<Eigen::Matrix3d>& orientations) const {
  std::vector<Eigen::Matrix3d> local;
  local.reserve(orientations.size());
  for (const Eigen::Matrix3d& R : orientations) local.push_back(R0_.transpose() * R);
  const std::optional<Eigen::AlignedBox3d> module_box = design_.module->workspace_search_box(local);
  if (!module_box) return std::nullopt;
  Eigen::AlignedBox3d box;  // empty
  if (module_box->isEmpty()) return box;
  const unsigned serial_vertices = 1u << num_serial_;
  for (int c = 0; c < 8; ++c) {
    const Eigen::Vector3d corner =
        t0_ + R0_ * module_box->corner(static_cast<Eigen::AlignedBox3d::CornerType>(c));
    for (unsigned g = 0; g < serial_vertices; ++g) {
      Eigen::Vector3d point = corner;
      for (int i = 0; i < num_serial_; ++i) {
        const HybridAxis& a = design_.axes[static_cast<std::size_t>(i)];
        point += ((g >> i) & 1u ? a.max : a.min) * A_.col(i);
      }
      box.extend(point);
    }
  }
  return box;
}

std::string HybridMachine::actuator_coordinates_requirement(const Eigen::VectorXd& q) const {
  if (q.size() != num_actuators()) return fmt::format("{} actuator coordinates", num_actuators());
  const std::string inner =
      design_.module->actuator_coordinates_requirement(q.tail(num_actuators() - num_serial_));
  if (inner.empty()) return {};
  return fmt::format("{} serial axis positions (m), then {}", num_serial_, inner);
}

Eigen::VectorXd HybridMachine::free_axes(const HybridSplit& s) const {
  Eigen::VectorXd free(num_serial_);
  for (int i = 0; i < num_serial_; ++i) {
    const HybridAxis& a = design_.axes[static_cast<std::size_t>(i)];
    free(i) = s.unclamped(i) > a.min && s.unclamped(i) < a.max ? 1.0 : 0.0;
  }
  return free;
}

bool HybridMachine::twist_jacobian(MachineData& data, const Pose& pose, Eigen::MatrixXd& J) const {
  auto& d = data_of<HybridData>(data);
  const HybridSplit s = split(pose);
  if (!design_.module->twist_jacobian(*d.module, s.local, d.module_jacobian)) return false;
  const int n = num_actuators();
  const int n_module = n - num_serial_;
  // Axes strictly inside their range follow; clamped ones stand still.
  const Eigen::VectorXd free = free_axes(s);
  Eigen::Matrix<double, 6, 6> to_local = Eigen::Matrix<double, 6, 6>::Zero();
  to_local.topLeftCorner<3, 3>() = R0_.transpose();
  to_local.bottomRightCorner<3, 3>() = R0_.transpose();
  Eigen::MatrixXd out(n, 6);
  if (parasitic_module_ == nullptr) {
    // q_s_dot = D A^+ v; local twist = to_local [v - A q_s_dot; omega].
    Eigen::MatrixXd serial = Eigen::MatrixXd::Zero(num_serial_, 6);
    serial.leftCols<3>() = free.asDiagonal() * A_pinv_;
    Eigen::Matrix<double, 6, 6> remaining = Eigen::Matrix<double, 6, 6>::Identity();
    remaining.topLeftCorner<3, 3>() -= A_ * serial.leftCols<3>();
    out.topRows(num_serial_) = serial;
    out.bottomRows(n_module) = d.module_jacobian * to_local * remaining;
  } else {
    // [A D, R0 T_v; 0, R0 T_w] [q_s_dot; eta] = xi in the least-squares sense.
    const Eigen::MatrixXd T = parasitic_module_->twist_basis(*d.module);  // 6 x dof
    const int dof = static_cast<int>(T.cols());
    Eigen::MatrixXd M = Eigen::MatrixXd::Zero(6, num_serial_ + dof);
    M.topLeftCorner(3, num_serial_) = A_ * free.asDiagonal();
    M.topRightCorner(3, dof) = R0_ * T.topRows(3);
    M.bottomRightCorner(3, dof) = R0_ * T.bottomRows(3);
    const Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd> cod(M);
    const Eigen::MatrixXd M_pinv = cod.pseudoInverse();
    out.topRows(num_serial_) = M_pinv.topRows(num_serial_);
    out.bottomRows(n_module) = d.module_jacobian * T * M_pinv.bottomRows(dof);
  }
  if (!out.allFinite()) return false;
  J = std::move(out);
  return true;
}

}  // namespace pkmopt

namespace pkmopt {

bool HybridMachine::sketch(MachineData& data, const Pose& pose, MachineSketch& out) const {
  if (!pose.position.allFinite() || !pose.angles.allFinite()) return false;
  auto& d = data_of<HybridData>(data);
  const HybridSplit s = split(pose);
  MachineSketch module_sketch;
  if (!design_.module->sketch(*d.module, s.local, module_sketch)) return false;
  // Module-local points to the world: p -> R0 p + t0 + A q_s.
  const Eigen::Vector3d shift = t0_ + A_ * s.serial;
  auto world = [&](const Eigen::Vector3d& p) -> Eigen::Vector3d { return R0_ * p + shift; };
  out = MachineSketch{};
  // Each axis's travel, carried by the axes before it, from the mount t0.
  Eigen::Vector3d carried = t0_;
  for (int i = 0; i < num_serial_; ++i) {
    const HybridAxis& axis = design_.axes[static_cast<std::size_t>(i)];
    const Eigen::Vector3d a = A_.col(i);
    out.lines.push_back(
        {carried + axis.min * a, carried + axis.max * a, MachineSketch::Part::kGuide, -1});
    carried += s.serial(i) * a;
  }
  for (MachineSketch::Line line : module_sketch.lines) {
    line.from = world(line.from);
    line.to = world(line.to);
    if (line.leg >= 0) line.leg += num_serial_;  // actuators are numbered axes first
    out.lines.push_back(line);
  }
  for (const Eigen::Vector3d& p : module_sketch.base_joints) out.base_joints.push_back(world(p));
  for (const Eigen::Vector3d& p : module_sketch.platform_joints)
    out.platform_joints.push_back(world(p));
  out.tcp = world(module_sketch.tcp);
  out.reachable = module_sketch.reachable && s.attained;
  return true;
}

std::optional<double> HybridMachine::envelope_volume() const {
  const std::optional<double> module_volume = design_.module->envelope_volume();
  if (!module_volume) return std::nullopt;
  const double side = std::cbrt(*module_volume);
  double volume = 1.0;
  for (int k = 0; k < 3; ++k) {
    double travel = 0.0;
    for (int i = 0; i < num_serial_; ++i) {
      const HybridAxis& a = design_.axes[static_cast<std::size_t>(i)];
      travel += (a.max - a.min) * std::abs(A_(k, i));
    }
    volume *= side + travel;
  }
  return volume;
}

}  // namespace pkmopt
