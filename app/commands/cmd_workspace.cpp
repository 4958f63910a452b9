// pkmopt workspace MACHINE.yaml [--orientation rx,ry,rz] [--tilt DEG] [--yaw-range DEG]
//   [--mode all|some] [--orientation-step DEG] [--resolution M | --tolerance T] [--min-margin X]
//   [--min-stiffness K] [--wrench fx,fy,fz,mx,my,mz] [--slice-axis x|y|z] [--slice-at M]
//   [--slice-metric NAME] [--slice-pixel M] [--certify [--certify-size M] [--certify-margin X]]
//   [--out DIR]
// See docs/workspace.md for the options, the files and every summary.json field.
#include <fmt/format.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>

#include "app/cli_args.hpp"
#include "app/commands.hpp"
#include "io/format/csv.hpp"
#include "io/format/input_error.hpp"
#include "io/format/output_file.hpp"
#include "io/machine/machine_file.hpp"
#include "io/results/certificate_files.hpp"
#include "models/core/pose.hpp"
#include "models/workspace/mode_certificate.hpp"
#include "models/workspace/slice_plane.hpp"
#include "models/workspace/volume_accuracy.hpp"
#include "models/workspace/workspace.hpp"
#include "report/workspace_export.hpp"
#include "studies/distribute.hpp"

namespace pkmopt::cli {
namespace {

struct WorkspaceCommandOptions {
  std::string machine_file;
  std::string orientation;
  double tilt_deg = 0.0;
  double yaw_range_deg = 0.0;
  std::string mode = "all";
  double orientation_step_deg = 5.0;
  std::optional<double> resolution;
  double tolerance = 0.005;
  std::optional<double> min_margin;
  std::optional<double> min_stiffness;
  std::string wrench;
  std::string slice_axis = "z";
  std::optional<double> slice_at;
  std::string slice_metric = "singularity_margin";
  std::optional<double> slice_pixel;
  bool certify = false;
  std::optional<double> certify_size;  // m
  double certify_margin = 0.0;
  std::string out_dir;
};

// The orientation set, grid and filters of the options, validated (InputError naming the option).
WorkspaceOptions read_workspace_options(const WorkspaceCommandOptions& opt) {
  WorkspaceOptions options;
  if (!opt.orientation.empty()) {
    const auto a = parse_number_list("--orientation", opt.orientation, 3);
    options.orientations.nominal_angles = deg_to_rad(Eigen::Vector3d(a[0], a[1], a[2]));
  }
  using namespace workspace_limits;  // one rule per limit, shared with studies and Python
  if (!kTiltDeg.accepts(opt.tilt_deg)) bad_option("--tilt", kTiltDeg.expected, opt.tilt_deg);
  if (!kYawRangeDeg.accepts(opt.yaw_range_deg))
    bad_option("--yaw-range", kYawRangeDeg.expected, opt.yaw_range_deg);
  if (!kOrientationStepDeg.accepts(opt.orientation_step_deg))
    bad_option("--orientation-step", kOrientationStepDeg.expected, opt.orientation_step_deg);
  options.orientations.tilt = deg_to_rad(opt.tilt_deg);
  options.orientations.yaw_range = deg_to_rad(opt.yaw_range_deg);
  options.orientations.orientation_step = deg_to_rad(opt.orientation_step_deg);
  if (const std::int64_t count = orientation_count(options.orientations); count > kMaxOrientations)
    throw InputError(fmt::format(
        "--orientation-step: expected a step that samples at most {} orientations of the tilt "
        "and yaw range, found {} ({} orientations)",
        kMaxOrientations, format_number(opt.orientation_step_deg), count));
  if (opt.mode == "all") {
    options.orientations.mode = OrientationSet::Mode::kAll;
  } else if (opt.mode == "some") {
    options.orientations.mode = OrientationSet::Mode::kSome;
  } else {
    throw InputError(
        fmt::format("--mode: expected 'all' or 'some', found {}", quote_found(opt.mode)));
  }
  if (opt.resolution && !kResolution.accepts(*opt.resolution))
    bad_option("--resolution", kResolution.expected, *opt.resolution);
  if (!kTolerance.accepts(opt.tolerance))
    bad_option("--tolerance", kTolerance.expected, opt.tolerance);
  // The grid's spacing: given, or chosen below for --tolerance (validated with a placeholder).
  options.resolution = opt.resolution.value_or(0.02);
  if (opt.min_margin && !kMinMargin.accepts(*opt.min_margin))
    bad_option("--min-margin", kMinMargin.expected, *opt.min_margin);
  if (opt.min_stiffness && !kMinStiffness.accepts(*opt.min_stiffness))
    bad_option("--min-stiffness", kMinStiffness.expected, *opt.min_stiffness);
  options.min_singularity_margin = opt.min_margin;
  options.min_stiffness = opt.min_stiffness;
  if (!opt.wrench.empty()) {
    const auto w = parse_wrench_option(opt.wrench);
    for (int i = 0; i < 6; ++i) options.wrench(i) = w[static_cast<std::size_t>(i)];
  }
  return options;
}

// The slice's metric, with its axis, plane and pixel validated.
SliceMetric read_slice_options(const WorkspaceCommandOptions& opt) {
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
        fmt::format("--slice-metric: expected singularity_margin, stiffness_min, max_leg_force, "
                    "tcp_error_max, tcp_deflection, stiffness_min_loaded or natural_frequency_1, "
                    "found {}",
                    quote_found(opt.slice_metric)));
  }
  if (opt.slice_pixel && !(std::isfinite(*opt.slice_pixel) && *opt.slice_pixel > 0.0)) {
    bad_option("--slice-pixel", "a pixel size in metres > 0", *opt.slice_pixel);
  }
  return *metric;
}

// The workspace at --resolution, or at the coarsest grid that meets --tolerance, and how accurate
// its volume is.
WorkspaceResult compute_with_accuracy(const Machine& machine, const WorkspaceCommandOptions& opt,
                                      WorkspaceOptions& options, VolumeAccuracy& accuracy) {
  WorkspaceResult ws;
  try {
    if (!opt.resolution) {
      accuracy = choose_workspace_resolution(machine, options, opt.tolerance);
      options.resolution = accuracy.resolution;
    }
    ws = compute_workspace(machine, options);
    if (opt.resolution) accuracy = workspace_volume_accuracy(machine, options, ws.volume);
  } catch (const std::invalid_argument& e) {
    // Only a grid too fine is the resolution's fault; anything else is the machine's.
    const std::string what = e.what();
    const bool grid = what.find("workspace grid") != std::string::npos;
    throw InputError(fmt::format("{}: {}", grid ? "--resolution" : opt.machine_file, what));
  }
  return ws;
}

// The slice plane (through the middle of the workspace unless --slice-at is given), at most 4e6
// pixels.
SlicePlane slice_plane_of(const WorkspaceResult& ws, const WorkspaceOptions& options,
                          const WorkspaceCommandOptions& opt) {
  // The slice: through the middle of the workspace unless --slice-at is given.
  const SlicePlane plane =
      choose_slice_plane(ws, options.resolution, opt.slice_axis[0], opt.slice_at, opt.slice_pixel);
  if (!(plane.pixel_count <= 4e6)) {
    if (opt.slice_pixel) {
      throw InputError(fmt::format(
          "--slice-pixel: expected at most 4e6 pixels in the slice, found {:.3g} (pixel {} m)",
          plane.pixel_count, plane.pixel));
    }
    throw InputError(fmt::format(
        "{}: the workspace slice would have {:.3g} pixels of {} m (the grid spacing), more than "
        "4e6; give a coarser --slice-pixel or --resolution",
        opt.machine_file, plane.pixel_count, plane.pixel));
  }
  return plane;
}

// The --certify options, checked (InputError naming the option).
void check_certify_options(const WorkspaceCommandOptions& opt) {
  if (!opt.certify && (opt.certify_size || opt.certify_margin != 0.0))
    throw InputError("--certify-size/--certify-margin: expected only together with --certify");
  if (opt.certify_size &&
      !(std::isfinite(*opt.certify_size) && *opt.certify_size > 0.0 && *opt.certify_size <= 1.0))
    bad_option("--certify-size", "a box size in m, > 0 and <= 1", *opt.certify_size);
  if (!(std::isfinite(opt.certify_margin) && opt.certify_margin >= 0.0 && opt.certify_margin < 1.0))
    bad_option("--certify-margin", "a margin 0 <= X < 1", opt.certify_margin);
}

// The certificate of the workspace's cells (not empty) times its orientation set (--certify),
// with the settings it was made with.
std::pair<ModeCertificate, CertificateSetting> certify_workspace(const WorkspaceCommandOptions& opt,
                                                                 const Machine& machine,
                                                                 const WorkspaceOptions& options,
                                                                 const WorkspaceResult& ws) {
  const auto start = std::chrono::steady_clock::now();
  const auto enclosure = machine.jacobian_enclosure();
  CertificateSetting setting;
  setting.first_boxes = static_cast<std::int64_t>(ws.points.size());
  setting.region = fmt::format("the workspace's {} grid cells of {:.4g} mm", ws.points.size(),
                               1e3 * ws.resolution);
  setting.nominal_angles_deg = rad_to_deg(options.orientations.nominal_angles);
  setting.tilt_deg = opt.tilt_deg;
  setting.yaw_range_deg = opt.yaw_range_deg;
  setting.options.min_size = opt.certify_size.value_or(ws.resolution / 4.0);
  setting.options.min_margin = opt.certify_margin;
  const ModeCertificate c = certify_working_mode(
      *enclosure.get(),
      workspace_cells(ws.points, ws.resolution, orientation_box(options.orientations)),
      setting.options);
  setting.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return {c, setting};
}

// Writes the result files (all or none), prints the summary line and says what is off.
void report_workspace(
    const WorkspaceCommandOptions& opt, const Machine& machine, const WorkspaceOptions& options,
    const VolumeAccuracy& accuracy, const WorkspaceResult& ws, const WorkspaceSlice& slice,
    SliceMetric metric, double seconds,
    const std::optional<std::pair<ModeCertificate, CertificateSetting>>& certificate) {
  const std::filesystem::path out_dir(opt.out_dir);
  if (!opt.out_dir.empty()) {
    std::error_code ec;
    std::filesystem::create_directories(out_dir, ec);
    if (ec) {
      throw InputError(fmt::format("--out: cannot create the folder {}: {}",
                                   quote_found(opt.out_dir), ec.message()));
    }
    // Everything is rendered first; then each file is written whole or not at all.
    const WorkspaceRequest request{.machine_file = opt.machine_file,
                                   .model = std::string(machine.model()),
                                   .options = options,
                                   .tilt_deg = opt.tilt_deg,
                                   .yaw_range_deg = opt.yaw_range_deg,
                                   .orientation_step_deg = opt.orientation_step_deg,
                                   .accuracy = accuracy};
    const std::string summary = workspace_summary_json(request, ws, slice, metric, seconds);
    std::vector<std::pair<std::string, std::string>> files;
    for (const auto& [name, content] : workspace_files(ws, slice, metric, summary))
      files.emplace_back((out_dir / name).string(), content);
    if (certificate) {
      files.emplace_back((out_dir / "certificate.json").string(),
                         certificate_json(certificate->first, certificate->second));
      files.emplace_back((out_dir / "uncertified.csv").string(),
                         uncertified_boxes_csv(certificate->first));
    }
    write_files_together(files);  // the mesh, points, slice and summary, all of them or none
  }
  fmt::print(
      "workspace ({}): volume {:.5g} l (estimated error {:.2g} %), convex hull {:.5g} l, GCI "
      "{:.4g}, envelope ratio {}, resolution {:.4g} mm, {:.3g} s{}\n",
      workspace_kind(options.orientations), 1e3 * ws.volume, 100.0 * accuracy.relative_error(),
      1e3 * ws.convex_hull_volume, ws.maps.global_conditioning_index,
      ws.envelope_ratio ? fmt::format("{:.4g}", *ws.envelope_ratio) : "n/a", 1e3 * ws.resolution,
      seconds, opt.out_dir.empty() ? "" : " -> " + opt.out_dir);
  if (certificate) {
    fmt::print("{}", certificate_text(certificate->first, certificate->second));
    if (!certificate->first.certified())
      fmt::print(stderr,
                 "pkmopt: warning: the workspace is not certified free of parallel singularities "
                 "(see the certificate lines{})\n",
                 opt.out_dir.empty() ? "" : " and certificate.json");
    if (options.orientations.mode == OrientationSet::Mode::kSome)
      fmt::print(
          "  (--mode some: the cells hold positions reachable with some orientation; the "
          "certificate covers every orientation of the set)\n");
  }
  // The search box of some models is their travel (a tripod's z stroke): touching it is then
  // no error, so it is a warning only.
  if (ws.touches_search_box)
    fmt::print(stderr, "pkmopt: warning: the workspace reaches the search box; volume cut off\n");
  std::fflush(stdout);
  // An empty workspace is a finding (the joint limits of a design may forbid a tilt), said
  // loudly; a volume whose refinement did not reach --tolerance is written, said, and exits 3.
  if (!(ws.volume > 0.0))
    fmt::print(stderr,
               "pkmopt: warning: the workspace is empty: no node of the search grid is reachable "
               "(check the strokes, the joint limits and the orientations)\n");
  if (!opt.resolution && !accuracy.met && ws.volume > 0.0)
    throw ProbablyWrongResult(fmt::format(
        "the volume's estimated error {:.2g} % is above --tolerance {:.2g} %: the finest grid the "
        "refinement allows ({} m) was not fine enough; give --resolution",
        100.0 * accuracy.relative_error(), 100.0 * opt.tolerance, accuracy.resolution));
}

void run_workspace(const WorkspaceCommandOptions& opt) {
  const auto start = std::chrono::steady_clock::now();
  // Read and validate every input before anything is written.
  WorkspaceOptions options = read_workspace_options(opt);
  const SliceMetric metric = read_slice_options(opt);
  const std::filesystem::path out_dir(opt.out_dir);
  if (!opt.out_dir.empty() && std::filesystem::exists(out_dir) &&
      !std::filesystem::is_directory(out_dir)) {
    throw InputError(
        fmt::format("--out: expected a folder, found the file {}", quote_found(opt.out_dir)));
  }
  check_certify_options(opt);
  options.keep_points = !opt.out_dir.empty() || opt.certify;
  const std::string invalid = validate(options);
  if (!invalid.empty()) throw InputError(invalid);
  const std::unique_ptr<Machine> machine = load_machine_file(opt.machine_file);
  if (metric == SliceMetric::kNaturalFrequency1 && !machine->dynamics()) {
    throw InputError(fmt::format(
        "--slice-metric natural_frequency_1: {} has no masses (docs/dynamics.md), found a model "
        "'{}' without them",
        opt.machine_file, machine->model()));
  }
  if (opt.certify && !machine->jacobian_enclosure())
    throw InputError(
        fmt::format("--certify: expected a machine whose Jacobian can be enclosed over boxes of "
                    "poses, found {}: {}",
                    opt.machine_file, machine->jacobian_enclosure().reason()));
  const auto box = workspace_search_box(*machine, sample_orientations(options.orientations));
  if (!box) {
    throw InputError(fmt::format("{}: model '{}' has no workspace search box yet", opt.machine_file,
                                 machine->model()));
  }

  // Under mpirun every rank computes its share of the grid and has the whole result; rank 0
  // writes it (docs/distributed.md).
  std::optional<MpiSession> session;
  std::optional<MpiShare> share;
  if (mpi_launch_from_environment().launched) {
    session.emplace();
    share.emplace(*session);
    options.share = &*share;
  }
  VolumeAccuracy accuracy;
  const WorkspaceResult ws = compute_with_accuracy(*machine, opt, options, accuracy);

  // A machine whose legs have no common reach at any orientation has an empty search box: it
  // cannot be assembled anywhere, and there is no plane to slice.
  if (ws.bounding_box.isEmpty() && ws.search_box.isEmpty()) {
    throw InputError(fmt::format(
        "{}: expected legs that reach a common platform pose, found none at any orientation (the "
        "reach of the legs does not overlap: check the leg or strut lengths, the radii and the "
        "strokes)",
        opt.machine_file));
  }
  const SlicePlane plane = slice_plane_of(ws, options, opt);
  const WorkspaceSlice slice = compute_workspace_slice(
      *machine, options, plane.box, plane.normal_axis, plane.offset, plane.pixel);
  if (session && session->rank() > 0) return;
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  std::optional<std::pair<ModeCertificate, CertificateSetting>> certificate;
  if (opt.certify && !ws.points.empty())
    certificate = certify_workspace(opt, *machine, options, ws);
  report_workspace(opt, *machine, options, accuracy, ws, slice, metric, seconds, certificate);
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
  cmd->add_option("--resolution", opt->resolution,
                  "Grid spacing (m); default: the coarsest grid (halving from 1/16 of the search "
                  "box) whose volume meets --tolerance")
      ->check(length_in_metres());
  cmd->add_option("--tolerance", opt->tolerance,
                  "Relative accuracy of the volume when --resolution is not given (the estimated "
                  "error is the difference to the grid at twice the spacing); default 0.005");
  cmd->add_option("--min-margin", opt->min_margin,
                  "Keep only poses with singularity_margin >= X (0..1)");
  cmd->add_option("--min-stiffness", opt->min_stiffness,
                  "Keep only poses with stiffness_min >= K (N/m)");
  cmd->add_option("--wrench", opt->wrench,
                  "Wrench at the TCP for max_leg_force: fx,fy,fz,mx,my,mz (N, N*m); default 0");
  cmd->add_option("--slice-axis", opt->slice_axis, "Slice plane normal: x, y or z; default z");
  cmd->add_option("--slice-at", opt->slice_at,
                  "Slice plane coordinate (m); default the middle of the workspace")
      ->check(length_in_metres());
  cmd->add_option("--slice-metric", opt->slice_metric,
                  "Slice colour: singularity_margin, stiffness_min, max_leg_force, tcp_error_max, "
                  "tcp_deflection or stiffness_min_loaded (both under --wrench), "
                  "natural_frequency_1 (machine files with masses); default singularity_margin");
  cmd->add_option("--slice-pixel", opt->slice_pixel,
                  "Slice pixel size (m); default 1/300 of the larger slice side")
      ->check(length_in_metres());
  cmd->add_flag("--certify", opt->certify,
                "Prove that the workspace (its grid cells times the orientation set) holds no "
                "parallel singularity: one working mode (hexapod; certificate.json, "
                "uncertified.csv)");
  cmd->add_option("--certify-size", opt->certify_size,
                  "Boxes are split down to this size (m) before they are reported as not "
                  "proved; default resolution/4")
      ->check(length_in_metres());
  cmd->add_option("--certify-margin", opt->certify_margin,
                  "Certify only where the margin 1/||J_c^-1||_inf is proved >= X; default 0");
  cmd->add_option("--out", opt->out_dir,
                  "Folder for summary.json, boundary.ply/.stl, points.csv, slice_*.svg/.png "
                  "(default: print the summary line only)");
  cmd->callback([opt] { run_workspace(*opt); });
}

}  // namespace pkmopt::cli
