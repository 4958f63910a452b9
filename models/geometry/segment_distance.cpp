#include "models/geometry/segment_distance.hpp"

#include <algorithm>
#include <limits>

namespace pkmopt {
namespace {

double clamp01(double x) { return std::clamp(x, 0.0, 1.0); }

// The parameter of the point of [o, o + d] closest to x (d != 0).
double project(const Eigen::Vector3d& x, const Eigen::Vector3d& o, const Eigen::Vector3d& d) {
  return clamp01((x - o).dot(d) / d.squaredNorm());
}

}  // namespace

SegmentClosest segment_closest(const Eigen::Vector3d& a0, const Eigen::Vector3d& a1,
                               const Eigen::Vector3d& b0, const Eigen::Vector3d& b1) {
  // Squared lengths below this (m^2) make a segment a point.
  constexpr double kPoint = 1e-30;
  const Eigen::Vector3d d1 = a1 - a0, d2 = b1 - b0, r = a0 - b0;
  const double a = d1.squaredNorm(), e = d2.squaredNorm(), f = d2.dot(r);
  double s = 0.0, t = 0.0;
  if (a <= kPoint && e <= kPoint) {
    // two points
  } else if (a <= kPoint) {
    t = clamp01(f / e);
  } else {
    const double c = d1.dot(r);
    if (e <= kPoint) {
      s = clamp01(-c / a);
    } else {
      const double b = d1.dot(d2);
      const double denom = a * e - b * b;  // >= 0; 0 for parallel segments
      if (denom > 1e-14 * a * e) {
        s = clamp01((b * f - c * e) / denom);
        t = clamp01((b * s + f) / e);
        // s again from the clamped t (for t inside [0, 1] the same s; the SIMD batch path of the
        // hexapod does the same without branches).
        s = clamp01((b * t - c) / a);
      } else {
        // (Nearly) parallel, angle below 1e-7 rad: the closest pair of parallel segments has an
        // end of one of them; take the best of the four ends projected on the other segment
        // (for a small angle theta this errs by at most length * theta / 2).
        const double candidates[4][2] = {{0.0, project(a0, b0, d2)},
                                         {1.0, project(a1, b0, d2)},
                                         {project(b0, a0, d1), 0.0},
                                         {project(b1, a0, d1), 1.0}};
        double best = std::numeric_limits<double>::infinity();
        for (const auto& st : candidates) {
          const double d = ((a0 + st[0] * d1) - (b0 + st[1] * d2)).squaredNorm();
          if (d < best) {
            best = d;
            s = st[0];
            t = st[1];
          }
        }
      }
    }
  }
  SegmentClosest out;
  out.s = s;
  out.t = t;
  out.distance = ((a0 + s * d1) - (b0 + t * d2)).norm();
  return out;
}

}  // namespace pkmopt
