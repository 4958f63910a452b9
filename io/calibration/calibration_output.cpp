#include "io/calibration/calibration_output.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <nlohmann/json.hpp>

#include "io/calibration/calibration_report.hpp"
#include "io/format/csv.hpp"
#include "io/format/input_error.hpp"
#include "io/machine/machine_file.hpp"

namespace pkmopt {
namespace {

// x,y,z (m),rx,ry,rz (deg) of a pose, without a trailing comma.
std::string pose_fields(const Pose& pose) {
  const Eigen::Vector3d deg = rad_to_deg(pose.angles);
  return fmt::format("{},{},{},{},{},{}", format_number(pose.position(0)),
                     format_number(pose.position(1)), format_number(pose.position(2)),
                     format_number(deg(0)), format_number(deg(1)), format_number(deg(2)));
}

}  // namespace

std::string calibrated_machine_yaml(const CalibrationSetup& setup,
                                    const CalibrationResult& result) {
  std::string machine = fmt::format(
      "# Calibrated by pkmopt calibrate {}.\n# Leg offsets (leg length at reading 0, m) and "
      "gain errors are in report.json: leg length = offset + (1 + gain) * reading * {} m.\n",
      setup.file, format_number(setup.unit_scale));
  if (setup.stiffness_placeholder)
    machine +=
        "# The nominal machine file gives no leg stiffness (calibration does not use it): "
        "axial_stiffness below is a placeholder of 1 N/m; give the real one before analyze.\n";
  if (setup.unit == "rev" && setup.leg_scale.maxCoeff() != setup.leg_scale.minCoeff())
    machine += fmt::format("# Screw leads per leg (m/rev): {}, {}, {}, {}, {}, {}.\n",
                           format_number(setup.leg_scale(0)), format_number(setup.leg_scale(1)),
                           format_number(setup.leg_scale(2)), format_number(setup.leg_scale(3)),
                           format_number(setup.leg_scale(4)), format_number(setup.leg_scale(5)));
  machine += hexapod_design_to_yaml(calibrated_design(setup.nominal_design, result.estimate));
  return machine;
}

std::string measurement_csv(const std::vector<CalibrationMeasurement>& measurements,
                            double unit_scale) {
  std::string csv = "x,y,z,rx,ry,rz,q_1,q_2,q_3,q_4,q_5,q_6\n";
  for (const auto& m : measurements) {
    csv += pose_fields(m.pose);
    for (int i = 0; i < 6; ++i) csv += "," + format_number(m.stroke(i) / unit_scale);
    csv += "\n";
  }
  return csv;
}

double reading_unit_scale(const SimulationFileSettings& settings) {
  return settings.unit == "mm" ? 1e-3 : 1.0;
}

std::string simulated_calibration_yaml(const SimulationFileSettings& settings,
                                       double mean_position_sigma) {
  CalibrationFile file;
  file.machine = "nominal.yaml";
  file.measurements = "measurements.csv";
  file.frame = "base";
  file.unit = settings.unit;
  file.zero_length = {settings.zero_length};
  file.noise_position = std::max(mean_position_sigma, 1e-9);
  file.noise_orientation_deg = std::max(settings.orientation_sigma_deg, 1e-9);
  file.noise_actuator = std::max(settings.actuator_sigma, 1e-12) / reading_unit_scale(settings);
  file.model = settings.model;
  file.gauge = "auto";
  file.loss = CalibrationLoss::kHuber;
  file.loss_scale = 5.0;
  file.every = std::max(2, settings.holdout_every);
  return fmt::format(
             "# Calibration of simulated measurements (pkmopt simulate-measurements --seed "
             "{}).\n",
             settings.seed) +
         calibration_file_yaml(file);
}

std::string simulation_truth_json(std::uint64_t seed, const SimulatedMeasurements& data) {
  nlohmann::json truth;
  truth["seed"] = seed;
  truth["outlier_rows"] = nlohmann::json::array();
  for (int k : data.outliers) truth["outlier_rows"].push_back(k + 1);
  for (int i = 0; i < kCalibrationMachineParameters; ++i) {
    truth["parameters"][calibration_parameter_name(i)] = data.truth(i);
  }
  truth["mean_position_sigma"] = data.mean_position_sigma;
  return truth.dump(2) + "\n";
}

std::vector<std::pair<std::string, std::string>> simulated_measurement_files(
    const HexapodDesign& nominal, const SimulatedMeasurements& data,
    const SimulationFileSettings& settings) {
  std::vector<std::pair<std::string, std::string>> files;
  files.emplace_back("measurements.csv",
                     measurement_csv(data.measurements, reading_unit_scale(settings)));
  files.emplace_back("nominal.yaml", hexapod_design_to_yaml(nominal));
  files.emplace_back("truth.yaml",
                     "# The true machine the measurements were drawn from.\n" +
                         hexapod_design_to_yaml(calibrated_design(nominal, data.truth)));
  files.emplace_back("truth.json", simulation_truth_json(settings.seed, data));
  files.emplace_back("calibration.yaml",
                     simulated_calibration_yaml(settings, data.mean_position_sigma));
  return files;
}

std::string selected_poses_csv(const CalibrationCandidates& candidates,
                               const PoseSelection& selection) {
  std::string csv = "x,y,z,rx,ry,rz,candidate\n";
  for (int c : selection.selected) {
    const auto i = static_cast<std::size_t>(c);
    csv += fmt::format("{},{}\n", pose_fields(candidates.poses[i]), candidates.labels[i]);
  }
  return csv;
}

CalibrationRun run_calibration(const CalibrationSetup& setup) {
  CalibrationResult result;
  try {
    result =
        calibrate(setup.nominal_design, setup.nominal, fitted_measurements(setup), setup.options);
  } catch (const CalibrationError& e) {
    throw InputError(fmt::format("{}: {}", setup.file, e.what()));
  }
  CalibrationRun run;
  run.report = calibration_report_json(setup, result);
  run.text = calibration_report_text(run.report);
  run.machine_yaml = calibrated_machine_yaml(setup, result);
  return run;
}

std::vector<std::pair<std::string, std::string>> CalibrationRun::files() const {
  return {{"report.json", report.dump(2) + "\n"},
          {"report.txt", text},
          {"calibrated.yaml", machine_yaml}};
}

std::string CalibrationRun::problems() const {
  std::string reasons;
  if (report["status"]["ok"].get<bool>()) return reasons;
  for (const auto& w : report["status"]["warnings"])
    reasons += (reasons.empty() ? "" : "; ") + w.get<std::string>();
  return reasons;
}

}  // namespace pkmopt
