// Tests of models/geometry/solid_bodies: the segment-to-prism distance against brute-force sampling
// of both the segment and the solid (discs, polygons, turned frames, crossing, touching, parallel
// to a face), which leg bodies each solid sees, the hexapod's clearance to a spindle against a
// capsule computation written here, the batch path with solids, and the validation.
#include "models/geometry/solid_bodies.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

#include "models/geometry/segment_distance.hpp"
#include "models/hexapod/hexapod.hpp"
#include "models/hexapod/hexapod_batch.hpp"
#include "tests/sample_machines.hpp"

namespace pkmopt {
namespace {

using sample_machines::Uniform;

// Inside test of a convex polygon written here: the point is on the inner side of every edge of
// the counter-clockwise polygon.
bool inside_polygon(const std::vector<Eigen::Vector2d>& ccw, const Eigen::Vector2d& p) {
  for (std::size_t i = 0; i < ccw.size(); ++i) {
    const Eigen::Vector2d e = ccw[(i + 1) % ccw.size()] - ccw[i], w = p - ccw[i];
    if (e.x() * w.y() - e.y() * w.x() < 0.0) return false;
  }
  return true;
}

// Points filling the prism (a grid of spacing h over its bounding box, in the parent frame).
std::vector<Eigen::Vector3d> fill_prism(const ConvexPrism& p, double h) {
  double lo_x = -p.radius, hi_x = p.radius, lo_y = -p.radius, hi_y = p.radius;
  for (const auto& v : p.polygon) {
    lo_x = std::min(lo_x, v.x());
    hi_x = std::max(hi_x, v.x());
    lo_y = std::min(lo_y, v.y());
    hi_y = std::max(hi_y, v.y());
  }
  // The polygon counter-clockwise (by its signed area).
  std::vector<Eigen::Vector2d> ccw = p.polygon;
  double area = 0.0;
  for (std::size_t i = 0; i < ccw.size(); ++i) {
    const Eigen::Vector2d& u = ccw[i];
    const Eigen::Vector2d& v = ccw[(i + 1) % ccw.size()];
    area += u.x() * v.y() - u.y() * v.x();
  }
  if (area < 0.0) std::reverse(ccw.begin(), ccw.end());
  std::vector<Eigen::Vector3d> out;
  for (double x = lo_x; x <= hi_x + 1e-12; x += h)
    for (double y = lo_y; y <= hi_y + 1e-12; y += h) {
      const Eigen::Vector2d q(x, y);
      const bool in = p.polygon.empty() ? q.norm() <= p.radius : inside_polygon(ccw, q);
      if (!in) continue;
      for (double z = p.z_min; z <= p.z_max + 1e-12; z += h)
        out.push_back(p.origin + p.axes * Eigen::Vector3d(x, y, z));
    }
  return out;
}

// The smallest distance between 601 points of the segment and the prism's fill points.
double sampled_distance(const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                        const std::vector<Eigen::Vector3d>& fill) {
  double best = std::numeric_limits<double>::infinity();
  for (int i = 0; i <= 600; ++i) {
    const Eigen::Vector3d x = a + (b - a) * (i / 600.0);
    for (const auto& y : fill) best = std::min(best, (x - y).norm());
  }
  return best;
}

// A point with coordinates drawn in [lo, hi], in sequence: the order in which a compiler
// evaluates constructor arguments is unspecified (GCC goes right to left, clang left to right),
// and the test's draws must not depend on it.
Eigen::Vector3d random_point(Uniform& u, double lo, double hi) {
  Eigen::Vector3d p;
  for (int i = 0; i < 3; ++i) p(i) = u(lo, hi);
  return p;
}

ConvexPrism random_prism(Uniform& u, bool polygon) {
  ConvexPrism p;
  if (polygon) {
    // A convex polygon: points on an ellipse at increasing angles (counter-clockwise), then
    // reversed half of the time.
    const int n = 3 + static_cast<int>(u(0, 5));
    double angle = u(0, 1);
    const double ax = u(0.1, 0.3), ay = u(0.1, 0.3);
    for (int i = 0; i < n; ++i) {
      p.polygon.emplace_back(ax * std::cos(angle), ay * std::sin(angle));
      angle += 2.0 * std::numbers::pi / n * u(0.6, 1.0);
    }
    if (u(0, 1) < 0.5) std::reverse(p.polygon.begin(), p.polygon.end());
  } else {
    p.radius = u(0.05, 0.3);
  }
  p.z_min = u(-0.1, 0.0);
  p.z_max = p.z_min + u(0.01, 0.1);
  p.origin = random_point(u, -0.1, 0.1);
  const double angle = u(0, 3);
  p.axes = Eigen::AngleAxisd(angle, random_point(u, -1, 1).normalized()).toRotationMatrix();
  return p;
}

TEST(SolidBodies, SegmentPrismDistanceAgreesWithSampling) {
  Uniform u(11);
  const double h = 0.008;
  // Fill spacing h: a point of the solid is within a cell diagonal h sqrt(3) of a fill point
  // (the fill starts at the solid's low corner), a segment point within a step of a sample.
  // Every fourth segment is aimed through a fill point (inside the solid), so that crossing
  // segments are tested whatever the draws give.
  int apart = 0, crossing = 0;
  for (int k = 0; k < 40; ++k) {
    const ConvexPrism p = random_prism(u, k % 2 == 1);
    const std::vector<Eigen::Vector3d> fill = fill_prism(p, h);
    ASSERT_FALSE(fill.empty()) << k;
    const Eigen::Vector3d a = random_point(u, -0.5, 0.5);
    Eigen::Vector3d b = random_point(u, -0.5, 0.5);
    if (k % 4 == 0) {
      const auto pick = static_cast<std::size_t>(u(0, 1) * static_cast<double>(fill.size()));
      b = 2.0 * fill[std::min(pick, fill.size() - 1)] - a;  // the segment's midpoint is inside
    }
    const double exact = segment_prism_distance(a, b, p);
    const double sampled = sampled_distance(a, b, fill);
    const double step = (b - a).norm() / 600.0;
    EXPECT_GE(sampled, exact - 1e-9) << k;  // no sample is closer than the exact distance
    EXPECT_LE(sampled - exact, h * std::sqrt(3.0) + step + 1e-9) << k;
    (exact > 0.0 ? apart : crossing) += 1;
  }
  EXPECT_GT(apart, 10);
  EXPECT_GE(crossing, 10);
}

TEST(SolidBodies, AnalyticCases) {
  ConvexPrism disc;  // radius 0.2, z in [0, 0.05]
  disc.radius = 0.2;
  disc.z_max = 0.05;
  // Parallel to the top face, 0.1 above it, crossing the axis.
  EXPECT_NEAR(segment_prism_distance({-1, 0, 0.15}, {1, 0, 0.15}, disc), 0.1, 1e-9);
  // Beside the rim, vertical: 0.3 from the axis.
  EXPECT_NEAR(segment_prism_distance({0.5, 0, -1}, {0.5, 0, 1}, disc), 0.3, 1e-9);
  // Towards the corner of the rim: from (0.5, 0, 0.45) to the edge at (0.2, 0, 0.05).
  EXPECT_NEAR(segment_prism_distance({0.5, 0, 0.45}, {0.5, 0, 2}, disc), 0.5, 1e-9);
  // Through the disc, and touching its face at a point.
  EXPECT_EQ(segment_prism_distance({0, 0, -1}, {0.1, 0, 1}, disc), 0.0);
  EXPECT_NEAR(segment_prism_distance({0.1, 0, 0.05}, {0.1, 0, 1}, disc), 0.0, 1e-12);
  // A square in a frame turned 90 deg about x (its z is the parent's -y).
  ConvexPrism square;
  square.polygon = {{-0.1, -0.1}, {0.1, -0.1}, {0.1, 0.1}, {-0.1, 0.1}};
  square.z_max = 0.02;
  square.axes =
      Eigen::AngleAxisd(std::numbers::pi / 2, Eigen::Vector3d::UnitX()).toRotationMatrix();
  // The local y is the parent's z: the square spans parent x, z in [-0.1, 0.1], y in [-0.02, 0].
  EXPECT_NEAR(segment_prism_distance({-1, 0.3, 0}, {1, 0.3, 0}, square), 0.3, 1e-9);
  EXPECT_NEAR(segment_prism_distance({0.4, -0.01, 0.5}, {0.4, -0.01, -0.5}, square), 0.3, 1e-9);
  // A tool cylinder from (0, 0, 0) to (0, 0, -0.3), diameter 0.1.
  const ConvexPrism tool = cylinder_prism({0, 0, 0}, {0, 0, -0.3}, 0.05);
  EXPECT_NEAR(segment_prism_distance({0.25, 0, -0.5}, {0.25, 0, 0.5}, tool), 0.2, 1e-9);
  EXPECT_NEAR(segment_prism_distance({0, 0, -0.4}, {0, 0, -1}, tool), 0.1, 1e-9);
}

// Legs: a cylinder body (base side), a rod body (platform side) and a one-capsule leg, all
// crossing a platform disc, a base disc and a tool: each solid sees only the bodies the rule says.
TEST(SolidBodies, EachSolidSeesTheBodiesNotJointedToIt) {
  MachineBodies bodies;
  bodies.platform.radius = 0.3;
  bodies.platform.z_max = 0.04;  // platform frame, here at the base origin (R = I)
  bodies.base.radius = 0.3;
  bodies.base.z_min = -0.04;
  bodies.tool = {0.1, {0, 0, 0}, {0, 0, -0.3}};
  const Capsule through{{0.1, 0, -1}, {0.1, 0, 1}, 0.01, 0, true, true};
  const Eigen::Matrix3d R = Eigen::Matrix3d::Identity();
  const Eigen::Vector3d origin(0, 0, 0);
  auto clearance_of = [&](const Capsule& c, const MachineBodies& b) {
    Clearance out;
    body_clearance(std::span<const Capsule>(&c, 1), b, R, origin, out);
    return out;
  };
  MachineBodies only_platform, only_base, only_tool;
  only_platform.platform = bodies.platform;
  only_base.base = bodies.base;
  only_tool.tool = bodies.tool;
  Capsule cylinder = through, rod = through;
  cylinder.on_platform = false;  // jointed to the base only
  rod.on_base = false;           // jointed to the platform only
  EXPECT_EQ(clearance_of(cylinder, only_platform).second, kPlatformBody);
  EXPECT_DOUBLE_EQ(clearance_of(cylinder, only_platform).value, -0.01);
  EXPECT_EQ(clearance_of(cylinder, only_base).first, -1);  // not checked: +inf
  EXPECT_EQ(clearance_of(rod, only_base).second, kBaseBody);
  EXPECT_EQ(clearance_of(rod, only_platform).first, -1);
  EXPECT_EQ(clearance_of(through, only_platform).first, -1);
  EXPECT_EQ(clearance_of(through, only_base).first, -1);
  // The tool sees every body: the axis 0.1 from the tool's axis, radii 0.05 and 0.01.
  const Clearance t = clearance_of(through, only_tool);
  EXPECT_EQ(t.second, kToolBody);
  EXPECT_NEAR(t.value, 0.04, 1e-9);
  EXPECT_EQ(clearance_pair_text(t.first, t.second), "1-tool");
  EXPECT_FALSE(bodies_apart(std::span<const Capsule>(&through, 1), only_tool, R, origin, 0.05));
  EXPECT_TRUE(bodies_apart(std::span<const Capsule>(&through, 1), only_tool, R, origin, 0.039));
  // The platform frame moved: the plate follows it.
  Clearance moved;
  body_clearance(std::span<const Capsule>(&cylinder, 1), only_platform, R, Eigen::Vector3d(0, 0, 2),
                 moved);
  EXPECT_NEAR(moved.value, 1.0 - 0.01, 1e-9);  // the cylinder's end (z = 1) below z = 2
}

// A hexapod with a spindle: its clearance is the smallest of the legs' own and, per leg, the
// capsule-to-cylinder gap computed here from the legs' axes and the spindle's side.
TEST(SolidBodies, HexapodSpindleClearanceAndBatch) {
  Uniform u(3);
  HexapodDesign design = sample_machines::conventions_hexapod_design();
  design.leg_shape.diameter = 0.05;
  design.bodies.tool = {0.3, {0, 0, 0.3}, {0, 0, -0.6}};  // long: the legs pass its side
  const Hexapod hexapod(design);
  std::vector<Pose> poses;
  for (int k = 0; k < 128; ++k) poses.push_back(sample_machines::random_pose(u));
  int tool_closest = 0;
  for (const Pose& pose : poses) {
    const Clearance c = hexapod.leg_clearance(pose);
    const Eigen::Matrix3d R = rotation_zyx<double>(pose.angles);
    const Eigen::Vector3d origin = pose.position - R * design.tcp;
    const Eigen::Vector3d t0 = origin + R * design.bodies.tool.from;
    const Eigen::Vector3d t1 = origin + R * design.bodies.tool.to;
    for (int i = 0; i < 6; ++i) {
      const Eigen::Vector3d a = design.base_joints.col(i);
      const Eigen::Vector3d p = pose.position + R * hexapod.platform_rel_tcp().col(i);
      const SegmentClosest sc = segment_closest(a, p, t0, t1);
      // The cylinder's distance where the closest point is on its side: the axes' distance less
      // the radius.
      if (!(sc.t > 1e-6 && sc.t < 1 - 1e-6 && sc.distance > 0.15)) continue;
      const double gap = sc.distance - 0.15 - 0.025;
      EXPECT_LE(c.value, gap + 1e-12);
      if (c.second == kToolBody && c.first == i) {
        EXPECT_NEAR(c.value, gap, 1e-8);
        ++tool_closest;
      }
    }
  }
  EXPECT_GT(tool_closest, 10);
  // The batch path gives the scalar clearance, pair and reachability.
  std::vector<PoseMetrics> batch(poses.size());
  analyze_hexapod_batch(hexapod, poses.data(), poses.size(), Wrench::Zero(), batch.data());
  auto data = hexapod.make_data();
  for (std::size_t k = 0; k < poses.size(); ++k) {
    PoseMetrics m;
    hexapod.analyze(*data, poses[k], Wrench::Zero(), m);
    EXPECT_NEAR(batch[k].leg_clearance, m.leg_clearance, 1e-12) << k;
    // The pair: the same solid (two legs may tie to rounding in the kernel).
    EXPECT_EQ(batch[k].clearance_second >= kPlatformBody, m.clearance_second >= kPlatformBody);
    if (m.clearance_second >= kPlatformBody) {
      EXPECT_EQ(batch[k].clearance_first, m.clearance_first) << k;
      EXPECT_EQ(batch[k].clearance_second, m.clearance_second) << k;
    }
    EXPECT_EQ(batch[k].reachable, m.reachable) << k;
    EXPECT_EQ(hexapod.reachable(*data, poses[k]), m.reachable) << k;
  }
}

TEST(SolidBodies, ValidationNamesTheKey) {
  auto message = [](const MachineBodies& b) {
    try {
      check_machine_bodies(b);
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  MachineBodies b;
  EXPECT_EQ(message(b), "");
  b.platform.polygon = {{0, 0}, {1, 0}, {0.2, 0.2}, {0, 1}};  // turns inwards at vertex 3
  b.platform.z_max = 0.01;
  EXPECT_NE(message(b).find("bodies.platform.polygon must be convex"), std::string::npos);
  b.platform.polygon = {{0, 0}, {1, 0}, {0, 1}};
  EXPECT_EQ(message(b), "");
  // A pentagram turns the same way at every vertex but winds round twice.
  b.platform.polygon.clear();
  for (const int k : {0, 2, 4, 1, 3})
    b.platform.polygon.emplace_back(std::cos(2 * std::numbers::pi * k / 5),
                                    std::sin(2 * std::numbers::pi * k / 5));
  EXPECT_NE(message(b).find("wind round once"), std::string::npos);
  b.platform.polygon = {{0, 0}, {1, 0}, {0, 1}};
  b.platform.radius = 0.3;
  EXPECT_NE(message(b).find("either radius"), std::string::npos);
  b.platform = {};
  b.base.radius = 0.3;  // no z
  EXPECT_NE(message(b).find("bodies.base.z"), std::string::npos);
  b.base = {};
  b.tool = {0.1, {0, 0, 0}, {0, 0, 0}};
  EXPECT_NE(message(b).find("bodies.tool"), std::string::npos);
  HexapodDesign design = sample_machines::conventions_hexapod_design();
  design.bodies.tool = {0.1, {0, 0, 0}, {0, 0, -0.2}};
  EXPECT_THROW(Hexapod{design}, std::invalid_argument);  // solids need a leg shape
  // A plate with one-capsule legs (jointed to both plates) would be checked against nothing.
  design.leg_shape.diameter = 0.05;
  design.bodies = {};
  design.bodies.platform.radius = 0.3;
  design.bodies.platform.z_max = 0.03;
  try {
    Hexapod{design};
    ADD_FAILURE() << "no exception";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("give legs.cylinder and legs.rod"), std::string::npos);
  }
  design.leg_shape = {};
  design.leg_shape.cylinder_diameter = 0.08;  // a cylinder: the platform plate sees it
  design.leg_shape.cylinder_length = 0.5;
  EXPECT_NO_THROW(Hexapod{design});
  design.bodies.base.radius = 0.6;  // no rod: the base plate would see nothing
  design.bodies.base.z_min = -0.03;
  EXPECT_THROW(Hexapod{design}, std::invalid_argument);
}

}  // namespace
}  // namespace pkmopt
