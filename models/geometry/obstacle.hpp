// Obstacles at the work: boxes (the workpiece, its fixture and clamps, a neighbouring part) the
// machine must keep out of, and how deep a segment of the machine's drawing goes into one.
//
// The depth of a point p in a box [lo, hi] is d(p) = min over the axes a of
// min(p_a - lo_a, hi_a - p_a): > 0 inside (the distance to the nearest face), <= 0 outside. Along
// a segment p(t) = a + t (b - a), d is the minimum of six affine functions of t, so it is concave
// and its maximum over [0, 1] lies at an end or where two of the six cross: intrusion() takes the
// largest d over those candidates, exactly.
//
// Example:
//   pkmopt::ObstacleBox fixture{{-0.2, -0.2, 0.0}, {0.2, 0.2, 0.1}};
//   const double depth = pkmopt::intrusion(fixture, a, b);  // m, > 0: the segment goes in
#pragma once

#include <Eigen/Core>

namespace pkmopt {

struct ObstacleBox {
  Eigen::Vector3d min = Eigen::Vector3d::Zero();  ///< m
  Eigen::Vector3d max = Eigen::Vector3d::Zero();  ///< m
};

/// The depth of point p in the box (m; > 0 inside, <= 0 outside).
double depth(const ObstacleBox& box, const Eigen::Vector3d& p);

/// The largest depth of the segment a-b in the box (m; > 0 when the segment enters it).
double intrusion(const ObstacleBox& box, const Eigen::Vector3d& a, const Eigen::Vector3d& b);

/// Throws std::invalid_argument unless min < max on every axis and both are finite
/// ("obstacle: ...").
void check_obstacle(const ObstacleBox& box);

}  // namespace pkmopt
