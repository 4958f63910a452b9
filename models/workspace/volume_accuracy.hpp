// How accurate a workspace volume is, and the grid that makes it accurate enough.
//
// The grid volume converges like h^2 where the boundary is smooth and more slowly where the grid
// cuts a sharp edge of the region (models/workspace/workspace.hpp). The estimate of the error of
// V(h) is the difference to the grid at twice the spacing,
//   error(h) = |V(h) - V(2h)|,
// a bound whenever the error at least halves when h does (order >= 1) and keeps its sign; a pure
// h^2 error would be a third of it (Richardson), which measured errors at sharp edges exceed (the
// docs/conventions.md hexapod at 20 mm: true error 0.12 %, h^2 estimate 0.08 %, this one 0.23 %).
// choose_workspace_resolution starts at h0 (default: the largest side of the search box / 16)
// and halves h until error(h) <= tolerance * V(h) (default tolerance 0.5 %), or until the next
// grid would pass 3e7 nodes or max_grid_nodes (then `met` is false and the caller says so). A fixed
// resolution gets its estimate from one extra grid at 2h (1/8 of the nodes).
//
// Example:
//   pkmopt::WorkspaceOptions options;                 // orientations, restrictions, ...
//   const auto acc = pkmopt::choose_workspace_resolution(machine, options, 0.005);
//   options.resolution = acc.resolution;              // then compute_workspace(machine, options)
#pragma once

#include <optional>

#include "models/core/machine.hpp"
#include "models/workspace/workspace.hpp"

namespace pkmopt {

struct VolumeAccuracy {
  double resolution = 0.0;     ///< h (m): the grid the estimate belongs to
  double volume = 0.0;         ///< V(h) (m^3)
  double coarse_volume = 0.0;  ///< V(2h) (m^3)
  double error = 0.0;          ///< |V(h) - V(2h)| (m^3)
  double tolerance = 0.0;      ///< the relative accuracy asked for (0 for a fixed resolution)
  bool met = false;            ///< error <= tolerance * volume (always false for a fixed h)
  int grids = 0;               ///< volume-only grids computed
  /// error / volume; 0 for an empty workspace.
  double relative_error() const { return volume > 0.0 ? error / volume : 0.0; }
};

/// The error estimate of a workspace volume at options.resolution (one more grid at 2h);
/// `volume` is V(h) when already known (compute_workspace's), else it is computed.
VolumeAccuracy workspace_volume_accuracy(const Machine& machine, const WorkspaceOptions& options,
                                         std::optional<double> volume = std::nullopt);

/// The coarsest resolution h0 / 2^k whose estimated relative error is within `tolerance`
/// (0 < tolerance < 1); `start` overrides h0. Throws std::invalid_argument for a bad tolerance or
/// options (validate) and when the machine has no search box.
VolumeAccuracy choose_workspace_resolution(const Machine& machine, const WorkspaceOptions& options,
                                           double tolerance,
                                           std::optional<double> start = std::nullopt);

}  // namespace pkmopt
