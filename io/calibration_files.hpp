// Calibration files: the calibration YAML, the measurement CSV and the reports.
//
// Calibration YAML (paths relative to the YAML file; docs/calibration.md has every key):
//   machine: nominal.yaml            # nominal hexapod machine file
//   measurements: measurements.csv   # one row per measured pose
//   frame: base                      # base: poses measured in the base frame (TCP);
//                                    # instrument: target poses in the instrument's frame
//   instrument: {position: [x, y, z], angles_deg: [rx, ry, rz]}  # start (frame: instrument)
//   target: {position: [x, y, z], angles_deg: [rx, ry, rz]}      # target in the TCP frame
//   actuators: {unit: mm, zero_length: 0.70}   # unit m|mm|rev|counts; lead (m/rev),
//                                              # counts_per_metre; zero_length m (1 or 6)
//   noise: {position: 2.0e-5, orientation_deg: 0.003, actuator: 0.001}  # m, deg, actuator unit
//   model: 48                        # 42 | 48
//   fixed: [a1.z]                    # parameters held at nominal (optional)
//   gauge: auto                      # auto | none
//   loss: {type: huber, scale: 5}    # huber | cauchy | none; scale in sigma units
//   outlier_chi2: 27.86
//   validation: {every: 4}           # or {rows: [3, 7, 11]} (1-based data rows)
//   parameter_scale: {length: 1.0e-3, gain: 2.0e-4}  # a-priori sigmas for the scaled indices
//                                    # (also frame_position m, frame_angle_deg); optional
//
// Measurement CSV: header x,y,z, then qw,qx,qy,qz or rx,ry,rz (degrees), then q_1..q_6 in the
// actuator unit; no other columns. Positions in metres.
//
// The nominal machine of a calibration must be a hexapod machine file (io/machine_file.hpp).
//
// Example:
//   CalibrationSetup setup = read_calibration_setup("calibration.yaml");   // InputError
//   CalibrationResult result = calibrate(setup.nominal_design, setup.nominal,
//                                        fitted_measurements(setup), setup.options);
//   std::string text = calibration_report_text(calibration_report_json(setup, result));
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "models/hexapod.hpp"
#include "problems/calibration.hpp"

namespace pkmopt {

/// Everything a calibration run needs, read and validated.
struct CalibrationSetup {
  std::string file;          ///< the calibration YAML
  std::string machine_file;  ///< resolved path of the nominal machine
  std::string measurement_file;
  HexapodDesign nominal_design;
  CalibrationVector nominal = CalibrationVector::Zero();
  std::string frame = "base";
  std::string unit = "m";
  double unit_scale = 1.0;  ///< metres per actuator unit
  CalibrationOptions options;
  std::string model = "48";
  std::vector<int> fixed;        ///< held by the user (`fixed:`)
  std::vector<int> gauge_fixed;  ///< held to fix the gauge (`gauge: auto`)
  std::string gauge = "auto";
  std::vector<CalibrationMeasurement> measurements;
  std::vector<int> fit;       ///< indices of the fitted rows
  std::vector<int> held_out;  ///< indices of the validation rows
};

/// A hexapod machine file for calibration; InputError naming file, line and column when the file
/// is not one (`model:` other than hexapod: "expected 'hexapod' (calibration)").
HexapodDesign read_calibration_machine(const std::string& path);

/// The measurements of the fitted rows (setup.fit), in that order; the held-out rows are left out.
std::vector<CalibrationMeasurement> fitted_measurements(const CalibrationSetup& setup);

/// Reads the YAML, the machine and the measurements; validates everything; chooses the gauge.
/// Throws InputError naming file, line, column or key, expected and found.
CalibrationSetup read_calibration_setup(const std::string& path);

/// Measurements from a CSV file (readings times `unit_scale` into `stroke`).
std::vector<CalibrationMeasurement> read_measurement_csv(const std::string& path,
                                                         double unit_scale);

/// The report of a calibration as JSON (see docs/calibration.md for every field).
nlohmann::json calibration_report_json(const CalibrationSetup& setup,
                                       const CalibrationResult& result);
/// The same report as readable text.
std::string calibration_report_text(const nlohmann::json& report);

}  // namespace pkmopt
