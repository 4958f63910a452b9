// Named sample machines: the fixtures of tests, benchmarks and examples.
//
//   pkmopt::Hexapod hexapod(pkmopt::sample_machines::conventions_hexapod_design());
#pragma once

#include "models/hexapod/hexapod.hpp"

namespace pkmopt::sample_machines {

/// The hexapod of docs/conventions.md (examples/hexapod.yaml): base r 0.60 m, platform r 0.25 m,
/// pair separations 20 deg, legs 0.70..1.15 m, E 2.1e11 Pa, area 3e-4 m^2, actuator 2e8 N/m in
/// series, joint limits 45 deg, TCP 0.10 m below the platform origin.
inline HexapodDesign conventions_hexapod_design() {
  HexapodDesign d = semi_regular_hexapod(0.60, deg_to_rad(20), 0.25, deg_to_rad(20));
  d.min_length = 0.70;
  d.max_length = 1.15;
  d.stiffness.E = 2.1e11;
  d.stiffness.area = 3.0e-4;
  d.stiffness.actuator_stiffness = 2.0e8;
  d.joints.base_max_angle = deg_to_rad(45);
  d.joints.platform_max_angle = deg_to_rad(45);
  d.tcp = {0, 0, -0.10};
  return d;
}

/// The moving masses of examples/hexapod_masses.yaml: a 45 kg platform with its spindle (centre
/// of mass 40 mm below the joint plane, Ixx = Iyy = 1.3, Izz = 2.0 kg m^2), 6 kg cylinders (centre
/// 0.2 m from the base joint, 0.125 kg m^2) and 3 kg rods (0.3 m from the platform joint,
/// 0.0625 kg m^2).
inline MassModel milling_hexapod_masses() {
  MassModel m;
  m.present = true;
  m.platform.mass = 45.0;
  m.platform.centre_of_mass = {0, 0, -0.04};
  m.platform.inertia = Eigen::Vector3d(1.3, 1.3, 2.0).asDiagonal();
  m.legs.cylinder = {.mass = 6.0, .centre = 0.2, .inertia = 0.125};
  m.legs.rod = {.mass = 3.0, .centre = 0.3, .inertia = 0.0625};
  return m;
}

}  // namespace pkmopt::sample_machines
