// Calibration files: the calibration YAML and the measurement CSV (the reports are in
// io/calibration/calibration_report.hpp).
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
// The nominal machine of a calibration must be a hexapod machine file
// (io/machine/machine_file.hpp).
//
// The keys are described once (io/calibration/calibration_setup_fields.cpp): read_calibration_file
// reads them strictly, calibration_file_yaml writes them, calibration_fields_markdown is the table
// of docs/calibration.md. read_calibration_setup adds what needs the machine and the measurements.
//
// Example:
//   CalibrationSetup setup = read_calibration_setup("calibration.yaml");   // InputError
//   CalibrationResult result = calibrate(setup.nominal_design, setup.nominal,
//                                        fitted_measurements(setup), setup.options);
//   std::string text = calibration_report_text(calibration_report_json(setup, result));
//                                          // io/calibration/calibration_report.hpp
#pragma once

#include <Eigen/Core>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "io/format/yaml_reader.hpp"
#include "models/hexapod/hexapod.hpp"
#include "problems/calibration/calibration.hpp"

namespace pkmopt {

/// The keys of a calibration YAML as the file holds them (paths as written, angles in degrees,
/// noise.actuator in the actuator unit). One field list
/// (io/calibration/calibration_setup_fields.cpp) reads, writes and documents them; the defaults are
/// those of CalibrationOptions.
struct CalibrationFile {
  std::string machine;       ///< nominal machine file, relative to the calibration file
  std::string measurements;  ///< measurement CSV, relative to the calibration file
  std::string frame = "base";
  Eigen::Vector3d instrument_position = Eigen::Vector3d::Zero();    ///< m
  Eigen::Vector3d instrument_angles_deg = Eigen::Vector3d::Zero();  ///< deg
  Eigen::Vector3d target_position = Eigen::Vector3d::Zero();        ///< m
  Eigen::Vector3d target_angles_deg = Eigen::Vector3d::Zero();      ///< deg
  std::string unit;                                                 ///< m, mm, rev or counts
  std::vector<double> lead;            ///< m per revolution (unit rev); one, or one per leg
  double counts_per_metre = 0.0;       ///< unit counts; 0: not given
  std::vector<double> zero_length;     ///< m; empty: 0; one number for every leg, or six
  double noise_position = 0.0;         ///< m
  double noise_orientation_deg = 0.0;  ///< deg
  double noise_actuator = 0.0;         ///< actuator unit
  bool noise_estimate = true;          ///< estimate the sigmas from the data (given: the start)
  std::string pose_unit = "m";         ///< unit of the measured positions: m or mm
  std::string quaternion_order;        ///< "": by column name; wxyz or xyzw: by column order
  /// pkmopt's column names -> the measurement file's (x, y, z, rx..rz, qw..qz, q_1..q_6).
  std::vector<std::pair<std::string, std::string>> columns;
  double max_rejected_share = 0.2;  ///< more rejected poses: a probably wrong result
  std::string model = "48";
  std::vector<std::string> fixed;  ///< parameter names
  std::string gauge = "auto";
  CalibrationLoss loss = CalibrationLoss::kHuber;
  double loss_scale = 5.0;
  double outlier_chi2 = 27.86;
  int max_iterations = 200;
  double correlation_threshold = 0.9;
  double length_scale = 1e-3;                   ///< m
  double gain_scale = 2e-4;                     ///< 1
  double frame_position_scale = 5e-3;           ///< m
  std::optional<double> frame_angle_scale_deg;  ///< deg; unset: 1e-3 rad
  long long every = 0;                          ///< every n-th data row held out; 0: none
  std::vector<long long> rows;                  ///< 1-based data rows held out
};

/// Reads the keys of a calibration YAML with every check that needs no other file (unknown keys,
/// bounds, unit and lead, instrument only with frame: instrument, parameter names). Throws
/// InputError naming file, line, column, key, expected and found.
CalibrationFile read_calibration_file(const YamlValue& root);

/// The calibration YAML of `file`, one "key: value" line per top-level key (maps as flow maps,
/// in the order of docs/calibration.md; numbers in the shortest text that reads back the same).
/// Left out: keys not given (lead, zero_length, fixed, validation, ...), instrument and target
/// positions and angles at zero, instrument with frame: base, and outlier_chi2, max_iterations,
/// correlation_threshold and parameter_scale at their defaults; frame, model, gauge and loss are
/// always written. Reads back to the same keys (texts are written unquoted).
std::string calibration_file_yaml(const CalibrationFile& file);

/// The key table of the calibration YAML in docs/calibration.md (a test compares them).
std::string calibration_fields_markdown();

/// Everything a calibration run needs, read and validated.
struct CalibrationSetup {
  std::string file;          ///< the calibration YAML
  std::string machine_file;  ///< resolved path of the nominal machine
  std::string measurement_file;
  HexapodDesign nominal_design;
  CalibrationVector nominal = CalibrationVector::Zero();
  std::string frame = "base";
  std::string unit = "m";
  double unit_scale = 1.0;  ///< metres per actuator unit (the mean over the legs)
  Vec6<double> leg_scale = Vec6<double>::Ones();  ///< metres per actuator unit, per leg
  CalibrationOptions options;
  /// Things in the input that look wrong but are not errors (a quaternion whose scalar part
  /// seems to be in another column, ...): printed on stderr and listed in the report.
  std::vector<std::string> warnings;
  bool stiffness_placeholder = false;  ///< the machine file gives no leg stiffness
  /// The measurement campaigns' labels (the `campaign` column), the reference first; empty when
  /// the file has one campaign.
  std::vector<std::string> campaigns;
  std::string model = "48";
  std::vector<int> fixed;        ///< held by the user (`fixed:`)
  std::vector<int> gauge_fixed;  ///< held to fix the gauge (`gauge: auto`)
  std::string gauge = "auto";
  std::vector<CalibrationMeasurement> measurements;
  std::vector<int> fit;       ///< indices of the fitted rows
  std::vector<int> held_out;  ///< indices of the validation rows
};

/// A hexapod machine file for calibration; InputError naming file, line and column when the file
/// is not one (`model:` other than hexapod: "expected 'hexapod' (calibration)"). The legs'
/// stiffness may be left out (calibration does not use it): the design then gets a placeholder
/// axial_stiffness of 1 N/m and `stiffness_placeholder` (if given) is set.
HexapodDesign read_calibration_machine(const std::string& path,
                                       bool* stiffness_placeholder = nullptr);

/// The measurements of the fitted rows (setup.fit), in that order; the held-out rows are left out.
std::vector<CalibrationMeasurement> fitted_measurements(const CalibrationSetup& setup);

/// Reads the YAML, the machine and the measurements; validates everything; chooses the gauge.
/// Throws InputError naming file, line, column or key, expected and found.
CalibrationSetup read_calibration_setup(const std::string& path);

/// Measurements from a CSV file (readings times `unit_scale` into `stroke`).
/// How a measurement CSV is read: metres per reading unit of each leg, metres per position unit,
/// the quaternion order ("" by column name, "wxyz" or "xyzw" by column order) and renamed
/// columns (pkmopt name -> the file's).
struct MeasurementFormat {
  Vec6<double> reading_scale = Vec6<double>::Ones();
  double position_scale = 1.0;
  std::string quaternion_order;
  std::vector<std::pair<std::string, std::string>> columns;
};

/// A measurement CSV read with `format`; `warnings` (if given) receives what looks wrong
/// (e.g. quaternions whose scalar part seems to sit in another column).
/// An optional `campaign` column labels each row's measurement campaign (any text); the labels
/// in order of first appearance go to `campaigns` (the first is the reference, campaign 0).
std::vector<CalibrationMeasurement> read_measurement_csv(
    const std::string& path, const MeasurementFormat& format, std::vector<std::string>* warnings,
    std::vector<std::string>* campaigns = nullptr);
std::vector<CalibrationMeasurement> read_measurement_csv(const std::string& path,
                                                         double unit_scale);

}  // namespace pkmopt
