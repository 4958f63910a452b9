// Shared by problems/design/hexapod_design.cpp (the aggregate formulation, the designs) and
// problems/design/hexapod_design_smooth.cpp (the smooth formulation and its gradient). Not part
// of the public interface: problems/design/hexapod_design.hpp is.
#pragma once

#include <Eigen/Core>
#include <cmath>

#include "models/core/pose.hpp"

namespace pkmopt::hexapod_design_detail {

// Semi-regular joints (docs/conventions.md) for any scalar type.
template <typename T>
Eigen::Matrix<T, 3, 6> semi_regular_joints(const T& radius, const T& separation, bool platform) {
  using std::cos;
  using std::sin;
  Eigen::Matrix<T, 3, 6> joints;
  for (int i = 0; i < 6; ++i) {
    const double k120 = 120.0 * kDegToRad * (i / 2);
    const bool even = i % 2 == 0;
    T angle;
    if (!platform) {
      angle = even ? T(k120) - separation / 2.0 : T(k120) + separation / 2.0;
    } else {
      angle = even ? T(k120 - 60.0 * kDegToRad) + separation / 2.0
                   : T(k120 + 60.0 * kDegToRad) - separation / 2.0;
    }
    joints(0, i) = radius * cos(angle);
    joints(1, i) = radius * sin(angle);
    joints(2, i) = T(0.0);
  }
  return joints;
}

}  // namespace pkmopt::hexapod_design_detail
