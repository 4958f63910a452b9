// Named sample machines and seeded random geometries shared by the tests. The seeded stream
// Uniform is bench/uniform_stream.hpp's (the benchmarks draw their poses from the same one); the
// conventions hexapod is models/sample_machines.hpp's.
#pragma once

#include <cstdint>

#include "bench/uniform_stream.hpp"
#include "models/hexapod.hpp"
#include "models/sample_machines.hpp"

namespace pkmopt::sample_machines {

/// Dietmaier's general Stewart-Gough platform with 40 real assembly modes (P. Dietmaier,
/// "The Stewart-Gough platform of general geometry can have 40 real postures", Advances in
/// Robot Kinematics: Analysis and Control, Kluwer 1998, pp. 7-16). Leg lengths: dietmaier_legs().
inline pkmopt::HexapodDesign dietmaier_design() {
  pkmopt::HexapodDesign d;
  d.base_joints << 0, 1.107915, 0.549094, 0.735077, 0.514188, 0.590473,  //
      0, 0, 0.756063, -0.223935, -0.526063, 0.094733,                    //
      0, 0, 0, 0.525991, -0.368418, -0.205018;
  d.platform_joints << 0, 0.542805, 0.956919, 0.665885, 0.478359, -0.137087,  //
      0, 0, -0.528915, -0.353482, 1.158742, -0.235121,                        //
      0, 0, 0, 1.402538, 0.107672, 0.353913;
  d.min_length = 0.01;
  d.max_length = 10.0;
  d.stiffness.axial_stiffness = 1e7;
  return d;
}
inline Eigen::Matrix<double, 6, 1> dietmaier_legs() {
  return (Eigen::Matrix<double, 6, 1>() << 1, 0.645275, 1.086284, 1.503439, 1.281933, 0.771071)
      .finished();
}

/// A general 6-6 hexapod: joints scattered around semi-regular hexagons (non-planar), random
/// TCP, stiffness either constant or E*A with an actuator in series.
inline pkmopt::HexapodDesign random_hexapod_design(Uniform& u) {
  pkmopt::HexapodDesign d = pkmopt::semi_regular_hexapod(
      u(0.4, 0.9), pkmopt::deg_to_rad(u(5, 50)), u(0.15, 0.4), pkmopt::deg_to_rad(u(5, 50)));
  for (int i = 0; i < 6; ++i) {
    for (int k = 0; k < 3; ++k) {
      d.base_joints(k, i) += u(-0.05, 0.05);
      d.platform_joints(k, i) += u(-0.03, 0.03);
    }
  }
  d.min_length = 0.3;
  d.max_length = 2.0;
  if (u(0, 1) < 0.5) {
    d.stiffness.axial_stiffness = u(1e7, 1e8);
  } else {
    d.stiffness.E = 2.1e11;
    d.stiffness.area = u(1e-4, 5e-4);
    d.stiffness.actuator_stiffness = u(0, 1) < 0.5 ? 0.0 : u(1e8, 5e8);
  }
  d.tcp = {u(-0.05, 0.05), u(-0.05, 0.05), u(-0.2, 0.0)};
  d.actuator_error = u(1e-6, 1e-4);
  return d;
}

/// A pose near the middle of a random hexapod's workspace.
inline pkmopt::Pose random_pose(Uniform& u) {
  pkmopt::Pose p;
  p.position = {u(-0.1, 0.1), u(-0.1, 0.1), u(0.6, 1.0)};
  p.angles = pkmopt::deg_to_rad(Eigen::Vector3d(u(-20, 20), u(-20, 20), u(-30, 30)));
  return p;
}

}  // namespace pkmopt::sample_machines

// Test code outside namespace pkmopt names the fixtures sample_machines::...
namespace sample_machines = pkmopt::sample_machines;
