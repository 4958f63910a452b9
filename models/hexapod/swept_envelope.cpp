#include "models/hexapod/swept_envelope.hpp"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_2_algorithms.h>
#include <CGAL/convex_hull_2.h>

#include <cmath>
#include <iterator>
#include <numbers>

#include "models/workspace/workspace.hpp"

namespace pkmopt {

namespace {

constexpr int kSides = 32;

// The outline points of a prism (its parent frame): the circumscribed 32-gon of a disc or the
// polygon's vertices, at both end heights.
void add_prism(const ConvexPrism& p, const Eigen::Matrix3d& R, const Eigen::Vector3d& t,
               std::vector<Eigen::Vector3d>& out) {
  std::vector<Eigen::Vector2d> outline = p.polygon;
  if (outline.empty()) {
    const double r = p.radius / std::cos(std::numbers::pi / kSides);
    for (int k = 0; k < kSides; ++k) {
      const double a = 2.0 * std::numbers::pi * k / kSides;
      outline.emplace_back(r * std::cos(a), r * std::sin(a));
    }
  }
  for (const double z : {p.z_min, p.z_max})
    for (const Eigen::Vector2d& v : outline)
      out.push_back(t + R * (p.origin + p.axes * Eigen::Vector3d(v.x(), v.y(), z)));
}

}  // namespace

void solid_outline_points(const MachineBodies& bodies, const Eigen::Matrix3d& R,
                          const Eigen::Vector3d& origin, std::vector<Eigen::Vector3d>& out) {
  if (bodies.base.present())
    add_prism(bodies.base, Eigen::Matrix3d::Identity(), Eigen::Vector3d::Zero(), out);
  if (bodies.platform.present()) add_prism(bodies.platform, R, origin, out);
  if (bodies.tool.present()) add_prism(bodies.tool.prism(), R, origin, out);
}

std::vector<Eigen::Vector3d> swept_points(const Hexapod& hexapod, const std::vector<Pose>& poses) {
  const HexapodDesign& d = hexapod.design();
  std::vector<Eigen::Vector3d> out;
  for (int i = 0; i < 6; ++i) out.push_back(d.base_joints.col(i));
  if (d.bodies.base.present())
    add_prism(d.bodies.base, Eigen::Matrix3d::Identity(), Eigen::Vector3d::Zero(), out);
  const ConvexPrism tool = d.bodies.tool.present() ? d.bodies.tool.prism() : ConvexPrism{};
  for (const Pose& pose : poses) {
    const Eigen::Matrix3d R = rotation_zyx<double>(pose.angles);
    const Eigen::Vector3d origin = pose.position - R * d.tcp;
    for (int i = 0; i < 6; ++i) out.push_back(origin + R * d.platform_joints.col(i));
    if (d.bodies.platform.present()) add_prism(d.bodies.platform, R, origin, out);
    if (tool.present()) add_prism(tool, R, origin, out);
  }
  return out;
}

SweptEnvelope swept_envelope(const Hexapod& hexapod, const std::vector<Pose>& poses) {
  const std::vector<Eigen::Vector3d> points = swept_points(hexapod, poses);
  return {convex_hull_volume(points), footprint_area(points)};
}

}  // namespace pkmopt
