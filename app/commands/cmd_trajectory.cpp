// pkmopt trajectory MACHINE.yaml (--path PATH.csv | --helix [--helix-* ...])
//   [--t-start S] [--t-end S] [--samples N | --dt S] [--jacobian] [--out FILE.csv]
//   [--singular-out FILE.csv] [--wrench fx,fy,fz,mx,my,mz] [--catalog CATALOG.yaml --drive NAME]
//   [--assembly-modes [--mode-warning M]]
// See docs/trajectory.md for the options, the helix formula and every output column.
#include <fmt/format.h>

#include <cmath>
#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>

#include "app/cli_args.hpp"
#include "app/commands.hpp"
#include "io/design/actuator_catalog_file.hpp"
#include "io/format/csv.hpp"
#include "io/format/input_error.hpp"
#include "io/format/number_policy.hpp"
#include "io/format/output_file.hpp"
#include "io/machine/machine_file.hpp"
#include "io/results/trajectory_files.hpp"
#include "models/motion/trajectory.hpp"
#include "models/motion/trajectory_modes.hpp"

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
  std::string wrench;
  std::string catalog_file;
  std::string drive;
  bool assembly_modes = false;
  std::optional<double> mode_warning;  // m
};

Eigen::Vector3d vector3_option(std::string_view option, const std::string& text,
                               double max_magnitude = 1e15) {
  const auto v = parse_number_list(option, text, 3, max_magnitude);
  return {v[0], v[1], v[2]};
}

HelixParameters read_helix(const TrajectoryCommandOptions& opt) {
  HelixParameters h;
  if (!opt.helix_centre.empty())
    h.centre = vector3_option("--helix-centre", opt.helix_centre, kMaxInputLength);
  if (!opt.helix_radius.empty()) {
    const auto r = parse_number_list("--helix-radius", opt.helix_radius, 2, kMaxInputLength);
    h.radius_start = r[0];
    h.radius_growth = r[1];
  }
  if (!opt.helix_height.empty()) {
    const auto z = parse_number_list("--helix-height", opt.helix_height, 2, kMaxInputLength);
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

// The path options fit together: --path or --helix, helix and sampling options only with --helix.
void check_path_options(const TrajectoryCommandOptions& opt) {
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
  if (opt.mode_warning) {
    if (!opt.assembly_modes)
      throw InputError("--mode-warning: expected only together with --assembly-modes");
    if (!(std::isfinite(*opt.mode_warning) && *opt.mode_warning >= 0.0 &&
          *opt.mode_warning <= kMaxInputLength))
      bad_option("--mode-warning", "a pose distance in m, 0 .. 1000", *opt.mode_warning);
  }
}

// The assembly modes at every sample (--assembly-modes), and the summary lines about them.
std::optional<TrajectoryModes> assembly_modes_of(const TrajectoryCommandOptions& opt,
                                                 const Machine& machine,
                                                 const TrajectoryResult& result,
                                                 std::string& summary) {
  if (!opt.assembly_modes) return std::nullopt;
  const auto solver = machine.all_forward_kinematics_solver();
  if (!solver)
    throw InputError(
        fmt::format("--assembly-modes: expected a machine whose forward kinematics "
                    "can be solved completely (a hexapod), found {}: {}",
                    opt.machine_file, solver.reason()));
  TrajectoryModes modes = trajectory_assembly_modes(*solver.get(), result);
  // By default a tenth of rho: the platform's joints within a tenth of its radius of another
  // mode.
  summary +=
      assembly_modes_text(result, modes, opt.mode_warning.value_or(0.1 * modes.distance_length));
  return modes;
}

// The helix of the --helix-* options and its sample times (--samples or --dt, within the limits;
// the helix must stay within +-1000 m).
std::unique_ptr<TcpPath> helix_path(const TrajectoryCommandOptions& opt,
                                    std::vector<double>& times) {
  std::unique_ptr<TcpPath> path;
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
      bad_option("--dt", fmt::format("a time step in s > 0 giving at most {} samples", kMaxSamples),
                 *opt.dt);
    }
    if (*opt.dt > span) {
      bad_option("--dt",
                 fmt::format("a time step of at most the path's duration ({} s, from "
                             "--t-start to --t-end)",
                             format_number(span)),
                 *opt.dt);
    }
    // The step is kept; the last sample is t_end (a shorter last step if dt does not divide).
    times = stepped_times(h.t_start, h.t_end, *opt.dt);
  } else {
    times = uniform_times(h.t_start, h.t_end, count);
  }
  path = std::make_unique<HelixPath>(h);
  // Each option is a length within +-1000 m; the helix they make must stay there too.
  for (const double t : times)
    if (const Eigen::Vector3d p = path->at(t).pose.position;
        !(p.cwiseAbs().maxCoeff() <= kMaxInputLength))
      throw InputError(
          fmt::format("--helix-*: expected a helix within +-{:g} m, found the TCP at ({}, {}, "
                      "{}) m at t = {} "
                      "s (--helix-centre, --helix-radius, --helix-height, --t-start, --t-end)",
                      kMaxInputLength, format_number(p.x()), format_number(p.y()),
                      format_number(p.z()), format_number(t)));
  return path;
}

// The drive of --catalog/--drive to check the forces against (null without); `catalog` holds it.
const ActuatorEntry* read_drive(const TrajectoryCommandOptions& opt, const Machine& machine,
                                std::optional<ActuatorCatalog>& catalog) {
  const ActuatorEntry* drive = nullptr;
  if (!opt.catalog_file.empty()) {
    if (machine.any_revolute_actuator()) {
      throw InputError(fmt::format(
          "--catalog: expected a machine with linear actuators (the catalog holds linear drives), "
          "found {} with revolute ones",
          opt.machine_file));
    }
    catalog = load_actuator_catalog(opt.catalog_file);
    drive = find_actuator(*catalog, opt.drive);
    if (drive == nullptr) {
      std::string names;
      for (const ActuatorEntry& e : catalog->entries) names += (names.empty() ? "" : ", ") + e.name;
      throw InputError(fmt::format("--drive: expected an entry of {} ({}), found '{}'",
                                   opt.catalog_file, names, opt.drive));
    }
  }

  return drive;
}

// The table (to --out or stdout), the singular poses (--singular-out) and the summary (stdout
// when the table goes to a file, else stderr).
void write_trajectory_outputs(const TrajectoryCommandOptions& opt, const std::string& table,
                              const TrajectoryResult& result, const std::string& summary) {
  // Both files are written to temporaries first and moved into place together: when the
  // second cannot be, the first is removed again (no output is left by a failed command).
  std::optional<AtomicOutputFile> out, singular;
  if (!opt.out_file.empty()) {
    out.emplace(opt.out_file);
    out->stream() << table;
  }
  if (!opt.singular_out_file.empty()) {
    singular.emplace(opt.singular_out_file);
    singular->stream() << singular_poses_csv(result);
  }
  if (out) out->commit();
  if (singular) {
    try {
      singular->commit();
    } catch (...) {
      if (out) out->revert();
      throw;
    }
  }
  if (opt.out_file.empty()) {
    std::cout << table;
    std::cout.flush();
    // The table did not reach standard output (closed, a full disk): no summary after it, the
    // one error line is main's.
    if (!std::cout) return;
  }
  if (opt.out_file.empty()) {
    std::cerr << summary;
  } else {
    std::cout << summary;
    std::cout.flush();
  }
}

void run_trajectory(const TrajectoryCommandOptions& opt) {
  // Read and validate every input before anything is written.
  check_path_options(opt);
  std::unique_ptr<TcpPath> path;
  std::vector<double> times;
  if (opt.helix) {
    path = helix_path(opt, times);
  } else {
    auto sampled = std::make_unique<SampledPath>(read_path_csv(opt.path_file));
    times = sampled->times();
    path = std::move(sampled);
  }
  Wrench wrench = Wrench::Zero();
  if (!opt.wrench.empty()) {
    const auto w = parse_wrench_option(opt.wrench);
    for (int i = 0; i < 6; ++i) wrench(i) = w[static_cast<std::size_t>(i)];
  }
  if (opt.catalog_file.empty() != opt.drive.empty()) {
    throw InputError(
        opt.drive.empty()
            ? "--catalog: expected --drive NAME with it (the entry to check), found none"
            : "--drive: expected --catalog CATALOG.yaml with it, found none");
  }
  const std::unique_ptr<Machine> machine = load_machine_file(opt.machine_file);
  std::optional<ActuatorCatalog> catalog;
  const ActuatorEntry* drive = read_drive(opt, *machine, catalog);
  const TrajectoryResult result = evaluate_trajectory(*machine, *path, times, wrench);

  std::string modes_summary;
  const std::optional<TrajectoryModes> modes =
      assembly_modes_of(opt, *machine, result, modes_summary);
  const std::string table =
      trajectory_csv(*machine, result, opt.jacobian, modes ? &*modes : nullptr);
  // The summary: ranges along the path, the agreement of q_dot with the IK differences, and the
  // singular poses. On stdout when the table goes to a file, else on stderr.
  const TrajectorySummary reduced = summarize_trajectory(result, machine->num_actuators());
  std::string summary = trajectory_summary_text(*machine, result, reduced) + modes_summary;
  if (drive != nullptr) {
    bool carries = false;
    summary += drive_check_text(*drive, reduced, carries);
  }

  write_trajectory_outputs(opt, table, result, summary);
}

}  // namespace

void add_trajectory_command(CLI::App& app) {
  auto opt = std::make_shared<TrajectoryCommandOptions>();
  CLI::App* cmd = app.add_subcommand(
      "trajectory",
      "Follow a TCP path (CSV samples or the built-in test helix): actuator coordinates and rates "
      "from the inverse Jacobian, checked against differences of the IK, the singular poses on "
      "the path and, with masses, the actuator forces of the inverse dynamics");
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
  cmd->add_option("--wrench", opt->wrench,
                  "External wrench on the tool at every sample, TCP, base axes: fx,fy,fz,mx,my,mz "
                  "(N, N*m); default 0");
  cmd->add_option("--catalog", opt->catalog_file,
                  "Actuator catalog (YAML) holding the drive to check against the path's forces");
  cmd->add_option("--drive", opt->drive,
                  "Catalog entry to check: peak and RMS force, speed and stroke of every actuator");
  cmd->add_flag("--assembly-modes", opt->assembly_modes,
                "At every sample, solve the forward kinematics completely (hexapod) and give the "
                "pose distance to the nearest other assembly mode (column mode_distance)");
  cmd->add_option("--mode-warning", opt->mode_warning,
                  "Warn where another assembly mode comes nearer than this pose distance (m); "
                  "default a tenth of the platform's joint radius");
  cmd->callback([opt] { run_trajectory(*opt); });
}

}  // namespace pkmopt::cli
