// Acceleration capability: the worst actuator forces when the TCP, at rest at a pose, accelerates
// in any direction with |a| <= a_max on top of an external wrench and gravity (docs/dynamics.md).
// Drives of a machine tool are sized for its rapid moves: 1-2 g for hexapods and tripod heads.
//
// At zero velocity the inertia of every body is linear in the TCP acceleration xi_dot = [a; 0]:
// w_dyn = w_g - M [a; 0] (M the TCP mass matrix, models/machine_dynamics.hpp), and the actuator
// forces of the static solve are linear in the wrench, tau(w) (Machine::analyze). So
//   tau(a) = tau(w + w_g) - G a,   G = [tau(M e_x), tau(M e_y), tau(M e_z)]   (n x 3),
// and the worst a on the ball |a| <= a_max is a_max G_i / |G_i| (or its opposite):
//   max over |a| <= a_max of |tau_i(a)| = |tau_i(w + w_g)| + a_max |G_i|
// exactly. Velocity-dependent (Coriolis and centripetal) forces are left out: they vanish where
// a rapid move starts and stops, where its acceleration is largest; a path's own inverse
// dynamics with them is `pkmopt trajectory`. Angular accelerations are not included (the TCP is
// translated).
//
// For platforms that translate freely (hexapods, deltas, the hexaglide, Schoenflies machines).
//
// Example:
//   Eigen::VectorXd bound;
//   if (pkmopt::acceleration_force_bound(machine, *data, pose, wrench, 9.81, bound))
//     worst = std::max(worst, bound.maxCoeff());   // N (or N*m for revolute drives)
#pragma once

#include <Eigen/Core>

#include "models/machine.hpp"
#include "models/pose.hpp"

namespace pkmopt {

/// Per actuator, max over |a| <= a_max (m/s^2) of |tau_i| at `pose` under `wrench` (N, N*m at
/// the TCP, base axes), gravity and the inertia of a_max (see the header comment). Returns false
/// (bound untouched) without a mass model, when a leg cannot close or at a singular pose. Leaves
/// data.compliance_metrics as it found it.
bool acceleration_force_bound(const Machine& machine, MachineData& data, const Pose& pose,
                              const Wrench& wrench, double a_max, Eigen::VectorXd& bound);

}  // namespace pkmopt
