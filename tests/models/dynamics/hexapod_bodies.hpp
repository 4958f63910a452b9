// The tests' own model of a hexapod's moving bodies (the platform and each UPS leg's cylinder
// and rod, models/dynamics/mass_model.hpp), written from the geometry alone: body positions at a
// pose, momenta along a path and virtual velocities per unit TCP twist, all by central differences
// of positions. Used to check the inverse dynamics independently of models/dynamics/leg_dynamics.
#pragma once

#include <Eigen/Geometry>
#include <array>

#include "models/hexapod/hexapod.hpp"
#include "models/motion/trajectory.hpp"

namespace pkmopt::test_bodies {

// The test's own model of a hexapod's moving bodies at a pose: the platform (centre of mass and
// rotation) and per leg the unit vector s from the base joint and the two centres.
struct HexapodBodies {
  Eigen::Vector3d platform_centre;
  Eigen::Matrix3d R;
  std::array<Eigen::Vector3d, 6> s, cylinder, rod;
};

inline HexapodBodies bodies_at(const HexapodDesign& d, const Pose& pose) {
  HexapodBodies b;
  b.R = rotation_zyx<double>(pose.angles);
  b.platform_centre = pose.position + b.R * (d.masses.platform.centre_of_mass - d.tcp);
  for (int i = 0; i < 6; ++i) {
    const Eigen::Vector3d P = pose.position + b.R * (d.platform_joints.col(i) - d.tcp);
    const Eigen::Vector3d a = d.base_joints.col(i);
    b.s[i] = (P - a).normalized();
    b.cylinder[i] = a + d.masses.legs.cylinder.centre * b.s[i];
    b.rod[i] = P - d.masses.legs.rod.centre * b.s[i];
  }
  return b;
}

// Every body's linear momentum and angular momentum about its centre (base axes) at time t, by
// central differences of the positions along the path. Bodies: 0 platform, 1 + 2i cylinder i,
// 2 + 2i rod i.
struct Momenta {
  std::array<Eigen::Vector3d, 13> linear, angular;
};

inline Momenta momenta_at(const HexapodDesign& d, const TcpPath& path, double t) {
  const double h = 1e-5;
  const HexapodBodies b = bodies_at(d, path.at(t).pose), plus = bodies_at(d, path.at(t + h).pose),
                      minus = bodies_at(d, path.at(t - h).pose);
  const MassModel& m = d.masses;
  Momenta out;
  out.linear[0] = m.platform.mass * (plus.platform_centre - minus.platform_centre) / (2 * h);
  const Eigen::Matrix3d W = (plus.R - minus.R) / (2 * h) * b.R.transpose();  // [omega]x
  const Eigen::Vector3d omega(W(2, 1), W(0, 2), W(1, 0));
  out.angular[0] = b.R * m.platform.inertia * b.R.transpose() * omega;
  for (int i = 0; i < 6; ++i) {
    const Eigen::Vector3d s_dot = (plus.s[i] - minus.s[i]) / (2 * h);
    const Eigen::Vector3d w = b.s[i].cross(s_dot);  // no spin about the leg axis
    out.linear[1 + 2 * i] = m.legs.cylinder.mass * (plus.cylinder[i] - minus.cylinder[i]) / (2 * h);
    out.linear[2 + 2 * i] = m.legs.rod.mass * (plus.rod[i] - minus.rod[i]) / (2 * h);
    out.angular[1 + 2 * i] = m.legs.cylinder.inertia * w;  // I_t (I - s s^T) w = I_t w
    out.angular[2 + 2 * i] = m.legs.rod.inertia * w;
  }
  return out;
}

// The virtual velocities of every body (centre velocity and angular velocity) per unit TCP
// twist e_j at a pose, by central differences of the body model along e_j.
inline void virtual_velocities(const HexapodDesign& d, const Pose& pose, int j,
                               std::array<Eigen::Vector3d, 13>& v,
                               std::array<Eigen::Vector3d, 13>& w) {
  const double h = 1e-6;
  auto moved = [&](double e) {
    Pose p = pose;
    Eigen::Matrix3d R = rotation_zyx<double>(pose.angles);
    if (j < 3) {
      p.position(j) += e;
    } else {
      R = Eigen::AngleAxisd(e, Eigen::Vector3d::Unit(j - 3)).toRotationMatrix() * R;
      p.angles = angles_from_rotation(R);
    }
    return bodies_at(d, p);
  };
  const HexapodBodies b = bodies_at(d, pose), plus = moved(h), minus = moved(-h);
  v[0] = (plus.platform_centre - minus.platform_centre) / (2 * h);
  w[0] = Eigen::Vector3d::Zero();
  if (j >= 3) w[0](j - 3) = 1.0;
  for (int i = 0; i < 6; ++i) {
    const Eigen::Vector3d s_dot = (plus.s[i] - minus.s[i]) / (2 * h);
    v[1 + 2 * i] = (plus.cylinder[i] - minus.cylinder[i]) / (2 * h);
    v[2 + 2 * i] = (plus.rod[i] - minus.rod[i]) / (2 * h);
    w[1 + 2 * i] = w[2 + 2 * i] = b.s[i].cross(s_dot);
  }
}

inline std::array<double, 13> body_masses(const MassModel& m) {
  std::array<double, 13> out;
  out[0] = m.platform.mass;
  for (int i = 0; i < 6; ++i) {
    out[1 + 2 * i] = m.legs.cylinder.mass;
    out[2 + 2 * i] = m.legs.rod.mass;
  }
  return out;
}

}  // namespace pkmopt::test_bodies
