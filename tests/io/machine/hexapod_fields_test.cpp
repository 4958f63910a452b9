// Tests of io/machine/hexapod_fields.hpp: the hexapod's leg stiffness, joints, tool and actuator
// error, one list for the machine file and the design study's machine section.
#include "io/machine/hexapod_fields.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>

#include "io/format/input_error.hpp"

namespace pkmopt {
namespace {

struct Sample {
  LegStiffness stiffness;
  HexapodJointLimits joints;
  Eigen::Vector3d tcp = Eigen::Vector3d::Zero();
  double actuator_error = 1e-5;
};

template <class Fields>
void describe_fields(Fields& f, Sample& s) {
  f.section("legs", {.required = true}, [&](auto& g) { describe_leg_stiffness(g, s.stiffness); });
  f.section("joints", {}, [&](auto& g) { describe_hexapod_joints(g, s.joints); });
  f.section("tool", {}, [&](auto& g) { describe_hexapod_tool(g, s.tcp); });
  describe_actuator_error(f, s.actuator_error);
}

// Reads `yaml` with the list and the checks that follow it; "" or the InputError message.
std::string error_of(const std::string& yaml, Sample* out = nullptr) {
  try {
    const YamlValue root = YamlValue::load_string(yaml, "h.yaml");
    Sample s;
    read_fields(root, s);
    check_leg_stiffness(root.required("legs"), s.stiffness);
    normalize_joint_axes(root, s.joints);
    if (out) *out = s;
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(HexapodFields, ReadsStiffnessJointsToolAndNormalisesAxes) {
  Sample s;
  ASSERT_EQ(error_of("{legs: {E: 2.1e11, area: 3e-4, actuator_stiffness: 2e8}, joints: "
                     "{base_max_angle_deg: 45, base_axis: [0, 0, 2]}, tool: {tcp: [0, 0, -0.1]}, "
                     "actuator_error: 2e-5}",
                     &s),
            "");
  EXPECT_EQ(s.stiffness.E, 2.1e11);
  EXPECT_EQ(s.stiffness.area, 3e-4);
  EXPECT_EQ(s.stiffness.actuator_stiffness, 2e8);
  EXPECT_DOUBLE_EQ(s.joints.base_max_angle, std::numbers::pi / 4);
  EXPECT_TRUE(std::isinf(s.joints.platform_max_angle));
  EXPECT_EQ(s.joints.base_axis, Eigen::Vector3d(0, 0, 1));
  EXPECT_EQ(s.tcp, Eigen::Vector3d(0, 0, -0.1));
  EXPECT_EQ(s.actuator_error, 2e-5);
}

TEST(HexapodFields, LegStiffnessIsEitherAxialOrEAndArea) {
  EXPECT_EQ(error_of("{legs: {axial_stiffness: 1e8, E: 2e11}}"),
            "h.yaml:1:26: legs.axial_stiffness: either axial_stiffness or E and area, not both");
  EXPECT_EQ(error_of("{legs: {}}"),
            "h.yaml:1:8: legs: missing the leg stiffness: give axial_stiffness (N/m), or E (Pa) "
            "and area (m^2), or the drive train")
      << "the message names what is missing";
  EXPECT_EQ(error_of("{legs: {actuator_stiffness: 1e8}}"), "") << "a lumped actuator is a leg";
  Sample s;
  ASSERT_EQ(error_of("{legs: {drive: {E: 2.1e11, root_diameter: 0.025, free_length_at_min: 0.1, "
                     "free_length_at_max: 0.5, nut_stiffness: 6e8, torsional_stiffness: 3000, "
                     "lead: 0.01}, base_joint_stiffness: 4e8}}",
                     &s),
            "");
  EXPECT_EQ(s.stiffness.drive.root_diameter, 0.025);
  EXPECT_EQ(s.stiffness.drive.lead, 0.01);
  EXPECT_EQ(s.stiffness.base_joint_stiffness, 4e8);
  EXPECT_EQ(error_of("{legs: {drive: {torsional_stiffness: 3000}}}"),
            "h.yaml:1:16: legs.drive: the motor torsion acts through the lead: give "
            "torsional_stiffness and lead together");
  EXPECT_NE(error_of("{legs: {E: 2e11}}").find("legs: missing required key 'area'"),
            std::string::npos)
      << error_of("{legs: {E: 2e11}}");
  EXPECT_EQ(error_of("{legs: {axial_stiffness: 1e8}, joints: {platform_axis: [0, 0, 0]}}"),
            "h.yaml:1:56: joints.platform_axis: expected a non-zero vector, found a list of 3");
  EXPECT_EQ(error_of("{legs: {axial_stiffness: 1e8}, joints: {base_max_angle_deg: 0}}"),
            "h.yaml:1:61: joints.base_max_angle_deg: expected an angle in degrees in (0, 180], "
            "found '0'");
}

TEST(HexapodFields, WriterLeavesUnsetKeysAndDefaultAxesOut) {
  Sample s;
  s.stiffness.axial_stiffness = 1e8;
  s.stiffness.E = 2e11;  // not written: the constant stiffness is used
  FieldWriter writer;
  describe_fields(writer, s);
  EXPECT_EQ(writer.flow_lines(),
            "legs: {axial_stiffness: 100000000}\ntool: {tcp: [0, 0, 0]}\nactuator_error: 1e-05\n");
  s.joints.platform_axis = Eigen::Vector3d(0, 1, 0);
  s.joints.base_max_angle = 60 * (std::numbers::pi / 180);  // as read from "60"
  FieldWriter with_axes;
  describe_fields(with_axes, s);
  EXPECT_NE(with_axes.flow_lines().find("joints: {base_max_angle_deg: 60, base_axis: [0, 0, 1], "
                                        "platform_axis: [0, 1, 0]}"),
            std::string::npos)
      << with_axes.flow_lines();
}

}  // namespace
}  // namespace pkmopt
