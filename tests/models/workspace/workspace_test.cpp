// Tests of models/workspace: volumes against exact values and Monte Carlo (also with the legs'
// interference), convergence, the boundary mesh, orientation sets, restrictions, maps and slices.
#include "models/workspace/workspace.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <numbers>
#include <utility>

#include "models/hexapod/hexapod.hpp"
#include "models/sample_machines.hpp"
#include "tests/models/workspace/monte_carlo_volume.hpp"

namespace pkmopt {
namespace {

constexpr double kPi = std::numbers::pi;

double ball_volume(double r) { return 4.0 / 3.0 * kPi * r * r * r; }

// Volume of the intersection of two balls of radii r1, r2 whose centres are d apart.
double lens_volume(double r1, double r2, double d) {
  if (d >= r1 + r2) return 0.0;
  if (d <= std::abs(r1 - r2)) return ball_volume(std::min(r1, r2));
  return kPi * (r1 + r2 - d) * (r1 + r2 - d) *
         (d * d + 2 * d * r2 - 3 * r2 * r2 + 2 * d * r1 + 6 * r1 * r2 - 3 * r1 * r1) / (12 * d);
}

// Legs 0-2 keep the TCP in the shell [min, max] about centre_a, legs 3-5 about centre_b
// (a_i = b_i + centre, tcp = 0, R = I): the workspace is the intersection of two shells.
Hexapod two_shell_hexapod(const Eigen::Vector3d& centre_a, const Eigen::Vector3d& centre_b,
                          double min_length, double max_length) {
  HexapodDesign design = semi_regular_hexapod(0.6, deg_to_rad(20), 0.25, deg_to_rad(20));
  for (int i = 0; i < 6; ++i) {
    design.base_joints.col(i) = design.platform_joints.col(i) + (i < 3 ? centre_a : centre_b);
  }
  design.min_length = min_length;
  design.max_length = max_length;
  design.stiffness.E = 2.1e11;
  design.stiffness.area = 3e-4;
  return Hexapod(design);
}

// The sample hexapod of docs/conventions.md.
Hexapod sample_hexapod() { return Hexapod(sample_machines::conventions_hexapod_design()); }

WorkspaceOptions volume_only(double resolution) {
  WorkspaceOptions options;
  options.resolution = resolution;
  options.compute_maps = false;
  options.compute_hull = false;
  return options;
}

double relative_error(double value, double exact) { return std::abs(value - exact) / exact; }

TEST(WorkspaceVolume, SphericalShellIsExactToHalfAPercent) {
  const Hexapod shell = two_shell_hexapod({0, 0, 0}, {0, 0, 0}, 0.7, 1.15);
  const double exact = ball_volume(1.15) - ball_volume(0.7);
  WorkspaceOptions options = volume_only(0.03);
  options.compute_hull = true;
  const WorkspaceResult ws = compute_workspace(shell, options);
  EXPECT_LT(relative_error(ws.volume, exact), 0.005) << ws.volume << " vs " << exact;
  EXPECT_FALSE(ws.touches_search_box);
  // The hull of the boundary vertices lies inside the outer ball and fills it nearly.
  EXPECT_GE(ws.convex_hull_volume, ws.volume);
  EXPECT_LE(ws.convex_hull_volume, ball_volume(1.15));
  EXPECT_GT(ws.convex_hull_volume, 0.99 * ball_volume(1.15));
}

TEST(WorkspaceVolume, IntersectionOfTwoShellsMatchesTheLensFormula) {
  const double d = 0.5, r_in = 0.7, r_out = 1.15;
  const Hexapod shells = two_shell_hexapod({0, 0, 0}, {d, 0, 0}, r_in, r_out);
  // (B_a \ b_a) n (B_b \ b_b) by inclusion-exclusion over the balls.
  const double exact =
      lens_volume(r_out, r_out, d) - 2.0 * lens_volume(r_in, r_out, d) + lens_volume(r_in, r_in, d);
  const double volume = workspace_volume(shells, volume_only(0.02));
  EXPECT_LT(relative_error(volume, exact), 0.005) << volume << " vs " << exact;
}

TEST(WorkspaceVolume, ErrorFallsFastWithResolution) {
  const double d = 0.5, r_in = 0.7, r_out = 1.15;
  const Hexapod shells = two_shell_hexapod({0, 0, 0}, {d, 0, 0}, r_in, r_out);
  const double exact =
      lens_volume(r_out, r_out, d) - 2.0 * lens_volume(r_in, r_out, d) + lens_volume(r_in, r_in, d);
  double previous_error = 1.0;
  for (double h : {0.1, 0.05, 0.025}) {
    const double error = relative_error(workspace_volume(shells, volume_only(h)), exact);
    // Second order: halving h should divide the error by about 4; demand at least 2.5.
    EXPECT_LT(error, previous_error / 2.5) << "h = " << h;
    previous_error = error;
  }
}

TEST(WorkspaceVolume, AgreesWithMonteCarloOnTheSampleHexapod) {
  const Hexapod hexapod = sample_hexapod();
  WorkspaceOptions options = volume_only(0.02);
  options.compute_hull = true;
  const WorkspaceResult ws = compute_workspace(hexapod, options);
  ASSERT_GT(ws.volume, 0.0);
  EXPECT_FALSE(ws.touches_search_box);
  EXPECT_GE(ws.convex_hull_volume, ws.volume);

  // 1e6 uniform samples in the search box: relative standard error about 0.2 %.
  const test_volume::MonteCarlo mc =
      test_volume::monte_carlo_volume(hexapod, ws.search_box, Eigen::Vector3d::Zero(), 20240611);
  const double monte_carlo = mc.volume, standard_error = mc.standard_error;
  EXPECT_LT(std::abs(ws.volume - monte_carlo), 4.0 * standard_error + 1e-3 * monte_carlo)
      << ws.volume << " vs Monte Carlo " << monte_carlo << " +- " << standard_error;
}

// Legs of 80 mm on the sample hexapod (no joint limits, long stroke) turned by 60 degrees about
// the vertical: legs that would touch cut the constant-orientation workspace to less than half,
// and the grid volume equals a Monte Carlo estimate of the same rule (Hexapod::reachable, which
// includes the clearance).
TEST(WorkspaceVolume, LegInterferenceShrinksItAndAgreesWithMonteCarlo) {
  HexapodDesign design = sample_machines::conventions_hexapod_design();
  design.joints = HexapodJointLimits{};
  design.max_length = 1.4;
  WorkspaceOptions options = volume_only(0.02);
  options.orientations.nominal_angles = Eigen::Vector3d(0, 0, deg_to_rad(60.0));
  const WorkspaceResult free = compute_workspace(Hexapod(design), options);
  design.leg_shape.diameter = 0.08;
  const Hexapod hexapod(design);
  const WorkspaceResult ws = compute_workspace(hexapod, options);
  ASSERT_GT(ws.volume, 0.0);
  EXPECT_LT(ws.volume, 0.5 * free.volume) << ws.volume << " of " << free.volume;
  EXPECT_FALSE(ws.touches_search_box);
  const test_volume::MonteCarlo mc = test_volume::monte_carlo_volume(
      hexapod, ws.search_box, options.orientations.nominal_angles, 20261202);
  const double monte_carlo = mc.volume, standard_error = mc.standard_error;
  EXPECT_LT(std::abs(ws.volume - monte_carlo), 4.0 * standard_error + 1e-3 * monte_carlo)
      << ws.volume << " vs Monte Carlo " << monte_carlo << " +- " << standard_error;
}

TEST(WorkspaceMesh, IsClosedConsistentlyOrientedAndEnclosesPositiveVolume) {
  // Euler characteristic V - E + F of the boundary: 2 per sphere-like surface. The sample
  // workspace is a ball-like solid; the spherical shell is bounded by two spheres.
  const std::pair<Hexapod, std::int64_t> cases[] = {
      {sample_hexapod(), 2}, {two_shell_hexapod({0, 0, 0}, {0, 0, 0}, 0.7, 1.15), 4}};
  for (const auto& [machine, expected_euler] : cases) {
    const WorkspaceResult ws = compute_workspace(machine, volume_only(0.04));
    ASSERT_FALSE(ws.boundary.triangles.empty());
    const MeshTopology topology = mesh_topology(ws.boundary);
    EXPECT_GT(topology.edges, 0);
    EXPECT_EQ(topology.open_edges, 0);
    EXPECT_EQ(topology.non_manifold_edges, 0);
    EXPECT_EQ(topology.misoriented_edges, 0);
    EXPECT_TRUE(topology.closed_and_oriented());
    EXPECT_GT(mesh_volume(ws.boundary), 0.0);
    const std::int64_t euler = static_cast<std::int64_t>(ws.boundary.vertices.size()) -
                               topology.edges +
                               static_cast<std::int64_t>(ws.boundary.triangles.size());
    EXPECT_EQ(euler, expected_euler);
  }
}

TEST(WorkspaceMesh, TopologyDetectsOpenAndMisorientedMeshes) {
  // A tetrahedron, outward-oriented.
  TriangleMesh tetra;
  tetra.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  tetra.triangles = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  EXPECT_TRUE(mesh_topology(tetra).closed_and_oriented());
  EXPECT_NEAR(mesh_volume(tetra), 1.0 / 6.0, 1e-15);
  TriangleMesh flipped = tetra;
  std::swap(flipped.triangles[3][1], flipped.triangles[3][2]);
  EXPECT_EQ(mesh_topology(flipped).misoriented_edges, 3);
  TriangleMesh open = tetra;
  open.triangles.pop_back();
  EXPECT_EQ(mesh_topology(open).open_edges, 3);
}

TEST(ConvexHull, UnitCubeAndDegenerateInput) {
  std::vector<Eigen::Vector3d> cube;
  for (int c = 0; c < 8; ++c) cube.emplace_back(c & 1, (c >> 1) & 1, (c >> 2) & 1);
  cube.emplace_back(0.5, 0.5, 0.5);  // interior point
  EXPECT_NEAR(convex_hull_volume(cube), 1.0, 1e-12);
  const std::vector<Eigen::Vector3d> flat = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}};
  EXPECT_EQ(convex_hull_volume(flat), 0.0);
}

// A grid of points has many coplanar hull facets, which CGAL may triangulate differently; the
// volume is summed exactly, so it is the correctly rounded exact value and the same every call.
TEST(ConvexHull, GridOfCoplanarPointsGivesTheExactVolumeEveryTime) {
  std::vector<Eigen::Vector3d> grid;
  for (int i = 0; i <= 10; ++i)
    for (int j = 0; j <= 10; ++j)
      for (int k = 0; k <= 4; ++k) grid.emplace_back(0.1 * i, 0.3 * j, 0.7 * k);
  // The hull is the box of the extreme coordinates; its volume computed here independently.
  const double a = 0.1 * 10, b = 0.3 * 10, c = 0.7 * 4;
  const double first = convex_hull_volume(grid);
  EXPECT_NEAR(first, a * b * c, 1e-14 * a * b * c);
  for (int repeat = 0; repeat < 20; ++repeat) EXPECT_EQ(convex_hull_volume(grid), first);
}

TEST(Orientations, SamplesStayInTheConeAndReachItsRimAndYawEnds) {
  OrientationSet set;
  set.nominal_angles = deg_to_rad(Eigen::Vector3d(5, -10, 30));
  set.tilt = deg_to_rad(20);
  set.yaw_range = deg_to_rad(15);
  set.orientation_step = deg_to_rad(5);
  const auto rotations = sample_orientations(set);
  const Eigen::Matrix3d R0 = rotation_zyx<double>(set.nominal_angles);
  double max_tilt = 0.0;
  double max_yaw = 0.0;
  for (const auto& R : rotations) {
    const double tilt = std::acos(std::clamp(R.col(2).dot(R0.col(2)), -1.0, 1.0));
    EXPECT_LE(tilt, set.tilt + 1e-12);
    max_tilt = std::max(max_tilt, tilt);
    // R0^T R = Rot(u, tilt) Rz(gamma) with u horizontal in the tool frame: undo the tilt.
    const Eigen::Matrix3d M = R0.transpose() * R;
    const Eigen::Vector3d axis = Eigen::Vector3d::UnitZ().cross(M.col(2));
    EXPECT_NEAR(axis.z(), 0.0, 1e-15);
    Eigen::Matrix3d untilt = Eigen::Matrix3d::Identity();
    if (axis.norm() > 1e-15)
      untilt = Eigen::AngleAxisd(-tilt, axis.normalized()).toRotationMatrix();
    const Eigen::Matrix3d yaw = untilt * M;
    EXPECT_NEAR(yaw(2, 2), 1.0, 1e-12);
    const double gamma = std::atan2(yaw(1, 0), yaw(0, 0));
    EXPECT_LE(std::abs(gamma), set.yaw_range + 1e-12);
    max_yaw = std::max(max_yaw, std::abs(gamma));
  }
  EXPECT_NEAR(max_tilt, set.tilt, 1e-12);
  EXPECT_NEAR(max_yaw, set.yaw_range, 1e-12);
  // Rings 0..4, rim first; yaw samples 0..6 per (ring, azimuth).
  EXPECT_EQ(rotations.size() % 7, 0u);
  EXPECT_NEAR(std::acos(std::clamp(rotations.front().col(2).dot(R0.col(2)), -1.0, 1.0)), set.tilt,
              1e-12);
  OrientationSet constant;
  EXPECT_EQ(sample_orientations(constant).size(), 1u);
}

// orientation_count counts what sample_orientations makes without making it; validate refuses
// sets of more than kMaxOrientations and steps outside the limits users see in degrees.
TEST(Orientations, CountWithoutSamplingAndTheLimitsUsersSee) {
  for (const auto& [tilt, yaw, step] : std::vector<std::array<double, 3>>{
           {0, 0, 5}, {20, 15, 5}, {45, 0, 3}, {0, 90, 7}, {89, 179, 10}, {179, 0, 30}}) {
    OrientationSet set;
    set.tilt = deg_to_rad(tilt);
    set.yaw_range = deg_to_rad(yaw);
    set.orientation_step = deg_to_rad(step);
    EXPECT_EQ(orientation_count(set), static_cast<std::int64_t>(sample_orientations(set).size()))
        << tilt << " " << yaw << " " << step;
  }
  WorkspaceOptions options;
  options.orientations.tilt = deg_to_rad(179);
  options.orientations.yaw_range = deg_to_rad(179);
  options.orientations.orientation_step = deg_to_rad(0.01);
  EXPECT_GT(orientation_count(options.orientations), kMaxOrientations);
  EXPECT_NE(validate(options).find("Violated constraint: at most 1000000"), std::string::npos)
      << validate(options);
  options.orientations.tilt = 0.0;
  options.orientations.yaw_range = 0.0;
  EXPECT_EQ(validate(options), "");  // 0.01 deg is the smallest step
  options.orientations.orientation_step = deg_to_rad(0.009);
  EXPECT_NE(validate(options), "");
  EXPECT_TRUE(workspace_limits::kOrientationStepDeg.accepts(90.0));
  EXPECT_FALSE(workspace_limits::kOrientationStepDeg.accepts(90.5));
  EXPECT_FALSE(workspace_limits::kTiltDeg.accepts(180.0));
  EXPECT_FALSE(workspace_limits::kTiltDeg.accepts(std::nan("")));
}

TEST(OrientationWorkspace, AllIsInsideConstantIsInsideSome) {
  const Hexapod hexapod = sample_hexapod();
  WorkspaceOptions options = volume_only(0.04);
  const double constant = workspace_volume(hexapod, options);
  options.orientations.tilt = deg_to_rad(10);
  options.orientations.orientation_step = deg_to_rad(5);
  options.orientations.mode = OrientationSet::Mode::kAll;
  const double all = workspace_volume(hexapod, options);
  options.orientations.mode = OrientationSet::Mode::kSome;
  const double some = workspace_volume(hexapod, options);
  EXPECT_GT(all, 0.0);
  EXPECT_LT(all, constant);
  EXPECT_GT(some, constant);
}

TEST(OrientationWorkspace, JointsAtTheTcpMakeOrientationIrrelevant) {
  // Every platform joint at the TCP: the leg lengths do not depend on R, so the workspace of
  // every orientation set is the shell of radii [min, max] about the common base point.
  HexapodDesign design = semi_regular_hexapod(0.6, deg_to_rad(20), 0.25, deg_to_rad(20));
  design.base_joints.setZero();
  design.platform_joints.setZero();
  design.characteristic_length = 0.25;
  design.min_length = 0.5;
  design.max_length = 0.9;
  design.stiffness.axial_stiffness = 1e8;
  const Hexapod point(design);
  const double exact = ball_volume(0.9) - ball_volume(0.5);
  WorkspaceOptions options = volume_only(0.05);
  options.orientations.tilt = deg_to_rad(30);
  options.orientations.yaw_range = deg_to_rad(20);
  options.orientations.orientation_step = deg_to_rad(15);
  for (auto mode : {OrientationSet::Mode::kAll, OrientationSet::Mode::kSome}) {
    options.orientations.mode = mode;
    EXPECT_LT(relative_error(workspace_volume(point, options), exact), 0.005);
  }
}

TEST(Restrictions, MarginAndStiffnessShrinkTheWorkspaceAndHoldAtEveryPoint) {
  const Hexapod hexapod = sample_hexapod();
  WorkspaceOptions options = volume_only(0.04);
  options.compute_maps = true;
  options.keep_points = true;
  const WorkspaceResult free = compute_workspace(hexapod, options);
  ASSERT_GT(free.maps.points, 0);
  const double margin =
      0.5 * (free.maps.singularity_margin_min + free.maps.global_conditioning_index);
  const double stiffness = free.maps.stiffness_min_mean;

  options.min_singularity_margin = margin;
  const WorkspaceResult by_margin = compute_workspace(hexapod, options);
  EXPECT_LT(by_margin.volume, free.volume);
  EXPECT_GT(by_margin.volume, 0.0);
  for (const auto& p : by_margin.points) EXPECT_GE(p.metrics.singularity_margin, margin);
  EXPECT_GE(by_margin.maps.singularity_margin_min, margin);

  options.min_singularity_margin.reset();
  options.min_stiffness = stiffness;
  const WorkspaceResult by_stiffness = compute_workspace(hexapod, options);
  EXPECT_LT(by_stiffness.volume, free.volume);
  for (const auto& p : by_stiffness.points) EXPECT_GE(p.metrics.stiffness_min, stiffness);
}

TEST(Maps, ReduceThePointMetricsAndMatchAnalyze) {
  const Hexapod hexapod = sample_hexapod();
  WorkspaceOptions options = volume_only(0.05);
  options.compute_maps = true;
  options.keep_points = true;
  options.wrench << 0, 0, -1000, 0, 0, 0;
  const WorkspaceResult ws = compute_workspace(hexapod, options);
  ASSERT_EQ(static_cast<std::int64_t>(ws.points.size()), ws.maps.points);
  ASSERT_GT(ws.maps.points, 100);
  const auto data = hexapod.make_data();
  PoseMetrics m;
  double margin_sum = 0.0, stiffness_min = 1e300, force_max = 0.0, error_max = 0.0;
  for (const auto& p : ws.points) {
    hexapod.analyze(*data, Pose{p.position, Eigen::Vector3d::Zero()}, options.wrench, m);
    EXPECT_TRUE(m.reachable);
    EXPECT_EQ(p.metrics.singularity_margin, m.singularity_margin);
    EXPECT_EQ(p.metrics.max_leg_force, m.tau.cwiseAbs().maxCoeff());
    margin_sum += m.singularity_margin;
    stiffness_min = std::min(stiffness_min, m.stiffness_min);
    force_max = std::max(force_max, m.tau.cwiseAbs().maxCoeff());
    error_max = std::max(error_max, m.tcp_error_max);
  }
  EXPECT_NEAR(ws.maps.global_conditioning_index, margin_sum / ws.points.size(), 1e-12);
  EXPECT_EQ(ws.maps.stiffness_min_min, stiffness_min);
  EXPECT_EQ(ws.maps.max_leg_force, force_max);
  EXPECT_EQ(ws.maps.tcp_error_max, error_max);
  EXPECT_GT(ws.maps.max_leg_force, 1000.0 / 6.0);  // six legs share at least the load
  // Envelope: cylinder of radius 0.6 (base joints) and height max_length 1.15.
  ASSERT_TRUE(ws.envelope_volume.has_value());
  EXPECT_NEAR(*ws.envelope_volume, kPi * 0.36 * 1.15, 1e-12);
  ASSERT_TRUE(ws.envelope_ratio.has_value());
  EXPECT_NEAR(*ws.envelope_ratio, *ws.envelope_volume / ws.volume, 1e-12);
}

TEST(Slices, ShellSectionHasTheAnnulusArea) {
  const Hexapod shell = two_shell_hexapod({0, 0, 0}, {0, 0, 0}, 0.7, 1.15);
  WorkspaceOptions options = volume_only(0.05);
  const Eigen::AlignedBox3d box(Eigen::Vector3d::Constant(-1.2), Eigen::Vector3d::Constant(1.2));
  const WorkspaceSlice slice = compute_workspace_slice(shell, options, box, 'z', 0.0, 0.005);
  ASSERT_EQ(slice.inside.size(), static_cast<std::size_t>(slice.width) * slice.height);
  std::int64_t inside = 0;
  for (int j = 0; j < slice.height; ++j) {
    for (int i = 0; i < slice.width; ++i) {
      const double u = slice.origin(0) + i * slice.pixel, v = slice.origin(1) + j * slice.pixel;
      const double r = std::hypot(u, v);
      const bool in = slice.inside[static_cast<std::size_t>(j * slice.width + i)] != 0;
      if (std::abs(r - 0.7) > 1e-9 && std::abs(r - 1.15) > 1e-9) {
        EXPECT_EQ(in, r > 0.7 && r < 1.15) << u << ", " << v;
      }
      inside += in;
    }
  }
  const double area = static_cast<double>(inside) * slice.pixel * slice.pixel;
  EXPECT_LT(relative_error(area, kPi * (1.15 * 1.15 - 0.7 * 0.7)), 0.01);
}

TEST(Options, ValidateNamesTheViolatedConstraint) {
  WorkspaceOptions options;
  EXPECT_EQ(validate(options), "");
  options.resolution = 0.0;
  EXPECT_NE(validate(options).find("resolution"), std::string::npos);
  options = WorkspaceOptions{};
  options.orientations.tilt = -0.1;
  EXPECT_NE(validate(options).find("tilt"), std::string::npos);
  options = WorkspaceOptions{};
  options.min_singularity_margin = 1.5;
  EXPECT_NE(validate(options).find("min_singularity_margin"), std::string::npos);
  EXPECT_THROW(compute_workspace(sample_hexapod(), options), std::invalid_argument);
  options = WorkspaceOptions{};
  options.resolution = 1e-5;  // far too many nodes
  EXPECT_THROW(compute_workspace(sample_hexapod(), options), std::invalid_argument);
}

}  // namespace
}  // namespace pkmopt
