// Solid bodies beside the legs for the interference check: the platform plate, the base plate
// and the tool (spindle), each a convex prism: a convex cross-section (a disc or a convex
// polygon) in its local x-y plane, extruded over [z_min, z_max] along its local z.
//
//   platform  in the platform frame (moves with the pose), local axes = the platform axes;
//   base      in the base frame, local axes = the base axes;
//   tool      a cylinder of `diameter` from `from` to `to` (platform frame).
//
// Which leg bodies each solid is checked against (a body is not checked against what it is
// jointed to: they touch at the joint, whose limits say how far they may turn):
//   platform  leg bodies not jointed to the platform (a hexapod leg's cylinder; a crank);
//   base      leg bodies not jointed to the base (a hexapod leg's rod; a delta's rods, a strut
//             on a carriage);
//   tool      every leg body.
// A one-capsule hexapod leg is jointed to both plates and is checked against the tool only.
//
// Distance: the distance from a point to a prism is exact, sqrt(d_xy^2 + d_z^2) with d_xy the
// distance of (x, y) to the cross-section and d_z the distance of z to [z_min, z_max] (a
// Cartesian product of convex sets). Along a leg's axis it is a convex function of the segment
// parameter; golden-section search finds its minimum to 1e-9 of the segment length. The
// clearance of a capsule (radius r) and a prism is that minimum - r: exact while they are apart;
// when the axis enters the prism it is -r (the depth is not measured further).
//
// Example:
//   pkmopt::MachineBodies bodies;                               // a spindle of 120 mm
//   bodies.tool = {0.12, {0, 0, 0}, {0, 0, -0.3}};
//   pkmopt::Clearance c = pkmopt::leg_clearance(legs);          // the legs' own, then
//   pkmopt::body_clearance(legs, bodies, R, origin, c);         // R, origin: platform frame
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <span>
#include <string>
#include <vector>

#include "models/geometry/leg_interference.hpp"

namespace pkmopt {

/// A convex prism in a local frame: points origin + axes * (x, y, z) with (x, y) in the
/// cross-section and z in [z_min, z_max]. Not present when z_max <= z_min.
struct ConvexPrism {
  double radius = 0.0;                   ///< a disc about the local z axis (m), or ...
  std::vector<Eigen::Vector2d> polygon;  ///< ... a convex polygon (m), either orientation
  double z_min = 0.0, z_max = 0.0;       ///< m
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();    ///< in the parent frame (m)
  Eigen::Matrix3d axes = Eigen::Matrix3d::Identity();  ///< columns: local x, y, z
  bool present() const { return z_max > z_min; }
};

/// A cylinder of radius `radius` with its axis from `from` to `to`.
ConvexPrism cylinder_prism(const Eigen::Vector3d& from, const Eigen::Vector3d& to, double radius);

/// The tool (spindle) as a cylinder, platform frame. Not present when diameter is 0.
struct ToolBody {
  double diameter = 0.0;                           ///< m
  Eigen::Vector3d from = Eigen::Vector3d::Zero();  ///< axis ends (m)
  Eigen::Vector3d to = Eigen::Vector3d::Zero();
  bool present() const { return diameter > 0.0; }
  ConvexPrism prism() const { return cylinder_prism(from, to, 0.5 * diameter); }
};

/// The solids of a machine file's `bodies` section.
struct MachineBodies {
  ConvexPrism platform;  ///< platform frame
  ConvexPrism base;      ///< base frame
  ToolBody tool;
  bool present() const { return platform.present() || base.present() || tool.present(); }
};

/// Throws std::invalid_argument naming the key (`bodies.platform.polygon`, ...) unless every
/// present solid has exactly one cross-section, a finite radius > 0 or a convex polygon of at
/// least 3 distinct vertices with non-zero area, and finite coordinates.
void check_machine_bodies(const MachineBodies& bodies);

/// Throws std::invalid_argument when a plate would be checked against nothing: the platform
/// plate needs leg bodies on the base side (not jointed to the platform), the base plate leg
/// bodies on the platform side; `shape_keys` says which keys give them.
void check_solids_have_leg_bodies(const MachineBodies& bodies, bool base_side_bodies,
                                  bool platform_side_bodies, const std::string& shape_keys);

/// A hexapod's solids: check_machine_bodies, a leg shape to check them against, and leg bodies
/// each plate can see (a cylinder for the platform plate, a rod for the base plate).
void check_hexapod_bodies(const LegShape& shape, const MachineBodies& bodies);

/// Distance (m) from the segment [a, b] to the prism, both in the prism's parent frame.
double segment_prism_distance(const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                              const ConvexPrism& prism);

/// Lowers `best` to the smallest clearance between the leg bodies and the solids (by the rule of
/// the file comment), the platform frame at (R, origin) in the base frame. Pairs whose lower
/// bound (distance to the solid's slab of heights, or to a ball holding it) cannot beat `best`
/// skip the exact distance.
void body_clearance(std::span<const Capsule> legs, const MachineBodies& bodies,
                    const Eigen::Matrix3d& R, const Eigen::Vector3d& origin, Clearance& best);

/// True when every leg body is at least `min_clearance` from the solids it is checked against
/// (decided faster: bounding spheres skip the exact distance, the first one too close ends it).
bool bodies_apart(std::span<const Capsule> legs, const MachineBodies& bodies,
                  const Eigen::Matrix3d& R, const Eigen::Vector3d& origin, double min_clearance);

}  // namespace pkmopt
