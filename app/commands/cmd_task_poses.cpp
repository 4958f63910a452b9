// pkmopt task-poses STUDY.yaml [--design DIR/designs/dNNNN.yaml | --home-height H] [--out FILE]
//
// Writes the task poses of a design study as a pose CSV (x,y,z in m, rx,ry,rz in degrees, base
// frame) that `pkmopt analyze` reads: the poses every design is measured at, lifted by the
// design's home_height. With --design the lift is read from the pareto.json of the run the
// design file belongs to (DIR/pareto.json); --home-height gives it directly; without either the
// poses are written as the study defines them, before any lift.
#include <fmt/format.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>

#include "app/commands.hpp"
#include "io/format/csv.hpp"
#include "io/format/input_error.hpp"
#include "io/format/number_policy.hpp"
#include "io/format/output_file.hpp"
#include "io/format/pose_csv.hpp"
#include "io/results/pareto_json.hpp"
#include "studies/design_study.hpp"

namespace pkmopt::cli {
namespace {

struct TaskPosesOptions {
  std::string study_file;
  std::string design_file;
  std::optional<double> home_height;
  std::string out_file;
};

// The home_height of a design file written by `pkmopt run` (DIR/designs/dNNNN.yaml), from
// DIR/pareto.json.
double home_height_of_design(const std::string& design_file) {
  namespace fs = std::filesystem;
  const fs::path design = fs::absolute(design_file).lexically_normal();
  if (!fs::is_regular_file(design))
    throw InputError(fmt::format("--design: cannot open the file '{}'", design_file));
  const fs::path pareto = design.parent_path().parent_path() / "pareto.json";
  if (!fs::exists(pareto))
    throw InputError(fmt::format(
        "--design: expected a design of a run (DIR/designs/NAME.yaml next to DIR/pareto.json), "
        "found no '{}'; give the lift with --home-height",
        pareto.string()));
  const ParetoFront front = read_pareto_json(pareto.string());
  const std::string relative = "designs/" + design.filename().string();
  for (const ParetoDesign& d : front.designs)
    if (d.machine_file && *d.machine_file == relative) return d.home_height;
  throw InputError(fmt::format("--design: '{}' lists no design with machine_file '{}'",
                               pareto.string(), relative));
}

void run_task_poses(const TaskPosesOptions& opt) {
  if (!opt.design_file.empty() && opt.home_height)
    throw InputError("--design and --home-height: expected one of them, found both");
  if (!is_design_study_file(opt.study_file))
    throw InputError(
        fmt::format("{}: expected a design study (a file with a 'machine:' section), "
                    "found a benchmark study, which has no task",
                    opt.study_file));
  const DesignStudy study = load_design_study(opt.study_file);
  double lift = 0.0;
  if (opt.home_height) {
    if (!(std::abs(*opt.home_height) <= kMaxInputLength))
      throw InputError(fmt::format("--home-height: expected a length within +-{} m, found {}",
                                   kMaxInputLength, *opt.home_height));
    lift = *opt.home_height;
  } else if (!opt.design_file.empty()) {
    lift = home_height_of_design(opt.design_file);
  }
  std::vector<Pose> poses = study.task().poses;
  for (Pose& p : poses) p.position.z() += lift;
  const std::string csv = pose_csv_text(poses);
  if (opt.out_file.empty()) {
    std::cout << csv;
    std::cout.flush();
  } else {
    write_file_atomically(opt.out_file, csv);
  }
  fmt::print(stderr, "pkmopt: task-poses: {} poses of '{}', lifted by home_height {} m\n",
             poses.size(), study.name, format_number(lift));
}

}  // namespace

void add_task_poses_command(CLI::App& app) {
  auto opt = std::make_shared<TaskPosesOptions>();
  CLI::App* cmd = app.add_subcommand(
      "task-poses",
      "Write the task poses of a design study as a pose CSV for 'pkmopt analyze' (base frame, "
      "lifted by a design's home_height)");
  cmd->add_option("study", opt->study_file, "Design study file (YAML)")->required();
  cmd->add_option("--design", opt->design_file,
                  "A design of a run, DIR/designs/dNNNN.yaml: its home_height (from "
                  "DIR/pareto.json) lifts the poses");
  cmd->add_option("--home-height", opt->home_height, "Lift the poses by this along base z (m)")
      ->check(length_in_metres());
  cmd->add_option("--out", opt->out_file, "Output CSV (default: standard output)");
  cmd->callback([opt] { run_task_poses(*opt); });
}

}  // namespace pkmopt::cli
