#include "io/machine/machine_file.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "io/design/hexapod_study_machine.hpp"
#include "io/format/csv.hpp"
#include "io/format/field_list.hpp"
#include "io/machine/body_fields.hpp"
#include "io/machine/hexapod_fields.hpp"
#include "io/machine/leg_shape_fields.hpp"
#include "io/machine/mass_fields.hpp"
#include "io/machine/model_registry.hpp"

namespace pkmopt {
namespace {

Eigen::Matrix<double, 3, 6> read_joint_list(const YamlValue& value) {
  Eigen::Matrix<double, 3, 6> joints;
  const auto rows = value.elements(6);
  for (int i = 0; i < 6; ++i) {
    const auto xyz = rows[static_cast<std::size_t>(i)].as_lengths(3);
    joints.col(i) << xyz[0], xyz[1], xyz[2];
  }
  return joints;
}

// Semi-regular hexagon {radius, pair_separation_deg}; `platform` selects the platform form.
Eigen::Matrix<double, 3, 6> read_hexagon(const YamlValue& value, bool platform) {
  value.check_keys({"radius", "pair_separation_deg"});
  const double radius = value.required("radius").as_positive_length();
  const YamlValue sep_value = value.required("pair_separation_deg");
  const double sep = sep_value.as_double();
  if (!(sep >= 0.0 && sep <= 120.0)) {
    sep_value.fail("an angle in degrees in [0, 120]", sep_value.describe());
  }
  return platform ? semi_regular_platform_joints(radius, deg_to_rad(sep))
                  : semi_regular_base_joints(radius, deg_to_rad(sep));
}

Eigen::Matrix<double, 3, 6> read_joints(const YamlValue& root, const char* form_key,
                                        const char* list_key, bool platform) {
  const bool has_form = root.has(form_key);
  const bool has_list = root.has(list_key);
  if (has_form && has_list) {
    root.required(list_key).fail(fmt::format("either '{}' or '{}', not both", form_key, list_key));
  }
  if (!has_form && !has_list) {
    root.fail(fmt::format("missing required key '{}' (or '{}')", form_key, list_key));
  }
  return has_form ? read_hexagon(root.required(form_key), platform)
                  : read_joint_list(root.required(list_key));
}

}  // namespace

template <class Fields>
void describe_fields(Fields& f, HexapodDesign& d) {
  f.note("model", kHexapodModel, "", "required", "the machine model");
  f.note("name", "a text", "", "none", "free text");
  f.note("description", "a text", "", "none", "free text");
  f.note("base", "{radius, pair_separation_deg}", "m, deg", "required (or base_joints)",
         "semi-regular base: joint i at angle 120k ∓ α_b/2 (even/odd i, k = ⌊i/2⌋), radius > 0, "
         "α_b in [0, 120]");
  f.note("base_joints", "[[x, y, z] × 6]", "m", "required (or base)",
         "the six base joints a_i in the base frame (general 6-6 geometry)");
  f.note("platform", "{radius, pair_separation_deg}", "m, deg", "required (or platform_joints)",
         "semi-regular platform: joint i at angle 120k − 60 + α_p/2 (even i) or 120k + 60 − α_p/2 "
         "(odd i)");
  f.note("platform_joints", "[[x, y, z] × 6]", "m", "required (or platform)",
         "the six platform joints b_i in the platform frame");
  f.section("legs", {.required = true}, [&](auto& g) {
    g.field("min_length", d.min_length,
            {.min = 0,
             .min_exclusive = true,
             .required = true,
             .unit = "m",
             .doc = "shortest leg length (stroke limit)"});
    g.field("max_length", d.max_length,
            {.min = 0,
             .min_exclusive = true,
             .required = true,
             .unit = "m",
             .expected = "a number > legs.min_length",
             .doc = "longest leg length (stroke limit)"});
    describe_leg_stiffness(g, d.stiffness);
    describe_leg_shape(g, d.leg_shape);
  });
  describe_min_clearance(f, d.min_clearance);
  describe_machine_bodies(f, d.bodies);
  f.section("joints", {}, [&](auto& g) { describe_hexapod_joints(g, d.joints); });
  f.section("tool", {}, [&](auto& g) { describe_hexapod_tool(g, d.tcp); });
  f.field("characteristic_length", d.characteristic_length,
          {.min = 0,
           .min_exclusive = true,
           .unit = "m",
           .default_text = "mean distance from the TCP to the platform joints",
           .doc = "L of J_h = J·diag(1, 1, 1, 1/L, 1/L, 1/L) in singularity_margin"});
  describe_actuator_error(f, d.actuator_error);
  MassFields masses{d.masses, kTelescopicBodies};
  describe_mass_section(f, masses);
}

HexapodDesign read_hexapod_design(const YamlValue& root) {
  HexapodDesign design;
  {
    FieldKeys keys;
    describe_fields(keys, design);
    root.check_keys(keys.keys);
  }
  design.base_joints = read_joints(root, "base", "base_joints", false);
  design.platform_joints = read_joints(root, "platform", "platform_joints", true);
  const YamlValue legs = root.required("legs");
  FieldReader reader(root);
  describe_fields(reader, design);
  if (!(design.max_length > design.min_length)) {
    const YamlValue max_value = legs.required("max_length");
    max_value.fail(fmt::format("a number > legs.min_length ({})", format_number(design.min_length)),
                   max_value.describe());
  }
  check_leg_stiffness(legs, design.stiffness);
  normalize_joint_axes(root, design.joints);
  check_mass_fields(root, design.masses);
  try {
    check_leg_shape(design.leg_shape, design.min_clearance);
  } catch (const std::invalid_argument& e) {
    legs.fail(e.what());
  }
  if (root.has("bodies")) {
    try {
      check_hexapod_bodies(design.leg_shape, design.bodies);
    } catch (const std::invalid_argument& e) {
      root.required("bodies").fail(e.what());
    }
  }
  try {
    Hexapod check(design);  // the constructor's own validation (degenerate platform, ...)
  } catch (const std::invalid_argument& e) {
    root.fail(e.what());
  }
  return design;
}

std::string hexapod_machine_fields_markdown() {
  FieldDocs docs;
  HexapodDesign design;
  describe_fields(docs, design);
  return docs.markdown();
}

std::unique_ptr<Machine> load_machine(const YamlValue& root) {
  root.expect_map();
  return machine_model(root.required("model")).load(root);
}

namespace {

// The hexapod of an architecture synthesis: the compare-300 design space (a 300 mm task) scaled
// by the task's size, steel legs, actuators of 2e8 N/m, 45 deg joints, the TCP 0.1 m below the
// platform, drives with 5 um errors; the task 0.9 scale above the base.
std::vector<SynthesisTemplate> hexapod_synthesis(const SynthesisScale& scale) {
  const double s = std::max(scale.size, 0.1) / 0.3;
  auto range = [s](double lo, double hi) {
    return fmt::format("{{min: {:.4g}, max: {:.4g}}}", lo * s, hi * s);
  };
  SynthesisTemplate t;
  t.name = std::string(kHexapodModel);
  t.structure = "Gough–Stewart hexapod (6-UPS)";
  t.machine_yaml = fmt::format(
      "model: hexapod\n"
      "parameters:\n"
      "  base_radius: {}\n"
      "  platform_radius: {}\n"
      "  base_pair_separation_deg: 20\n"
      "  platform_pair_separation_deg: 20\n"
      "  min_length: {}\n"
      "  stroke: {}\n"
      "  home_height: {}\n"
      "legs: {{E: 2.1e11, area: 3.0e-4, actuator_stiffness: 2.0e8}}\n"
      "joints: {{base_max_angle_deg: 45, platform_max_angle_deg: 45}}\n"
      "tool: {{tcp: [0, 0, -0.10]}}\n"
      "actuator_error: 5.0e-6\n",
      range(0.35, 0.75), range(0.15, 0.30), range(0.35, 0.90), range(0.25, 0.70),
      range(-0.60, 0.20));
  // With masses: a steel actuator housing (1e-3 m^2) and rod (the legs' 3e-4 m^2) at the middle
  // of the length and stroke ranges.
  t.machine_yaml += synthesis_masses_yaml(
      scale, {steel_link("cylinder", 1.0e-3, 0.625 * s), steel_link("rod", 3.0e-4, 0.475 * s)});
  t.task_centre = {0.0, 0.0, 0.9 * s};
  return {t};
}

}  // namespace

ModelEntry hexapod_model_entry() {
  ModelEntry entry;
  entry.name = kHexapodModel;
  entry.load = [](const YamlValue& root) {
    return std::make_unique<Hexapod>(read_hexapod_design(root));
  };
  entry.fields_markdown = hexapod_machine_fields_markdown;
  entry.platform_dofs = [](const YamlValue&) { return PlatformDofs{3, 3}; };
  entry.study_machine = read_hexapod_study_machine;
  entry.study_fields_markdown = hexapod_study_machine_markdown;
  entry.synthesis = hexapod_synthesis;
  return entry;
}

std::unique_ptr<Machine> load_machine_file(const std::string& path) {
  return load_machine(YamlValue::load_file(path));
}

std::string hexapod_design_to_yaml(const HexapodDesign& design) {
  auto vec = [](const Eigen::Vector3d& v) {
    return fmt::format("[{}, {}, {}]", format_number(v(0)), format_number(v(1)),
                       format_number(v(2)));
  };
  std::string out = "model: hexapod\n";
  out += "base_joints:\n";
  for (int i = 0; i < 6; ++i) out += "  - " + vec(design.base_joints.col(i)) + "\n";
  out += "platform_joints:\n";
  for (int i = 0; i < 6; ++i) out += "  - " + vec(design.platform_joints.col(i)) + "\n";
  FieldWriter writer;
  HexapodDesign copy = design;
  describe_fields(writer, copy);
  return out + writer.block();
}

}  // namespace pkmopt
