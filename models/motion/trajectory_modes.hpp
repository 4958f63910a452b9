// How near another assembly mode a trajectory passes: at each sample, every real solution of the
// forward kinematics for the sample's actuator values (Machine::all_forward_kinematics_solver),
// and the pose distance from the tracked one (the sample's own pose) to the nearest other.
//
// The distance is that of the forward-kinematics solutions (ForwardSolutions):
//     d = sqrt(|p_a - p_b|^2 + (rho theta)^2),   theta the angle of R_a^T R_b,
// rho the mean distance of the platform joints from the TCP (m): how far the platform's joints
// move. Two assembly modes meet at a parallel (type II) singularity, where d falls to 0; d is the
// room the machine has before a disturbance could carry it into another mode.
//
// Example:
//   if (const auto solver = machine.all_forward_kinematics_solver())
//     use(trajectory_assembly_modes(*solver.get(), run).samples[k].nearest_other);
#pragma once

#include <cmath>
#include <cstddef>
#include <vector>

#include "models/core/capabilities.hpp"
#include "models/motion/trajectory.hpp"

namespace pkmopt {

/// The assembly modes at one sample.
struct AssemblyModeSample {
  double nearest_other = INFINITY;  ///< m; inf when the tracked mode is the only real one
  std::size_t real_modes = 0;       ///< real solutions, the tracked one included
  std::size_t failed_paths = 0;     ///< paths that failed (their solutions may be missing)
  bool tracked_found = false;       ///< the sample's own pose is among the solutions
};

struct TrajectoryModes {
  std::vector<AssemblyModeSample> samples;  ///< one per trajectory sample
  double distance_length = 0.0;             ///< rho of the pose distance (m)
};

/// The assembly modes at every sample of `run`, by `solver` (the machine's
/// all_forward_kinematics_solver; parallel over the samples, the same result for any thread
/// count). A singular sample (two modes meet there), or one whose own pose is not among the
/// solutions (a path failed), gets nearest_other = 0.
TrajectoryModes trajectory_assembly_modes(const AllForwardKinematics& solver,
                                          const TrajectoryResult& run);

}  // namespace pkmopt
