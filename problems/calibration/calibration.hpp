// Kinematic calibration of a hexapod from measured platform poses and actuator readings.
//
// The real machine (60 parameters, a CalibrationVector; index = 8 * leg + k for the legs):
//   per leg i = 1..6:  a_i (3, m, base frame)          "a1.x" "a1.y" "a1.z"
//                      b_i (3, m, platform frame)      "b1.x" ...
//                      leg offset d_i (m)              "offset1"  leg length at reading 0
//                      actuator gain error g_i (1)     "gain1"    relative, nominal 0
//   instrument: the pose of the measuring instrument's frame in the base frame
//               (x, y, z in m; rx, ry, rz in rad, R = Rz Ry Rx)       "instrument.x" ...
//   target:     the pose of the measured target frame in the TCP frame  "target.x" ...
// The 42-parameter model frees a, b and d; the 48-parameter model also frees g. When poses are
// measured in the base frame directly, instrument and target are held at the identity.
//
// Measurement k: the target pose M_k measured in the instrument frame (p_m, R_m) and the six
// actuator readings converted to metres with the nominal unit scale, s_ik ("stroke").
// Leg length from the readings: L_i = d_i + (1 + g_i) s_ik.
//
// Errors-in-variables (implicit) formulation. Every measured pose has its own unknown true TCP
// pose (p_k, R_k = R(angles_k)) in the base frame; the least-squares problem has, per pose,
// 12 whitened residuals
//   leg:         (|p_k + R_k (b_i - tcp) - a_i| - L_i) / sigma_actuator           (6)
//   position:    (R_I^T (p_k + R_k t_T - t_I) - p_m) / sigma_position             (3)
//   orientation: log(R_m^T R_I^T R_k R_T) / sigma_orientation                    (3)
// (T_I = (t_I, R_I) instrument, T_T = (t_T, R_T) target), so neither the instrument nor the
// actuators are taken as exact. A robust loss (Huber or Cauchy) on each pose's squared norm
// bounds the influence of gross outliers; poses whose chi^2 exceeds the threshold are rejected
// and the inliers refitted without a loss for the final estimate and covariance.
// Solver: Ceres, DENSE_SCHUR eliminating the pose unknowns, one thread. Each pose is one
// 12-row residual block; leg i's row depends only on the pose and leg i's 8 parameters and
// has analytic derivatives, the measured-pose rows are differentiated by autodiff over the
// pose and the frames (checked against central differences in the tests).
//
// Identification Jacobian: eliminating the six pose unknowns of pose k from its 12 residuals
// (r = A dtheta + B dpose, project onto the complement of range(B)) leaves 6 rows per pose;
// stacking them gives J_id (6N x n_free) with J_id^T J_id = the Schur-reduced information, so
// cov(theta) = (J_id^T J_id)^-1 (whitened residuals, no variance-factor scaling), computed from
// the SVD of J_id or, on request, by ceres::Covariance on the full problem (the same matrix).
// Units: rows whitened (1), columns in the parameters' units (m, 1, rad), so the O indices
// below mix units when the model mixes lengths, gains and angles; `Identification::scaled` has them
// for J_id * diag(a-priori sigma), dimensionless. With singular values sigma_1 >= ... >= sigma_n of
// J_id and N poses (Borm & Menq 1991; Nahvi & Hollerbach 1996):
//   O1 = (sigma_1 ... sigma_n)^(1/n) / sqrt(N),  O2 = sigma_1 / sigma_n (condition number),
//   O3 = sigma_n,  O4 = sigma_n^2 / sigma_1 (noise amplification index).
// Singular values < rank_tolerance * sigma_1 count as zero: those right singular vectors name
// the parameter combinations the data cannot identify.
//
// Gauge: with the instrument transform free, any rigid motion of the base frame (moving every
// a_i, every pose and the instrument together) leaves every residual unchanged: 6 freedoms.
// With the target transform free the same holds for the platform frame: 6 more. They are fixed
// explicitly by holding 6 base-joint (resp. platform-joint) coordinates at their nominal values;
// `choose_gauge_fixing` picks the coordinates by column-pivoted QR of the null space, i.e. the
// best-conditioned choice. When poses are measured in the base frame (instrument and target
// fixed) the frames are defined by the instrument and target themselves and no gauge exists.
//
// Example:
//   CalibrationVector nominal = nominal_calibration_vector(design, 0.0);
//   CalibrationOptions options;  // sigmas, loss, ...
//   options.free = model_free_mask(CalibrationModelKind::k48);
//   CalibrationResult result = calibrate(design, nominal, measurements, options);
//   HexapodDesign calibrated = calibrated_design(design, result.estimate);
#pragma once

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "models/core/pose.hpp"
#include "models/hexapod/hexapod.hpp"

namespace pkmopt {

inline constexpr int kCalibrationLegParameters = 8;
inline constexpr int kCalibrationMachineParameters = 48;
inline constexpr int kCalibrationInstrumentIndex = 48;
inline constexpr int kCalibrationTargetIndex = 54;
inline constexpr int kCalibrationParameters = 60;

using CalibrationVector = Eigen::Matrix<double, kCalibrationParameters, 1>;
using CalibrationMask = std::array<bool, kCalibrationParameters>;

/// A calibration that cannot be done as asked (non-identifiable parameters, too few poses).
/// The message says which parameters and what to change.
class CalibrationError : public std::runtime_error {
 public:
  explicit CalibrationError(const std::string& message) : std::runtime_error(message) {}
};

/// "a1.x", "offset3", "gain6", "instrument.rz", "target.y", ...
std::string calibration_parameter_name(int index);
/// Index of a parameter name, or -1.
int calibration_parameter_index(const std::string& name);
/// "m", "1" or "rad".
std::string calibration_parameter_unit(int index);

/// The nominal vector of a design: joints from the design, offsets = zero_length (m),
/// gains 0, instrument and target at the identity (or the given poses).
CalibrationVector nominal_calibration_vector(const HexapodDesign& design,
                                             const Vec6<double>& zero_length,
                                             const Pose& instrument = Pose{},
                                             const Pose& target = Pose{});
/// The design with the joints of x (everything else from `nominal`).
HexapodDesign calibrated_design(const HexapodDesign& nominal, const CalibrationVector& x);

enum class CalibrationModelKind { k42, k48 };
/// Free mask of the 42- (a, b, d) or 48-parameter (a, b, d, g) model; instrument/target fixed.
CalibrationMask model_free_mask(CalibrationModelKind kind);

/// One measured pose.
struct CalibrationMeasurement {
  Pose pose;                                   ///< target pose in the instrument frame (rad)
  Vec6<double> stroke = Vec6<double>::Zero();  ///< readings times the nominal scale (m)
  int line = 0;                                ///< line in the measurement file (messages)
  /// The measurement campaign (0: the reference). Campaigns 1, 2, ... have their own leg zero
  /// offsets: leg length = d_i + shift_i + (1 + g_i) stroke_i, shift estimated by calibrate.
  int campaign = 0;
  /// The campaign's leg zero shifts (m) the residuals use; calibrate sets them in its copies
  /// (0 for the reference campaign).
  Vec6<double> offset_shift = Vec6<double>::Zero();
};

enum class CalibrationLoss { kNone, kHuber, kCauchy };

/// How the covariance of the estimate is computed (both give the same matrix; tested).
enum class CalibrationCovarianceMethod {
  /// (J_id^T J_id)^-1 from the SVD of the identification Jacobian (no extra factorisation).
  kReducedInformation,
  /// ceres::Covariance (SPARSE_QR) on the full EIV problem, pose unknowns included.
  kCeres,
};

/// The a-priori uncertainty of each parameter, used only to scale the identification Jacobian
/// for the dimensionless observability indices (`Identification::scaled`): joint coordinates
/// and offsets `length` (m), gains `gain` (1), frame positions `frame_position` (m), frame
/// angles `frame_angle` (rad). Defaults: 1 mm, 2e-4, 5 mm, 1e-3 rad (the simulation's spread).
CalibrationVector calibration_parameter_scale(double length = 1e-3, double gain = 2e-4,
                                              double frame_position = 5e-3,
                                              double frame_angle = 1e-3);

struct CalibrationOptions {
  CalibrationMask free = model_free_mask(CalibrationModelKind::k48);
  double sigma_position = 20e-6;    ///< instrument position noise (m)
  double sigma_orientation = 5e-5;  ///< instrument orientation noise (rad)
  double sigma_actuator = 1e-6;     ///< actuator reading noise (m)
  CalibrationLoss loss = CalibrationLoss::kHuber;
  double loss_scale = 5.0;  ///< in whitened units (sqrt of a pose's chi^2)
  /// A pose is an outlier when its chi^2 (12 residuals, 6 pose unknowns) exceeds this;
  /// default: the 0.9999 quantile of chi^2 with 6 degrees of freedom.
  double outlier_chi2 = 27.86;
  bool reject_outliers = true;
  /// Estimate the three sigmas from the residuals (problems/calibration/calibration_noise.cpp): a
  /// robust start from the median residuals, then variance-component estimation on the inliers,
  /// iterated with the outlier test and the fit; the given sigmas are only the start. Off: the
  /// given sigmas are taken as true.
  bool estimate_noise = true;
  int noise_iterations = 30;  ///< variance-component iterations at most
  /// A result with more rejected poses than this share is reported as probably wrong.
  double max_rejected_share = 0.2;
  int max_iterations = 200;
  double rank_tolerance = 1e-8;  ///< relative to the largest singular value of J_id
  double correlation_threshold = 0.9;
  bool compute_covariance = true;
  CalibrationCovarianceMethod covariance_method = CalibrationCovarianceMethod::kReducedInformation;
  /// Column scaling of the identification Jacobian for the scaled indices (parameter units).
  CalibrationVector parameter_scale = calibration_parameter_scale();

  /// Empty when valid, else "CalibrationOptions::x = v. Violated constraint: ...".
  std::string validate() const;
};

/// Singular values and observability indices of one scaling of the identification Jacobian.
struct ObservabilityIndices {
  Eigen::VectorXd singular_values;  ///< descending
  double O1 = 0.0, O2 = 0.0, O3 = 0.0, O4 = 0.0;
};

/// Rank, singular values and observability indices of the identification Jacobian.
/// Unscaled: columns in the parameters' own units (m, 1, rad), rows whitened (dimensionless),
/// so a singular value has the unit 1/(parameter unit) of the direction it belongs to, and O1,
/// O3, O4 mix metres and gains. `scaled`: each column multiplied by the parameter's a-priori
/// uncertainty (`CalibrationOptions::parameter_scale`), i.e. parameters counted in units of
/// their expected error; these indices are dimensionless and comparable between models.
struct Identification {
  std::vector<int> free_indices;  ///< parameter index of each column of J_id
  int num_poses = 0;
  int rank = 0;
  Eigen::VectorXd singular_values;                ///< descending (unscaled)
  double O1 = 0.0, O2 = 0.0, O3 = 0.0, O4 = 0.0;  ///< unscaled
  Eigen::VectorXd column_scale;                   ///< parameter_scale of each column
  ObservabilityIndices scaled;                    ///< of J_id * diag(column_scale)
  /// Unidentifiable directions (free_indices.size() x (n - rank)), unit columns.
  Eigen::MatrixXd null_space;
  /// Names of the parameters taking part in the null space (|component| > 0.05), sorted.
  std::vector<std::string> unidentifiable;
};

struct CorrelatedPair {
  int first = 0, second = 0;
  double correlation = 0.0;
};

/// Before/after error figures on a set of poses.
struct CalibrationErrors {
  int count = 0;
  Vec6<double> leg_rms = Vec6<double>::Zero();  ///< model length - reading length (m)
  Vec6<double> leg_max = Vec6<double>::Zero();
  double tcp_position_rms = 0.0, tcp_position_max = 0.0;        ///< m
  double tcp_orientation_rms = 0.0, tcp_orientation_max = 0.0;  ///< rad
  int fk_failures = 0;  ///< poses where forward kinematics did not converge (not counted)
};

struct CalibrationResult {
  CalibrationVector estimate = CalibrationVector::Zero();
  /// 60 x 60 covariance of the estimate: (J_id^T J_id)^-1 of the whitened problem times the
  /// a-posteriori variance factor chi2_per_dof (`covariance_scale`), so that the sigmas hold
  /// whatever the noise sigmas were; rows/columns of fixed parameters are zero.
  Eigen::MatrixXd covariance;
  double covariance_scale = 1.0;  ///< the factor the whitened covariance was multiplied by
  CalibrationVector sigma = CalibrationVector::Zero();  ///< sqrt of the covariance diagonal
  std::vector<CorrelatedPair> correlated;
  std::vector<Pose> adjusted_poses;  ///< estimated true TCP poses in the base frame
  std::vector<double> chi2;   ///< per pose, at the final (inlier) fit; robust fit for outliers
  std::vector<int> outliers;  ///< indices into the measurements
  Identification identification;
  double chi2_per_dof = 0.0;  ///< a-posteriori variance factor (1 when the sigmas are right)
  /// The noise sigmas: as given, and as used for the final fit (estimated from the data with
  /// CalibrationOptions::estimate_noise, else the given ones): position (m), orientation (rad),
  /// actuator (m).
  Eigen::Vector3d given_sigma = Eigen::Vector3d::Zero();
  Eigen::Vector3d estimated_sigma = Eigen::Vector3d::Zero();
  bool noise_estimated = false;
  /// Per group: whether the data resolve its sigma (Helmert's variance-component estimate with
  /// a relative standard deviation of at most 20 %, problems/calibration/calibration_noise.cpp); an
  /// unresolved group keeps the sigma it had (the given one after the robust start).
  std::array<bool, 3> noise_resolved{};
  /// The relative standard deviation of each resolved group's variance estimate (inf if not).
  Eigen::Vector3d noise_relative_sd = Eigen::Vector3d::Zero();
  int noise_iterations = 0;  ///< variance-component iterations done
  /// Redundancy of each group (position, orientation, actuator) in the last estimate; they sum
  /// to the degrees of freedom 6 N - n_free.
  Eigen::Vector3d group_redundancy = Eigen::Vector3d::Zero();
  bool converged = false;
  int iterations = 0;
  std::string solver_message;
  /// Per measurement campaign c = 1, 2, ... (index c - 1): the leg zero shifts against the
  /// reference campaign 0 (m) and their standard deviations (scaled as the covariance).
  std::vector<Vec6<double>> campaign_shifts;
  std::vector<Vec6<double>> campaign_shift_sigma;
  /// Whether campaign c's shifts were estimated (false: every pose of it rejected; shifts 0).
  std::vector<bool> campaign_estimated;
};

/// Whitened residuals of one pose (12: 6 legs, 3 position, 3 orientation) for a TCP pose in
/// the base frame.
Eigen::Matrix<double, 12, 1> calibration_residuals(const CalibrationVector& x,
                                                   const Eigen::Vector3d& tcp,
                                                   const CalibrationMeasurement& measurement,
                                                   const Pose& tcp_pose,
                                                   const CalibrationOptions& options);

/// Autodiff Jacobian (12 x 66) of calibration_residuals: columns 0..59 the parameters x,
/// 60..65 the TCP pose (x, y, z, rx, ry, rz).
Eigen::Matrix<double, 12, 66> calibration_jacobian(const CalibrationVector& x,
                                                   const Eigen::Vector3d& tcp,
                                                   const CalibrationMeasurement& measurement,
                                                   const Pose& tcp_pose,
                                                   const CalibrationOptions& options);

/// The 12 x 6 Jacobian of calibration_residuals with respect to the TCP pose alone, as the solver
/// evaluates it when the instrument and target transforms are held (a separate 6-jet path).
Eigen::Matrix<double, 12, 6> calibration_pose_jacobian(const CalibrationVector& x,
                                                       const Eigen::Vector3d& tcp,
                                                       const CalibrationMeasurement& measurement,
                                                       const Pose& tcp_pose,
                                                       const CalibrationOptions& options);

/// The TCP pose in the base frame of a measured target pose: T_I * M * T_T^-1.
Pose tcp_pose_from_measurement(const CalibrationVector& x, const Pose& measured);
/// The target pose in the instrument frame of a TCP pose in the base frame (inverse of above).
Pose measurement_from_tcp_pose(const CalibrationVector& x, const Pose& tcp_pose);
/// Readings-to-length: d_i + (1 + g_i) stroke_i.
Vec6<double> leg_lengths_from_stroke(const CalibrationVector& x, const Vec6<double>& stroke);
/// The same for a measurement, with its campaign's shifts: d_i + shift_i + (1 + g_i) stroke_i.
Vec6<double> leg_lengths_of(const CalibrationVector& x, const CalibrationMeasurement& m);

/// The 6 x n_free reduced identification rows of one pose (pose unknowns eliminated).
Eigen::MatrixXd reduced_identification_rows(const CalibrationVector& x, const Eigen::Vector3d& tcp,
                                            const CalibrationMeasurement& measurement,
                                            const Pose& tcp_pose,
                                            const std::vector<int>& free_indices,
                                            const CalibrationOptions& options);

/// Identification of the free parameters from the given poses (TCP poses in the base frame).
Identification identify(const CalibrationVector& x, const Eigen::Vector3d& tcp,
                        const std::vector<CalibrationMeasurement>& measurements,
                        const std::vector<Pose>& tcp_poses, const CalibrationOptions& options);

/// The parameters to hold at nominal so that the frame freedoms (6 if the instrument transform
/// has a free coordinate, 6 more for the target) disappear: chosen among the free joint
/// coordinates by column-pivoted QR of the null space of J_id at x. Empty when there is none.
std::vector<int> choose_gauge_fixing(const CalibrationVector& x, const Eigen::Vector3d& tcp,
                                     const std::vector<CalibrationMeasurement>& measurements,
                                     const CalibrationOptions& options);

/// Calibrates: checks identifiability at the start (throws CalibrationError naming the
/// parameters), solves the robust EIV problem with Ceres, rejects outliers, refits on the
/// inliers, computes covariance and identification at the solution.
CalibrationResult calibrate(const HexapodDesign& nominal_design, const CalibrationVector& start,
                            const std::vector<CalibrationMeasurement>& measurements,
                            const CalibrationOptions& options);

/// The measurements with their campaigns' leg zero shifts from `result` (offset_shift), as the
/// fit saw them: for errors and screening of the calibrated machine. A campaign without fitted
/// poses has no estimated shift and gets none.
std::vector<CalibrationMeasurement> with_campaign_shifts(
    const std::vector<CalibrationMeasurement>& measurements, const CalibrationResult& result);

/// Errors of the machine x on the given measurements (indices), TCP errors by forward
/// kinematics from the readings compared with the measured pose mapped into the base frame.
CalibrationErrors calibration_errors(const HexapodDesign& nominal_design,
                                     const CalibrationVector& x,
                                     const std::vector<CalibrationMeasurement>& measurements,
                                     const std::vector<int>& indices);

/// Screens poses that were not fitted (held-out rows): for each measurement in `indices`, its
/// own TCP pose is fitted with the machine x held (12 whitened residuals, 6 pose unknowns), and
/// the minimum chi^2 (6 degrees of freedom) is returned, in the order of `indices`. A pose whose
/// chi^2 exceeds options.outlier_chi2 is a gross outlier, as in the fit.
std::vector<double> fixed_machine_chi2(const Eigen::Vector3d& tcp, const CalibrationVector& x,
                                       const std::vector<CalibrationMeasurement>& measurements,
                                       const std::vector<int>& indices,
                                       const CalibrationOptions& options);

// ---- Synthetic measurements -------------------------------------------------------------------

struct MeasurementSimulationOptions {
  std::uint64_t seed = 1;
  int num_poses = 60;
  double joint_sigma = 1e-3;              ///< true joint position errors (m, each coordinate)
  double offset_sigma = 1e-3;             ///< true leg offset errors (m)
  double gain_sigma = 2e-4;               ///< true gain errors (relative)
  double tracker_sigma = 15e-6;           ///< instrument position noise, constant part (m)
  double tracker_sigma_per_metre = 6e-6;  ///< plus this times the distance to the instrument
  double orientation_sigma = 5e-5;        ///< instrument orientation noise (rad)
  double actuator_sigma = 1e-6;           ///< reading noise (m)
  int num_outliers = 3;
  double outlier_magnitude = 1e-3;        ///< gross position error of an outlier (m)
  double xy_range = 0.15;                 ///< |x|, |y| <= this (m)
  double z_min = 0.75, z_max = 0.95;      ///< TCP height range (m)
  double angle_range = 12.0 * kDegToRad;  ///< |rx|, |ry|, |rz| <= this (rad)
};

struct SimulatedMeasurements {
  CalibrationVector truth = CalibrationVector::Zero();
  std::vector<CalibrationMeasurement> measurements;
  std::vector<Pose> true_poses;      ///< TCP poses in the base frame
  std::vector<int> outliers;         ///< indices of the poses given a gross error
  double mean_position_sigma = 0.0;  ///< mean instrument position sigma over the poses (m)
};

/// Draws a true machine around `nominal` (fixed instrument/target are kept), reachable random
/// poses, and noisy measurements. Deterministic for a seed.
SimulatedMeasurements simulate_measurements(const HexapodDesign& nominal_design,
                                            const CalibrationVector& nominal,
                                            const CalibrationMask& perturbed,
                                            const MeasurementSimulationOptions& options);

// ---- Pose selection ---------------------------------------------------------------------------

struct PoseSelection {
  std::vector<int> selected;  ///< indices into the candidates, ascending
  double log_det = 0.0;       ///< log det(J_id^T J_id) of the selection
  Identification identification;
  int exchanges = 0;
};

/// D-optimal selection of `count` poses (TCP poses, base frame) among candidates: greedy start,
/// then Fedorov exchange until no swap raises det(J_id^T J_id). Evaluated at the machine x with
/// perfect measurements. Throws CalibrationError if count * 6 < number of free parameters or
/// the candidates cannot identify them.
PoseSelection select_calibration_poses(const CalibrationVector& x, const Eigen::Vector3d& tcp,
                                       const std::vector<Pose>& candidates, int count,
                                       const CalibrationOptions& options);

}  // namespace pkmopt
