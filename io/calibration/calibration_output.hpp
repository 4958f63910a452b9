// The files written by the calibration commands (docs/calibration.md): `pkmopt calibrate`'s
// calibrated machine, `pkmopt simulate-measurements`' measurement set and
// `pkmopt calibration-poses`' chosen poses. The files they read are in
// io/calibration/calibration_files.hpp.
//
//   calibrated_machine_yaml      calibrated.yaml: two comment lines (the calibration file and
//                                leg length = offset + (1 + gain) * reading * unit m), then the
//                                calibrated hexapod machine file (io/machine/machine_file.hpp).
//   measurement_csv              x,y,z (m),rx,ry,rz (deg),q_1..q_6 (stroke / unit_scale, in the
//                                actuator unit): what read_measurement_csv reads back.
//   simulated_calibration_yaml   calibration.yaml naming nominal.yaml and measurements.csv, with
//                                the noise of the simulation (floored at 1e-9 m, 1e-9 deg and
//                                1e-12 m so that the file is valid), huber loss, gauge auto and
//                                every n-th row held out (n >= 2); a comment line, then
//                                calibration_file_yaml (io/calibration/calibration_files.hpp).
//   simulation_truth_json        truth.json: seed, outlier_rows (1-based data rows), the 48 true
//                                machine parameters by name (m, rad, relative gain),
//                                mean_position_sigma (m).
//   simulated_measurement_files  every file of `simulate-measurements --out DIR` by name:
//                                measurements.csv, nominal.yaml, truth.yaml, truth.json,
//                                calibration.yaml.
//   selected_poses_csv           x,y,z (m),rx,ry,rz (deg),candidate: the chosen poses in
//                                ascending candidate order, each with its candidate label.
// Numbers in the shortest text that reads back to the same double (format_number). Each
// function returns the file's bytes; the caller writes them (io/format/output_file.hpp).
//
// Example:
//   const SimulatedMeasurements data = simulate_measurements(design, nominal, mask, sim);
//   SimulationFileSettings settings;
//   settings.seed = sim.seed;
//   for (const auto& [name, bytes] : simulated_measurement_files(design, data, settings))
//     write_file_atomically((dir / name).string(), bytes);
#pragma once

#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

#include "io/calibration/calibration_files.hpp"
#include "models/hexapod/hexapod.hpp"
#include "problems/calibration/calibration.hpp"
#include "problems/calibration/calibration_candidates.hpp"

namespace pkmopt {

/// calibrated.yaml for a calibration of `setup` (its file and actuator unit appear in the
/// comment).
std::string calibrated_machine_yaml(const CalibrationSetup& setup, const CalibrationResult& result);

/// The measurement CSV; `unit_scale` is metres per actuator unit (1e-3 for mm).
std::string measurement_csv(const std::vector<CalibrationMeasurement>& measurements,
                            double unit_scale);

/// How a simulated measurement set is described in its calibration.yaml.
struct SimulationFileSettings {
  std::uint64_t seed = 1;
  std::string unit = "mm";               ///< reading unit written: "m" or "mm"
  double zero_length = 0.7;              ///< leg length at reading 0 (m)
  double orientation_sigma_deg = 0.003;  ///< instrument orientation noise (deg)
  double actuator_sigma = 1e-6;          ///< reading noise (m)
  std::string model = "48";              ///< "42" or "48"
  int holdout_every = 4;                 ///< every n-th row held out for validation
};

/// Metres per reading unit of the settings: 1e-3 for "mm", else 1.
double reading_unit_scale(const SimulationFileSettings& settings);

/// calibration.yaml of a simulated set whose mean instrument position sigma is
/// `mean_position_sigma` (m).
std::string simulated_calibration_yaml(const SimulationFileSettings& settings,
                                       double mean_position_sigma);

/// truth.json of a simulated set drawn with `seed`.
std::string simulation_truth_json(std::uint64_t seed, const SimulatedMeasurements& data);

/// Every file of a simulated set drawn around `nominal`, as (name, bytes) in writing order.
std::vector<std::pair<std::string, std::string>> simulated_measurement_files(
    const HexapodDesign& nominal, const SimulatedMeasurements& data,
    const SimulationFileSettings& settings);

/// The chosen poses; selection.selected indexes candidates.poses and candidates.labels.
std::string selected_poses_csv(const CalibrationCandidates& candidates,
                               const PoseSelection& selection);

/// What `pkmopt calibrate` makes of a calibration setup: the report (report.json), its text
/// (report.txt) and the calibrated machine (calibrated.yaml). A calibration that cannot be done
/// (CalibrationError) throws InputError naming setup.file.
struct CalibrationRun {
  nlohmann::json report;
  std::string text;
  std::string machine_yaml;
  /// The files of the run by name: report.json, report.txt, calibrated.yaml.
  std::vector<std::pair<std::string, std::string>> files() const;
  /// "" when the report's status is ok, else its warnings joined by "; ".
  std::string problems() const;
};
CalibrationRun run_calibration(const CalibrationSetup& setup);

}  // namespace pkmopt
