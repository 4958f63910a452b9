// The field lists of a leg's compliance chain beyond the strut: the drive train (ball screw, nut,
// bearing, motor torsion; models/stiffness/compliance_chain.hpp) and the joints' axial stiffness.
// Machine files of every model (and the hexapod design study's machine section) read, write and
// document these keys from the one list here.
//
// Example:
//   g.section("drive", {}, [&](auto& h) { describe_screw_drive(h, k.drive); });
//   describe_joint_stiffness(g, k.base_joint_stiffness, k.platform_joint_stiffness);
//   ...
//   check_drive_section(legs, k.drive, /*revolute=*/false);  // after reading
#pragma once

#include <stdexcept>

#include "io/format/field_list.hpp"
#include "io/format/yaml_reader.hpp"
#include "models/stiffness/compliance_chain.hpp"

namespace pkmopt {

/// `drive:` {E, root_diameter, free_length_at_min, free_length_at_max, nut_stiffness,
/// bearing_stiffness, torsional_stiffness, lead}, every key optional (unset: rigid).
template <class Fields>
void describe_screw_drive(Fields& g, ScrewDrive& d) {
  const FieldRule positive{.min = 0, .min_exclusive = true, .zero_is_unset = true};
  auto rule = [&](std::string_view unit, std::string_view doc) {
    FieldRule r = positive;
    r.unit = unit;
    r.doc = doc;
    return r;
  };
  g.field("E", d.E, rule("Pa", "Young's modulus of the ball screw (with root_diameter)"));
  g.field("root_diameter", d.root_diameter,
          rule("m", "root (core) diameter of the screw: area π d²/4"));
  g.field("free_length_at_min", d.free_length_at_min,
          rule("m",
               "screw length from the fixed bearing to the nut with the actuator at its "
               "shortest (q_min)"));
  g.field("free_length_at_max", d.free_length_at_max,
          rule("m", "the same at its longest (q_max); linear in between: compliance l(q)/(E·A)"));
  g.field("nut_stiffness", d.nut_stiffness, rule("N/m", "axial stiffness of the ball nut"));
  g.field("bearing_stiffness", d.bearing_stiffness,
          rule("N/m", "axial stiffness of the screw's fixed bearing"));
  g.field("torsional_stiffness", d.torsional_stiffness,
          rule("N·m/rad",
               "motor, coupling and gearbox torsion at the screw (a crank: at the "
               "crank), seen axially as k_t·(2π/lead)²"));
  g.field("lead", d.lead,
          rule("m", "screw lead, metres per revolution (with torsional_stiffness)"));
}

/// The joints' own axial stiffness (unset: rigid), in series with the leg.
template <class Fields>
void describe_joint_stiffness(Fields& g, double& base, double& platform) {
  g.field("base_joint_stiffness", base,
          {.min = 0,
           .min_exclusive = true,
           .zero_is_unset = true,
           .unit = "N/m",
           .doc = "axial stiffness of the base-side joint, in series with the leg"});
  g.field("platform_joint_stiffness", platform,
          {.min = 0,
           .min_exclusive = true,
           .zero_is_unset = true,
           .unit = "N/m",
           .doc = "axial stiffness of the platform joint, in series with the leg"});
}

/// After the list has read `parent.<key>` (`drive` unless told): a half-given screw, torsion
/// without lead, or screw terms on a revolute actuator fail at that key
/// (models/stiffness/compliance_chain.hpp's rules).
inline void check_drive_section(const YamlValue& parent, const ScrewDrive& drive, bool revolute,
                                const std::string& key = "drive") {
  const std::optional<YamlValue> section = parent.optional(key);
  if (!section) return;
  try {
    check_screw_drive(drive, key, revolute);
  } catch (const std::invalid_argument& e) {
    std::string message = e.what();
    const std::string prefix = key + ": ";
    if (message.rfind(prefix, 0) == 0) message = message.substr(prefix.size());
    section->fail(message);
  }
}

}  // namespace pkmopt
