// Named sample machines and seeded random geometries shared by the tests. The seeded stream
// Uniform is bench/uniform_stream.hpp's (the benchmarks draw their poses from the same one); the
// conventions hexapod is models/sample_machines.hpp's.
#pragma once

#include <Eigen/Geometry>
#include <cmath>
#include <cstdint>

#include "bench/uniform_stream.hpp"
#include "models/hexapod/hexapod.hpp"
#include "models/leg_chain/leg_chain.hpp"
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

/// Random platform and UPS leg masses: the platform a 0.6 x 0.5 x 0.2 m box of 20..60 kg turned
/// by a random rotation, its centre of mass off the TCP; gravity slightly off the vertical.
inline pkmopt::MassModel random_hexapod_masses(Uniform& u) {
  pkmopt::MassModel m;
  m.present = true;
  m.platform.mass = u(20, 60);
  m.platform.centre_of_mass = {u(-0.05, 0.05), u(-0.05, 0.05), u(-0.1, 0.1)};
  // A box of sides 0.6 x 0.5 x 0.2 turned by a random rotation: a real inertia tensor.
  const double a = 0.6, b = 0.5, c = 0.2, mass = m.platform.mass;
  const Eigen::Vector3d principal(mass * (b * b + c * c) / 12, mass * (a * a + c * c) / 12,
                                  mass * (a * a + b * b) / 12);
  const Eigen::Matrix3d Q =
      Eigen::AngleAxisd(u(-1, 1), Eigen::Vector3d(u(-1, 1), u(-1, 1), 1).normalized())
          .toRotationMatrix();
  m.platform.inertia = Q * principal.asDiagonal() * Q.transpose();
  m.platform.inertia = 0.5 * (m.platform.inertia + m.platform.inertia.transpose()).eval();
  m.legs.cylinder = {.mass = u(3, 8), .centre = u(0.1, 0.3), .inertia = u(0.02, 0.1)};
  m.legs.rod = {.mass = u(1, 4), .centre = u(0.1, 0.3), .inertia = u(0.01, 0.05)};
  m.gravity = {u(-1, 1), u(-1, 1), -9.81};
  return m;
}

/// Masses for the linear delta of examples/linear_delta.yaml: a 6 kg platform (centre of mass off
/// the TCP), 4 kg carriages and 1.5 kg links (parallelogram pairs) centred 0.2 m from the
/// carriage joints.
inline void add_linear_delta_masses(pkmopt::LegChainDesign& design) {
  design.masses.present = true;
  design.masses.platform.mass = 6.0;
  design.masses.platform.centre_of_mass = {0.01, -0.02, 0.03};
  design.masses.platform.inertia = Eigen::Vector3d(0.05, 0.06, 0.09).asDiagonal();
  design.masses.legs.carriage = 4.0;
  design.masses.legs.link = {.mass = 1.5, .centre = 0.2, .inertia = 0.03};
}

/// A pose near the middle of a random hexapod's workspace.
inline pkmopt::Pose random_pose(Uniform& u) {
  pkmopt::Pose p;
  p.position = {u(-0.1, 0.1), u(-0.1, 0.1), u(0.6, 1.0)};
  p.angles = pkmopt::deg_to_rad(Eigen::Vector3d(u(-20, 20), u(-20, 20), u(-30, 30)));
  return p;
}

/// The cubic (orthogonal) Gough-Stewart platform of Geng & Haynes ("Six degree-of-freedom active
/// vibration control using the Stewart platforms", IEEE TCST 2, 1994), cube side Hc * sqrt(3)
/// with its diagonal vertical and its centre at the platform frame's origin at the home pose
/// (legs: cube edges, every leg axial_stiffness; lengths 0.1..0.5 m; TCP at the origin).
inline pkmopt::HexapodDesign cubic_hexapod_design(double Hc, double axial_stiffness) {
  const double L = Hc * std::sqrt(3.0);
  Eigen::Matrix3d R;  // columns: the cube's axes turned so that its diagonal is vertical
  R.col(0) = Eigen::Vector3d(2, -1, -1).normalized();
  R.col(1) = Eigen::Vector3d(0, 1, -1).normalized();
  R.col(2) = Eigen::Vector3d(1, 1, 1).normalized();
  auto vertex = [&](double x, double y, double z) {
    return Eigen::Vector3d(R.transpose() * Eigen::Vector3d(x, y, z) -
                           Eigen::Vector3d(0, 0, 1.5 * Hc));
  };
  const Eigen::Vector3d bottom[6] = {vertex(0, 0, L), vertex(L, 0, 0), vertex(L, 0, 0),
                                     vertex(0, L, 0), vertex(0, L, 0), vertex(0, 0, L)};
  const Eigen::Vector3d top[6] = {vertex(L, 0, L), vertex(L, 0, L), vertex(L, L, 0),
                                  vertex(L, L, 0), vertex(0, L, L), vertex(0, L, L)};
  pkmopt::HexapodDesign design;
  for (int i = 0; i < 6; ++i) {
    const Eigen::Vector3d s = (top[i] - bottom[i]).normalized();
    design.base_joints.col(i) = bottom[i] - 0.05 * s;  // anywhere on the leg's line
    design.platform_joints.col(i) = top[i];            // platform frame = cube frame at home
  }
  design.min_length = 0.1;
  design.max_length = 0.5;
  design.stiffness.axial_stiffness = axial_stiffness;
  return design;
}

}  // namespace pkmopt::sample_machines

// Test code outside namespace pkmopt names the fixtures sample_machines::...
namespace sample_machines = pkmopt::sample_machines;
