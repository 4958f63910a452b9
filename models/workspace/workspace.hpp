// Workspace analysis of any Machine: which TCP positions it reaches, the volume of that region,
// its boundary, convex hull, and maps of the per-pose metrics over it.
//
// Kinds of workspace (all for TCP positions p, base frame, metres):
//   constant orientation  W(R0)  = { p : reachable(p, R0) }                 (tilt = yaw = 0)
//   all orientations      W_all  = { p : reachable(p, R) for every R in S }  (Mode::kAll)
//   some orientation      W_some = { p : reachable(p, R) for some R in S }   (Mode::kSome)
// where "reachable" is Machine::reachable (actuator ranges and joint limits, docs/conventions.md),
// optionally tightened to singularity_margin >= m and/or stiffness_min >= k.
//
// Orientation set S: R = R0 * Rot(u(phi), theta) * Rz(gamma), where R0 = rotation_zyx(nominal),
// u(phi) = (cos phi, sin phi, 0) in the tool frame (a horizontal base axis when R0 = I), so the
// tool axis stays in the cone of half-angle `tilt` about R0's tool axis (0 <= theta <= tilt), and
// |gamma| <= yaw_range is a turn about the tool's own z axis. S is sampled, with at most
// `orientation_step` between neighbours:
//   theta_j = tilt * j / n_r (j = 0..n_r, n_r = ceil(tilt / step)); ring j holds
//   n_phi = max(4, ceil(2 pi sin(theta_j) / step)) azimuths phi_k = 2 pi k / n_phi;
//   gamma_m = -yaw_range + 2 yaw_range m / n_g (m = 0..n_g, n_g = ceil(2 yaw_range / step)).
// The cone rim (theta = tilt) and the yaw ends are sampled exactly, so between samples the
// constraints (smooth in R) err only to second order: a leg length or joint angle is off by at
// most about r_max * step^2 / 8 (r_max the largest distance from the TCP to a platform joint).
// With the default step 5 deg and r_max = 0.3 m that moves the boundary < 0.3 mm. W_all computed
// from samples is an outer approximation of the true W_all, W_some an inner one.
//
// Volume: the search box (from the machine, see workspace_search_box) is covered by a grid of
// spacing h = resolution. Every node is classified inside/outside. On every grid edge of the
// Freudenthal (Kuhn) triangulation of the cells (3 axis edges, 3 face diagonals, 1 body diagonal
// per node) whose ends differ, the boundary crossing is located by `bisection_steps` bisections
// (to h / 2^steps). Marching tetrahedra on the 6 tetrahedra of each cell joins the crossings into
// a closed, consistently oriented triangle mesh (normals point out of the workspace); its volume
// by the divergence theorem, V = sum (1/6) v0 . (v1 x v2), is `volume` (= `surface_volume`).
// The mesh interpolates a boundary whose vertices are exact (to h / 2^steps), so the error falls
// like h^2 (a smooth surface of curvature radius rho gives about -A h^2 / (16 rho); sharp edges of
// the region are cut and make the error depend a little on how the grid meets them). Features
// thinner than h can be missed. On the docs/conventions.md hexapod (0.10505 m^3) the error
// is -0.35 % at h = 40 mm, -0.12 % at h = 20 mm, -0.05 % at h = 10 mm (docs/workspace.md).
//
// Maps (over the grid nodes inside, each the worst over the orientations of S that count at that
// node — all of S for kAll, the admissible ones for kSome):
//   global_conditioning_index = mean singularity_margin (Gosselin & Angeles 1991, as a volume mean)
//   stiffness_min_min / stiffness_min_mean (N/m), max_leg_force = max |tau_i| under the wrench
//   (N or N*m), tcp_error_max (m). Envelope ratio = machine_envelope_volume / volume.
//
// Threads: OpenMP; the Machine is shared, every thread makes its own MachineData.
//
// Example:
//   pkmopt::WorkspaceOptions options;
//   options.resolution = 0.02;
//   pkmopt::WorkspaceResult ws = pkmopt::compute_workspace(hexapod, options);
//   // ws.volume (m^3), ws.convex_hull_volume, ws.boundary (mesh), ws.maps...
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "models/core/machine.hpp"
#include "models/core/pose.hpp"
#include "models/core/process_share.hpp"

namespace pkmopt {

/// The orientations a workspace is taken over (see the header comment).
struct OrientationSet {
  enum class Mode { kAll, kSome };
  Eigen::Vector3d nominal_angles = Eigen::Vector3d::Zero();  ///< R0 as (rx, ry, rz), rad
  double tilt = 0.0;       ///< cone half-angle about R0's tool axis, rad, 0 <= tilt < pi
  double yaw_range = 0.0;  ///< turn about the tool axis within +-yaw_range, rad, < pi
  double orientation_step = 5.0 * kDegToRad;  ///< largest sample spacing, rad
  Mode mode = Mode::kAll;

  bool constant() const { return tilt == 0.0 && yaw_range == 0.0; }
};

/// The sampled rotation matrices of a set, the cone rim first (the likeliest to fail).
std::vector<Eigen::Matrix3d> sample_orientations(const OrientationSet& set);
/// How many rotations sample_orientations gives, counted without making them.
std::int64_t orientation_count(const OrientationSet& set);
/// Sets that sample more orientations are refused (validate): a coarser step is the answer.
inline constexpr std::int64_t kMaxOrientations = 1'000'000;

/// A limit on a value a user gives, in the unit users give it (degrees for angles). The
/// workspace command, study files, the Python package and validate() below read the same ones,
/// with the same words.
struct ValueLimit {
  double min = -std::numeric_limits<double>::infinity();
  double max = std::numeric_limits<double>::infinity();
  bool min_exclusive = false;
  bool max_exclusive = false;
  std::string_view expected;  ///< what a message says is expected
  bool accepts(double value) const {
    return std::isfinite(value) && (min_exclusive ? value > min : value >= min) &&
           (max_exclusive ? value < max : value <= max);
  }
};

/// The limits of orientation sets and workspace grids.
namespace workspace_limits {
inline constexpr ValueLimit kTiltDeg{.min = 0,
                                     .max = 180,
                                     .max_exclusive = true,
                                     .expected = "an angle in degrees, 0 <= tilt < 180"};
inline constexpr ValueLimit kYawRangeDeg{.min = 0,
                                         .max = 180,
                                         .max_exclusive = true,
                                         .expected = "an angle in degrees, 0 <= yaw range < 180"};
inline constexpr ValueLimit kOrientationStepDeg{
    .min = 0.01, .max = 90, .expected = "an angle in degrees, 0.01 <= step <= 90"};
inline constexpr ValueLimit kResolution{
    .min = 0, .min_exclusive = true, .expected = "a grid spacing in metres > 0"};
inline constexpr ValueLimit kTolerance{
    .min = 1e-4, .max = 0.5, .expected = "a relative accuracy 1e-4 <= T <= 0.5"};
inline constexpr ValueLimit kMinMargin{
    .min = 0, .max = 1, .expected = "a singularity margin 0 <= X <= 1"};
inline constexpr ValueLimit kMinStiffness{.min = 0, .expected = "a stiffness in N/m >= 0"};
}  // namespace workspace_limits

struct WorkspaceOptions {
  OrientationSet orientations;
  double resolution = 0.02;                      ///< grid spacing h (m)
  int bisection_steps = 10;                      ///< boundary crossings located to h / 2^steps
  std::optional<double> min_singularity_margin;  ///< keep poses with margin >= this (0..1)
  std::optional<double> min_stiffness;           ///< keep poses with stiffness_min >= this (N/m)
  Wrench wrench = Wrench::Zero();                ///< external wrench at the TCP for max_leg_force
  bool compute_maps = true;  ///< evaluate metric maps (analyze at every inside node)
  /// The maps include tcp_deflection and stiffness_min_loaded (each node's compliance); off, they
  /// stay 0 and the maps cost about half as much.
  bool compliance_maps = true;
  bool compute_hull = true;  ///< convex hull volume (CGAL)
  bool keep_points = false;  ///< return every inside node with its metrics
  /// Region to search; default workspace_search_box(machine, orientations).
  std::optional<Eigen::AlignedBox3d> search_box;
  /// Refuse grids with more nodes than this (memory: about 2 bytes per node).
  std::int64_t max_grid_nodes = 200'000'000;
  /// Processes (MPI ranks) that compute this workspace together, each a share of the grid
  /// layers, boundary crossings, inside nodes and slice pixels (models/core/process_share.hpp);
  /// every process gets the whole result. nullptr: this process computes everything.
  const ProcessShare* share = nullptr;
};

/// "" when the options are valid, else a message "WorkspaceOptions::x = v. Violated constraint:
/// x > 0".
std::string validate(const WorkspaceOptions& options);

/// A triangle mesh; triangles index `vertices`, counter-clockwise seen from outside.
struct TriangleMesh {
  std::vector<Eigen::Vector3d> vertices;
  std::vector<std::array<int, 3>> triangles;
};

/// Metrics at one point, the worst over the orientations that count there.
struct WorkspacePointMetrics {
  double singularity_margin = 0.0;    ///< min over orientations
  double stiffness_min = 0.0;         ///< min over orientations (N/m)
  double max_leg_force = 0.0;         ///< max |tau_i| over actuators and orientations
  double tcp_error_max = 0.0;         ///< max over orientations (m)
  double tcp_deflection = 0.0;        ///< max over orientations of |(C w)_t| under the wrench (m)
  double stiffness_min_loaded = 0.0;  ///< min over orientations (N/m), with the wrench's load
  /// min over orientations of the first natural frequency (Hz); 0 without a mass model.
  double natural_frequency_1 = 0.0;
};

struct WorkspacePoint {
  Eigen::Vector3d position;
  WorkspacePointMetrics metrics;
};

/// Reductions of the point metrics over the inside grid nodes. Infinite values (a singular
/// node) stay infinite; with no inside node every field is 0.
struct WorkspaceMaps {
  std::int64_t points = 0;                 ///< inside grid nodes used
  double global_conditioning_index = 0.0;  ///< mean singularity_margin
  double singularity_margin_min = 0.0;
  double stiffness_min_min = 0.0;         ///< N/m
  double stiffness_min_mean = 0.0;        ///< N/m
  double max_leg_force = 0.0;             ///< N (N*m for revolute actuators)
  double tcp_error_max = 0.0;             ///< m
  double tcp_deflection_max = 0.0;        ///< m, under the options' wrench
  double stiffness_min_loaded_min = 0.0;  ///< N/m, under the options' wrench
  /// True when the machine has a mass model (the maps then carry the natural frequencies).
  bool natural_frequencies = false;
  double natural_frequency_min = 0.0;  ///< Hz, min of natural_frequency_1 over the nodes
};

struct WorkspaceResult {
  double volume = 0.0;              ///< best estimate (m^3), see the header comment
  double surface_volume = 0.0;      ///< volume enclosed by the boundary mesh (m^3)
  double convex_hull_volume = 0.0;  ///< of the boundary mesh vertices (m^3); 0 if not computed
  double voxel_volume = 0.0;        ///< plain count of inside nodes * h^3 (m^3), for comparison
  std::optional<double> envelope_volume;  ///< machine_envelope_volume (m^3), if known
  std::optional<double> envelope_ratio;   ///< envelope_volume / volume, if both > 0
  WorkspaceMaps maps;
  TriangleMesh boundary;
  std::vector<WorkspacePoint> points;  ///< when keep_points
  Eigen::AlignedBox3d search_box;      ///< the box searched
  Eigen::AlignedBox3d bounding_box;    ///< of the boundary vertices (empty if no workspace)
  Eigen::Vector3i grid_nodes = Eigen::Vector3i::Zero();  ///< nodes along x, y, z
  double resolution = 0.0;                               ///< h (m)
  int orientation_count = 0;                             ///< sampled orientations
  std::int64_t inside_nodes = 0;
  std::int64_t boundary_edges = 0;  ///< grid edges bisected
  bool touches_search_box = false;  ///< an inside node on the search box rim: volume cut off
};

/// Validates the options (throws std::invalid_argument with validate()'s message) and computes
/// the workspace. With a search box that the machine reaches beyond, the region is cut at the
/// box (and touches_search_box is set).
WorkspaceResult compute_workspace(const Machine& machine, const WorkspaceOptions& options);

/// The volume only (no maps, hull, points): the fast path for optimisation loops.
double workspace_volume(const Machine& machine, const WorkspaceOptions& options);

/// A box that contains every reachable TCP position for the sampled orientations, from the
/// machine's geometry; nullopt for machines it does not know (give WorkspaceOptions::search_box).
/// Hexapod: leg i puts the TCP in the ball of radius max_length about c_i = a_i - R (b_i - tcp);
/// with a base joint limit beta < 90 deg about +z the leg also keeps
/// min_length cos(beta) <= l_z and |l_xy| <= max_length sin(beta). The box is the intersection over
/// legs, united over the orientations. Empty box: nothing is reachable.
std::optional<Eigen::AlignedBox3d> workspace_search_box(
    const Machine& machine, const std::vector<Eigen::Matrix3d>& orientations);

/// The machine envelope (m^3), nullopt for machines it does not know. Hexapod: the vertical
/// cylinder about the centroid of the base joints whose radius is the largest horizontal distance
/// of a base joint from that axis and whose height is the z extent of the base joints plus
/// max_length (the legs standing straight up at full stroke).
std::optional<double> machine_envelope_volume(const Machine& machine);

/// Volume enclosed by a closed, outward-oriented mesh (divergence theorem), m^3.
double mesh_volume(const TriangleMesh& mesh);

/// Topology of a mesh: every undirected edge must be used by exactly two triangles, once in each
/// direction, for a closed, consistently oriented surface.
struct MeshTopology {
  std::int64_t edges = 0;
  std::int64_t open_edges = 0;          ///< used by one triangle
  std::int64_t non_manifold_edges = 0;  ///< used by three or more
  std::int64_t misoriented_edges = 0;   ///< used twice in the same direction
  bool closed_and_oriented() const {
    return open_edges == 0 && non_manifold_edges == 0 && misoriented_edges == 0;
  }
};
MeshTopology mesh_topology(const TriangleMesh& mesh);

/// Volume of the convex hull of points (CGAL convex_hull_3), m^3; 0 for fewer than 4 points or
/// coplanar points.
double convex_hull_volume(const std::vector<Eigen::Vector3d>& points);
/// Area (m^2) of the convex hull of the points' (x, y) (CGAL convex_hull_2); 0 for fewer than 3
/// or collinear points.
double footprint_area(const std::vector<Eigen::Vector3d>& points);

/// A plane section through the workspace sampled on a pixel grid: pixel (i, j) is at
/// origin + i * pixel * axis_u + j * pixel * axis_v (pixel centres).
struct WorkspaceSlice {
  char normal_axis = 'z';  ///< 'x', 'y' or 'z': the plane is normal_axis = offset
  double offset = 0.0;     ///< m
  int width = 0, height = 0;
  double pixel = 0.0;                          ///< m
  Eigen::Vector2d origin;                      ///< in-plane coordinates (u, v) of pixel (0, 0) (m)
  std::vector<std::uint8_t> inside;            ///< width * height, row j major (j * width + i)
  std::vector<WorkspacePointMetrics> metrics;  ///< width * height (valid where inside)
};

/// Samples the plane normal_axis = offset over the box's extent in the two other axes with square
/// pixels of size `pixel` (m). Uses the orientations and restrictions of `options`.
WorkspaceSlice compute_workspace_slice(const Machine& machine, const WorkspaceOptions& options,
                                       const Eigen::AlignedBox3d& box, char normal_axis,
                                       double offset, double pixel);

}  // namespace pkmopt
