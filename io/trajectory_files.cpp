#include "io/trajectory_files.hpp"

#include <fmt/format.h>

#include <limits>
#include <sstream>
#include <utility>

#include "io/csv.hpp"
#include "io/pose_csv.hpp"

namespace pkmopt {
namespace {

std::string joined(const Eigen::VectorXd& v, double scale) {
  std::string s;
  for (Eigen::Index i = 0; i < v.size(); ++i) s += ',' + format_number(v(i) * scale);
  return s;
}

// Actuator coordinates in the files: metres, or degrees for revolute drives.
double actuator_scale(const Machine& machine) {
  return machine.revolute_actuators() ? kRadToDeg : 1.0;
}

}  // namespace

SampledPath read_path_csv(const std::string& path) {
  PoseTable table = read_timed_pose_csv(path, 2);
  return SampledPath(std::move(table.times), std::move(table.poses));
}

std::string trajectory_csv(const Machine& machine, const TrajectoryResult& result, bool jacobian) {
  const int na = machine.num_actuators();
  const double q_scale = actuator_scale(machine);
  std::ostringstream out;
  out << "t,x,y,z,rx,ry,rz,vx,vy,vz,wx,wy,wz,reachable,singular";
  for (int j = 1; j <= na; ++j) out << ",q_" << j;
  for (int j = 1; j <= na; ++j) out << ",q_dot_" << j;
  for (int j = 1; j <= na; ++j) out << ",q_dot_fd_" << j;
  out << ",singularity_margin,det_j";
  if (jacobian) {
    for (int r = 1; r <= na; ++r) {
      for (int c = 1; c <= 6; ++c) out << ",J_" << r << '_' << c;
    }
  }
  out << '\n';
  for (const TrajectorySample& s : result.samples) {
    std::string line = format_number(s.t);
    for (int k = 0; k < 3; ++k) line += ',' + format_number(s.pose.position(k));
    for (int k = 0; k < 3; ++k) line += ',' + format_number(rad_to_deg(s.pose.angles(k)));
    for (int k = 0; k < 3; ++k) line += ',' + format_number(s.twist(k));
    for (int k = 3; k < 6; ++k) line += ',' + format_number(rad_to_deg(s.twist(k)));
    line += s.metrics.reachable ? ",1" : ",0";
    line += s.metrics.singular ? ",1" : ",0";
    line += joined(s.metrics.q, q_scale);
    line += joined(s.q_dot, q_scale);
    line += joined(s.q_dot_fd, q_scale);
    line += ',' + format_number(s.metrics.singularity_margin);
    line += ',' + format_number(s.metrics.det_j);
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
  const double q_scale = actuator_scale(machine);
  const char* q_unit = machine.revolute_actuators() ? "deg" : "m";
  std::string text = fmt::format(
      "trajectory: {} samples, t {} .. {} s, {} reachable, min singularity_margin {:.4g}\n",
      summary.samples, format_number(result.samples.front().t),
      format_number(result.samples.back().t), summary.reachable, summary.singularity_margin_min);
  for (int i = 0; i < na; ++i) {
    text += fmt::format("  q_{}: {:.6g} .. {:.6g} {}, max |q_dot| {:.4g} {}/s\n", i + 1,
                        summary.q_min(i) * q_scale, summary.q_max(i) * q_scale, q_unit,
                        summary.q_dot_max(i) * q_scale, q_unit);
  }
  text += fmt::format("  max |q_dot - q_dot_fd| {:.3g} {}/s (interior samples)\n",
                      summary.q_dot_mismatch_max * q_scale, q_unit);
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

}  // namespace pkmopt
