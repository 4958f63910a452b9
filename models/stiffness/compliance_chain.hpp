// The compliance chain of a leg's drive: ball screw, nut, axial bearing and motor torsion in
// series, each element optional (0 = absent, i.e. rigid).
//
//   base joint ── strut/cylinder ── [fixed bearing]──screw (free length l)──[nut] ── platform joint
//                                        │
//                               motor + coupling (torsion k_t)
//
// Compliances (m/N) of a prismatic actuator at position q in [q_min, q_max]:
//   screw:    l(q) / (E_s · π d_r² / 4),  l(q) = l_min + (l_max − l_min)(q − q_min)/(q_max − q_min)
//             (the free screw length between the fixed bearing and the nut: it grows with q when
//             the nut moves away from the bearing as the actuator extends, l_max > l_min, and
//             shrinks otherwise; l_min = l_max gives a constant length);
//   nut:      1 / k_nut;   bearing: 1 / k_bearing;
//   torsion:  (lead / 2π)² / k_t  (the motor, coupling and gearbox torsion k_t in N·m/rad seen
//             through the screw: an axial force F needs the torque F·lead/2π).
// A revolute actuator (a crank on a motor shaft) has only the torsion term, 1 / k_t in rad/(N·m);
// the screw, nut, bearing and lead must be absent.
// Sum of the terms: drive_compliance(). A constant lumped `actuator_stiffness` of the leg still
// adds in series; so do the joints' own axial stiffnesses (base and platform joint, N/m).
//
// Example:
//   ScrewDrive drive{.E = 2.1e11, .root_diameter = 0.028, .free_length_at_min = 0.15,
//                    .free_length_at_max = 0.60, .nut_stiffness = 8e8, .bearing_stiffness = 1.2e9,
//                    .torsional_stiffness = 4000, .lead = 0.01};
//   double c = drive_compliance(drive, q, 0.7, 1.15, /*revolute=*/false);   // m/N
#pragma once

#include <string>

namespace pkmopt {

/// A ball-screw drive train (all values >= 0; 0: the element is absent). Units: Pa, m, N/m,
/// N·m/rad, m per revolution.
struct ScrewDrive {
  double E = 0.0;                   ///< Young's modulus of the screw (Pa)
  double root_diameter = 0.0;       ///< screw root (core) diameter (m)
  double free_length_at_min = 0.0;  ///< screw length from the fixed bearing to the nut at q_min
  double free_length_at_max = 0.0;  ///< ... at q_max (m)
  double nut_stiffness = 0.0;       ///< axial stiffness of the nut (N/m)
  double bearing_stiffness = 0.0;   ///< axial stiffness of the fixed bearing (N/m)
  double torsional_stiffness =
      0.0;            ///< motor + coupling (+ gearbox) torsion at the screw (N·m/rad)
  double lead = 0.0;  ///< screw lead (m per revolution)

  /// True when some element is given.
  bool any() const;
  /// True when the screw itself (E, root diameter and a free length) is given.
  bool has_screw() const { return E > 0.0 && root_diameter > 0.0; }
};

/// The drive's compliance at actuator position q (m/N; rad/(N·m) for a revolute actuator); 0 when
/// no element is given. q outside [q_min, q_max] extrapolates the screw length linearly.
double drive_compliance(const ScrewDrive& drive, double q, double q_min, double q_max,
                        bool revolute);

/// Throws std::invalid_argument (messages start with `where`, e.g. "legs.drive") when a value is
/// negative or not finite, the screw is half given (E without root diameter, a free length
/// without the screw), the torsion of a prismatic drive lacks its lead, or a revolute drive has
/// screw, nut, bearing or lead terms.
void check_screw_drive(const ScrewDrive& drive, const std::string& where, bool revolute);

}  // namespace pkmopt
