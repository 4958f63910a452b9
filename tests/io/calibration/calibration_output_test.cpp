// The files of the calibration commands (io/calibration/calibration_output.hpp): exact text for
// hand-made inputs, and the measurement CSV read back by read_measurement_csv.
#include "io/calibration/calibration_output.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "io/machine/machine_file.hpp"
#include "models/sample_machines.hpp"
#include "tests/scratch_dir.hpp"

namespace {

namespace fs = std::filesystem;
using pkmopt::CalibrationMeasurement;

std::vector<CalibrationMeasurement> two_measurements() {
  CalibrationMeasurement a;
  a.pose.position = {0.1, -0.05, 0.85};
  a.stroke << 0.5, 0.75, 1.0, 0.625, 0.875, 0.25;
  CalibrationMeasurement b;
  b.pose.position = {0, 0, 0.9};
  b.pose.angles = {pkmopt::deg_to_rad(2.0), 0, 0};
  b.stroke << 0.5, 0.5, 0.5, 0.5, 0.5, 0.5;
  return {a, b};
}

TEST(MeasurementCsv, ReadingsInTheActuatorUnit) {
  const std::string csv = pkmopt::measurement_csv({two_measurements()[0]}, 1e-3);
  EXPECT_EQ(csv,
            "x,y,z,rx,ry,rz,q_1,q_2,q_3,q_4,q_5,q_6\n"
            "0.1,-0.05,0.85,0,0,0,500,750,1000,625,875,250\n");
}

TEST(MeasurementCsv, ReadsBackTheSameMeasurements) {
  const scratch::ScratchDir dir;
  const fs::path file =
      dir.write("measurements.csv", pkmopt::measurement_csv(two_measurements(), 1e-3));
  const auto back = pkmopt::read_measurement_csv(file.string(), 1e-3);
  const auto original = two_measurements();
  ASSERT_EQ(back.size(), 2u);
  for (std::size_t k = 0; k < 2; ++k) {
    EXPECT_EQ(back[k].pose.position, original[k].pose.position);
    EXPECT_NEAR((back[k].pose.angles - original[k].pose.angles).norm(), 0.0, 1e-15);
    EXPECT_NEAR((back[k].stroke - original[k].stroke).norm(), 0.0, 1e-15);
  }
}

TEST(SimulatedCalibrationYaml, FloorsTheNoiseAndTheHoldout) {
  pkmopt::SimulationFileSettings s;
  s.seed = 7;
  s.unit = "mm";
  s.zero_length = 0.7;
  s.orientation_sigma_deg = 0.0;  // floored to 1e-9
  s.actuator_sigma = 1e-6;        // 0.001 mm
  s.model = "42";
  s.holdout_every = 1;  // at least every 2nd row
  EXPECT_EQ(pkmopt::simulated_calibration_yaml(s, 2e-5),
            "# Calibration of simulated measurements (pkmopt simulate-measurements --seed 7).\n"
            "machine: nominal.yaml\n"
            "measurements: measurements.csv\n"
            "frame: base\n"
            "actuators: {unit: mm, zero_length: 0.7}\n"
            "noise: {position: 2e-05, orientation_deg: 1e-09, actuator: 0.001}\n"
            "model: 42\n"
            "gauge: auto\n"
            "loss: {type: huber, scale: 5}\n"
            "validation: {every: 2}\n");
  s.unit = "m";
  s.holdout_every = 5;
  const std::string in_metres = pkmopt::simulated_calibration_yaml(s, 0.0);
  EXPECT_NE(in_metres.find("noise: {position: 1e-09, orientation_deg: 1e-09, actuator: 1e-06}"),
            std::string::npos)
      << in_metres;
  EXPECT_NE(in_metres.find("validation: {every: 5}\n"), std::string::npos);
  EXPECT_EQ(pkmopt::reading_unit_scale(s), 1.0);
}

pkmopt::SimulatedMeasurements simulated() {
  pkmopt::SimulatedMeasurements data;
  const auto design = pkmopt::sample_machines::conventions_hexapod_design();
  data.truth = pkmopt::nominal_calibration_vector(design, pkmopt::Vec6<double>::Constant(0.7));
  data.measurements = two_measurements();
  data.outliers = {0, 4};
  data.mean_position_sigma = 1.5e-5;
  return data;
}

TEST(SimulationTruthJson, SeedOutlierRowsAndEveryParameter) {
  const pkmopt::SimulatedMeasurements data = simulated();
  const auto j = nlohmann::json::parse(pkmopt::simulation_truth_json(11, data));
  EXPECT_EQ(j["seed"], 11);
  EXPECT_EQ(j["outlier_rows"], nlohmann::json::parse("[1, 5]"));  // 1-based rows
  ASSERT_EQ(j["parameters"].size(),
            static_cast<std::size_t>(pkmopt::kCalibrationMachineParameters));
  for (int i = 0; i < pkmopt::kCalibrationMachineParameters; ++i) {
    EXPECT_EQ(j["parameters"][pkmopt::calibration_parameter_name(i)], data.truth(i)) << i;
  }
  EXPECT_EQ(j["mean_position_sigma"], 1.5e-5);
}

TEST(SimulatedMeasurementFiles, NamesAndContents) {
  const auto design = pkmopt::sample_machines::conventions_hexapod_design();
  const pkmopt::SimulatedMeasurements data = simulated();
  pkmopt::SimulationFileSettings s;
  s.seed = 3;
  const auto files = pkmopt::simulated_measurement_files(design, data, s);
  std::vector<std::string> names;
  for (const auto& [name, bytes] : files) names.push_back(name);
  EXPECT_EQ(names, (std::vector<std::string>{"measurements.csv", "nominal.yaml", "truth.yaml",
                                             "truth.json", "calibration.yaml"}));
  EXPECT_EQ(files[0].second, pkmopt::measurement_csv(data.measurements, 1e-3));  // default mm
  EXPECT_EQ(files[1].second, pkmopt::hexapod_design_to_yaml(design));
  EXPECT_EQ(files[2].second.rfind("# The true machine the measurements were drawn from.\n", 0), 0u);
  EXPECT_EQ(files[3].second, pkmopt::simulation_truth_json(3, data));
  EXPECT_EQ(files[4].second, pkmopt::simulated_calibration_yaml(s, 1.5e-5));
}

TEST(CalibratedMachineYaml, CommentThenTheCalibratedMachine) {
  pkmopt::CalibrationSetup setup;
  setup.file = "cal/calibration.yaml";
  setup.unit_scale = 1e-3;
  setup.nominal_design = pkmopt::sample_machines::conventions_hexapod_design();
  pkmopt::CalibrationResult result;
  result.estimate =
      pkmopt::nominal_calibration_vector(setup.nominal_design, pkmopt::Vec6<double>::Constant(0.7));
  result.estimate(0) += 1e-3;  // base joint 1 moved by 1 mm
  const std::string yaml = pkmopt::calibrated_machine_yaml(setup, result);
  const std::string comment =
      "# Calibrated by pkmopt calibrate cal/calibration.yaml.\n"
      "# Leg offsets (leg length at reading 0, m) and gain errors are in report.json: leg length "
      "= offset + (1 + gain) * reading * 0.001 m.\n";
  ASSERT_EQ(yaml.rfind(comment, 0), 0u) << yaml;
  EXPECT_EQ(yaml.substr(comment.size()), pkmopt::hexapod_design_to_yaml(pkmopt::calibrated_design(
                                             setup.nominal_design, result.estimate)));
  EXPECT_NE(yaml.substr(comment.size()), pkmopt::hexapod_design_to_yaml(setup.nominal_design));
}

TEST(SelectedPosesCsv, ChosenRowsWithTheirLabels) {
  pkmopt::CalibrationCandidates c;
  c.poses.resize(3);
  c.poses[0].position = {0.1, 0, 0.8};
  c.poses[1].position = {0, 0.1, 0.8};
  c.poses[2].position = {-0.1, 0, 0.9};
  c.labels = {7, 9, 12};
  pkmopt::PoseSelection selection;
  selection.selected = {0, 2};
  EXPECT_EQ(pkmopt::selected_poses_csv(c, selection),
            "x,y,z,rx,ry,rz,candidate\n"
            "0.1,0,0.8,0,0,0,7\n"
            "-0.1,0,0.9,0,0,0,12\n");
}

}  // namespace
