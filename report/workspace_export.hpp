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
//   workspace_summary_json        summary.json of `pkmopt workspace`: the request (machine,
//                                 orientations in degrees as given, restrictions, wrench in N and
//                                 N*m), the volumes (m^3), the map reductions, the grid, the boxes
//                                 (m, base frame), the slice and the run time; non-finite numbers
//                                 and absent values are null. docs/workspace.md lists every field.
//   workspace_files               every file above under its name in the --out folder:
//                                 boundary.ply, boundary.stl, points.csv, slice_<axis>.svg/.png,
//                                 summary.json.
//
// Each function returns the file's bytes; the caller writes them atomically.
//
//   const std::string svg = pkmopt::slice_svg(slice, pkmopt::SliceMetric::kSingularityMargin);
//   const std::string json = pkmopt::workspace_summary_json(request, ws, slice, metric, seconds);
//   for (const auto& [name, bytes] : pkmopt::workspace_files(ws, slice, metric, json))
//     pkmopt::write_file_atomically((dir / name).string(), bytes);
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "models/workspace/volume_accuracy.hpp"
#include "models/workspace/workspace.hpp"

namespace pkmopt {

enum class SliceMetric {
  kSingularityMargin,
  kStiffnessMin,
  kMaxLegForce,
  kTcpErrorMax,
  kTcpDeflection,       ///< under the workspace options' wrench (m)
  kStiffnessMinLoaded,  ///< under the workspace options' wrench (N/m)
  kNaturalFrequency1,   ///< the first natural frequency (Hz; machines with a mass model)
};

/// "singularity_margin", "stiffness_min", "max_leg_force", "tcp_error_max"; nullopt otherwise.
std::optional<SliceMetric> parse_slice_metric(std::string_view name);
std::string slice_metric_name(SliceMetric metric);
/// The metric's label with its unit, e.g. "stiffness_min [N/m]".
std::string slice_metric_label(SliceMetric metric);
double slice_metric_value(const WorkspacePointMetrics& metrics, SliceMetric metric);

std::string boundary_ply(const TriangleMesh& mesh);
std::string boundary_stl(const TriangleMesh& mesh);
/// `natural_frequencies`: add the column natural_frequency_1 (Hz; machines with masses).
std::string point_cloud_csv(const std::vector<WorkspacePoint>& points,
                            bool natural_frequencies = false);
/// What a slice picture shows over the workspace: a task region's rectangle in the plane
/// (in-plane coordinates u, v in m, as WorkspaceSlice::origin), drawn red and labelled "task".
struct SliceOverlay {
  std::optional<std::pair<Eigen::Vector2d, Eigen::Vector2d>> task_rect;  ///< (min, max)
};
/// The colour bar carries the metric's name above it.
std::string slice_svg(const WorkspaceSlice& slice, SliceMetric metric,
                      const SliceOverlay& overlay = {});
/// 8-bit RGB PNG (libpng).
std::string slice_png(const WorkspaceSlice& slice, SliceMetric metric,
                      const SliceOverlay& overlay = {});

/// "constant_orientation" (no tilt, no yaw range), else "all_orientations" (Mode::kAll) or
/// "some_orientation" (Mode::kSome).
std::string workspace_kind(const OrientationSet& set);

/// What summary.json repeats of a workspace request. The angles are the user's degrees, written
/// unconverted (options.orientations holds them in radians).
struct WorkspaceRequest {
  std::string machine_file;  ///< the machine file as named by the user
  std::string model;         ///< Machine::model()
  WorkspaceOptions options;  ///< orientations, min margin and stiffness, wrench
  double tilt_deg = 0.0;
  double yaw_range_deg = 0.0;
  double orientation_step_deg = 5.0;
  /// The volume's error estimate and how the resolution was chosen (models/workspace/
  /// volume_accuracy.hpp): tolerance > 0 when it was chosen for --tolerance.
  VolumeAccuracy accuracy;
};

/// summary.json (two-space indented, ending in a newline) of a workspace, its slice coloured by
/// `metric`, computed in `seconds` (s).
std::string workspace_summary_json(const WorkspaceRequest& request, const WorkspaceResult& ws,
                                   const WorkspaceSlice& slice, SliceMetric metric, double seconds);

/// The files of `pkmopt workspace --out DIR` as (name, bytes), in the order they are written;
/// `summary_json` is workspace_summary_json's text.
std::vector<std::pair<std::string, std::string>> workspace_files(const WorkspaceResult& ws,
                                                                 const WorkspaceSlice& slice,
                                                                 SliceMetric metric,
                                                                 const std::string& summary_json);

}  // namespace pkmopt
