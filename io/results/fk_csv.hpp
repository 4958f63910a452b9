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

#include "models/core/machine.hpp"

namespace pkmopt {

/// The header line and the row of `result`, each ending in a newline.
std::string fk_csv(const FkResult& result);

}  // namespace pkmopt
