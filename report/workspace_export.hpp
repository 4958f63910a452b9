// Files written from a workspace analysis (models/workspace/workspace.hpp).
//
//   boundary_ply / boundary_stl   the closed boundary mesh: ASCII PLY (float vertices, triangle
//                                 faces) and binary STL; coordinates in metres, triangles
//                                 counter-clockwise seen from outside (normals point outwards).
//   point_cloud_csv               one row per inside grid node:
//                                 x,y,z (m),singularity_margin (0..1),stiffness_min (N/m),
//                                 max_leg_force (N or N*m),tcp_error_max (m); "inf" at singular
//                                 nodes.
//   slice_svg / slice_png         a plane section coloured by one metric (viridis, low = dark),
//                                 axes in mm with ticks, a colour bar with its value range;
//                                 grey = outside the workspace, black = infinite value (singular).
//
// Each function returns the file's bytes; the caller writes them atomically.
//
//   const std::string svg = pkmopt::slice_svg(slice, pkmopt::SliceMetric::kSingularityMargin);
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "models/workspace/workspace.hpp"

namespace pkmopt {

enum class SliceMetric { kSingularityMargin, kStiffnessMin, kMaxLegForce, kTcpErrorMax };

/// "singularity_margin", "stiffness_min", "max_leg_force", "tcp_error_max"; nullopt otherwise.
std::optional<SliceMetric> parse_slice_metric(std::string_view name);
std::string slice_metric_name(SliceMetric metric);
/// The metric's label with its unit, e.g. "stiffness_min [N/m]".
std::string slice_metric_label(SliceMetric metric);
double slice_metric_value(const WorkspacePointMetrics& metrics, SliceMetric metric);

std::string boundary_ply(const TriangleMesh& mesh);
std::string boundary_stl(const TriangleMesh& mesh);
std::string point_cloud_csv(const std::vector<WorkspacePoint>& points);
std::string slice_svg(const WorkspaceSlice& slice, SliceMetric metric);
/// 8-bit RGB PNG (libpng).
std::string slice_png(const WorkspaceSlice& slice, SliceMetric metric);

}  // namespace pkmopt
