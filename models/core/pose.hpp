// Poses, rotations and wrenches shared by every machine model.
//
// A pose is the pose of the tool centre point (TCP) in the base frame:
//   position p = (x, y, z) in metres, and orientation angles (rx, ry, rz) in radians inside
//   the code (degrees in every file a person reads), with
//       R = Rz(rz) * Ry(ry) * Rx(rx)
//   i.e. rotations about the fixed base axes, first x, then y, then z.
// A wrench w = [f; m] is a force (N) and a moment (N*m) applied to the platform at the TCP,
// both in base axes. A twist [v; omega] is the TCP velocity and the angular velocity, base axes.
//
// Everything here is templated on the scalar type T so that double, ceres::Jet and
// Eigen::AutoDiffScalar run the same code.
//
// Example:
//   pkmopt::Pose pose{{0.0, 0.0, 0.9}, pkmopt::deg_to_rad(Eigen::Vector3d(10, 0, 30))};
//   Eigen::Matrix3d R = pkmopt::rotation_zyx(pose.angles);
#pragma once

#include <Eigen/Core>
#include <cmath>
#include <numbers>

namespace pkmopt {

template <typename T>
using Vec3 = Eigen::Matrix<T, 3, 1>;
template <typename T>
using Mat3 = Eigen::Matrix<T, 3, 3>;
template <typename T>
using Vec6 = Eigen::Matrix<T, 6, 1>;
template <typename T>
using Mat6 = Eigen::Matrix<T, 6, 6>;

using Vector6d = Eigen::Matrix<double, 6, 1>;
using Matrix6d = Eigen::Matrix<double, 6, 6>;
/// A wrench [fx, fy, fz, mx, my, mz] at the TCP in base axes (N, N*m).
using Wrench = Vector6d;
/// The largest force (N) or moment (N*m) component a wrench may have: 1e9, far beyond any
/// machine tool, so that leg forces and deflections computed from it stay finite.
inline constexpr double kMaxWrenchComponent = 1e9;
/// True when every component is finite and within +-kMaxWrenchComponent.
inline bool wrench_within_limits(const Wrench& w) {
  return w.allFinite() && w.cwiseAbs().maxCoeff() <= kMaxWrenchComponent;
}

/// TCP pose: position (m, base frame) and angles (rx, ry, rz) in radians.
template <typename T>
struct PoseT {
  Vec3<T> position = Vec3<T>::Zero();
  Vec3<T> angles = Vec3<T>::Zero();
};
using Pose = PoseT<double>;

inline constexpr double kDegToRad = std::numbers::pi / 180.0;
inline constexpr double kRadToDeg = 180.0 / std::numbers::pi;

inline double deg_to_rad(double deg) { return deg * kDegToRad; }
inline double rad_to_deg(double rad) { return rad * kRadToDeg; }
inline Eigen::Vector3d deg_to_rad(const Eigen::Vector3d& deg) { return deg * kDegToRad; }
inline Eigen::Vector3d rad_to_deg(const Eigen::Vector3d& rad) { return rad * kRadToDeg; }

/// R = Rz(rz) * Ry(ry) * Rx(rx) for angles (rx, ry, rz) in radians.
template <typename T>
Mat3<T> rotation_zyx(const Vec3<T>& angles) {
  using std::cos;
  using std::sin;
  const T cx = cos(angles(0)), sx = sin(angles(0));
  const T cy = cos(angles(1)), sy = sin(angles(1));
  const T cz = cos(angles(2)), sz = sin(angles(2));
  Mat3<T> R;
  R(0, 0) = cz * cy;
  R(0, 1) = cz * sy * sx - sz * cx;
  R(0, 2) = cz * sy * cx + sz * sx;
  R(1, 0) = sz * cy;
  R(1, 1) = sz * sy * sx + cz * cx;
  R(1, 2) = sz * sy * cx - cz * sx;
  R(2, 0) = -sy;
  R(2, 1) = cy * sx;
  R(2, 2) = cy * cx;
  return R;
}

/// The angles (rx, ry, rz) in radians of a rotation matrix, R = Rz Ry Rx, with
/// ry in [-pi/2, pi/2] and rx, rz in (-pi, pi]. At ry = +-pi/2 (gimbal lock) rx is set to 0.
Eigen::Vector3d angles_from_rotation(const Eigen::Matrix3d& R);

/// The rotation exp([omega]x) for a rotation vector omega (rad), by Rodrigues' formula.
Eigen::Matrix3d rotation_from_vector(const Eigen::Vector3d& omega);

/// The rotation vector omega with exp([omega]x) = R (the inverse of rotation_from_vector).
Eigen::Vector3d rotation_vector(const Eigen::Matrix3d& R);

}  // namespace pkmopt
