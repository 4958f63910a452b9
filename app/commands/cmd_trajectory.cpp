// pkmopt trajectory MACHINE.yaml (--path PATH.csv | --helix [--helix-* ...])
//   [--t-start S] [--t-end S] [--samples N | --dt S] [--jacobian] [--out FILE.csv]
//   [--singular-out FILE.csv]
// See docs/trajectory.md for the options, the helix formula and every output column.
#include <fmt/format.h>

#include <cmath>
#include <iostream>
#include <memory>
#include <optional>
#include <sstream>
#include <stdexcept>

#include "app/cli_args.hpp"
#include "app/commands.hpp"
#include "io/csv.hpp"
#include "io/input_error.hpp"
#include "io/machine_file.hpp"
#include "io/output_file.hpp"
#include "io/pose_csv.hpp"
#include "models/trajectory.hpp"

namespace pkmopt::cli {
namespace {

constexpr int kMaxSamples = 10'000'000;

struct TrajectoryCommandOptions {
  std::string machine_file;
  std::string path_file;
  bool helix = false;
  std::string helix_centre;       // m
  std::string helix_radius;       // r0,r1 (m)
  std::string helix_height;       // z0,z1 (m)
  std::string helix_angles;       // ax,ay,az (deg)
  std::string helix_orientation;  // ox,oy,oz (deg)
  std::optional<double> helix_frequency;
  std::optional<double> t_start;
  std::optional<double> t_end;
  std::optional<int> samples;
  std::optional<double> dt;
  bool jacobian = false;
  std::string out_file;
  std::string singular_out_file;
};

Eigen::Vector3d vector3_option(std::string_view option, const std::string& text) {
  const auto v = parse_number_list(option, text, 3);
  return {v[0], v[1], v[2]};
}

// The path from a CSV file: t (s), x, y, z (m), optional rx, ry, rz (deg).
SampledPath read_path_file(const std::string& file) {
  PoseTable path = read_timed_pose_csv(file, 2);
  return SampledPath(std::move(path.times), std::move(path.poses));
}

HelixParameters read_helix(const TrajectoryCommandOptions& opt) {
  HelixParameters h;
  if (!opt.helix_centre.empty()) h.centre = vector3_option("--helix-centre", opt.helix_centre);
  if (!opt.helix_radius.empty()) {
    const auto r = parse_number_list("--helix-radius", opt.helix_radius, 2);
    h.radius_start = r[0];
    h.radius_growth = r[1];
  }
  if (!opt.helix_height.empty()) {
    const auto z = parse_number_list("--helix-height", opt.helix_height, 2);
    h.height_start = z[0];
    h.height_growth = z[1];
  }
  if (!opt.helix_angles.empty()) {
    h.angle_amplitudes = deg_to_rad(vector3_option("--helix-angles", opt.helix_angles));
  }
  if (!opt.helix_orientation.empty()) {
    h.nominal_angles = deg_to_rad(vector3_option("--helix-orientation", opt.helix_orientation));
  }
  if (opt.helix_frequency) {
    if (!(std::isfinite(*opt.helix_frequency) && *opt.helix_frequency > 0.0)) {
      bad_option("--helix-frequency", "an angular frequency in rad/s > 0", *opt.helix_frequency);
    }
    h.angular_frequency = *opt.helix_frequency;
  }
  return h;
}

std::string joined(const Eigen::VectorXd& v, double scale) {
  std::string s;
  for (Eigen::Index i = 0; i < v.size(); ++i) s += ',' + format_number(v(i) * scale);
  return s;
}

void run_trajectory(const TrajectoryCommandOptions& opt) {
  // Read and validate every input before anything is written.
  if (opt.helix == !opt.path_file.empty()) {
    throw InputError(opt.helix ? "--path and --helix: expected one of them, found both"
                               : "expected --path PATH.csv or --helix, found neither");
  }
  const bool helix_option_given = !opt.helix_centre.empty() || !opt.helix_radius.empty() ||
                                  !opt.helix_height.empty() || !opt.helix_angles.empty() ||
                                  !opt.helix_orientation.empty() || opt.helix_frequency;
  if (!opt.helix) {
    if (helix_option_given) {
      throw InputError("--helix-*: expected only together with --helix, found them with --path");
    }
    if (opt.samples || opt.dt || opt.t_start || opt.t_end) {
      throw InputError(
          "--samples/--dt/--t-start/--t-end: expected only with --helix (a --path is evaluated "
          "at its own samples), found them with --path");
    }
  }
  if (opt.samples && opt.dt) {
    throw InputError("--samples and --dt: expected one of them, found both");
  }
  std::unique_ptr<TcpPath> path;
  std::vector<double> times;
  if (opt.helix) {
    HelixParameters h = read_helix(opt);
    if (opt.t_start) h.t_start = *opt.t_start;
    if (opt.t_end) h.t_end = *opt.t_end;
    if (!std::isfinite(h.t_start)) bad_option("--t-start", "a finite time in s", h.t_start);
    if (!(std::isfinite(h.t_end) && h.t_end > h.t_start)) {
      bad_option("--t-end", fmt::format("a finite time in s > t-start = {}", h.t_start), h.t_end);
    }
    int count = 201;
    if (opt.samples) {
      if (!(*opt.samples >= 2 && *opt.samples <= kMaxSamples)) {
        bad_option("--samples", fmt::format("a sample count 2 <= N <= {}", kMaxSamples),
                   *opt.samples);
      }
      count = *opt.samples;
    }
    if (opt.dt) {
      const double span = h.t_end - h.t_start;
      if (!(std::isfinite(*opt.dt) && *opt.dt > 0.0 && span / *opt.dt < kMaxSamples)) {
        bad_option("--dt",
                   fmt::format("a time step in s > 0 giving at most {} samples", kMaxSamples),
                   *opt.dt);
      }
      // The step is kept; the last sample is t_end (a shorter last step if dt does not divide).
      for (double t = h.t_start; t < h.t_end - 1e-9 * *opt.dt;
           t = h.t_start + static_cast<double>(times.size()) * *opt.dt) {
        times.push_back(t);
      }
      times.push_back(h.t_end);
    } else {
      times = uniform_times(h.t_start, h.t_end, count);
    }
    path = std::make_unique<HelixPath>(h);
  } else {
    auto sampled = std::make_unique<SampledPath>(read_path_file(opt.path_file));
    times = sampled->times();
    path = std::move(sampled);
  }
  const std::unique_ptr<Machine> machine = load_machine_file(opt.machine_file);

  const TrajectoryResult result = evaluate_trajectory(*machine, *path, times);

  const int na = machine->num_actuators();
  const double q_scale = machine->revolute_actuators() ? kRadToDeg : 1.0;
  std::ostringstream out;
  out << "t,x,y,z,rx,ry,rz,vx,vy,vz,wx,wy,wz,reachable,singular";
  for (int j = 1; j <= na; ++j) out << ",q_" << j;
  for (int j = 1; j <= na; ++j) out << ",q_dot_" << j;
  for (int j = 1; j <= na; ++j) out << ",q_dot_fd_" << j;
  out << ",singularity_margin,det_j";
  if (opt.jacobian) {
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
    if (opt.jacobian) {
      for (int r = 0; r < na; ++r) {
        for (int c = 0; c < 6; ++c) {
          line += ',' + format_number(s.jacobian_ok ? s.J(r, c)
                                                    : std::numeric_limits<double>::infinity());
        }
      }
    }
    out << line << '\n';
  }

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

  // The summary: ranges along the path, the agreement of q_dot with the IK differences, and the
  // singular poses. On stdout when the table goes to a file, else on stderr.
  std::ostringstream summary;
  std::size_t reachable = 0;
  double worst_mismatch = 0.0;
  Eigen::VectorXd q_min = Eigen::VectorXd::Constant(na, std::numeric_limits<double>::infinity());
  Eigen::VectorXd q_max = -q_min;
  Eigen::VectorXd q_dot_max = Eigen::VectorXd::Zero(na);
  double margin_min = std::numeric_limits<double>::infinity();
  for (std::size_t k = 0; k < result.samples.size(); ++k) {
    const TrajectorySample& s = result.samples[k];
    const bool interior = k > 0 && k + 1 < result.samples.size();
    if (s.metrics.reachable) ++reachable;
    q_min = q_min.cwiseMin(s.metrics.q);
    q_max = q_max.cwiseMax(s.metrics.q);
    q_dot_max = q_dot_max.cwiseMax(s.q_dot.cwiseAbs());
    margin_min = std::min(margin_min, s.metrics.singularity_margin);
    if (s.jacobian_ok && interior)
      worst_mismatch = std::max(worst_mismatch, (s.q_dot - s.q_dot_fd).cwiseAbs().maxCoeff());
  }
  const char* q_unit = machine->revolute_actuators() ? "deg" : "m";
  summary << fmt::format(
      "trajectory: {} samples, t {} .. {} s, {} reachable, min singularity_margin {:.4g}\n",
      result.samples.size(), format_number(times.front()), format_number(times.back()), reachable,
      margin_min);
  for (int i = 0; i < na; ++i) {
    summary << fmt::format("  q_{}: {:.6g} .. {:.6g} {}, max |q_dot| {:.4g} {}/s\n", i + 1,
                           q_min(i) * q_scale, q_max(i) * q_scale, q_unit, q_dot_max(i) * q_scale,
                           q_unit);
  }
  summary << fmt::format("  max |q_dot - q_dot_fd| {:.3g} {}/s (interior samples)\n",
                         worst_mismatch * q_scale, q_unit);
  summary << fmt::format("  singular poses: {}\n", result.singular_poses.size());
  for (const SingularPose& p : result.singular_poses) {
    summary << fmt::format(
        "    t = {:.12g} s ({}): x,y,z = {:.6g},{:.6g},{:.6g} m, rx,ry,rz = {:.6g},{:.6g},{:.6g} "
        "deg, det_j {:.3g} -> {:.3g}\n",
        p.t, p.kind == SingularPose::Kind::kSample ? "singular sample" : "det_j changes sign",
        p.pose.position(0), p.pose.position(1), p.pose.position(2), rad_to_deg(p.pose.angles(0)),
        rad_to_deg(p.pose.angles(1)), rad_to_deg(p.pose.angles(2)), p.det_j_before, p.det_j_after);
  }

  if (opt.out_file.empty()) {
    std::cout << out.str();
    std::cout.flush();
  } else {
    write_file_atomically(opt.out_file, out.str());
  }
  if (!opt.singular_out_file.empty()) write_file_atomically(opt.singular_out_file, singular.str());
  if (opt.out_file.empty()) {
    std::cerr << summary.str();
  } else {
    std::cout << summary.str();
    std::cout.flush();
  }
}

}  // namespace

void add_trajectory_command(CLI::App& app) {
  auto opt = std::make_shared<TrajectoryCommandOptions>();
  CLI::App* cmd = app.add_subcommand(
      "trajectory",
      "Follow a TCP path (CSV samples or the built-in test helix): actuator coordinates and rates "
      "from the inverse Jacobian, checked against differences of the IK, and the singular poses "
      "on the path");
  cmd->add_option("machine", opt->machine_file, "Machine file (YAML)")->required();
  cmd->add_option("--path", opt->path_file,
                  "Path CSV with columns t (s), x,y,z (m) and optionally rx,ry,rz (deg)");
  cmd->add_flag("--helix", opt->helix, "Follow the built-in test helix (docs/trajectory.md)");
  cmd->add_option("--helix-centre", opt->helix_centre, "Helix centre cx,cy,cz (m); default 0,0,0");
  cmd->add_option("--helix-radius", opt->helix_radius,
                  "r0,r1 (m): amp = r0 + r1 phi/(2 pi); default 0.01,0.02");
  cmd->add_option("--helix-height", opt->helix_height,
                  "z0,z1 (m): z = cz + z0 + z1 phi^2/(4 pi^2); default 0.01,0.01");
  cmd->add_option(
      "--helix-angles", opt->helix_angles,
      "ax,ay,az (deg): rx = ax sin phi, ry = ay cos phi, rz = az sin 2phi; default 0,0,0");
  cmd->add_option("--helix-orientation", opt->helix_orientation,
                  "Nominal angles added to the harmonic ones, rx,ry,rz (deg); default 0,0,0");
  cmd->add_option("--helix-frequency", opt->helix_frequency,
                  "w (rad/s): phase phi = w t; default 1");
  cmd->add_option("--t-start", opt->t_start, "Helix start time (s); default 0");
  cmd->add_option("--t-end", opt->t_end, "Helix end time (s); default 2 pi");
  cmd->add_option("--samples", opt->samples, "Helix samples, ends included; default 201");
  cmd->add_option("--dt", opt->dt, "Helix time step (s), instead of --samples");
  cmd->add_flag("--jacobian", opt->jacobian, "Append the inverse Jacobian J_r_c (SI units)");
  cmd->add_option("--out", opt->out_file, "Output CSV (default: standard output)");
  cmd->add_option("--singular-out", opt->singular_out_file,
                  "CSV of the singular poses found on the path");
  cmd->callback([opt] { run_trajectory(*opt); });
}

}  // namespace pkmopt::cli
