// pkmopt analyze MACHINE.yaml --poses POSES.csv [--wrench fx,fy,fz,mx,my,mz] [--compliance]
//                [--mode-shapes] [--out FILE.csv]
#include <fmt/format.h>

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <iostream>
#include <memory>

#include "app/cli_args.hpp"
#include "app/commands.hpp"
#include "io/format/input_error.hpp"
#include "io/format/output_file.hpp"
#include "io/format/pose_csv.hpp"
#include "io/machine/machine_file.hpp"
#include "io/results/analyze_csv.hpp"
#include "models/core/capabilities.hpp"
#include "models/core/pose_analysis.hpp"
#include "studies/distribute.hpp"

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
void warn_if_nothing_reachable(const PoseTable& poses, bool any_reachable,
                               const std::string& poses_file) {
  if (poses.poses.empty() || any_reachable) return;
  double farthest = 0.0;
  for (const Pose& p : poses.poses) farthest = std::max(farthest, p.position.cwiseAbs().maxCoeff());
  fmt::print(stderr,
             "pkmopt: warning: analyze: none of the {} poses of '{}' is reachable (every row has "
             "reachable = 0){}\n",
             poses.poses.size(), poses_file,
             farthest > 10.0
                 ? fmt::format("; a coordinate reaches {:.4g} m: pose positions are in metres, "
                               "not millimetres",
                               farthest)
                 : std::string("; check that the positions are in metres in the base frame and "
                               "the angles in degrees"));
}

void write_analyze_output(const AnalyzeOptions& opt, const std::string& csv) {
  if (opt.out_file.empty()) {
    std::cout << csv;
    std::cout.flush();
  } else {
    write_file_atomically(opt.out_file, csv);
  }
}

// Under mpirun: every rank analyzes the poses it owns (pose i: rank i % N) and formats their
// rows; rank 0 gathers them in pose order and writes the file the run on one process writes.
void analyze_shared(const AnalyzeOptions& opt, const Machine& machine, const PoseTable& poses,
                    const Wrench& wrench, const ProcessShare& share) {
  std::vector<std::size_t> mine;
  std::vector<Pose> my_poses;
  for (std::size_t i = 0; i < poses.poses.size(); ++i)
    if (owns(&share, i)) {
      mine.push_back(i);
      my_poses.push_back(poses.poses[i]);
    }
  std::vector<PoseCompliance> matrices;
  const std::vector<PoseMetrics> metrics =
      analyze_poses(machine, my_poses, wrench, opt.compliance ? &matrices : nullptr);
  std::vector<PoseModes> modes;
  if (opt.modes) modes = mode_shapes_of_poses(machine, my_poses);
  std::vector<char> packed;  // per pose: reachable (1 byte), row length (8 bytes), row
  for (std::size_t k = 0; k < mine.size(); ++k) {
    const std::string row =
        analyze_csv_row(machine, poses, mine[k], metrics[k], opt.modes ? &modes[k] : nullptr,
                        opt.compliance ? &matrices[k] : nullptr);
    packed.push_back(metrics[k].reachable ? 1 : 0);
    const std::uint64_t length = row.size();
    const auto* l = reinterpret_cast<const char*>(&length);
    packed.insert(packed.end(), l, l + sizeof length);
    packed.insert(packed.end(), row.begin(), row.end());
  }
  const std::vector<std::vector<char>> parts = share.all_gather(packed);
  if (share.part() > 0) return;
  const AnalyzeCsvOptions columns{.compliance = opt.compliance ? &matrices : nullptr,
                                  .modes = opt.modes ? &modes : nullptr};
  std::string csv = analyze_csv_header(machine, poses, columns);
  std::vector<std::size_t> at(parts.size(), 0);
  bool any_reachable = false;
  for (std::size_t i = 0; i < poses.poses.size(); ++i) {
    const std::vector<char>& part = parts[i % parts.size()];
    std::size_t& p = at[i % parts.size()];
    any_reachable = any_reachable || part.at(p) != 0;
    std::uint64_t length = 0;
    std::memcpy(&length, part.data() + p + 1, sizeof length);
    csv.append(part.data() + p + 1 + sizeof length, length);
    p += 1 + sizeof length + length;
  }
  write_analyze_output(opt, csv);
  warn_if_nothing_reachable(poses, any_reachable, opt.poses_file);
}

void run_analyze(const AnalyzeOptions& opt) {
  // Read and validate every input before anything is written.
  const std::unique_ptr<Machine> machine = load_machine_file(opt.machine_file);
  if (const Capability<Dynamics> dynamics = machine->dynamics(); opt.modes && !dynamics) {
    throw InputError(fmt::format("{}: --mode-shapes needs a mass model: {} (docs/dynamics.md)",
                                 opt.machine_file, dynamics.reason()));
  }
  Wrench wrench = Wrench::Zero();
  if (!opt.wrench.empty()) {
    const auto w = parse_wrench_option(opt.wrench);
    for (int i = 0; i < 6; ++i) wrench(i) = w[static_cast<std::size_t>(i)];
  }
  const PoseTable poses = read_pose_csv(opt.poses_file);
  if (mpi_launch_from_environment().launched) {
    const MpiSession session;
    const MpiShare share(session);
    if (session.size() > 1) {
      analyze_shared(opt, *machine, poses, wrench, share);
      return;
    }
  }
  std::vector<PoseCompliance> matrices;
  const std::vector<PoseMetrics> metrics =
      analyze_poses(*machine, poses.poses, wrench, opt.compliance ? &matrices : nullptr);
  std::vector<PoseModes> modes;
  if (opt.modes) modes = mode_shapes_of_poses(*machine, poses.poses);
  const std::string csv = analyze_csv(
      *machine, poses, metrics,
      {.compliance = opt.compliance ? &matrices : nullptr, .modes = opt.modes ? &modes : nullptr});
  write_analyze_output(opt, csv);
  warn_if_nothing_reachable(
      poses,
      std::any_of(metrics.begin(), metrics.end(), [](const PoseMetrics& m) { return m.reachable; }),
      opt.poses_file);
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
