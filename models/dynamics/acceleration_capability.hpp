// Acceleration capability: the worst actuator forces when the TCP, at rest at a pose, accelerates
// in any direction with |a| <= a_max on top of an external wrench and gravity (docs/dynamics.md).
// Drives of a machine tool are sized for its rapid moves: 1-2 g for hexapods and tripod heads.
//
// At zero velocity the inertia of every body is linear in the TCP acceleration xi_dot = [a; 0],
// and so are the actuator forces of the inverse dynamics (Machine::inverse_dynamics: the static
// solve under the wrench, gravity and inertia). So
//   tau(a) = tau(0) + G a,   G_k = tau(e_k) - tau(0)   (n x 3, the forces per unit acceleration),
// and the worst a on the ball |a| <= a_max is a_max G_i / |G_i| (or its opposite):
//   max over |a| <= a_max of |tau_i(a)| = |tau_i(0)| + a_max |G_i|
// exactly. Velocity-dependent (Coriolis and centripetal) forces are left out: they vanish where
// a rapid move starts and stops, where its acceleration is largest; a path's own inverse
// dynamics with them is `pkmopt trajectory`. Angular accelerations are not included (the TCP is
// translated).
//
// For platforms that translate freely (hexapods, deltas, the hexaglide, Schoenflies machines,
// hybrid machines whose serial axes carry such a module).
//
// Example:
//   Eigen::VectorXd bound;
//   if (pkmopt::acceleration_force_bound(machine, *data, pose, wrench, 9.81, bound))
//     worst = std::max(worst, bound.maxCoeff());   // N (or N*m for revolute drives)
#pragma once

#include <Eigen/Core>

#include "models/core/machine.hpp"
#include "models/core/pose.hpp"

namespace pkmopt {

/// Per actuator, max over |a| <= a_max (m/s^2) of |tau_i| at `pose` under `wrench` (N, N*m at
/// the TCP, base axes), gravity and the inertia of a_max (see the header comment). Returns false
/// (bound untouched) without a mass model, when a leg cannot close or at a singular pose. Leaves
/// data.compliance_metrics as it found it.
bool acceleration_force_bound(const Machine& machine, MachineData& data, const Pose& pose,
                              const Wrench& wrench, double a_max, Eigen::VectorXd& bound);

}  // namespace pkmopt
