// The output CSV of `pkmopt fk`: the forward-kinematics solution (Machine::forward_kinematics)
// as a header and one row,
//
//   x,y,z,rx,ry,rz,converged,iterations,residual
//
// x, y, z the TCP position (m, base frame), rx, ry, rz its orientation (deg, R = Rz Ry Rx),
// converged 1 or 0, the solver's iteration count, and residual = max |q(pose) - q| at the
// returned pose (the actuators' internal units: m, or rad for revolute drives). Numbers in the
// shortest text that reads back to the same double (format_number).
//
// Example:
//   const FkResult r = machine.forward_kinematics(q, std::nullopt, FkOptions{});
//   std::cout << pkmopt::fk_csv(r);
#pragma once

#include <string>

#include "models/core/capabilities.hpp"
#include "models/core/machine.hpp"

namespace pkmopt {

/// The header line and the row of `result`, each ending in a newline.
std::string fk_csv(const FkResult& result);

/// Every real solution (`pkmopt fk --all`), one row each, nearest the reference pose first:
///   mode,x,y,z,rx,ry,rz,residual,det_j,reachable,nearest_other,to_reference
/// mode numbers the rows from 1; residual as above (m); det_j the determinant of the inverse
/// Jacobian (dq/dx; its sign tells the working mode, 0 at a parallel singularity); reachable 1
/// or 0 (strokes, joint limits); nearest_other and to_reference the pose distance
/// sqrt(|dp|^2 + (rho theta)^2) (m) to the nearest other real solution (empty when there is
/// none) and to the reference pose (the guess, else the home pose).
std::string fk_all_csv(const ForwardSolutions& solutions);

}  // namespace pkmopt
