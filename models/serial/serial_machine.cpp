#include "models/serial/serial_machine.hpp"

#include <fmt/format.h>

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <Eigen/LU>
#include <Eigen/SVD>
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <utility>

#include "models/core/linalg.hpp"
#include "models/core/require.hpp"
#include "models/serial/serial_statics.hpp"
#include "models/stiffness/compliance_metrics.hpp"

namespace pkmopt {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kTwoPi = 2.0 * std::numbers::pi;

double middle(const SerialAxis& a) { return 0.5 * (a.min + a.max); }

// The value of a rotary axis moved by whole turns to the one nearest the middle of its range.
double nearest_turn(double value, const SerialAxis& a) {
  return value + kTwoPi * std::round((middle(a) - value) / kTwoPi);
}

double excess_of(double value, const SerialAxis& a) {
  return std::max({a.min - value, value - a.max, 0.0});
}

// The metrics that a pose without any branch (the tool axis out of reach) gets.
void set_unreachable(PoseMetrics& out, bool compliance_metrics, PoseCompliance& matrices) {
  out.reachable = false;
  out.singular = true;
  out.det_j = 0.0;
  set_singular_metrics(out, compliance_metrics, matrices);
}

}  // namespace

SerialMachine::SerialMachine(SerialDesign design) : design_(std::move(design)) {
  const SerialChain& chain = design_.chain;
  const int variables = chain.num_variables();
  require(design_.spindle >= -1 && design_.spindle < variables,
          fmt::format("serial: spindle index {} is not one of the {} axes", design_.spindle,
                      variables));
  int k = 0;
  for (const ChainElement& e : chain.elements()) {
    if (!e.variable) continue;
    if (k == design_.spindle) {
      require(e.motion >= 4, "serial: the spindle must be a rotary axis (motion 4, 5 or 6)");
    } else {
      feed_.push_back(k);
      rotary_.push_back(e.motion >= 4);
    }
    ++k;
  }
  const auto rotaries = std::count(rotary_.begin(), rotary_.end(), true);
  require(rotaries == 2 && feed_.size() == 5,
          fmt::format("serial: expected two rotary and three linear feed axes besides the spindle "
                      "(a 5-axis machine), found {} rotary and {} linear in '{}'",
                      rotaries, feed_.size() - static_cast<std::size_t>(rotaries), chain.code()));
  for (int i = 0; i < 5; ++i) {
    if (!rotary_[static_cast<std::size_t>(i)]) continue;
    (first_rotary_ < 0 ? first_rotary_ : second_rotary_) = i;
  }
  require(design_.axes.size() == feed_.size(),
          fmt::format("serial: {} feed axes need {} axis entries, found {}", feed_.size(),
                      feed_.size(), design_.axes.size()));
  for (std::size_t i = 0; i < design_.axes.size(); ++i) {
    const SerialAxis& a = design_.axes[i];
    require(std::isfinite(a.min) && std::isfinite(a.max) && a.min <= a.max,
            fmt::format("serial: axis {} range must be finite with min <= max, found [{}, {}]",
                        i + 1, a.min, a.max));
    require(std::isfinite(a.stiffness) && a.stiffness >= 0.0,
            fmt::format("serial: axis {} stiffness must be >= 0, found {}", i + 1, a.stiffness));
    require(std::isfinite(a.error) && a.error >= 0.0,
            fmt::format("serial: axis {} error must be >= 0, found {}", i + 1, a.error));
    require(a.mass == 0.0, "serial: axis masses are not modelled for serial machines");
  }
  require(design_.tool_point.allFinite(), "serial: the tool point must be finite");
  require(design_.tool_axis.allFinite() && design_.tool_axis.norm() > 1e-12,
          "serial: the tool axis must be a finite nonzero vector");
  design_.tool_axis.normalize();
  require(std::isfinite(design_.characteristic_length) && design_.characteristic_length > 0.0,
          fmt::format("serial: characteristic_length must be > 0, found {}",
                      design_.characteristic_length));
  tool_align_ = Eigen::Quaterniond::FromTwoVectors(Eigen::Vector3d::UnitZ(), design_.tool_axis)
                    .toRotationMatrix();
  // The IK's own checks (parallel rotary axes, dependent linear axes show per pose).
  (void)five_axis_inverse_kinematics(chain, design_.spindle, design_.tool_point, design_.tool_axis,
                                     Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitZ());
}

bool SerialMachine::revolute_actuator(int i) const {
  return i >= 0 && i < num_actuators() && rotary_[static_cast<std::size_t>(i)];
}

std::unique_ptr<MachineData> SerialMachine::make_data() const { return new_data<SerialData>(); }

Eigen::VectorXd SerialMachine::full_coordinates(const Eigen::VectorXd& q) const {
  Eigen::VectorXd full = Eigen::VectorXd::Zero(design_.chain.num_variables());
  for (std::size_t i = 0; i < feed_.size(); ++i) full(feed_[i]) = q(static_cast<Eigen::Index>(i));
  return full;
}

Eigen::Vector3d SerialMachine::tool_axis_at(const Eigen::VectorXd& q) const {
  return design_.chain.transform(full_coordinates(q)).topLeftCorner<3, 3>() * design_.tool_axis;
}

FeedJacobian SerialMachine::feed_jacobian(const Eigen::VectorXd& q) const {
  const FeedJacobian all = design_.chain.twist_jacobian(full_coordinates(q), design_.tool_point);
  FeedJacobian J(6, num_actuators());
  for (std::size_t i = 0; i < feed_.size(); ++i)
    J.col(static_cast<Eigen::Index>(i)) = all.col(feed_[i]);
  return J;
}

Eigen::MatrixXd SerialMachine::geometric_stiffness(const FeedJacobian& Jf,
                                                   const Wrench& wrench) const {
  // Column j = [v_j; omega_j] (rotary) or [u_j; 0] (linear). An axis k before j turns column j
  // with it (rotary k: d col_j = [u_k x v_j; u_k x omega_j]; linear k: no change); an axis k at or
  // after j moves only the tool point, which a rotary j sees as dv_j = u_j x v_k.
  const int n = num_actuators();
  Eigen::MatrixXd Kg = Eigen::MatrixXd::Zero(n, n);
  for (int j = 0; j < n; ++j) {
    const Eigen::Vector3d v_j = Jf.block<3, 1>(0, j), w_j = Jf.block<3, 1>(3, j);
    for (int k = 0; k < n; ++k) {
      Vector6d d = Vector6d::Zero();
      if (k < j && rotary_[static_cast<std::size_t>(k)]) {
        const Eigen::Vector3d u_k = Jf.block<3, 1>(3, k);
        d.head<3>() = u_k.cross(v_j);
        d.tail<3>() = u_k.cross(w_j);
      } else if (k >= j && rotary_[static_cast<std::size_t>(j)]) {
        d.head<3>() = w_j.cross(Jf.block<3, 1>(0, k));
      }
      Kg(j, k) = d.dot(wrench);
    }
  }
  return Kg;
}

std::optional<SerialMachine::Branch> SerialMachine::inverse_kinematics(const Pose& pose) const {
  if (!pose.position.allFinite() || !pose.angles.allFinite()) return std::nullopt;
  const Eigen::Vector3d a0 = rotation_zyx<double>(pose.angles).col(2);
  const SerialAxis& free_axis = design_.axes[static_cast<std::size_t>(first_rotary_)];
  const std::vector<FiveAxisSolution> solutions =
      five_axis_inverse_kinematics(design_.chain, design_.spindle, design_.tool_point,
                                   design_.tool_axis, pose.position, a0, middle(free_axis));
  std::optional<Branch> best;
  const SerialAxis& tilt = design_.axes[static_cast<std::size_t>(second_rotary_)];
  for (const FiveAxisSolution& s : solutions) {
    Branch b;
    b.q.resize(num_actuators());
    b.singular = s.singular;
    for (int i = 0; i < num_actuators(); ++i) {
      const SerialAxis& a = design_.axes[static_cast<std::size_t>(i)];
      double v = s.q(feed_[static_cast<std::size_t>(i)]);
      if (rotary_[static_cast<std::size_t>(i)]) v = nearest_turn(v, a);
      b.q(i) = v;
      b.excess = std::max(b.excess, excess_of(v, a));
    }
    if (!b.q.allFinite()) continue;
    b.in_range = b.excess == 0.0;
    bool better = !best;
    if (best && b.in_range != best->in_range) {
      better = b.in_range;
    } else if (best && !b.in_range) {
      better = b.excess < best->excess;
    } else if (best) {
      const double d_new = std::abs(b.q(second_rotary_) - middle(tilt));
      const double d_old = std::abs(best->q(second_rotary_) - middle(tilt));
      better = d_new < d_old - 1e-9 ||
               (d_new <= d_old + 1e-9 && b.q(second_rotary_) > best->q(second_rotary_));
    }
    if (better) best = std::move(b);
  }
  return best;
}

void SerialMachine::conditioning(const FeedJacobian& Jf, const Eigen::Vector3d& a0,
                                 PoseMetrics& out) const {
  Matrix6d M;
  M.leftCols(5) = Jf;
  M.col(5) << 0.0, 0.0, 0.0, a0;
  out.det_j = M.determinant() + 0.0;
  // M_h = diag(I, L I) M diag(c): the rotary columns and the spin over L.
  const double L = design_.characteristic_length;
  Matrix6d Mh = M;
  Mh.bottomRows<3>() *= L;
  for (int i = 0; i < 5; ++i)
    if (rotary_[static_cast<std::size_t>(i)]) Mh.col(i) /= L;
  Mh.col(5) /= L;
  const Eigen::JacobiSVD<Matrix6d> svd(Mh);
  const auto& sv = svd.singularValues();
  const double rcond = sv(0) > 0.0 ? sv(5) / sv(0) : 0.0;
  out.singular = !(rcond >= kSingularRcond);
  out.singularity_margin = out.singular ? 0.0 : rcond;
}

void SerialMachine::loaded_compliance(const FeedJacobian& Jf, const Wrench& wrench,
                                      PoseMetrics& out, PoseCompliance& matrices) const {
  const int n = num_actuators();
  Eigen::VectorXd D(n);
  std::vector<int> soft;  // the elastic axes
  for (int i = 0; i < n; ++i) {
    const double k = design_.axes[static_cast<std::size_t>(i)].stiffness;
    D(i) = k > 0.0 ? 1.0 / k : 0.0;
    if (k > 0.0) soft.push_back(i);
  }
  if (soft.empty()) {  // every drive rigid: nothing yields
    matrices.loaded_compliance_tt.setZero();
    out.stiffness_min_loaded = kInf;
    return;
  }
  const Eigen::MatrixXd Kg = geometric_stiffness(Jf, wrench);
  // Stable when K - K_g is positive definite on the elastic axes (its symmetric part).
  const Eigen::MatrixXd Kg_sym = 0.5 * (Kg + Kg.transpose());
  const Eigen::MatrixXd S =
      Eigen::MatrixXd(D(soft).cwiseInverse().asDiagonal()) - Kg_sym(soft, soft);
  const Eigen::LLT<Eigen::MatrixXd> llt(S);
  // C_T = J_f (I - D K_g)^-1 D J_f^T, its translational block.
  const Eigen::MatrixXd A = Eigen::MatrixXd::Identity(n, n) - D.asDiagonal() * Kg;
  const Eigen::MatrixXd X =
      Eigen::PartialPivLU<Eigen::MatrixXd>(A).solve(D.asDiagonal() * Jf.transpose());
  const Eigen::Matrix3d loaded = Jf.topRows<3>() * X.leftCols<3>();
  if (llt.info() != Eigen::Success || !loaded.allFinite()) {
    matrices.loaded_compliance_tt.setConstant(kInf);
    out.stiffness_min_loaded = 0.0;
    return;
  }
  matrices.loaded_compliance_tt = loaded;
  out.stiffness_min_loaded = loaded_stiffness_of(loaded);
  if (out.stiffness_min_loaded == 0.0 && loaded.isZero(0.0)) out.stiffness_min_loaded = kInf;
}

void SerialMachine::analyze(MachineData& data, const Pose& pose, const Wrench& wrench,
                            PoseMetrics& out) const {
  auto& d = data_of<SerialData>(data);
  const int n = num_actuators();
  out.q = Eigen::VectorXd::Zero(n);
  out.tau = Eigen::VectorXd::Zero(n);
  out.natural_frequencies.resize(0);
  out.leg_clearance = kInf;
  out.clearance_first = out.clearance_second = -1;
  const std::optional<Branch> branch = inverse_kinematics(pose);
  if (!branch || !wrench.allFinite()) {
    set_unreachable(out, d.compliance_metrics, d.matrices);
    return;
  }
  out.q = branch->q;
  out.reachable = branch->in_range;

  const FeedJacobian Jf = feed_jacobian(branch->q);
  conditioning(Jf, tool_axis_at(branch->q), out);
  out.tau = serial_drive_loads(Jf, wrench);

  // The drives in series.
  Matrix6d C = Matrix6d::Zero();
  add_serial_compliance(Jf, design_.axes, C);
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig;
  eig.computeDirect(C.topLeftCorner<3, 3>(), Eigen::EigenvaluesOnly);
  const double c_max = eig.eigenvalues()(2);
  out.stiffness_min = c_max > 0.0 ? 1.0 / c_max : kInf;
  if (d.compliance_metrics) {
    fill_compliance_metrics(C, wrench, out, d.matrices);
    loaded_compliance(Jf, wrench, out, d.matrices);
  }

  Eigen::Matrix<double, 3, Eigen::Dynamic, 0, 3, 5> columns(3, n);
  int used = 0;
  append_serial_error_columns(Jf, design_.axes, columns, used);
  out.tcp_error_max = max_norm_over_sign_vectors(columns.leftCols(used));
}

bool SerialMachine::reachable(MachineData& data, const Pose& pose) const {
  (void)data_of<SerialData>(data);
  const std::optional<Branch> branch = inverse_kinematics(pose);
  return branch && branch->in_range;
}

FkResult SerialMachine::forward_kinematics(const Eigen::VectorXd& q,
                                           const std::optional<Pose>& /*guess*/,
                                           const FkOptions& /*options*/) const {
  FkResult result;
  if (const std::string expected = actuator_coordinates_requirement(q); !expected.empty()) {
    result.message = "expected " + expected;
    result.residual = kInf;
    return result;
  }
  const Eigen::Matrix4d T = design_.chain.transform(full_coordinates(q));
  result.pose.position = T.topLeftCorner<3, 3>() * design_.tool_point + T.topRightCorner<3, 1>();
  result.pose.angles = angles_from_rotation(Eigen::Matrix3d(T.topLeftCorner<3, 3>() * tool_align_));
  result.converged = true;
  return result;
}

std::string SerialMachine::actuator_coordinates_requirement(const Eigen::VectorXd& q) const {
  if (q.size() == num_actuators() && q.allFinite()) return {};
  return fmt::format("{} finite axis values", num_actuators());
}

bool SerialMachine::twist_jacobian(MachineData& data, const Pose& pose, Eigen::MatrixXd& J) const {
  (void)data_of<SerialData>(data);
  const std::optional<Branch> branch = inverse_kinematics(pose);
  if (!branch) return false;
  Matrix6d M;
  M.leftCols(5) = feed_jacobian(branch->q);
  M.col(5) << Eigen::Vector3d::Zero(), tool_axis_at(branch->q);
  const Eigen::FullPivLU<Matrix6d> lu(M);
  if (!lu.isInvertible() || lu.rcond() < kSingularRcond) return false;
  const Matrix6d inverse = lu.inverse();
  if (!inverse.allFinite()) return false;
  J = inverse.topRows(5);
  return true;
}

std::optional<double> SerialMachine::reach_excess(const Pose& pose) const {
  const std::optional<Branch> branch = inverse_kinematics(pose);
  if (!branch) return std::nullopt;
  return branch->excess;
}

std::optional<double> SerialMachine::envelope_volume() const {
  const double reach = design_.tool_point.norm();
  double volume = 1.0;
  for (std::size_t i = 0; i < design_.axes.size(); ++i)
    if (!revolute_actuator(static_cast<int>(i)))
      volume *= design_.axes[i].max - design_.axes[i].min + 2.0 * reach;
  return volume;
}

std::optional<Eigen::AlignedBox3d> SerialMachine::workspace_search_box(
    const std::vector<Eigen::Matrix3d>& /*orientations*/) const {
  // From the tool back to the workpiece: p_before = A_k(v) p_after over the element's values.
  Eigen::AlignedBox3d box(design_.tool_point, design_.tool_point);
  const std::vector<ChainElement>& elements = design_.chain.elements();
  int variable = design_.chain.num_variables();
  for (auto e = elements.rbegin(); e != elements.rend(); ++e) {
    double lo = e->value, hi = e->value;
    if (e->variable) {
      --variable;
      lo = hi = 0.0;  // the spindle
      const auto feed = std::find(feed_.begin(), feed_.end(), variable);
      if (feed != feed_.end()) {
        const SerialAxis& a = design_.axes[static_cast<std::size_t>(feed - feed_.begin())];
        lo = a.min;
        hi = a.max;
      }
    }
    const int axis = (e->motion - 1) % 3;
    if (e->motion <= 3) {
      box.min()(axis) += lo;
      box.max()(axis) += hi;
      continue;
    }
    if (lo == hi) {  // a fixed rotation: the box of its turned corners
      const Eigen::Matrix3d R = elementary_motion<double>(e->motion, lo).topLeftCorner<3, 3>();
      Eigen::AlignedBox3d turned;
      for (int c = 0; c < 8; ++c)
        turned.extend(R * box.corner(static_cast<Eigen::AlignedBox3d::CornerType>(c)));
      box = turned;
      continue;
    }
    // A turning axis: the disc of the largest radius about it.
    const int u = (axis + 1) % 3, w = (axis + 2) % 3;
    double radius = 0.0;
    for (int c = 0; c < 8; ++c) {
      const Eigen::Vector3d p = box.corner(static_cast<Eigen::AlignedBox3d::CornerType>(c));
      radius = std::max(radius, std::hypot(p(u), p(w)));
    }
    box.min()(u) = box.min()(w) = -radius;
    box.max()(u) = box.max()(w) = radius;
  }
  return box;
}

bool SerialMachine::sketch(MachineData& data, const Pose& pose, MachineSketch& out) const {
  (void)data_of<SerialData>(data);
  const std::optional<Branch> branch = inverse_kinematics(pose);
  if (!branch) return false;
  out = MachineSketch{};
  const Eigen::VectorXd q = full_coordinates(branch->q);
  Eigen::Matrix4d T = Eigen::Matrix4d::Identity();
  int variable = 0;
  std::size_t feed = 0;
  for (const ChainElement& e : design_.chain.elements()) {
    const double v = e.variable ? q(variable) : e.value;
    const Eigen::Vector3d from = T.topRightCorner<3, 1>();
    T = T * elementary_motion<double>(e.motion, v);
    const Eigen::Vector3d to = T.topRightCorner<3, 1>();
    int leg = -1;
    if (e.variable && feed < feed_.size() && feed_[feed] == variable)
      leg = static_cast<int>(feed++);
    if (e.variable) ++variable;
    if ((to - from).norm() > 0.0)
      out.lines.push_back(
          {from, to, leg >= 0 ? MachineSketch::Part::kActuator : MachineSketch::Part::kLink, leg});
  }
  out.tcp = T.topLeftCorner<3, 3>() * design_.tool_point + T.topRightCorner<3, 1>();
  out.lines.push_back({T.topRightCorner<3, 1>(), out.tcp, MachineSketch::Part::kTool, -1});
  out.reachable = branch->in_range;
  return true;
}

}  // namespace pkmopt
