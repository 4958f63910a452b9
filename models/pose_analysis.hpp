// Every per-pose metric of a machine over a list of poses, in parallel.
//
// analyze_poses(machine, poses, wrench) returns, for pose i, what machine.analyze gives
// (reachable, q, tau, stiffness_min, singularity_margin, det_j, tcp_error_max; frames and units
// in docs/conventions.md). The machine is shared by the OpenMP threads, each owns its
// MachineData. A hexapod goes through the SIMD batch path (models/hexapod_batch.hpp: the same
// metrics, four poses at a time) on slices of 1024 poses; a pose's result depends neither on its
// slice nor on the thread count.
//
// Example:
//   std::vector<PoseMetrics> m = pkmopt::analyze_poses(hexapod, poses, Wrench::Zero());
#pragma once

#include <span>
#include <vector>

#include "models/machine.hpp"

namespace pkmopt {

/// The metrics of every pose under the external wrench `wrench` at the TCP (base axes), and,
/// when `matrices` is given, each pose's compliance matrices (resized to the poses).
std::vector<PoseMetrics> analyze_poses(const Machine& machine, std::span<const Pose> poses,
                                       const Wrench& wrench,
                                       std::vector<PoseCompliance>* matrices = nullptr);

/// The natural frequencies and mode shapes of every pose (Machine::mode_shapes), in parallel;
/// a pose without modes (no mass model, unreachable, singular) gets empty matrices.
std::vector<PoseModes> mode_shapes_of_poses(const Machine& machine, std::span<const Pose> poses);

}  // namespace pkmopt
