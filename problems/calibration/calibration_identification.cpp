// Identification of the calibration parameters: the reduced identification Jacobian (pose
// unknowns eliminated), its rank, null space and observability indices O1..O4, and the choice of
// the gauge-fixing coordinates.
#include <Eigen/QR>
#include <Eigen/SVD>
#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "problems/calibration/calibration.hpp"
#include "problems/calibration/calibration_detail.hpp"

namespace pkmopt {
namespace {

using detail::free_indices_of;
using detail::IdentificationWithBasis;
using detail::identify_with_basis;

bool is_joint_coordinate(int index) {
  return index < kCalibrationMachineParameters && index % kCalibrationLegParameters < 6;
}

}  // namespace

// ---- Identification ---------------------------------------------------------------------------

Eigen::MatrixXd reduced_identification_rows(const CalibrationVector& x, const Eigen::Vector3d& tcp,
                                            const CalibrationMeasurement& measurement,
                                            const Pose& tcp_pose,
                                            const std::vector<int>& free_indices,
                                            const CalibrationOptions& options) {
  const Eigen::Matrix<double, 12, 66> full =
      calibration_jacobian(x, tcp, measurement, tcp_pose, options);
  const Eigen::Matrix<double, 12, kCalibrationParameters> A = full.leftCols<60>();
  const Eigen::Matrix<double, 12, 6> d_pose = full.rightCols<6>();
  // Rows orthogonal to the pose directions: the last 6 columns of Q in B = Q R.
  const Eigen::HouseholderQR<Eigen::Matrix<double, 12, 6>> qr(d_pose);
  const Eigen::Matrix<double, 12, 12> Q = qr.householderQ();
  const Eigen::Matrix<double, 6, 12> complement = Q.rightCols<6>().transpose();
  Eigen::MatrixXd rows(6, static_cast<Eigen::Index>(free_indices.size()));
  for (std::size_t j = 0; j < free_indices.size(); ++j) {
    rows.col(static_cast<Eigen::Index>(j)) = complement * A.col(free_indices[j]);
  }
  return rows;
}

namespace {

// O1..O4 of singular values s (descending) from num_poses poses; zero/inf when rank deficient.
ObservabilityIndices observability_indices(const Eigen::VectorXd& s, int rank, int num_poses) {
  ObservabilityIndices indices;
  indices.singular_values = s;
  const Eigen::Index n = s.size();
  if (n == 0) return indices;
  if (rank < n) {
    indices.O2 = std::numeric_limits<double>::infinity();
    return indices;
  }
  const double s_max = s(0), s_min = s(n - 1);
  indices.O1 = std::exp(s.array().log().mean()) / std::sqrt(static_cast<double>(num_poses));
  indices.O2 = s_max / s_min;
  indices.O3 = s_min;
  indices.O4 = s_min * s_min / s_max;
  return indices;
}

// JacobiSVD (column-pivoting QR first, then one-sided Jacobi on the n x n factor): accurate
// for the small singular values, and it runs no threaded matrix products.
Eigen::VectorXd padded_singular_values(const Eigen::JacobiSVD<Eigen::MatrixXd>& svd,
                                       Eigen::Index n) {
  Eigen::VectorXd s = Eigen::VectorXd::Zero(n);
  s.head(svd.singularValues().size()) = svd.singularValues();
  return s;
}

IdentificationWithBasis identification_from_rows(const Eigen::MatrixXd& J,
                                                 const std::vector<int>& free_indices,
                                                 int num_poses, const CalibrationOptions& options,
                                                 bool rank_only = false) {
  IdentificationWithBasis out;
  Identification& id = out.identification;
  id.free_indices = free_indices;
  id.num_poses = num_poses;
  const Eigen::Index n = J.cols();
  if (n == 0) return out;
  Eigen::JacobiSVD<Eigen::MatrixXd> svd(J, rank_only ? 0 : Eigen::ComputeFullV);
  const Eigen::VectorXd s = padded_singular_values(svd, n);
  id.singular_values = s;
  id.rank = 0;
  for (Eigen::Index i = 0; i < n; ++i) {
    if (s(i) > options.rank_tolerance * s(0) && s(i) > 0.0) ++id.rank;
  }
  const ObservabilityIndices indices = observability_indices(s, id.rank, num_poses);
  id.O1 = indices.O1;
  id.O2 = indices.O2;
  id.O3 = indices.O3;
  id.O4 = indices.O4;
  if (rank_only) {
    if (id.rank == n) return out;
    svd.compute(J, Eigen::ComputeFullV);  // the null space names the parameters
  }
  out.V = svd.matrixV();

  // The same with each column times the parameter's a-priori uncertainty (dimensionless).
  id.column_scale.resize(n);
  for (Eigen::Index j = 0; j < n; ++j) {
    id.column_scale(j) = options.parameter_scale(free_indices[static_cast<std::size_t>(j)]);
  }
  const Eigen::JacobiSVD<Eigen::MatrixXd> scaled_svd(J * id.column_scale.asDiagonal());
  id.scaled = observability_indices(padded_singular_values(scaled_svd, n), id.rank, num_poses);

  if (id.rank < n) {
    id.null_space = out.V.rightCols(n - id.rank);
    for (Eigen::Index j = 0; j < n; ++j) {
      if (id.null_space.row(j).norm() > 0.05) {
        id.unidentifiable.push_back(calibration_parameter_name(free_indices[j]));
      }
    }
  }
  return out;
}

// The stacked reduced identification rows J_id (6N x n_free).
Eigen::MatrixXd identification_jacobian(const CalibrationVector& x, const Eigen::Vector3d& tcp,
                                        const std::vector<CalibrationMeasurement>& measurements,
                                        const std::vector<Pose>& tcp_poses,
                                        const std::vector<int>& free_indices,
                                        const CalibrationOptions& options) {
  const auto num_poses = static_cast<Eigen::Index>(measurements.size());
  Eigen::MatrixXd J(6 * num_poses, static_cast<Eigen::Index>(free_indices.size()));
  for (Eigen::Index k = 0; k < num_poses; ++k) {
    J.middleRows(6 * k, 6) =
        reduced_identification_rows(x, tcp, measurements[static_cast<std::size_t>(k)],
                                    tcp_poses[static_cast<std::size_t>(k)], free_indices, options);
  }
  return J;
}

}  // namespace

IdentificationWithBasis detail::identify_with_basis(
    const CalibrationVector& x, const Eigen::Vector3d& tcp,
    const std::vector<CalibrationMeasurement>& measurements, const std::vector<Pose>& tcp_poses,
    const CalibrationOptions& options, bool rank_only) {
  const std::vector<int> free_indices = free_indices_of(options.free);
  return identification_from_rows(
      identification_jacobian(x, tcp, measurements, tcp_poses, free_indices, options), free_indices,
      static_cast<int>(measurements.size()), options, rank_only);
}

Identification identify(const CalibrationVector& x, const Eigen::Vector3d& tcp,
                        const std::vector<CalibrationMeasurement>& measurements,
                        const std::vector<Pose>& tcp_poses, const CalibrationOptions& options) {
  return identify_with_basis(x, tcp, measurements, tcp_poses, options).identification;
}

std::vector<int> choose_gauge_fixing(const CalibrationVector& x, const Eigen::Vector3d& tcp,
                                     const std::vector<CalibrationMeasurement>& measurements,
                                     const CalibrationOptions& options) {
  int frames = 0;
  auto any_free = [&](int start) {
    for (int i = start; i < start + 6; ++i) {
      if (options.free[static_cast<std::size_t>(i)]) return true;
    }
    return false;
  };
  if (any_free(kCalibrationInstrumentIndex)) frames += 6;
  if (any_free(kCalibrationTargetIndex)) frames += 6;
  if (frames == 0) return {};
  std::vector<Pose> poses;
  for (const auto& m : measurements) poses.push_back(tcp_pose_from_measurement(x, m.pose));
  const Identification id = identify(x, tcp, measurements, poses, options);
  if (id.null_space.cols() == 0) return {};
  std::vector<Eigen::Index> candidate_rows;
  for (std::size_t j = 0; j < id.free_indices.size(); ++j) {
    if (is_joint_coordinate(id.free_indices[j])) {
      candidate_rows.push_back(static_cast<Eigen::Index>(j));
    }
  }
  Eigen::MatrixXd M(id.null_space.cols(), static_cast<Eigen::Index>(candidate_rows.size()));
  for (std::size_t c = 0; c < candidate_rows.size(); ++c) {
    M.col(static_cast<Eigen::Index>(c)) = id.null_space.row(candidate_rows[c]).transpose();
  }
  const Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(M);
  const Eigen::Index count =
      std::min<Eigen::Index>({static_cast<Eigen::Index>(frames), M.rows(), M.cols()});
  std::vector<int> fixed;
  for (Eigen::Index c = 0; c < count; ++c) {
    const Eigen::Index column = qr.colsPermutation().indices()(c);
    fixed.push_back(id.free_indices[static_cast<std::size_t>(candidate_rows[column])]);
  }
  std::sort(fixed.begin(), fixed.end());
  return fixed;
}

}  // namespace pkmopt
