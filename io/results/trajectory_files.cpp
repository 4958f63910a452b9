#include "io/results/trajectory_files.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <sstream>
#include <utility>

#include "io/format/csv.hpp"
#include "io/format/pose_csv.hpp"
#include "models/dynamics/mass_model.hpp"
#include "models/geometry/leg_interference.hpp"

namespace pkmopt {
namespace {

std::string joined(const Eigen::VectorXd& v, const Eigen::VectorXd& scale) {
  std::string s;
  for (Eigen::Index i = 0; i < v.size(); ++i) s += ',' + format_number(v(i) * scale(i));
  return s;
}

// Actuator coordinates in the files: metres, or degrees for revolute drives.
Eigen::VectorXd actuator_scales(const Machine& machine) {
  Eigen::VectorXd scale(machine.num_actuators());
  for (int i = 0; i < machine.num_actuators(); ++i)
    scale(i) = machine.revolute_actuator(i) ? kRadToDeg : 1.0;
  return scale;
}

}  // namespace

SampledPath read_path_csv(const std::string& path) {
  PoseTable table = read_timed_pose_csv(path, 2);
  return SampledPath(std::move(table.times), std::move(table.poses));
}

std::string trajectory_csv(const Machine& machine, const TrajectoryResult& result, bool jacobian,
                           const TrajectoryModes* modes) {
  const int na = machine.num_actuators();
  const Eigen::VectorXd q_scale = actuator_scales(machine);
  const Eigen::VectorXd unit = Eigen::VectorXd::Ones(na);
  std::ostringstream out;
  const bool dynamics = !result.samples.empty() && result.samples.front().tau_dyn.size() > 0;
  out << "t,x,y,z,rx,ry,rz,vx,vy,vz,wx,wy,wz,ax,ay,az,alpha_x,alpha_y,alpha_z,reachable,singular";
  for (int j = 1; j <= na; ++j) out << ",q_" << j;
  for (int j = 1; j <= na; ++j) out << ",q_dot_" << j;
  for (int j = 1; j <= na; ++j) out << ",q_dot_fd_" << j;
  for (int j = 1; j <= na; ++j) out << ",tau_" << j;
  if (dynamics) {
    for (int j = 1; j <= na; ++j) out << ",tau_dyn_" << j;
  }
  out << ",singularity_margin,det_j";
  const bool interference = machine.checks_leg_interference();
  if (interference) out << ",leg_clearance,clearance_pair";
  if (modes) out << ",mode_distance,real_modes,failed_paths";
  if (jacobian) {
    for (int r = 1; r <= na; ++r) {
      for (int c = 1; c <= 6; ++c) out << ",J_" << r << '_' << c;
    }
  }
  out << '\n';
  for (std::size_t k = 0; k < result.samples.size(); ++k) {
    const TrajectorySample& s = result.samples[k];
    std::string line = format_number(s.t);
    for (int i = 0; i < 3; ++i) line += ',' + format_number(s.pose.position(i));
    for (int i = 0; i < 3; ++i) line += ',' + format_number(rad_to_deg(s.pose.angles(i)));
    for (int i = 0; i < 3; ++i) line += ',' + format_number(s.twist(i));
    for (int i = 3; i < 6; ++i) line += ',' + format_number(rad_to_deg(s.twist(i)));
    for (int i = 0; i < 3; ++i) line += ',' + format_number(s.twist_rate(i));
    for (int i = 3; i < 6; ++i) line += ',' + format_number(rad_to_deg(s.twist_rate(i)));
    line += s.metrics.reachable ? ",1" : ",0";
    line += s.metrics.singular ? ",1" : ",0";
    line += joined(s.metrics.q, q_scale);
    line += joined(s.q_dot, q_scale);
    line += joined(s.q_dot_fd, q_scale);
    line += joined(s.metrics.tau, unit);
    if (dynamics) line += joined(s.tau_dyn, unit);
    line += ',' + format_number(s.metrics.singularity_margin);
    line += ',' + format_number(s.metrics.det_j);
    if (interference) {
      line += ',' + format_number(s.metrics.leg_clearance);
      line += ',' + clearance_pair_text(s.metrics.clearance_first, s.metrics.clearance_second);
    }
    if (modes) {
      const AssemblyModeSample& m = modes->samples[k];
      line +=
          fmt::format(",{},{},{}", format_number(m.nearest_other), m.real_modes, m.failed_paths);
    }
    if (jacobian) {
      for (int r = 0; r < na; ++r) {
        for (int c = 0; c < 6; ++c) {
          line += ',' + format_number(s.jacobian_ok ? s.J(r, c)
                                                    : std::numeric_limits<double>::infinity());
        }
      }
    }
    out << line << '\n';
  }
  return out.str();
}

std::string singular_poses_csv(const TrajectoryResult& result) {
  std::ostringstream singular;
  singular << "t,x,y,z,rx,ry,rz,kind,singularity_margin,det_j_before,det_j_after\n";
  for (const SingularPose& p : result.singular_poses) {
    singular << format_number(p.t);
    for (int k = 0; k < 3; ++k) singular << ',' << format_number(p.pose.position(k));
    for (int k = 0; k < 3; ++k) singular << ',' << format_number(rad_to_deg(p.pose.angles(k)));
    singular << ',' << (p.kind == SingularPose::Kind::kSample ? "sample" : "det_j_sign_change");
    singular << ',' << format_number(p.singularity_margin) << ',' << format_number(p.det_j_before)
             << ',' << format_number(p.det_j_after) << '\n';
  }
  return singular.str();
}

std::string trajectory_summary_text(const Machine& machine, const TrajectoryResult& result,
                                    const TrajectorySummary& summary) {
  const int na = machine.num_actuators();
  // Engineering units on the terminal: prismatic coordinates in mm, revolute ones in degrees.
  auto q_scale = [&](int i) { return machine.revolute_actuator(i) ? kRadToDeg : 1e3; };
  auto q_unit = [&](int i) { return machine.revolute_actuator(i) ? "deg" : "mm"; };
  std::string text = fmt::format(
      "trajectory: {} samples, t {} .. {} s, {} reachable, min singularity_margin {:.4g}\n",
      summary.samples, format_number(result.samples.front().t),
      format_number(result.samples.back().t), summary.reachable, summary.singularity_margin_min);
  if (summary.reachable < summary.samples) {
    text += fmt::format(
        "  WARNING: {} of {} samples are not reachable (actuator ranges, joint limits or leg "
        "interference): the machine cannot follow this path\n",
        summary.samples - summary.reachable, summary.samples);
  }
  if (!result.samples.empty() && summary.singularity_margin_min < kNearSingularMargin) {
    const TrajectorySample& s = result.samples[summary.singularity_margin_min_sample];
    int fastest = 0;
    for (int i = 1; i < na && i < s.q_dot.size(); ++i)
      if (std::abs(s.q_dot(i) * q_scale(i)) > std::abs(s.q_dot(fastest) * q_scale(fastest)))
        fastest = i;
    text += fmt::format(
        "  WARNING: near a singular pose at t = {} s (x,y,z = {:.6g},{:.6g},{:.6g} m, rx,ry,rz = "
        "{:.6g},{:.6g},{:.6g} deg): singularity_margin {:.3g} < {:g}; the drive rates grow as "
        "1/margin there (fastest: q_{} at {:.4g} {}/s)\n",
        format_number(s.t), s.pose.position(0), s.pose.position(1), s.pose.position(2),
        rad_to_deg(s.pose.angles(0)), rad_to_deg(s.pose.angles(1)), rad_to_deg(s.pose.angles(2)),
        s.metrics.singularity_margin, kNearSingularMargin, fastest + 1,
        s.q_dot.size() > fastest ? std::abs(s.q_dot(fastest)) * q_scale(fastest) : 0.0,
        q_unit(fastest));
  }
  if (machine.checks_leg_interference() && !result.samples.empty()) {
    const TrajectorySample& closest = result.samples[summary.clearance_min_sample];
    text += fmt::format(
        "  legs: min clearance {:.4g} mm (legs {}) at t = {} s\n", summary.clearance_min * 1e3,
        clearance_pair_text(closest.metrics.clearance_first, closest.metrics.clearance_second),
        format_number(closest.t));
    if (summary.first_intersecting) {
      const TrajectorySample& first = result.samples[*summary.first_intersecting];
      text += fmt::format(
          "  WARNING: legs {} intersect first at sample {} (t = {} s, x {:.4g}, y {:.4g}, z {:.4g} "
          "m)\n",
          clearance_pair_text(first.metrics.clearance_first, first.metrics.clearance_second),
          *summary.first_intersecting, format_number(first.t), first.pose.position.x(),
          first.pose.position.y(), first.pose.position.z());
    }
  }
  for (int i = 0; i < na; ++i) {
    text += fmt::format("  q_{}: {:.6g} .. {:.6g} {}, max |q_dot| {:.4g} {}/s\n", i + 1,
                        summary.q_min(i) * q_scale(i), summary.q_max(i) * q_scale(i), q_unit(i),
                        summary.q_dot_max(i) * q_scale(i), q_unit(i));
  }
  if (machine.any_revolute_actuator() && !machine.revolute_actuators() &&
      summary.q_dot_mismatch.size() == na) {
    double linear = 0.0, rotary = 0.0;
    for (int i = 0; i < na; ++i)
      (machine.revolute_actuator(i) ? rotary : linear) =
          std::max(machine.revolute_actuator(i) ? rotary : linear, summary.q_dot_mismatch(i));
    text += fmt::format(
        "  max |q_dot - q_dot_fd| {:.3g} mm/s (linear axes), {:.3g} deg/s (rotary axes) (interior "
        "samples)\n",
        linear * 1e3, rotary * kRadToDeg);
  } else {
    text += fmt::format("  max |q_dot - q_dot_fd| {:.3g} {}/s (interior samples)\n",
                        summary.q_dot_mismatch_max * q_scale(0), q_unit(0));
  }
  text += fmt::format("  TCP: max speed {:.4g} m/s, max acceleration {:.4g} m/s^2 ({:.3g} g)\n",
                      summary.speed_max, summary.acceleration_max,
                      summary.acceleration_max / kStandardGravity);
  auto force_unit = [&](int i) { return machine.revolute_actuator(i) ? "N*m" : "N"; };
  // The force lines when there are forces: a wrench or masses.
  const bool forces = summary.dynamics || (summary.tau_max.size() == na && summary.tau_max.any());
  for (int i = 0; i < na && forces; ++i) {
    std::string line = fmt::format("  tau_{}: max |tau| {:.5g} {} under the wrench", i + 1,
                                   summary.tau_max(i), force_unit(i));
    if (summary.dynamics) {
      line += fmt::format(
          "; with gravity and inertia: peak {:.5g} {}, RMS {:.5g} {}, peak power {:.4g} W",
          summary.tau_dyn_max(i), force_unit(i), summary.tau_dyn_rms(i), force_unit(i),
          summary.power_max(i));
    }
    text += line + '\n';
  }
  if (!summary.dynamics) {
    text += "  no masses in the machine file: tau_dyn (gravity and inertia) not computed\n";
  }
  text += fmt::format("  singular poses: {}\n", result.singular_poses.size());
  for (const SingularPose& p : result.singular_poses) {
    text += fmt::format(
        "    t = {:.12g} s ({}): x,y,z = {:.6g},{:.6g},{:.6g} m, rx,ry,rz = {:.6g},{:.6g},{:.6g} "
        "deg, det_j {:.3g} -> {:.3g}\n",
        p.t, p.kind == SingularPose::Kind::kSample ? "singular sample" : "det_j changes sign",
        p.pose.position(0), p.pose.position(1), p.pose.position(2), rad_to_deg(p.pose.angles(0)),
        rad_to_deg(p.pose.angles(1)), rad_to_deg(p.pose.angles(2)), p.det_j_before, p.det_j_after);
  }
  return text;
}

DriveDuty actuator_duty(const TrajectorySummary& summary, int i) {
  DriveDuty duty;
  duty.peak_force = summary.dynamics ? summary.tau_dyn_max(i) : summary.tau_max(i);
  duty.rms_force = summary.dynamics ? summary.tau_dyn_rms(i) : summary.tau_max(i);
  duty.speed = summary.q_dot_max(i);
  duty.stroke = summary.q_max(i) - summary.q_min(i);
  return duty;
}

std::string drive_check_text(const ActuatorEntry& entry, const TrajectorySummary& summary,
                             bool& carries) {
  const int na = static_cast<int>(summary.q_dot_max.size());
  std::string text = fmt::format(
      "drive {}: rated {:.6g} N continuous, {:.6g} N peak{}, {:.4g} m/s, stroke {:.4g} m{}\n",
      entry.name, entry.max_force, entry.peak_force.value_or(entry.max_force),
      entry.peak_force ? "" : " (no peak rating: the continuous one)", entry.max_speed,
      entry.stroke,
      summary.dynamics ? ""
                       : "; no masses: forces under the wrench alone (no gravity, no inertia)");
  carries = true;
  auto verdict = [](bool ok) { return ok ? "ok" : "EXCEEDED"; };
  for (int i = 0; i < na; ++i) {
    const DriveDuty duty = actuator_duty(summary, i);
    const DriveCheck check = check_drive(entry, duty);
    carries = carries && check.carries();
    text += fmt::format(
        "  actuator {}: peak {:.5g} N {}, RMS {:.5g} N {}, speed {:.4g} m/s {}, stroke {:.4g} m "
        "{}\n",
        i + 1, duty.peak_force, verdict(check.peak_ok), duty.rms_force, verdict(check.rms_ok),
        duty.speed, verdict(check.speed_ok), duty.stroke, verdict(check.stroke_ok));
  }
  text += carries ? fmt::format("  {} carries every actuator along this path\n", entry.name)
                  : fmt::format("  WARNING: {} does NOT carry this path (EXCEEDED above)\n",
                                entry.name);
  return text;
}

}  // namespace pkmopt

namespace pkmopt {

std::string assembly_modes_text(const TrajectoryResult& result, const TrajectoryModes& modes,
                                double warn_below) {
  std::size_t nearest = 0, near_count = 0, not_found = 0, failed = 0;
  std::size_t first_near = 0, first_not_found = 0, first_failed = 0;
  std::size_t fewest = SIZE_MAX, most = 0;
  for (std::size_t k = 0; k < modes.samples.size(); ++k) {
    const AssemblyModeSample& m = modes.samples[k];
    if (m.nearest_other < modes.samples[nearest].nearest_other) nearest = k;
    fewest = std::min(fewest, m.real_modes);
    most = std::max(most, m.real_modes);
    if (m.nearest_other < warn_below && near_count++ == 0) first_near = k;
    if (!m.tracked_found && !result.samples[k].metrics.singular && not_found++ == 0)
      first_not_found = k;
    if (m.failed_paths > 0 && failed++ == 0) first_failed = k;
  }
  if (modes.samples.empty()) return "";
  auto t = [&](std::size_t k) { return format_number(result.samples[k].t); };
  std::string text = fmt::format(
      "  assembly modes: {} .. {} real; nearest other mode {:.4g} m, at t = {} s (pose distance "
      "sqrt(|dp|^2 + (rho theta)^2), rho = {:.4g} m)\n",
      fewest, most, modes.samples[nearest].nearest_other, t(nearest), modes.distance_length);
  if (near_count > 0)
    text += fmt::format(
        "  WARNING: another assembly mode comes within {:.4g} m of the tracked pose (below "
        "{:.4g} m) at {} samples, first at t = {} s: the path runs near a parallel singularity, "
        "where a disturbance could carry the machine into that mode\n",
        modes.samples[nearest].nearest_other, warn_below, near_count, t(first_near));
  if (not_found > 0)
    text += fmt::format(
        "  WARNING: the tracked pose was not among the forward-kinematics solutions at {} samples, "
        "first at t = {} s (mode_distance 0 there)\n",
        not_found, t(first_not_found));
  if (failed > 0)
    text += fmt::format(
        "  WARNING: forward-kinematics paths failed at {} samples, first at t = {} s: other modes "
        "may be missing there (failed_paths)\n",
        failed, t(first_failed));
  return text;
}

}  // namespace pkmopt
