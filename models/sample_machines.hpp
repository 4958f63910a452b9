// Named sample machines: the fixtures of tests, benchmarks and examples.
//
//   pkmopt::Hexapod hexapod(pkmopt::sample_machines::conventions_hexapod_design());
#pragma once

#include "models/hexapod.hpp"

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

}  // namespace pkmopt::sample_machines
