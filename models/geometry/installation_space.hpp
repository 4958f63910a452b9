// The space a whole machine must fit in (a box or a vertical cylinder, base frame), and how far a
// body sticks out of it.
//
// Bodies are capsules (models/geometry/leg_interference.hpp; a point is a capsule of radius 0). The
// regions are convex, so a capsule is inside exactly when both balls at its ends are:
//   box       excess(ball c, r) = max over axes of (min_a + r - c_a, c_a + r - max_a)
//   cylinder  excess(ball c, r) = max(|c_xy - centre| + r - radius, z_min + r - c_z,
//                                     c_z + r - z_max)
//   excess(capsule) = max of its two end balls' excess      (m; <= 0 inside)
//
// Example:
//   pkmopt::InstallationSpace space;
//   space.kind = pkmopt::InstallationSpace::Kind::kBox;
//   space.min = {-0.8, -0.8, 0.0};
//   space.max = {0.8, 0.8, 1.6};
//   const double e = space.excess(capsule);  // > 0: sticks out by e metres
#pragma once

#include <Eigen/Core>

#include "models/geometry/leg_interference.hpp"

namespace pkmopt {

struct InstallationSpace {
  enum class Kind { kNone, kBox, kCylinder };
  Kind kind = Kind::kNone;
  Eigen::Vector3d min = Eigen::Vector3d::Zero(), max = Eigen::Vector3d::Zero();  ///< box (m)
  Eigen::Vector2d centre = Eigen::Vector2d::Zero();  ///< cylinder axis (x, y) (m)
  double radius = 0.0, z_min = 0.0, z_max = 0.0;     ///< cylinder (m)

  bool present() const { return kind != Kind::kNone; }
  /// How far a ball of radius r about c sticks out (m; <= 0 inside).
  double excess(const Eigen::Vector3d& c, double r) const;
  /// How far a capsule sticks out (m; <= 0 inside).
  double excess(const Capsule& body) const {
    const double a = excess(body.a, body.radius), b = excess(body.b, body.radius);
    return a > b ? a : b;
  }
};

/// Throws std::invalid_argument unless the region is finite and not empty ("installation_space:
/// ...").
void check_installation_space(const InstallationSpace& space);

}  // namespace pkmopt
