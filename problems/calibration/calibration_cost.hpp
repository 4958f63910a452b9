// The per-pose cost of the errors-in-variables calibration problem (internal): the 12 whitened
// residuals of one measured pose as one Ceres residual block, with analytic leg derivatives and
// autodiff of the measured-pose rows. Used by problems/calibration/calibration*.cpp only.
#pragma once

#include <ceres/ceres.h>
#include <ceres/rotation.h>

#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <memory>

#include "problems/calibration/calibration.hpp"

namespace pkmopt::detail {

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
        offset_shift_(m.offset_shift),
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
      const double from_reading = leg[6] + offset_shift_(i) + (1.0 + leg[7]) * stroke_(i);
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
  Vec6<double> offset_shift_;
  double inv_sigma_actuator_;
};

// A pose of a measurement campaign c >= 1: the pose cost with the campaign's six leg zero shifts
// as a fifth parameter block; leg i's residual depends on shift_i as on offset_i (-1/sigma), the
// other rows not at all. The measurement's own offset_shift is ignored (the block replaces it).
class CampaignPoseCost final
    : public ceres::SizedCostFunction<12, kCalibrationMachineParameters, 6, 6, 6, 6> {
 public:
  CampaignPoseCost(const Eigen::Vector3d& tcp, CalibrationMeasurement m,
                   const CalibrationOptions& options)
      : inner_(tcp, without_shift(std::move(m)), options),
        inv_sigma_actuator_(1.0 / options.sigma_actuator) {}

  bool Evaluate(double const* const* parameters, double* residuals,
                double** jacobians) const override {
    std::array<double, kCalibrationMachineParameters> machine;
    std::copy(parameters[0], parameters[0] + kCalibrationMachineParameters, machine.begin());
    for (int i = 0; i < 6; ++i) machine[kCalibrationLegParameters * i + 6] += parameters[4][i];
    const double* inner_parameters[4] = {machine.data(), parameters[1], parameters[2],
                                         parameters[3]};
    if (!jacobians) return inner_.Evaluate(inner_parameters, residuals, nullptr);
    double* inner_jacobians[4] = {jacobians[0], jacobians[1], jacobians[2], jacobians[3]};
    if (!inner_.Evaluate(inner_parameters, residuals, inner_jacobians)) return false;
    if (jacobians[4]) {
      std::fill(jacobians[4], jacobians[4] + 72, 0.0);
      for (int i = 0; i < 6; ++i) jacobians[4][6 * i + i] = -inv_sigma_actuator_;
    }
    return true;
  }

 private:
  static CalibrationMeasurement without_shift(CalibrationMeasurement m) {
    m.offset_shift.setZero();
    return m;
  }
  PoseCostFunction inner_;
  double inv_sigma_actuator_;
};

}  // namespace pkmopt::detail
