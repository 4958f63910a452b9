#include "io/machine_file_leg_chain.hpp"

#include <fmt/format.h>

#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <type_traits>

#include "io/compliance_fields.hpp"
#include "io/csv.hpp"
#include "io/field_list.hpp"
#include "io/input_error.hpp"
#include "models/hexapod.hpp"

namespace pkmopt {
namespace {

// Rules shared by the models' field lists.
FieldRule positive(std::string_view unit, std::string_view doc) {
  return {.min = 0, .min_exclusive = true, .required = true, .unit = unit, .doc = doc};
}

FieldRule non_negative(std::string_view unit, std::string_view doc) {
  return {.min = 0, .required = true, .unit = unit, .doc = doc};
}

// A joint angle limit in degrees, (0, 180], unlimited when absent; written to 12 digits.
FieldRule angle_limit(std::string_view doc) {
  return {.min = 0,
          .max = 180,
          .min_exclusive = true,
          .infinite_is_unset = true,
          .degrees = true,
          .digits = 12,
          .unit = "deg",
          .expected = "an angle in degrees in (0, 180]",
          .doc = doc};
}

// A guide inclination in degrees, (-90, 90).
FieldRule inclination(std::string_view doc) {
  return {.min = -90,
          .max = 90,
          .min_exclusive = true,
          .max_exclusive = true,
          .degrees = true,
          .digits = 12,
          .unit = "deg",
          .expected = "an angle in degrees in (-90, 90)",
          .doc = doc};
}

// An actuator stiffness in series with the links: written when > 0, absent = a rigid drive.
FieldRule drive_stiffness(LinkStiffness& k, std::string_view unit, std::string_view doc) {
  return {.min = 0,
          .min_exclusive = true,
          .zero_is_unset = true,
          .unit = unit,
          .doc = doc,
          .omit_when = [&k] { return !(k.actuator_stiffness > 0.0); }};
}

template <class Fields>
void describe_model(Fields& f, std::string_view model) {
  f.note("model", model, "", "required", "the machine model");
  f.note("name", "a text", "", "none", "free text");
  f.note("description", "a text", "", "none", "free text");
}

// The docs lines of a link stiffness: E, area and axial_stiffness.
struct LinkStiffnessDocs {
  std::string_view E, area, axial_stiffness;
};

// `{E, area}`, `{axial_stiffness}` or `{section}` of a link (the readers check the choice); the
// members are those of a LinkStiffness or of one leg of the generic form.
template <class Fields>
void describe_link_stiffness(Fields& g, double& E, double& area, double& axial_stiffness,
                             const std::optional<BeamSection>& section,
                             const LinkStiffnessDocs& docs) {
  g.field("E", E,
          {.min = 0,
           .min_exclusive = true,
           .unit = "Pa",
           .default_text = "required (or axial_stiffness, or section)",
           .doc = docs.E,
           .omit_when = [&] { return axial_stiffness > 0.0 || section.has_value(); }});
  g.field("area", area,
          {.min = 0,
           .min_exclusive = true,
           .unit = "m²",
           .default_text = "required (or axial_stiffness, or section)",
           .doc = docs.area,
           .omit_when = [&] { return axial_stiffness > 0.0 || section.has_value(); }});
  g.field("axial_stiffness", axial_stiffness,
          {.min = 0,
           .min_exclusive = true,
           .zero_is_unset = true,
           .unit = "N/m",
           .default_text = "required (or E and area, or section)",
           .doc = docs.axial_stiffness,
           .omit_when = [&section] { return section.has_value(); }});
}

// `section:` or `crank_section:`, a beam section (BeamSectionFields): read into `target` with the
// located checks of resolve_beam_section, written and documented from it.
template <class Fields>
void describe_beam_section(Fields& g, std::string_view key, std::optional<BeamSection>& target,
                           std::string_view doc) {
  BeamSectionFields fields{target};
  if (target) {
    fields.E = target->E;
    fields.G = target->G;
    fields.A = target->A;
    fields.Iy = target->Iy;
    fields.Iz = target->Iz;
    fields.J = target->J;
  }
  g.section(key, {.doc = doc}, [&](auto& h) {
    describe_fields(h, fields);
    if constexpr (std::is_same_v<std::decay_t<decltype(h)>, FieldReader>)
      target = resolve_beam_section(h.section(), fields);
  });
}

FieldRule width_rule(std::string_view doc) {
  return {.min = 0, .min_exclusive = true, .zero_is_unset = true, .unit = "m", .doc = doc};
}

// A named model's links; `section_doc` says what a section changes, `pairs` adds the
// parallelogram width (deltas).
template <class Fields>
void describe_links(Fields& f, std::string_view key, LinkStiffness& k, std::string_view per,
                    std::string_view section_doc, bool pairs) {
  f.section(key, {.required = true}, [&](auto& g) {
    describe_link_stiffness(g, k.E, k.area, k.axial_stiffness, k.section,
                            {"Young's modulus of the links (with area)", per,
                             "constant axial stiffness of a link instead of E and area"});
    describe_beam_section(g, "section", k.section, section_doc);
    describe_joint_stiffness(g, k.base_joint_stiffness, k.platform_joint_stiffness);
    if (pairs)
      g.field("parallelogram_width", k.parallelogram_width,
              width_rule("distance between the two rods of a pair (along the bars): the pairs "
                         "then hold the orientation elastically; unset: rigidly"));
  });
}

// `drive:` the actuators' drive train, in series with their `*_stiffness`.
template <class Fields>
void describe_drive(Fields& f, ScrewDrive& drive, std::string_view doc) {
  f.section("drive", {.doc = doc}, [&](auto& g) { describe_screw_drive(g, drive); });
}

template <class Fields>
void describe_joints(Fields& f, std::string_view base_key, double& base_limit,
                     std::string_view base_doc, double& platform_limit,
                     std::string_view platform_doc) {
  f.section("joints", {}, [&](auto& g) {
    g.field(base_key, base_limit, angle_limit(base_doc));
    g.field("platform_max_angle_deg", platform_limit, angle_limit(platform_doc));
  });
}

template <class Fields>
void describe_tool(Fields& f, Eigen::Vector3d& tcp) {
  f.section("tool", {}, [&](auto& g) {
    g.field("tcp", tcp, {.unit = "m", .doc = "the TCP in the platform frame"});
  });
}

template <class Fields>
void describe_characteristic_length(Fields& f, std::optional<double>& length) {
  f.field("characteristic_length", length,
          {.min = 0,
           .min_exclusive = true,
           .unit = "m",
           .default_text = "mean distance from the TCP to the platform joints",
           .doc = "L of J_h in singularity_margin (unused by 3-DOF translational machines)"});
}

FieldRule stroke_rule(std::string_view doc) { return {.required = true, .unit = "m", .doc = doc}; }

// The choice of `{E, area}`, `{axial_stiffness}` or `{section}`, after the list has read the
// values.
void check_links(const YamlValue& section) {
  const bool has_axial = section.has("axial_stiffness");
  const bool has_e = section.has("E");
  const bool has_area = section.has("area");
  if (section.has("section")) {
    for (const char* key : {"E", "area", "axial_stiffness"})
      if (section.has(key))
        section.required(key).fail(
            "either a section (its E and A give the axial stiffness) or E and area "
            "(or axial_stiffness), not both");
    return;
  }
  if (has_axial && (has_e || has_area)) {
    section.required("axial_stiffness").fail("either axial_stiffness or E and area, not both");
  }
  if (has_axial) return;
  if (!has_e && !has_area) {
    section.fail(
        "missing the link stiffness: give axial_stiffness (N/m), or E (Pa) and area (m^2)");
  }
  (void)section.required("E");  // both are needed: names the missing one
  (void)section.required("area");
}

void check_non_zero(const YamlValue& map, const char* key, const Eigen::Vector3d& v) {
  if (auto value = map.optional(key)) {
    if (!(v.norm() > 1e-12)) value->fail("a non-zero vector", value->describe());
  }
}

// Runs the machine's own validation and turns its message into an InputError at `root`.
template <typename Design, typename Make>
void validate(const YamlValue& root, const Design& design, Make make) {
  try {
    (void)make(design);
  } catch (const std::invalid_argument& e) {
    root.fail(e.what());
  }
}

// The design a reader starts from: the model's defaults with the links' stiffness unset (the
// file gives it) and a rigid drive unless the file gives its stiffness.
template <typename Design>
Design reader_start() {
  Design d;
  d.stiffness = {0.0, 0.0, 0.0, 0.0};
  return d;
}

template <typename Design>
std::string markdown_of(Design d) {
  FieldDocs docs;
  describe_fields(docs, d);
  return docs.markdown();
}

}  // namespace

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
  describe_drive(f, d.stiffness.drive, "the ball-screw drive train of each actuator, in series");
  describe_joints(f, "revolute_max_angle_deg", d.revolute_max_angle,
                  "limit of the strut's angle from the slide's +z (in the leg plane)",
                  d.platform_max_angle,
                  "limit of the angle between the strut and the platform normal");
  describe_characteristic_length(f, d.characteristic_length);
  f.field("actuator_error", d.actuator_error,
          {.min = 0, .unit = "m", .doc = "half-width of the actuator error box of tcp_error_max"});
}

template <class Fields>
void describe_fields(Fields& f, LegChainDesign& d) {
  describe_model(f, "leg_chain");
  FieldChoice<PlatformMobility> mobility{d.mobility,
                                         {{"six_dof", PlatformMobility::kSixDof},
                                          {"translational", PlatformMobility::kTranslational},
                                          {"schoenflies", PlatformMobility::kSchoenflies},
                                          {"planar_legs", PlatformMobility::kPlanarLegs}}};
  f.field("mobility", mobility,
          {.required = true,
           .doc = "the platform DOF: 6 legs (six_dof), 3 (translational, planar_legs) or 4 "
                  "(schoenflies)"});
  f.field("rotation_axis", d.rotation_axis,
          {.expected = "a non-zero vector",
           .doc = "schoenflies only: the platform's rotation axis e (base frame)",
           .omit_when = [&d] { return d.mobility != PlatformMobility::kSchoenflies; }});
  f.note("legs", "a list of legs (legs[] below)", "", "required",
         "exactly as many as the mobility needs, all RUS or all prismatic");
  describe_tool(f, d.tcp);
  describe_characteristic_length(f, d.characteristic_length);
  f.note("actuator_error", "a number >= 0", "m", "1e-05",
         "prismatic legs: half-width of the actuator error box of tcp_error_max");
  f.note("actuator_error_deg", "a number >= 0", "deg", "0.001",
         "RUS legs: the same in degrees (actuator_error is then an error)");
  f.section("home", {}, [&](auto& g) {
    g.field("position", d.home.position,
            {.required = true, .unit = "m", .doc = "position of the FK start pose"});
    g.field("angles_deg", d.home.angles,
            {.degrees = true, .digits = 12, .unit = "deg", .doc = "angles of the FK start pose"});
  });
}

template <class Fields>
void describe_leg_kind(Fields& f, LegChainLeg& leg) {
  FieldChoice<LegKind> kind{leg.kind,
                            {{"UPS", LegKind::kUPS},
                             {"PUS", LegKind::kPUS},
                             {"PUU", LegKind::kPUS},
                             {"RUS", LegKind::kRUS}}};
  f.field("kind", kind,
          {.required = true,
           .doc = "telescopic leg (UPS), carriage and strut (PUS; PUU a synonym), crank and rod "
                  "(RUS)"});
}

template <class Fields>
void describe_fields(Fields& f, LegChainLegFields& fields) {
  LegChainLeg& leg = fields.leg;
  const bool all = fields.all;
  const bool ups = leg.kind == LegKind::kUPS;
  const bool rus = leg.kind == LegKind::kRUS;
  describe_leg_kind(f, leg);
  f.field("base_point", leg.base_point,
          {.required = true,
           .unit = "m",
           .doc = "UPS: base joint; PUS: guide point (carriage joint at q = 0); RUS: crank pivot "
                  "(base frame)"});
  f.field("platform_point", leg.platform_point,
          {.required = true, .unit = "m", .doc = "platform joint b_i (platform frame)"});
  FieldRange range{leg.q_min, leg.q_max};
  FieldRule range_rule{.required = true,
                       .unit = "m",
                       .doc =
                           "UPS: leg lengths [min > 0, max] (m); PUS: carriage travel (m); RUS: "
                           "crank angle within [-180, 180] (deg)"};
  if (all) {
    range_rule.unit = "m or deg";
  } else if (rus) {
    range_rule.min = -180;
    range_rule.max = 180;
    range_rule.degrees = true;
    range_rule.digits = 12;
    range_rule.unit = "deg";
  } else if (ups) {
    range_rule.min = 0;
  }
  f.field("range", range, range_rule);
  f.section("link", {.required = true}, [&](auto& g) {
    describe_link_stiffness(
        g, leg.E, leg.area, leg.axial_stiffness, leg.link_section,
        {"Young's modulus of the link's rods (with area)", "cross-section of a rod",
         "constant axial stiffness of the link instead of E and area"});
    describe_beam_section(g, "section", leg.link_section,
                          "a rod's section: its E·A replaces E and area; bending and torsion "
                          "enter planar legs (local y: plane_normal)");
    g.field("rods", leg.rods,
            {.min = 1,
             .max = 16,
             .doc = "parallel rods of the link (2 for a parallelogram pair)",
             .omit_when = [&leg] { return leg.rods == 1; }});
    describe_joint_stiffness(g, leg.base_joint_stiffness, leg.platform_joint_stiffness);
    g.field("parallelogram_width", leg.parallelogram_width,
            width_rule("rods: 2 (translational, schoenflies): distance between the pair's rods "
                       "along the bars; unset: one line"));
    g.field("parallelogram_axis", leg.parallelogram_axis,
            {.expected = "a non-zero vector",
             .default_text = "the crank axis (RUS), rotation_axis (schoenflies)",
             .doc = "direction of the pair's bars (base frame); needed for PUS pairs of "
                    "translational platforms",
             .omit_when = [&leg] {
               return !(leg.parallelogram_width > 0.0) || leg.parallelogram_axis.isZero();
             }});
  });
  f.section("joints", {}, [&](auto& g) {
    g.field("base_max_angle_deg", leg.base_max_angle,
            angle_limit("limit of the angle between the leg and the base joint axis"));
    g.field("platform_max_angle_deg", leg.platform_max_angle,
            angle_limit("limit of the angle between the leg and the platform joint axis"));
    const bool default_axes =
        leg.base_axis == Eigen::Vector3d::UnitZ() && leg.platform_axis == -Eigen::Vector3d::UnitZ();
    g.field("base_axis", leg.base_axis,
            {.expected = "a non-zero vector",
             .doc = "base joint axis: base frame (UPS, PUS), crank frame at q = 0 (RUS)",
             .omit_when = [default_axes] { return default_axes; }});
    g.field("platform_axis", leg.platform_axis,
            {.expected = "a non-zero vector",
             .default_text = "[0, 0, -1]",
             .doc = "platform joint axis in the platform frame",
             .omit_when = [default_axes] { return default_axes; }});
  });
  f.field("actuator_stiffness", leg.actuator_stiffness,
          {.min = 0,
           .min_exclusive = true,
           .zero_is_unset = true,
           .unit = "N/m or N·m/rad",
           .doc = "actuator in series with the link (N·m/rad for RUS); unset: rigid"});
  describe_drive(f, leg.drive,
                 "the actuator's drive train in series (RUS: torsional_stiffness only)");
  if (all || !ups) {
    f.field("axis", leg.axis,
            {.required = !all,
             .expected = "a non-zero vector",
             .default_text = "required (PUS, RUS)",
             .doc = "PUS: guide direction; RUS: crank axis"});
    f.field("link_length", leg.link_length,
            {.min = 0,
             .min_exclusive = true,
             .required = !all,
             .unit = "m",
             .default_text = "required (PUS, RUS)",
             .doc = "constant strut or rod length"});
    f.field("branch", leg.branch,
            {.min = -1,
             .max = 1,
             .expected = "1 or -1",
             .doc = "PUS, RUS: the IK solution with B_i > 0 (1) or B_i < 0 (-1)"});
  }
  if (all || rus) {
    f.field("crank_zero", leg.crank_zero,
            {.required = !all,
             .default_text = "required (RUS)",
             .doc = "RUS: crank direction at q = 0"});
    f.field("crank_length", leg.crank_length,
            {.min = 0,
             .min_exclusive = true,
             .required = !all,
             .unit = "m",
             .default_text = "required (RUS)",
             .doc = "RUS: crank length"});
    describe_beam_section(f, "crank_section", leg.crank_section,
                          "RUS: the crank's section (local y: the crank axis); unset: rigid");
  }
  if (all || fields.mobility == PlatformMobility::kPlanarLegs) {
    f.field("plane_normal", leg.plane_normal,
            {.required = !all,
             .expected = "a non-zero vector",
             .default_text = "required (planar_legs)",
             .doc = "planar_legs: normal of the leg's plane (its revolute joint's axis)"});
  }
}

DeltaDesign read_delta_design(const YamlValue& root) {
  DeltaDesign d = reader_start<DeltaDesign>();
  read_fields(root, d);
  check_links(root.required("rods"));
  check_drive_section(root, d.stiffness.drive, true);
  validate(root, d, make_delta);
  return d;
}

LinearDeltaDesign read_linear_delta_design(const YamlValue& root) {
  LinearDeltaDesign d = reader_start<LinearDeltaDesign>();
  read_fields(root, d);
  check_links(root.required("rods"));
  check_drive_section(root, d.stiffness.drive, false);
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
    const double radius = p.required("radius").as_positive();
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
  validate(root, d, make_hexaglide);
  return d;
}

Tripod3PrsDesign read_tripod_3prs_design(const YamlValue& root) {
  Tripod3PrsDesign d = reader_start<Tripod3PrsDesign>();
  read_fields(root, d);
  check_links(root.required("struts"));
  check_drive_section(root, d.stiffness.drive, false);
  validate(root, d, make_tripod_3prs);
  return d;
}

namespace {

LegChainLeg read_leg(const YamlValue& node, PlatformMobility mobility, bool& revolute) {
  node.expect_map();
  LegChainLeg leg;
  {
    FieldReader kind(node);  // the kind first: it says which keys the leg has
    describe_leg_kind(kind, leg);
  }
  revolute = leg.kind == LegKind::kRUS;
  LegChainLegFields fields{leg, mobility};
  read_fields(node, fields);
  if (leg.kind == LegKind::kUPS && !(leg.q_min > 0.0)) {
    const YamlValue range = node.required("range");
    range.fail("leg lengths [min, max] with min > 0 (m)", range.describe());
  }
  if (leg.kind != LegKind::kUPS) {
    check_non_zero(node, "axis", leg.axis);
    if (leg.branch == 0) {
      const YamlValue branch = node.required("branch");
      branch.fail("1 or -1", branch.describe());
    }
  }
  if (mobility == PlatformMobility::kPlanarLegs) {
    check_non_zero(node, "plane_normal", leg.plane_normal);
  }
  check_links(node.required("link"));
  check_non_zero(node.required("link"), "parallelogram_axis", leg.parallelogram_axis);
  check_drive_section(node, leg.drive, leg.kind == LegKind::kRUS);
  if (auto joints = node.optional("joints")) {
    check_non_zero(*joints, "base_axis", leg.base_axis);
    check_non_zero(*joints, "platform_axis", leg.platform_axis);
  }
  return leg;
}

}  // namespace

LegChainDesign read_leg_chain_design(const YamlValue& root) {
  LegChainDesign d;
  d.model = "leg_chain";
  read_fields(root, d);
  int expected_legs = 6;
  if (d.mobility == PlatformMobility::kTranslational) expected_legs = 3;
  if (d.mobility == PlatformMobility::kSchoenflies) expected_legs = 4;
  if (d.mobility == PlatformMobility::kPlanarLegs) expected_legs = 3;
  if (auto v = root.optional("rotation_axis")) {
    if (d.mobility != PlatformMobility::kSchoenflies) {
      v->fail("no rotation_axis (it is for mobility: schoenflies)", v->describe());
    }
    check_non_zero(root, "rotation_axis", d.rotation_axis);
  }
  const auto legs = root.required("legs").elements(expected_legs);
  int revolute = 0;
  for (const YamlValue& node : legs) {
    bool is_revolute = false;
    d.legs.push_back(read_leg(node, d.mobility, is_revolute));
    revolute += is_revolute ? 1 : 0;
  }
  if (revolute != 0 && revolute != expected_legs) {
    root.required("legs").fail(
        "legs that are all RUS or all prismatic (UPS, PUS)",
        std::to_string(revolute) + " RUS legs of " + std::to_string(expected_legs));
  }
  if (revolute > 0) {
    if (auto v = root.optional("actuator_error")) {
      v->fail("actuator_error_deg (the legs are revolute)", v->describe());
    }
    d.actuator_error = deg_to_rad(1e-3);
    if (auto v = root.optional("actuator_error_deg"))
      d.actuator_error = deg_to_rad(v->as_non_negative());
  } else {
    if (auto v = root.optional("actuator_error_deg")) {
      v->fail("actuator_error in m (the legs are prismatic)", v->describe());
    }
    if (auto v = root.optional("actuator_error")) d.actuator_error = v->as_non_negative();
  }
  validate(root, d, make_leg_chain_machine);
  return d;
}

std::unique_ptr<Machine> load_leg_chain_machine(const YamlValue& root, const std::string& model) {
  if (model == "delta") return make_delta(read_delta_design(root));
  if (model == "linear_delta") return make_linear_delta(read_linear_delta_design(root));
  if (model == "hexaglide") return make_hexaglide(read_hexaglide_design(root));
  if (model == "tripod_3prs") return make_tripod_3prs(read_tripod_3prs_design(root));
  if (model == "leg_chain") return make_leg_chain_machine(read_leg_chain_design(root));
  return nullptr;
}

const char* leg_chain_model_names() {
  return "delta, linear_delta, hexaglide, tripod_3prs, leg_chain";
}

std::string leg_chain_machine_fields_markdown(std::string_view model) {
  if (model == "delta") return markdown_of(reader_start<DeltaDesign>());
  if (model == "linear_delta") return markdown_of(reader_start<LinearDeltaDesign>());
  if (model == "hexaglide") return markdown_of(reader_start<HexaglideDesign>());
  if (model == "tripod_3prs") return markdown_of(reader_start<Tripod3PrsDesign>());
  if (model == "leg_chain") {
    FieldDocs docs;
    LegChainDesign design;
    describe_fields(docs, design);
    LegChainLeg leg;
    LegChainLegFields fields{leg, PlatformMobility::kSixDof, true};
    docs.set_prefix("legs[].");
    describe_fields(docs, fields);
    return docs.markdown();
  }
  throw std::invalid_argument("leg_chain_machine_fields_markdown: unknown model '" +
                              std::string(model) + "'");
}

// The writers (io/machine_file_writer.cpp) take the same lists.
template void describe_fields(FieldWriter&, DeltaDesign&);
template void describe_fields(FieldWriter&, LinearDeltaDesign&);
template void describe_fields(FieldWriter&, HexaglideDesign&);
template void describe_fields(FieldWriter&, Tripod3PrsDesign&);
template void describe_fields(FieldWriter&, LegChainDesign&);
template void describe_fields(FieldWriter&, LegChainLegFields&);
template void describe_fields(FieldWriter&, BeamSectionFields&);

}  // namespace pkmopt
