// Tests of models/workspace/mode_certificate: a region about the sample hexapod's home is
// certified with the sign of det J there and a margin bound that random poses respect; a thin
// singular surface (Fichter's: the platform turned 90 degrees about z) crossing a region is found
// although the workspace grid of the same region, with its margin filter, keeps every node; the
// budget, the orientation set's box, thread counts and bad input.
#include "models/workspace/mode_certificate.hpp"

#include <gtest/gtest.h>
#include <omp.h>

#include <cmath>
#include <numbers>
#include <random>
#include <stdexcept>

#include "models/hexapod/hexapod.hpp"
#include "models/sample_machines.hpp"

namespace pkmopt {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

double random_in(std::mt19937_64& engine, double lo, double hi) {
  return lo + std::uniform_real_distribution<double>(0.0, 1.0)(engine) * (hi - lo);
}

// The region about the home pose: +-5 cm, 0.85 .. 0.95 m high, tilt 10 deg, yaw +-5 deg.
PoseBox home_region() {
  PoseBox b;
  b.position_lo = {-0.05, -0.05, 0.85};
  b.position_hi = {0.05, 0.05, 0.95};
  b.theta = Interval(0.0, 10 * kDeg);
  b.phi = Interval(0.0, 2 * std::numbers::pi);
  b.gamma = Interval(-5 * kDeg, 5 * kDeg);
  return b;
}

TEST(ModeCertificate, TheRegionAboutHomeIsCertifiedAndItsMarginBoundHolds) {
  const Hexapod hexapod(sample_machines::conventions_hexapod_design());
  const PoseBox region = home_region();
  const ModeCertificate c = certify_working_mode(hexapod, {region}, {});
  ASSERT_TRUE(c.certified());
  const double home_det = hexapod.inverse_jacobian(Pose{{0, 0, 0.9}, {0, 0, 0}}).determinant();
  EXPECT_EQ(c.positive_boxes > 0 ? 1 : -1, home_det > 0 ? 1 : -1);
  EXPECT_GT(c.min_margin, 0.0);
  EXPECT_LE(c.min_margin, c.min_centre_margin);
  EXPECT_NEAR(c.positive_fraction + c.negative_fraction, 1.0, 1e-12);
  // At random poses of the region: det J has the certified sign, and margin(x) =
  // 1/||J_c^-1||_inf (computed here from the hexapod's own Jacobian) is at least the bound.
  std::mt19937_64 engine(23);
  for (int k = 0; k < 2000; ++k) {
    const double theta = random_in(engine, region.theta.lo, region.theta.hi);
    const double phi = random_in(engine, region.phi.lo, region.phi.hi);
    const double gamma = random_in(engine, region.gamma.lo, region.gamma.hi);
    Pose pose;
    for (int i = 0; i < 3; ++i)
      pose.position(i) = random_in(engine, region.position_lo(i), region.position_hi(i));
    pose.angles = angles_from_rotation(box_rotation(region.R0, theta, phi, gamma));
    Eigen::Matrix<double, 6, 6> J = hexapod.inverse_jacobian(pose);
    J.rightCols<3>() /= hexapod.enclosure_length();
    EXPECT_EQ(J.determinant() > 0 ? 1 : -1, home_det > 0 ? 1 : -1);
    const Eigen::Matrix<double, 6, 6> inverse = J.inverse();
    double norm = 0.0;
    for (int r = 0; r < 6; ++r) norm = std::max(norm, inverse.row(r).cwiseAbs().sum());
    EXPECT_GE(1.0 / norm, c.min_margin);
  }
}

// The sample hexapod with legs to 1.4 m and joints to 80 degrees: the turn of 90 degrees about z
// (Fichter's singularity) is within its reach.
HexapodDesign long_legged() {
  HexapodDesign d = sample_machines::conventions_hexapod_design();
  d.max_length = 1.4;
  d.joints.base_max_angle = 80 * kDeg;
  d.joints.platform_max_angle = 80 * kDeg;
  return d;
}

TEST(ModeCertificate, AThinSingularSurfaceTheGridMissesIsFound) {
  const Hexapod hexapod(long_legged());
  // The region: +-5 mm about (0, 0, 0.9), turned 88.5 +- 10 degrees about z. det J changes
  // sign at 90 degrees (x = y = 0: det J = 0 exactly there, checked).
  PoseBox region;
  region.position_lo = {-0.005, -0.005, 0.895};
  region.position_hi = {0.005, 0.005, 0.905};
  region.R0 = rotation_zyx<double>(Eigen::Vector3d(0, 0, 88.5 * kDeg));
  region.gamma = Interval(-10 * kDeg, 10 * kDeg);
  EXPECT_LT(std::abs(hexapod.inverse_jacobian(Pose{{0, 0, 0.9}, {0, 0, 90 * kDeg}}).determinant()),
            1e-15);

  // The workspace grid of the same region (5 mm, yaw sampled every 4 degrees: 78.5, 82.5, ...,
  // 98.5) keeps only poses with singularity_margin >= 0.001, and keeps every node: the grid
  // passes over the singular surface.
  WorkspaceOptions grid;
  grid.orientations.nominal_angles = Eigen::Vector3d(0, 0, 88.5 * kDeg);
  grid.orientations.yaw_range = 10 * kDeg;
  grid.orientations.orientation_step = 4 * kDeg;
  grid.resolution = 0.005;
  grid.min_singularity_margin = 0.001;
  grid.search_box = Eigen::AlignedBox3d(region.position_lo, region.position_hi);
  grid.compute_hull = false;
  const WorkspaceResult ws = compute_workspace(hexapod, grid);
  // Every node of the region is kept: the grid's nodes less its rim, one cell outside the box.
  EXPECT_EQ(ws.inside_nodes,
            static_cast<std::int64_t>((ws.grid_nodes - Eigen::Vector3i::Constant(2)).prod()));
  EXPECT_EQ(ws.inside_nodes, 27);
  EXPECT_GE(ws.maps.singularity_margin_min, 0.001);

  CertifyOptions options;
  options.min_size = 0.001;
  options.keep_parts = true;
  const ModeCertificate c = certify_working_mode(hexapod, {region}, options);
  EXPECT_FALSE(c.certified());
  // Both working modes are proved inside the region: a singular surface lies between them.
  EXPECT_GT(c.positive_boxes, 0);
  EXPECT_GT(c.negative_boxes, 0);
  ASSERT_EQ(c.uncertified.size(), 1u);
  EXPECT_EQ(c.uncertified.front().parts, static_cast<std::int64_t>(c.parts.size()));
  EXPECT_LT(c.uncertified_fraction, 0.2);
  // The parts left hug the surface: every one is within 1 degree of the turn of 90 degrees, and
  // one holds the singular pose itself.
  bool holds_singular_pose = false;
  for (const UncertifiedBox& part : c.parts) {
    EXPECT_FALSE(part.budget);
    EXPECT_LT(std::abs(part.box.gamma.mid() - 1.5 * kDeg), 1.0 * kDeg);
    holds_singular_pose =
        holds_singular_pose || (part.box.gamma.contains(1.5 * kDeg) &&
                                (part.box.position_lo.array() <= Eigen::Array3d(0, 0, 0.9)).all() &&
                                (part.box.position_hi.array() >= Eigen::Array3d(0, 0, 0.9)).all());
  }
  EXPECT_TRUE(holds_singular_pose);
}

TEST(ModeCertificate, ARunOutBudgetLeavesBoxesReported) {
  const Hexapod hexapod(sample_machines::conventions_hexapod_design());
  CertifyOptions options;
  options.max_evaluations = 5;
  const ModeCertificate c = certify_working_mode(hexapod, {home_region()}, options);
  EXPECT_FALSE(c.certified());
  ASSERT_EQ(c.uncertified.size(), 1u);
  EXPECT_TRUE(c.uncertified.front().budget);
  EXPECT_EQ(c.evaluations, 5);
}

TEST(ModeCertificate, TheOrientationBoxHoldsTheWorkspacesSampledOrientations) {
  OrientationSet set;
  set.nominal_angles = Eigen::Vector3d(0.1, -0.2, 0.4);
  set.tilt = 25 * kDeg;
  set.yaw_range = 15 * kDeg;
  const PoseBox box = orientation_box(set);
  EXPECT_EQ(box.theta.lo, 0.0);
  EXPECT_EQ(box.theta.hi, set.tilt);
  const IntervalRotation E = enclose_rotation(box);
  for (const Eigen::Matrix3d& R : sample_orientations(set))
    for (int r = 0; r < 3; ++r)
      for (int k = 0; k < 3; ++k) EXPECT_TRUE(E[r][k].contains(R(r, k)));
  // The cells of a grid: each node +- h/2 with that orientation box.
  std::vector<WorkspacePoint> points(2);
  points[1].position = Eigen::Vector3d(0.1, 0.2, 0.3);
  const auto cells = workspace_cells(points, 0.02, box);
  ASSERT_EQ(cells.size(), 2u);
  EXPECT_TRUE(cells[1].position_lo.isApprox(Eigen::Vector3d(0.09, 0.19, 0.29)));
  EXPECT_TRUE(cells[1].position_hi.isApprox(Eigen::Vector3d(0.11, 0.21, 0.31)));
  EXPECT_EQ(cells[1].gamma.hi, set.yaw_range);
}

TEST(ModeCertificate, TheSameForAnyThreadCount) {
  const Hexapod hexapod(long_legged());
  std::vector<PoseBox> region;
  for (int k = 0; k < 4; ++k) {
    PoseBox b;
    b.position_lo = {-0.01 + 0.005 * k, -0.005, 0.895};
    b.position_hi = {-0.005 + 0.005 * k, 0.005, 0.905};
    b.R0 = rotation_zyx<double>(Eigen::Vector3d(0, 0, 88 * kDeg));
    b.gamma = Interval(0.0, 4 * kDeg);
    region.push_back(b);
  }
  CertifyOptions options;
  options.min_size = 0.002;
  const int before = omp_get_max_threads();
  omp_set_num_threads(1);
  const ModeCertificate one = certify_working_mode(hexapod, region, options);
  omp_set_num_threads(2);
  const ModeCertificate two = certify_working_mode(hexapod, region, options);
  omp_set_num_threads(before);
  EXPECT_EQ(one.positive_boxes, two.positive_boxes);
  EXPECT_EQ(one.negative_boxes, two.negative_boxes);
  EXPECT_EQ(one.evaluations, two.evaluations);
  EXPECT_EQ(one.uncertified.size(), two.uncertified.size());
  EXPECT_EQ(one.min_margin, two.min_margin);
}

TEST(ModeCertificate, BadInputIsRefused) {
  const Hexapod hexapod(sample_machines::conventions_hexapod_design());
  EXPECT_THROW(certify_working_mode(hexapod, {}, {}), std::invalid_argument);
  PoseBox reversed = home_region();
  std::swap(reversed.position_lo, reversed.position_hi);
  EXPECT_THROW(certify_working_mode(hexapod, {reversed}, {}), std::invalid_argument);
  PoseBox nan = home_region();
  nan.gamma.hi = NAN;
  EXPECT_THROW(certify_working_mode(hexapod, {nan}, {}), std::invalid_argument);
  CertifyOptions bad;
  bad.min_size = 0.0;
  EXPECT_THROW(certify_working_mode(hexapod, {home_region()}, bad), std::invalid_argument);
  bad = {};
  bad.min_margin = -1.0;
  EXPECT_THROW(certify_working_mode(hexapod, {home_region()}, bad), std::invalid_argument);
}

}  // namespace
}  // namespace pkmopt
