// pkmopt calibrate CALIBRATION.yaml --out DIR
// pkmopt simulate-measurements MACHINE.yaml --out DIR [--poses N --seed S ...]
// pkmopt calibration-poses MACHINE.yaml --count N (--candidates FILE.csv | --grid)
#include <fmt/format.h>

#include <cmath>
#include <filesystem>
#include <iostream>
#include <memory>

#include "app/cli_args.hpp"
#include "app/commands.hpp"
#include "io/calibration/calibration_files.hpp"
#include "io/calibration/calibration_output.hpp"
#include "io/format/csv.hpp"
#include "io/format/input_error.hpp"
#include "io/format/number_policy.hpp"
#include "io/format/output_file.hpp"
#include "io/format/pose_csv.hpp"
#include "problems/calibration/calibration_candidates.hpp"

namespace pkmopt::cli {
namespace {

void make_output_directory(const std::string& dir) {
  std::error_code error;
  std::filesystem::create_directories(dir, error);
  if (error || !std::filesystem::is_directory(dir)) {
    throw InputError(fmt::format("--out {}: expected a writable directory, found: {}", dir,
                                 error ? error.message() : "not a directory"));
  }
}

// ---- calibrate --------------------------------------------------------------------------------

struct CalibrateOptions {
  std::string file;
  std::string out;
};

void run_calibrate(const CalibrateOptions& opt) {
  const CalibrationSetup setup = read_calibration_setup(opt.file);
  for (const std::string& warning : setup.warnings)
    std::cerr << "pkmopt: warning: " << warning << '\n';
  const CalibrationRun run = run_calibration(setup);
  make_output_directory(opt.out);
  const std::filesystem::path dir(opt.out);
  for (const auto& [name, bytes] : run.files()) write_file_atomically((dir / name).string(), bytes);
  std::cout << run.text;
  std::cout.flush();
  if (const std::string problems = run.problems(); !problems.empty())
    throw ProbablyWrongResult(fmt::format(
        "{}: the calibration is probably wrong: {} (report in {})", opt.file, problems, opt.out));
}

// ---- simulate-measurements --------------------------------------------------------------------

struct SimulateOptions {
  std::string machine;
  std::string out;
  int poses = 60;
  std::uint64_t seed = 1;
  int outliers = 3;
  std::string model = "48";
  std::string unit = "mm";
  double zero_length = 0.7;
  int holdout_every = 4;
  double joint_error = 1e-3;
  double tracker_sigma = 15e-6;
  double tracker_sigma_per_metre = 6e-6;
  double orientation_sigma_deg = 0.003;
  double actuator_sigma = 1e-6;
};

void run_simulate(const SimulateOptions& opt) {
  if (!(std::isfinite(opt.zero_length) && opt.zero_length >= 0.0 && opt.zero_length < 1e3))
    bad_option("--zero-length", "a leg length at reading 0 in metres, 0 <= L < 1000",
               opt.zero_length);
  const HexapodDesign design = read_calibration_machine(opt.machine);
  if (opt.model != "42" && opt.model != "48") {
    throw InputError(fmt::format("--model: expected 42 or 48, found '{}'", opt.model));
  }
  if (opt.unit != "m" && opt.unit != "mm") {
    throw InputError(fmt::format("--unit: expected m or mm, found '{}'", opt.unit));
  }
  if (opt.poses < 1 || opt.poses > 100000 || opt.outliers < 0 || opt.outliers > opt.poses) {
    throw InputError(fmt::format(
        "--poses/--outliers: expected 1 <= poses <= 100000 and 0 <= outliers <= poses, found {} "
        "and {}",
        opt.poses, opt.outliers));
  }
  for (auto [name, value] : {std::pair{"--joint-error", opt.joint_error},
                             std::pair{"--tracker-sigma", opt.tracker_sigma},
                             std::pair{"--tracker-sigma-per-metre", opt.tracker_sigma_per_metre},
                             std::pair{"--orientation-sigma-deg", opt.orientation_sigma_deg},
                             std::pair{"--actuator-sigma", opt.actuator_sigma}}) {
    if (!(value >= 0.0) || !std::isfinite(value)) {
      throw InputError(fmt::format("{}: expected a finite number >= 0, found {}", name, value));
    }
  }
  const CalibrationModelKind kind =
      opt.model == "42" ? CalibrationModelKind::k42 : CalibrationModelKind::k48;
  const CalibrationVector nominal =
      nominal_calibration_vector(design, Vec6<double>::Constant(opt.zero_length));
  MeasurementSimulationOptions sim;
  sim.seed = opt.seed;
  sim.num_poses = opt.poses;
  sim.num_outliers = opt.outliers;
  sim.joint_sigma = opt.joint_error;
  sim.offset_sigma = opt.joint_error;
  sim.gain_sigma = kind == CalibrationModelKind::k48 ? 2e-4 : 0.0;
  sim.tracker_sigma = opt.tracker_sigma;
  sim.tracker_sigma_per_metre = opt.tracker_sigma_per_metre;
  sim.orientation_sigma = deg_to_rad(opt.orientation_sigma_deg);
  sim.actuator_sigma = opt.actuator_sigma;
  SimulatedMeasurements data;
  try {
    data = simulate_measurements(design, nominal, model_free_mask(kind), sim);
  } catch (const CalibrationError& e) {
    throw InputError(fmt::format("{}: {}", opt.machine, e.what()));
  }
  SimulationFileSettings settings;
  settings.seed = opt.seed;
  settings.unit = opt.unit;
  settings.zero_length = opt.zero_length;
  settings.orientation_sigma_deg = opt.orientation_sigma_deg;
  settings.actuator_sigma = opt.actuator_sigma;
  settings.model = opt.model;
  settings.holdout_every = opt.holdout_every;
  const auto files = simulated_measurement_files(design, data, settings);
  make_output_directory(opt.out);
  const std::filesystem::path dir(opt.out);
  for (const auto& [name, content] : files) write_file_atomically((dir / name).string(), content);
  fmt::print("wrote {} poses ({} outliers) to {}\n", data.measurements.size(), data.outliers.size(),
             opt.out);
}

// ---- calibration-poses ------------------------------------------------------------------------

struct PosesOptions {
  std::string machine;
  int count = 0;
  std::string candidates;
  bool grid = false;
  double xy_range = 0.15;
  std::string z_range = "0.75,0.95";
  double angle_range_deg = 12.0;
  int steps = 3;
  std::string model = "48";
  double zero_length = 0.7;
  double sigma_position = 20e-6;
  double sigma_orientation_deg = 0.003;
  double sigma_actuator = 1e-6;
  std::string out;
};

void run_poses(const PosesOptions& opt) {
  if (!(std::isfinite(opt.zero_length) && opt.zero_length >= 0.0 && opt.zero_length < 1e3))
    bad_option("--zero-length", "a leg length at reading 0 in metres, 0 <= L < 1000",
               opt.zero_length);
  const HexapodDesign design = read_calibration_machine(opt.machine);
  if (opt.model != "42" && opt.model != "48") {
    throw InputError(fmt::format("--model: expected 42 or 48, found '{}'", opt.model));
  }
  if (opt.candidates.empty() == !opt.grid) {
    throw InputError("calibration-poses: expected exactly one of --candidates FILE or --grid");
  }
  const Hexapod hexapod(design);
  CalibrationCandidates candidates;
  if (!opt.candidates.empty()) {
    const PoseTable table = read_pose_csv(opt.candidates);
    std::vector<int> lines;
    for (const CsvRow& row : table.table.rows) lines.push_back(row.line);
    candidates = reachable_candidates(hexapod, table.poses, lines);
  } else {
    const auto z = parse_number_list("--z-range", opt.z_range, 2, kMaxInputLength);
    if (opt.steps < 2 || opt.steps > 7) {
      throw InputError(fmt::format("--steps: expected an integer in 2..7, found {}", opt.steps));
    }
    CandidateGrid grid;
    grid.xy_range = opt.xy_range;
    grid.z_min = z[0];
    grid.z_max = z[1];
    grid.angle_range = deg_to_rad(opt.angle_range_deg);
    grid.steps = opt.steps;
    candidates = grid_candidates(hexapod, grid);
  }
  CalibrationOptions options;
  options.free =
      model_free_mask(opt.model == "42" ? CalibrationModelKind::k42 : CalibrationModelKind::k48);
  options.sigma_position = opt.sigma_position;
  options.sigma_orientation = deg_to_rad(opt.sigma_orientation_deg);
  options.sigma_actuator = opt.sigma_actuator;
  if (const std::string error = options.validate(); !error.empty()) throw InputError(error);
  const CalibrationVector nominal =
      nominal_calibration_vector(design, Vec6<double>::Constant(opt.zero_length));
  PoseSelection selection;
  try {
    selection = select_calibration_poses(nominal, design.tcp, candidates.poses, opt.count, options);
  } catch (const CalibrationError& e) {
    throw InputError(
        fmt::format("calibration-poses ({} reachable candidates, {} unreachable "
                    "skipped): {}",
                    candidates.poses.size(), candidates.unreachable, e.what()));
  }
  const std::string csv = selected_poses_csv(candidates, selection);
  if (opt.out.empty()) {
    std::cout << csv;
    std::cout.flush();
  } else {
    write_file_atomically(opt.out, csv);
  }
  const Identification& id = selection.identification;
  fmt::print(stderr,
             "calibration-poses: {} of {} reachable candidates ({} unreachable skipped), {} "
             "exchanges; rank {} of {}, log det {:.6g}, O1 {:.6g}, O3 {:.6g}, O4 {:.6g}\n",
             selection.selected.size(), candidates.poses.size(), candidates.unreachable,
             selection.exchanges, id.rank, id.free_indices.size(), selection.log_det, id.O1, id.O3,
             id.O4);
}

}  // namespace

void add_calibrate_command(CLI::App& app) {
  auto opt = std::make_shared<CalibrateOptions>();
  CLI::App* cmd = app.add_subcommand(
      "calibrate", "Calibrate a hexapod's geometry from measured poses and actuator readings");
  cmd->add_option("calibration", opt->file, "Calibration file (YAML)")->required();
  cmd->add_option("--out", opt->out, "Output directory (report.json, report.txt, calibrated.yaml)")
      ->required();
  cmd->callback([opt] { run_calibrate(*opt); });
}

void add_simulate_measurements_command(CLI::App& app) {
  auto opt = std::make_shared<SimulateOptions>();
  CLI::App* cmd = app.add_subcommand(
      "simulate-measurements",
      "Draw a true machine around a nominal hexapod and simulate laser-tracker measurements");
  cmd->add_option("machine", opt->machine, "Nominal machine file (YAML)")->required();
  cmd->add_option("--out", opt->out, "Output directory")->required();
  cmd->add_option("--poses", opt->poses, "Number of measured poses (default 60)");
  cmd->add_option("--seed", opt->seed, "Random seed (default 1)");
  cmd->add_option("--outliers", opt->outliers, "Poses with a gross 1 mm error (default 3)");
  cmd->add_option("--model", opt->model, "42 or 48 (48 adds gain errors; default 48)");
  cmd->add_option("--unit", opt->unit, "Reading unit written: mm or m (default mm)");
  cmd->add_option("--zero-length", opt->zero_length, "Leg length at reading 0 (m, default 0.7)")
      ->check(length_in_metres());
  cmd->add_option("--holdout-every", opt->holdout_every,
                  "Every n-th row is held out for validation (default 4)");
  cmd->add_option("--joint-error", opt->joint_error,
                  "Sigma of joint and offset errors (m, default 1e-3)")
      ->check(length_in_metres());
  cmd->add_option("--tracker-sigma", opt->tracker_sigma, "Tracker sigma (m, default 15e-6)")
      ->check(length_in_metres());
  cmd->add_option("--tracker-sigma-per-metre", opt->tracker_sigma_per_metre,
                  "Plus this times the distance (default 6e-6)");
  cmd->add_option("--orientation-sigma-deg", opt->orientation_sigma_deg,
                  "Orientation sigma (deg, default 0.003)");
  cmd->add_option("--actuator-sigma", opt->actuator_sigma, "Reading sigma (m, default 1e-6)")
      ->check(length_in_metres());
  cmd->callback([opt] { run_simulate(*opt); });
}

void add_calibration_poses_command(CLI::App& app) {
  auto opt = std::make_shared<PosesOptions>();
  CLI::App* cmd = app.add_subcommand(
      "calibration-poses",
      "Choose the poses to measure for calibration (D-optimal exchange over candidates)");
  cmd->add_option("machine", opt->machine, "Nominal machine file (YAML)")->required();
  cmd->add_option("--count", opt->count, "Number of poses to choose")->required();
  cmd->add_option("--candidates", opt->candidates, "Candidate poses (CSV x,y,z[,rx,ry,rz])");
  cmd->add_flag("--grid", opt->grid, "Candidates on a grid (--xy-range, --z-range, ...)");
  cmd->add_option("--xy-range", opt->xy_range, "Grid |x|, |y| <= (m, default 0.15)")
      ->check(length_in_metres());
  cmd->add_option("--z-range", opt->z_range, "Grid z range zmin,zmax (m, default 0.75,0.95)");
  cmd->add_option("--angle-range", opt->angle_range_deg, "Grid |rx|,|ry|,|rz| <= (deg, 12)");
  cmd->add_option("--steps", opt->steps, "Grid levels per axis (2..7, default 3)");
  cmd->add_option("--model", opt->model, "42 or 48 (default 48)");
  cmd->add_option("--zero-length", opt->zero_length, "Leg length at reading 0 (m, default 0.7)")
      ->check(length_in_metres());
  cmd->add_option("--sigma-position", opt->sigma_position, "Tracker sigma (m, default 2e-5)")
      ->check(length_in_metres());
  cmd->add_option("--sigma-orientation-deg", opt->sigma_orientation_deg,
                  "Orientation sigma (deg, default 0.003)");
  cmd->add_option("--sigma-actuator", opt->sigma_actuator, "Reading sigma (m, default 1e-6)")
      ->check(length_in_metres());
  cmd->add_option("--out", opt->out, "Output CSV (default: standard output)");
  cmd->callback([opt] { run_poses(*opt); });
}

}  // namespace pkmopt::cli
