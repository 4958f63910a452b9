#include "models/workspace/slice_plane.hpp"

#include "models/core/require.hpp"

namespace pkmopt {

SlicePlane choose_slice_plane(const WorkspaceResult& ws, double resolution, char normal_axis,
                              std::optional<double> offset, std::optional<double> pixel) {
  require(normal_axis == 'x' || normal_axis == 'y' || normal_axis == 'z',
          "choose_slice_plane: the normal axis must be 'x', 'y' or 'z'");
  const int axis_index = normal_axis - 'x';
  SlicePlane plane;
  plane.normal_axis = normal_axis;
  Eigen::AlignedBox3d box = ws.bounding_box.isEmpty() ? ws.search_box : ws.bounding_box;
  require(!box.isEmpty() && box.sizes().allFinite(),
          "choose_slice_plane: the workspace and its search box are empty (nothing to slice)");
  const Eigen::Vector3d pad = 0.05 * box.sizes() + Eigen::Vector3d::Constant(resolution);
  plane.box = Eigen::AlignedBox3d(box.min() - pad, box.max() + pad);
  plane.offset = offset ? *offset : plane.box.center()(axis_index);
  Eigen::Vector3d in_plane = plane.box.sizes();
  in_plane(axis_index) = 0.0;
  plane.pixel = pixel ? *pixel : in_plane.maxCoeff() / 300.0;
  plane.pixel_count = (plane.box.sizes()(axis_index == 0 ? 1 : 0) / plane.pixel) *
                      (plane.box.sizes()(axis_index == 2 ? 1 : 2) / plane.pixel);
  return plane;
}

}  // namespace pkmopt
