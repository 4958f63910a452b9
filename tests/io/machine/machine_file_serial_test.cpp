// Tests of io/machine/machine_file_serial: the serial axes of a coordinate code read into a
// machine description (drives, degrees of freedom, details), the spindle rule, and the errors;
// the machine of a 5-axis file (units per axis: degrees for rotary values, metres for linear
// ones) and every refusal with its file, line, column and key.
// `pkmopt describe` on whole serial files is tested in machine_description_test.cpp.
#include "io/machine/machine_file_serial.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>

#include "io/format/input_error.hpp"
#include "io/machine/machine_file.hpp"

namespace pkmopt {
namespace {

YamlValue yaml(const std::string& text) { return YamlValue::load_string(text, "s.yaml"); }

TEST(MachineFileSerial, TheSpindleIsNotAFeedDrive) {
  MachineDescription d;
  const int axes = describe_serial_axes(
      yaml("{code: \"641236\", axes: [C, A, X, Y, Z, S], spindle: S}"), true, d);
  EXPECT_EQ(axes, 6);
  EXPECT_EQ(d.serial_drives, 5);
  EXPECT_EQ(d.translations, 3);
  EXPECT_EQ(d.rotations, 2);
  ASSERT_EQ(d.details.size(), 2u);
  EXPECT_EQ(d.details[0], "code: 641236");
  EXPECT_EQ(d.details[1], "axes: C(6) A(4) X(1) Y(2) Z(3) S(6, spindle)");
}

TEST(MachineFileSerial, AxesAreNamedQ1ToQnByDefaultAndFixedMotionsShowTheirValue) {
  MachineDescription d;
  EXPECT_EQ(describe_serial_axes(yaml("{code: \"12\"}"), false, d), 2);
  EXPECT_EQ(d.serial_drives, 2);
  EXPECT_EQ(d.translations, 2);
  EXPECT_EQ(d.rotations, 0);
  EXPECT_EQ(d.details[1], "axes: q1(1) q2(2)");
}

TEST(MachineFileSerial, BadAxesAndSpindlesNameTheKey) {
  const auto error = [](const std::string& text) {
    MachineDescription d;
    try {
      describe_serial_axes(yaml(text), true, d);
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(error("{code: \"12\", axes: [X, X]}").find("distinct axis names"), std::string::npos);
  EXPECT_NE(error("{code: \"12\", axes: [X, Y], spindle: Z}").find("one of the names in 'axes'"),
            std::string::npos);
  EXPECT_NE(
      error("{code: \"12\", axes: [X, Y], spindle: Y}").find("a rotary axis (motion 4, 5 or 6)"),
      std::string::npos);
}

constexpr const char* kFile =
    "model: serial\n"
    "code: \"641236\"\n"
    "axes: [C, A, X, Y, Z, S]\n"
    "spindle: S\n"
    "range: [[-360, 360], [-120, 30], [-0.4, 0.4], [-0.4, 0.4], [-0.2, 0.5]]\n"
    "stiffness: [1.0e6, 2.0e6, 1.5e8, 1.5e8, 1.2e8]\n"
    "error: [0.0014, 0.0014, 5.0e-6, 5.0e-6, 5.0e-6]\n"
    "tool: [0, 0, 0.1]\n";

std::string replace(std::string text, const std::string& from, const std::string& to) {
  const auto at = text.find(from);
  if (at == std::string::npos) return "'" + from + "' not in the file";
  return text.replace(at, from.size(), to);
}

std::string load_error(const std::string& text) {
  try {
    (void)load_machine(yaml(text));
  } catch (const InputError& e) {
    return e.what();
  }
  return "no error";
}

TEST(MachineFileSerial, AFiveAxisFileIsAMachineWithItsUnitsPerAxis) {
  const SerialDesign d = read_serial_design(yaml(kFile));
  constexpr double kDeg = std::numbers::pi / 180.0;
  ASSERT_EQ(d.axes.size(), 5u);
  EXPECT_EQ(d.spindle, 5);
  EXPECT_DOUBLE_EQ(d.axes[0].min, -360 * kDeg);
  EXPECT_DOUBLE_EQ(d.axes[1].max, 30 * kDeg);
  EXPECT_DOUBLE_EQ(d.axes[1].error, 0.0014 * kDeg);
  EXPECT_DOUBLE_EQ(d.axes[2].min, -0.4);
  EXPECT_DOUBLE_EQ(d.axes[4].max, 0.5);
  EXPECT_DOUBLE_EQ(d.axes[3].stiffness, 1.5e8);
  EXPECT_DOUBLE_EQ(d.axes[4].error, 5e-6);
  EXPECT_EQ(d.tool_point, Eigen::Vector3d(0, 0, 0.1));
  EXPECT_EQ(d.tool_axis, Eigen::Vector3d::UnitZ());
  EXPECT_EQ(d.chain.elements()[1].name, "A");
  const std::unique_ptr<Machine> machine = load_machine(yaml(kFile));
  EXPECT_EQ(machine->model(), "serial");
  EXPECT_EQ(machine->num_actuators(), 5);
  EXPECT_TRUE(machine->revolute_actuator(1));
  EXPECT_FALSE(machine->revolute_actuator(2));
  // A constant rotation in a code is in degrees too.
  const SerialDesign tilted =
      read_serial_design(yaml(replace(kFile, "\"641236\"", "\"6 4 1 2 3 5:45 6\"")));
  EXPECT_DOUBLE_EQ(tilted.chain.elements()[5].value, 45 * kDeg);
}

TEST(MachineFileSerial, BadFilesNameTheKey) {
  EXPECT_EQ(load_error(replace(kFile, "[-120, 30]", "[30, -120]")),
            "s.yaml:5:22: range[1]: expected [min, max] with min <= max (deg), found [30, -120]");
  EXPECT_EQ(load_error(replace(kFile, "[-0.4, 0.4], [-0.2", "[-0.4, 4000], [-0.2")),
            "s.yaml:5:54: range[3][1]: expected a length within +-1000 m, found '4000'");
  EXPECT_NE(load_error(replace(kFile, "1.2e8]", "-1.2e8]")).find("s.yaml:6:"), std::string::npos);
  EXPECT_NE(load_error(replace(kFile, "stiffness: [1.0e6, ", "stiffness: [")).find("stiffness"),
            std::string::npos);
  EXPECT_NE(load_error(replace(kFile, "tool: [0, 0, 0.1]", "tool_axis: [0, 0, 0]"))
                .find("tool_axis: expected a nonzero direction"),
            std::string::npos);
  EXPECT_NE(
      load_error(replace(kFile, "tool: [0, 0, 0.1]", "toolpoint: [0, 0, 0.1]")).find("toolpoint"),
      std::string::npos);
  EXPECT_NE(load_error(replace(kFile, "tool: [0, 0, 0.1]", "characteristic_length: 0"))
                .find("characteristic_length"),
            std::string::npos);
  // Two rotary axes that are parallel: the model's own check, at the code.
  EXPECT_NE(load_error(replace(replace(kFile, "\"641236\"", "\"661236\""), "spindle: S\n", ""))
                .find("s.yaml:2:7: code:"),
            std::string::npos);
  EXPECT_EQ(load_error(replace(kFile, "range: [[-360, 360], ", "range: [")),
            "s.yaml:5:8: range: expected a list of 5, found a list of 4");
}

}  // namespace
}  // namespace pkmopt
