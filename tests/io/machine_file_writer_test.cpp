// Tests of io/machine_file_writer: the machine file each writer gives for a design with every
// key away from its default, read back by the io readers (io/machine_file_leg_chain,
// io/machine_file_lathe), is the same design (lengths exactly, angles to the 12 significant
// digits the writers give degrees); every registered family writes its model's files; and a
// family design's file loads to the machine the family builds.
#include "io/machine_file_writer.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "io/machine_file.hpp"
#include "io/machine_file_lathe.hpp"
#include "io/machine_file_leg_chain.hpp"
#include "io/model_registry.hpp"
#include "io/yaml_reader.hpp"

namespace pkmopt {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

YamlValue yaml(const std::string& text, const std::string& name) {
  return YamlValue::load_string(text, name);
}

// Angles go through the file in degrees with 12 significant digits.
void expect_angle(double read, double written, const char* what) {
  if (std::isinf(written)) {
    EXPECT_EQ(read, written) << what;
  } else {
    EXPECT_NEAR(read, written, 1e-11 * std::max(1.0, std::abs(written))) << what;
  }
}

// The file gives either axial_stiffness or E and area (the other is not read back).
void expect_stiffness(const LinkStiffness& read, const LinkStiffness& written) {
  EXPECT_EQ(read.axial_stiffness, written.axial_stiffness);
  if (written.axial_stiffness <= 0.0) {
    EXPECT_EQ(read.E, written.E);
    EXPECT_EQ(read.area, written.area);
  }
  EXPECT_EQ(read.actuator_stiffness, written.actuator_stiffness);
}

DeltaDesign sample_delta() {
  DeltaDesign d;
  d.base_radius = 0.2;
  d.platform_radius = 0.05;
  d.upper_arm = 0.4;
  d.rod = 0.9;
  d.theta_min = deg_to_rad(-40.0);
  d.theta_max = deg_to_rad(90.0);
  d.branch = -1;
  d.stiffness = {0.0, 7.1e10, 6.0e-5, 5.0e4};
  d.elbow_max_angle = deg_to_rad(35.0);
  d.platform_max_angle = deg_to_rad(40.0);
  d.tcp = {0.0, 0.01, -0.05};
  d.characteristic_length = 0.3;
  d.actuator_error = deg_to_rad(2e-3);
  return d;
}

LinearDeltaDesign sample_linear_delta() {
  LinearDeltaDesign d;
  d.guide_radius = 0.3;
  d.platform_radius = 0.05;
  d.rod = 0.7;
  d.inclination = deg_to_rad(12.0);
  d.q_min = 0.05;
  d.q_max = 0.8;
  d.stiffness = {2.0e7, 0.0, 0.0, 1.5e8};   // axial form
  d.carriage_max_angle = deg_to_rad(60.0);  // platform joints unlimited
  d.tcp = {0.01, 0.0, -0.05};
  d.actuator_error = 2e-5;
  return d;
}

HexaglideDesign sample_hexaglide() {
  HexaglideDesign d;  // the default platform joints and guides
  d.guide_z = {0.01, -0.01, 0.02, -0.02, 0.0, 0.03};
  d.inclination = deg_to_rad(5.0);
  d.strut = 0.9;
  d.q_min = -1.0;
  d.q_max = 1.3;
  d.stiffness = {0.0, 2.0e11, 3.5e-4, 1.0e8};
  d.platform_max_angle = deg_to_rad(50.0);
  d.tcp = {0.0, 0.0, -0.12};
  d.characteristic_length = 0.25;
  d.actuator_error = 3e-5;
  d.home_height = 0.65;
  return d;
}

Tripod3PrsDesign sample_tripod() {
  Tripod3PrsDesign d;
  d.base_radius = 0.32;
  d.platform_radius = 0.14;
  d.strut = 0.6;
  d.q_min = 0.05;
  d.q_max = 0.9;
  d.tool_length = 0.25;
  d.revolute_max_angle = deg_to_rad(45.0);
  d.platform_max_angle = deg_to_rad(60.0);
  d.stiffness = {3.0e8, 0.0, 0.0, 1.0e8};
  d.characteristic_length = 0.4;
  d.actuator_error = 1.5e-5;
  return d;
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

TEST(MachineFileWriter, DeltaReadsBackToTheSameDesign) {
  const DeltaDesign d = sample_delta();
  const std::string text = delta_machine_file(d);
  EXPECT_EQ(text.rfind("model: delta\n", 0), 0u) << text;
  const DeltaDesign r = read_delta_design(yaml(text, "delta.yaml"));
  EXPECT_EQ(r.base_radius, d.base_radius);
  EXPECT_EQ(r.platform_radius, d.platform_radius);
  EXPECT_EQ(r.upper_arm, d.upper_arm);
  EXPECT_EQ(r.rod, d.rod);
  expect_angle(r.theta_min, d.theta_min, "theta_min");
  expect_angle(r.theta_max, d.theta_max, "theta_max");
  EXPECT_EQ(r.branch, -1);
  expect_stiffness(r.stiffness, d.stiffness);
  expect_angle(r.elbow_max_angle, d.elbow_max_angle, "elbow_max_angle");
  expect_angle(r.platform_max_angle, d.platform_max_angle, "platform_max_angle");
  EXPECT_EQ(r.tcp, d.tcp);
  EXPECT_EQ(r.characteristic_length, d.characteristic_length);
  expect_angle(r.actuator_error, d.actuator_error, "actuator_error");
  // Writing the design read gives the same text: a fixed point.
  EXPECT_EQ(delta_machine_file(r), text);
}

TEST(MachineFileWriter, LinearDeltaReadsBackToTheSameDesign) {
  const LinearDeltaDesign d = sample_linear_delta();
  const std::string text = linear_delta_machine_file(d);
  EXPECT_EQ(text.rfind("model: linear_delta\n", 0), 0u) << text;
  const LinearDeltaDesign r = read_linear_delta_design(yaml(text, "linear_delta.yaml"));
  EXPECT_EQ(r.guide_radius, d.guide_radius);
  EXPECT_EQ(r.platform_radius, d.platform_radius);
  EXPECT_EQ(r.rod, d.rod);
  expect_angle(r.inclination, d.inclination, "inclination");
  EXPECT_EQ(r.q_min, d.q_min);
  EXPECT_EQ(r.q_max, d.q_max);
  expect_stiffness(r.stiffness, d.stiffness);
  expect_angle(r.carriage_max_angle, d.carriage_max_angle, "carriage_max_angle");
  EXPECT_EQ(r.platform_max_angle, kInf);
  EXPECT_EQ(r.tcp, d.tcp);
  EXPECT_FALSE(r.characteristic_length.has_value());
  EXPECT_EQ(r.actuator_error, d.actuator_error);
  EXPECT_EQ(linear_delta_machine_file(r), text);
}

TEST(MachineFileWriter, HexaglideReadsBackToTheSameDesign) {
  const HexaglideDesign d = sample_hexaglide();
  const std::string text = hexaglide_machine_file(d);
  EXPECT_EQ(text.rfind("model: hexaglide\n", 0), 0u) << text;
  const HexaglideDesign r = read_hexaglide_design(yaml(text, "hexaglide.yaml"));
  EXPECT_EQ(r.guide_y, d.guide_y);
  EXPECT_EQ(r.guide_z, d.guide_z);
  expect_angle(r.inclination, d.inclination, "inclination");
  EXPECT_EQ(r.strut, d.strut);
  EXPECT_EQ(r.platform_joints, d.platform_joints);
  EXPECT_EQ(r.q_min, d.q_min);
  EXPECT_EQ(r.q_max, d.q_max);
  expect_stiffness(r.stiffness, d.stiffness);
  EXPECT_EQ(r.carriage_max_angle, kInf);
  expect_angle(r.platform_max_angle, d.platform_max_angle, "platform_max_angle");
  EXPECT_EQ(r.tcp, d.tcp);
  EXPECT_EQ(r.characteristic_length, d.characteristic_length);
  EXPECT_EQ(r.actuator_error, d.actuator_error);
  EXPECT_EQ(r.home_height, d.home_height);
  EXPECT_EQ(hexaglide_machine_file(r), text);
}

TEST(MachineFileWriter, Tripod3PrsReadsBackToTheSameDesign) {
  const Tripod3PrsDesign d = sample_tripod();
  const std::string text = tripod_3prs_machine_file(d);
  EXPECT_EQ(text.rfind("model: tripod_3prs\n", 0), 0u) << text;
  const Tripod3PrsDesign r = read_tripod_3prs_design(yaml(text, "tripod.yaml"));
  EXPECT_EQ(r.base_radius, d.base_radius);
  EXPECT_EQ(r.platform_radius, d.platform_radius);
  EXPECT_EQ(r.strut, d.strut);
  EXPECT_EQ(r.q_min, d.q_min);
  EXPECT_EQ(r.q_max, d.q_max);
  EXPECT_EQ(r.tool_length, d.tool_length);
  expect_angle(r.revolute_max_angle, d.revolute_max_angle, "revolute_max_angle");
  expect_angle(r.platform_max_angle, d.platform_max_angle, "platform_max_angle");
  expect_stiffness(r.stiffness, d.stiffness);
  EXPECT_EQ(r.characteristic_length, d.characteristic_length);
  EXPECT_EQ(r.actuator_error, d.actuator_error);
  EXPECT_EQ(tripod_3prs_machine_file(r), text);
}

TEST(MachineFileWriter, LatheReadsBackToTheSameDesign) {
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

// Every design family of the registry writes its designs with its model's writer: the default
// design's file starts with the model's name and reads back to a machine of that model.
TEST(MachineFileWriter, EveryRegisteredFamilyWritesItsModelsMachineFile) {
  int families = 0;
  for (const ModelEntry* entry : registered_models()) {
    if (!entry->design_family) continue;
    const DesignFamily family = entry->design_family(nullptr);
    ASSERT_TRUE(family.machine_file) << entry->name;
    const std::string text = family.machine_file(family.default_parameters());
    EXPECT_EQ(text.substr(0, text.find('\n')), "model: " + entry->name);
    EXPECT_EQ(load_machine(YamlValue::load_string(text, entry->name + ".yaml"))->model(),
              entry->name);
    ++families;
  }
  EXPECT_EQ(families, 5);
  EXPECT_EQ(delta_family(sample_delta(), delta_machine_file)
                .machine_file({0.2, 0.05, 0.4, 0.9, deg_to_rad(-40), deg_to_rad(90), 0.0}),
            [] {
              DeltaDesign d = sample_delta();
              d.base_radius = 0.2;
              d.platform_radius = 0.05;
              d.upper_arm = 0.4;
              d.rod = 0.9;
              d.theta_min = deg_to_rad(-40);
              d.theta_max = deg_to_rad(90);
              return delta_machine_file(d);
            }());
}

// Moved from tests/problems/machine_design_test.cpp: the written machine file of a family design,
// read by the machine-file reader, gives the machine the family builds.
TEST(MachineFileWriter, FamilyDesignsLoadBackToTheSameMachine) {
  const std::vector<std::pair<DesignFamily, std::vector<double>>> cases = {
      {delta_family(DeltaDesign{}, delta_machine_file),
       {0.2, 0.05, 0.4, 0.9, deg_to_rad(-40), deg_to_rad(90), 0.0}},
      {linear_delta_family(LinearDeltaDesign{}, linear_delta_machine_file),
       {0.4, 0.05, 0.8, 0.7, deg_to_rad(12), 0.0}},
      {hexaglide_family(HexaglideDesign{}, hexaglide_machine_file),
       {0.2, deg_to_rad(25), 0.2, 0.9, 1.6, deg_to_rad(5), 0.1}},
      {tripod_3prs_family(Tripod3PrsDesign{}, tripod_3prs_machine_file),
       {0.32, 0.14, 0.6, 0.9, 0.0}}};
  const std::vector<Pose> poses = {
      Pose{{0.02, 0.03, -0.75}, {0, 0, 0}}, Pose{{0.02, 0.03, -0.55}, {0, 0, 0}},
      Pose{{0.05, -0.02, 0.45}, {0.03, 0.02, -0.01}}, Pose{{0.0, 0.0, 1.0}, {0.2, -0.1, 0.0}}};
  for (std::size_t c = 0; c < cases.size(); ++c) {
    const auto& [family, p] = cases[c];
    const std::string text = family.machine_file(p);
    const YamlValue root = YamlValue::load_string(text, family.model + ".yaml");
    const std::unique_ptr<Machine> loaded = load_machine(root);
    ASSERT_NE(loaded, nullptr) << text;
    const std::unique_ptr<Machine> built = family.build(p);
    EXPECT_EQ(loaded->model(), family.model);
    EXPECT_NEAR(*loaded->envelope_volume() / *built->envelope_volume(), 1.0, 1e-12);
    PoseMetrics a, b;
    loaded->analyze(*loaded->make_data(), poses[c], Wrench::Constant(50.0), a);
    built->analyze(*built->make_data(), poses[c], Wrench::Constant(50.0), b);
    ASSERT_FALSE(b.singular) << family.model;
    EXPECT_EQ(a.reachable, b.reachable) << family.model;
    EXPECT_NEAR((a.q - b.q).norm(), 0.0, 1e-9) << family.model;
    EXPECT_NEAR((a.tau - b.tau).norm() / b.tau.norm(), 0.0, 1e-9) << family.model;
    EXPECT_NEAR(a.stiffness_min / b.stiffness_min, 1.0, 1e-9) << family.model;
  }
}

}  // namespace
}  // namespace pkmopt
