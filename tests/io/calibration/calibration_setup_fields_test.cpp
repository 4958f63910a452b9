// Tests of io/calibration/calibration_setup_fields.cpp: the calibration YAML's keys described once
// (reader, writer, docs table).
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <string>

#include "io/calibration/calibration_files.hpp"
#include "io/format/input_error.hpp"
#include "problems/calibration/calibration.hpp"

namespace {

// docs/calibration.md carries the calibration YAML's key table exactly as the field list
// generates it; the failure message shows the block to paste.
TEST(CalibrationFileFields, DocsTableMatchesTheFieldList) {
  std::ifstream in(std::string(PKMOPT_SOURCE_DIR) + "/docs/calibration.md");
  std::stringstream docs;
  docs << in.rdbuf();
  const std::string block = "<!-- fields: calibration -->\n" +
                            pkmopt::calibration_fields_markdown() + "<!-- /fields -->\n";
  EXPECT_NE(docs.str().find(block), std::string::npos)
      << "docs/calibration.md lacks the generated calibration table:\n"
      << block;
}

const char* kMinimal =
    "machine: nominal.yaml\n"
    "measurements: measurements.csv\n"
    "actuators: {unit: mm}\n"
    "noise: {position: 2.0e-5, orientation_deg: 0.003, actuator: 0.001}\n";

pkmopt::CalibrationFile read_text(const std::string& text) {
  return pkmopt::read_calibration_file(pkmopt::YamlValue::load_string(text, "cal.yaml"));
}

// The InputError message of reading `text`, "" when it reads.
std::string error_of(const std::string& text) {
  try {
    read_text(text);
  } catch (const pkmopt::InputError& e) {
    return e.what();
  }
  return "";
}

TEST(CalibrationFileFields, DefaultsAreThoseOfTheSolver) {
  const pkmopt::CalibrationFile c = read_text(kMinimal);
  const pkmopt::CalibrationOptions options;
  EXPECT_EQ(c.frame, "base");
  EXPECT_EQ(c.model, "48");
  EXPECT_EQ(c.gauge, "auto");
  EXPECT_EQ(c.loss, options.loss);
  EXPECT_EQ(c.loss_scale, options.loss_scale);
  EXPECT_EQ(c.outlier_chi2, options.outlier_chi2);
  EXPECT_EQ(c.outlier_chi2, 27.86);
  EXPECT_EQ(c.max_iterations, options.max_iterations);
  EXPECT_EQ(c.max_iterations, 200);
  EXPECT_EQ(c.correlation_threshold, options.correlation_threshold);
  EXPECT_EQ(c.correlation_threshold, 0.9);
  EXPECT_EQ(pkmopt::calibration_parameter_scale(c.length_scale, c.gain_scale,
                                                c.frame_position_scale, 1e-3),
            options.parameter_scale);
  EXPECT_FALSE(c.frame_angle_scale_deg.has_value());
  EXPECT_TRUE(c.zero_length.empty());
  EXPECT_EQ(c.every, 0);
  EXPECT_TRUE(c.rows.empty());
}

TEST(CalibrationFileFields, UnknownKeyInASectionNamesFileLineColumnAndKey) {
  const std::string message = error_of(
      "machine: nominal.yaml\n"
      "measurements: measurements.csv\n"
      "actuators: {unit: mm}\n"
      "noise:\n"
      "  position: 2.0e-5\n"
      "  orientation_deg: 0.003\n"
      "  actuator: 0.001\n"
      "  sigma: 2\n");
  EXPECT_EQ(message.rfind("cal.yaml:8:3: noise.sigma: unknown key 'sigma'; allowed keys here: ", 0),
            0u)
      << message;
  EXPECT_NE(message.find("position"), std::string::npos) << message;
  const std::string in_loss = error_of(std::string(kMinimal) + "loss: {type: huber, width: 5}\n");
  EXPECT_EQ(in_loss.rfind("cal.yaml:5:21: loss.width: unknown key 'width'", 0), 0u) << in_loss;
  const std::string top = error_of(std::string(kMinimal) + "iterations: 10\n");
  EXPECT_EQ(top.rfind("cal.yaml:5:1: iterations: unknown key 'iterations'", 0), 0u) << top;
}

TEST(CalibrationFileFields, OutOfBoundsValuesNameFileLineColumnKeyExpectedAndFound) {
  EXPECT_EQ(error_of(std::string(kMinimal) + "max_iterations: 0\n"),
            "cal.yaml:5:17: max_iterations: expected an integer in [1, 100000], found '0'");
  EXPECT_EQ(error_of(std::string(kMinimal) + "correlation_threshold: 1.5\n"),
            "cal.yaml:5:24: correlation_threshold: expected a number in (0, 1], found '1.5'");
  EXPECT_EQ(error_of(std::string(kMinimal) + "parameter_scale: {gain: -2e-4}\n"),
            "cal.yaml:5:25: parameter_scale.gain: expected a number > 0, found '-2e-4'");
  EXPECT_EQ(error_of(std::string(kMinimal) + "validation: {every: 1}\n"),
            "cal.yaml:5:21: validation.every: expected an integer >= 2, found '1'");
  EXPECT_EQ(error_of(std::string(kMinimal) + "outlier_chi2: 0\n"),
            "cal.yaml:5:15: outlier_chi2: expected a number > 0, found '0'");
  EXPECT_EQ(error_of(std::string(kMinimal) + "loss: {type: l2}\n"),
            "cal.yaml:5:14: loss.type: expected huber, cauchy or none, found 'l2'");
  EXPECT_EQ(error_of(std::string(kMinimal) + "model: 36\n"),
            "cal.yaml:5:8: model: expected 42 or 48, found '36'");
  EXPECT_EQ(error_of("machine: nominal.yaml\nmeasurements: m.csv\nactuators: {unit: mm}\n"
                     "noise: {position: 2.0e-5, orientation_deg: 0, actuator: 0.001}\n"),
            "cal.yaml:4:44: noise.orientation_deg: expected a number > 0, found '0'");
  EXPECT_EQ(error_of("machine: nominal.yaml\nmeasurements: m.csv\nactuators: {unit: mm}\n"),
            "cal.yaml:1:1: missing required key 'noise'");
}

// The keys checked by hand next to the list: located like the others.
TEST(CalibrationFileFields, HandCheckedKeys) {
  const std::string base =
      "machine: nominal.yaml\n"
      "measurements: measurements.csv\n"
      "noise: {position: 2.0e-5, orientation_deg: 0.003, actuator: 0.001}\n";
  EXPECT_EQ(error_of(base + "actuators: {unit: inch}\n"),
            "cal.yaml:4:19: actuators.unit: expected m, mm, rev or counts, found 'inch'");
  EXPECT_EQ(error_of(base + "actuators: {unit: rev}\n"),
            "cal.yaml:4:12: actuators: missing required key 'lead'");
  EXPECT_EQ(error_of(base + "actuators: {unit: mm, lead: 0.005}\n"),
            "cal.yaml:4:29: actuators.lead: no lead unless unit: rev");
  EXPECT_EQ(error_of(base + "actuators: {unit: m, counts_per_metre: 1000}\n"),
            "cal.yaml:4:40: actuators.counts_per_metre: no counts_per_metre unless unit: counts");
  EXPECT_EQ(error_of(base + "actuators: {unit: mm, zero_length: [0.7, 0.7]}\n"),
            "cal.yaml:4:36: actuators.zero_length: expected a list of 6, found a list of 2");
  const std::string fixed = error_of(base + "actuators: {unit: mm}\nfixed: [a1.z, a7.x]\n");
  EXPECT_EQ(fixed.rfind("cal.yaml:5:15: fixed[1]: expected a parameter name (a1.x .. b6.z, ", 0),
            0u)
      << fixed;
  EXPECT_EQ(error_of(base + "actuators: {unit: mm}\ninstrument: {position: [0, 0, 1]}\n"),
            "cal.yaml:5:13: instrument: no instrument with frame: base (poses measured in the "
            "base frame); set frame: instrument");
  EXPECT_EQ(read_text(base + "actuators: {unit: rev, lead: 0.005, zero_length: 0.7}\n").lead,
            std::vector<double>{0.005});
  EXPECT_EQ(
      read_text(base + "actuators: {unit: rev, lead: [0.005, 0.005, 0.004, 0.005, 0.005, 0.006]}\n")
          .lead,
      (std::vector<double>{0.005, 0.005, 0.004, 0.005, 0.005, 0.006}));
  EXPECT_EQ(error_of(base + "actuators: {unit: rev, lead: [0.005, -1, 1, 1, 1, 1]}\n"),
            "cal.yaml:4:30: actuators.lead: expected screw leads > 0 (m/rev), found a list of 6");
  EXPECT_EQ(error_of(base + "actuators: {unit: mm}\ncolumns: {leg_1: length_1}\n"),
            "cal.yaml:5:18: columns.leg_1: expected a pkmopt column name (x, y, z, rx, ry, rz, "
            "qw, qx, qy, qz, q_1..q_6, campaign), found 'leg_1'");
  EXPECT_EQ(error_of(base + "actuators: {unit: mm}\nquaternion_order: zyxw\n"),
            "cal.yaml:5:19: quaternion_order: expected wxyz or xyzw, found 'zyxw'");
}

// Every key set to a value other than its default: written, read back, written again.
TEST(CalibrationFileFields, WriterAndReaderRoundTripEveryKey) {
  pkmopt::CalibrationFile c;
  c.machine = "machines/nominal.yaml";
  c.measurements = "data/measurements.csv";
  c.frame = "instrument";
  c.instrument_position = {1.25, -0.5, 0.1};
  c.instrument_angles_deg = {0.1, 0.2, 1.0 / 3.0};
  c.target_position = {0.01, 0.02, 0.03};
  c.target_angles_deg = {5, -5, 90};
  c.unit = "counts";
  c.counts_per_metre = 1e6 / 3.0;
  c.zero_length = {0.7, 0.71, 0.72, 0.73, 0.74, 0.1 + 0.2};
  c.noise_position = 1.9973118650304625e-05;
  c.noise_orientation_deg = 0.003;
  c.noise_actuator = 7;
  c.model = "42";
  c.fixed = {"a1.z", "gain3", "target.rz"};
  c.gauge = "none";
  c.loss = pkmopt::CalibrationLoss::kCauchy;
  c.loss_scale = 2.5;
  c.outlier_chi2 = 16.81;
  c.max_iterations = 50;
  c.correlation_threshold = 0.95;
  c.length_scale = 2e-3;
  c.gain_scale = 1e-4;
  c.frame_position_scale = 1e-2;
  c.frame_angle_scale_deg = 0.1;
  c.every = 3;
  c.rows = {1, 5, 8};
  c.noise_estimate = false;
  c.max_rejected_share = 0.5;
  c.pose_unit = "mm";
  c.quaternion_order = "xyzw";
  c.columns = {{"q_1", "leg length 1"}, {"x", "pos_x"}};
  const std::string yaml = pkmopt::calibration_file_yaml(c);
  const pkmopt::CalibrationFile back = read_text(yaml);
  EXPECT_EQ(pkmopt::calibration_file_yaml(back), yaml);
  EXPECT_EQ(back.machine, c.machine);
  EXPECT_EQ(back.instrument_angles_deg, c.instrument_angles_deg);
  EXPECT_EQ(back.counts_per_metre, c.counts_per_metre);
  EXPECT_EQ(back.zero_length, c.zero_length);
  EXPECT_EQ(back.noise_position, c.noise_position);
  EXPECT_EQ(back.loss, c.loss);
  EXPECT_EQ(back.frame_angle_scale_deg, c.frame_angle_scale_deg);
  EXPECT_EQ(back.fixed, c.fixed);
  EXPECT_EQ(back.rows, c.rows);
  EXPECT_EQ(back.noise_estimate, c.noise_estimate);
  EXPECT_EQ(back.max_rejected_share, c.max_rejected_share);
  EXPECT_EQ(back.pose_unit, c.pose_unit);
  EXPECT_EQ(back.quaternion_order, c.quaternion_order);
  EXPECT_EQ(back.columns, c.columns);
  for (const char* key : {"instrument:", "target:", "counts_per_metre:", "fixed:", "gauge: none",
                          "outlier_chi2:", "max_iterations:", "correlation_threshold:",
                          "parameter_scale:", "frame_angle_deg:", "rows: [1, 5, 8]"}) {
    EXPECT_NE(yaml.find(key), std::string::npos) << key << " in\n" << yaml;
  }
}

// Keys at their defaults and keys not given are left out; frame, model, gauge and loss are not.
TEST(CalibrationFileFields, WriterLeavesOutDefaults) {
  pkmopt::CalibrationFile c = read_text(kMinimal);
  EXPECT_EQ(pkmopt::calibration_file_yaml(c),
            "machine: nominal.yaml\n"
            "measurements: measurements.csv\n"
            "frame: base\n"
            "actuators: {unit: mm}\n"
            "noise: {position: 2e-05, orientation_deg: 0.003, actuator: 0.001}\n"
            "model: 48\n"
            "gauge: auto\n"
            "loss: {type: huber, scale: 5}\n");
  c.zero_length = {0.7};
  c.target_angles_deg = {0, 0, 30};
  const std::string yaml = pkmopt::calibration_file_yaml(c);
  EXPECT_NE(yaml.find("target: {angles_deg: [0, 0, 30]}\n"), std::string::npos) << yaml;
  EXPECT_NE(yaml.find("actuators: {unit: mm, zero_length: 0.7}\n"), std::string::npos) << yaml;
}

}  // namespace
