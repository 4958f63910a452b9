// pkmopt workspace MACHINE.yaml [--orientation rx,ry,rz] [--tilt DEG] [--yaw-range DEG]
//   [--mode all|some] [--orientation-step DEG] [--resolution M] [--min-margin X]
//   [--min-stiffness K] [--wrench fx,fy,fz,mx,my,mz] [--slice-axis x|y|z] [--slice-at M]
//   [--slice-metric NAME] [--slice-pixel M] [--out DIR]
// See docs/workspace.md for the options, the files and every summary.json field.
#include <fmt/format.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <stdexcept>

#include "app/cli_args.hpp"
#include "app/commands.hpp"
#include "io/input_error.hpp"
#include "io/machine_file.hpp"
#include "io/output_file.hpp"
#include "report/workspace_export.hpp"
#include "models/workspace/workspace.hpp"

namespace pkmopt::cli {
namespace {

struct WorkspaceCommandOptions {
  std::string machine_file;
  std::string orientation;
  double tilt_deg = 0.0;
  double yaw_range_deg = 0.0;
  std::string mode = "all";
  double orientation_step_deg = 5.0;
  double resolution = 0.02;
  std::optional<double> min_margin;
  std::optional<double> min_stiffness;
  std::string wrench;
  std::string slice_axis = "z";
  std::optional<double> slice_at;
  std::string slice_metric = "singularity_margin";
  std::optional<double> slice_pixel;
  std::string out_dir;
};

nlohmann::json number_or_null(double v) {
  return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr);
}

nlohmann::json vector_json(const Eigen::Vector3d& v) {
  return nlohmann::json::array({number_or_null(v(0)), number_or_null(v(1)), number_or_null(v(2))});
}

void run_workspace(const WorkspaceCommandOptions& opt) {
  const auto start = std::chrono::steady_clock::now();
  // Read and validate every input before anything is written.
  WorkspaceOptions options;
  if (!opt.orientation.empty()) {
    const auto a = parse_number_list("--orientation", opt.orientation, 3);
    options.orientations.nominal_angles = deg_to_rad(Eigen::Vector3d(a[0], a[1], a[2]));
  }
  if (!(std::isfinite(opt.tilt_deg) && opt.tilt_deg >= 0.0 && opt.tilt_deg < 180.0)) {
    bad_option("--tilt", "an angle in degrees, 0 <= tilt < 180", opt.tilt_deg);
  }
  if (!(std::isfinite(opt.yaw_range_deg) && opt.yaw_range_deg >= 0.0 &&
        opt.yaw_range_deg < 180.0)) {
    bad_option("--yaw-range", "an angle in degrees, 0 <= yaw range < 180", opt.yaw_range_deg);
  }
  if (!(std::isfinite(opt.orientation_step_deg) && opt.orientation_step_deg >= 0.01 &&
        opt.orientation_step_deg <= 90.0)) {
    bad_option("--orientation-step", "an angle in degrees, 0.01 <= step <= 90",
               opt.orientation_step_deg);
  }
  options.orientations.tilt = deg_to_rad(opt.tilt_deg);
  options.orientations.yaw_range = deg_to_rad(opt.yaw_range_deg);
  options.orientations.orientation_step = deg_to_rad(opt.orientation_step_deg);
  if (opt.mode == "all") {
    options.orientations.mode = OrientationSet::Mode::kAll;
  } else if (opt.mode == "some") {
    options.orientations.mode = OrientationSet::Mode::kSome;
  } else {
    throw InputError(
        fmt::format("--mode: expected 'all' or 'some', found {}", quote_found(opt.mode)));
  }
  if (!(std::isfinite(opt.resolution) && opt.resolution > 0.0)) {
    bad_option("--resolution", "a grid spacing in metres > 0", opt.resolution);
  }
  options.resolution = opt.resolution;
  if (opt.min_margin && !(*opt.min_margin >= 0.0 && *opt.min_margin <= 1.0)) {
    bad_option("--min-margin", "a singularity margin 0 <= X <= 1", *opt.min_margin);
  }
  if (opt.min_stiffness && !(std::isfinite(*opt.min_stiffness) && *opt.min_stiffness >= 0.0)) {
    bad_option("--min-stiffness", "a stiffness in N/m >= 0", *opt.min_stiffness);
  }
  options.min_singularity_margin = opt.min_margin;
  options.min_stiffness = opt.min_stiffness;
  if (!opt.wrench.empty()) {
    const auto w = parse_number_list("--wrench", opt.wrench, 6);
    for (int i = 0; i < 6; ++i) options.wrench(i) = w[static_cast<std::size_t>(i)];
  }
  if (opt.slice_axis != "x" && opt.slice_axis != "y" && opt.slice_axis != "z") {
    throw InputError(
        fmt::format("--slice-axis: expected x, y or z, found {}", quote_found(opt.slice_axis)));
  }
  if (opt.slice_at && !std::isfinite(*opt.slice_at)) {
    bad_option("--slice-at", "a finite coordinate in metres", *opt.slice_at);
  }
  const auto metric = parse_slice_metric(opt.slice_metric);
  if (!metric) {
    throw InputError(
        fmt::format("--slice-metric: expected singularity_margin, stiffness_min, max_leg_force or "
                    "tcp_error_max, found {}",
                    quote_found(opt.slice_metric)));
  }
  if (opt.slice_pixel && !(std::isfinite(*opt.slice_pixel) && *opt.slice_pixel > 0.0)) {
    bad_option("--slice-pixel", "a pixel size in metres > 0", *opt.slice_pixel);
  }
  const std::filesystem::path out_dir(opt.out_dir);
  if (!opt.out_dir.empty() && std::filesystem::exists(out_dir) &&
      !std::filesystem::is_directory(out_dir)) {
    throw InputError(
        fmt::format("--out: expected a folder, found the file {}", quote_found(opt.out_dir)));
  }
  options.keep_points = !opt.out_dir.empty();
  const std::string invalid = validate(options);
  if (!invalid.empty()) throw InputError(invalid);
  const std::unique_ptr<Machine> machine = load_machine_file(opt.machine_file);
  const auto box = workspace_search_box(*machine, sample_orientations(options.orientations));
  if (!box) {
    throw InputError(fmt::format("{}: model '{}' has no workspace search box yet", opt.machine_file,
                                 machine->model()));
  }

  WorkspaceResult ws;
  try {
    ws = compute_workspace(*machine, options);
  } catch (const std::invalid_argument& e) {
    throw InputError(fmt::format("--resolution: {}", e.what()));
  }

  // The slice: through the middle of the workspace unless --slice-at is given.
  const char axis = opt.slice_axis[0];
  const int axis_index = axis - 'x';
  Eigen::AlignedBox3d slice_box = ws.bounding_box.isEmpty() ? ws.search_box : ws.bounding_box;
  const Eigen::Vector3d pad =
      0.05 * slice_box.sizes() + Eigen::Vector3d::Constant(options.resolution);
  slice_box = Eigen::AlignedBox3d(slice_box.min() - pad, slice_box.max() + pad);
  const double slice_at = opt.slice_at ? *opt.slice_at : slice_box.center()(axis_index);
  Eigen::Vector3d in_plane = slice_box.sizes();
  in_plane(axis_index) = 0.0;
  const double pixel = opt.slice_pixel ? *opt.slice_pixel : in_plane.maxCoeff() / 300.0;
  const double pixel_count = (slice_box.sizes()(axis_index == 0 ? 1 : 0) / pixel) *
                             (slice_box.sizes()(axis_index == 2 ? 1 : 2) / pixel);
  if (pixel_count > 4e6) {
    throw InputError(fmt::format(
        "--slice-pixel: expected at most 4e6 pixels in the slice, found {:.3g} (pixel {} m)",
        pixel_count, pixel));
  }
  const WorkspaceSlice slice =
      compute_workspace_slice(*machine, options, slice_box, axis, slice_at, pixel);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  const OrientationSet& set = options.orientations;
  const std::string kind =
      set.constant()
          ? "constant_orientation"
          : (set.mode == OrientationSet::Mode::kAll ? "all_orientations" : "some_orientation");
  nlohmann::ordered_json summary;
  summary["machine"] = opt.machine_file;
  summary["model"] = std::string(machine->model());
  summary["kind"] = kind;
  summary["orientation_deg"] = vector_json(rad_to_deg(set.nominal_angles));
  summary["tilt_deg"] = opt.tilt_deg;
  summary["yaw_range_deg"] = opt.yaw_range_deg;
  summary["orientation_step_deg"] = opt.orientation_step_deg;
  summary["orientation_count"] = ws.orientation_count;
  summary["min_singularity_margin"] =
      opt.min_margin ? nlohmann::json(*opt.min_margin) : nlohmann::json(nullptr);
  summary["min_stiffness"] =
      opt.min_stiffness ? nlohmann::json(*opt.min_stiffness) : nlohmann::json(nullptr);
  summary["wrench"] = std::vector<double>(options.wrench.data(), options.wrench.data() + 6);
  summary["volume"] = ws.volume;
  summary["surface_volume"] = ws.surface_volume;
  summary["convex_hull_volume"] = ws.convex_hull_volume;
  summary["voxel_volume"] = ws.voxel_volume;
  summary["convexity"] =
      ws.convex_hull_volume > 0.0 ? nlohmann::json(ws.volume / ws.convex_hull_volume) : nullptr;
  summary["global_conditioning_index"] = number_or_null(ws.maps.global_conditioning_index);
  summary["singularity_margin_min"] = number_or_null(ws.maps.singularity_margin_min);
  summary["stiffness_min_min"] = number_or_null(ws.maps.stiffness_min_min);
  summary["stiffness_min_mean"] = number_or_null(ws.maps.stiffness_min_mean);
  summary["max_leg_force"] = number_or_null(ws.maps.max_leg_force);
  summary["tcp_error_max"] = number_or_null(ws.maps.tcp_error_max);
  summary["envelope_volume"] =
      ws.envelope_volume ? nlohmann::json(*ws.envelope_volume) : nlohmann::json(nullptr);
  summary["envelope_ratio"] =
      ws.envelope_ratio ? nlohmann::json(*ws.envelope_ratio) : nlohmann::json(nullptr);
  summary["resolution"] = ws.resolution;
  summary["grid_nodes"] = {ws.grid_nodes(0), ws.grid_nodes(1), ws.grid_nodes(2)};
  summary["inside_nodes"] = ws.inside_nodes;
  summary["boundary_vertices"] = ws.boundary.vertices.size();
  summary["boundary_triangles"] = ws.boundary.triangles.size();
  summary["search_box"] = {{"min", vector_json(ws.search_box.min())},
                           {"max", vector_json(ws.search_box.max())}};
  if (ws.bounding_box.isEmpty()) {
    summary["bounding_box"] = nullptr;
  } else {
    summary["bounding_box"] = {{"min", vector_json(ws.bounding_box.min())},
                               {"max", vector_json(ws.bounding_box.max())}};
  }
  summary["touches_search_box"] = ws.touches_search_box;
  summary["slice"] = {{"axis", std::string(1, axis)}, {"offset", slice_at},
                      {"metric", opt.slice_metric},   {"pixel", pixel},
                      {"width", slice.width},         {"height", slice.height}};
  summary["seconds"] = seconds;

  if (!opt.out_dir.empty()) {
    std::error_code ec;
    std::filesystem::create_directories(out_dir, ec);
    if (ec) {
      throw InputError(fmt::format("--out: cannot create the folder {}: {}",
                                   quote_found(opt.out_dir), ec.message()));
    }
    // Everything is rendered first; then each file is written whole or not at all.
    const std::string slice_name = fmt::format("slice_{}", axis);
    const std::pair<std::string, std::string> files[] = {
        {"boundary.ply", boundary_ply(ws.boundary)},
        {"boundary.stl", boundary_stl(ws.boundary)},
        {"points.csv", point_cloud_csv(ws.points)},
        {slice_name + ".svg", slice_svg(slice, *metric)},
        {slice_name + ".png", slice_png(slice, *metric)},
        {"summary.json", summary.dump(2) + "\n"},
    };
    for (const auto& [name, content] : files) {
      write_file_atomically((out_dir / name).string(), content);
    }
  }
  fmt::print(
      "workspace ({}): volume {:.6g} m^3, convex hull {:.6g} m^3, GCI {:.4g}, "
      "envelope ratio {}, resolution {} m, {:.3g} s{}\n",
      kind, ws.volume, ws.convex_hull_volume, ws.maps.global_conditioning_index,
      ws.envelope_ratio ? fmt::format("{:.4g}", *ws.envelope_ratio) : "n/a", ws.resolution, seconds,
      opt.out_dir.empty() ? "" : " -> " + opt.out_dir);
  if (ws.touches_search_box) {
    fmt::print(stderr, "pkmopt: warning: the workspace reaches the search box; volume cut off\n");
  }
  std::fflush(stdout);
}

}  // namespace

void add_workspace_command(CLI::App& app) {
  auto opt = std::make_shared<WorkspaceCommandOptions>();
  CLI::App* cmd = app.add_subcommand(
      "workspace",
      "Workspace of a machine: volume (with convex hull and boundary mesh), conditioning, "
      "stiffness, force and accuracy maps, boundary mesh and slice pictures");
  cmd->add_option("machine", opt->machine_file, "Machine file (YAML)")->required();
  cmd->add_option("--orientation", opt->orientation,
                  "Nominal orientation rx,ry,rz (deg), R = Rz Ry Rx; default 0,0,0");
  cmd->add_option("--tilt", opt->tilt_deg,
                  "Tilt cone half-angle about the nominal tool axis (deg); default 0");
  cmd->add_option("--yaw-range", opt->yaw_range_deg,
                  "Turn about the tool axis within +-DEG (deg); default 0");
  cmd->add_option("--mode", opt->mode,
                  "all: positions reachable with every orientation of the set; some: with at "
                  "least one; default all");
  cmd->add_option("--orientation-step", opt->orientation_step_deg,
                  "Largest spacing of the sampled orientations (deg); default 5");
  cmd->add_option("--resolution", opt->resolution, "Grid spacing (m); default 0.02");
  cmd->add_option("--min-margin", opt->min_margin,
                  "Keep only poses with singularity_margin >= X (0..1)");
  cmd->add_option("--min-stiffness", opt->min_stiffness,
                  "Keep only poses with stiffness_min >= K (N/m)");
  cmd->add_option("--wrench", opt->wrench,
                  "Wrench at the TCP for max_leg_force: fx,fy,fz,mx,my,mz (N, N*m); default 0");
  cmd->add_option("--slice-axis", opt->slice_axis, "Slice plane normal: x, y or z; default z");
  cmd->add_option("--slice-at", opt->slice_at,
                  "Slice plane coordinate (m); default the middle of the workspace");
  cmd->add_option("--slice-metric", opt->slice_metric,
                  "Slice colour: singularity_margin, stiffness_min, max_leg_force or "
                  "tcp_error_max; default singularity_margin");
  cmd->add_option("--slice-pixel", opt->slice_pixel,
                  "Slice pixel size (m); default 1/300 of the larger slice side");
  cmd->add_option("--out", opt->out_dir,
                  "Folder for summary.json, boundary.ply/.stl, points.csv, slice_*.svg/.png "
                  "(default: print the summary line only)");
  cmd->callback([opt] { run_workspace(*opt); });
}

}  // namespace pkmopt::cli
