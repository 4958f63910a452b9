// Every per-pose metric of a machine over a list of poses, in parallel.
//
// analyze_poses(machine, poses, wrench) returns, for pose i, what machine.analyze gives
// (reachable, q, tau, stiffness_min, singularity_margin, det_j, tcp_error_max; frames and units
// in docs/conventions.md). The machine is shared by the OpenMP threads, each owns its
// MachineData. A hexapod goes through the SIMD batch path (models/hexapod/hexapod_batch.hpp: the
// same metrics, four poses at a time) on slices of 1024 poses; a pose's result depends neither on
// its slice nor on the thread count.
//
// Example:
//   std::vector<PoseMetrics> m = pkmopt::analyze_poses(hexapod, poses, Wrench::Zero());
#pragma once

#include <cstddef>
#include <functional>
#include <span>
#include <vector>

#include "models/core/capabilities.hpp"
#include "models/core/machine.hpp"

namespace pkmopt {

/// The metrics of every pose under the external wrench `wrench` at the TCP (base axes), and,
/// when `matrices` is given, each pose's compliance matrices (resized to the poses).
std::vector<PoseMetrics> analyze_poses(const Machine& machine, std::span<const Pose> poses,
                                       const Wrench& wrench,
                                       std::vector<PoseCompliance>* matrices = nullptr);

/// The poses of analyze_pose_slices go through in one piece.
inline constexpr std::size_t kPoseSlice = 1024;

/// One slice of analyze_pose_slices: poses [start, start + poses.size()).
struct PoseSlice {
  std::size_t start = 0;
  std::span<Pose> poses;               ///< filled by `fill`
  std::span<PoseMetrics> metrics;      ///< the results, for `consume`
  std::span<PoseCompliance> matrices;  ///< the compliance matrices (empty unless asked for)
};

/// analyze_poses for `count` poses that the caller hands over and takes back slice by slice
/// (kPoseSlice poses), so that neither the poses nor the results of all of them need to be held
/// at once: `fill(slice)` writes slice.poses, the slice is analyzed (the SIMD batch path for a
/// hexapod), and `consume(slice)` reads slice.metrics (and slice.matrices when `matrices` is
/// set). Both are called from OpenMP threads (`threads` of them; 0: OpenMP's default), each
/// slice once, so they must only touch the slice's own poses. The results are those of
/// analyze_poses for the same poses, whatever the thread count. An exception thrown by `fill`
/// or `consume` is rethrown once every thread has stopped.
void analyze_pose_slices(const Machine& machine, std::size_t count, const Wrench& wrench,
                         bool matrices, int threads,
                         const std::function<void(const PoseSlice&)>& fill,
                         const std::function<void(const PoseSlice&)>& consume);

/// The natural frequencies and mode shapes of every pose (Machine::mode_shapes), in parallel;
/// a pose without modes (no mass model, unreachable, singular) gets empty matrices.
std::vector<PoseModes> mode_shapes_of_poses(const Machine& machine, std::span<const Pose> poses);

}  // namespace pkmopt
