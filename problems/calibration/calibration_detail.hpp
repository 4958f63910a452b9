// Internal helpers shared by the calibration sources (problems/calibration/calibration*.cpp): pose
// vectors, free-parameter indices, name lists and the identification with its right singular
// vectors.
#pragma once

#include <Eigen/Core>
#include <array>
#include <string>
#include <vector>

#include "problems/calibration/calibration.hpp"

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

/// The noise groups of a fit (problems/calibration/calibration_noise.cpp): 0 instrument position,
/// 1 instrument orientation, 2 actuator readings.
struct NoiseGroups {
  Eigen::Vector3d omega = Eigen::Vector3d::Zero();       ///< sum of squared whitened residuals
  Eigen::Vector3d redundancy = Eigen::Vector3d::Zero();  ///< sum of 1 - H_ii over the rows
  Eigen::Vector3i rows = Eigen::Vector3i::Zero();
  std::array<std::vector<double>, 3> residuals;  ///< the whitened residuals of each group
  /// T_gh = sum over rows i of g and j of h of R_ij^2, R = I - H: E[omega_g] = sum_h T_gh s_h^2
  /// when group h's errors have variance s_h^2 in whitened units (Helmert's variance-component
  /// equations); row and column sums are the redundancies.
  Eigen::Matrix3d T = Eigen::Matrix3d::Zero();
};

/// The noise groups of the poses in `active` at the parameters x and pose vectors `poses`
/// (whitened with options' sigmas; the free parameters of options.free).
NoiseGroups noise_groups(const CalibrationVector& x, const Eigen::Vector3d& tcp,
                         const std::vector<CalibrationMeasurement>& measurements,
                         const std::vector<Vec6<double>>& poses, const std::vector<int>& active,
                         const CalibrationOptions& options);

/// The factors s_g (sqrt of the variance factors) that make the groups' sigmas right: the
/// solution of T s^2 = omega over the groups marked resolved, the others held at 1. A group whose
/// variance factor the data do not determine (relative standard deviation sqrt(2 (T^-1)_gg)
/// above its max_relative_sd, or a factor <= 0) is marked unresolved and held. `relative_sd`
/// receives each resolved group's relative standard deviation of s_g^2 (inf for the held ones).
Eigen::Vector3d helmert_factors(const NoiseGroups& groups, std::array<bool, 3>& resolved,
                                const Eigen::Vector3d& max_relative_sd,
                                Eigen::Vector3d* relative_sd = nullptr);

/// The groups with omega_g replaced by a robust value, n_g median(r_i^2) / 0.4549 (the median of
/// chi^2 with one degree of freedom): insensitive to a minority of gross errors, for the
/// variance components before outliers are known.
NoiseGroups robust_noise_groups(const NoiseGroups& groups);

}  // namespace pkmopt::detail
