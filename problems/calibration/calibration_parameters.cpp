// The calibration parameter vector and what it means: parameter names and units, nominal vector
// and calibrated design, the 42/48-parameter free masks, a-priori scales, option checks, and the
// instrument / target frame transforms and readings-to-length map.
#include <fmt/format.h>

#include <cmath>
#include <string>
#include <string_view>

#include "problems/calibration/calibration.hpp"

namespace pkmopt {
namespace {

constexpr const char* kAxisNames[3] = {"x", "y", "z"};
constexpr const char* kFrameNames[6] = {"x", "y", "z", "rx", "ry", "rz"};

Pose frame_pose(const CalibrationVector& x, int start) {
  return Pose{x.segment<3>(start), x.segment<3>(start + 3)};
}

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
  if (noise_iterations < 0) return bad("noise_iterations", noise_iterations, ">= 0");
  if (!(max_rejected_share > 0.0 && max_rejected_share <= 1.0)) {
    return bad("max_rejected_share", max_rejected_share, "0 < share <= 1");
  }
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

Vec6<double> leg_lengths_of(const CalibrationVector& x, const CalibrationMeasurement& m) {
  return leg_lengths_from_stroke(x, m.stroke) + m.offset_shift;
}

}  // namespace pkmopt
