#include "io/machine/machine_file_lathe.hpp"

#include <stdexcept>

#include "io/format/field_list.hpp"
#include "io/machine/body_fields.hpp"
#include "io/machine/compliance_fields.hpp"
#include "io/machine/mass_fields.hpp"
#include "io/machine/model_registry.hpp"
#include "problems/design/lathe_design.hpp"

namespace pkmopt {
namespace {

FieldRule number(std::string_view unit, std::string_view doc) { return {.unit = unit, .doc = doc}; }

FieldRule positive(std::string_view unit, std::string_view doc) {
  return {.min = 0, .min_exclusive = true, .unit = unit, .doc = doc};
}

FieldRule non_negative(std::string_view unit, std::string_view doc) {
  return {.min = 0, .unit = unit, .doc = doc};
}

// An angle in degrees in the open interval (lo, hi), written in its shortest round-trip form.
FieldRule angle(double lo, double hi, std::string_view expected, std::string_view doc) {
  return {.min = lo,
          .max = hi,
          .min_exclusive = true,
          .max_exclusive = true,
          .degrees = true,
          .unit = "deg",
          .expected = expected,
          .doc = doc};
}

}  // namespace

template <class Fields>
void describe_fields(Fields& f, Lathe16k20f3Design& d) {
  f.note("model", "lathe_16k20f3", "", "required", "the machine model");
  f.note("name", "a text", "", "none", "free text");
  f.note("description", "a text", "", "none", "free text");
  f.field("centre_height", d.centre_height, positive("m", "spindle axis above the guideways"));
  f.field("tool_reach", d.tool_reach,
          non_negative("m", "turret centre to the working tool's tip (0: the TCP is the centre)"));
  f.field("approach_angle_deg", d.approach_angle,
          angle(-90, 90, "an angle in degrees in (-90, 90)",
                "a0: the tool's approach angle at phi = 0"));
  f.field("strut_length", d.strut_length,
          positive("m", "constant length of the parallelogram strut pairs (PUS)"));
  f.field("guide_y", d.guide_y, number("m", "y of the carriages' hinge line"));
  f.field("guide_z", d.guide_z, number("m", "z of the carriages' hinge line"));
  f.field("strut_joint_spread", d.strut_joint_spread,
          positive("m", "platform strut joints at (∓spread, strut_joint_y, strut_joint_z)"));
  f.field("strut_joint_y", d.strut_joint_y, number("m", "platform strut joints, platform frame y"));
  f.field("strut_joint_z", d.strut_joint_z, number("m", "platform strut joints, platform frame z"));
  FieldRange travel{d.carriage_min, d.carriage_max};
  f.field("carriage_travel", travel,
          {.unit = "m", .doc = "carriage position range along x (both carriages)"});
  f.field("strut_max_angle_deg", d.strut_max_angle,
          angle(0, 90, "an angle in degrees in (0, 90)",
                "hinge limit: angle between a strut and its guide"));
  f.field("strut_E", d.strut_E, positive("Pa", "Young's modulus of the strut rods"));
  f.field("strut_area", d.strut_area, positive("m²", "cross-section of a rod (2 rods per pair)"));
  f.field("carriage_stiffness", d.carriage_stiffness,
          non_negative("N/m", "carriage drive along x (0: rigid)"));
  f.section("carriage_drive",
            {.doc = "the carriages' drive train in series with carriage_stiffness; free lengths "
                    "at the carriage positions carriage_travel[0] and [1]"},
            [&](auto& g) { describe_screw_drive(g, d.carriage_drive); });
  f.section("strut_joints", {.doc = "the struts' joints, per rod"}, [&](auto& g) {
    describe_joint_stiffness(g, d.strut_base_joint_stiffness, d.strut_platform_joint_stiffness);
  });
  f.field("leg_base_x", d.leg_base_x, number("m", "overhead base joints at (x, y ∓ spacing/2, z)"));
  f.field("leg_base_y", d.leg_base_y, number("m", "y of the base joints' centre"));
  f.field("leg_base_z", d.leg_base_z, number("m", "z of the base joints"));
  f.field("leg_base_spacing", d.leg_base_spacing,
          positive("m", "y distance between the two base joints"));
  f.field("leg_joint_spacing", d.leg_joint_spacing,
          positive("m", "platform leg joints at (0, ∓spacing/2, leg_joint_z)"));
  f.field("leg_joint_z", d.leg_joint_z, number("m", "platform leg joints, platform frame z"));
  FieldRange leg_length{d.leg_min_length, d.leg_max_length};
  f.field("leg_length", leg_length,
          {.min = 0,
           .min_exclusive = true,
           .unit = "m",
           .expected = "[low, high] with 0 < low < high (m)",
           .doc = "electro-cylinder (UPS leg) length range"});
  f.field("leg_max_angle_deg", d.leg_max_angle,
          angle(0, 180, "an angle in degrees in (0, 180)", "U joint at the beam, from −z"));
  f.field("leg_E", d.leg_E, positive("Pa", "Young's modulus of the legs"));
  f.field("leg_area", d.leg_area, positive("m²", "cross-section of a cylinder housing"));
  f.field("leg_actuator_stiffness", d.leg_actuator_stiffness,
          non_negative("N/m", "screw and nut of the electro-cylinder, in series (0: rigid)"));
  f.section("leg_drive",
            {.doc = "the cylinders' drive train in series with leg_actuator_stiffness; free "
                    "lengths at the leg lengths leg_length[0] and [1]"},
            [&](auto& g) { describe_screw_drive(g, d.leg_drive); });
  f.section("leg_joints", {.doc = "the cylinders' joints"}, [&](auto& g) {
    describe_joint_stiffness(g, d.leg_base_joint_stiffness, d.leg_platform_joint_stiffness);
  });
  f.field("actuator_error", d.actuator_error,
          non_negative("m", "half-width of the actuator error box of tcp_error_max"));
  MassFields masses{d.masses, {.telescopic = true, .carriage = true}};
  describe_mass_section(f, masses);
  describe_link_shapes(f, d.shapes, false);
}

Lathe16k20f3Design read_lathe_16k20f3_design(const YamlValue& root) {
  Lathe16k20f3Design d;
  read_fields(root, d);
  check_drive_section(root, d.carriage_drive, false, "carriage_drive");
  check_drive_section(root, d.leg_drive, false, "leg_drive");
  check_mass_fields(root, d.masses);
  try {
    (void)make_lathe_16k20f3(d);
  } catch (const std::invalid_argument& e) {
    root.fail(e.what());
  }
  return d;
}

std::string lathe_machine_fields_markdown() { return fields_markdown(Lathe16k20f3Design{}); }

ModelEntry lathe_model_entry() {
  ModelEntry entry;
  entry.name = "lathe_16k20f3";
  entry.load = [](const YamlValue& root) {
    return make_lathe_16k20f3(read_lathe_16k20f3_design(root));
  };
  entry.fields_markdown = lathe_machine_fields_markdown;
  entry.platform_dofs = [](const YamlValue&) { return PlatformDofs{3, 1}; };
  entry.design_family = [](const YamlValue* machine) {
    return lathe_16k20f3_family(
        machine ? read_lathe_16k20f3_design(*machine) : Lathe16k20f3Design{},
        lathe_16k20f3_machine_file);
  };
  return entry;
}

// The writer (lathe_16k20f3_machine_file, below) takes the same list.
template void describe_fields(FieldWriter&, Lathe16k20f3Design&);

std::string lathe_16k20f3_machine_file(const Lathe16k20f3Design& d) {
  return model_file_text("lathe_16k20f3", d);
}

}  // namespace pkmopt
