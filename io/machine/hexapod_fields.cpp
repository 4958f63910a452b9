#include "io/machine/hexapod_fields.hpp"

namespace pkmopt {

void check_leg_stiffness(const YamlValue& legs, const LegStiffness& s) {
  const bool e_or_area = legs.has("E") || legs.has("area");
  if (legs.has("axial_stiffness") && e_or_area)
    legs.required("axial_stiffness").fail("either axial_stiffness or E and area, not both");
  check_drive_section(legs, s.drive, false);
  if (s.axial_stiffness > 0.0) return;
  if (e_or_area) {
    (void)legs.required("E");  // both are needed: names the missing one
    (void)legs.required("area");
    return;
  }
  if (s.actuator_stiffness > 0.0 || s.drive.any() || s.base_joint_stiffness > 0.0 ||
      s.platform_joint_stiffness > 0.0)
    return;  // a leg of drive train and joints only
  legs.fail(
      "missing the leg stiffness: give axial_stiffness (N/m), or E (Pa) and area (m^2), or the "
      "drive train");
}

void normalize_joint_axes(const YamlValue& parent, HexapodJointLimits& j) {
  const std::optional<YamlValue> joints = parent.optional("joints");
  if (!joints) return;
  for (auto [key, axis] :
       {std::pair{"base_axis", &j.base_axis}, std::pair{"platform_axis", &j.platform_axis}}) {
    if (auto v = joints->optional(key)) {
      if (!(axis->norm() > 1e-12)) v->fail("a non-zero vector", v->describe());
      axis->normalize();
    }
  }
}

}  // namespace pkmopt
