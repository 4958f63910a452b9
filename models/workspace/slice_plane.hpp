// The plane and pixel size of a workspace slice picture (compute_workspace_slice in
// models/workspace/workspace.hpp), chosen from a computed workspace.
//
// choose_slice_plane(ws, resolution, axis, offset, pixel) picks what `pkmopt workspace` slices:
//   box     the workspace's bounding box (the search box when nothing is reachable), grown on
//           every side by 5 % of its size plus one grid spacing `resolution`;
//   offset  the plane normal_axis = offset, through the box centre unless `offset` is given;
//   pixel   1/300 of the larger in-plane side of the box unless `pixel` is given;
//   pixel_count = (u extent / pixel) * (v extent / pixel), the size of the picture as a real
//           number (u, v: the two other axes, in the order x, y, z), so that a caller can refuse
//           a huge picture before computing it.
// Base frame, metres. The function only does geometry: it neither checks the pixel count nor
// evaluates the machine.
//
// Example:
//   const pkmopt::SlicePlane plane = pkmopt::choose_slice_plane(ws, options.resolution, 'z');
//   const pkmopt::WorkspaceSlice slice = pkmopt::compute_workspace_slice(
//       machine, options, plane.box, plane.normal_axis, plane.offset, plane.pixel);
#pragma once

#include <Eigen/Geometry>
#include <optional>

#include "models/workspace/workspace.hpp"

namespace pkmopt {

/// Where a slice picture lies and how fine it is (m, base frame).
struct SlicePlane {
  Eigen::AlignedBox3d box;   ///< the picture covers the box's extent in the two in-plane axes
  char normal_axis = 'z';    ///< 'x', 'y' or 'z'
  double offset = 0.0;       ///< the plane normal_axis = offset (m)
  double pixel = 0.0;        ///< square pixel size (m)
  double pixel_count = 0.0;  ///< (u extent / pixel) * (v extent / pixel)
};

/// The slice plane through `ws` (see the header comment). `normal_axis` is 'x', 'y' or 'z'
/// (std::invalid_argument otherwise, and when both the workspace's bounding box and its search
/// box are empty: a machine whose legs have no common reach); `resolution` is the grid spacing the
/// workspace was computed with (m); `offset` and `pixel` (m) replace the defaults when given.
SlicePlane choose_slice_plane(const WorkspaceResult& ws, double resolution, char normal_axis,
                              std::optional<double> offset = std::nullopt,
                              std::optional<double> pixel = std::nullopt);

}  // namespace pkmopt
