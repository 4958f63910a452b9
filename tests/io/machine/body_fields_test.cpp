// Tests of io/machine/body_fields: the solids (`bodies`) of hexapod and leg-chain machine files and
// the leg chains' link shapes are read, written back to the same design, and their errors located.
#include "io/machine/body_fields.hpp"

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <string>

#include "io/format/input_error.hpp"
#include "io/format/yaml_reader.hpp"
#include "io/machine/machine_file.hpp"
#include "io/machine/machine_file_leg_chain.hpp"
#include "io/machine/machine_file_leg_chain.hpp"

namespace pkmopt {
namespace {

std::string replace(std::string text, const std::string& from, const std::string& to) {
  text.replace(text.find(from), from.size(), to);
  return text;
}

std::string read_text(const std::string& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

YamlValue yaml_of(const std::string& text) { return YamlValue::load_string(text, "m.yaml"); }

// The sample hexapod without a leg shape (examples/hexapod.yaml, 7 lines).
const std::string kGood = read_text(std::string(PKMOPT_SOURCE_DIR) + "/examples/hexapod.yaml");

std::string hexapod_error_of(const std::string& text) {
  try {
    read_hexapod_design(yaml_of(text));
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

std::string leg_chain_error_of(const std::string& text) {
  try {
    (void)load_machine(yaml_of(text));
  } catch (const InputError& e) {
    return e.what();
  }
  return "no error";
}

// The solids: read, written back, and their errors located.
TEST(BodyFields, HexapodBodiesAreReadWrittenAndChecked) {
  const std::string legs =
      replace(kGood, "actuator_stiffness: 2.0e8}",
              "actuator_stiffness: 2.0e8, cylinder: {diameter: 0.1, length: 0.6}, rod: {diameter: "
              "0.05}}");
  const std::string bodies =
      "bodies:\n"
      "  platform: {radius: 0.3, z: [0, 0.04]}\n"
      "  base: {polygon: [[0.7, 0], [-0.35, 0.61], [-0.35, -0.61]], z: [-0.05, 0]}\n"
      "  tool: {diameter: 0.12, from: [0, 0, 0], to: [0, 0, -0.3]}\n";
  const HexapodDesign d = read_hexapod_design(YamlValue::load_string(legs + bodies, "m.yaml"));
  EXPECT_EQ(d.bodies.platform.radius, 0.3);
  EXPECT_EQ(d.bodies.platform.z_min, 0.0);
  EXPECT_EQ(d.bodies.platform.z_max, 0.04);
  ASSERT_EQ(d.bodies.base.polygon.size(), 3u);
  EXPECT_EQ(d.bodies.base.polygon[1], Eigen::Vector2d(-0.35, 0.61));
  EXPECT_EQ(d.bodies.base.z_min, -0.05);
  EXPECT_EQ(d.bodies.tool.diameter, 0.12);
  EXPECT_EQ(d.bodies.tool.to, Eigen::Vector3d(0, 0, -0.3));
  const std::string text = hexapod_design_to_yaml(d);
  const HexapodDesign back = read_hexapod_design(YamlValue::load_string(text, "w.yaml"));
  EXPECT_EQ(back.bodies.base.polygon, d.bodies.base.polygon) << text;
  EXPECT_EQ(back.bodies.platform.z_max, 0.04) << text;
  EXPECT_EQ(back.bodies.tool.from, d.bodies.tool.from) << text;
  EXPECT_EQ(hexapod_design_to_yaml(back), text);
  // Errors: no leg shape, a polygon that is not convex, a plate without z, an unknown key.
  EXPECT_EQ(hexapod_error_of(std::string(kGood) + bodies),
            "m.yaml:9:3: bodies: bodies are checked against the legs: give the legs' shape "
            "(legs.diameter, or legs.cylinder and legs.rod)");
  EXPECT_EQ(
      hexapod_error_of(legs + "bodies: {base: {polygon: [[0, 0], [1, 0], [0.2, 0.2], [0, 1]], z: "
                              "[-0.05, 0]}}\n"),
      "m.yaml:8:9: bodies: bodies.base.polygon must be convex, its vertices in order around "
      "it (vertex 3 turns the other way)");
  EXPECT_EQ(hexapod_error_of(legs + "bodies: {platform: {radius: 0.3}}\n"),
            "m.yaml:8:20: bodies.platform: missing required key 'z'");
  EXPECT_EQ(hexapod_error_of(legs + "bodies: {spindle: {diameter: 0.1}}\n").find("m.yaml:8:10: "),
            0u);
}

// The links' shape and the solids of a delta: read, written back, and checked.
TEST(BodyFields, DeltaLinkShapesRoundTrip) {
  DeltaDesign d;
  d.shapes.link_diameter = 0.03;
  d.shapes.crank_diameter = 0.08;
  d.shapes.min_clearance = 0.002;
  d.shapes.bodies.tool = {0.1, {0, 0, 0}, {0, 0, -0.2}};
  d.shapes.bodies.base.polygon = {{0.3, 0}, {-0.15, 0.26}, {-0.15, -0.26}};
  d.shapes.bodies.base.z_min = 0.0;
  d.shapes.bodies.base.z_max = 0.03;
  const std::string text = delta_machine_file(d);
  const DeltaDesign r = read_delta_design(yaml_of(text));
  EXPECT_EQ(r.shapes.link_diameter, 0.03) << text;
  EXPECT_EQ(r.shapes.crank_diameter, 0.08);
  EXPECT_EQ(r.shapes.min_clearance, 0.002);
  EXPECT_EQ(r.shapes.bodies.tool.to, d.shapes.bodies.tool.to);
  EXPECT_EQ(r.shapes.bodies.base.polygon, d.shapes.bodies.base.polygon);
  EXPECT_EQ(delta_machine_file(r), text);
  const auto machine = load_machine(yaml_of(text));
  EXPECT_TRUE(machine->checks_leg_interference());
  // A linear delta has no cranks: crank_diameter is not one of its keys.
  EXPECT_NE(
      leg_chain_error_of("model: linear_delta\ncrank_diameter: 0.05\n").find("crank_diameter"),
      std::string::npos);
  EXPECT_NE(
      leg_chain_error_of(read_text(std::string(PKMOPT_SOURCE_DIR) + "/examples/linear_delta.yaml") +
                         "bodies: {tool: {diameter: 0.1, from: [0, 0, 0], to: [0, 0, -0.1]}}\n")
          .find("give link_diameter"),
      std::string::npos);
}

}  // namespace
}  // namespace pkmopt
