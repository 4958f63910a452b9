#include "problems/calibration.hpp"

#include <ceres/ceres.h>
#include <ceres/rotation.h>
#include <fmt/format.h>

#include <Eigen/Cholesky>
#include <Eigen/QR>
#include <Eigen/SVD>
#include <algorithm>
#include <cmath>
#include <memory>
#include <numeric>

namespace pkmopt {
namespace {

constexpr const char* kAxisNames[3] = {"x", "y", "z"};
constexpr const char* kFrameNames[6] = {"x", "y", "z", "rx", "ry", "rz"};

bool is_joint_coordinate(int index) {
  return index < kCalibrationMachineParameters && index % kCalibrationLegParameters < 6;
}

// The 6 residuals of the measured pose: position and orientation of the target predicted from
// the TCP pose, the instrument and the target transforms, minus the measurement.
struct MeasuredPoseResidual {
  Eigen::Vector3d measured_position;
  Eigen::Matrix3d measured_rotation_transpose;
  double inv_sigma_position;
  double inv_sigma_orientation;

  template <typename T>
  bool operator()(const T* pose, const T* instrument, const T* target, T* out) const {
    const Vec3<T> position(pose[0], pose[1], pose[2]);
    const Mat3<T> R = rotation_zyx<T>(Vec3<T>(pose[3], pose[4], pose[5]));
    const Vec3<T> t_instrument(instrument[0], instrument[1], instrument[2]);
    const Mat3<T> R_instrument =
        rotation_zyx<T>(Vec3<T>(instrument[3], instrument[4], instrument[5]));
    const Vec3<T> t_target(target[0], target[1], target[2]);
    const Mat3<T> R_target = rotation_zyx<T>(Vec3<T>(target[3], target[4], target[5]));
    const Vec3<T> predicted_position =
        R_instrument.transpose() * (position + R * t_target - t_instrument);
    const Mat3<T> error_rotation =
        measured_rotation_transpose.cast<T>() * R_instrument.transpose() * R * R_target;
    T angle_axis[3];
    const T* error_data = error_rotation.data();
    ceres::RotationMatrixToAngleAxis(ceres::ColumnMajorAdapter3x3(error_data), angle_axis);
    for (int c = 0; c < 3; ++c) {
      out[c] = (predicted_position(c) - T(measured_position(c))) * T(inv_sigma_position);
      out[3 + c] = angle_axis[c] * T(inv_sigma_orientation);
    }
    return true;
  }
};

using MeasuredPoseCost = ceres::AutoDiffCostFunction<MeasuredPoseResidual, 6, 6, 6, 6>;

// The 12 whitened residuals of one pose as one residual block (so that the robust loss acts on
// the pose's whole chi^2), parameter blocks machine (48), TCP pose (6), instrument (6),
// target (6). Leg i's residual depends only on the pose and leg i's 8 parameters; its
// derivatives are analytic (checked against central differences in the tests). The 6
// measured-pose residuals are differentiated by autodiff over the pose and the two frames
// (18 jets), or over the pose alone (6 jets) when both frames are held constant.
class PoseCostFunction final
    : public ceres::SizedCostFunction<12, kCalibrationMachineParameters, 6, 6, 6> {
 public:
  PoseCostFunction(const Eigen::Vector3d& tcp, const CalibrationMeasurement& m,
                   const CalibrationOptions& options)
      : measured_{m.pose.position, rotation_zyx<double>(m.pose.angles).transpose(),
                  1.0 / options.sigma_position, 1.0 / options.sigma_orientation},
        measured_cost_(std::make_unique<MeasuredPoseCost>(new MeasuredPoseResidual(measured_))),
        tcp_(tcp),
        stroke_(m.stroke),
        inv_sigma_actuator_(1.0 / options.sigma_actuator) {}

  bool Evaluate(double const* const* parameters, double* residuals,
                double** jacobians) const override {
    const double* machine = parameters[0];
    const double* pose = parameters[1];
    const double* instrument = parameters[2];
    const double* target = parameters[3];
    // Leg residuals, with their analytic derivatives. With R = Rz Ry Rx, v = b_i - tcp,
    // l = p + R v - a_i and u = l / |l|:  d|l|/da = -u, d|l|/db = R^T u, d|l|/dp = u,
    // d(R v)/drx = Rz Ry (e_x x Rx v), d(R v)/dry = Rz (e_y x Ry Rx v), d(R v)/drz = e_z x R v.
    const Eigen::Map<const Eigen::Vector3d> position(pose);
    const Eigen::Matrix3d Rx = rotation_zyx<double>(Eigen::Vector3d(pose[3], 0.0, 0.0));
    const Eigen::Matrix3d Ry = rotation_zyx<double>(Eigen::Vector3d(0.0, pose[4], 0.0));
    const Eigen::Matrix3d Rz = rotation_zyx<double>(Eigen::Vector3d(0.0, 0.0, pose[5]));
    const Eigen::Matrix3d RzRy = Rz * Ry;
    const Eigen::Matrix3d R = RzRy * Rx;
    const double w = inv_sigma_actuator_;
    for (int i = 0; i < 6; ++i) {
      const double* leg = machine + kCalibrationLegParameters * i;
      const Eigen::Map<const Eigen::Vector3d> base_joint(leg);
      const Eigen::Vector3d v = Eigen::Map<const Eigen::Vector3d>(leg + 3) - tcp_;
      const Eigen::Vector3d Rv = R * v;
      const Eigen::Vector3d l = position + Rv - base_joint;
      const double length = l.norm();
      const double from_reading = leg[6] + (1.0 + leg[7]) * stroke_(i);
      residuals[i] = (length - from_reading) * w;
      if (!jacobians) continue;
      const Eigen::Vector3d u = l / length;
      if (jacobians[0]) {
        double* row = jacobians[0] + kCalibrationMachineParameters * i;
        std::fill(row, row + kCalibrationMachineParameters, 0.0);
        double* d_leg = row + kCalibrationLegParameters * i;
        const Eigen::Vector3d d_platform = R.transpose() * u;
        for (int c = 0; c < 3; ++c) {
          d_leg[c] = -u(c) * w;
          d_leg[3 + c] = d_platform(c) * w;
        }
        d_leg[6] = -w;
        d_leg[7] = -stroke_(i) * w;
      }
      if (jacobians[1]) {
        const Eigen::Vector3d Rx_v = Rx * v;
        const Eigen::Vector3d d_rx = RzRy * Eigen::Vector3d::UnitX().cross(Rx_v);
        const Eigen::Vector3d d_ry = Rz * Eigen::Vector3d::UnitY().cross(Ry * Rx_v);
        const Eigen::Vector3d d_rz = Eigen::Vector3d::UnitZ().cross(Rv);
        double* d_pose = jacobians[1] + 6 * i;
        for (int c = 0; c < 3; ++c) d_pose[c] = u(c) * w;
        d_pose[3] = u.dot(d_rx) * w;
        d_pose[4] = u.dot(d_ry) * w;
        d_pose[5] = u.dot(d_rz) * w;
      }
    }
    // Rows 6..11 of the pose block's Jacobian are the measured-pose piece; the machine
    // parameters do not enter it.
    if (jacobians && jacobians[0]) {
      std::fill(jacobians[0] + 6 * kCalibrationMachineParameters,
                jacobians[0] + 12 * kCalibrationMachineParameters, 0.0);
    }
    double* pose_rows = jacobians && jacobians[1] ? jacobians[1] + 36 : nullptr;
    if (jacobians && (jacobians[2] || jacobians[3])) {
      const double* frame_parameters[3] = {pose, instrument, target};
      double* frame_jacobians[3] = {pose_rows, jacobians[2] ? jacobians[2] + 36 : nullptr,
                                    jacobians[3] ? jacobians[3] + 36 : nullptr};
      if (jacobians[2]) std::fill(jacobians[2], jacobians[2] + 36, 0.0);
      if (jacobians[3]) std::fill(jacobians[3], jacobians[3] + 36, 0.0);
      return measured_cost_->Evaluate(frame_parameters, residuals + 6, frame_jacobians);
    }
    if (pose_rows == nullptr) {
      return measured_(pose, instrument, target, residuals + 6);
    }
    // Frames held: differentiate with respect to the pose only (6-dual-number jets).
    using PoseJet = ceres::Jet<double, 6>;
    std::array<PoseJet, 6> pose_jet, instrument_jet, target_jet, out;
    for (int j = 0; j < 6; ++j) {
      pose_jet[static_cast<std::size_t>(j)] = PoseJet(pose[j], j);
      instrument_jet[static_cast<std::size_t>(j)] = PoseJet(instrument[j]);
      target_jet[static_cast<std::size_t>(j)] = PoseJet(target[j]);
    }
    if (!measured_(pose_jet.data(), instrument_jet.data(), target_jet.data(), out.data())) {
      return false;
    }
    for (int r = 0; r < 6; ++r) {
      residuals[6 + r] = out[static_cast<std::size_t>(r)].a;
      for (int c = 0; c < 6; ++c) pose_rows[6 * r + c] = out[static_cast<std::size_t>(r)].v(c);
    }
    return true;
  }

 private:
  MeasuredPoseResidual measured_;
  std::unique_ptr<MeasuredPoseCost> measured_cost_;
  Eigen::Vector3d tcp_;
  Vec6<double> stroke_;
  double inv_sigma_actuator_;
};

Vec6<double> pose_vector(const Pose& pose) {
  Vec6<double> v;
  v << pose.position, pose.angles;
  return v;
}

Pose pose_from_vector(const Vec6<double>& v) { return Pose{v.head<3>(), v.tail<3>()}; }

Pose frame_pose(const CalibrationVector& x, int start) {
  return Pose{x.segment<3>(start), x.segment<3>(start + 3)};
}

std::vector<int> free_indices_of(const CalibrationMask& free) {
  std::vector<int> indices;
  for (int i = 0; i < kCalibrationParameters; ++i) {
    if (free[static_cast<std::size_t>(i)]) indices.push_back(i);
  }
  return indices;
}

// Fixes the coordinates of a parameter block that are not free.
void constrain_block(ceres::Problem& problem, double* block, int start, int size,
                     const CalibrationMask& free) {
  std::vector<int> fixed;
  for (int i = 0; i < size; ++i) {
    if (!free[static_cast<std::size_t>(start + i)]) fixed.push_back(i);
  }
  if (static_cast<int>(fixed.size()) == size) {
    problem.SetParameterBlockConstant(block);
  } else if (!fixed.empty()) {
    problem.SetManifold(block, new ceres::SubsetManifold(size, fixed));
  }
}

struct FitOutcome {
  bool converged = false;
  int iterations = 0;
  std::string message;
};

// The EIV least-squares problem over the poses in `active` (indices); the parameter blocks
// are x's machine, instrument and target segments and the pose vectors, all owned by the caller.
void build_eiv_problem(ceres::Problem& problem, const Eigen::Vector3d& tcp, CalibrationVector& x,
                       std::vector<Vec6<double>>& poses,
                       const std::vector<CalibrationMeasurement>& measurements,
                       const std::vector<int>& active, const CalibrationOptions& options,
                       bool robust) {
  double* machine = x.data();
  double* instrument = x.data() + kCalibrationInstrumentIndex;
  double* target = x.data() + kCalibrationTargetIndex;
  for (int k : active) {
    const auto& m = measurements[static_cast<std::size_t>(k)];
    ceres::LossFunction* loss = nullptr;
    if (robust && options.loss == CalibrationLoss::kHuber) {
      loss = new ceres::HuberLoss(options.loss_scale);
    } else if (robust && options.loss == CalibrationLoss::kCauchy) {
      loss = new ceres::CauchyLoss(options.loss_scale);
    }
    problem.AddResidualBlock(new PoseCostFunction(tcp, m, options), loss, machine,
                             poses[static_cast<std::size_t>(k)].data(), instrument, target);
  }
  constrain_block(problem, machine, 0, kCalibrationMachineParameters, options.free);
  constrain_block(problem, instrument, kCalibrationInstrumentIndex, 6, options.free);
  constrain_block(problem, target, kCalibrationTargetIndex, 6, options.free);
}

// Solves the EIV problem over the poses in `active`, updating x and the pose vectors.
FitOutcome solve_eiv(const Eigen::Vector3d& tcp, CalibrationVector& x,
                     std::vector<Vec6<double>>& poses,
                     const std::vector<CalibrationMeasurement>& measurements,
                     const std::vector<int>& active, const CalibrationOptions& options,
                     bool robust) {
  ceres::Problem problem;
  build_eiv_problem(problem, tcp, x, poses, measurements, active, options, robust);
  ceres::Solver::Options solver_options;
  // Poses are eliminated (Schur complement); the reduced system over the machine parameters
  // is small and dense.
  solver_options.linear_solver_type = ceres::DENSE_SCHUR;
  solver_options.max_num_iterations = options.max_iterations;
  // The robust pass only has to find the outliers; the inlier refit polishes.
  solver_options.function_tolerance = robust ? 1e-7 : 1e-12;
  solver_options.gradient_tolerance = 1e-20;
  solver_options.parameter_tolerance = robust ? 1e-8 : 1e-13;
  // The whitened problem is badly scaled (1 um actuator sigma against mm joint errors); the
  // default initial radius (1e4) damps the weak directions so much that LM needs ~10 extra
  // iterations to grow it. Start nearly Gauss-Newton; LM shrinks the radius if a step fails.
  solver_options.initial_trust_region_radius = 1e12;
  solver_options.num_threads = 1;  // deterministic, and the problem is too small to share
  solver_options.logging_type = ceres::SILENT;
  auto* ordering = new ceres::ParameterBlockOrdering;
  for (int k : active) ordering->AddElementToGroup(poses[static_cast<std::size_t>(k)].data(), 0);
  ordering->AddElementToGroup(x.data(), 1);
  ordering->AddElementToGroup(x.data() + kCalibrationInstrumentIndex, 1);
  ordering->AddElementToGroup(x.data() + kCalibrationTargetIndex, 1);
  solver_options.linear_solver_ordering.reset(ordering);
  ceres::Solver::Summary summary;
  ceres::Solve(solver_options, &problem, &summary);

  FitOutcome outcome;
  outcome.converged = summary.termination_type == ceres::CONVERGENCE;
  outcome.iterations = static_cast<int>(summary.iterations.size());
  outcome.message = summary.message;
  return outcome;
}

// Ceres' covariance (60 x 60, zero rows/columns for fixed parameters) of the EIV problem over
// `active` without a loss, at x and the poses as they are (no solve). Empty on failure.
Eigen::MatrixXd eiv_covariance(const Eigen::Vector3d& tcp, CalibrationVector& x,
                               std::vector<Vec6<double>>& poses,
                               const std::vector<CalibrationMeasurement>& measurements,
                               const std::vector<int>& active, const CalibrationOptions& options) {
  ceres::Problem problem;
  build_eiv_problem(problem, tcp, x, poses, measurements, active, options, false);
  std::vector<std::pair<double*, int>> blocks;
  for (auto [block, start] :
       {std::pair{x.data(), 0},
        std::pair{x.data() + kCalibrationInstrumentIndex, kCalibrationInstrumentIndex},
        std::pair{x.data() + kCalibrationTargetIndex, kCalibrationTargetIndex}}) {
    if (!problem.IsParameterBlockConstant(block)) blocks.emplace_back(block, start);
  }
  std::vector<std::pair<const double*, const double*>> pairs;
  for (std::size_t i = 0; i < blocks.size(); ++i) {
    for (std::size_t j = i; j < blocks.size(); ++j) {
      pairs.emplace_back(blocks[i].first, blocks[j].first);
    }
  }
  ceres::Covariance::Options covariance_options;
  covariance_options.algorithm_type = ceres::SPARSE_QR;
  covariance_options.num_threads = 1;
  ceres::Covariance covariance(covariance_options);
  if (pairs.empty() || !covariance.Compute(pairs, &problem)) return {};
  Eigen::MatrixXd out = Eigen::MatrixXd::Zero(kCalibrationParameters, kCalibrationParameters);
  for (std::size_t i = 0; i < blocks.size(); ++i) {
    for (std::size_t j = i; j < blocks.size(); ++j) {
      const int size_i = problem.ParameterBlockSize(blocks[i].first);
      const int size_j = problem.ParameterBlockSize(blocks[j].first);
      Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> block(size_i, size_j);
      covariance.GetCovarianceBlock(blocks[i].first, blocks[j].first, block.data());
      out.block(blocks[i].second, blocks[j].second, size_i, size_j) = block;
      out.block(blocks[j].second, blocks[i].second, size_j, size_i) = block.transpose();
    }
  }
  return out;
}

// Fits the pose of one measurement with the machine held fixed; returns its chi^2.
double fit_single_pose(const Eigen::Vector3d& tcp, const CalibrationVector& x_in,
                       const CalibrationMeasurement& m, Vec6<double>& pose,
                       const CalibrationOptions& options) {
  CalibrationVector x = x_in;
  ceres::Problem problem;
  problem.AddResidualBlock(new PoseCostFunction(tcp, m, options), nullptr, x.data(), pose.data(),
                           x.data() + kCalibrationInstrumentIndex,
                           x.data() + kCalibrationTargetIndex);
  problem.SetParameterBlockConstant(x.data());
  problem.SetParameterBlockConstant(x.data() + kCalibrationInstrumentIndex);
  problem.SetParameterBlockConstant(x.data() + kCalibrationTargetIndex);
  ceres::Solver::Options solver_options;
  solver_options.linear_solver_type = ceres::DENSE_QR;
  solver_options.max_num_iterations = 50;
  solver_options.initial_trust_region_radius = 1e12;  // nearly Gauss-Newton, as in solve_eiv
  solver_options.function_tolerance = 1e-14;
  solver_options.parameter_tolerance = 1e-14;
  solver_options.logging_type = ceres::SILENT;
  ceres::Solver::Summary summary;
  ceres::Solve(solver_options, &problem, &summary);
  return 2.0 * summary.final_cost;
}

std::string join_names(const std::vector<std::string>& names) {
  std::string text;
  for (const auto& name : names) {
    if (!text.empty()) text.append(", ");
    text.append(name);
  }
  return text;
}

// splitmix64 and the distributions drawn from it (bit-reproducible for a seed).
class Random {
 public:
  explicit Random(std::uint64_t seed) : state_(seed) {}
  std::uint64_t next() {
    std::uint64_t z = (state_ += 0x9e3779b97f4a7c15ULL);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31);
  }
  double uniform() { return static_cast<double>(next() >> 11) * 0x1.0p-53; }
  double uniform(double lo, double hi) { return lo + (hi - lo) * uniform(); }
  double normal() {  // Box-Muller
    const double u1 = 1.0 - uniform();
    const double u2 = uniform();
    return std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * std::numbers::pi * u2);
  }
  Eigen::Vector3d normal3() {
    const double a = normal(), b = normal(), c = normal();
    return {a, b, c};
  }

 private:
  std::uint64_t state_;
};

}  // namespace

// ---- Names, vectors, frames -------------------------------------------------------------------

std::string calibration_parameter_name(int index) {
  if (index < 0 || index >= kCalibrationParameters) return "?";
  if (index >= kCalibrationTargetIndex) {
    return std::string("target.") + kFrameNames[index - kCalibrationTargetIndex];
  }
  if (index >= kCalibrationInstrumentIndex) {
    return std::string("instrument.") + kFrameNames[index - kCalibrationInstrumentIndex];
  }
  const int leg = index / kCalibrationLegParameters + 1;
  const int k = index % kCalibrationLegParameters;
  if (k < 3) return fmt::format("a{}.{}", leg, kAxisNames[k]);
  if (k < 6) return fmt::format("b{}.{}", leg, kAxisNames[k - 3]);
  return (k == 6 ? "offset" : "gain") + std::to_string(leg);
}

int calibration_parameter_index(const std::string& name) {
  for (int i = 0; i < kCalibrationParameters; ++i) {
    if (calibration_parameter_name(i) == name) return i;
  }
  return -1;
}

std::string calibration_parameter_unit(int index) {
  if (index >= kCalibrationInstrumentIndex) {
    return (index - kCalibrationInstrumentIndex) % 6 < 3 ? "m" : "rad";
  }
  return index % kCalibrationLegParameters == 7 ? "1" : "m";
}

CalibrationVector nominal_calibration_vector(const HexapodDesign& design,
                                             const Vec6<double>& zero_length,
                                             const Pose& instrument, const Pose& target) {
  CalibrationVector x = CalibrationVector::Zero();
  for (int i = 0; i < 6; ++i) {
    x.segment<3>(kCalibrationLegParameters * i) = design.base_joints.col(i);
    x.segment<3>(kCalibrationLegParameters * i + 3) = design.platform_joints.col(i);
    x(kCalibrationLegParameters * i + 6) = zero_length(i);
  }
  x.segment<3>(kCalibrationInstrumentIndex) = instrument.position;
  x.segment<3>(kCalibrationInstrumentIndex + 3) = instrument.angles;
  x.segment<3>(kCalibrationTargetIndex) = target.position;
  x.segment<3>(kCalibrationTargetIndex + 3) = target.angles;
  return x;
}

HexapodDesign calibrated_design(const HexapodDesign& nominal, const CalibrationVector& x) {
  HexapodDesign design = nominal;
  for (int i = 0; i < 6; ++i) {
    design.base_joints.col(i) = x.segment<3>(kCalibrationLegParameters * i);
    design.platform_joints.col(i) = x.segment<3>(kCalibrationLegParameters * i + 3);
  }
  return design;
}

CalibrationVector calibration_parameter_scale(double length, double gain, double frame_position,
                                              double frame_angle) {
  CalibrationVector scale;
  for (int i = 0; i < kCalibrationParameters; ++i) {
    if (i < kCalibrationMachineParameters) {
      scale(i) = i % kCalibrationLegParameters == 7 ? gain : length;
    } else {
      scale(i) = (i - kCalibrationInstrumentIndex) % 6 < 3 ? frame_position : frame_angle;
    }
  }
  return scale;
}

CalibrationMask model_free_mask(CalibrationModelKind kind) {
  CalibrationMask free{};
  for (int i = 0; i < kCalibrationMachineParameters; ++i) {
    const int k = i % kCalibrationLegParameters;
    free[static_cast<std::size_t>(i)] = k < 7 || kind == CalibrationModelKind::k48;
  }
  return free;
}

std::string CalibrationOptions::validate() const {
  auto bad = [](std::string_view name, double value, std::string_view constraint) {
    return fmt::format("CalibrationOptions::{} = {}. Violated constraint: {}", name, value,
                       constraint);
  };
  if (!(sigma_position > 0.0) || !std::isfinite(sigma_position)) {
    return bad("sigma_position", sigma_position, "finite and > 0");
  }
  if (!(sigma_orientation > 0.0) || !std::isfinite(sigma_orientation)) {
    return bad("sigma_orientation", sigma_orientation, "finite and > 0");
  }
  if (!(sigma_actuator > 0.0) || !std::isfinite(sigma_actuator)) {
    return bad("sigma_actuator", sigma_actuator, "finite and > 0");
  }
  if (!(loss_scale > 0.0) || !std::isfinite(loss_scale)) {
    return bad("loss_scale", loss_scale, "finite and > 0");
  }
  if (!(outlier_chi2 > 0.0)) return bad("outlier_chi2", outlier_chi2, "> 0");
  if (max_iterations < 1) return bad("max_iterations", max_iterations, ">= 1");
  if (!(rank_tolerance > 0.0 && rank_tolerance < 1.0)) {
    return bad("rank_tolerance", rank_tolerance, "0 < rank_tolerance < 1");
  }
  for (int i = 0; i < kCalibrationParameters; ++i) {
    if (!(parameter_scale(i) > 0.0) || !std::isfinite(parameter_scale(i))) {
      return fmt::format(
          "CalibrationOptions::parameter_scale({}) ({}) = {}. Violated constraint: finite and > 0",
          i, calibration_parameter_name(i), parameter_scale(i));
    }
  }
  return {};
}

Pose tcp_pose_from_measurement(const CalibrationVector& x, const Pose& measured) {
  const Pose instrument = frame_pose(x, kCalibrationInstrumentIndex);
  const Pose target = frame_pose(x, kCalibrationTargetIndex);
  const Eigen::Matrix3d R_instrument = rotation_zyx<double>(instrument.angles);
  const Eigen::Matrix3d R_measured = rotation_zyx<double>(measured.angles);
  const Eigen::Matrix3d R_target = rotation_zyx<double>(target.angles);
  const Eigen::Matrix3d R = R_instrument * R_measured * R_target.transpose();
  const Eigen::Vector3d p =
      instrument.position + R_instrument * measured.position - R * target.position;
  return Pose{p, angles_from_rotation(R)};
}

Pose measurement_from_tcp_pose(const CalibrationVector& x, const Pose& tcp_pose) {
  const Pose instrument = frame_pose(x, kCalibrationInstrumentIndex);
  const Pose target = frame_pose(x, kCalibrationTargetIndex);
  const Eigen::Matrix3d R_instrument = rotation_zyx<double>(instrument.angles);
  const Eigen::Matrix3d R = rotation_zyx<double>(tcp_pose.angles);
  const Eigen::Matrix3d R_target = rotation_zyx<double>(target.angles);
  const Eigen::Vector3d p =
      R_instrument.transpose() * (tcp_pose.position + R * target.position - instrument.position);
  return Pose{p, angles_from_rotation(R_instrument.transpose() * R * R_target)};
}

Vec6<double> leg_lengths_from_stroke(const CalibrationVector& x, const Vec6<double>& stroke) {
  Vec6<double> lengths;
  for (int i = 0; i < 6; ++i) {
    const int leg = kCalibrationLegParameters * i;
    lengths(i) = x(leg + 6) + (1.0 + x(leg + 7)) * stroke(i);
  }
  return lengths;
}

namespace {

// Evaluates the pose cost at (x, tcp_pose): residuals, and the Jacobian blocks whose pointers
// are not null (row-major, as Ceres writes them): machine, pose, instrument, target.
// `jacobians` null: residuals only.
void evaluate_pose_cost(const CalibrationVector& x, const Eigen::Vector3d& tcp,
                        const CalibrationMeasurement& measurement, const Pose& tcp_pose,
                        const CalibrationOptions& options, double* residuals,
                        double* const* jacobians) {
  const PoseCostFunction cost(tcp, measurement, options);
  const Vec6<double> pose = pose_vector(tcp_pose);
  const double* parameters[4] = {x.data(), pose.data(), x.data() + kCalibrationInstrumentIndex,
                                 x.data() + kCalibrationTargetIndex};
  if (jacobians == nullptr) {
    cost.Evaluate(parameters, residuals, nullptr);
    return;
  }
  double* blocks[4] = {jacobians[0], jacobians[1], jacobians[2], jacobians[3]};
  cost.Evaluate(parameters, residuals, blocks);
}

}  // namespace

Eigen::Matrix<double, 12, 1> calibration_residuals(const CalibrationVector& x,
                                                   const Eigen::Vector3d& tcp,
                                                   const CalibrationMeasurement& measurement,
                                                   const Pose& tcp_pose,
                                                   const CalibrationOptions& options) {
  Eigen::Matrix<double, 12, 1> out;
  evaluate_pose_cost(x, tcp, measurement, tcp_pose, options, out.data(), nullptr);
  return out;
}

Eigen::Matrix<double, 12, 66> calibration_jacobian(const CalibrationVector& x,
                                                   const Eigen::Vector3d& tcp,
                                                   const CalibrationMeasurement& measurement,
                                                   const Pose& tcp_pose,
                                                   const CalibrationOptions& options) {
  Eigen::Matrix<double, 12, 1> residuals;
  Eigen::Matrix<double, 12, kCalibrationMachineParameters, Eigen::RowMajor> d_machine;
  Eigen::Matrix<double, 12, 6, Eigen::RowMajor> d_pose, d_instrument, d_target;
  double* const jacobians[4] = {d_machine.data(), d_pose.data(), d_instrument.data(),
                                d_target.data()};
  evaluate_pose_cost(x, tcp, measurement, tcp_pose, options, residuals.data(), jacobians);
  Eigen::Matrix<double, 12, 66> J;
  J << d_machine, d_instrument, d_target, d_pose;
  return J;
}

Eigen::Matrix<double, 12, 6> calibration_pose_jacobian(const CalibrationVector& x,
                                                       const Eigen::Vector3d& tcp,
                                                       const CalibrationMeasurement& measurement,
                                                       const Pose& tcp_pose,
                                                       const CalibrationOptions& options) {
  Eigen::Matrix<double, 12, 1> residuals;
  Eigen::Matrix<double, 12, 6, Eigen::RowMajor> d_pose;
  double* const jacobians[4] = {nullptr, d_pose.data(), nullptr, nullptr};
  evaluate_pose_cost(x, tcp, measurement, tcp_pose, options, residuals.data(), jacobians);
  return d_pose;
}

// ---- Identification ---------------------------------------------------------------------------

Eigen::MatrixXd reduced_identification_rows(const CalibrationVector& x, const Eigen::Vector3d& tcp,
                                            const CalibrationMeasurement& measurement,
                                            const Pose& tcp_pose,
                                            const std::vector<int>& free_indices,
                                            const CalibrationOptions& options) {
  const Eigen::Matrix<double, 12, 66> full =
      calibration_jacobian(x, tcp, measurement, tcp_pose, options);
  const Eigen::Matrix<double, 12, kCalibrationParameters> A = full.leftCols<60>();
  const Eigen::Matrix<double, 12, 6> d_pose = full.rightCols<6>();
  // Rows orthogonal to the pose directions: the last 6 columns of Q in B = Q R.
  const Eigen::HouseholderQR<Eigen::Matrix<double, 12, 6>> qr(d_pose);
  const Eigen::Matrix<double, 12, 12> Q = qr.householderQ();
  const Eigen::Matrix<double, 6, 12> complement = Q.rightCols<6>().transpose();
  Eigen::MatrixXd rows(6, static_cast<Eigen::Index>(free_indices.size()));
  for (std::size_t j = 0; j < free_indices.size(); ++j) {
    rows.col(static_cast<Eigen::Index>(j)) = complement * A.col(free_indices[j]);
  }
  return rows;
}

namespace {

// O1..O4 of singular values s (descending) from num_poses poses; zero/inf when rank deficient.
ObservabilityIndices observability_indices(const Eigen::VectorXd& s, int rank, int num_poses) {
  ObservabilityIndices indices;
  indices.singular_values = s;
  const Eigen::Index n = s.size();
  if (n == 0) return indices;
  if (rank < n) {
    indices.O2 = std::numeric_limits<double>::infinity();
    return indices;
  }
  const double s_max = s(0), s_min = s(n - 1);
  indices.O1 = std::exp(s.array().log().mean()) / std::sqrt(static_cast<double>(num_poses));
  indices.O2 = s_max / s_min;
  indices.O3 = s_min;
  indices.O4 = s_min * s_min / s_max;
  return indices;
}

// JacobiSVD (column-pivoting QR first, then one-sided Jacobi on the n x n factor): accurate
// for the small singular values, and it runs no threaded matrix products.
Eigen::VectorXd padded_singular_values(const Eigen::JacobiSVD<Eigen::MatrixXd>& svd,
                                       Eigen::Index n) {
  Eigen::VectorXd s = Eigen::VectorXd::Zero(n);
  s.head(svd.singularValues().size()) = svd.singularValues();
  return s;
}

struct IdentificationWithBasis {
  Identification identification;
  Eigen::MatrixXd V;  ///< right singular vectors (n x n), columns in singular-value order
};

IdentificationWithBasis identification_from_rows(const Eigen::MatrixXd& J,
                                                 const std::vector<int>& free_indices,
                                                 int num_poses, const CalibrationOptions& options,
                                                 bool rank_only = false) {
  IdentificationWithBasis out;
  Identification& id = out.identification;
  id.free_indices = free_indices;
  id.num_poses = num_poses;
  const Eigen::Index n = J.cols();
  if (n == 0) return out;
  Eigen::JacobiSVD<Eigen::MatrixXd> svd(J, rank_only ? 0 : Eigen::ComputeFullV);
  const Eigen::VectorXd s = padded_singular_values(svd, n);
  id.singular_values = s;
  id.rank = 0;
  for (Eigen::Index i = 0; i < n; ++i) {
    if (s(i) > options.rank_tolerance * s(0) && s(i) > 0.0) ++id.rank;
  }
  const ObservabilityIndices indices = observability_indices(s, id.rank, num_poses);
  id.O1 = indices.O1;
  id.O2 = indices.O2;
  id.O3 = indices.O3;
  id.O4 = indices.O4;
  if (rank_only) {
    if (id.rank == n) return out;
    svd.compute(J, Eigen::ComputeFullV);  // the null space names the parameters
  }
  out.V = svd.matrixV();

  // The same with each column times the parameter's a-priori uncertainty (dimensionless).
  id.column_scale.resize(n);
  for (Eigen::Index j = 0; j < n; ++j) {
    id.column_scale(j) = options.parameter_scale(free_indices[static_cast<std::size_t>(j)]);
  }
  const Eigen::JacobiSVD<Eigen::MatrixXd> scaled_svd(J * id.column_scale.asDiagonal());
  id.scaled = observability_indices(padded_singular_values(scaled_svd, n), id.rank, num_poses);

  if (id.rank < n) {
    id.null_space = out.V.rightCols(n - id.rank);
    for (Eigen::Index j = 0; j < n; ++j) {
      if (id.null_space.row(j).norm() > 0.05) {
        id.unidentifiable.push_back(calibration_parameter_name(free_indices[j]));
      }
    }
  }
  return out;
}

// The stacked reduced identification rows J_id (6N x n_free).
Eigen::MatrixXd identification_jacobian(const CalibrationVector& x, const Eigen::Vector3d& tcp,
                                        const std::vector<CalibrationMeasurement>& measurements,
                                        const std::vector<Pose>& tcp_poses,
                                        const std::vector<int>& free_indices,
                                        const CalibrationOptions& options) {
  const auto num_poses = static_cast<Eigen::Index>(measurements.size());
  Eigen::MatrixXd J(6 * num_poses, static_cast<Eigen::Index>(free_indices.size()));
  for (Eigen::Index k = 0; k < num_poses; ++k) {
    J.middleRows(6 * k, 6) =
        reduced_identification_rows(x, tcp, measurements[static_cast<std::size_t>(k)],
                                    tcp_poses[static_cast<std::size_t>(k)], free_indices, options);
  }
  return J;
}

// rank_only: singular values and rank, plus the null space when rank deficient (no V, no
// scaled indices otherwise).
IdentificationWithBasis identify_with_basis(const CalibrationVector& x, const Eigen::Vector3d& tcp,
                                            const std::vector<CalibrationMeasurement>& measurements,
                                            const std::vector<Pose>& tcp_poses,
                                            const CalibrationOptions& options,
                                            bool rank_only = false) {
  const std::vector<int> free_indices = free_indices_of(options.free);
  return identification_from_rows(
      identification_jacobian(x, tcp, measurements, tcp_poses, free_indices, options), free_indices,
      static_cast<int>(measurements.size()), options, rank_only);
}

}  // namespace

Identification identify(const CalibrationVector& x, const Eigen::Vector3d& tcp,
                        const std::vector<CalibrationMeasurement>& measurements,
                        const std::vector<Pose>& tcp_poses, const CalibrationOptions& options) {
  return identify_with_basis(x, tcp, measurements, tcp_poses, options).identification;
}

std::vector<int> choose_gauge_fixing(const CalibrationVector& x, const Eigen::Vector3d& tcp,
                                     const std::vector<CalibrationMeasurement>& measurements,
                                     const CalibrationOptions& options) {
  int frames = 0;
  auto any_free = [&](int start) {
    for (int i = start; i < start + 6; ++i) {
      if (options.free[static_cast<std::size_t>(i)]) return true;
    }
    return false;
  };
  if (any_free(kCalibrationInstrumentIndex)) frames += 6;
  if (any_free(kCalibrationTargetIndex)) frames += 6;
  if (frames == 0) return {};
  std::vector<Pose> poses;
  for (const auto& m : measurements) poses.push_back(tcp_pose_from_measurement(x, m.pose));
  const Identification id = identify(x, tcp, measurements, poses, options);
  if (id.null_space.cols() == 0) return {};
  std::vector<Eigen::Index> candidate_rows;
  for (std::size_t j = 0; j < id.free_indices.size(); ++j) {
    if (is_joint_coordinate(id.free_indices[j])) {
      candidate_rows.push_back(static_cast<Eigen::Index>(j));
    }
  }
  Eigen::MatrixXd M(id.null_space.cols(), static_cast<Eigen::Index>(candidate_rows.size()));
  for (std::size_t c = 0; c < candidate_rows.size(); ++c) {
    M.col(static_cast<Eigen::Index>(c)) = id.null_space.row(candidate_rows[c]).transpose();
  }
  const Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(M);
  const Eigen::Index count =
      std::min<Eigen::Index>({static_cast<Eigen::Index>(frames), M.rows(), M.cols()});
  std::vector<int> fixed;
  for (Eigen::Index c = 0; c < count; ++c) {
    const Eigen::Index column = qr.colsPermutation().indices()(c);
    fixed.push_back(id.free_indices[static_cast<std::size_t>(candidate_rows[column])]);
  }
  std::sort(fixed.begin(), fixed.end());
  return fixed;
}

// ---- Calibration ------------------------------------------------------------------------------

CalibrationResult calibrate(const HexapodDesign& nominal_design, const CalibrationVector& start,
                            const std::vector<CalibrationMeasurement>& measurements,
                            const CalibrationOptions& options) {
  if (const std::string error = options.validate(); !error.empty()) {
    throw std::invalid_argument(error);
  }
  const Eigen::Vector3d tcp = nominal_design.tcp;
  const std::vector<int> free_indices = free_indices_of(options.free);
  const int num_free = static_cast<int>(free_indices.size());
  const int num_poses = static_cast<int>(measurements.size());
  if (6 * num_poses < num_free + 1) {
    throw CalibrationError(fmt::format(
        "too few poses: {} fitted poses give {} equations (6 per pose after the pose unknowns), "
        "the {} free parameters need more than {}; measure at least {} poses (3 times as many "
        "is a good rule) or free fewer parameters",
        num_poses, 6 * num_poses, num_free, num_free, num_free / 6 + 1));
  }

  CalibrationResult result;
  CalibrationVector x = start;
  std::vector<Vec6<double>> poses;
  std::vector<Pose> start_poses;
  for (const auto& m : measurements) {
    start_poses.push_back(tcp_pose_from_measurement(x, m.pose));
    poses.push_back(pose_vector(start_poses.back()));
  }
  {
    const Identification id =
        identify_with_basis(x, tcp, measurements, start_poses, options, true).identification;
    if (id.rank < num_free) {
      throw CalibrationError(fmt::format(
          "the measured poses cannot identify every free parameter: the identification "
          "Jacobian has rank {} for {} free parameters; the combination(s) left undetermined "
          "involve {}. Fix some of these parameters (the `fixed:` list or `gauge: auto`) or "
          "measure poses that move them (rotations as well as translations)",
          id.rank, num_free, join_names(id.unidentifiable)));
    }
  }

  std::vector<int> active(static_cast<std::size_t>(num_poses));
  std::iota(active.begin(), active.end(), 0);
  const bool robust = options.loss != CalibrationLoss::kNone;
  FitOutcome outcome = solve_eiv(tcp, x, poses, measurements, active, options, robust);
  result.iterations += outcome.iterations;

  std::vector<double> chi2(static_cast<std::size_t>(num_poses), 0.0);
  auto pose_chi2 = [&](int k) {
    return calibration_residuals(x, tcp, measurements[static_cast<std::size_t>(k)],
                                 pose_from_vector(poses[static_cast<std::size_t>(k)]), options)
        .squaredNorm();
  };
  std::vector<bool> rejected(static_cast<std::size_t>(num_poses), false);
  bool refit = robust;
  for (int round = 0; round < 5; ++round) {
    bool new_outliers = false;
    if (options.reject_outliers) {
      for (int k : active) {
        chi2[static_cast<std::size_t>(k)] = pose_chi2(k);
        if (chi2[static_cast<std::size_t>(k)] > options.outlier_chi2) {
          rejected[static_cast<std::size_t>(k)] = true;
          new_outliers = true;
        }
      }
    }
    if (!new_outliers && !refit) break;
    active.clear();
    for (int k = 0; k < num_poses; ++k) {
      if (!rejected[static_cast<std::size_t>(k)]) active.push_back(k);
    }
    if (6 * static_cast<int>(active.size()) < num_free + 1) {
      throw CalibrationError(fmt::format(
          "{} of {} poses were rejected as outliers (chi^2 > {}); the {} inliers are too few "
          "for {} free parameters. Check the noise sigmas and the units of the readings",
          num_poses - static_cast<int>(active.size()), num_poses, options.outlier_chi2,
          active.size(), num_free));
    }
    outcome = solve_eiv(tcp, x, poses, measurements, active, options, false);
    result.iterations += outcome.iterations;
    refit = false;
  }
  for (int k : active) chi2[static_cast<std::size_t>(k)] = pose_chi2(k);
  for (int k = 0; k < num_poses; ++k) {
    if (rejected[static_cast<std::size_t>(k)]) {
      result.outliers.push_back(k);
      chi2[static_cast<std::size_t>(k)] =
          fit_single_pose(tcp, x, measurements[static_cast<std::size_t>(k)],
                          poses[static_cast<std::size_t>(k)], options);
    }
  }

  // Identification at the solution (inliers, adjusted poses).
  std::vector<CalibrationMeasurement> inlier_measurements;
  std::vector<Pose> inlier_poses;
  for (int k : active) {
    inlier_measurements.push_back(measurements[static_cast<std::size_t>(k)]);
    inlier_poses.push_back(pose_from_vector(poses[static_cast<std::size_t>(k)]));
  }
  const IdentificationWithBasis final_identification =
      identify_with_basis(x, tcp, inlier_measurements, inlier_poses, options);
  result.identification = final_identification.identification;

  if (options.compute_covariance) {
    // Covariance of the final (inlier, no loss) problem on whitened residuals: the inverse
    // of the Schur-reduced information J_id^T J_id = V S^2 V^T, i.e. V S^-2 V^T from the
    // identification SVD; or Ceres' own (ceres::Covariance, SPARSE_QR on the full problem).
    Eigen::MatrixXd covariance =
        Eigen::MatrixXd::Zero(kCalibrationParameters, kCalibrationParameters);
    if (result.identification.rank == num_free && num_free > 0) {
      if (options.covariance_method == CalibrationCovarianceMethod::kCeres) {
        covariance = eiv_covariance(tcp, x, poses, measurements, active, options);
      }
      if (options.covariance_method == CalibrationCovarianceMethod::kReducedInformation ||
          covariance.size() == 0) {
        const Eigen::MatrixXd& V = final_identification.V;
        const Eigen::VectorXd inverse_s2 =
            result.identification.singular_values.array().square().inverse();
        // lazyProduct: a plain coefficient loop (no threaded GEMM for a 48 x 48 product).
        const Eigen::MatrixXd inverse = (V * inverse_s2.asDiagonal()).lazyProduct(V.transpose());
        covariance = Eigen::MatrixXd::Zero(kCalibrationParameters, kCalibrationParameters);
        for (int a = 0; a < num_free; ++a) {
          for (int b = 0; b < num_free; ++b) {
            covariance(free_indices[static_cast<std::size_t>(a)],
                       free_indices[static_cast<std::size_t>(b)]) = inverse(a, b);
          }
        }
      }
    }
    result.covariance = covariance;
    result.sigma = covariance.diagonal().cwiseMax(0.0).cwiseSqrt();
    for (int a = 0; a < num_free; ++a) {
      for (int b = a + 1; b < num_free; ++b) {
        const int i = free_indices[static_cast<std::size_t>(a)];
        const int j = free_indices[static_cast<std::size_t>(b)];
        const double denominator = result.sigma(i) * result.sigma(j);
        if (denominator <= 0.0) continue;
        const double rho = covariance(i, j) / denominator;
        if (std::abs(rho) >= options.correlation_threshold) {
          result.correlated.push_back({i, j, rho});
        }
      }
    }
    std::sort(result.correlated.begin(), result.correlated.end(),
              [](const CorrelatedPair& l, const CorrelatedPair& r) {
                return std::abs(l.correlation) > std::abs(r.correlation);
              });
  }

  result.estimate = x;
  for (const auto& pose : poses) result.adjusted_poses.push_back(pose_from_vector(pose));
  result.chi2 = chi2;
  double total = 0.0;
  for (int k : active) total += chi2[static_cast<std::size_t>(k)];
  const int dof = 6 * static_cast<int>(active.size()) - num_free;
  result.chi2_per_dof = dof > 0 ? total / dof : 0.0;
  result.converged = outcome.converged;
  result.solver_message = outcome.message;
  return result;
}

CalibrationErrors calibration_errors(const HexapodDesign& nominal_design,
                                     const CalibrationVector& x,
                                     const std::vector<CalibrationMeasurement>& measurements,
                                     const std::vector<int>& indices) {
  CalibrationErrors errors;
  const Hexapod hexapod(calibrated_design(nominal_design, x));
  Vec6<double> leg_sum = Vec6<double>::Zero();
  double position_sum = 0.0, orientation_sum = 0.0;
  int fk_count = 0;
  for (int k : indices) {
    const auto& m = measurements[static_cast<std::size_t>(k)];
    const Pose measured = tcp_pose_from_measurement(x, m.pose);
    const Vec6<double> lengths = leg_lengths_from_stroke(x, m.stroke);
    const Vec6<double> leg_error = hexapod.inverse_kinematics(measured) - lengths;
    leg_sum += leg_error.cwiseAbs2();
    errors.leg_max = errors.leg_max.cwiseMax(leg_error.cwiseAbs());
    ++errors.count;
    const FkResult fk = hexapod.forward_kinematics(lengths, measured);
    if (!fk.converged) {
      ++errors.fk_failures;
      continue;
    }
    const double position_error = (fk.pose.position - measured.position).norm();
    const double orientation_error =
        rotation_vector(rotation_zyx<double>(measured.angles).transpose() *
                        rotation_zyx<double>(fk.pose.angles))
            .norm();
    position_sum += position_error * position_error;
    orientation_sum += orientation_error * orientation_error;
    errors.tcp_position_max = std::max(errors.tcp_position_max, position_error);
    errors.tcp_orientation_max = std::max(errors.tcp_orientation_max, orientation_error);
    ++fk_count;
  }
  if (errors.count > 0) errors.leg_rms = (leg_sum / errors.count).cwiseSqrt();
  if (fk_count > 0) {
    errors.tcp_position_rms = std::sqrt(position_sum / fk_count);
    errors.tcp_orientation_rms = std::sqrt(orientation_sum / fk_count);
  }
  return errors;
}

std::vector<double> fixed_machine_chi2(const Eigen::Vector3d& tcp, const CalibrationVector& x,
                                       const std::vector<CalibrationMeasurement>& measurements,
                                       const std::vector<int>& indices,
                                       const CalibrationOptions& options) {
  std::vector<double> chi2;
  chi2.reserve(indices.size());
  for (int k : indices) {
    const auto& m = measurements[static_cast<std::size_t>(k)];
    Vec6<double> pose = pose_vector(tcp_pose_from_measurement(x, m.pose));
    chi2.push_back(fit_single_pose(tcp, x, m, pose, options));
  }
  return chi2;
}

// ---- Synthetic measurements -------------------------------------------------------------------

SimulatedMeasurements simulate_measurements(const HexapodDesign& nominal_design,
                                            const CalibrationVector& nominal,
                                            const CalibrationMask& perturbed,
                                            const MeasurementSimulationOptions& options) {
  Random random(options.seed);
  SimulatedMeasurements out;
  CalibrationVector truth = nominal;
  for (int i = 0; i < kCalibrationParameters; ++i) {
    if (!perturbed[static_cast<std::size_t>(i)]) continue;
    double sigma = 0.0;
    if (i < kCalibrationMachineParameters) {
      const int k = i % kCalibrationLegParameters;
      sigma = k < 6 ? options.joint_sigma : (k == 6 ? options.offset_sigma : options.gain_sigma);
    } else {
      sigma = (i - kCalibrationInstrumentIndex) % 6 < 3 ? 5.0 * options.joint_sigma : 1e-3;
    }
    truth(i) += sigma * random.normal();
  }
  out.truth = truth;
  const Hexapod hexapod(calibrated_design(nominal_design, truth));
  auto data = hexapod.make_data();
  const int max_attempts = 1000 * std::max(1, options.num_poses);
  double sigma_sum = 0.0;
  for (int attempt = 0;
       attempt < max_attempts && static_cast<int>(out.true_poses.size()) < options.num_poses;
       ++attempt) {
    Pose pose;
    pose.position = {random.uniform(-options.xy_range, options.xy_range),
                     random.uniform(-options.xy_range, options.xy_range),
                     random.uniform(options.z_min, options.z_max)};
    pose.angles = {random.uniform(-options.angle_range, options.angle_range),
                   random.uniform(-options.angle_range, options.angle_range),
                   random.uniform(-options.angle_range, options.angle_range)};
    if (!hexapod.reachable(*data, pose)) continue;
    const Vec6<double> lengths = hexapod.inverse_kinematics(pose);
    CalibrationMeasurement m;
    for (int i = 0; i < 6; ++i) {
      const int leg = kCalibrationLegParameters * i;
      m.stroke(i) = (lengths(i) - truth(leg + 6)) / (1.0 + truth(leg + 7)) +
                    options.actuator_sigma * random.normal();
    }
    const Pose exact = measurement_from_tcp_pose(truth, pose);
    const double sigma =
        options.tracker_sigma + options.tracker_sigma_per_metre * exact.position.norm();
    sigma_sum += sigma;
    m.pose.position = exact.position + sigma * random.normal3();
    m.pose.angles =
        angles_from_rotation(rotation_zyx<double>(exact.angles) *
                             rotation_from_vector(options.orientation_sigma * random.normal3()));
    out.true_poses.push_back(pose);
    out.measurements.push_back(m);
  }
  if (static_cast<int>(out.measurements.size()) < options.num_poses) {
    throw CalibrationError(fmt::format(
        "could only draw {} reachable poses of {} in the sampling box; widen or move the box",
        out.measurements.size(), options.num_poses));
  }
  const int num_outliers = std::min(options.num_outliers, options.num_poses);
  while (static_cast<int>(out.outliers.size()) < num_outliers) {
    const int k = static_cast<int>(random.next() % static_cast<std::uint64_t>(options.num_poses));
    if (std::find(out.outliers.begin(), out.outliers.end(), k) != out.outliers.end()) continue;
    out.outliers.push_back(k);
    const Eigen::Vector3d direction = random.normal3().normalized();
    out.measurements[static_cast<std::size_t>(k)].pose.position +=
        options.outlier_magnitude * direction;
  }
  std::sort(out.outliers.begin(), out.outliers.end());
  out.mean_position_sigma = options.num_poses > 0 ? sigma_sum / options.num_poses : 0.0;
  return out;
}

// ---- Pose selection ---------------------------------------------------------------------------

PoseSelection select_calibration_poses(const CalibrationVector& x, const Eigen::Vector3d& tcp,
                                       const std::vector<Pose>& candidates, int count,
                                       const CalibrationOptions& options) {
  const std::vector<int> free_indices = free_indices_of(options.free);
  const int n = static_cast<int>(free_indices.size());
  const int num_candidates = static_cast<int>(candidates.size());
  if (count < 1 || 6 * count < n + 1) {
    throw CalibrationError(fmt::format(
        "--count {} poses give {} equations; the {} free parameters need at least {} poses", count,
        6 * count, n, n / 6 + 1));
  }
  if (count > num_candidates) {
    throw CalibrationError(fmt::format("--count {} is more than the {} usable candidate poses",
                                       count, num_candidates));
  }
  // Perfect measurements of each candidate on the machine x.
  std::vector<CalibrationMeasurement> measurements(static_cast<std::size_t>(num_candidates));
  std::vector<Eigen::MatrixXd> rows(static_cast<std::size_t>(num_candidates));
  Eigen::MatrixXd total = Eigen::MatrixXd::Zero(n, n);
  for (int c = 0; c < num_candidates; ++c) {
    const Pose& pose = candidates[static_cast<std::size_t>(c)];
    auto& m = measurements[static_cast<std::size_t>(c)];
    m.pose = measurement_from_tcp_pose(x, pose);
    Eigen::Matrix<double, 3, 6> platform_rel;
    for (int i = 0; i < 6; ++i) {
      platform_rel.col(i) = x.segment<3>(kCalibrationLegParameters * i + 3) - tcp;
    }
    Eigen::Matrix<double, 3, 6> base;
    for (int i = 0; i < 6; ++i) base.col(i) = x.segment<3>(kCalibrationLegParameters * i);
    Vec6<double> lengths;
    hexapod_legs<double>(base, platform_rel, pose.position, pose.angles, &lengths);
    for (int i = 0; i < 6; ++i) {
      const int leg = kCalibrationLegParameters * i;
      m.stroke(i) = (lengths(i) - x(leg + 6)) / (1.0 + x(leg + 7));
    }
    rows[static_cast<std::size_t>(c)] =
        reduced_identification_rows(x, tcp, m, pose, free_indices, options);
    total += rows[static_cast<std::size_t>(c)].transpose() * rows[static_cast<std::size_t>(c)];
  }
  const double regularisation = 1e-12 * total.trace() / std::max(1, n);
  auto log_det = [](const Eigen::MatrixXd& M) {
    const Eigen::LLT<Eigen::MatrixXd> llt(M);
    if (llt.info() != Eigen::Success) return -std::numeric_limits<double>::infinity();
    return 2.0 * llt.matrixL().toDenseMatrix().diagonal().array().log().sum();
  };
  // Gain in log det from adding the rows A to a matrix with inverse M_inverse (determinant lemma).
  auto gain = [&](const Eigen::MatrixXd& M_inverse, const Eigen::MatrixXd& A) {
    const Eigen::MatrixXd S = Eigen::MatrixXd::Identity(6, 6) + A * M_inverse * A.transpose();
    return log_det(S);
  };

  PoseSelection selection;
  std::vector<bool> chosen(static_cast<std::size_t>(num_candidates), false);
  Eigen::MatrixXd M = regularisation * Eigen::MatrixXd::Identity(n, n);
  for (int step = 0; step < count; ++step) {
    const Eigen::MatrixXd M_inverse = M.ldlt().solve(Eigen::MatrixXd::Identity(n, n));
    int best = -1;
    double best_gain = -std::numeric_limits<double>::infinity();
    for (int c = 0; c < num_candidates; ++c) {
      if (chosen[static_cast<std::size_t>(c)]) continue;
      const double g = gain(M_inverse, rows[static_cast<std::size_t>(c)]);
      if (g > best_gain) {
        best_gain = g;
        best = c;
      }
    }
    chosen[static_cast<std::size_t>(best)] = true;
    selection.selected.push_back(best);
    M += rows[static_cast<std::size_t>(best)].transpose() * rows[static_cast<std::size_t>(best)];
  }
  // Fedorov exchange: swap a chosen pose for an unchosen one while det grows.
  for (int pass = 0; pass < 50; ++pass) {
    bool improved = false;
    for (std::size_t s = 0; s < selection.selected.size(); ++s) {
      const int out_index = selection.selected[s];
      const Eigen::MatrixXd& A_out = rows[static_cast<std::size_t>(out_index)];
      const Eigen::MatrixXd M_without = M - A_out.transpose() * A_out;
      const Eigen::MatrixXd M_inverse = M_without.ldlt().solve(Eigen::MatrixXd::Identity(n, n));
      const double current = gain(M_inverse, A_out);
      int best = -1;
      double best_gain = current + 1e-9 * std::max(1.0, std::abs(current));
      for (int c = 0; c < num_candidates; ++c) {
        if (chosen[static_cast<std::size_t>(c)]) continue;
        const double g = gain(M_inverse, rows[static_cast<std::size_t>(c)]);
        if (g > best_gain) {
          best_gain = g;
          best = c;
        }
      }
      if (best >= 0) {
        chosen[static_cast<std::size_t>(out_index)] = false;
        chosen[static_cast<std::size_t>(best)] = true;
        selection.selected[s] = best;
        const Eigen::MatrixXd& A_in = rows[static_cast<std::size_t>(best)];
        M = M_without + A_in.transpose() * A_in;
        ++selection.exchanges;
        improved = true;
      }
    }
    if (!improved) break;
  }
  std::sort(selection.selected.begin(), selection.selected.end());
  std::vector<CalibrationMeasurement> chosen_measurements;
  std::vector<Pose> chosen_poses;
  for (int c : selection.selected) {
    chosen_measurements.push_back(measurements[static_cast<std::size_t>(c)]);
    chosen_poses.push_back(candidates[static_cast<std::size_t>(c)]);
  }
  selection.identification = identify(x, tcp, chosen_measurements, chosen_poses, options);
  Eigen::MatrixXd information = Eigen::MatrixXd::Zero(n, n);
  for (int c : selection.selected) {
    information +=
        rows[static_cast<std::size_t>(c)].transpose() * rows[static_cast<std::size_t>(c)];
  }
  selection.log_det = log_det(information);
  if (selection.identification.rank < n) {
    throw CalibrationError(fmt::format(
        "the candidate poses cannot identify every free parameter (rank {} of {}); the "
        "undetermined combination(s) involve {}. Add candidates with rotations or fix these",
        selection.identification.rank, n, join_names(selection.identification.unidentifiable)));
  }
  return selection;
}

}  // namespace pkmopt
