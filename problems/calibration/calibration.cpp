// Calibration by the robust errors-in-variables least-squares problem: the Ceres problem and its
// solve, outlier rejection and inlier refit, covariance and correlations (calibrate); screening
// of held-out poses (fixed_machine_chi2) and the before/after errors by forward kinematics.
#include "problems/calibration/calibration.hpp"

#include <ceres/ceres.h>
#include <fmt/format.h>
#include <glog/logging.h>

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <numeric>
#include <string>
#include <utility>
#include <vector>

#include "problems/calibration/calibration_cost.hpp"
#include "problems/calibration/calibration_detail.hpp"

namespace pkmopt {
namespace {

// Ceres' own messages (glog warnings such as "Linear solver failure", written to stderr when the
// program has not initialised glog) are not for users: what went wrong is in the calibration's
// status and report. Process-wide, like glog itself.
void silence_ceres_log() { FLAGS_minloglevel = google::GLOG_FATAL; }

using detail::free_indices_of;
using detail::IdentificationWithBasis;
using detail::identify_with_basis;
using detail::join_names;
using detail::pose_from_vector;
using detail::pose_vector;
using detail::PoseCostFunction;

// Fixes the coordinates of a parameter block that are not free.
void constrain_block(ceres::Problem& problem, double* block, int start, int size,
                     const CalibrationMask& free) {
  std::vector<int> fixed;
  for (int i = 0; i < size; ++i) {
    if (!free[static_cast<std::size_t>(start + i)]) fixed.push_back(i);
  }
  if (static_cast<int>(fixed.size()) == size) {
    problem.SetParameterBlockConstant(block);
  } else if (!fixed.empty()) {
    problem.SetManifold(block, new ceres::SubsetManifold(size, fixed));
  }
}

struct FitOutcome {
  bool converged = false;
  int iterations = 0;
  std::string message;
};

// The EIV least-squares problem over the poses in `active` (indices); the parameter blocks
// are x's machine, instrument and target segments and the pose vectors, all owned by the caller.
void build_eiv_problem(ceres::Problem& problem, const Eigen::Vector3d& tcp, CalibrationVector& x,
                       std::vector<Vec6<double>>& poses,
                       const std::vector<CalibrationMeasurement>& measurements,
                       const std::vector<int>& active, const CalibrationOptions& options,
                       bool robust, std::vector<Vec6<double>>& shifts) {
  double* machine = x.data();
  double* instrument = x.data() + kCalibrationInstrumentIndex;
  double* target = x.data() + kCalibrationTargetIndex;
  for (int k : active) {
    const auto& m = measurements[static_cast<std::size_t>(k)];
    ceres::LossFunction* loss = nullptr;
    if (robust && options.loss == CalibrationLoss::kHuber) {
      loss = new ceres::HuberLoss(options.loss_scale);
    } else if (robust && options.loss == CalibrationLoss::kCauchy) {
      loss = new ceres::CauchyLoss(options.loss_scale);
    }
    if (m.campaign > 0) {
      problem.AddResidualBlock(new detail::CampaignPoseCost(tcp, m, options), loss, machine,
                               poses[static_cast<std::size_t>(k)].data(), instrument, target,
                               shifts[static_cast<std::size_t>(m.campaign - 1)].data());
    } else {
      problem.AddResidualBlock(new PoseCostFunction(tcp, m, options), loss, machine,
                               poses[static_cast<std::size_t>(k)].data(), instrument, target);
    }
  }
  constrain_block(problem, machine, 0, kCalibrationMachineParameters, options.free);
  constrain_block(problem, instrument, kCalibrationInstrumentIndex, 6, options.free);
  constrain_block(problem, target, kCalibrationTargetIndex, 6, options.free);
}

// Solves the EIV problem over the poses in `active`, updating x and the pose vectors.
FitOutcome solve_eiv(const Eigen::Vector3d& tcp, CalibrationVector& x,
                     std::vector<Vec6<double>>& poses,
                     std::vector<CalibrationMeasurement>& measurements,
                     const std::vector<int>& active, const CalibrationOptions& options, bool robust,
                     std::vector<Vec6<double>>& shifts) {
  ceres::Problem problem;
  build_eiv_problem(problem, tcp, x, poses, measurements, active, options, robust, shifts);
  ceres::Solver::Options solver_options;
  // Poses are eliminated (Schur complement); the reduced system over the machine parameters
  // is small and dense.
  solver_options.linear_solver_type = ceres::DENSE_SCHUR;
  solver_options.max_num_iterations = options.max_iterations;
  // The robust pass only has to find the outliers; the inlier refit polishes.
  solver_options.function_tolerance = robust ? 1e-7 : 1e-12;
  solver_options.gradient_tolerance = 1e-20;
  solver_options.parameter_tolerance = robust ? 1e-8 : 1e-13;
  // The whitened problem is badly scaled (1 um actuator sigma against mm joint errors); the
  // default initial radius (1e4) damps the weak directions so much that LM needs ~10 extra
  // iterations to grow it. Start nearly Gauss-Newton; LM shrinks the radius if a step fails.
  solver_options.initial_trust_region_radius = 1e12;
  solver_options.num_threads = 1;  // deterministic, and the problem is too small to share
  solver_options.logging_type = ceres::SILENT;
  auto* ordering = new ceres::ParameterBlockOrdering;
  for (int k : active) ordering->AddElementToGroup(poses[static_cast<std::size_t>(k)].data(), 0);
  ordering->AddElementToGroup(x.data(), 1);
  ordering->AddElementToGroup(x.data() + kCalibrationInstrumentIndex, 1);
  ordering->AddElementToGroup(x.data() + kCalibrationTargetIndex, 1);
  for (Vec6<double>& shift : shifts)
    if (problem.HasParameterBlock(shift.data())) ordering->AddElementToGroup(shift.data(), 1);
  solver_options.linear_solver_ordering.reset(ordering);
  ceres::Solver::Summary summary;
  silence_ceres_log();
  ceres::Solve(solver_options, &problem, &summary);
  // The other per-pose functions read the shifts from the measurements.
  for (CalibrationMeasurement& m : measurements)
    m.offset_shift =
        m.campaign > 0 ? shifts[static_cast<std::size_t>(m.campaign - 1)] : Vec6<double>::Zero();

  FitOutcome outcome;
  outcome.converged = summary.termination_type == ceres::CONVERGENCE;
  outcome.iterations = static_cast<int>(summary.iterations.size());
  outcome.message = summary.message;
  return outcome;
}

// Ceres' covariance (60 x 60, zero rows/columns for fixed parameters) of the EIV problem over
// `active` without a loss, at x and the poses as they are (no solve). Empty on failure.
Eigen::MatrixXd eiv_covariance(const Eigen::Vector3d& tcp, CalibrationVector& x,
                               std::vector<Vec6<double>>& poses,
                               const std::vector<CalibrationMeasurement>& measurements,
                               const std::vector<int>& active, const CalibrationOptions& options,
                               std::vector<Vec6<double>>& shifts) {
  ceres::Problem problem;
  build_eiv_problem(problem, tcp, x, poses, measurements, active, options, false, shifts);
  std::vector<std::pair<double*, int>> blocks;
  for (auto [block, start] :
       {std::pair{x.data(), 0},
        std::pair{x.data() + kCalibrationInstrumentIndex, kCalibrationInstrumentIndex},
        std::pair{x.data() + kCalibrationTargetIndex, kCalibrationTargetIndex}}) {
    if (!problem.IsParameterBlockConstant(block)) blocks.emplace_back(block, start);
  }
  std::vector<std::pair<const double*, const double*>> pairs;
  for (std::size_t i = 0; i < blocks.size(); ++i) {
    for (std::size_t j = i; j < blocks.size(); ++j) {
      pairs.emplace_back(blocks[i].first, blocks[j].first);
    }
  }
  ceres::Covariance::Options covariance_options;
  covariance_options.algorithm_type = ceres::SPARSE_QR;
  covariance_options.num_threads = 1;
  ceres::Covariance covariance(covariance_options);
  if (pairs.empty() || !covariance.Compute(pairs, &problem)) return {};
  Eigen::MatrixXd out = Eigen::MatrixXd::Zero(kCalibrationParameters, kCalibrationParameters);
  for (std::size_t i = 0; i < blocks.size(); ++i) {
    for (std::size_t j = i; j < blocks.size(); ++j) {
      const int size_i = problem.ParameterBlockSize(blocks[i].first);
      const int size_j = problem.ParameterBlockSize(blocks[j].first);
      Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> block(size_i, size_j);
      covariance.GetCovarianceBlock(blocks[i].first, blocks[j].first, block.data());
      out.block(blocks[i].second, blocks[j].second, size_i, size_j) = block;
      out.block(blocks[j].second, blocks[i].second, size_j, size_i) = block.transpose();
    }
  }
  return out;
}

// The standard deviations of the campaigns' shifts (ceres::Covariance of the final, loss-free
// problem over `active`, times `scale`); zero where Ceres cannot compute them.
std::vector<Vec6<double>> campaign_shift_sigma(
    const Eigen::Vector3d& tcp, CalibrationVector& x, std::vector<Vec6<double>>& poses,
    const std::vector<CalibrationMeasurement>& measurements, const std::vector<int>& active,
    const CalibrationOptions& options, std::vector<Vec6<double>>& shifts, double scale) {
  std::vector<Vec6<double>> sigma(shifts.size(), Vec6<double>::Zero());
  ceres::Problem problem;
  build_eiv_problem(problem, tcp, x, poses, measurements, active, options, false, shifts);
  std::vector<std::pair<const double*, const double*>> pairs;
  for (Vec6<double>& shift : shifts)
    if (problem.HasParameterBlock(shift.data())) pairs.emplace_back(shift.data(), shift.data());
  ceres::Covariance::Options covariance_options;
  covariance_options.algorithm_type = ceres::SPARSE_QR;
  covariance_options.num_threads = 1;
  ceres::Covariance covariance(covariance_options);
  if (pairs.empty() || !covariance.Compute(pairs, &problem)) return sigma;
  for (std::size_t c = 0; c < shifts.size(); ++c) {
    if (!problem.HasParameterBlock(shifts[c].data())) continue;
    Eigen::Matrix<double, 6, 6, Eigen::RowMajor> block;
    covariance.GetCovarianceBlock(shifts[c].data(), shifts[c].data(), block.data());
    sigma[c] = (block.diagonal() * scale).cwiseMax(0.0).cwiseSqrt();
  }
  return sigma;
}

// Fits the pose of one measurement with the machine held fixed; returns its chi^2.
double fit_single_pose(const Eigen::Vector3d& tcp, const CalibrationVector& x_in,
                       const CalibrationMeasurement& m, Vec6<double>& pose,
                       const CalibrationOptions& options) {
  CalibrationVector x = x_in;
  ceres::Problem problem;
  problem.AddResidualBlock(new PoseCostFunction(tcp, m, options), nullptr, x.data(), pose.data(),
                           x.data() + kCalibrationInstrumentIndex,
                           x.data() + kCalibrationTargetIndex);
  problem.SetParameterBlockConstant(x.data());
  problem.SetParameterBlockConstant(x.data() + kCalibrationInstrumentIndex);
  problem.SetParameterBlockConstant(x.data() + kCalibrationTargetIndex);
  ceres::Solver::Options solver_options;
  solver_options.linear_solver_type = ceres::DENSE_QR;
  solver_options.max_num_iterations = 50;
  solver_options.initial_trust_region_radius = 1e12;  // nearly Gauss-Newton, as in solve_eiv
  solver_options.function_tolerance = 1e-14;
  solver_options.parameter_tolerance = 1e-14;
  solver_options.logging_type = ceres::SILENT;
  ceres::Solver::Summary summary;
  silence_ceres_log();
  ceres::Solve(solver_options, &problem, &summary);
  return 2.0 * summary.final_cost;
}

}  // namespace

// ---- Calibration ------------------------------------------------------------------------------

CalibrationResult calibrate(const HexapodDesign& nominal_design, const CalibrationVector& start,
                            const std::vector<CalibrationMeasurement>& measurements_in,
                            const CalibrationOptions& options) {
  // A copy: the campaigns' leg zero shifts are written into it after every solve.
  std::vector<CalibrationMeasurement> measurements = measurements_in;
  int num_campaigns = 1;
  for (const CalibrationMeasurement& m : measurements) {
    if (m.campaign < 0) throw std::invalid_argument("CalibrationMeasurement::campaign < 0");
    num_campaigns = std::max(num_campaigns, m.campaign + 1);
  }
  std::vector<Vec6<double>> shifts(static_cast<std::size_t>(num_campaigns - 1),
                                   Vec6<double>::Zero());
  // Each campaign needs poses of its own: the reference's fix the offsets (without them the
  // offsets and every campaign's shifts are one and the same unknown), and a further campaign's
  // six shifts need at least 3 poses for their rows to keep any redundancy.
  {
    std::vector<int> per_campaign(static_cast<std::size_t>(num_campaigns), 0);
    for (const CalibrationMeasurement& m : measurements)
      ++per_campaign[static_cast<std::size_t>(m.campaign)];
    for (int c = 0; c < num_campaigns; ++c) {
      const int count = per_campaign[static_cast<std::size_t>(c)];
      if (c == 0 ? count == 0 : count < 3)
        throw CalibrationError(fmt::format(
            "measurement campaign {} has {} fitted pose(s): {}", c, count,
            c == 0 ? "the reference campaign (the first in the file) needs fitted poses, or its "
                     "leg offsets cannot be told from the other campaigns' shifts"
                   : "a campaign's six leg zero shifts need at least 3 fitted poses"));
    }
  }
  const int num_shift_parameters = 6 * (num_campaigns - 1);
  if (const std::string error = options.validate(); !error.empty()) {
    throw std::invalid_argument(error);
  }
  const Eigen::Vector3d tcp = nominal_design.tcp;
  const std::vector<int> free_indices = free_indices_of(options.free);
  const int num_free = static_cast<int>(free_indices.size());
  const int num_poses = static_cast<int>(measurements.size());
  if (6 * num_poses < num_free + num_shift_parameters + 1) {
    throw CalibrationError(fmt::format(
        "too few poses: {} fitted poses give {} equations (6 per pose after the pose unknowns), "
        "the {} free parameters need more than {}; measure at least {} poses (3 times as many "
        "is a good rule) or free fewer parameters",
        num_poses, 6 * num_poses, num_free, num_free, num_free / 6 + 1));
  }

  CalibrationResult result;
  CalibrationVector x = start;
  std::vector<Vec6<double>> poses;
  std::vector<Pose> start_poses;
  for (const auto& m : measurements) {
    start_poses.push_back(tcp_pose_from_measurement(x, m.pose));
    poses.push_back(pose_vector(start_poses.back()));
  }
  {
    const Identification id =
        identify_with_basis(x, tcp, measurements, start_poses, options, true).identification;
    if (id.rank < num_free) {
      throw CalibrationError(fmt::format(
          "the measured poses cannot identify every free parameter: the identification "
          "Jacobian has rank {} for {} free parameters; the combination(s) left undetermined "
          "involve {}. Fix some of these parameters (the `fixed:` list or `gauge: auto`) or "
          "measure poses that move them (rotations as well as translations)",
          id.rank, num_free, join_names(id.unidentifiable)));
    }
  }

  // The sigmas whiten the residuals; with estimate_noise they are re-estimated from the data
  // (problems/calibration/calibration_noise.cpp) and the given ones are only the start.
  CalibrationOptions opt = options;
  result.given_sigma = {options.sigma_position, options.sigma_orientation, options.sigma_actuator};
  auto sigma_of = [&](int g) -> double& {
    return g == 0 ? opt.sigma_position : (g == 1 ? opt.sigma_orientation : opt.sigma_actuator);
  };

  std::vector<int> active(static_cast<std::size_t>(num_poses));
  std::iota(active.begin(), active.end(), 0);
  const bool robust = options.loss != CalibrationLoss::kNone;
  // How well the data must determine a group's variance (relative standard deviation of the
  // variance component) before its sigma is taken from them: the instrument's sigmas, which
  // users guess, whenever the estimate is within +-50 % of sigma; the readings' (usually known
  // and far smaller, so that the pose unknowns absorb their rows) only when within +-10 %.
  const Eigen::Vector3d kMaxRelativeSd(1.0, 1.0, 0.2);
  FitOutcome outcome = solve_eiv(tcp, x, poses, measurements, active, opt, robust, shifts);
  result.iterations += outcome.iterations;
  if (options.estimate_noise) {
    // A robust start (medians, insensitive to a minority of gross errors), so that the outlier
    // test below does not depend on the given sigmas; repeated with the robust fit while a
    // sigma still moves by more than 10 %.
    for (int round = 0; round < 5; ++round) {
      const detail::NoiseGroups groups = detail::robust_noise_groups(
          detail::noise_groups(x, tcp, measurements, poses, active, opt));
      std::array<bool, 3> resolved{true, true, true};
      const Eigen::Vector3d factors = detail::helmert_factors(groups, resolved, kMaxRelativeSd);
      double largest_change = 0.0;
      for (int g = 0; g < 3; ++g) {
        sigma_of(g) *= factors(g);  // 1 for a group the data do not resolve
        largest_change = std::max(largest_change, std::abs(std::log(factors(g))));
      }
      if (largest_change < std::log(1.1)) break;
      outcome = solve_eiv(tcp, x, poses, measurements, active, opt, robust, shifts);
      result.iterations += outcome.iterations;
    }
  }

  std::vector<double> chi2(static_cast<std::size_t>(num_poses), 0.0);
  auto pose_chi2 = [&](int k) {
    return calibration_residuals(x, tcp, measurements[static_cast<std::size_t>(k)],
                                 pose_from_vector(poses[static_cast<std::size_t>(k)]), opt)
        .squaredNorm();
  };
  std::vector<bool> rejected(static_cast<std::size_t>(num_poses), false);
  // Rejects every pose whose chi^2 at the current machine exceeds the threshold (a rejected
  // pose is re-admitted when it no longer does) and refits the inliers without a loss, until
  // the set stops changing. Returns true when the set changed.
  auto select_and_refit = [&](bool force_refit) {
    bool changed_any = false;
    for (int round = 0; round < 10; ++round) {
      bool changed = false;
      if (options.reject_outliers) {
        for (int k = 0; k < num_poses; ++k) {
          const std::size_t u = static_cast<std::size_t>(k);
          chi2[u] =
              rejected[u] ? fit_single_pose(tcp, x, measurements[u], poses[u], opt) : pose_chi2(k);
          const bool out = chi2[u] > options.outlier_chi2;
          changed = changed || out != rejected[u];
          rejected[u] = out;
        }
      }
      changed_any = changed_any || changed;
      if (!changed && !force_refit) break;
      active.clear();
      for (int k = 0; k < num_poses; ++k) {
        if (!rejected[static_cast<std::size_t>(k)]) active.push_back(k);
      }
      if (6 * static_cast<int>(active.size()) < num_free + num_shift_parameters + 1) {
        throw CalibrationError(fmt::format(
            "{} of {} poses were rejected as outliers (chi^2 > {}); the {} inliers are too few "
            "for {} free parameters. Check the units of the readings and poses (and the "
            "quaternion order)",
            num_poses - static_cast<int>(active.size()), num_poses, options.outlier_chi2,
            active.size(), num_free));
      }
      outcome = solve_eiv(tcp, x, poses, measurements, active, opt, false, shifts);
      result.iterations += outcome.iterations;
      force_refit = false;
    }
    return changed_any;
  };
  select_and_refit(robust || options.estimate_noise);
  if (options.estimate_noise) {
    // Variance-component estimation on the inliers (Helmert: the cross terms of the groups
    // included, so that a group whose rows the fit holds nearly exact is still corrected),
    // iterated with the outlier test and the fit until the factors settle.
    for (int iteration = 0; iteration < options.noise_iterations; ++iteration) {
      const detail::NoiseGroups groups =
          detail::noise_groups(x, tcp, measurements, poses, active, opt);
      std::array<bool, 3> resolved{true, true, true};
      Eigen::Vector3d relative_sd;
      const Eigen::Vector3d factors =
          detail::helmert_factors(groups, resolved, kMaxRelativeSd, &relative_sd);
      result.noise_relative_sd = relative_sd;
      double largest_change = 0.0;
      for (int g = 0; g < 3; ++g) {
        sigma_of(g) *= factors(g);
        largest_change = std::max(largest_change, std::abs(factors(g) - 1.0));
      }
      result.noise_resolved = resolved;
      result.group_redundancy = groups.redundancy;
      ++result.noise_iterations;
      const bool changed = select_and_refit(true);
      if (largest_change < 1e-4 && !changed) break;
    }
  }
  result.estimated_sigma = {opt.sigma_position, opt.sigma_orientation, opt.sigma_actuator};
  result.noise_estimated = options.estimate_noise;
  for (int k : active) chi2[static_cast<std::size_t>(k)] = pose_chi2(k);
  for (int k = 0; k < num_poses; ++k) {
    if (rejected[static_cast<std::size_t>(k)]) {
      result.outliers.push_back(k);
      chi2[static_cast<std::size_t>(k)] =
          fit_single_pose(tcp, x, measurements[static_cast<std::size_t>(k)],
                          poses[static_cast<std::size_t>(k)], opt);
    }
  }

  // Identification at the solution (inliers, adjusted poses).
  std::vector<CalibrationMeasurement> inlier_measurements;
  std::vector<Pose> inlier_poses;
  for (int k : active) {
    inlier_measurements.push_back(measurements[static_cast<std::size_t>(k)]);
    inlier_poses.push_back(pose_from_vector(poses[static_cast<std::size_t>(k)]));
  }
  const IdentificationWithBasis final_identification =
      identify_with_basis(x, tcp, inlier_measurements, inlier_poses, opt);
  result.identification = final_identification.identification;

  if (options.compute_covariance) {
    // Covariance of the final (inlier, no loss) problem on whitened residuals: the inverse
    // of the Schur-reduced information J_id^T J_id = V S^2 V^T, i.e. V S^-2 V^T from the
    // identification SVD; or Ceres' own (ceres::Covariance, SPARSE_QR on the full problem).
    Eigen::MatrixXd covariance =
        Eigen::MatrixXd::Zero(kCalibrationParameters, kCalibrationParameters);
    if (result.identification.rank == num_free && num_free > 0) {
      if (options.covariance_method == CalibrationCovarianceMethod::kCeres) {
        covariance = eiv_covariance(tcp, x, poses, measurements, active, opt, shifts);
      }
      if (options.covariance_method == CalibrationCovarianceMethod::kReducedInformation ||
          covariance.size() == 0) {
        const Eigen::MatrixXd& V = final_identification.V;
        const Eigen::VectorXd inverse_s2 =
            result.identification.singular_values.array().square().inverse();
        // lazyProduct: a plain coefficient loop (no threaded GEMM for a 48 x 48 product).
        const Eigen::MatrixXd inverse = (V * inverse_s2.asDiagonal()).lazyProduct(V.transpose());
        covariance = Eigen::MatrixXd::Zero(kCalibrationParameters, kCalibrationParameters);
        for (int a = 0; a < num_free; ++a) {
          for (int b = 0; b < num_free; ++b) {
            covariance(free_indices[static_cast<std::size_t>(a)],
                       free_indices[static_cast<std::size_t>(b)]) = inverse(a, b);
          }
        }
      }
    }
    result.covariance = covariance;
    result.sigma = covariance.diagonal().cwiseMax(0.0).cwiseSqrt();
    for (int a = 0; a < num_free; ++a) {
      for (int b = a + 1; b < num_free; ++b) {
        const int i = free_indices[static_cast<std::size_t>(a)];
        const int j = free_indices[static_cast<std::size_t>(b)];
        const double denominator = result.sigma(i) * result.sigma(j);
        if (denominator <= 0.0) continue;
        const double rho = covariance(i, j) / denominator;
        if (std::abs(rho) >= options.correlation_threshold) {
          result.correlated.push_back({i, j, rho});
        }
      }
    }
    std::sort(result.correlated.begin(), result.correlated.end(),
              [](const CorrelatedPair& l, const CorrelatedPair& r) {
                return std::abs(l.correlation) > std::abs(r.correlation);
              });
  }

  result.estimate = x;
  for (const auto& pose : poses) result.adjusted_poses.push_back(pose_from_vector(pose));
  result.chi2 = chi2;
  double total = 0.0;
  for (int k : active) total += chi2[static_cast<std::size_t>(k)];
  // A campaign whose poses were all rejected has no estimated shifts.
  std::vector<bool> campaign_fitted(static_cast<std::size_t>(num_campaigns), false);
  for (int k : active)
    campaign_fitted[static_cast<std::size_t>(measurements[static_cast<std::size_t>(k)].campaign)] =
        true;
  int estimated_shifts = 0;
  for (int c = 1; c < num_campaigns; ++c) {
    if (campaign_fitted[static_cast<std::size_t>(c)]) {
      estimated_shifts += 6;
    } else {
      shifts[static_cast<std::size_t>(c - 1)].setZero();
    }
  }
  const int dof = 6 * static_cast<int>(active.size()) - num_free - estimated_shifts;
  result.chi2_per_dof = dof > 0 ? total / dof : 0.0;
  if (options.compute_covariance && result.chi2_per_dof > 0.0) {
    result.covariance_scale = result.chi2_per_dof;
    result.covariance *= result.covariance_scale;
    result.sigma = result.covariance.diagonal().cwiseMax(0.0).cwiseSqrt();
  }
  result.converged = outcome.converged;
  result.solver_message = outcome.message;
  result.campaign_shifts = shifts;
  for (int c = 1; c < num_campaigns; ++c)
    result.campaign_estimated.push_back(campaign_fitted[static_cast<std::size_t>(c)]);
  if (!shifts.empty())
    result.campaign_shift_sigma = campaign_shift_sigma(tcp, x, poses, measurements, active, opt,
                                                       shifts, result.covariance_scale);
  return result;
}

std::vector<CalibrationMeasurement> with_campaign_shifts(
    const std::vector<CalibrationMeasurement>& measurements, const CalibrationResult& result) {
  std::vector<CalibrationMeasurement> out = measurements;
  for (CalibrationMeasurement& m : out) {
    const std::size_t c = static_cast<std::size_t>(m.campaign);
    m.offset_shift = m.campaign > 0 && c <= result.campaign_shifts.size()
                         ? result.campaign_shifts[c - 1]
                         : Vec6<double>::Zero();
  }
  return out;
}

CalibrationErrors calibration_errors(const HexapodDesign& nominal_design,
                                     const CalibrationVector& x,
                                     const std::vector<CalibrationMeasurement>& measurements,
                                     const std::vector<int>& indices) {
  CalibrationErrors errors;
  const Hexapod hexapod(calibrated_design(nominal_design, x));
  Vec6<double> leg_sum = Vec6<double>::Zero();
  double position_sum = 0.0, orientation_sum = 0.0;
  int fk_count = 0;
  for (int k : indices) {
    const auto& m = measurements[static_cast<std::size_t>(k)];
    const Pose measured = tcp_pose_from_measurement(x, m.pose);
    const Vec6<double> lengths = leg_lengths_of(x, m);
    const Vec6<double> leg_error = hexapod.inverse_kinematics(measured) - lengths;
    leg_sum += leg_error.cwiseAbs2();
    errors.leg_max = errors.leg_max.cwiseMax(leg_error.cwiseAbs());
    ++errors.count;
    const FkResult fk = hexapod.forward_kinematics(lengths, measured);
    if (!fk.converged) {
      ++errors.fk_failures;
      continue;
    }
    const double position_error = (fk.pose.position - measured.position).norm();
    const double orientation_error =
        rotation_vector(rotation_zyx<double>(measured.angles).transpose() *
                        rotation_zyx<double>(fk.pose.angles))
            .norm();
    position_sum += position_error * position_error;
    orientation_sum += orientation_error * orientation_error;
    errors.tcp_position_max = std::max(errors.tcp_position_max, position_error);
    errors.tcp_orientation_max = std::max(errors.tcp_orientation_max, orientation_error);
    ++fk_count;
  }
  if (errors.count > 0) errors.leg_rms = (leg_sum / errors.count).cwiseSqrt();
  if (fk_count > 0) {
    errors.tcp_position_rms = std::sqrt(position_sum / fk_count);
    errors.tcp_orientation_rms = std::sqrt(orientation_sum / fk_count);
  }
  return errors;
}

std::vector<double> fixed_machine_chi2(const Eigen::Vector3d& tcp, const CalibrationVector& x,
                                       const std::vector<CalibrationMeasurement>& measurements,
                                       const std::vector<int>& indices,
                                       const CalibrationOptions& options) {
  std::vector<double> chi2;
  chi2.reserve(indices.size());
  for (int k : indices) {
    const auto& m = measurements[static_cast<std::size_t>(k)];
    Vec6<double> pose = pose_vector(tcp_pose_from_measurement(x, m.pose));
    chi2.push_back(fit_single_pose(tcp, x, m, pose, options));
  }
  return chi2;
}

}  // namespace pkmopt
