// The mass model of a machine: the platform as a rigid body, the moving bodies of its legs, and
// gravity (docs/dynamics.md).
//
// Units and frames (docs/conventions.md): kg, m, kg*m^2, m/s^2.
//   platform.mass            the moving mass carried by the legs: platform, spindle, tool holder
//                            and tool (the tool and spindle are part of the platform);
//   platform.centre_of_mass  in the platform frame (the frame of the platform joints b_i);
//   platform.inertia         the 3x3 inertia tensor about the centre of mass in platform axes,
//                            given in files as [Ixx, Iyy, Izz, Ixy, Ixz, Iyz], the tensor's
//                            entries (I_xy = -integral of x y dm, the URDF convention);
//   gravity                  base frame, default (0, 0, -9.81).
// Leg bodies are slender links moving with the leg kinematics (models/dynamics/leg_dynamics.hpp):
//   cylinder  UPS: the part fixed to the base joint; centre of mass `centre` from the base joint
//             along the leg;
//   rod       UPS: the part fixed to the platform joint; `centre` from the platform joint back
//             along the leg;
//   carriage  PUS: the carriage on its guide (mass only, it translates);
//   link      PUS: the strut from the carriage joint, RUS: the rod from the elbow, `centre` from
//             that joint along the link (both rods of a parallelogram pair together);
//   crank     RUS: the crank from its pivot, `centre` from the pivot along the crank.
// `inertia` of a link: its moment of inertia about the centre of mass for rotations
// perpendicular to the link (kg*m^2; a thin rod of length l: m l^2 / 12); a crank's: about the
// centre of mass, about the crank axis. The spin of a link about its own axis is not set by the
// platform's motion (universal-spherical ends) and is neglected, as in the classical leg models
// (Dasgupta & Mruthyunjaya 1998; Tsai, "Robot Analysis", 1999).
#pragma once

#include <Eigen/Core>
#include <array>
#include <string>

namespace pkmopt {

/// A rigid body: mass, centre of mass in its own frame, inertia about the centre of mass.
struct RigidBody {
  double mass = 0.0;                                         ///< kg
  Eigen::Vector3d centre_of_mass = Eigen::Vector3d::Zero();  ///< m, body frame
  Eigen::Matrix3d inertia = Eigen::Matrix3d::Zero();         ///< kg*m^2, about the COM, body axes
};

/// The tensor of [Ixx, Iyy, Izz, Ixy, Ixz, Iyz] (its entries; symmetric).
Eigen::Matrix3d inertia_tensor(const std::array<double, 6>& components);
/// [Ixx, Iyy, Izz, Ixy, Ixz, Iyz] of a symmetric tensor.
std::array<double, 6> inertia_components(const Eigen::Matrix3d& inertia);

/// A slender link of a leg (see the header comment).
struct LinkMass {
  double mass = 0.0;     ///< kg
  double centre = 0.0;   ///< m, from the body's joint along the body
  double inertia = 0.0;  ///< kg*m^2 about the centre of mass (perpendicular; crank: its axis)
  bool any() const { return mass > 0.0 || inertia > 0.0; }
};

/// The moving bodies of a leg, by kind: UPS cylinder and rod, PUS carriage and link, RUS crank
/// and link. A body the leg's kind does not have is ignored.
struct LegMasses {
  LinkMass cylinder;
  LinkMass rod;
  double carriage = 0.0;  ///< kg
  LinkMass link;
  LinkMass crank;
  bool any() const {
    return cylinder.any() || rod.any() || carriage > 0.0 || link.any() || crank.any();
  }
};

/// Standard gravity g_n (m/s^2, ISO 80000-3): the unit of accelerations quoted in g.
inline constexpr double kStandardGravity = 9.80665;

/// Platform, legs (the same bodies on every leg) and gravity. `present` is false for a machine
/// without a mass model (no frequencies, no dynamics).
struct MassModel {
  bool present = false;
  RigidBody platform;
  LegMasses legs;
  Eigen::Vector3d gravity{0.0, 0.0, -9.81};  ///< m/s^2, base frame
};

/// Throws std::invalid_argument (message starting with `where`) unless the platform has a
/// mass > 0 and a positive definite inertia tensor satisfying the triangle inequalities of its
/// principal moments, every leg body has mass, centre and inertia finite and >= 0, and gravity
/// is finite.
void check_mass_model(const MassModel& model, const std::string& where);

}  // namespace pkmopt
