// read_calibration_machine, fitted_measurements and the calibration YAML's field list
// (read_calibration_file, calibration_file_yaml, the docs table;
// io/calibration/calibration_files.hpp).
#include "io/calibration/calibration_files.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "io/format/input_error.hpp"
#include "models/sample_machines.hpp"
#include "tests/scratch_dir.hpp"

namespace {

std::string example(const std::string& name) {
  return (std::filesystem::path(PKMOPT_SOURCE_DIR) / "examples" / name).string();
}

TEST(ReadCalibrationMachine, ReadsAHexapodMachineFile) {
  // examples/hexapod.yaml is the docs/conventions.md hexapod.
  const pkmopt::HexapodDesign d = pkmopt::read_calibration_machine(example("hexapod.yaml"));
  const pkmopt::HexapodDesign expected = pkmopt::sample_machines::conventions_hexapod_design();
  EXPECT_NEAR((d.base_joints - expected.base_joints).norm(), 0.0, 1e-9);
  EXPECT_NEAR((d.platform_joints - expected.platform_joints).norm(), 0.0, 1e-9);
  EXPECT_EQ(d.min_length, 0.70);
  EXPECT_EQ(d.max_length, 1.15);
  EXPECT_EQ(d.tcp, expected.tcp);
}

TEST(ReadCalibrationMachine, OtherModelsAreRefused) {
  try {
    pkmopt::read_calibration_machine(example("delta.yaml"));
    FAIL() << "expected InputError";
  } catch (const pkmopt::InputError& e) {
    const std::string message = e.what();
    EXPECT_EQ(message.rfind(example("delta.yaml") + ":", 0), 0u) << message;
    EXPECT_NE(message.find("expected 'hexapod' (calibration)"), std::string::npos) << message;
  }
}

TEST(FittedMeasurements, TheFitRowsInOrder) {
  pkmopt::CalibrationSetup setup;
  for (int line = 2; line <= 6; ++line) {
    pkmopt::CalibrationMeasurement m;
    m.line = line;
    setup.measurements.push_back(m);
  }
  setup.fit = {0, 2, 3};
  setup.held_out = {1, 4};
  const auto fitted = pkmopt::fitted_measurements(setup);
  ASSERT_EQ(fitted.size(), 3u);
  EXPECT_EQ(fitted[0].line, 2);
  EXPECT_EQ(fitted[1].line, 4);
  EXPECT_EQ(fitted[2].line, 5);
}

class CalibrationSetupFile : public scratch::ScratchDirTest {
 protected:
  // A calibration YAML with `body` next to examples/hexapod.yaml and a 20-pose CSV.
  std::string setup_file(const std::string& name, const std::string& body) {
    std::string csv = "x,y,z,rx,ry,rz,q_1,q_2,q_3,q_4,q_5,q_6\n";
    for (int k = 0; k < 20; ++k)
      csv += "0,0," + std::to_string(0.8 + 0.01 * k) + ",1,2,3,0.9,0.9,0.9,0.9,0.9,0.9\n";
    write("measurements.csv", csv);
    return write(
        name, "machine: " + example("hexapod.yaml") + "\nmeasurements: measurements.csv\n" + body);
  }
};

TEST_F(CalibrationSetupFile, ValidationRowOutsideTheDataIsAnError) {
  const std::string file = setup_file("cal.yaml",
                                      "actuators: {unit: m}\n"
                                      "noise: {position: 2.0e-5, orientation_deg: 0.003, "
                                      "actuator: 1e-6}\n"
                                      "validation: {rows: [2, 21]}\n");
  try {
    pkmopt::read_calibration_setup(file);
    FAIL() << "expected InputError";
  } catch (const pkmopt::InputError& e) {
    EXPECT_EQ(std::string(e.what()),
              file + ":5:24: validation.rows[1]: expected a data row number in 1..20, found '21'");
  }
}

// An unknown measurement column: the message offers the other orientation form than the file's.
TEST_F(CalibrationSetupFile, UnknownColumnOffersTheOtherOrientationForm) {
  auto message = [&](const std::string& header) {
    write("m.csv", header + "\n0,0,0.9,1,0,0,0,0.9,0.9,0.9,0.9,0.9,0.9,7\n");
    try {
      pkmopt::read_measurement_csv(path("m.csv"), 1.0);
    } catch (const pkmopt::InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  const std::string euler = message("x,y,z,rx,ry,rz,w,q_1,q_2,q_3,q_4,q_5,q_6,extra");
  EXPECT_NE(euler.find("column 7 'w': expected only the columns x,y,z,rx,ry,rz,q_1,q_2,q_3,q_4,"
                       "q_5,q_6 (or qw,qx,qy,qz instead of rx,ry,rz)"),
            std::string::npos)
      << euler;
  const std::string quaternion = message("x,y,z,qw,qx,qy,qz,q_1,q_2,q_3,q_4,q_5,q_6,extra");
  EXPECT_NE(quaternion.find("column 14 'extra': expected only the columns x,y,z,qw,qx,qy,qz,q_1,"
                            "q_2,q_3,q_4,q_5,q_6 (or rx,ry,rz instead of qw,qx,qy,qz)"),
            std::string::npos)
      << quaternion;
}

// columns: renames by the file's own names, all at once (a swap works in any key order), and
// refuses two columns of one name; quaternion_order needs quaternion columns.
TEST_F(CalibrationSetupFile, ColumnsRenameAtOnceAndRefuseCollisions) {
  write("m.csv",
        "x,y,z,rx,ry,rz,q_1,q_2,q_3,q_4,q_5,q_6,X\n0,0,0.9,1,2,3,0.1,0.2,0.3,0.4,0.5,0.6,7\n");
  for (const auto& order :
       {std::vector<std::pair<std::string, std::string>>{{"q_1", "q_2"}, {"q_2", "q_1"}},
        std::vector<std::pair<std::string, std::string>>{{"q_2", "q_1"}, {"q_1", "q_2"}}}) {
    pkmopt::MeasurementFormat format;
    format.columns = order;
    format.columns.emplace_back("z", "X");
    format.columns.emplace_back("campaign", "z");  // keeps the file's z as a campaign label
    const auto m = pkmopt::read_measurement_csv(path("m.csv"), format, nullptr);
    ASSERT_EQ(m.size(), 1u);
    EXPECT_EQ(m[0].stroke(0), 0.2);
    EXPECT_EQ(m[0].stroke(1), 0.1);
    EXPECT_EQ(m[0].pose.position(2), 7.0);
  }
  pkmopt::MeasurementFormat collide;
  collide.columns = {{"x", "X"}};
  try {
    pkmopt::read_measurement_csv(path("m.csv"), collide, nullptr);
    FAIL() << "expected InputError";
  } catch (const pkmopt::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("columns: expected one column named 'x', found two"),
              std::string::npos)
        << e.what();
  }
  pkmopt::MeasurementFormat order;
  order.quaternion_order = "xyzw";
  order.columns = {{"q_1", "X"}, {"campaign", "q_1"}};
  EXPECT_THROW(pkmopt::read_measurement_csv(path("m.csv"), order, nullptr), pkmopt::InputError);
}

// The written file of a setup's keys loads to the same setup.
TEST_F(CalibrationSetupFile, WrittenKeysLoadToTheSameSetup) {
  const std::string file = setup_file(
      "cal.yaml",
      "target: {position: [0.001, 0, -0.002], angles_deg: [0.5, 0, 0.1]}\n"
      "actuators: {unit: rev, lead: 0.005, zero_length: [0.7, 0.7, 0.71, 0.7, 0.7, 0.7]}\n"
      "noise: {position: 1.5e-5, orientation_deg: 0.002, actuator: 0.0001}\n"
      "model: 42\n"
      "fixed: [a2.z]\n"
      "loss: {type: cauchy}\n"
      "outlier_chi2: 30\n"
      "max_iterations: 20\n"
      "correlation_threshold: 0.8\n"
      "parameter_scale: {length: 2e-3, frame_angle_deg: 0.1}\n"
      "validation: {every: 3, rows: [1]}\n");
  const pkmopt::CalibrationFile keys =
      pkmopt::read_calibration_file(pkmopt::YamlValue::load_file(file));
  const std::string rewritten = write("rewritten.yaml", pkmopt::calibration_file_yaml(keys));
  const pkmopt::CalibrationSetup a = pkmopt::read_calibration_setup(file);
  const pkmopt::CalibrationSetup b = pkmopt::read_calibration_setup(rewritten);
  EXPECT_EQ(a.nominal, b.nominal);
  EXPECT_EQ(a.frame, b.frame);
  EXPECT_EQ(a.unit_scale, b.unit_scale);
  EXPECT_EQ(a.model, b.model);
  EXPECT_EQ(a.fixed, b.fixed);
  EXPECT_EQ(a.gauge_fixed, b.gauge_fixed);
  EXPECT_EQ(a.options.free, b.options.free);
  EXPECT_EQ(a.options.sigma_position, b.options.sigma_position);
  EXPECT_EQ(a.options.sigma_orientation, b.options.sigma_orientation);
  EXPECT_EQ(a.options.sigma_actuator, b.options.sigma_actuator);
  EXPECT_EQ(a.options.loss, b.options.loss);
  EXPECT_EQ(a.options.loss_scale, b.options.loss_scale);
  EXPECT_EQ(a.options.outlier_chi2, b.options.outlier_chi2);
  EXPECT_EQ(a.options.max_iterations, b.options.max_iterations);
  EXPECT_EQ(a.options.correlation_threshold, b.options.correlation_threshold);
  EXPECT_EQ(a.options.parameter_scale, b.options.parameter_scale);
  EXPECT_EQ(a.fit, b.fit);
  EXPECT_EQ(a.held_out, b.held_out);
  EXPECT_EQ(a.held_out, (std::vector<int>{0, 2, 5, 8, 11, 14, 17}));
  EXPECT_EQ(a.options.max_iterations, 20);
  EXPECT_EQ(a.options.sigma_actuator, 0.0001 * 0.005);
}

}  // namespace
