// The field lists of the hexapod's leg stiffness, joint limits, tool and actuator error: the
// hexapod machine file (io/machine/machine_file.cpp) and the `machine:` section of a hexapod design
// study (studies/design_study_machine.cpp) read, write and document these keys from the one list
// here.
//
// Example:
//   f.section("legs", {.required = true}, [&](auto& g) { describe_leg_stiffness(g, d.stiffness);
//   });
//   ...
//   check_leg_stiffness(root.required("legs"), d.stiffness);  // the either/or rule
//   normalize_joint_axes(root, d.joints);                     // non-zero axes, made unit
#pragma once

#include <cmath>

#include "io/format/field_list.hpp"
#include "io/format/yaml_reader.hpp"
#include "io/machine/compliance_fields.hpp"
#include "models/hexapod/hexapod.hpp"

namespace pkmopt {

/// axial_stiffness | E and area, actuator_stiffness, drive, joint stiffnesses: the compliance
/// chain of a leg (docs/stiffness.md).
template <class Fields>
void describe_leg_stiffness(Fields& g, LegStiffness& s) {
  g.field("axial_stiffness", s.axial_stiffness,
          {.min = 0,
           .min_exclusive = true,
           .zero_is_unset = true,
           .unit = "N/m",
           .doc = "constant leg stiffness; give it, or E and area"});
  const bool axial = s.axial_stiffness > 0.0;
  g.field("E", s.E,
          {.min = 0,
           .min_exclusive = true,
           .zero_is_unset = true,
           .unit = "Pa",
           .doc = "Young's modulus of the leg (with area): k = E·area/q, q the leg length",
           .omit_when = [axial] { return axial; }});
  g.field("area", s.area,
          {.min = 0,
           .min_exclusive = true,
           .zero_is_unset = true,
           .unit = "m²",
           .doc = "cross-section of the leg",
           .omit_when = [axial] { return axial; }});
  g.field("actuator_stiffness", s.actuator_stiffness,
          {.min = 0,
           .min_exclusive = true,
           .zero_is_unset = true,
           .unit = "N/m",
           .doc = "in series with the leg: k = 1/(1/k_leg + 1/actuator_stiffness); unset: rigid"});
  g.section("drive", {.doc = "the leg's ball-screw drive train, in series (docs/stiffness.md)"},
            [&](auto& h) { describe_screw_drive(h, s.drive); });
  describe_joint_stiffness(g, s.base_joint_stiffness, s.platform_joint_stiffness);
}

/// base/platform_max_angle_deg (unset: unlimited) and the joint axes (written when not default).
template <class Fields>
void describe_hexapod_joints(Fields& g, HexapodJointLimits& j) {
  const bool default_axes = j.base_axis.isApprox(Eigen::Vector3d(0, 0, 1), 0.0) &&
                            j.platform_axis.isApprox(Eigen::Vector3d(0, 0, -1), 0.0);
  const FieldRule angle{.min = 0,
                        .max = 180,
                        .min_exclusive = true,
                        .infinite_is_unset = true,
                        .degrees = true,
                        .unit = "deg",
                        .expected = "an angle in degrees in (0, 180]"};
  FieldRule base = angle, platform = angle;
  base.doc = "limit of the angle between the leg direction s_i and the base joint axis";
  platform.doc = "limit of the angle between −s_i and R·platform_axis";
  g.field("base_max_angle_deg", j.base_max_angle, base);
  g.field("platform_max_angle_deg", j.platform_max_angle, platform);
  g.field("base_axis", j.base_axis,
          {.expected = "a non-zero vector",
           .doc = "base joint axis in the base frame (unit after reading)",
           .omit_when = [default_axes] { return default_axes; }});
  g.field("platform_axis", j.platform_axis,
          {.expected = "a non-zero vector",
           .doc = "platform joint axis in the platform frame (unit after reading)",
           .omit_when = [default_axes] { return default_axes; }});
}

/// The `tool:` section: the TCP in the platform frame.
template <class Fields>
void describe_hexapod_tool(Fields& g, Eigen::Vector3d& tcp) {
  g.field("tcp", tcp, {.unit = "m", .doc = "the TCP in the platform frame"});
}

/// `actuator_error`: the half-width of the actuator error box.
template <class Fields>
void describe_actuator_error(Fields& f, double& actuator_error) {
  f.field("actuator_error", actuator_error,
          {.min = 0, .unit = "m", .doc = "half-width of the actuator error box of tcp_error_max"});
}

/// After the list has read `legs`: either axial_stiffness or E and area (not both; the pair
/// complete), at least one element of the chain, and a consistent drive.
void check_leg_stiffness(const YamlValue& legs, const LegStiffness& s);

/// After the list has read `joints` (a key of `parent`, optional): the given axes are non-zero
/// and made unit.
void normalize_joint_axes(const YamlValue& parent, HexapodJointLimits& j);

}  // namespace pkmopt
