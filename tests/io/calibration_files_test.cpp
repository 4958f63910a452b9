// read_calibration_machine and fitted_measurements (io/calibration_files.hpp).
#include "io/calibration_files.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "io/input_error.hpp"
#include "models/sample_machines.hpp"

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

}  // namespace
