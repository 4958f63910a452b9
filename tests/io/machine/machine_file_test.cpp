// Tests of io/machine/machine_file: the hexapod file form of docs/conventions.md and its strict
// errors.
#include "io/machine/machine_file.hpp"

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <string>

#include "tests/sample_machines.hpp"

namespace pkmopt {
namespace {

const char* kGood = R"(model: hexapod
base: {radius: 0.60, pair_separation_deg: 20}
platform: {radius: 0.25, pair_separation_deg: 20}
legs: {min_length: 0.70, max_length: 1.15, E: 2.1e11, area: 3.0e-4, actuator_stiffness: 2.0e8}
joints: {base_max_angle_deg: 45, platform_max_angle_deg: 45}
tool: {tcp: [0, 0, -0.10]}
)";

std::string error_of(const std::string& text) {
  try {
    read_hexapod_design(YamlValue::load_string(text, "m.yaml"));
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

std::string replace(std::string text, const std::string& from, const std::string& to) {
  text.replace(text.find(from), from.size(), to);
  return text;
}

TEST(MachineFile, ReadsTheConventionsExample) {
  const HexapodDesign d = read_hexapod_design(YamlValue::load_string(kGood, "m.yaml"));
  const HexapodDesign expected = sample_machines::conventions_hexapod_design();
  EXPECT_LT((d.base_joints - expected.base_joints).norm(), 1e-15);
  EXPECT_LT((d.platform_joints - expected.platform_joints).norm(), 1e-15);
  EXPECT_EQ(d.min_length, 0.70);
  EXPECT_EQ(d.stiffness.actuator_stiffness, 2.0e8);
  EXPECT_NEAR(d.joints.base_max_angle, deg_to_rad(45), 1e-15);
  EXPECT_EQ(d.tcp, Eigen::Vector3d(0, 0, -0.10));
  EXPECT_FALSE(d.characteristic_length.has_value());
  EXPECT_EQ(d.actuator_error, 1e-5);
}

TEST(MachineFile, WrittenDesignReadsBackExactly) {
  sample_machines::Uniform u(1);
  for (int k = 0; k < 10; ++k) {
    HexapodDesign d = sample_machines::random_hexapod_design(u);
    d.joints.base_max_angle = deg_to_rad(u(10, 80));
    if (k % 2) d.characteristic_length = u(0.1, 0.4);
    const HexapodDesign back =
        read_hexapod_design(YamlValue::load_string(hexapod_design_to_yaml(d), "w.yaml"));
    EXPECT_EQ(back.base_joints, d.base_joints);
    EXPECT_EQ(back.platform_joints, d.platform_joints);
    EXPECT_EQ(back.min_length, d.min_length);
    EXPECT_EQ(back.max_length, d.max_length);
    EXPECT_EQ(back.stiffness.E, d.stiffness.E);
    EXPECT_EQ(back.stiffness.axial_stiffness, d.stiffness.axial_stiffness);
    EXPECT_EQ(back.tcp, d.tcp);
    EXPECT_EQ(back.characteristic_length, d.characteristic_length);
    EXPECT_EQ(back.actuator_error, d.actuator_error);
    EXPECT_NEAR(back.joints.base_max_angle, d.joints.base_max_angle, 1e-15);
  }
}

TEST(MachineFile, ErrorsNameFileLineColumnKeyExpectedAndFound) {
  EXPECT_EQ(error_of(replace(kGood, "min_length: 0.70", "min_length: abc")),
            "m.yaml:4:20: legs.min_length: expected a finite number, found 'abc'");
  EXPECT_EQ(error_of(replace(kGood, "max_length: 1.15", "max_length: 0.5")),
            "m.yaml:4:38: legs.max_length: expected a number > legs.min_length (0.7), found '0.5'");
  EXPECT_EQ(
      error_of(replace(kGood, "tool:", "toll:")),
      "m.yaml:6:1: toll: unknown key 'toll'; allowed keys here: model, name, description, "
      "base, base_joints, platform, platform_joints, legs, min_clearance, bodies, joints, tool, "
      "characteristic_length, actuator_error, masses, gravity");
  EXPECT_EQ(error_of(replace(kGood, "E: 2.1e11", "E: .nan")),
            "m.yaml:4:47: legs.E: expected a finite number, found '.nan'");
  EXPECT_EQ(error_of(replace(kGood, "E: 2.1e11", "E: inf")),
            "m.yaml:4:47: legs.E: expected a finite number, found 'inf'");
  EXPECT_EQ(error_of(replace(kGood, "tcp: [0, 0, -0.10]", "tcp: [0, 0]")),
            "m.yaml:6:13: tool.tcp: expected a list of 3, found a list of 2");
  EXPECT_EQ(error_of(replace(kGood, "legs: {min_length: 0.70, ", "legs: {")),
            "m.yaml:4:7: legs: missing required key 'min_length'");
  EXPECT_EQ(error_of(replace(kGood, "actuator_stiffness: 2.0e8", "actuator_stiffness: -2")),
            "m.yaml:4:89: legs.actuator_stiffness: expected a number > 0, found '-2'");
  EXPECT_EQ(error_of("model: hexapod\nbase: {radius: 0.6, pair_separation_deg: 20}\n"
                     "platform_joints: [[0,0,0], [1,0,0]]\n"),
            "m.yaml:3:18: platform_joints: expected a list of 6, found a list of 2");
  EXPECT_EQ(error_of("model: hexapod\nbase: [1, 2\n"),
            "m.yaml:3:1: malformed YAML: end of sequence flow not found");
  EXPECT_NE(error_of(replace(kGood, "base: {", "base_joints: [[0,0,0]]\nbase: {"))
                .find("either 'base' or 'base_joints', not both"),
            std::string::npos);
  EXPECT_NE(error_of(replace(kGood, "E: 2.1e11, area: 3.0e-4, actuator_stiffness: 2.0e8", ""))
                .find("missing the leg stiffness"),
            std::string::npos);
  // A leg of actuator and drive train alone is a leg; a half-given screw is not.
  EXPECT_EQ(error_of(replace(kGood, "E: 2.1e11, area: 3.0e-4, ", "")), "");
  EXPECT_EQ(error_of(replace(kGood, "actuator_stiffness: 2.0e8",
                             "drive: {E: 2.1e11, free_length_at_min: 0.2}")),
            "m.yaml:4:76: legs.drive: the screw needs both E and root_diameter");
}

TEST(MachineFile, UnknownModelIsAnError) {
  try {
    load_machine(YamlValue::load_string("model: octopod\n", "m.yaml"));
    FAIL();
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(),
                 "m.yaml:1:8: model: expected a known model (hexapod, delta, linear_delta, "
                 "hexaglide, tripod_3prs, tripod_3rps, leg_chain, lathe_16k20f3, hybrid, serial), "
                 "found 'octopod'");
  }
  EXPECT_THROW(load_machine_file("/nonexistent/machine.yaml"), InputError);
}

}  // namespace
}  // namespace pkmopt

namespace pkmopt {
namespace {

// README.md carries the hexapod machine file's key table exactly as the field list generates
// it; the failure message shows the block to paste.
TEST(MachineFileFields, ReadmeTableMatchesTheFieldList) {
  std::ifstream in(std::string(PKMOPT_SOURCE_DIR) + "/README.md");
  std::stringstream readme;
  readme << in.rdbuf();
  const std::string block =
      "<!-- fields: hexapod -->\n" + hexapod_machine_fields_markdown() + "<!-- /fields -->\n";
  EXPECT_NE(readme.str().find(block), std::string::npos)
      << "README.md lacks the generated hexapod table:\n"
      << block;
}

// The writer and the reader come from one field list: a design with every optional key set
// (joint limits, custom axes, an actuator in series, L) is written and read back unchanged.
TEST(MachineFileFields, WriterAndReaderRoundTripEveryKey) {
  HexapodDesign d = semi_regular_hexapod(0.6, deg_to_rad(20), 0.25, deg_to_rad(30));
  d.min_length = 0.7;
  d.max_length = 1.15;
  d.stiffness.E = 2.1e11;
  d.stiffness.area = 3e-4;
  d.stiffness.actuator_stiffness = 2e8;
  d.joints.base_max_angle = deg_to_rad(45);
  d.joints.platform_max_angle = deg_to_rad(50);
  d.joints.base_axis = Eigen::Vector3d(0, 0.6, 0.8);
  d.tcp = Eigen::Vector3d(0, 0, -0.1);
  d.characteristic_length = 0.3;
  d.actuator_error = 2e-5;
  const std::string text = hexapod_design_to_yaml(d);
  const HexapodDesign back = read_hexapod_design(YamlValue::load_string(text, "rt.yaml"));
  EXPECT_EQ(back.base_joints, d.base_joints);
  EXPECT_EQ(back.platform_joints, d.platform_joints);
  EXPECT_EQ(back.min_length, d.min_length);
  EXPECT_EQ(back.max_length, d.max_length);
  EXPECT_EQ(back.stiffness.E, d.stiffness.E);
  EXPECT_EQ(back.stiffness.area, d.stiffness.area);
  EXPECT_EQ(back.stiffness.actuator_stiffness, d.stiffness.actuator_stiffness);
  EXPECT_NEAR(back.joints.base_max_angle, d.joints.base_max_angle, 1e-15);
  EXPECT_NEAR(back.joints.platform_max_angle, d.joints.platform_max_angle, 1e-15);
  EXPECT_TRUE(back.joints.base_axis.isApprox(d.joints.base_axis, 1e-15));
  EXPECT_EQ(back.joints.platform_axis, d.joints.platform_axis);
  EXPECT_EQ(back.tcp, d.tcp);
  EXPECT_EQ(back.characteristic_length, d.characteristic_length);
  EXPECT_EQ(back.actuator_error, d.actuator_error);
  // Written in block style, the custom axes both present, the limits in degrees.
  EXPECT_NE(text.find("joints:\n  base_max_angle_deg: 45\n  platform_max_angle_deg: 50\n"
                      "  base_axis: [0, 0.6, 0.8]\n  platform_axis: [0, 0, -1]\n"),
            std::string::npos)
      << text;
  // A constant axial stiffness is written alone (no E or area).
  d.stiffness.axial_stiffness = 5e7;
  const std::string axial = hexapod_design_to_yaml(d);
  EXPECT_NE(axial.find("  axial_stiffness: 50000000\n  actuator_stiffness: 200000000\n"),
            std::string::npos)
      << axial;
  EXPECT_EQ(axial.find("  E: "), std::string::npos) << axial;
}

// The mass model: read, written back to the same design, its values checked where they are.
TEST(MachineFileFields, MassesAreReadWrittenAndChecked) {
  const std::string masses =
      "masses:\n"
      "  platform: {mass: 45, centre_of_mass: [0, 0.01, -0.05], inertia: [1.2, 1.3, 2.0, 0.01, "
      "0, -0.02]}\n"
      "  legs:\n"
      "    cylinder: {mass: 6, centre: 0.2, inertia: 0.08}\n"
      "    rod: {mass: 3, centre: 0.25, inertia: 0.05}\n"
      "gravity: [0, 0, -9.80665]\n";
  const HexapodDesign d = read_hexapod_design(YamlValue::load_string(kGood + masses, "m.yaml"));
  ASSERT_TRUE(d.masses.present);
  EXPECT_EQ(d.masses.platform.mass, 45.0);
  EXPECT_EQ(d.masses.platform.centre_of_mass, Eigen::Vector3d(0, 0.01, -0.05));
  EXPECT_EQ(d.masses.platform.inertia(0, 1), 0.01);
  EXPECT_EQ(d.masses.platform.inertia(2, 1), -0.02);
  EXPECT_EQ(d.masses.platform.inertia(2, 2), 2.0);
  EXPECT_EQ(d.masses.legs.cylinder.centre, 0.2);
  EXPECT_EQ(d.masses.legs.rod.inertia, 0.05);
  EXPECT_EQ(d.masses.gravity(2), -9.80665);
  const std::string text = hexapod_design_to_yaml(d);
  const HexapodDesign back = read_hexapod_design(YamlValue::load_string(text, "w.yaml"));
  EXPECT_EQ(back.masses.platform.inertia, d.masses.platform.inertia) << text;
  EXPECT_EQ(back.masses.legs.rod.centre, d.masses.legs.rod.centre);
  EXPECT_EQ(back.masses.gravity, d.masses.gravity);
  EXPECT_EQ(hexapod_design_to_yaml(back), text);
  // Without masses: none written, none present.
  EXPECT_FALSE(read_hexapod_design(YamlValue::load_string(kGood, "m.yaml")).masses.present);
  EXPECT_EQ(hexapod_design_to_yaml(sample_machines::conventions_hexapod_design()).find("masses"),
            std::string::npos);
  // Errors at the key.
  EXPECT_EQ(error_of(std::string(kGood) + "gravity: [0, 0, -9.81]\n"),
            "m.yaml:7:10: gravity: no gravity without masses (it acts on them)");
  EXPECT_EQ(error_of(std::string(kGood) + "masses:\n  platform: {mass: 10, inertia: [1, 1, 3, 0, "
                                          "0, 0]}\n"),
            "m.yaml:8:3: masses: platform.inertia: the principal moments violate I1 + I2 >= I3 "
            "(no body has it)");
  EXPECT_EQ(error_of(std::string(kGood) + "masses:\n  platform: {mass: 10, inertia: [1, 1, 1, 2, "
                                          "0, 0]}\n"),
            "m.yaml:8:3: masses: platform.inertia must be positive definite (every principal "
            "moment > 0)");
  EXPECT_EQ(error_of(std::string(kGood) + "masses:\n  platform: {mass: 0, inertia: [1, 1, 1, 0, "
                                          "0, 0]}\n"),
            "m.yaml:8:20: masses.platform.mass: expected a number > 0, found '0'");
  EXPECT_EQ(error_of(std::string(kGood) + "masses:\n  platform: {mass: 1, inertia: [1, 1, 1, 0, "
                                          "0, 0]}\n  legs: {carriage: {mass: 2}}\n"),
            "m.yaml:9:10: masses.legs.carriage: unknown key 'carriage'; allowed keys here: "
            "cylinder, rod");
}

// The legs' shape: read, written back, and checked at the key.
TEST(MachineFileFields, LegShapeIsReadWrittenAndChecked) {
  const HexapodDesign capsule = read_hexapod_design(YamlValue::load_string(
      replace(kGood, "actuator_stiffness: 2.0e8}", "actuator_stiffness: 2.0e8, diameter: 0.08}") +
          "min_clearance: 0.005\n",
      "m.yaml"));
  EXPECT_EQ(capsule.leg_shape.diameter, 0.08);
  EXPECT_EQ(capsule.min_clearance, 0.005);
  const std::string text = hexapod_design_to_yaml(capsule);
  const HexapodDesign back = read_hexapod_design(YamlValue::load_string(text, "w.yaml"));
  EXPECT_EQ(back.leg_shape.diameter, 0.08) << text;
  EXPECT_EQ(back.min_clearance, 0.005) << text;
  const HexapodDesign pair = read_hexapod_design(YamlValue::load_string(
      replace(kGood, "actuator_stiffness: 2.0e8}",
              "actuator_stiffness: 2.0e8, cylinder: {diameter: 0.1, length: 0.6}, rod: {diameter: "
              "0.05}}"),
      "m.yaml"));
  EXPECT_EQ(pair.leg_shape.cylinder_diameter, 0.1);
  EXPECT_EQ(pair.leg_shape.cylinder_length, 0.6);
  EXPECT_EQ(pair.leg_shape.rod_diameter, 0.05);
  const HexapodDesign pair_back =
      read_hexapod_design(YamlValue::load_string(hexapod_design_to_yaml(pair), "w.yaml"));
  EXPECT_EQ(pair_back.leg_shape.cylinder_length, 0.6);
  EXPECT_EQ(pair_back.leg_shape.rod_diameter, 0.05);
  // Without a shape nothing is written.
  EXPECT_EQ(hexapod_design_to_yaml(sample_machines::conventions_hexapod_design()).find("diameter"),
            std::string::npos);
  EXPECT_EQ(error_of(replace(kGood, "actuator_stiffness: 2.0e8}",
                             "actuator_stiffness: 2.0e8, diameter: -0.08}")),
            "m.yaml:4:106: legs.diameter: expected a number > 0, found '-0.08'");
  EXPECT_EQ(error_of(replace(kGood, "actuator_stiffness: 2.0e8}",
                             "actuator_stiffness: 2.0e8, rod: {diameter: 0.05}}")),
            "m.yaml:4:7: legs: legs.rod needs legs.cylinder (the rod runs from the platform joint "
            "into it)");
  EXPECT_EQ(error_of(std::string(kGood) + "min_clearance: -1\n"),
            "m.yaml:7:16: min_clearance: expected a number >= 0, found '-1'");
}

}  // namespace
}  // namespace pkmopt
