#include "io/machine/machine_file_leg_chain.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <type_traits>

#include "io/format/csv.hpp"
#include "io/format/field_list.hpp"
#include "io/format/input_error.hpp"
#include "io/machine/body_fields.hpp"
#include "io/machine/compliance_fields.hpp"
#include "io/machine/leg_chain_fields.hpp"
#include "io/machine/mass_fields.hpp"
#include "io/machine/model_registry.hpp"
#include "models/hexapod/hexapod.hpp"
#include "problems/design/leg_chain_design.hpp"

namespace pkmopt {
using namespace leg_chain_fields;  // NOLINT: the shared rules of the field lists

template <class Fields>
void describe_fields(Fields& h, BeamSectionFields& s) {
  auto rule = [](std::string_view unit, bool required, std::string_view default_text,
                 std::string_view doc) {
    return FieldRule{.min = 0,
                     .min_exclusive = true,
                     .required = required,
                     .zero_is_unset = true,
                     .unit = unit,
                     .default_text = default_text,
                     .doc = doc};
  };
  constexpr std::string_view kValues = "required (or outer_diameter)";
  h.field("E", s.E, rule("Pa", true, "", "Young's modulus"));
  h.field("G", s.G, rule("Pa", true, "", "shear modulus (steel 8.1e10, aluminium 2.6e10)"));
  h.field("outer_diameter", s.outer_diameter,
          rule("m", false, "required (or A, Iy, Iz, J)", "a circular tube: outer diameter"));
  FieldRule bore = rule("m", false, "0 (a solid rod)", "the tube's inner diameter");
  bore.min_exclusive = false;
  h.field("inner_diameter", s.inner_diameter, bore);
  h.field("A", s.A, rule("m²", false, kValues, "area (the axial stiffness E·A / length)"));
  h.field("Iy", s.Iy,
          rule("m⁴", false, kValues,
               "second moment of area about the local y axis (the revolute axis of a tripod "
               "strut, the axis of a crank)"));
  h.field("Iz", s.Iz, rule("m⁴", false, kValues, "second moment of area about the local z axis"));
  h.field("J", s.J,
          rule("m⁴", false, kValues, "torsion constant (a circular section: the polar moment)"));
}

BeamSection resolve_beam_section(const YamlValue& map, const BeamSectionFields& s) {
  static constexpr std::array<const char*, 4> kValueKeys{"A", "Iy", "Iz", "J"};
  bool values = false;
  for (const char* key : kValueKeys) values = values || map.has(key);
  if (map.has("outer_diameter") || map.has("inner_diameter")) {
    for (const char* key : kValueKeys)
      if (map.has(key))
        map.required(key).fail(
            "either outer_diameter (and inner_diameter) of a tube or A, Iy, Iz and J, not both");
    (void)map.required("outer_diameter");  // names the missing key
    if (!(s.inner_diameter < s.outer_diameter)) {
      const YamlValue bore = map.required("inner_diameter");
      bore.fail("a number < outer_diameter (m)", bore.describe());
    }
    return tube_section(s.E, s.G, s.outer_diameter, s.inner_diameter);
  }
  if (!values)
    map.fail("a section needs outer_diameter (and inner_diameter) of a tube, or A, Iy, Iz and J");
  for (const char* key : kValueKeys) (void)map.required(key);  // a section half given
  return BeamSection{s.E, s.G, s.A, s.Iy, s.Iz, s.J};
}

template <class Fields>
void describe_fields(Fields& f, DeltaDesign& d) {
  describe_model(f, "delta");
  f.field("base_radius", d.base_radius, positive("m", "centre to each drive pivot"));
  f.field("platform_radius", d.platform_radius,
          non_negative("m", "TCP to each rod-pair centre (same azimuth as its drive)"));
  f.field("upper_arm", d.upper_arm, positive("m", "crank length"));
  f.field("rod", d.rod, positive("m", "parallelogram rod length"));
  FieldRange drive{d.theta_min, d.theta_max};
  f.field("drive_range_deg", drive,
          {.min = -180,
           .max = 180,
           .required = true,
           .degrees = true,
           .digits = 12,
           .unit = "deg",
           .doc = "drive angle range (θ = 0: crank horizontal outwards; θ > 0 lowers the elbow)"});
  FieldChoice<int> branch{d.branch, {{"elbow_out", 1}, {"elbow_in", -1}}};
  f.field("branch", branch, {.doc = "the elbow branch of the inverse kinematics"});
  describe_links(f, "rods", d.stiffness, "cross-section of a rod (2 rods per parallelogram)",
                 "a rod's section: its E·A replaces E and area (rods with ball joints at both "
                 "ends carry axial forces only)",
                 true);
  describe_beam_section(f, "crank_section", d.crank_section,
                        "the cranks' section (bending and torsion of the upper arms; local y: "
                        "the crank axis); unset: rigid cranks");
  f.field("drive_stiffness", d.stiffness.actuator_stiffness,
          drive_stiffness(d.stiffness, "N·m/rad", "motor and gearbox in series; unset: rigid"));
  describe_drive(f, d.stiffness.drive,
                 "the crank drive's torsion (torsional_stiffness only), in series");
  describe_joints(f, "elbow_max_angle_deg", d.elbow_max_angle,
                  "limit of the elbow joint angle (axis: the crank's down direction)",
                  d.platform_max_angle, "limit of the platform joint angle (axis: platform +z)");
  describe_tool(f, d.tcp);
  describe_characteristic_length(f, d.characteristic_length);
  f.field("actuator_error_deg", d.actuator_error,
          {.min = 0,
           .degrees = true,
           .digits = 12,
           .unit = "deg",
           .doc = "half-width of the drive angle error box of tcp_error_max"});
  MassFields masses{d.masses, kCrankBodies};
  describe_mass_section(f, masses);
  describe_link_shapes(f, d.shapes, true);
}

// The keys after the links of a carriage-driven model (linear delta, hexaglide): the carriage
// drive, its drive train, joint limits, tool, characteristic length and actuator error.
template <class Fields, class Design>
void describe_carriage_drive_and_rest(Fields& f, Design& d) {
  f.field("carriage_stiffness", d.stiffness.actuator_stiffness,
          drive_stiffness(d.stiffness, "N/m", "carriage drive along the guide; unset: rigid"));
  describe_drive(f, d.stiffness.drive, "the ball-screw drive train of each actuator, in series");
  describe_joints(f, "carriage_max_angle_deg", d.carriage_max_angle,
                  "limit of the carriage joint angle", d.platform_max_angle,
                  "limit of the platform joint angle");
  describe_tool(f, d.tcp);
  describe_characteristic_length(f, d.characteristic_length);
  f.field("actuator_error", d.actuator_error,
          {.min = 0, .unit = "m", .doc = "half-width of the actuator error box of tcp_error_max"});
}

template <class Fields>
void describe_fields(Fields& f, LinearDeltaDesign& d) {
  describe_model(f, "linear_delta");
  f.field("guide_radius", d.guide_radius,
          positive("m", "centre to each guide at z = 0 (guides at azimuths −90 + 120 (i − 1))"));
  f.field("platform_radius", d.platform_radius, non_negative("m", "TCP to each rod-pair centre"));
  f.field("rod", d.rod, positive("m", "parallelogram rod length"));
  f.field("inclination_deg", d.inclination,
          inclination("guide tilt towards the centre (0: vertical guides)"));
  FieldRange stroke{d.q_min, d.q_max};
  f.field("stroke", stroke, stroke_rule("carriage travel along the guide (upwards)"));
  describe_links(f, "rods", d.stiffness, "cross-section of a rod (2 rods per parallelogram)",
                 "a rod's section: its E·A replaces E and area (rods with ball joints at both "
                 "ends carry axial forces only)",
                 true);
  describe_carriage_drive_and_rest(f, d);
  MassFields masses{d.masses, kCarriageBodies};
  describe_mass_section(f, masses);
  describe_link_shapes(f, d.shapes, false);
}

template <class Fields>
void describe_fields(Fields& f, HexaglideDesign& d) {
  describe_model(f, "hexaglide");
  f.section("guides", {.required = true}, [&](auto& g) {
    g.field("y", d.guide_y,
            {.required = true, .unit = "m", .doc = "lateral position of each guide (x parallel)"});
    g.field("z", d.guide_z, {.unit = "m", .doc = "height of each guide"});
    g.field("inclination_deg", d.inclination, inclination("guide tilt about the y axis"));
  });
  f.field("strut", d.strut, positive("m", "constant strut length"));
  f.note("platform", "{radius, pair_separation_deg, rotation_deg}", "m, deg",
         "required (or platform_joints)",
         "semi-regular platform of docs/conventions.md turned by rotation_deg (default 0) about z; "
         "radius > 0, pair_separation_deg in [0, 120]");
  f.field("platform_joints", d.platform_joints,
          {.unit = "m",
           .default_text = "required (or platform)",
           .doc = "the six platform joints b_i in the platform frame"});
  FieldRange stroke{d.q_min, d.q_max};
  f.field("stroke", stroke, stroke_rule("carriage travel along the guide (from x = 0)"));
  describe_links(f, "struts", d.stiffness, "cross-section of a strut",
                 "a strut's section: its E·A replaces E and area (a strut between a universal and "
                 "a spherical joint carries its axial force only)",
                 false);
  describe_carriage_drive_and_rest(f, d);
  f.field("home_height", d.home_height, {.unit = "m", .doc = "z of the FK start pose"});
  MassFields masses{d.masses, kCarriageBodies};
  describe_mass_section(f, masses);
  describe_link_shapes(f, d.shapes, false);
}

// The keys after the drive stiffness of the tripod heads (3-PRS, 3-RPS).
template <class Fields, class Tripod>
void describe_tripod_rest(Fields& f, Tripod& d, std::string_view revolute_doc,
                          std::string_view platform_doc, LegBodies bodies) {
  describe_drive(f, d.stiffness.drive, "the ball-screw drive train of each actuator, in series");
  describe_joints(f, "revolute_max_angle_deg", d.revolute_max_angle, revolute_doc,
                  d.platform_max_angle, platform_doc);
  describe_characteristic_length(f, d.characteristic_length);
  f.field("actuator_error", d.actuator_error,
          {.min = 0, .unit = "m", .doc = "half-width of the actuator error box of tcp_error_max"});
  MassFields masses{d.masses, bodies};
  describe_mass_section(f, masses);
  describe_link_shapes(f, d.shapes, false);
}

template <class Fields>
void describe_fields(Fields& f, Tripod3PrsDesign& d) {
  describe_model(f, "tripod_3prs");
  f.field("base_radius", d.base_radius, positive("m", "head axis to each slide"));
  f.field("platform_radius", d.platform_radius,
          positive("m", "platform centre to each spherical joint"));
  f.field("strut", d.strut, positive("m", "constant strut length"));
  FieldRange stroke{d.q_min, d.q_max};
  f.field("stroke", stroke, stroke_rule("carriage travel along each slide (+z)"));
  f.field("tool_length", d.tool_length,
          {.unit = "m", .doc = "TCP beyond the platform centre along the platform's +z"});
  describe_links(f, "struts", d.stiffness, "cross-section of a strut",
                 "a strut's section (local y: the revolute axis): its E·A replaces E and area, "
                 "its bending and torsion enter the stiffness",
                 false);
  f.field("slide_stiffness", d.stiffness.actuator_stiffness,
          drive_stiffness(d.stiffness, "N/m", "drive along the slide; unset: rigid"));
  describe_tripod_rest(f, d, "limit of the strut's angle from the slide's +z (in the leg plane)",
                       "limit of the angle between the strut and the platform normal",
                       kCarriageBodies);
}

template <class Fields>
void describe_fields(Fields& f, Tripod3RpsDesign& d) {
  describe_model(f, "tripod_3rps");
  f.field("base_radius", d.base_radius, positive("m", "head axis to each base revolute joint"));
  f.field("platform_radius", d.platform_radius,
          positive("m", "platform centre to each spherical joint"));
  FieldRange length{d.q_min, d.q_max};
  f.field("leg_length", length,
          stroke_rule("range of each telescopic leg, revolute axis to spherical joint"));
  f.field("tool_length", d.tool_length,
          {.unit = "m", .doc = "TCP beyond the platform centre along the platform's +z"});
  describe_links(f, "legs", d.stiffness, "cross-section of a leg",
                 "a leg's section (local y: the revolute axis), taken as one beam over its "
                 "length: its E·A replaces E and area, its bending and torsion enter the stiffness",
                 false);
  f.field("actuator_stiffness", d.stiffness.actuator_stiffness,
          drive_stiffness(d.stiffness, "N/m", "drive along the leg; unset: rigid"));
  describe_tripod_rest(f, d, "limit of the leg's angle from the base's +z (in the leg plane)",
                       "limit of the angle between the leg and the platform normal",
                       kTelescopicBodies);
}

DeltaDesign read_delta_design(const YamlValue& root) {
  DeltaDesign d = reader_start<DeltaDesign>();
  read_fields(root, d);
  check_links(root.required("rods"));
  check_drive_section(root, d.stiffness.drive, true);
  check_mass_fields(root, d.masses);
  validate(root, d, make_delta);
  return d;
}

LinearDeltaDesign read_linear_delta_design(const YamlValue& root) {
  LinearDeltaDesign d = reader_start<LinearDeltaDesign>();
  read_fields(root, d);
  check_links(root.required("rods"));
  check_drive_section(root, d.stiffness.drive, false);
  check_mass_fields(root, d.masses);
  validate(root, d, make_linear_delta);
  return d;
}

HexaglideDesign read_hexaglide_design(const YamlValue& root) {
  HexaglideDesign d = reader_start<HexaglideDesign>();
  read_fields(root, d);
  const bool has_form = root.has("platform");
  const bool has_list = root.has("platform_joints");
  if (has_form && has_list) {
    root.required("platform_joints").fail("either 'platform' or 'platform_joints', not both");
  }
  if (!has_form && !has_list) root.fail("missing required key 'platform' (or 'platform_joints')");
  if (has_form) {
    const YamlValue p = root.required("platform");
    p.check_keys({"radius", "pair_separation_deg", "rotation_deg"});
    const double radius = p.required("radius").as_positive_length();
    const YamlValue sep_value = p.required("pair_separation_deg");
    const double sep = sep_value.as_double();
    if (!(sep >= 0.0 && sep <= 120.0)) {
      sep_value.fail("an angle in degrees in [0, 120]", sep_value.describe());
    }
    double rotation = 0.0;
    if (auto v = p.optional("rotation_deg")) rotation = deg_to_rad(v->as_double());
    d.platform_joints = Eigen::AngleAxisd(rotation, Eigen::Vector3d::UnitZ()).toRotationMatrix() *
                        semi_regular_platform_joints(radius, deg_to_rad(sep));
  }
  check_links(root.required("struts"));
  check_drive_section(root, d.stiffness.drive, false);
  check_mass_fields(root, d.masses);
  validate(root, d, make_hexaglide);
  return d;
}

Tripod3PrsDesign read_tripod_3prs_design(const YamlValue& root) {
  Tripod3PrsDesign d = reader_start<Tripod3PrsDesign>();
  read_fields(root, d);
  check_links(root.required("struts"));
  check_drive_section(root, d.stiffness.drive, false);
  check_mass_fields(root, d.masses);
  validate(root, d, make_tripod_3prs);
  return d;
}

Tripod3RpsDesign read_tripod_3rps_design(const YamlValue& root) {
  Tripod3RpsDesign d = reader_start<Tripod3RpsDesign>();
  read_fields(root, d);
  check_links(root.required("legs"));
  check_drive_section(root, d.stiffness.drive, false);
  check_mass_fields(root, d.masses);
  validate(root, d, make_tripod_3rps);
  return d;
}

std::string leg_chain_machine_fields_markdown(std::string_view model) {
  for (const ModelEntry& entry : leg_chain_model_entries())
    if (entry.name == model) return entry.fields_markdown();
  throw std::invalid_argument("leg_chain_machine_fields_markdown: unknown model '" +
                              std::string(model) + "'");
}

namespace {

// An entry whose machine is `make(read(root))`, whose docs table comes from the design's field
// list and whose design family is `family` around a template the reader reads.
template <class Design>
ModelEntry leg_chain_entry(const char* name, Design (*read)(const YamlValue&),
                           std::unique_ptr<Machine> (*make)(const Design&), PlatformDofs dofs,
                           DesignFamily (*family)(const Design&, DesignWriter<Design>),
                           std::string (*write)(const Design&)) {
  ModelEntry entry;
  entry.design_family = [read, family, write](const YamlValue* machine) {
    return family(machine ? read(*machine) : Design{}, write);
  };
  entry.name = name;
  entry.load = [read, make](const YamlValue& root) -> std::unique_ptr<Machine> {
    return make(read(root));
  };
  entry.fields_markdown = [] { return markdown_of(reader_start<Design>()); };
  entry.platform_dofs = [dofs](const YamlValue&) { return dofs; };
  return entry;
}

// The platform mobility of a `model: leg_chain` file from its `mobility:` key (validated by
// the reader before).
PlatformDofs generic_leg_chain_dofs(const YamlValue& root) {
  const std::string mobility = root.required("mobility").as_string();
  if (mobility == "translational") return {3, 0};
  if (mobility == "schoenflies") return {3, 1};
  if (mobility == "planar_legs") return {1, 2};
  return {3, 3};
}

// Architecture synthesis: each model's design space scaled from the task's size (s = 1 for a
// 300 mm task; studies/library/compare-300 and tripod-z3 are the unscaled ones), the same
// engineering assumptions for all (steel links, drives of 2e8 N/m with 5 um errors, the TCP 0.1 m
// from the platform), and where the task sits in the model's frame.
// With masses (SynthesisScale::masses) the links are steel of their sections at the middle of
// their length ranges and a carriage with its joint weighs kSynthesisCarriage.
double synthesis_factor(const SynthesisScale& scale) { return std::max(scale.size, 0.1) / 0.3; }
constexpr double kSynthesisCarriage = 8.0;  // kg

std::string synthesis_range(double s, double lo, double hi) {
  return fmt::format("{{min: {:.4g}, max: {:.4g}}}", lo * s, hi * s);
}

std::vector<SynthesisTemplate> delta_synthesis(const SynthesisScale& scale) {
  const double s = synthesis_factor(scale);
  SynthesisTemplate t;
  t.name = "delta";
  t.structure = "delta robot (3-RUU parallelograms, rotary drives)";
  t.machine_yaml = fmt::format(
      "model: delta\n"
      "parameters:\n"
      "  base_radius: {}\n"
      "  platform_radius: {:.4g}\n"
      "  upper_arm: {}\n"
      "  rod: {}\n"
      "  drive_min_deg: -60\n"
      "  drive_max_deg: 100\n"
      "  home_height: {}\n"
      "rods: {{E: 2.1e11, area: 1.5e-4}}\n"
      "drive_stiffness: 2.0e6\n"
      "joints: {{elbow_max_angle_deg: 60, platform_max_angle_deg: 60}}\n"
      "tool: {{tcp: [0, 0, -0.10]}}\n",
      synthesis_range(s, 0.10, 0.30), 0.06 * s, synthesis_range(s, 0.20, 0.60),
      synthesis_range(s, 0.50, 1.20), synthesis_range(s, -0.30, 0.30));
  t.machine_yaml += synthesis_masses_yaml(
      scale, {steel_link("crank", 1.0e-3, 0.40 * s), steel_link("link", 3.0e-4, 0.85 * s)});
  t.task_centre = {0.0, 0.0, -0.8 * s};
  return {t};
}

std::vector<SynthesisTemplate> linear_delta_synthesis(const SynthesisScale& scale) {
  const double s = synthesis_factor(scale);
  SynthesisTemplate t;
  t.name = "linear_delta";
  t.structure = "linear delta (3-PUU parallelograms on guides)";
  t.machine_yaml = fmt::format(
      "model: linear_delta\n"
      "parameters:\n"
      "  guide_radius: {}\n"
      "  platform_radius: {:.4g}\n"
      "  rod: {}\n"
      "  stroke: {}\n"
      "  inclination_deg: {{min: 0, max: 30}}\n"
      "  home_height: {}\n"
      "rods: {{E: 2.1e11, area: 1.5e-4}}\n"
      "carriage_stiffness: 2.0e8\n"
      "joints: {{carriage_max_angle_deg: 60, platform_max_angle_deg: 60}}\n"
      "tool: {{tcp: [0, 0, -0.10]}}\n"
      "actuator_error: 5.0e-6\n",
      synthesis_range(s, 0.25, 0.70), 0.06 * s, synthesis_range(s, 0.40, 1.10),
      synthesis_range(s, 0.30, 0.90), synthesis_range(s, -0.30, 0.30));
  t.machine_yaml += synthesis_masses_yaml(
      scale, {{"carriage", kSynthesisCarriage, 0.0}, steel_link("link", 3.0e-4, 0.75 * s)});
  t.task_centre = {0.0, 0.0, -0.4 * s};
  return {t};
}

std::vector<SynthesisTemplate> hexaglide_synthesis(const SynthesisScale& scale) {
  const double s = synthesis_factor(scale);
  SynthesisTemplate t;
  t.name = "hexaglide";
  t.structure = "hexaglide (6-PUS, carriages on parallel guides)";
  t.machine_yaml = fmt::format(
      "model: hexaglide\n"
      "parameters:\n"
      "  platform_radius: {}\n"
      "  pair_separation_deg: 20\n"
      "  guide_offset: {}\n"
      "  strut: {}\n"
      "  stroke: {}\n"
      "  inclination_deg: {{min: -30, max: 30}}\n"
      "  home_height: {}\n"
      "struts: {{E: 2.1e11, area: 3.0e-4}}\n"
      "carriage_stiffness: 2.0e8\n"
      "joints: {{carriage_max_angle_deg: 60, platform_max_angle_deg: 60}}\n"
      "tool: {{tcp: [0, 0, -0.10]}}\n"
      "actuator_error: 5.0e-6\n",
      synthesis_range(s, 0.10, 0.40), synthesis_range(s, 0.02, 0.60),
      synthesis_range(s, 0.50, 1.30), synthesis_range(s, 0.80, 2.60),
      synthesis_range(s, -0.20, 0.80));
  t.machine_yaml += synthesis_masses_yaml(
      scale, {{"carriage", kSynthesisCarriage, 0.0}, steel_link("link", 3.0e-4, 0.90 * s)});
  t.task_centre = {0.0, 0.0, 0.4 * s};
  return {t};
}

std::vector<SynthesisTemplate> tripod_3prs_synthesis(const SynthesisScale& scale) {
  const double s = synthesis_factor(scale);
  SynthesisTemplate t;
  t.name = "tripod_3prs";
  t.structure = "3-PRS tripod head";
  t.machine_yaml = fmt::format(
      "model: tripod_3prs\n"
      "parameters:\n"
      "  base_radius: {}\n"
      "  platform_radius: {}\n"
      "  strut: {}\n"
      "  stroke: {:.4g}\n"
      "  home_height: {}\n"
      "tool_length: 0.10\n"
      "struts: {{section: {{E: 2.1e11, G: 8.1e10, outer_diameter: 0.08, inner_diameter: 0.06}}}}\n"
      "slide_stiffness: 2.0e8\n"
      "joints: {{revolute_max_angle_deg: 50, platform_max_angle_deg: 70}}\n"
      "actuator_error: 5.0e-6\n",
      synthesis_range(s, 0.20, 0.45), synthesis_range(s, 0.08, 0.25),
      synthesis_range(s, 0.25, 0.80), 0.95 * s, synthesis_range(s, -0.3, 0.6));
  t.machine_yaml += synthesis_masses_yaml(
      scale, {{"carriage", kSynthesisCarriage, 0.0}, steel_link("link", 2.2e-3, 0.525 * s)});
  t.task_centre = {0.0, 0.0, 0.9 * s};
  return {t};
}

// The A3-like head: the 3-PRS head's radii and steel tube (its bending and torsion enter, as the
// 3-PRS head's struts'), legs from 0.35 s to 1.4 s at most, the same drives.
std::vector<SynthesisTemplate> tripod_3rps_synthesis(const SynthesisScale& scale) {
  const double s = synthesis_factor(scale);
  SynthesisTemplate t;
  t.name = "tripod_3rps";
  t.structure = "3-RPS tripod head (A3-like)";
  t.machine_yaml = fmt::format(
      "model: tripod_3rps\n"
      "parameters:\n"
      "  base_radius: {}\n"
      "  platform_radius: {}\n"
      "  min_length: {}\n"
      "  stroke: {}\n"
      "  home_height: {}\n"
      "tool_length: 0.10\n"
      "legs: {{section: {{E: 2.1e11, G: 8.1e10, outer_diameter: 0.08, inner_diameter: 0.06}}}}\n"
      "actuator_stiffness: 2.0e8\n"
      "joints: {{revolute_max_angle_deg: 50, platform_max_angle_deg: 70}}\n"
      "actuator_error: 5.0e-6\n",
      synthesis_range(s, 0.20, 0.45), synthesis_range(s, 0.08, 0.25),
      synthesis_range(s, 0.35, 0.80), synthesis_range(s, 0.25, 0.60),
      synthesis_range(s, -0.3, 0.6));
  t.machine_yaml += synthesis_masses_yaml(
      scale, {steel_link("cylinder", 2.2e-3, 0.55 * s), steel_link("rod", 2.2e-3, 0.45 * s)});
  t.task_centre = {0.0, 0.0, 0.9 * s};
  return {t};
}

}  // namespace

std::vector<ModelEntry> leg_chain_model_entries() {
  std::vector<ModelEntry> entries;
  entries.push_back(leg_chain_entry("delta", read_delta_design, make_delta, {3, 0}, delta_family,
                                    delta_machine_file));
  entries.push_back(leg_chain_entry("linear_delta", read_linear_delta_design, make_linear_delta,
                                    {3, 0}, linear_delta_family, linear_delta_machine_file));
  entries.push_back(leg_chain_entry("hexaglide", read_hexaglide_design, make_hexaglide, {3, 3},
                                    hexaglide_family, hexaglide_machine_file));
  entries.push_back(leg_chain_entry("tripod_3prs", read_tripod_3prs_design, make_tripod_3prs,
                                    {1, 2}, tripod_3prs_family, tripod_3prs_machine_file));
  entries[0].synthesis = delta_synthesis;
  entries[1].synthesis = linear_delta_synthesis;
  entries[2].synthesis = hexaglide_synthesis;
  entries.push_back(leg_chain_entry("tripod_3rps", read_tripod_3rps_design, make_tripod_3rps,
                                    {1, 2}, tripod_3rps_family, tripod_3rps_machine_file));
  entries[3].synthesis = tripod_3prs_synthesis;
  entries[4].synthesis = tripod_3rps_synthesis;
  ModelEntry generic;
  generic.name = "leg_chain";
  generic.load = [](const YamlValue& root) -> std::unique_ptr<Machine> {
    return make_leg_chain_machine(read_leg_chain_design(root));
  };
  generic.fields_markdown = leg_chain_fields::generic_fields_markdown;
  generic.platform_dofs = generic_leg_chain_dofs;
  entries.push_back(std::move(generic));
  return entries;
}

// The writers (delta_machine_file and the others, below) take the same lists.
template void describe_fields(FieldWriter&, DeltaDesign&);
template void describe_fields(FieldWriter&, LinearDeltaDesign&);
template void describe_fields(FieldWriter&, HexaglideDesign&);
template void describe_fields(FieldWriter&, Tripod3PrsDesign&);
template void describe_fields(FieldWriter&, Tripod3RpsDesign&);
template void describe_fields(FieldWriter&, BeamSectionFields&);
// The generic form's lists (io/machine/machine_file_leg_chain_generic.cpp) read and document
// sections.
template void describe_fields(FieldReader&, BeamSectionFields&);
template void describe_fields(FieldDocs&, BeamSectionFields&);

std::string delta_machine_file(const DeltaDesign& d) { return model_file_text("delta", d); }

std::string linear_delta_machine_file(const LinearDeltaDesign& d) {
  return model_file_text("linear_delta", d);
}

std::string hexaglide_machine_file(const HexaglideDesign& d) {
  return model_file_text("hexaglide", d);
}

std::string tripod_3prs_machine_file(const Tripod3PrsDesign& d) {
  return model_file_text("tripod_3prs", d);
}

std::string tripod_3rps_machine_file(const Tripod3RpsDesign& d) {
  return model_file_text("tripod_3rps", d);
}

std::string leg_chain_machine_file(const LegChainDesign& d) {
  std::string text = model_file_text("leg_chain", d);
  text += "legs:\n";
  bool revolute = false;
  for (const LegChainLeg& leg : d.legs) {
    LegChainLeg copy = leg;
    LegChainLegFields fields{copy, d.mobility};
    FieldWriter writer;
    describe_fields(writer, fields);
    text += "  - " + writer.flow_map() + "\n";
    revolute = revolute || leg.kind == LegKind::kRUS;
  }
  if (revolute)
    return text + fmt::format("actuator_error_deg: {:.12g}\n", rad_to_deg(d.actuator_error));
  return text + "actuator_error: " + format_number(d.actuator_error) + "\n";
}

}  // namespace pkmopt
