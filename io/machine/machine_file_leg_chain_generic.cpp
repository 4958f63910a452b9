// The generic leg-chain machine file `model: leg_chain` (any mobility, an explicit list of legs):
// its field lists, the reader of its legs and actuator error, and its docs table.
#include <string>

#include "io/machine/body_fields.hpp"
#include "io/machine/leg_chain_fields.hpp"
#include "io/machine/machine_file_leg_chain.hpp"
#include "io/machine/mass_fields.hpp"

namespace pkmopt {

using namespace leg_chain_fields;  // NOLINT: the shared rules of the field lists

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
  MassFields masses{d.masses, kAllBodies};
  describe_mass_section(f, masses);
  describe_link_shapes(f, d.shapes, true);
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
  check_mass_fields(root, d.masses);
  validate(root, d, make_leg_chain_machine);
  return d;
}

std::string leg_chain_fields::generic_fields_markdown() {
  FieldDocs docs;
  LegChainDesign design;
  describe_fields(docs, design);
  LegChainLeg leg;
  LegChainLegFields fields{leg, PlatformMobility::kSixDof, true};
  docs.set_prefix("legs[].");
  describe_fields(docs, fields);
  return docs.markdown();
}

// The writers (delta_machine_file and the others, io/machine/machine_file_leg_chain.cpp) take the
// same lists.
template void describe_fields(FieldWriter&, LegChainDesign&);
template void describe_fields(FieldWriter&, LegChainLegFields&);

}  // namespace pkmopt
