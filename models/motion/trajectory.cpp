#include "models/motion/trajectory.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "models/core/capabilities.hpp"

namespace pkmopt {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

void check_times(const std::vector<double>& times, const char* what) {
  if (times.size() < 2) {
    throw std::invalid_argument(std::string(what) + ": at least 2 times needed, found " +
                                std::to_string(times.size()));
  }
  for (std::size_t k = 0; k < times.size(); ++k) {
    if (!std::isfinite(times[k])) {
      throw std::invalid_argument(std::string(what) + ": time " + std::to_string(k) +
                                  " is not finite");
    }
    if (k > 0 && !(times[k] > times[k - 1])) {
      throw std::invalid_argument(std::string(what) + ": times must increase strictly (time " +
                                  std::to_string(k) + ")");
    }
  }
}

// The sign of det_j at a regular pose: +1, -1, or 0 at a singular pose.
int det_sign(const PoseMetrics& m) {
  if (m.singular || m.det_j == 0.0) return 0;
  return m.det_j > 0.0 ? 1 : -1;
}

}  // namespace

Eigen::Matrix3d angular_velocity_map(const Eigen::Vector3d& angles) {
  const double cy = std::cos(angles(1)), sy = std::sin(angles(1));
  const double cz = std::cos(angles(2)), sz = std::sin(angles(2));
  Eigen::Matrix3d E;
  E << cz * cy, -sz, 0.0,  //
      sz * cy, cz, 0.0,    //
      -sy, 0.0, 1.0;
  return E;
}

Vector6d twist_from_pose_rate(const PathPoint& point) {
  Vector6d twist;
  twist.head<3>() = point.pose_rate.head<3>();
  twist.tail<3>() = angular_velocity_map(point.pose.angles) * point.pose_rate.tail<3>();
  return twist;
}

Vector6d twist_rate_from_path(const PathPoint& point) {
  const Eigen::Vector3d& angles = point.pose.angles;
  const double cy = std::cos(angles(1)), sy = std::sin(angles(1));
  const double cz = std::cos(angles(2)), sz = std::sin(angles(2));
  const double rx1 = point.pose_rate(3), ry1 = point.pose_rate(4), rz1 = point.pose_rate(5);
  // E_dot a_dot: the derivative of E(a) along a_dot (E depends on ry and rz only).
  const Eigen::Vector3d e_dot_a_dot((-sz * cy * rz1 - cz * sy * ry1) * rx1 - cz * rz1 * ry1,
                                    (cz * cy * rz1 - sz * sy * ry1) * rx1 - sz * rz1 * ry1,
                                    -cy * ry1 * rx1);
  Vector6d rate;
  rate.head<3>() = point.pose_acceleration.head<3>();
  rate.tail<3>() = angular_velocity_map(angles) * point.pose_acceleration.tail<3>() + e_dot_a_dot;
  return rate;
}

PathPoint HelixPath::at(double t) const {
  const HelixParameters& p = parameters;
  constexpr double kTwoPi = 2.0 * std::numbers::pi;
  const double w = p.angular_frequency;
  const double phi = w * t;
  const double c = std::cos(phi), s = std::sin(phi);
  const double amp = p.radius_start + p.radius_growth * phi / kTwoPi;
  const double amp_rate = p.radius_growth / kTwoPi;  // d amp / d phi
  PathPoint out;
  out.pose.position =
      p.centre + Eigen::Vector3d(amp * c, amp * s,
                                 p.height_start + p.height_growth * phi * phi / (kTwoPi * kTwoPi));
  const Eigen::Vector3d& a = p.angle_amplitudes;
  out.pose.angles =
      p.nominal_angles + Eigen::Vector3d(a(0) * s, a(1) * c, a(2) * std::sin(2 * phi));
  out.pose_rate << amp_rate * c - amp * s, amp_rate * s + amp * c,
      2.0 * p.height_growth * phi / (kTwoPi * kTwoPi), a(0) * c, -a(1) * s,
      2.0 * a(2) * std::cos(2 * phi);
  out.pose_rate *= w;
  out.pose_acceleration << -2.0 * amp_rate * s - amp * c, 2.0 * amp_rate * c - amp * s,
      2.0 * p.height_growth / (kTwoPi * kTwoPi), -a(0) * s, -a(1) * c,
      -4.0 * a(2) * std::sin(2 * phi);
  out.pose_acceleration *= w * w;
  return out;
}

std::vector<Eigen::VectorXd> central_difference_rates(const std::vector<double>& times,
                                                      const std::vector<Eigen::VectorXd>& values) {
  check_times(times, "central_difference_rates");
  if (values.size() != times.size()) {
    throw std::invalid_argument("central_difference_rates: " + std::to_string(values.size()) +
                                " values for " + std::to_string(times.size()) + " times");
  }
  const std::size_t n = times.size();
  std::vector<Eigen::VectorXd> rates(n);
  rates[0] = (values[1] - values[0]) / (times[1] - times[0]);
  rates[n - 1] = (values[n - 1] - values[n - 2]) / (times[n - 1] - times[n - 2]);
  for (std::size_t k = 1; k + 1 < n; ++k) {
    // Derivative of the parabola through the three samples, at the middle one.
    const double h1 = times[k] - times[k - 1], h2 = times[k + 1] - times[k];
    rates[k] = -h2 / (h1 * (h1 + h2)) * values[k - 1] + (h2 - h1) / (h1 * h2) * values[k] +
               h1 / (h2 * (h1 + h2)) * values[k + 1];
  }
  return rates;
}

namespace {

CubicSpline pose_spline(std::vector<double> times, const std::vector<Pose>& poses) {
  check_times(times, "SampledPath");
  if (poses.size() != times.size()) {
    throw std::invalid_argument("SampledPath: " + std::to_string(poses.size()) + " poses for " +
                                std::to_string(times.size()) + " times");
  }
  Eigen::MatrixXd values(static_cast<Eigen::Index>(poses.size()), 6);
  for (std::size_t k = 0; k < poses.size(); ++k) {
    values.row(static_cast<Eigen::Index>(k)) << poses[k].position.transpose(),
        poses[k].angles.transpose();
  }
  return CubicSpline(std::move(times), std::move(values));
}

}  // namespace

SampledPath::SampledPath(std::vector<double> times, const std::vector<Pose>& poses)
    : spline_(pose_spline(std::move(times), poses)) {}

PathPoint SampledPath::at(double t) const {
  Eigen::VectorXd value, rate, acceleration;
  spline_.evaluate(t, value, rate, acceleration);
  PathPoint out;
  out.pose.position = value.head<3>();
  out.pose.angles = value.tail<3>();
  out.pose_rate = rate;
  out.pose_acceleration = acceleration;
  return out;
}

std::vector<double> uniform_times(double t_start, double t_end, int count) {
  if (count < 2) throw std::invalid_argument("uniform_times: count must be >= 2");
  std::vector<double> times(static_cast<std::size_t>(count));
  for (int k = 0; k < count; ++k) {
    times[static_cast<std::size_t>(k)] =
        k == count - 1 ? t_end : t_start + (t_end - t_start) * k / (count - 1);
  }
  return times;
}

std::vector<double> stepped_times(double t_start, double t_end, double dt) {
  if (!(std::isfinite(t_start) && std::isfinite(t_end) && t_end > t_start && std::isfinite(dt) &&
        dt > 0.0)) {
    throw std::invalid_argument(
        "stepped_times: needs finite t_start < t_end and a finite time step dt > 0");
  }
  // A last step shorter than a billionth of the step (or of the span) is rounding: dropped.
  const double tolerance = 1e-9 * std::min(dt, t_end - t_start);
  std::vector<double> times;
  for (double t = t_start; t < t_end - tolerance;
       t = t_start + static_cast<double>(times.size()) * dt) {
    times.push_back(t);
  }
  times.push_back(t_end);
  return times;
}

TrajectoryResult evaluate_trajectory(const Machine& machine, const TcpPath& path,
                                     const std::vector<double>& times, const Wrench& wrench) {
  check_times(times, "evaluate_trajectory");
  const int na = machine.num_actuators();
  const std::unique_ptr<MachineData> data = machine.make_data();
  const Capability<Dynamics> dynamics = machine.dynamics();
  PoseMetrics scratch;
  TrajectoryResult result;
  result.samples.resize(times.size());
  for (std::size_t k = 0; k < times.size(); ++k) {
    TrajectorySample& s = result.samples[k];
    s.t = times[k];
    const PathPoint point = path.at(s.t);
    s.pose = point.pose;
    s.twist = twist_from_pose_rate(point);
    s.twist_rate = twist_rate_from_path(point);
    if (dynamics) {
      // tau_dyn: the actuator forces under the wrench, gravity and inertia.
      if (dynamics->inverse_dynamics(*data, s.pose, s.twist, s.twist_rate, wrench, scratch)) {
        s.tau_dyn = scratch.tau;
        for (Eigen::Index i = 0; i < s.tau_dyn.size(); ++i) {
          if (!std::isfinite(s.tau_dyn(i)) || scratch.singular) s.tau_dyn(i) = kInf;
        }
      } else {
        s.tau_dyn = Eigen::VectorXd::Constant(na, kInf);
      }
    }
    machine.analyze(*data, s.pose, wrench, s.metrics);
    s.jacobian_ok = machine.twist_jacobian(*data, s.pose, s.J);
    if (s.jacobian_ok) {
      s.q_dot = s.J * s.twist;
    } else {
      s.J.resize(0, 0);
      s.q_dot = Eigen::VectorXd::Constant(na, kInf);
    }
  }

  // The check: q_dot from the IK coordinates at the neighbouring samples.
  std::vector<Eigen::VectorXd> q(times.size());
  for (std::size_t k = 0; k < times.size(); ++k) q[k] = result.samples[k].metrics.q;
  // A rotary axis that turns past its wrap (a table's C through 180 degrees) is unwrapped, so that
  // its whole turns do not show as rates.
  for (int i = 0; i < na; ++i) {
    if (!machine.revolute_actuator(i)) continue;
    for (std::size_t k = 1; k < q.size(); ++k) {
      const double step = q[k](i) - q[k - 1](i);
      if (std::isfinite(step)) q[k](i) = q[k - 1](i) + std::remainder(step, 2.0 * std::numbers::pi);
    }
  }
  const std::vector<Eigen::VectorXd> q_rate = central_difference_rates(times, q);
  for (std::size_t k = 0; k < times.size(); ++k) {
    Eigen::VectorXd fd = q_rate[k];
    for (int i = 0; i < na; ++i) {
      if (!std::isfinite(fd(i))) fd(i) = kInf;
    }
    result.samples[k].q_dot_fd = fd;
  }

  // Singular poses: singular samples, and det_j sign changes between regular samples.
  PoseMetrics m;
  for (std::size_t k = 0; k < times.size(); ++k) {
    const TrajectorySample& s = result.samples[k];
    if (s.metrics.singular) {
      SingularPose p;
      p.kind = SingularPose::Kind::kSample;
      p.t = s.t;
      p.pose = s.pose;
      p.singularity_margin = s.metrics.singularity_margin;
      p.det_j_before = k > 0 ? result.samples[k - 1].metrics.det_j : s.metrics.det_j;
      p.det_j_after = k + 1 < times.size() ? result.samples[k + 1].metrics.det_j : s.metrics.det_j;
      result.singular_poses.push_back(p);
      continue;
    }
    if (k + 1 == times.size()) continue;
    const TrajectorySample& next = result.samples[k + 1];
    const int sign_lo = det_sign(s.metrics), sign_hi = det_sign(next.metrics);
    if (sign_lo == 0 || sign_hi == 0 || sign_lo == sign_hi) continue;
    // Bisection on t: keep det_j(lo) with the sign of the left sample, det_j(hi) the other.
    double lo = s.t, hi = next.t;
    double det_lo = s.metrics.det_j, det_hi = next.metrics.det_j;
    double margin_at = s.metrics.singularity_margin;
    double t_singular = 0.5 * (lo + hi);
    bool hit = false;
    for (int iteration = 0; iteration < 200; ++iteration) {
      const double mid = 0.5 * (lo + hi);
      if (!(mid > lo && mid < hi)) break;  // the interval cannot shrink any further
      machine.analyze(*data, path.at(mid).pose, Wrench::Zero(), m);
      const int sign_mid = det_sign(m);
      if (sign_mid == 0) {  // landed on the singular pose itself
        t_singular = mid;
        margin_at = m.singularity_margin;
        hit = true;
        break;
      }
      if (sign_mid == sign_lo) {
        lo = mid;
        det_lo = m.det_j;
      } else {
        hi = mid;
        det_hi = m.det_j;
      }
    }
    if (!hit) {
      t_singular = 0.5 * (lo + hi);
      machine.analyze(*data, path.at(t_singular).pose, Wrench::Zero(), m);
      margin_at = m.singularity_margin;
    }
    SingularPose p;
    p.kind = SingularPose::Kind::kDetSignChange;
    p.t = t_singular;
    p.pose = path.at(t_singular).pose;
    p.singularity_margin = margin_at;
    p.det_j_before = det_lo;
    p.det_j_after = det_hi;
    result.singular_poses.push_back(p);
  }
  return result;
}

TrajectorySummary summarize_trajectory(const TrajectoryResult& result, int num_actuators) {
  TrajectorySummary summary;
  summary.samples = result.samples.size();
  summary.q_min = Eigen::VectorXd::Constant(num_actuators, kInf);
  summary.q_max = -summary.q_min;
  summary.q_dot_max = Eigen::VectorXd::Zero(num_actuators);
  summary.q_dot_mismatch = Eigen::VectorXd::Zero(num_actuators);
  summary.tau_max = Eigen::VectorXd::Zero(num_actuators);
  summary.dynamics = !result.samples.empty() && result.samples.front().tau_dyn.size() > 0;
  if (summary.dynamics) {
    summary.tau_dyn_max = Eigen::VectorXd::Zero(num_actuators);
    summary.tau_dyn_rms = Eigen::VectorXd::Zero(num_actuators);
    summary.power_max = Eigen::VectorXd::Zero(num_actuators);
  }
  for (std::size_t k = 0; k < result.samples.size(); ++k) {
    const TrajectorySample& s = result.samples[k];
    const bool interior = k > 0 && k + 1 < result.samples.size();
    if (s.metrics.reachable) ++summary.reachable;
    if (s.metrics.leg_clearance < summary.clearance_min) {
      summary.clearance_min = s.metrics.leg_clearance;
      summary.clearance_min_sample = k;
    }
    if (s.metrics.leg_clearance < 0.0 && !summary.first_intersecting)
      summary.first_intersecting = k;
    summary.q_min = summary.q_min.cwiseMin(s.metrics.q);
    summary.q_max = summary.q_max.cwiseMax(s.metrics.q);
    summary.q_dot_max = summary.q_dot_max.cwiseMax(s.q_dot.cwiseAbs());
    if (s.metrics.tau.size() == num_actuators) {
      summary.tau_max = summary.tau_max.cwiseMax(s.metrics.tau.cwiseAbs());
    }
    summary.speed_max = std::max(summary.speed_max, s.twist.head<3>().norm());
    summary.acceleration_max = std::max(summary.acceleration_max, s.twist_rate.head<3>().norm());
    if (summary.dynamics) {
      summary.tau_dyn_max = summary.tau_dyn_max.cwiseMax(s.tau_dyn.cwiseAbs());
      for (int i = 0; i < num_actuators; ++i) {
        double power = std::abs(s.tau_dyn(i) * s.q_dot(i));
        if (std::isnan(power)) power = kInf;  // 0 * inf: an unbounded force or rate
        summary.power_max(i) = std::max(summary.power_max(i), power);
      }
      if (k > 0) {  // trapezoidal integral of tau_dyn^2 over [t_k-1, t_k]
        const TrajectorySample& previous = result.samples[k - 1];
        summary.tau_dyn_rms +=
            0.5 * (s.t - previous.t) * (s.tau_dyn.cwiseAbs2() + previous.tau_dyn.cwiseAbs2());
      }
    }
    if (s.metrics.singularity_margin < summary.singularity_margin_min) {
      summary.singularity_margin_min = s.metrics.singularity_margin;
      summary.singularity_margin_min_sample = k;
    }
    if (s.jacobian_ok && interior) {
      const Eigen::VectorXd gap = (s.q_dot - s.q_dot_fd).cwiseAbs();
      summary.q_dot_mismatch = summary.q_dot_mismatch.cwiseMax(gap);
      summary.q_dot_mismatch_max = std::max(summary.q_dot_mismatch_max, gap.maxCoeff());
    }
  }
  if (summary.dynamics) {
    const double span = result.samples.back().t - result.samples.front().t;
    summary.tau_dyn_rms = (summary.tau_dyn_rms / span).cwiseSqrt();
  }
  return summary;
}

}  // namespace pkmopt
