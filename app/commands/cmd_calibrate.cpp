// pkmopt calibrate CALIBRATION.yaml --out DIR
// pkmopt simulate-measurements MACHINE.yaml --out DIR [--poses N --seed S ...]
// pkmopt calibration-poses MACHINE.yaml --count N (--candidates FILE.csv | --grid)
#include <fmt/format.h>

#include <filesystem>
#include <iostream>
#include <memory>

#include "io/calibration_files.hpp"
#include "app/cli_args.hpp"
#include "app/commands.hpp"
#include "io/csv.hpp"
#include "io/input_error.hpp"
#include "io/machine_file.hpp"
#include "io/output_file.hpp"
#include "io/pose_csv.hpp"
#include "io/yaml_reader.hpp"

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

HexapodDesign read_hexapod_machine(const std::string& path) {
  const YamlValue machine = YamlValue::load_file(path);
  const YamlValue model = machine.required("model");
  if (model.as_string() != "hexapod") model.fail("'hexapod' (calibration)", model.describe());
  return read_hexapod_design(machine);
}

// ---- calibrate --------------------------------------------------------------------------------

struct CalibrateOptions {
  std::string file;
  std::string out;
};

void run_calibrate(const CalibrateOptions& opt) {
  const CalibrationSetup setup = read_calibration_setup(opt.file);
  std::vector<CalibrationMeasurement> fitted;
  for (int k : setup.fit) fitted.push_back(setup.measurements[static_cast<std::size_t>(k)]);
  CalibrationResult result;
  try {
    result = calibrate(setup.nominal_design, setup.nominal, fitted, setup.options);
  } catch (const CalibrationError& e) {
    throw InputError(fmt::format("{}: {}", opt.file, e.what()));
  }
  const nlohmann::json report = calibration_report_json(setup, result);
  const std::string text = calibration_report_text(report);
  HexapodDesign calibrated = calibrated_design(setup.nominal_design, result.estimate);
  std::string machine = fmt::format(
      "# Calibrated by pkmopt calibrate {}.\n# Leg offsets (leg length at reading 0, m) and "
      "gain errors are in report.json: leg length = offset + (1 + gain) * reading * {} m.\n",
      opt.file, format_number(setup.unit_scale));
  machine += hexapod_design_to_yaml(calibrated);
  make_output_directory(opt.out);
  const std::filesystem::path dir(opt.out);
  write_file_atomically((dir / "report.json").string(), report.dump(2) + "\n");
  write_file_atomically((dir / "report.txt").string(), text);
  write_file_atomically((dir / "calibrated.yaml").string(), machine);
  std::cout << text;
  std::cout.flush();
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
  const HexapodDesign design = read_hexapod_machine(opt.machine);
  if (opt.model != "42" && opt.model != "48") {
    throw InputError(fmt::format("--model: expected 42 or 48, found '{}'", opt.model));
  }
  if (opt.unit != "m" && opt.unit != "mm") {
    throw InputError(fmt::format("--unit: expected m or mm, found '{}'", opt.unit));
  }
  if (opt.poses < 1 || opt.outliers < 0 || opt.outliers > opt.poses) {
    throw InputError(fmt::format(
        "--poses/--outliers: expected poses >= 1 and 0 <= outliers <= poses, found {} and {}",
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
  const double scale = opt.unit == "mm" ? 1e-3 : 1.0;
  std::string csv = "x,y,z,rx,ry,rz,q_1,q_2,q_3,q_4,q_5,q_6\n";
  for (const auto& m : data.measurements) {
    const Eigen::Vector3d angles = rad_to_deg(m.pose.angles);
    csv +=
        fmt::format("{},{},{},{},{},{}", format_number(m.pose.position(0)),
                    format_number(m.pose.position(1)), format_number(m.pose.position(2)),
                    format_number(angles(0)), format_number(angles(1)), format_number(angles(2)));
    for (int i = 0; i < 6; ++i) csv += "," + format_number(m.stroke(i) / scale);
    csv += "\n";
  }
  const double mean_sigma = std::max(data.mean_position_sigma, 1e-9);
  const double orientation = std::max(opt.orientation_sigma_deg, 1e-9);
  const double actuator = std::max(opt.actuator_sigma, 1e-12) / scale;
  std::string yaml = fmt::format(
      "# Calibration of simulated measurements (pkmopt simulate-measurements --seed {}).\n"
      "machine: nominal.yaml\n"
      "measurements: measurements.csv\n"
      "frame: base\n"
      "actuators: {{unit: {}, zero_length: {}}}\n"
      "noise: {{position: {}, orientation_deg: {}, actuator: {}}}\n"
      "model: {}\n"
      "gauge: auto\n"
      "loss: {{type: huber, scale: 5}}\n"
      "validation: {{every: {}}}\n",
      opt.seed, opt.unit, format_number(opt.zero_length), format_number(mean_sigma),
      format_number(orientation), format_number(actuator), opt.model,
      std::max(2, opt.holdout_every));
  nlohmann::json truth;
  truth["seed"] = opt.seed;
  truth["outlier_rows"] = nlohmann::json::array();
  for (int k : data.outliers) truth["outlier_rows"].push_back(k + 1);
  for (int i = 0; i < kCalibrationMachineParameters; ++i) {
    truth["parameters"][calibration_parameter_name(i)] = data.truth(i);
  }
  truth["mean_position_sigma"] = data.mean_position_sigma;
  make_output_directory(opt.out);
  const std::filesystem::path dir(opt.out);
  write_file_atomically((dir / "measurements.csv").string(), csv);
  write_file_atomically((dir / "nominal.yaml").string(), hexapod_design_to_yaml(design));
  write_file_atomically((dir / "truth.yaml").string(),
                        "# The true machine the measurements were drawn from.\n" +
                            hexapod_design_to_yaml(calibrated_design(design, data.truth)));
  write_file_atomically((dir / "truth.json").string(), truth.dump(2) + "\n");
  write_file_atomically((dir / "calibration.yaml").string(), yaml);
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
  const HexapodDesign design = read_hexapod_machine(opt.machine);
  if (opt.model != "42" && opt.model != "48") {
    throw InputError(fmt::format("--model: expected 42 or 48, found '{}'", opt.model));
  }
  if (opt.candidates.empty() == !opt.grid) {
    throw InputError("calibration-poses: expected exactly one of --candidates FILE or --grid");
  }
  const Hexapod hexapod(design);
  auto data = hexapod.make_data();
  std::vector<Pose> candidates;
  std::vector<int> candidate_lines;
  int unreachable = 0;
  if (!opt.candidates.empty()) {
    const CsvTable table = read_csv_file(opt.candidates);
    const PoseColumns columns = find_pose_columns(table);
    for (const CsvRow& row : table.rows) {
      const Pose pose = pose_of_row(table, row, columns);
      if (!hexapod.reachable(*data, pose)) {
        ++unreachable;
        continue;
      }
      candidates.push_back(pose);
      candidate_lines.push_back(row.line);
    }
  } else {
    const auto z = parse_number_list("--z-range", opt.z_range, 2);
    if (opt.steps < 2 || opt.steps > 7) {
      throw InputError(fmt::format("--steps: expected an integer in 2..7, found {}", opt.steps));
    }
    auto level = [&](double lo, double hi, int i) { return lo + (hi - lo) * i / (opt.steps - 1); };
    const double a = deg_to_rad(opt.angle_range_deg);
    const int n = opt.steps;
    for (int ix = 0; ix < n; ++ix)
      for (int iy = 0; iy < n; ++iy)
        for (int iz = 0; iz < n; ++iz)
          for (int ia = 0; ia < n; ++ia)
            for (int ib = 0; ib < n; ++ib)
              for (int ic = 0; ic < n; ++ic) {
                Pose pose;
                pose.position = {level(-opt.xy_range, opt.xy_range, ix),
                                 level(-opt.xy_range, opt.xy_range, iy), level(z[0], z[1], iz)};
                pose.angles = {level(-a, a, ia), level(-a, a, ib), level(-a, a, ic)};
                if (!hexapod.reachable(*data, pose)) {
                  ++unreachable;
                  continue;
                }
                candidates.push_back(pose);
                candidate_lines.push_back(static_cast<int>(candidates.size()));
              }
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
    selection = select_calibration_poses(nominal, design.tcp, candidates, opt.count, options);
  } catch (const CalibrationError& e) {
    throw InputError(
        fmt::format("calibration-poses ({} reachable candidates, {} unreachable "
                    "skipped): {}",
                    candidates.size(), unreachable, e.what()));
  }
  std::string csv = "x,y,z,rx,ry,rz,candidate\n";
  for (int c : selection.selected) {
    const Pose& pose = candidates[static_cast<std::size_t>(c)];
    const Eigen::Vector3d deg = rad_to_deg(pose.angles);
    csv += fmt::format("{},{},{},{},{},{},{}\n", format_number(pose.position(0)),
                       format_number(pose.position(1)), format_number(pose.position(2)),
                       format_number(deg(0)), format_number(deg(1)), format_number(deg(2)),
                       candidate_lines[static_cast<std::size_t>(c)]);
  }
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
             selection.selected.size(), candidates.size(), unreachable, selection.exchanges,
             id.rank, id.free_indices.size(), selection.log_det, id.O1, id.O3, id.O4);
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
  cmd->add_option("--zero-length", opt->zero_length, "Leg length at reading 0 (m, default 0.7)");
  cmd->add_option("--holdout-every", opt->holdout_every,
                  "Every n-th row is held out for validation (default 4)");
  cmd->add_option("--joint-error", opt->joint_error,
                  "Sigma of joint and offset errors (m, default 1e-3)");
  cmd->add_option("--tracker-sigma", opt->tracker_sigma, "Tracker sigma (m, default 15e-6)");
  cmd->add_option("--tracker-sigma-per-metre", opt->tracker_sigma_per_metre,
                  "Plus this times the distance (default 6e-6)");
  cmd->add_option("--orientation-sigma-deg", opt->orientation_sigma_deg,
                  "Orientation sigma (deg, default 0.003)");
  cmd->add_option("--actuator-sigma", opt->actuator_sigma, "Reading sigma (m, default 1e-6)");
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
  cmd->add_option("--xy-range", opt->xy_range, "Grid |x|, |y| <= (m, default 0.15)");
  cmd->add_option("--z-range", opt->z_range, "Grid z range zmin,zmax (m, default 0.75,0.95)");
  cmd->add_option("--angle-range", opt->angle_range_deg, "Grid |rx|,|ry|,|rz| <= (deg, 12)");
  cmd->add_option("--steps", opt->steps, "Grid levels per axis (2..7, default 3)");
  cmd->add_option("--model", opt->model, "42 or 48 (default 48)");
  cmd->add_option("--zero-length", opt->zero_length, "Leg length at reading 0 (m, default 0.7)");
  cmd->add_option("--sigma-position", opt->sigma_position, "Tracker sigma (m, default 2e-5)");
  cmd->add_option("--sigma-orientation-deg", opt->sigma_orientation_deg,
                  "Orientation sigma (deg, default 0.003)");
  cmd->add_option("--sigma-actuator", opt->sigma_actuator, "Reading sigma (m, default 1e-6)");
  cmd->add_option("--out", opt->out, "Output CSV (default: standard output)");
  cmd->callback([opt] { run_poses(*opt); });
}

}  // namespace pkmopt::cli
