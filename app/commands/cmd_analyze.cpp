// pkmopt analyze MACHINE.yaml --poses POSES.csv [--wrench fx,fy,fz,mx,my,mz] [--compliance]
//                [--mode-shapes] [--out FILE.csv]
#include <fmt/format.h>

#include <algorithm>
#include <cstdio>
#include <iostream>
#include <memory>

#include "app/cli_args.hpp"
#include "app/commands.hpp"
#include "io/analyze_csv.hpp"
#include "io/input_error.hpp"
#include "io/machine_file.hpp"
#include "io/output_file.hpp"
#include "io/pose_csv.hpp"
#include "models/pose_analysis.hpp"

namespace pkmopt::cli {
namespace {

struct AnalyzeOptions {
  std::string machine_file;
  std::string poses_file;
  std::string wrench;
  std::string out_file;
  bool compliance = false;
  bool modes = false;
};

// Every pose unreachable is almost always a wrong pose file (millimetres for metres, another
// machine's frame): said on stderr; the output is still written (exit 0).
void warn_if_nothing_reachable(const PoseTable& poses, const std::vector<PoseMetrics>& metrics,
                               const std::string& poses_file) {
  if (metrics.empty()) return;
  for (const PoseMetrics& m : metrics)
    if (m.reachable) return;
  double farthest = 0.0;
  for (const Pose& p : poses.poses) farthest = std::max(farthest, p.position.cwiseAbs().maxCoeff());
  fmt::print(stderr,
             "pkmopt: warning: analyze: none of the {} poses of '{}' is reachable (every row has "
             "reachable = 0){}\n",
             metrics.size(), poses_file,
             farthest > 10.0
                 ? fmt::format("; a coordinate reaches {:.4g} m: pose positions are in metres, "
                               "not millimetres",
                               farthest)
                 : std::string("; check that the positions are in metres in the base frame and "
                               "the angles in degrees"));
}

void run_analyze(const AnalyzeOptions& opt) {
  // Read and validate every input before anything is written.
  const std::unique_ptr<Machine> machine = load_machine_file(opt.machine_file);
  if (opt.modes && machine->natural_frequency_count() == 0) {
    throw InputError(
        fmt::format("{}: --mode-shapes needs a mass model: the machine file has no "
                    "'masses' (docs/dynamics.md)",
                    opt.machine_file));
  }
  Wrench wrench = Wrench::Zero();
  if (!opt.wrench.empty()) {
    const auto w = parse_wrench_option(opt.wrench);
    for (int i = 0; i < 6; ++i) wrench(i) = w[static_cast<std::size_t>(i)];
  }
  const PoseTable poses = read_pose_csv(opt.poses_file);
  std::vector<PoseCompliance> matrices;
  const std::vector<PoseMetrics> metrics =
      analyze_poses(*machine, poses.poses, wrench, opt.compliance ? &matrices : nullptr);
  std::vector<PoseModes> modes;
  if (opt.modes) modes = mode_shapes_of_poses(*machine, poses.poses);
  const std::string csv = analyze_csv(
      *machine, poses, metrics,
      {.compliance = opt.compliance ? &matrices : nullptr, .modes = opt.modes ? &modes : nullptr});
  if (opt.out_file.empty()) {
    std::cout << csv;
    std::cout.flush();
  } else {
    write_file_atomically(opt.out_file, csv);
  }
  warn_if_nothing_reachable(poses, metrics, opt.poses_file);
}

}  // namespace

void add_analyze_command(CLI::App& app) {
  auto opt = std::make_shared<AnalyzeOptions>();
  CLI::App* cmd =
      app.add_subcommand("analyze",
                         "Evaluate a machine at every pose of a CSV file: reachability, actuator "
                         "coordinates and forces, stiffness, singularity margin, accuracy");
  cmd->add_option("machine", opt->machine_file, "Machine file (YAML)")->required();
  cmd->add_option("--poses", opt->poses_file,
                  "Pose CSV with columns x,y,z (m) and optionally rx,ry,rz (deg)")
      ->required();
  cmd->add_option("--wrench", opt->wrench,
                  "External wrench at the TCP, base axes: fx,fy,fz,mx,my,mz (N, N*m); default 0");
  cmd->add_option("--out", opt->out_file, "Output CSV (default: standard output)");
  cmd->add_flag("--compliance", opt->compliance,
                "Add the 6x6 compliance matrix at the TCP as columns C_11..C_66 (twist per wrench, "
                "base axes)");
  cmd->add_flag("--mode-shapes", opt->modes,
                "With a mass model: add each natural mode's shape after the frequencies, "
                "mode_K_dx..mode_K_drz (TCP displacement m, platform rotation rad, base axes; "
                "mass-normalised), a hybrid machine's serial axes first as mode_K_axis_J (m)");
  cmd->callback([opt] { run_analyze(*opt); });
}

}  // namespace pkmopt::cli
