// Tests of problems/calibration/calibration_noise (and its use in calibrate): the group
// redundancies against the hat matrix of the whole EIV problem built independently here (dense QR
// over machine parameters and pose unknowns), their sum against the degrees of freedom, and the
// noise estimated from simulated data: the estimated sigmas land on the simulated ones and the
// rejected poses stay the same whether the given sigmas are ten times too small or too large.
#include <gtest/gtest.h>

#include <Eigen/QR>
#include <algorithm>
#include <cmath>
#include <vector>

#include "models/sample_machines.hpp"
#include "problems/calibration/calibration.hpp"
#include "problems/calibration/calibration_detail.hpp"

namespace pkmopt {
namespace {

HexapodDesign sample_hexapod() { return sample_machines::conventions_hexapod_design(); }

CalibrationVector sample_nominal(const HexapodDesign& design) {
  return nominal_calibration_vector(design, Vec6<double>::Constant(0.7));
}

// Noise with one sigma per group (the model the estimate assumes): 15 um, 5e-5 rad, 1 um.
MeasurementSimulationOptions simulation(std::uint64_t seed, int poses, int outliers) {
  MeasurementSimulationOptions sim;
  sim.seed = seed;
  sim.num_poses = poses;
  sim.tracker_sigma = 15e-6;
  sim.tracker_sigma_per_metre = 0.0;
  sim.orientation_sigma = 5e-5;
  sim.actuator_sigma = 1e-6;
  sim.num_outliers = outliers;
  return sim;
}

TEST(CalibrationNoise, RedundanciesAreTheHatMatrixDiagonalAndSumToTheDegreesOfFreedom) {
  const HexapodDesign design = sample_hexapod();
  const CalibrationVector nominal = sample_nominal(design);
  CalibrationOptions options;
  options.free = model_free_mask(CalibrationModelKind::k42);
  const SimulatedMeasurements sim =
      simulate_measurements(design, nominal, options.free, simulation(3, 20, 0));
  std::vector<Vec6<double>> poses;
  std::vector<int> active;
  for (std::size_t k = 0; k < sim.true_poses.size(); ++k) {
    poses.push_back(detail::pose_vector(sim.true_poses[k]));
    active.push_back(static_cast<int>(k));
  }
  const detail::NoiseGroups groups =
      detail::noise_groups(sim.truth, design.tcp, sim.measurements, poses, active, options);
  const std::vector<int> free = detail::free_indices_of(options.free);
  const int n = static_cast<int>(free.size()), N = static_cast<int>(poses.size());
  // The whole problem's Jacobian: 12 rows per pose; the free parameters, then 6 pose unknowns
  // per pose.
  Eigen::MatrixXd J = Eigen::MatrixXd::Zero(12 * N, n + 6 * N);
  Eigen::VectorXd r(12 * N);
  for (int k = 0; k < N; ++k) {
    const Eigen::Matrix<double, 12, 66> Jk = calibration_jacobian(
        sim.truth, design.tcp, sim.measurements[k], sim.true_poses[k], options);
    for (int j = 0; j < n; ++j) J.block(12 * k, j, 12, 1) = Jk.col(free[j]);
    J.block(12 * k, n + 6 * k, 12, 6) = Jk.rightCols<6>();
    r.segment<12>(12 * k) = calibration_residuals(sim.truth, design.tcp, sim.measurements[k],
                                                  sim.true_poses[k], options);
  }
  const Eigen::HouseholderQR<Eigen::MatrixXd> qr(J);
  const Eigen::MatrixXd Q = qr.householderQ() * Eigen::MatrixXd::Identity(12 * N, n + 6 * N);
  Eigen::Vector3d redundancy = Eigen::Vector3d::Zero(), omega = Eigen::Vector3d::Zero();
  for (int row = 0; row < 12 * N; ++row) {
    const int i = row % 12;
    const int g = i < 6 ? 2 : (i < 9 ? 0 : 1);
    redundancy(g) += 1.0 - Q.row(row).squaredNorm();
    omega(g) += r(row) * r(row);
  }
  for (int g = 0; g < 3; ++g) {
    EXPECT_NEAR(groups.redundancy(g), redundancy(g), 1e-8 * (6.0 * N)) << g;
    EXPECT_NEAR(groups.omega(g), omega(g), 1e-12 * omega(g)) << g;
  }
  EXPECT_EQ(groups.rows, Eigen::Vector3i(3 * N, 3 * N, 6 * N));
  EXPECT_NEAR(groups.redundancy.sum(), 6.0 * N - n, 1e-8 * N);
}

// The given sigmas off by 10 either way (all three, and one or two at a time). The simulated
// readings (1 um) are 15 times more precise than the instrument (15 um): the pose unknowns absorb
// their rows almost entirely, so the data do not resolve the reading sigma (relative standard
// deviation of its variance component > 20 %) and is not taken from them. The instrument sigmas are
// estimated (within 20 % of the simulated ones, the estimate's own spread being about 10 %) when
// the reading sigma is not overstated; with a reading sigma ten times too large (held, it takes
// a share of the instrument's noise) they come out up to 25 % low. In every case the same poses
// are rejected, within one.
TEST(CalibrationNoise, EstimatedSigmasAndOutliersDoNotDependOnTheGivenSigmas) {
  const HexapodDesign design = sample_hexapod();
  const CalibrationVector nominal = sample_nominal(design);
  const CalibrationMask free = model_free_mask(CalibrationModelKind::k48);
  const SimulatedMeasurements sim =
      simulate_measurements(design, nominal, free, simulation(11, 80, 4));
  const Eigen::Vector3d truth(15e-6, 5e-5, 1e-6);
  std::vector<int> reference_outliers;
  bool first = true;
  const std::vector<Eigen::Vector3d> factors = {{1, 1, 1},    {0.1, 0.1, 0.1}, {10, 10, 10},
                                                {0.1, 1, 1},  {1, 10, 1},      {1, 1, 0.1},
                                                {10, 0.1, 10}};
  for (const Eigen::Vector3d& f : factors) {
    CalibrationOptions options;
    options.free = free;
    options.sigma_position = truth(0) * f(0);
    options.sigma_orientation = truth(1) * f(1);
    options.sigma_actuator = truth(2) * f(2);
    const CalibrationResult result = calibrate(design, nominal, sim.measurements, options);
    SCOPED_TRACE(::testing::Message() << "factors " << f.transpose());
    EXPECT_TRUE(result.noise_estimated);
    EXPECT_EQ(result.given_sigma, Eigen::Vector3d(options.sigma_position, options.sigma_orientation,
                                                  options.sigma_actuator));
    EXPECT_FALSE(result.noise_resolved[2]);
    if (f(2) <= 1.0) {
      for (int g = 0; g < 2; ++g) {
        EXPECT_TRUE(result.noise_resolved[static_cast<std::size_t>(g)]) << g;
        EXPECT_NEAR(result.estimated_sigma(g) / truth(g), 1.0, 0.2) << "group " << g;
        EXPECT_LT(result.noise_relative_sd(g), 0.2) << g;
      }
      EXPECT_NEAR(result.chi2_per_dof, 1.0, 0.1);
    }
    if (first) {
      reference_outliers = result.outliers;
      first = false;
      // The simulated gross errors (1 mm) are among them.
      for (int k : sim.outliers)
        EXPECT_NE(std::find(result.outliers.begin(), result.outliers.end(), k),
                  result.outliers.end())
            << k;
    } else {
      std::vector<int> differ;
      std::set_symmetric_difference(reference_outliers.begin(), reference_outliers.end(),
                                    result.outliers.begin(), result.outliers.end(),
                                    std::back_inserter(differ));
      EXPECT_LE(differ.size(), 1u);
    }
  }
}

// An optimistic tracker sigma (4 um for a 15 um tracker) taken as true rejects more than a
// quarter of the poses (or so many that the fit is refused); estimated from the data, the same
// start rejects the 3 gross errors and at most one more.
TEST(CalibrationNoise, GuessedSigmasNoLongerDecideTheOutliers) {
  const HexapodDesign design = sample_hexapod();
  const CalibrationVector nominal = sample_nominal(design);
  const CalibrationMask free = model_free_mask(CalibrationModelKind::k48);
  const SimulatedMeasurements sim =
      simulate_measurements(design, nominal, free, simulation(12, 80, 3));
  CalibrationOptions options;
  options.free = free;
  options.sigma_position = 4e-6;  // a plausible but optimistic tracker figure
  options.sigma_orientation = 2e-5;
  options.sigma_actuator = 1e-6;
  options.estimate_noise = false;
  std::size_t fixed_outliers = 0;
  try {
    fixed_outliers = calibrate(design, nominal, sim.measurements, options).outliers.size();
  } catch (const CalibrationError&) {
    fixed_outliers = sim.measurements.size();  // so many rejected that the fit is impossible
  }
  options.estimate_noise = true;
  const CalibrationResult estimated = calibrate(design, nominal, sim.measurements, options);
  EXPECT_GT(fixed_outliers, 20u);
  EXPECT_LE(estimated.outliers.size(), 4u);
  EXPECT_GE(estimated.outliers.size(), 3u);
}

// A session of a machine measured with a coarse instrument (0.3 mm, 0.03 deg, readings 10 um;
// 108 poses, 5 of them with a 5 mm gross error): with the noise given right, 3 times too large
// (which once rejected every pose as an outlier), 3 times too small, and 10 times off either way,
// all three groups together or the instrument and the readings apart, the calibration rejects the
// same poses (the gross errors among them, at most two others differing) and gives the same
// parameters within their own uncertainty (each within 2 sigma of the estimate with the right
// noise), and the instrument sigmas, where the data resolve them, estimated within 25 % of the
// simulated ones (readings 10 times too noisy against an instrument 30 times too precise leave
// the instrument's sigmas unresolved: the pose unknowns follow the instrument).
TEST(CalibrationNoise, CalibrationWithNoiseOverstatedThreeTimes) {
  const HexapodDesign design = sample_hexapod();
  const CalibrationVector nominal = sample_nominal(design);
  const CalibrationMask free = model_free_mask(CalibrationModelKind::k48);
  MeasurementSimulationOptions sim_options = simulation(21, 108, 5);
  sim_options.tracker_sigma = 3e-4;
  sim_options.orientation_sigma = 0.03 * kDegToRad;
  sim_options.actuator_sigma = 1e-5;
  sim_options.joint_sigma = 3e-3;
  sim_options.offset_sigma = 3e-3;
  sim_options.outlier_magnitude = 5e-3;
  const SimulatedMeasurements sim = simulate_measurements(design, nominal, free, sim_options);
  const Eigen::Vector3d truth(3e-4, 0.03 * kDegToRad, 1e-5);
  const std::vector<Eigen::Vector3d> factors = {
      {1, 1, 1},    {3, 3, 3},       {1.0 / 3, 1.0 / 3, 1.0 / 3},
      {10, 10, 10}, {0.1, 0.1, 0.1}, {3, 3, 1},
      {1, 1, 3},    {0.1, 0.01, 1},  {0.03, 0.03, 10}};
  CalibrationResult reference;
  for (const Eigen::Vector3d& f : factors) {
    SCOPED_TRACE(::testing::Message() << "factors " << f.transpose());
    CalibrationOptions options;
    options.free = free;
    options.sigma_position = truth(0) * f(0);
    options.sigma_orientation = truth(1) * f(1);
    options.sigma_actuator = truth(2) * f(2);
    CalibrationResult result;
    ASSERT_NO_THROW(result = calibrate(design, nominal, sim.measurements, options));
    // A group the data do not resolve keeps its given sigma (and the report says so).
    for (int g = 0; g < 2; ++g) {
      if (result.noise_resolved[static_cast<std::size_t>(g)]) {
        EXPECT_NEAR(result.estimated_sigma(g) / truth(g), 1.0, 0.25) << "group " << g;
      }
    }
    if (f == Eigen::Vector3d::Ones()) {
      reference = result;
      for (int k : sim.outliers)
        EXPECT_NE(std::find(result.outliers.begin(), result.outliers.end(), k),
                  result.outliers.end())
            << k;
      continue;
    }
    std::vector<int> differ;
    std::set_symmetric_difference(reference.outliers.begin(), reference.outliers.end(),
                                  result.outliers.begin(), result.outliers.end(),
                                  std::back_inserter(differ));
    EXPECT_LE(differ.size(), 2u);
    for (int i = 0; i < kCalibrationParameters; ++i) {
      if (!(reference.sigma(i) > 0.0)) continue;  // a held parameter
      EXPECT_LT(std::abs(result.estimate(i) - reference.estimate(i)), 2.0 * reference.sigma(i))
          << calibration_parameter_name(i);
    }
  }
}

// Without the estimate the given sigmas are used as they are, and the covariance is still scaled
// by the a-posteriori variance factor: sigmas 3 times too large give chi2/dof 1/9 and the same
// reported parameter sigmas as the right ones.
TEST(CalibrationNoise, CovarianceIsScaledByTheVarianceFactor) {
  const HexapodDesign design = sample_hexapod();
  const CalibrationVector nominal = sample_nominal(design);
  const CalibrationMask free = model_free_mask(CalibrationModelKind::k42);
  const SimulatedMeasurements sim =
      simulate_measurements(design, nominal, free, simulation(5, 40, 0));
  CalibrationOptions right;
  right.free = free;
  right.estimate_noise = false;
  right.reject_outliers = false;
  right.sigma_position = 15e-6;
  right.sigma_orientation = 5e-5;
  right.sigma_actuator = 1e-6;
  CalibrationOptions large = right;
  large.sigma_position *= 3;
  large.sigma_orientation *= 3;
  large.sigma_actuator *= 3;
  const CalibrationResult a = calibrate(design, nominal, sim.measurements, right);
  const CalibrationResult b = calibrate(design, nominal, sim.measurements, large);
  EXPECT_FALSE(a.noise_estimated);
  EXPECT_EQ(a.estimated_sigma, a.given_sigma);
  EXPECT_NEAR(b.chi2_per_dof, a.chi2_per_dof / 9.0, 1e-6 * a.chi2_per_dof);
  for (int i = 0; i < kCalibrationParameters; ++i)
    EXPECT_NEAR(b.sigma(i), a.sigma(i), 1e-6 * a.sigma(i) + 1e-300) << i;
}

}  // namespace
}  // namespace pkmopt
