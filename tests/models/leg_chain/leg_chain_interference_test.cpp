// Tests of models/leg_chain/leg_chain_interference: the links' clearance of leg-chain machines
// (delta cranks and parallelogram rods, linear-delta rods, hexaglide struts) against brute-force
// sampling of link axes placed here from the IK and the published geometry, reachability with
// min_clearance, the solids seen by the links, and the validation.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>
#include <vector>

#include "models/geometry/solid_bodies.hpp"
#include "models/leg_chain/leg_chain.hpp"
#include "tests/sample_machines.hpp"

namespace pkmopt {
namespace {

using sample_machines::Uniform;

struct Segment {
  Eigen::Vector3d a, b;
  double radius;
  int leg;
};

// The smallest distance between two segments' surfaces, their axes sampled at 401 points each.
double sampled_gap(const Segment& x, const Segment& y) {
  double best = std::numeric_limits<double>::infinity();
  for (int i = 0; i <= 400; ++i) {
    const Eigen::Vector3d p = x.a + (x.b - x.a) * (i / 400.0);
    for (int j = 0; j <= 400; ++j)
      best = std::min(best, (p - (y.a + (y.b - y.a) * (j / 400.0))).norm());
  }
  return best - x.radius - y.radius;
}

// The delta's links at a pose, placed here: elbow c = o + r (cos q d + sin q (w x d)), platform
// point P = p + b (R = I), rods at c +- h, P +- h with h = width / 2 along the crank axis.
std::vector<Segment> delta_links(const LegChainDesign& d, const Eigen::VectorXd& q,
                                 const Eigen::Vector3d& p, double crank_d, double rod_d,
                                 double width) {
  std::vector<Segment> out;
  for (int i = 0; i < 3; ++i) {
    const LegChainLeg& leg = d.legs[static_cast<std::size_t>(i)];
    const Eigen::Vector3d w = leg.axis.normalized();
    const Eigen::Vector3d dz = (leg.crank_zero - leg.crank_zero.dot(w) * w).normalized();
    const Eigen::Vector3d c =
        leg.base_point + leg.crank_length * (std::cos(q(i)) * dz + std::sin(q(i)) * w.cross(dz));
    const Eigen::Vector3d P = p + leg.platform_point - d.tcp;
    out.push_back({leg.base_point, c, crank_d / 2, i});
    const Eigen::Vector3d h = 0.5 * width * w;
    if (width > 0.0) {
      out.push_back({c + h, P + h, rod_d / 2, i});
      out.push_back({c - h, P - h, rod_d / 2, i});
    } else {
      out.push_back({c, P, rod_d / 2, i});
    }
  }
  return out;
}

double sampled_clearance(const std::vector<Segment>& links) {
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t u = 0; u < links.size(); ++u)
    for (std::size_t v = u + 1; v < links.size(); ++v)
      if (links[u].leg != links[v].leg) best = std::min(best, sampled_gap(links[u], links[v]));
  return best;
}

TEST(LegChainInterference, DeltaClearanceAgreesWithSampledLinks) {
  for (const double width : {0.0, 0.08}) {
    DeltaDesign d;
    d.stiffness.parallelogram_width = width;
    d.shapes.link_diameter = 0.03;
    d.shapes.crank_diameter = 0.09;
    const LegChainDesign design = delta_design(d);
    const LegChainMachine delta(design);
    ASSERT_TRUE(delta.checks_leg_interference());
    Uniform u(7);
    auto data = delta.make_data();
    for (int k = 0; k < 12; ++k) {
      const Pose pose{{u(-0.4, 0.4), u(-0.4, 0.4), u(-1.2, -0.7)}, Eigen::Vector3d::Zero()};
      const auto q = delta.inverse_kinematics(pose);
      ASSERT_TRUE(q.has_value());
      const double sampled =
          sampled_clearance(delta_links(design, *q, pose.position, 0.09, 0.03, width));
      const Clearance c = delta.leg_clearance(pose);
      // Sampling overestimates by at most the 1/400 step of the longer axis.
      EXPECT_LE(c.value, sampled + 1e-9) << k;
      EXPECT_GE(c.value, sampled - 1.3 / 400) << k;
      PoseMetrics m;
      delta.analyze(*data, pose, Wrench::Zero(), m);
      EXPECT_EQ(m.leg_clearance, c.value);
      EXPECT_EQ(m.clearance_first, c.first);
      EXPECT_EQ(m.clearance_second, c.second);
    }
  }
}

// Links placed here from the carriage positions q along the guides: c = g + q u.
TEST(LegChainInterference, LinearDeltaAndHexaglideAgreeWithSampledLinks) {
  LinearDeltaDesign ld;
  ld.shapes.link_diameter = 0.02;
  HexaglideDesign hg;
  hg.shapes.link_diameter = 0.06;
  const LegChainDesign designs[] = {linear_delta_design(ld), hexaglide_design(hg)};
  Uniform u(9);
  for (const LegChainDesign& design : designs) {
    const LegChainMachine machine(design);
    int checked = 0;
    for (int k = 0; k < 40 && checked < 8; ++k) {
      Pose pose = design.home;
      pose.position += Eigen::Vector3d(u(-0.05, 0.05), u(-0.05, 0.05), u(-0.05, 0.05));
      if (design.mobility == PlatformMobility::kSixDof)
        pose.angles = deg_to_rad(Eigen::Vector3d(u(-5, 5), u(-5, 5), u(-5, 5)));
      const auto q = machine.inverse_kinematics(pose);
      if (!q) continue;
      ++checked;
      const Eigen::Matrix3d R = rotation_zyx<double>(pose.angles);
      std::vector<Segment> links;
      for (std::size_t i = 0; i < design.legs.size(); ++i) {
        const LegChainLeg& leg = design.legs[i];
        const Eigen::Vector3d c =
            leg.base_point + (*q)(static_cast<Eigen::Index>(i)) * leg.axis.normalized();
        const Eigen::Vector3d P = pose.position + R * (leg.platform_point - design.tcp);
        const double r = 0.5 * design.shapes.link_diameter;
        if (leg.parallelogram_width > 0.0) {
          const Eigen::Vector3d h = 0.5 * leg.parallelogram_width * leg.parallelogram_axis;
          links.push_back({c + h, P + h, r, static_cast<int>(i)});
          links.push_back({c - h, P - h, r, static_cast<int>(i)});
        } else {
          links.push_back({c, P, r, static_cast<int>(i)});
        }
      }
      const double sampled = sampled_clearance(links);
      const Clearance c = machine.leg_clearance(pose);
      EXPECT_LE(c.value, sampled + 1e-9) << design.model << " " << k;
      EXPECT_GE(c.value, sampled - 1.5 / 400) << design.model << " " << k;
    }
    EXPECT_EQ(checked, 8) << design.model;
  }
}

// Thick links lose poses: every pose reachable with them is reachable without, and every pose
// lost has a clearance below min_clearance. (A platform of radius 0.1 m: the rods' platform ends
// are 0.173 m apart, 0.123 m between their surfaces; rods and cranks come closer elsewhere.)
TEST(LegChainInterference, ReachabilityNeedsMinClearance) {
  DeltaDesign thin;
  thin.platform_radius = 0.1;
  DeltaDesign thick = thin;
  thick.shapes.link_diameter = 0.05;
  thick.shapes.crank_diameter = 0.12;
  thick.shapes.min_clearance = 0.121;
  const LegChainMachine a(delta_design(thin)), b(delta_design(thick));
  auto da = a.make_data(), db = b.make_data();
  Uniform u(2);
  int lost = 0, kept = 0;
  for (int k = 0; k < 2000; ++k) {
    const Pose pose{{u(-0.6, 0.6), u(-0.6, 0.6), u(-1.4, -0.5)}, Eigen::Vector3d::Zero()};
    const bool ra = a.reachable(*da, pose), rb = b.reachable(*db, pose);
    PoseMetrics m;
    b.analyze(*db, pose, Wrench::Zero(), m);
    EXPECT_EQ(m.reachable, rb) << k;
    if (rb) {
      EXPECT_TRUE(ra) << k;
      EXPECT_GE(m.leg_clearance, 0.121) << k;
      ++kept;
    }
    if (ra && !rb) {
      EXPECT_LT(m.leg_clearance, 0.121) << k;
      ++lost;
    }
  }
  EXPECT_GT(lost, 20);
  EXPECT_GT(kept, 100);
}

// The delta's rods against a base plate (they are not jointed to it); the cranks, jointed to the
// base, are not checked against it; a thin tool under the platform is closest to the rods' ends.
TEST(LegChainInterference, SolidsSeeTheLinksNotJointedToThem) {
  DeltaDesign d;
  d.shapes.link_diameter = 0.03;
  d.shapes.crank_diameter = 0.2;  // its capsule reaches 0.1 m into the plate round its pivot
  d.shapes.bodies.base.radius = 0.5;
  d.shapes.bodies.base.z_min = -0.05;
  d.shapes.bodies.base.z_max = 0.0;
  const LegChainDesign design = delta_design(d);
  const LegChainMachine delta(design);
  int plate_closest = 0;
  for (const Pose& pose : {Pose{{0.1, 0, -0.8}, Eigen::Vector3d::Zero()},
                           Pose{{0, 0.2, -1.1}, Eigen::Vector3d::Zero()},
                           Pose{{-0.3, 0.1, -1.3}, Eigen::Vector3d::Zero()}}) {
    const auto q = delta.inverse_kinematics(pose);
    ASSERT_TRUE(q.has_value());
    const Clearance c = delta.leg_clearance(pose);
    EXPECT_GT(c.value, -0.1);  // the cranks are not checked against the plate
    // The rods' distance to the plate, from rods placed here.
    double rods = std::numeric_limits<double>::infinity();
    int nearest = -1;
    for (const Segment& s : delta_links(design, *q, pose.position, 0.2, 0.03, 0.0)) {
      if ((s.a - design.legs[static_cast<std::size_t>(s.leg)].base_point).norm() < 1e-12)
        continue;  // a crank
      const double gap = segment_prism_distance(s.a, s.b, d.shapes.bodies.base) - s.radius;
      if (gap < rods) {
        rods = gap;
        nearest = s.leg;
      }
    }
    EXPECT_LE(c.value, rods + 1e-12);
    if (c.second == kBaseBody) {
      ++plate_closest;
      EXPECT_NEAR(c.value, rods, 1e-9);
      EXPECT_EQ(c.first, nearest);
    }
  }
  EXPECT_GE(plate_closest, 1);
  // A tool of 50 mm down from the platform: the rods' platform ends, 0.044 m from its axis at
  // the height of its top face, are platform_radius - 0.025 - 0.015 = 4 mm from it.
  DeltaDesign t;
  t.shapes.link_diameter = 0.03;
  t.shapes.bodies.tool = {0.05, {0, 0, 0}, {0, 0, -0.3}};
  const LegChainMachine tooled(delta_design(t));
  for (const Pose& pose : {Pose{{0, 0, -0.9}, Eigen::Vector3d::Zero()},
                           Pose{{0.3, -0.2, -1.1}, Eigen::Vector3d::Zero()}}) {
    const Clearance c = tooled.leg_clearance(pose);
    EXPECT_EQ(c.second, kToolBody);
    EXPECT_NEAR(c.value, t.platform_radius - 0.025 - 0.015, 1e-9);
  }
}

TEST(LegChainInterference, ValidationNamesTheKey) {
  auto message = [](const LegChainDesign& design) {
    try {
      check_link_shapes(design);
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  LegChainDesign design = linear_delta_design(LinearDeltaDesign{});
  EXPECT_EQ(message(design), "");
  design.shapes.crank_diameter = 0.05;  // a linear delta has no crank
  EXPECT_NE(message(design).find("crank_diameter needs a crank"), std::string::npos);
  design.shapes.crank_diameter = 0.0;
  design.shapes.link_diameter = std::nan("");
  EXPECT_NE(message(design).find("link_diameter must be"), std::string::npos);
  design.shapes.link_diameter = 0.0;
  design.shapes.bodies.tool = {0.1, {0, 0, 0}, {0, 0, -0.2}};
  EXPECT_NE(message(design).find("give link_diameter"), std::string::npos);
  EXPECT_THROW(LegChainMachine{design}, std::invalid_argument);
}

}  // namespace
}  // namespace pkmopt
