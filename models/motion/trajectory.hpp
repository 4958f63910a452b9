// TCP trajectories: a path pose(t) with its time derivative, the actuator coordinates and rates
// a machine needs to follow it, and the singular poses it crosses.
//
// Pose rate and twist. A path gives the TCP pose (p, a) at time t (a = (rx, ry, rz), radians,
// R = Rz(rz) Ry(ry) Rx(rx), docs/conventions.md) and its derivative (p_dot, a_dot). The twist a
// machine's inverse Jacobian takes is [v; omega] with omega the angular velocity in base axes,
// NOT the Euler angle rates:
//     omega = E(a) a_dot,   E(a) = [ cz*cy  -sz  0 ]
//                                  [ sz*cy   cz  0 ]
//                                  [  -sy     0  1 ]
// (omega = rz_dot e_z + ry_dot Rz e_y + rx_dot Rz Ry e_x; cy = cos ry, sz = sin rz, ...).
// The actuator rates are then q_dot = J(pose) [v; omega] (Machine::twist_jacobian).
//
// The helical test path (HelixPath), with the phase phi = w t (w in rad/s, 1 by default):
//     amp(phi) = r0 + r1 phi / (2 pi)
//     x = cx + amp cos phi,   y = cy + amp sin phi,   z = cz + z0 + z1 phi^2 / (4 pi^2)
//     rx = ox + ax sin phi,   ry = oy + ay cos phi,   rz = oz + az sin 2 phi
// (r0 = 0.01 m, r1 = 0.02 m, z0 = 0.01 m, z1 = 0.01 m as in the 16K20F3 lathe-conversion study;
// the harmonic angle form and its amplitudes a are this project's choice, not given there).
//
// Its second derivative is analytic too (d/dt = w d/dphi):
//     x'' = w^2 (-2 amp' sin phi - amp cos phi),   y'' = w^2 (2 amp' cos phi - amp sin phi),
//     z'' = w^2 2 z1 / (4 pi^2),   rx'' = -w^2 ax sin phi,   ry'' = -w^2 ay cos phi,
//     rz'' = -4 w^2 az sin 2 phi    (amp' = r1 / (2 pi)).
//
// A sampled path (SampledPath) interpolates given poses with the not-a-knot cubic spline in t
// (models/motion/cubic_spline.hpp): twice continuously differentiable, so its rates and
// accelerations are those of one smooth curve through the samples (a path that is a cubic in t is
// reproduced exactly). Angles must be continuous (no jump of 360 deg). The spline follows every
// sample, so noise in measured samples shows up, amplified, in the accelerations: give a smooth
// path.
//
// Twist rate. The TCP's acceleration a = p_ddot and the angular acceleration
//     alpha = d omega / dt = E(a) a_ddot + E_dot(a, a_dot) a_dot,
//     alpha_x = cz cy rx'' - sz ry'' - (sz cy rz' + cz sy ry') rx' - cz rz' ry'
//     alpha_y = sz cy rx'' + cz ry'' + (cz cy rz' - sz sy ry') rx' - sz rz' ry'
//     alpha_z = -sy rx'' + rz'' - cy ry' rx'
// give the twist rate xi_dot = [a; alpha] of the inverse dynamics.
//
// Inverse dynamics. With a mass model (Machine::mass_model), each sample also gets the actuator
// forces that balance the external wrench w on the tool, gravity and the inertia of the
// platform and every leg body, tau_dyn = the forces analyze gives for w + w_dyn(xi, xi_dot)
// (Machine::dynamic_wrench, models/dynamics/machine_dynamics.hpp: J^T tau_dyn = w + w_dyn); with
// zero velocity and acceleration it is tau under w plus gravity.
//
// evaluate_trajectory runs the machine along a path at given times: the pose, the twist, every
// metric of Machine::analyze (q, reachable, singularity_margin, det_j, singular), J, q_dot = J
// xi, and, as an independent check, q_dot_fd: the central difference of the IK coordinates q at
// the neighbouring samples (agrees with q_dot to O(dt^2)). Singular poses are reported where
// they occur: at a sample that is singular (PoseMetrics::singular: singularity_margin 0, or for
// leg chains a leg that cannot close), and between two regular samples whose det_j have
// opposite signs, located by bisection on t down to the last bit of t.
//
// stepped_times gives the sample times of a fixed time step; summarize_trajectory reduces a run
// to the ranges along the path (actuator coordinates and rates, reachable samples, the smallest
// singularity_margin) and the worst disagreement of q_dot with q_dot_fd at interior samples.
//
// Units: m, rad, s inside the code (files show degrees).
//
// Example:
//   pkmopt::HelixPath helix;                       // the test helix about the origin
//   helix.parameters.centre = {0, 0, 0.9};
//   std::vector<double> times = pkmopt::uniform_times(helix.t_start(), helix.t_end(), 201);
//   pkmopt::TrajectoryResult run = pkmopt::evaluate_trajectory(machine, helix, times);
//   for (const auto& s : run.samples) std::cout << s.t << " " << s.q_dot.transpose() << "\n";
//   for (const auto& p : run.singular_poses) std::cout << "singular at t = " << p.t << "\n";
//   const pkmopt::TrajectorySummary summary =
//       pkmopt::summarize_trajectory(run, machine.num_actuators());   // summary.q_dot_max ...
#pragma once

#include <Eigen/Core>
#include <cstddef>
#include <limits>
#include <numbers>
#include <optional>
#include <vector>

#include "models/core/machine.hpp"
#include "models/core/pose.hpp"
#include "models/motion/cubic_spline.hpp"

namespace pkmopt {

/// Below this singularity_margin a path sample is near a singular pose: the drive rates grow as
/// 1 / margin there (the trajectory summary warns).
inline constexpr double kNearSingularMargin = 0.01;

/// omega = E(angles) * angle_rates for R = Rz(rz) Ry(ry) Rx(rx) (angles in rad, base axes).
Eigen::Matrix3d angular_velocity_map(const Eigen::Vector3d& angles);

/// A pose and its time derivative [x_dot, y_dot, z_dot, rx_dot, ry_dot, rz_dot] (m/s, rad/s).
struct PathPoint {
  Pose pose;
  Vector6d pose_rate = Vector6d::Zero();
  Vector6d pose_acceleration = Vector6d::Zero();  ///< second time derivative (m/s^2, rad/s^2)
};

/// The TCP twist [v; omega] (m/s; rad/s, base axes) of a pose moving at pose_rate.
Vector6d twist_from_pose_rate(const PathPoint& point);
/// The TCP twist rate [a; alpha] (m/s^2; rad/s^2, base axes) of the point (header comment).
Vector6d twist_rate_from_path(const PathPoint& point);

/// A TCP path over the time interval [t_start, t_end] (s).
class TcpPath {
 public:
  virtual ~TcpPath() = default;
  virtual double t_start() const = 0;
  virtual double t_end() const = 0;
  /// The pose at t and its first and second time derivatives.
  virtual PathPoint at(double t) const = 0;
};

/// Parameters of the helical test path (see the header comment). Lengths in m, angles in rad.
struct HelixParameters {
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();            ///< (cx, cy, cz), m
  double radius_start = 0.01;                                  ///< r0, m
  double radius_growth = 0.02;                                 ///< r1, m per turn
  double height_start = 0.01;                                  ///< z0, m
  double height_growth = 0.01;                                 ///< z1, m after one turn (quadratic)
  Eigen::Vector3d nominal_angles = Eigen::Vector3d::Zero();    ///< (ox, oy, oz), rad
  Eigen::Vector3d angle_amplitudes = Eigen::Vector3d::Zero();  ///< (ax, ay, az), rad
  double angular_frequency = 1.0;                              ///< w, rad/s (phase = w t)
  double t_start = 0.0;                                        ///< s
  double t_end = 2.0 * std::numbers::pi;                       ///< s (one turn at w = 1)
};

/// The helical test path with analytic first and second derivatives.
class HelixPath final : public TcpPath {
 public:
  HelixPath() = default;
  explicit HelixPath(const HelixParameters& p) : parameters(p) {}
  double t_start() const override { return parameters.t_start; }
  double t_end() const override { return parameters.t_end; }
  PathPoint at(double t) const override;

  HelixParameters parameters;
};

/// Poses given at strictly increasing times (at least 2), interpolated by the not-a-knot cubic
/// spline of every coordinate (x, y, z, rx, ry, rz) in t.
class SampledPath final : public TcpPath {
 public:
  /// Throws std::invalid_argument when fewer than 2 samples, sizes differ, a value is not
  /// finite or the times do not increase strictly.
  SampledPath(std::vector<double> times, const std::vector<Pose>& poses);
  double t_start() const override { return spline_.times().front(); }
  double t_end() const override { return spline_.times().back(); }
  PathPoint at(double t) const override;
  const std::vector<double>& times() const { return spline_.times(); }

 private:
  CubicSpline spline_;
};

/// count >= 2 times evenly spaced from t_start to t_end (both included).
std::vector<double> uniform_times(double t_start, double t_end, int count);

/// t_start, t_start + dt, t_start + 2 dt, ... while below t_end - 1e-9 min(dt, t_end - t_start),
/// then t_end: the step is kept and the last step is shorter when dt does not divide the span
/// (a step longer than the span gives t_start and t_end). Sample k is
/// t_start + k dt (no accumulated rounding). Throws std::invalid_argument unless t_start and
/// t_end are finite with t_end > t_start and dt > 0 is finite.
std::vector<double> stepped_times(double t_start, double t_end, double dt);

/// d values / dt at every time by the three-point central difference for uneven spacing
/// (second order), one-sided first differences at the two ends. values[k] belongs to times[k];
/// needs at least 2 strictly increasing times.
std::vector<Eigen::VectorXd> central_difference_rates(const std::vector<double>& times,
                                                      const std::vector<Eigen::VectorXd>& values);

/// Everything at one sample of a trajectory.
struct TrajectorySample {
  double t = 0.0;                          ///< s
  Pose pose;                               ///< m, rad
  Vector6d twist = Vector6d::Zero();       ///< [v; omega], m/s and rad/s, base axes
  Vector6d twist_rate = Vector6d::Zero();  ///< [a; alpha], m/s^2 and rad/s^2, base axes
  PoseMetrics metrics;  ///< Machine::analyze at the pose under the external wrench (no gravity)
  bool jacobian_ok = false;  ///< Machine::twist_jacobian succeeded
  Eigen::MatrixXd J;         ///< num_actuators x 6 (empty when !jacobian_ok)
  Eigen::VectorXd q_dot;     ///< J twist (m/s or rad/s); +inf when !jacobian_ok
  Eigen::VectorXd q_dot_fd;  ///< central difference of metrics.q over the samples
  /// With a mass model: the actuator forces balancing the wrench, gravity and inertia (N or
  /// N*m; +inf where the pose is singular or a leg cannot close); empty without one.
  Eigen::VectorXd tau_dyn;
};

/// A singular pose on the path.
struct SingularPose {
  enum class Kind {
    kSample,         ///< a sample whose singularity_margin is 0
    kDetSignChange,  ///< det_j changes sign between two regular samples; located by bisection
  };
  Kind kind = Kind::kSample;
  double t = 0.0;  ///< s
  Pose pose;
  double singularity_margin = 0.0;  ///< at t (0 when the bisection closed in on the singularity)
  double det_j_before = 0.0;        ///< det_j at the sample (or bisection end) before t
  double det_j_after = 0.0;         ///< det_j at the sample (or bisection end) after t
};

struct TrajectoryResult {
  std::vector<TrajectorySample> samples;
  std::vector<SingularPose> singular_poses;  ///< in increasing t
};

/// Runs the machine along the path at the given strictly increasing times (at least 2), the
/// tool loaded by the external wrench `wrench` (N, N*m at the TCP, base axes) at every sample.
/// Throws std::invalid_argument for fewer than 2 or non-increasing times.
TrajectoryResult evaluate_trajectory(const Machine& machine, const TcpPath& path,
                                     const std::vector<double>& times,
                                     const Wrench& wrench = Wrench::Zero());

/// Ranges along a trajectory (SI units: m or rad for q, m/s or rad/s for rates).
struct TrajectorySummary {
  std::size_t samples = 0;
  std::size_t reachable = 0;  ///< samples with metrics.reachable
  /// min over the samples (+inf with no sample)
  double singularity_margin_min = std::numeric_limits<double>::infinity();
  Eigen::VectorXd q_min;      ///< per actuator, min of metrics.q (+inf with no sample)
  Eigen::VectorXd q_max;      ///< per actuator, max of metrics.q (-inf with no sample)
  Eigen::VectorXd q_dot_max;  ///< per actuator, max |q_dot| (0 with no sample)
  /// max over actuators and interior samples (not the first or last) with jacobian_ok of
  /// |q_dot - q_dot_fd|; 0 when there is none.
  double q_dot_mismatch_max = 0.0;
  /// The sample of singularity_margin_min (0 with no sample).
  std::size_t singularity_margin_min_sample = 0;
  /// The same per actuator (machines that mix linear and rotary axes report each in its unit).
  Eigen::VectorXd q_dot_mismatch;
  double speed_max = 0.0;         ///< max |v| of the TCP (m/s)
  double acceleration_max = 0.0;  ///< max |a| of the TCP (m/s^2)
  Eigen::VectorXd tau_max;        ///< per actuator, max |tau| under the wrench alone
  /// With a mass model (dynamics true), per actuator: the peak |tau_dyn|, its RMS over time
  /// (sqrt of the trapezoidal integral of tau_dyn^2 over the span, divided by the span), and the
  /// peak mechanical power max |tau_dyn q_dot| (W). +inf when some sample has none.
  bool dynamics = false;
  Eigen::VectorXd tau_dyn_max;
  Eigen::VectorXd tau_dyn_rms;
  Eigen::VectorXd power_max;
  /// With a leg shape (Machine::checks_leg_interference): the smallest leg_clearance over the
  /// samples (m; +inf without a shape), the sample it is at, and the first sample whose legs
  /// intersect (leg_clearance < 0), none when no sample does.
  double clearance_min = std::numeric_limits<double>::infinity();
  std::size_t clearance_min_sample = 0;
  std::optional<std::size_t> first_intersecting;
};

/// The summary of a run of a machine with `num_actuators` actuators.
TrajectorySummary summarize_trajectory(const TrajectoryResult& result, int num_actuators);

}  // namespace pkmopt
