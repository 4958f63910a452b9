// A box of poses, the region a proof about the Jacobian covers (JacobianEnclosure,
// models/core/capabilities.hpp; models/workspace/mode_certificate.hpp), and the interval
// enclosure of its rotations.
//
// TCP positions p in [position_lo, position_hi] (m, base frame) and rotations
//     R = R0 * Rot(theta, u(phi)) * Rz(gamma),   u(phi) = (cos phi, sin phi, 0),
// for theta, phi, gamma in their intervals (rad): a tilt theta of the tool axis away from R0's,
// toward the azimuth phi, and a turn gamma about the tilted axis. The orientation sets of
// models/workspace/workspace.hpp are such boxes (theta in [0, tilt], phi in [0, 2 pi], gamma in
// [-yaw, yaw]); they are sampled the same way there. With
//     Rot(theta, u) = cos theta I + sin theta [u]x + (1 - cos theta) u u^T
//                   = [ ct + (1-ct) c^2   (1-ct) c s         st s ]
//                     [ (1-ct) c s        ct + (1-ct) s^2   -st c ]
//                     [ -st s             st c               ct   ]
// (ct = cos theta, st = sin theta, c = cos phi, s = sin phi).
//
// Example:
//   PoseBox box;
//   box.position_lo = {-0.1, -0.1, 0.8};  box.position_hi = {0.1, 0.1, 1.0};
//   box.theta = {0.0, 0.35};  box.phi = {0.0, 2.0 * std::numbers::pi};
//   const IntervalRotation R = enclose_rotation(box);  // every rotation of the box inside
#pragma once

#include <Eigen/Core>
#include <array>
#include <cmath>
#include <type_traits>

#include "models/core/interval.hpp"

namespace pkmopt {

struct PoseBox {
  Eigen::Vector3d position_lo = Eigen::Vector3d::Zero();
  Eigen::Vector3d position_hi = Eigen::Vector3d::Zero();
  Eigen::Matrix3d R0 = Eigen::Matrix3d::Identity();
  Interval theta{0.0, 0.0};
  Interval phi{0.0, 0.0};
  Interval gamma{0.0, 0.0};
};

using IntervalRotation = std::array<std::array<Interval, 3>, 3>;

/// The rotation of a box at theta, phi, gamma (the formula above, in doubles).
Eigen::Matrix3d box_rotation(const Eigen::Matrix3d& R0, double theta, double phi, double gamma);

/// The rotation R0 Rot(theta, u(phi)) Rz(gamma) for any scalar with +, -, *, sin and cos
/// (double, Interval, IntervalGradient), entry by entry.
template <class T>
std::array<std::array<T, 3>, 3> box_rotation_of(const Eigen::Matrix3d& R0, const T& theta,
                                                const T& phi, const T& gamma) {
  using std::cos, std::sin;
  auto sq = [](const T& x) -> T {
    if constexpr (std::is_same_v<T, double>)
      return x * x;
    else
      return square(x);  // tighter than x * x for intervals about 0
  };
  const T ct = cos(theta), st = sin(theta), c = cos(phi), s = sin(phi);
  const T cg = cos(gamma), sg = sin(gamma);
  const T vt = T(1.0) - ct;
  const T A[3][3] = {{ct + vt * sq(c), vt * c * s, st * s},
                     {vt * c * s, ct + vt * sq(s), -(st * c)},
                     {-(st * s), st * c, ct}};
  // A Rz(gamma): columns (a0 cg + a1 sg, a1 cg - a0 sg, a2).
  T B[3][3];
  for (int r = 0; r < 3; ++r) {
    B[r][0] = A[r][0] * cg + A[r][1] * sg;
    B[r][1] = A[r][1] * cg - A[r][0] * sg;
    B[r][2] = A[r][2];
  }
  std::array<std::array<T, 3>, 3> R;
  for (int r = 0; r < 3; ++r)
    for (int k = 0; k < 3; ++k)
      R[r][k] = T(R0(r, 0)) * B[0][k] + T(R0(r, 1)) * B[1][k] + T(R0(r, 2)) * B[2][k];
  return R;
}

/// An interval matrix holding every rotation of the box, entry by entry.
inline IntervalRotation enclose_rotation(const PoseBox& box) {
  return box_rotation_of<Interval>(box.R0, box.theta, box.phi, box.gamma);
}

}  // namespace pkmopt
