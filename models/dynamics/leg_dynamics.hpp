// The moving bodies of a leg (models/dynamics/mass_model.hpp) as functions of the motion of the
// leg's platform point P: their velocity maps, their accelerations, and what they add to the TCP
// mass matrix and to the inertia and gravity wrench of the inverse dynamics (docs/dynamics.md).
//
// A leg at a pose is given by its joint points (base frame):
//   telescopic (UPS)  base joint a and P; d = P - a, q = |d|, s = d / q, Pi = I - s s^T;
//   carriage (PUS)    the carriage joint C on its guide of unit direction u, and P; d = P - C,
//                     |d| = L constant, s = d / L;
//   crank (RUS)       the pivot O, the unit crank axis w, the elbow E (crank c = E - O), and P;
//                     d = P - E, |d| = L constant, s = d / L, t = w x c (the elbow's velocity per
//                     unit crank rate).
// Velocities from v_P (the rates follow from the constant link length, d . d_dot = 0):
//   UPS  s_dot = Pi v_P / q, link angular velocity omega = s x s_dot; cylinder centre
//        a + e s, rod centre P - e s;
//   PUS  carriage rate q_dot = s . v_P / s . u; d_dot = v_P - q_dot u; omega = s x d_dot / L;
//        carriage q_dot u, link centre C + e s;
//   RUS  crank rate q_dot = s . v_P / s . t; d_dot = v_P - q_dot t; crank omega = q_dot w,
//        crank centre O + (e / |c|) c; link omega = s x d_dot / L, link centre E + e s.
// Accelerations from (v_P, a_P), by differentiating the same relations:
//   UPS  q_ddot = s_dot . v_P + s . a_P, s_ddot = (a_P - q_ddot s - 2 q_dot s_dot) / q,
//        alpha = s x s_ddot;
//   PUS  q_ddot = (s . a_P + |d_dot|^2 / L) / s . u, d_ddot = a_P - q_ddot u,
//        alpha = s x d_ddot / L;
//   RUS  q_ddot = (s . a_P - q_dot^2 s . (w x (w x c)) + |d_dot|^2 / L) / s . t,
//        c_ddot = q_ddot t + q_dot^2 w x (w x c), d_ddot = a_P - c_ddot.
// Each body then adds to the force at P that is equivalent, by virtual power, to its gravity
// and inertia: f_P += A^T m (g - a_c) + W^T (-I alpha - omega x I omega), with v_c = A v_P and
// omega = W v_P; and to the 3x3 mass matrix on v_P: M_P += m A^T A + W^T I W. A link's inertia
// tensor is I_t (I - s s^T) (no spin about its own axis), a crank's I_c w w^T.
//
// Example:
//   pkmopt::LegPoints leg{.kind = pkmopt::LegBodyKind::kTelescopic, .joint = a, .platform = P};
//   Eigen::Matrix3d M_P = pkmopt::leg_mass_matrix(leg, masses.legs);
//   Eigen::Vector3d f_P = pkmopt::leg_dynamic_force(leg, masses.legs, v_P, a_P, gravity);
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <vector>

#include "models/dynamics/mass_model.hpp"

namespace pkmopt {

/// Which bodies a leg has and how they move (see the header comment).
enum class LegBodyKind { kTelescopic, kCarriage, kCrank };

/// A leg's joint points at a pose (base frame).
struct LegPoints {
  LegBodyKind kind = LegBodyKind::kTelescopic;
  Eigen::Vector3d joint = Eigen::Vector3d::Zero();     ///< UPS: base joint a; PUS: C; RUS: E
  Eigen::Vector3d platform = Eigen::Vector3d::Zero();  ///< P
  Eigen::Vector3d axis = Eigen::Vector3d::Zero();      ///< PUS: guide u; RUS: crank axis w
  Eigen::Vector3d pivot = Eigen::Vector3d::Zero();     ///< RUS: crank pivot O
};

/// One body of a leg: mass, inertia tensor about its centre (base axes), velocity maps
/// v_c = A v_P, omega = W v_P, and its motion at the (v_P, a_P) it was evaluated with.
struct LegBody {
  double mass = 0.0;
  Eigen::Matrix3d inertia = Eigen::Matrix3d::Zero();
  Eigen::Matrix3d A = Eigen::Matrix3d::Zero();
  Eigen::Matrix3d W = Eigen::Matrix3d::Zero();
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();  ///< centre of mass (base frame)
  Eigen::Vector3d velocity = Eigen::Vector3d::Zero();
  Eigen::Vector3d angular_velocity = Eigen::Vector3d::Zero();
  Eigen::Vector3d acceleration = Eigen::Vector3d::Zero();
  Eigen::Vector3d angular_acceleration = Eigen::Vector3d::Zero();
};

/// The bodies of a leg (2 per kind; a massless body has mass and inertia 0) moving with the
/// platform point's velocity v_P and acceleration a_P. Returns false when the leg is degenerate
/// (zero length, or the actuator cannot drive P: s . u = 0 or s . t = 0, a serial singularity).
bool leg_bodies(const LegPoints& leg, const LegMasses& masses, const Eigen::Vector3d& v_P,
                const Eigen::Vector3d& a_P, LegBody (&bodies)[2]);

/// The leg's 3x3 mass matrix on v_P (kinetic energy 1/2 v_P^T M_P v_P); zero if degenerate.
Eigen::Matrix3d leg_mass_matrix(const LegPoints& leg, const LegMasses& masses);

/// The mass in motion: the platform and the bodies of legs of these kinds (kg).
double moving_mass(const MassModel& model, const std::vector<LegBodyKind>& legs);

/// The force at P equivalent to the leg bodies' gravity and inertia; zero if degenerate.
Eigen::Vector3d leg_dynamic_force(const LegPoints& leg, const LegMasses& masses,
                                  const Eigen::Vector3d& v_P, const Eigen::Vector3d& a_P,
                                  const Eigen::Vector3d& gravity);

}  // namespace pkmopt
