// Tests of io/machine/machine_file_serial: the serial axes of a coordinate code read into a
// machine description (drives, degrees of freedom, details), the spindle rule, and the errors.
// `pkmopt describe` on whole serial files is tested in machine_description_test.cpp.
#include "io/machine/machine_file_serial.hpp"

#include <gtest/gtest.h>

#include <string>

#include "io/format/input_error.hpp"

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

}  // namespace
}  // namespace pkmopt
