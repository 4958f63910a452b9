// Interference of a machine's legs: the clearance between the surfaces of their bodies.
//
// Every leg body is a capsule: a segment swept by a ball (radius r = diameter / 2). A leg is one
// capsule from joint centre to joint centre (`diameter`), or a cylinder (fixed to the base joint,
// `cylinder_diameter` and `cylinder_length` along the leg) with a rod (fixed to the platform
// joint, `rod_diameter`, from the platform joint to the cylinder's open end). A cylinder with
// flat ends is contained in the capsule over the same axis, so for such bodies the clearance is
// conservative: never larger than the true gap, smaller by at most the radius at the ends.
//
//   clearance(i, j) = min over the bodies B of leg i and B' of leg j of
//                     segment_distance(B, B') - r_B - r_B'      (m; < 0: they intersect)
//   leg_clearance   = min over the pairs i < j (the pair is reported, 1-based: "3-4").
// Bodies of one leg are not checked against each other (the rod slides in its cylinder), and a
// machine without a leg shape has leg_clearance = +inf.
//
// Example:
//   pkmopt::LegShape shape;
//   shape.diameter = 0.08;
//   const auto legs = pkmopt::leg_capsules(shape, base_joints, platform_joints);  // 3 x n each
//   const pkmopt::Clearance c = pkmopt::leg_clearance(legs);
#pragma once

#include <Eigen/Core>
#include <limits>
#include <span>
#include <string>
#include <vector>

namespace pkmopt {

/// The outer shape of a leg (every leg of a machine the same). All zero: not given.
struct LegShape {
  double diameter = 0.0;           ///< one capsule joint centre to joint centre (m)
  double cylinder_diameter = 0.0;  ///< the cylinder on the base joint (m)
  double cylinder_length = 0.0;    ///< from the base joint along the leg (m)
  double rod_diameter = 0.0;       ///< the rod from the platform joint into the cylinder (m)
  bool present() const { return diameter > 0.0 || cylinder_diameter > 0.0; }
  bool two_bodies() const { return cylinder_diameter > 0.0; }
};

/// One body of a leg.
struct Capsule {
  Eigen::Vector3d a = Eigen::Vector3d::Zero(), b = Eigen::Vector3d::Zero();  ///< axis ends (m)
  double radius = 0.0;                                                       ///< m
  int leg = 0;                                                               ///< 0-based
  bool on_base = true;      ///< jointed to the base (not checked against the base plate)
  bool on_platform = true;  ///< jointed to the platform (not checked against its plate)
};

/// Codes of the solids (models/geometry/solid_bodies.hpp) in Clearance::second (the first is the
/// leg).
inline constexpr int kPlatformBody = 1000, kBaseBody = 1001, kToolBody = 1002;

/// The smallest clearance and the pair of legs it belongs to.
struct Clearance {
  double value = std::numeric_limits<double>::infinity();  ///< m; +inf: nothing checked
  /// 0-based legs, first < second; or the leg and a solid's code
  /// (models/geometry/solid_bodies.hpp).
  int first = -1, second = -1;
};

/// Throws std::invalid_argument naming the key ("legs.diameter", ...) unless every size is finite
/// and >= 0, `diameter` and a cylinder are not both given, a cylinder has both diameter and
/// length, a rod has a cylinder, and min_clearance is finite and >= 0.
void check_leg_shape(const LegShape& shape, double min_clearance);

/// The bodies of leg `leg` running from its base-side joint `a` to its platform joint `p` (base
/// axes): writes 0 (no shape), 1 or 2 capsules to `out` and returns how many.
int leg_bodies(const LegShape& shape, const Eigen::Vector3d& a, const Eigen::Vector3d& p, int leg,
               Capsule* out);

/// The bodies of legs running from base-side joints `base` (3 x n, the actuated end) to
/// platform joints `platform` (3 x n), both in base axes.
std::vector<Capsule> leg_capsules(const LegShape& shape, const Eigen::Matrix3Xd& base,
                                  const Eigen::Matrix3Xd& platform);

/// The clearance over every pair of bodies of different legs.
Clearance leg_clearance(std::span<const Capsule> bodies);

/// True when every pair of bodies of different legs is at least `min_clearance` apart
/// (leg_clearance(bodies).value >= min_clearance, decided faster: pairs whose bounding boxes are
/// further apart than that skip the exact distance, and the first pair too close ends the test).
bool legs_apart(std::span<const Capsule> bodies, double min_clearance);

/// "3-4" (1-based legs), "3-platform", "3-base" or "3-tool" for a clearance that checked
/// something, else "".
std::string clearance_pair_text(int first, int second);

}  // namespace pkmopt
