// Candidate poses for choosing calibration measurements (select_calibration_poses in
// problems/calibration/calibration.hpp): the reachable ones of a list, or a grid of positions and
// orientations.
//
// reachable_candidates keeps, in order, the poses the machine reaches (Machine::reachable:
// actuator ranges and joint limits), each with its label (a line of the file it came from);
// grid_candidates does the same over a grid of steps^6 TCP poses in the base frame:
//   x, y in [-xy_range, xy_range], z in [z_min, z_max]  (m)
//   rx, ry, rz in [-angle_range, angle_range]             (rad, R = Rz Ry Rx)
// each at `steps` evenly spaced levels, ends included, x varying slowest and rz fastest; a
// reachable grid pose is labelled with its 1-based number among the reachable ones. Both count
// the poses left out as unreachable.
//
// Example:
//   CandidateGrid grid;                          // the defaults of `pkmopt calibration-poses
//   --grid` CalibrationCandidates c = grid_candidates(Hexapod(design), grid); PoseSelection s =
//   select_calibration_poses(x, design.tcp, c.poses, 12, options);
#pragma once

#include <vector>

#include "models/core/machine.hpp"
#include "models/core/pose.hpp"

namespace pkmopt {

/// Reachable candidate poses (base frame, m and rad) with their labels.
struct CalibrationCandidates {
  std::vector<Pose> poses;
  std::vector<int> labels;  ///< labels[i] belongs to poses[i]
  int unreachable = 0;      ///< poses left out
};

/// The poses of `poses` the machine reaches; `labels[i]` belongs to `poses[i]` (same size, else
/// std::invalid_argument).
CalibrationCandidates reachable_candidates(const Machine& machine, const std::vector<Pose>& poses,
                                           const std::vector<int>& labels);

/// A grid of candidate poses (see the header comment).
struct CandidateGrid {
  double xy_range = 0.15;                 ///< m
  double z_min = 0.75, z_max = 0.95;      ///< m
  double angle_range = 12.0 * kDegToRad;  ///< rad
  int steps = 3;                          ///< levels per coordinate, >= 2
};

/// The reachable poses of the grid; std::invalid_argument when steps < 2.
CalibrationCandidates grid_candidates(const Machine& machine, const CandidateGrid& grid);

}  // namespace pkmopt
