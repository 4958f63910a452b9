// Internal helpers shared by the calibration sources (problems/calibration*.cpp): pose vectors,
// free-parameter indices, name lists and the identification with its right singular vectors.
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "problems/calibration.hpp"

namespace pkmopt::detail {

inline Vec6<double> pose_vector(const Pose& pose) {
  Vec6<double> v;
  v << pose.position, pose.angles;
  return v;
}

inline Pose pose_from_vector(const Vec6<double>& v) { return Pose{v.head<3>(), v.tail<3>()}; }

inline std::vector<int> free_indices_of(const CalibrationMask& free) {
  std::vector<int> indices;
  for (int i = 0; i < kCalibrationParameters; ++i) {
    if (free[static_cast<std::size_t>(i)]) indices.push_back(i);
  }
  return indices;
}

inline std::string join_names(const std::vector<std::string>& names) {
  std::string text;
  for (const auto& name : names) {
    if (!text.empty()) text.append(", ");
    text.append(name);
  }
  return text;
}

struct IdentificationWithBasis {
  Identification identification;
  Eigen::MatrixXd V;  ///< right singular vectors (n x n), columns in singular-value order
};

// The identification of the free parameters from the given poses with its right singular vectors.
// rank_only: singular values and rank, plus the null space when rank deficient (no V, no
// scaled indices otherwise).
IdentificationWithBasis identify_with_basis(const CalibrationVector& x, const Eigen::Vector3d& tcp,
                                            const std::vector<CalibrationMeasurement>& measurements,
                                            const std::vector<Pose>& tcp_poses,
                                            const CalibrationOptions& options,
                                            bool rank_only = false);

}  // namespace pkmopt::detail
