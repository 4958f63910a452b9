// D-optimal selection of calibration poses: greedy start, then Fedorov exchange on
// det(J_id^T J_id) of the reduced identification rows.
#include <fmt/format.h>

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "problems/calibration/calibration.hpp"
#include "problems/calibration/calibration_detail.hpp"

namespace pkmopt {
namespace {

using detail::free_indices_of;
using detail::join_names;

}  // namespace

// ---- Pose selection ---------------------------------------------------------------------------

PoseSelection select_calibration_poses(const CalibrationVector& x, const Eigen::Vector3d& tcp,
                                       const std::vector<Pose>& candidates, int count,
                                       const CalibrationOptions& options) {
  const std::vector<int> free_indices = free_indices_of(options.free);
  const int n = static_cast<int>(free_indices.size());
  const int num_candidates = static_cast<int>(candidates.size());
  if (!x.allFinite())
    throw CalibrationError(
        "the machine's parameters are not all finite numbers (a zero length of nan or inf?)");
  if (count < 1 || 6 * count < n + 1) {
    throw CalibrationError(fmt::format(
        "--count {} poses give {} equations; the {} free parameters need at least {} poses", count,
        6 * count, n, n / 6 + 1));
  }
  if (count > num_candidates) {
    throw CalibrationError(fmt::format("--count {} is more than the {} usable candidate poses",
                                       count, num_candidates));
  }
  // Perfect measurements of each candidate on the machine x.
  std::vector<CalibrationMeasurement> measurements(static_cast<std::size_t>(num_candidates));
  std::vector<Eigen::MatrixXd> rows(static_cast<std::size_t>(num_candidates));
  Eigen::MatrixXd total = Eigen::MatrixXd::Zero(n, n);
  for (int c = 0; c < num_candidates; ++c) {
    const Pose& pose = candidates[static_cast<std::size_t>(c)];
    auto& m = measurements[static_cast<std::size_t>(c)];
    m.pose = measurement_from_tcp_pose(x, pose);
    Eigen::Matrix<double, 3, 6> platform_rel;
    for (int i = 0; i < 6; ++i) {
      platform_rel.col(i) = x.segment<3>(kCalibrationLegParameters * i + 3) - tcp;
    }
    Eigen::Matrix<double, 3, 6> base;
    for (int i = 0; i < 6; ++i) base.col(i) = x.segment<3>(kCalibrationLegParameters * i);
    Vec6<double> lengths;
    hexapod_legs<double>(base, platform_rel, pose.position, pose.angles, &lengths);
    for (int i = 0; i < 6; ++i) {
      const int leg = kCalibrationLegParameters * i;
      m.stroke(i) = (lengths(i) - x(leg + 6)) / (1.0 + x(leg + 7));
    }
    rows[static_cast<std::size_t>(c)] =
        reduced_identification_rows(x, tcp, m, pose, free_indices, options);
    total += rows[static_cast<std::size_t>(c)].transpose() * rows[static_cast<std::size_t>(c)];
  }
  const double regularisation = 1e-12 * total.trace() / std::max(1, n);
  auto log_det = [](const Eigen::MatrixXd& M) {
    const Eigen::LLT<Eigen::MatrixXd> llt(M);
    if (llt.info() != Eigen::Success) return -std::numeric_limits<double>::infinity();
    return 2.0 * llt.matrixL().toDenseMatrix().diagonal().array().log().sum();
  };
  // Gain in log det from adding the rows A to a matrix with inverse M_inverse (determinant lemma).
  auto gain = [&](const Eigen::MatrixXd& M_inverse, const Eigen::MatrixXd& A) {
    const Eigen::MatrixXd S = Eigen::MatrixXd::Identity(6, 6) + A * M_inverse * A.transpose();
    return log_det(S);
  };

  PoseSelection selection;
  std::vector<bool> chosen(static_cast<std::size_t>(num_candidates), false);
  Eigen::MatrixXd M = regularisation * Eigen::MatrixXd::Identity(n, n);
  for (int step = 0; step < count; ++step) {
    const Eigen::MatrixXd M_inverse = M.ldlt().solve(Eigen::MatrixXd::Identity(n, n));
    int best = -1;
    double best_gain = -std::numeric_limits<double>::infinity();
    for (int c = 0; c < num_candidates; ++c) {
      if (chosen[static_cast<std::size_t>(c)]) continue;
      const double g = gain(M_inverse, rows[static_cast<std::size_t>(c)]);
      if (g > best_gain) {
        best_gain = g;
        best = c;
      }
    }
    if (best < 0)
      throw CalibrationError(
          "no candidate pose gives a finite information gain: the sigmas or the machine's "
          "parameters are out of range");
    chosen[static_cast<std::size_t>(best)] = true;
    selection.selected.push_back(best);
    M += rows[static_cast<std::size_t>(best)].transpose() * rows[static_cast<std::size_t>(best)];
  }
  // Fedorov exchange: swap a chosen pose for an unchosen one while det grows.
  for (int pass = 0; pass < 50; ++pass) {
    bool improved = false;
    for (std::size_t s = 0; s < selection.selected.size(); ++s) {
      const int out_index = selection.selected[s];
      const Eigen::MatrixXd& A_out = rows[static_cast<std::size_t>(out_index)];
      const Eigen::MatrixXd M_without = M - A_out.transpose() * A_out;
      const Eigen::MatrixXd M_inverse = M_without.ldlt().solve(Eigen::MatrixXd::Identity(n, n));
      const double current = gain(M_inverse, A_out);
      int best = -1;
      double best_gain = current + 1e-9 * std::max(1.0, std::abs(current));
      for (int c = 0; c < num_candidates; ++c) {
        if (chosen[static_cast<std::size_t>(c)]) continue;
        const double g = gain(M_inverse, rows[static_cast<std::size_t>(c)]);
        if (g > best_gain) {
          best_gain = g;
          best = c;
        }
      }
      if (best >= 0) {
        chosen[static_cast<std::size_t>(out_index)] = false;
        chosen[static_cast<std::size_t>(best)] = true;
        selection.selected[s] = best;
        const Eigen::MatrixXd& A_in = rows[static_cast<std::size_t>(best)];
        M = M_without + A_in.transpose() * A_in;
        ++selection.exchanges;
        improved = true;
      }
    }
    if (!improved) break;
  }
  std::sort(selection.selected.begin(), selection.selected.end());
  std::vector<CalibrationMeasurement> chosen_measurements;
  std::vector<Pose> chosen_poses;
  for (int c : selection.selected) {
    chosen_measurements.push_back(measurements[static_cast<std::size_t>(c)]);
    chosen_poses.push_back(candidates[static_cast<std::size_t>(c)]);
  }
  selection.identification = identify(x, tcp, chosen_measurements, chosen_poses, options);
  Eigen::MatrixXd information = Eigen::MatrixXd::Zero(n, n);
  for (int c : selection.selected) {
    information +=
        rows[static_cast<std::size_t>(c)].transpose() * rows[static_cast<std::size_t>(c)];
  }
  selection.log_det = log_det(information);
  if (selection.identification.rank < n) {
    throw CalibrationError(fmt::format(
        "the candidate poses cannot identify every free parameter (rank {} of {}); the "
        "undetermined combination(s) involve {}. Add candidates with rotations or fix these",
        selection.identification.rank, n, join_names(selection.identification.unidentifiable)));
  }
  return selection;
}

}  // namespace pkmopt
