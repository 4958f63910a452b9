// The residuals of one measured pose and their Jacobians (calibration_residuals,
// calibration_jacobian, calibration_pose_jacobian), evaluated through the solver's cost function.
#include "problems/calibration/calibration_cost.hpp"

#include "problems/calibration/calibration.hpp"
#include "problems/calibration/calibration_detail.hpp"

namespace pkmopt {
namespace {

using detail::pose_vector;
using detail::PoseCostFunction;

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

}  // namespace pkmopt
