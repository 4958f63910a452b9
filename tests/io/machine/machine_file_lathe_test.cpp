// Tests of io/machine/machine_file_lathe: the field list of the lathe machine file gives the docs
// table of docs/machines.md, the writer built on it (lathe_16k20f3_machine_file) gives a file
// the reader reads back to the same design with every key away from its default, and bad values
// keep their messages.
#include "io/machine/machine_file_lathe.hpp"

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <string>

#include "io/format/input_error.hpp"
#include "tests/io/machine/readback.hpp"

namespace pkmopt {
namespace {

using readback_test::expect_angle;

std::string error_of(const std::string& text) {
  try {
    (void)read_lathe_16k20f3_design(YamlValue::load_string(text, "l.yaml"));
  } catch (const InputError& e) {
    return e.what();
  }
  return "no error";
}

TEST(LatheMachineFileFields, DocsCarryTheGeneratedTable) {
  std::ifstream in(std::string(PKMOPT_SOURCE_DIR) + "/docs/machines.md");
  std::stringstream docs;
  docs << in.rdbuf();
  const std::string block =
      "<!-- fields: lathe_16k20f3 -->\n" + lathe_machine_fields_markdown() + "<!-- /fields -->\n";
  EXPECT_NE(docs.str().find(block), std::string::npos)
      << "docs/machines.md lacks the generated lathe table:\n"
      << block;
}

TEST(LatheMachineFileFields, WriterAndReaderRoundTripEveryKey) {
  Lathe16k20f3Design d;
  d.centre_height = 0.22;
  d.tool_reach = 0.17;
  d.approach_angle = deg_to_rad(30.0);
  d.strut_length = 0.65;
  d.guide_y = 0.18;
  d.guide_z = -0.17;
  d.strut_joint_spread = 0.11;
  d.strut_joint_y = 0.16;
  d.strut_joint_z = -0.09;
  d.carriage_min = -1.2;
  d.carriage_max = 1.3;
  d.strut_max_angle = deg_to_rad(65.0);
  d.strut_E = 2.0e11;
  d.strut_area = 4.5e-4;
  d.carriage_stiffness = 1.4e8;
  d.leg_base_x = 0.01;
  d.leg_base_y = -0.05;
  d.leg_base_z = 1.62;
  d.leg_base_spacing = 0.42;
  d.leg_joint_spacing = 0.38;
  d.leg_joint_z = 0.11;
  d.leg_min_length = 1.2;
  d.leg_max_length = 1.6;
  d.leg_max_angle = deg_to_rad(35.0);
  d.leg_E = 2.0e11;
  d.leg_area = 1.6e-3;
  d.leg_actuator_stiffness = 1.2e8;
  d.carriage_drive = {.E = 2.1e11,
                      .root_diameter = 0.035,
                      .free_length_at_min = 0.2,
                      .free_length_at_max = 2.9,
                      .nut_stiffness = 6e8,
                      .bearing_stiffness = 9e8,
                      .torsional_stiffness = 4e3,
                      .lead = 0.01};
  d.strut_base_joint_stiffness = 3e8;
  d.strut_platform_joint_stiffness = 4e8;
  d.leg_drive = {.E = 2.0e11,
                 .root_diameter = 0.025,
                 .free_length_at_min = 0.1,
                 .free_length_at_max = 0.5,
                 .nut_stiffness = 5e8,
                 .bearing_stiffness = 7e8,
                 .torsional_stiffness = 2e3,
                 .lead = 0.005};
  d.leg_base_joint_stiffness = 5e8;
  d.leg_platform_joint_stiffness = 6e8;
  d.actuator_error = 2e-5;
  d.masses.present = true;
  d.masses.platform = {.mass = 60.0,
                       .centre_of_mass = {0.01, 0.02, -0.03},
                       .inertia = Eigen::Vector3d(1.5, 1.2, 1.1).asDiagonal()};
  d.masses.legs.carriage = 12.0;
  d.masses.legs.link = {.mass = 5.0, .centre = 0.35, .inertia = 0.2};
  d.masses.legs.cylinder = {.mass = 9.0, .centre = 0.3, .inertia = 0.4};
  d.masses.legs.rod = {.mass = 4.0, .centre = 0.4, .inertia = 0.15};
  const std::string text = lathe_16k20f3_machine_file(d);
  const Lathe16k20f3Design r = read_lathe_16k20f3_design(YamlValue::load_string(text, "l.yaml"));
  EXPECT_EQ(r.centre_height, d.centre_height);
  EXPECT_EQ(r.tool_reach, d.tool_reach);
  EXPECT_NEAR(r.approach_angle, d.approach_angle, 1e-15);
  EXPECT_EQ(r.strut_length, d.strut_length);
  EXPECT_EQ(r.guide_y, d.guide_y);
  EXPECT_EQ(r.guide_z, d.guide_z);
  EXPECT_EQ(r.strut_joint_spread, d.strut_joint_spread);
  EXPECT_EQ(r.strut_joint_y, d.strut_joint_y);
  EXPECT_EQ(r.strut_joint_z, d.strut_joint_z);
  EXPECT_EQ(r.carriage_min, d.carriage_min);
  EXPECT_EQ(r.carriage_max, d.carriage_max);
  EXPECT_NEAR(r.strut_max_angle, d.strut_max_angle, 1e-15);
  EXPECT_EQ(r.strut_E, d.strut_E);
  EXPECT_EQ(r.strut_area, d.strut_area);
  EXPECT_EQ(r.carriage_stiffness, d.carriage_stiffness);
  EXPECT_EQ(r.leg_base_x, d.leg_base_x);
  EXPECT_EQ(r.leg_base_y, d.leg_base_y);
  EXPECT_EQ(r.leg_base_z, d.leg_base_z);
  EXPECT_EQ(r.leg_base_spacing, d.leg_base_spacing);
  EXPECT_EQ(r.leg_joint_spacing, d.leg_joint_spacing);
  EXPECT_EQ(r.leg_joint_z, d.leg_joint_z);
  EXPECT_EQ(r.leg_min_length, d.leg_min_length);
  EXPECT_EQ(r.leg_max_length, d.leg_max_length);
  EXPECT_NEAR(r.leg_max_angle, d.leg_max_angle, 1e-15);
  EXPECT_EQ(r.leg_E, d.leg_E);
  EXPECT_EQ(r.leg_area, d.leg_area);
  EXPECT_EQ(r.leg_actuator_stiffness, d.leg_actuator_stiffness);
  for (const auto& [read, written] :
       {std::pair{r.carriage_drive, d.carriage_drive}, std::pair{r.leg_drive, d.leg_drive}}) {
    EXPECT_EQ(read.E, written.E);
    EXPECT_EQ(read.root_diameter, written.root_diameter);
    EXPECT_EQ(read.free_length_at_min, written.free_length_at_min);
    EXPECT_EQ(read.free_length_at_max, written.free_length_at_max);
    EXPECT_EQ(read.nut_stiffness, written.nut_stiffness);
    EXPECT_EQ(read.bearing_stiffness, written.bearing_stiffness);
    EXPECT_EQ(read.torsional_stiffness, written.torsional_stiffness);
    EXPECT_EQ(read.lead, written.lead);
  }
  EXPECT_EQ(r.strut_base_joint_stiffness, d.strut_base_joint_stiffness);
  EXPECT_EQ(r.strut_platform_joint_stiffness, d.strut_platform_joint_stiffness);
  EXPECT_EQ(r.leg_base_joint_stiffness, d.leg_base_joint_stiffness);
  EXPECT_EQ(r.leg_platform_joint_stiffness, d.leg_platform_joint_stiffness);
  EXPECT_EQ(r.actuator_error, d.actuator_error);
  EXPECT_TRUE(r.masses.present);
  EXPECT_EQ(r.masses.platform.inertia, d.masses.platform.inertia);
  EXPECT_EQ(r.masses.platform.centre_of_mass, d.masses.platform.centre_of_mass);
  EXPECT_EQ(r.masses.legs.carriage, d.masses.legs.carriage);
  EXPECT_EQ(r.masses.legs.link.centre, d.masses.legs.link.centre);
  EXPECT_EQ(r.masses.legs.rod.inertia, d.masses.legs.rod.inertia);
  EXPECT_EQ(lathe_16k20f3_machine_file(r), text);
  // Every key is written, one line each, in the list's order.
  EXPECT_EQ(text.substr(0, text.find("approach_angle_deg")),
            "model: lathe_16k20f3\ncentre_height: 0.22\ntool_reach: 0.17\n");
  EXPECT_NE(text.find("\ncarriage_travel: [-1.2, 1.3]\n"), std::string::npos) << text;
  EXPECT_NE(text.find("\nleg_length: [1.2, 1.6]\n"), std::string::npos) << text;
}

TEST(LatheMachineFileFields, BadValuesKeepTheirMessages) {
  EXPECT_EQ(error_of("model: lathe_16k20f3\n"), "no error");
  EXPECT_EQ(error_of("model: lathe_16k20f3\napproach_angle_deg: 90\n"),
            "l.yaml:2:21: approach_angle_deg: expected an angle in degrees in (-90, 90), found "
            "'90'");
  EXPECT_EQ(error_of("model: lathe_16k20f3\nstrut_max_angle_deg: 0\n"),
            "l.yaml:2:22: strut_max_angle_deg: expected an angle in degrees in (0, 90), found '0'");
  EXPECT_EQ(error_of("model: lathe_16k20f3\ncarriage_travel: [1, -1]\n"),
            "l.yaml:2:18: carriage_travel: expected [low, high] with low < high (m), found a list "
            "of 2");
  EXPECT_EQ(error_of("model: lathe_16k20f3\nleg_length: [0, 1.5]\n"),
            "l.yaml:2:13: leg_length: expected [low, high] with 0 < low < high (m), found a list "
            "of 2");
  EXPECT_EQ(error_of("model: lathe_16k20f3\nstrut_E: 0\n"),
            "l.yaml:2:10: strut_E: expected a number > 0, found '0'");
  EXPECT_EQ(error_of("model: lathe_16k20f3\ntool_reach: -0.1\n"),
            "l.yaml:2:13: tool_reach: expected a number >= 0, found '-0.1'");
  EXPECT_EQ(error_of("model: lathe_16k20f3\nleg_drive: {E: 2.1e11, root_diameter: 0.03}\n"),
            "l.yaml:2:12: leg_drive: the screw needs its free length (free_length_at_min, "
            "free_length_at_max)");
  EXPECT_EQ(error_of("model: lathe_16k20f3\ncarriage_drive: {torsional_stiffness: 3000}\n"),
            "l.yaml:2:17: carriage_drive: the motor torsion acts through the lead: give "
            "torsional_stiffness and lead together");
  const std::string unknown = error_of("model: lathe_16k20f3\ncolour: red\n");
  EXPECT_NE(unknown.find("l.yaml:2:1: colour: unknown key 'colour'; allowed keys here: model, "
                         "name, description, centre_height, tool_reach, approach_angle_deg,"),
            std::string::npos)
      << unknown;
}

namespace readback {

constexpr double kInf = std::numeric_limits<double>::infinity();

YamlValue yaml(const std::string& text, const std::string& name) {
  return YamlValue::load_string(text, name);
}

Lathe16k20f3Design sample_lathe() {
  Lathe16k20f3Design d;
  d.tool_reach = 0.17;
  d.approach_angle = deg_to_rad(30.0);
  d.strut_length = 0.65;
  d.guide_y = 0.18;
  d.carriage_min = -1.2;
  d.carriage_max = 1.3;
  d.strut_max_angle = deg_to_rad(65.0);
  d.leg_base_y = -0.05;
  d.leg_min_length = 1.2;
  d.leg_max_length = 1.6;
  d.leg_max_angle = deg_to_rad(35.0);
  d.leg_actuator_stiffness = 1.2e8;
  d.actuator_error = 2e-5;
  return d;
}

TEST(LatheWriter, LatheReadsBackToTheSameDesign) {
  const Lathe16k20f3Design d = sample_lathe();
  const std::string text = lathe_16k20f3_machine_file(d);
  EXPECT_EQ(text.rfind("model: lathe_16k20f3\n", 0), 0u) << text;
  const Lathe16k20f3Design r = read_lathe_16k20f3_design(yaml(text, "lathe.yaml"));
  EXPECT_EQ(r.centre_height, d.centre_height);
  EXPECT_EQ(r.tool_reach, d.tool_reach);
  expect_angle(r.approach_angle, d.approach_angle, "approach_angle");
  EXPECT_EQ(r.strut_length, d.strut_length);
  EXPECT_EQ(r.guide_y, d.guide_y);
  EXPECT_EQ(r.guide_z, d.guide_z);
  EXPECT_EQ(r.strut_joint_spread, d.strut_joint_spread);
  EXPECT_EQ(r.strut_joint_y, d.strut_joint_y);
  EXPECT_EQ(r.strut_joint_z, d.strut_joint_z);
  EXPECT_EQ(r.carriage_min, d.carriage_min);
  EXPECT_EQ(r.carriage_max, d.carriage_max);
  expect_angle(r.strut_max_angle, d.strut_max_angle, "strut_max_angle");
  EXPECT_EQ(r.strut_E, d.strut_E);
  EXPECT_EQ(r.strut_area, d.strut_area);
  EXPECT_EQ(r.carriage_stiffness, d.carriage_stiffness);
  EXPECT_EQ(r.leg_base_x, d.leg_base_x);
  EXPECT_EQ(r.leg_base_y, d.leg_base_y);
  EXPECT_EQ(r.leg_base_z, d.leg_base_z);
  EXPECT_EQ(r.leg_base_spacing, d.leg_base_spacing);
  EXPECT_EQ(r.leg_joint_spacing, d.leg_joint_spacing);
  EXPECT_EQ(r.leg_joint_z, d.leg_joint_z);
  EXPECT_EQ(r.leg_min_length, d.leg_min_length);
  EXPECT_EQ(r.leg_max_length, d.leg_max_length);
  expect_angle(r.leg_max_angle, d.leg_max_angle, "leg_max_angle");
  EXPECT_EQ(r.leg_E, d.leg_E);
  EXPECT_EQ(r.leg_area, d.leg_area);
  EXPECT_EQ(r.leg_actuator_stiffness, d.leg_actuator_stiffness);
  EXPECT_EQ(r.actuator_error, d.actuator_error);
}

}  // namespace readback

}  // namespace
}  // namespace pkmopt
