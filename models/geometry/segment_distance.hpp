// The distance between two line segments in space, exact (to rounding) for every configuration:
// skew, crossing, parallel, collinear, touching at an end, and segments of zero length (points).
// Two capsules (a segment swept by a ball of radius r) are apart by
// segment_distance(...) - r1 - r2, negative when they intersect.
//
// The closest points minimise |p(s) - q(t)|^2 over the unit square (s, t in [0, 1]); the
// algorithm is the clamped one of Ericson, "Real-Time Collision Detection" (Morgan Kaufmann
// 2005, section 5.1.9): the unconstrained minimiser of s clamped to [0, 1], t from s and
// clamped, then s recomputed from the clamped t (always: for an unclamped t it is the same s). For
// (nearly) parallel segments (angle below 1e-7 rad, the 2x2 system ill-conditioned) the closest
// pair has an end of one segment: the best of the four ends projected on the other segment.
//
// Example:
//   const pkmopt::SegmentClosest c = pkmopt::segment_closest(a0, a1, b0, b1);
//   const double gap = c.distance - 0.04 - 0.04;  // two legs of 80 mm diameter
#pragma once

#include <Eigen/Core>

namespace pkmopt {

/// The closest points p = a0 + s (a1 - a0) and q = b0 + t (b1 - b0) of two segments.
struct SegmentClosest {
  double distance = 0.0;  ///< |p - q| (m)
  double s = 0.0;         ///< parameter of p on the first segment, 0..1
  double t = 0.0;         ///< parameter of q on the second segment, 0..1
};

/// The closest points of the segments [a0, a1] and [b0, b1].
SegmentClosest segment_closest(const Eigen::Vector3d& a0, const Eigen::Vector3d& a1,
                               const Eigen::Vector3d& b0, const Eigen::Vector3d& b1);

/// The distance between the segments [a0, a1] and [b0, b1] (m).
inline double segment_distance(const Eigen::Vector3d& a0, const Eigen::Vector3d& a1,
                               const Eigen::Vector3d& b0, const Eigen::Vector3d& b1) {
  return segment_closest(a0, a1, b0, b1).distance;
}

}  // namespace pkmopt
