// Joint layouts shared by machine models: the semi-regular hexagon of Gough–Stewart platforms
// (docs/conventions.md), also the platform of the hexaglide and of generic leg chains.
//
//   Eigen::Matrix<double, 3, 6> a = pkmopt::semi_regular_base_joints(0.6, deg_to_rad(20));
//
// Joints lie in the z = 0 plane of their frame, at the given radius (m) about its origin. The
// pair separation (rad) is the angle between the two joints of a pair.
#pragma once

#include <Eigen/Core>

namespace pkmopt {

/// Joints of a semi-regular hexagon of given radius and pair separation (rad), docs/conventions.md:
/// base: angle 120k -+ sep/2 (even/odd i); platform: 120k - 60 + sep/2 (even), 120k + 60 - sep/2
/// (odd), with k = floor(i / 2).
Eigen::Matrix<double, 3, 6> semi_regular_base_joints(double radius, double pair_separation);
Eigen::Matrix<double, 3, 6> semi_regular_platform_joints(double radius, double pair_separation);

}  // namespace pkmopt
