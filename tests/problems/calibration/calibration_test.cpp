// Tests of problems/calibration/calibration: recovery, uncertainty, gauge, outliers, Jacobians,
// pose choice.
#include "problems/calibration/calibration.hpp"

#include <gtest/gtest.h>

#include <Eigen/Cholesky>
#include <Eigen/LU>
#include <Eigen/SVD>
#include <algorithm>
#include <cmath>
#include <numeric>

#include "models/sample_machines.hpp"

namespace pkmopt {
namespace {

// The sample hexapod of docs/conventions.md.
HexapodDesign sample_hexapod() { return sample_machines::conventions_hexapod_design(); }

// Readings are strokes from a 0.7 m zero length.
CalibrationVector sample_nominal(const HexapodDesign& design) {
  return nominal_calibration_vector(design, Vec6<double>::Constant(0.7));
}

MeasurementSimulationOptions noise_free(std::uint64_t seed, int poses) {
  MeasurementSimulationOptions sim;
  sim.seed = seed;
  sim.num_poses = poses;
  sim.tracker_sigma = 0.0;
  sim.tracker_sigma_per_metre = 0.0;
  sim.orientation_sigma = 0.0;
  sim.actuator_sigma = 0.0;
  sim.num_outliers = 0;
  return sim;
}

std::vector<int> all_indices(std::size_t n) {
  std::vector<int> indices(n);
  std::iota(indices.begin(), indices.end(), 0);
  return indices;
}

TEST(CalibrationParameters, NamesRoundTripAndUnits) {
  for (int i = 0; i < kCalibrationParameters; ++i) {
    EXPECT_EQ(calibration_parameter_index(calibration_parameter_name(i)), i);
  }
  EXPECT_EQ(calibration_parameter_name(0), "a1.x");
  EXPECT_EQ(calibration_parameter_name(8 * 2 + 4), "b3.y");
  EXPECT_EQ(calibration_parameter_name(8 * 5 + 7), "gain6");
  EXPECT_EQ(calibration_parameter_name(kCalibrationInstrumentIndex + 5), "instrument.rz");
  EXPECT_EQ(calibration_parameter_unit(8 * 5 + 7), "1");
  EXPECT_EQ(calibration_parameter_unit(kCalibrationTargetIndex + 3), "rad");
  EXPECT_EQ(calibration_parameter_index("nonsense"), -1);
}

TEST(CalibrationFrames, MeasurementAndTcpPoseAreInverse) {
  const HexapodDesign design = sample_hexapod();
  const CalibrationVector x = nominal_calibration_vector(
      design, Vec6<double>::Constant(0.7), Pose{{2.0, -1.0, 0.3}, {0.1, -0.2, 0.3}},
      Pose{{0.01, 0.02, 0.05}, {0.02, 0.01, -0.03}});
  const Pose tcp_pose{{0.05, -0.02, 0.85}, {0.1, 0.05, -0.08}};
  const Pose back = tcp_pose_from_measurement(x, measurement_from_tcp_pose(x, tcp_pose));
  EXPECT_LT((back.position - tcp_pose.position).norm(), 1e-14);
  EXPECT_LT((back.angles - tcp_pose.angles).norm(), 1e-14);
}

// The autodiff Jacobian against central differences of the residuals.
TEST(CalibrationJacobian, MatchesCentralDifferences) {
  const HexapodDesign design = sample_hexapod();
  CalibrationVector x = nominal_calibration_vector(design, Vec6<double>::Constant(0.7),
                                                   Pose{{1.5, 0.5, 0.2}, {0.05, -0.1, 0.2}},
                                                   Pose{{0.01, -0.02, 0.03}, {0.03, 0.02, -0.01}});
  for (int leg = 0; leg < 6; ++leg) x(8 * leg + 7) = 1e-3 * (leg - 2.5);
  CalibrationMeasurement m;
  m.pose = Pose{{-1.4, -0.3, 0.6}, {0.1, 0.2, -0.25}};
  m.stroke << 0.11, 0.13, 0.17, 0.12, 0.15, 0.16;
  const Pose tcp_pose{{0.04, -0.03, 0.86}, {0.07, -0.05, 0.1}};
  CalibrationOptions options;
  options.sigma_position = 1e-3;
  options.sigma_orientation = 1e-3;
  options.sigma_actuator = 1e-3;
  const Eigen::Matrix<double, 12, 66> J = calibration_jacobian(x, design.tcp, m, tcp_pose, options);
  const double h = 1e-6;
  for (int j = 0; j < 66; ++j) {
    CalibrationVector xp = x, xm = x;
    Pose pp = tcp_pose, pm = tcp_pose;
    if (j < 60) {
      xp(j) += h;
      xm(j) -= h;
    } else if (j < 63) {
      pp.position(j - 60) += h;
      pm.position(j - 60) -= h;
    } else {
      pp.angles(j - 63) += h;
      pm.angles(j - 63) -= h;
    }
    const Eigen::Matrix<double, 12, 1> numeric =
        (calibration_residuals(xp, design.tcp, m, pp, options) -
         calibration_residuals(xm, design.tcp, m, pm, options)) /
        (2 * h);
    EXPECT_LT((numeric - J.col(j)).norm(), 1e-6 * std::max(1.0, numeric.norm()))
        << "column " << j << " (" << (j < 60 ? calibration_parameter_name(j) : "pose") << ")";
  }
}

// With the frames held the solver differentiates the measured-pose residuals with respect to the
// pose alone (a separate 6-jet path): it must agree with central differences too.
TEST(CalibrationJacobian, PoseOnlyPathMatchesCentralDifferences) {
  const HexapodDesign design = sample_hexapod();
  const CalibrationVector x = nominal_calibration_vector(
      design, Vec6<double>::Constant(0.7), Pose{{1.5, 0.5, 0.2}, {0.05, -0.1, 0.2}},
      Pose{{0.01, -0.02, 0.03}, {0.03, 0.02, -0.01}});
  CalibrationMeasurement m;
  m.pose = Pose{{-1.4, -0.3, 0.6}, {0.1, 0.2, -0.25}};
  m.stroke << 0.11, 0.13, 0.17, 0.12, 0.15, 0.16;
  const Pose tcp_pose{{0.04, -0.03, 0.86}, {0.07, -0.05, 0.1}};
  CalibrationOptions options;
  options.sigma_position = 1e-3;
  options.sigma_orientation = 1e-3;
  options.sigma_actuator = 1e-3;
  const Eigen::Matrix<double, 12, 6> J =
      calibration_pose_jacobian(x, design.tcp, m, tcp_pose, options);
  const double h = 1e-6;
  for (int j = 0; j < 6; ++j) {
    Pose pp = tcp_pose, pm = tcp_pose;
    if (j < 3) {
      pp.position(j) += h;
      pm.position(j) -= h;
    } else {
      pp.angles(j - 3) += h;
      pm.angles(j - 3) -= h;
    }
    const Eigen::Matrix<double, 12, 1> numeric =
        (calibration_residuals(x, design.tcp, m, pp, options) -
         calibration_residuals(x, design.tcp, m, pm, options)) /
        (2 * h);
    EXPECT_LT((numeric - J.col(j)).norm(), 1e-6 * std::max(1.0, numeric.norm())) << "pose " << j;
  }
}

TEST(Calibration, RecoversPerturbationsFromNoiseFreeData) {
  const HexapodDesign design = sample_hexapod();
  const CalibrationVector nominal = sample_nominal(design);
  const CalibrationMask free48 = model_free_mask(CalibrationModelKind::k48);
  const SimulatedMeasurements sim =
      simulate_measurements(design, nominal, free48, noise_free(11, 30));
  CalibrationOptions options;
  options.free = free48;
  options.loss = CalibrationLoss::kNone;
  const CalibrationResult result = calibrate(design, nominal, sim.measurements, options);
  EXPECT_TRUE(result.outliers.empty());
  EXPECT_EQ(result.identification.rank, 48);
  EXPECT_GT((sim.truth - nominal).cwiseAbs().maxCoeff(), 1e-4);  // there was something to find
  for (int i = 0; i < kCalibrationParameters; ++i) {
    EXPECT_NEAR(result.estimate(i), sim.truth(i), 1e-9) << calibration_parameter_name(i);
  }
  for (std::size_t k = 0; k < sim.true_poses.size(); ++k) {
    EXPECT_LT((result.adjusted_poses[k].position - sim.true_poses[k].position).norm(), 1e-9);
  }
}

// Over 20 seeds the estimation errors normalised by the reported sigma behave like N(0, 1).
TEST(Calibration, ReportedSigmaMatchesSpreadOverSeeds) {
  const HexapodDesign design = sample_hexapod();
  const CalibrationVector nominal = sample_nominal(design);
  const CalibrationMask free48 = model_free_mask(CalibrationModelKind::k48);
  double sum_z2 = 0.0;
  int count = 0, beyond3 = 0;
  for (std::uint64_t seed = 100; seed < 120; ++seed) {
    MeasurementSimulationOptions sim_options;
    sim_options.seed = seed;
    sim_options.num_poses = 30;
    sim_options.num_outliers = 0;
    sim_options.tracker_sigma_per_metre = 0.0;  // constant sigma, as the model assumes
    const SimulatedMeasurements sim = simulate_measurements(design, nominal, free48, sim_options);
    CalibrationOptions options;
    options.free = free48;
    options.sigma_position = sim_options.tracker_sigma;
    options.sigma_orientation = sim_options.orientation_sigma;
    options.sigma_actuator = sim_options.actuator_sigma;
    const CalibrationResult result = calibrate(design, nominal, sim.measurements, options);
    for (int i = 0; i < kCalibrationMachineParameters; ++i) {
      ASSERT_GT(result.sigma(i), 0.0);
      const double z = (result.estimate(i) - sim.truth(i)) / result.sigma(i);
      sum_z2 += z * z;
      beyond3 += std::abs(z) > 3.0 ? 1 : 0;
      ++count;
    }
  }
  const double rms_z = std::sqrt(sum_z2 / count);
  EXPECT_GT(rms_z, 0.85);
  EXPECT_LT(rms_z, 1.15);
  EXPECT_LE(beyond3, count / 100);  // N(0,1): 0.27 % beyond 3 sigma
}

TEST(Calibration, CeresCovarianceEqualsReducedInformationInverse) {
  const HexapodDesign design = sample_hexapod();
  const CalibrationVector nominal = sample_nominal(design);
  const CalibrationMask free42 = model_free_mask(CalibrationModelKind::k42);
  MeasurementSimulationOptions sim_options;
  sim_options.seed = 5;
  sim_options.num_poses = 25;
  sim_options.num_outliers = 0;
  const SimulatedMeasurements sim = simulate_measurements(design, nominal, free42, sim_options);
  CalibrationOptions options;
  options.free = free42;
  const CalibrationResult result = calibrate(design, nominal, sim.measurements, options);
  CalibrationOptions ceres_options = options;
  ceres_options.covariance_method = CalibrationCovarianceMethod::kCeres;
  const CalibrationResult ceres_result =
      calibrate(design, nominal, sim.measurements, ceres_options);
  EXPECT_EQ(result.estimate, ceres_result.estimate);  // the method changes nothing else
  std::vector<int> free_indices;
  for (int i = 0; i < kCalibrationParameters; ++i) {
    if (free42[static_cast<std::size_t>(i)]) free_indices.push_back(i);
  }
  // The identification Jacobian whitened with the sigmas of the final fit (estimated from the
  // residuals), and the covariance scaled by the a-posteriori variance factor.
  CalibrationOptions used = options;
  used.sigma_position = result.estimated_sigma(0);
  used.sigma_orientation = result.estimated_sigma(1);
  used.sigma_actuator = result.estimated_sigma(2);
  Eigen::MatrixXd J(6 * 25, 42);
  for (int k = 0; k < 25; ++k) {
    J.middleRows(6 * k, 6) =
        reduced_identification_rows(result.estimate, design.tcp, sim.measurements[k],
                                    result.adjusted_poses[k], free_indices, used);
  }
  const Eigen::MatrixXd inverse = (J.transpose() * J).inverse() * result.covariance_scale;
  for (int a = 0; a < 42; ++a) {
    const int i = free_indices[static_cast<std::size_t>(a)];
    for (int b = 0; b < 42; ++b) {
      const int j = free_indices[static_cast<std::size_t>(b)];
      const double scale = std::sqrt(inverse(a, a) * inverse(b, b));
      EXPECT_NEAR(result.covariance(i, j), inverse(a, b), 1e-6 * scale);
      EXPECT_NEAR(ceres_result.covariance(i, j), inverse(a, b), 1e-6 * scale);
    }
  }
  for (int i = 0; i < kCalibrationParameters; ++i) {
    if (!free42[static_cast<std::size_t>(i)]) {
      EXPECT_EQ(result.sigma(i), 0.0);
    }
  }
  // Identification singular values are those of J.
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(J);
  EXPECT_NEAR(result.identification.O3, svd.singularValues()(41), 1e-8 * svd.singularValues()(0));
  const double O1 = std::exp(svd.singularValues().array().log().mean()) / std::sqrt(25.0);
  EXPECT_NEAR(result.identification.O1, O1, 1e-8 * O1);
  EXPECT_NEAR(result.identification.O4,
              std::pow(svd.singularValues()(41), 2) / svd.singularValues()(0),
              1e-8 * result.identification.O4);
  // Scaled indices: columns times the a-priori sigma (1 mm for joints and offsets here).
  Eigen::VectorXd scale(42);
  for (int a = 0; a < 42; ++a) {
    scale(a) = options.parameter_scale(free_indices[static_cast<std::size_t>(a)]);
  }
  EXPECT_EQ(scale.minCoeff(), 1e-3);
  EXPECT_EQ(scale.maxCoeff(), 1e-3);
  const Eigen::JacobiSVD<Eigen::MatrixXd> scaled_svd(J * scale.asDiagonal());
  const Eigen::VectorXd& s = scaled_svd.singularValues();
  const ObservabilityIndices& scaled = result.identification.scaled;
  EXPECT_NEAR(scaled.O1, std::exp(s.array().log().mean()) / std::sqrt(25.0), 1e-8 * scaled.O1);
  EXPECT_NEAR(scaled.O2, s(0) / s(41), 1e-6 * scaled.O2);
  EXPECT_NEAR(scaled.O3, s(41), 1e-8 * s(0));
  EXPECT_NEAR(scaled.O4, s(41) * s(41) / s(0), 1e-8 * scaled.O4);
  // With one scale for every column the scaled indices are the unscaled ones times it.
  EXPECT_NEAR(scaled.O3, 1e-3 * result.identification.O3, 1e-8 * scaled.O3);
}

TEST(Calibration, RejectsOutliersAndImprovesHeldOutPoses) {
  const HexapodDesign design = sample_hexapod();
  const CalibrationVector nominal = sample_nominal(design);
  const CalibrationMask free48 = model_free_mask(CalibrationModelKind::k48);
  MeasurementSimulationOptions sim_options;
  sim_options.seed = 7;
  sim_options.num_poses = 60;
  sim_options.num_outliers = 3;
  const SimulatedMeasurements sim = simulate_measurements(design, nominal, free48, sim_options);
  std::vector<CalibrationMeasurement> fit, held_out, held_out_gross;
  std::vector<int> fit_outliers;
  for (int k = 0; k < 60; ++k) {
    const bool is_outlier =
        std::find(sim.outliers.begin(), sim.outliers.end(), k) != sim.outliers.end();
    if (k % 4 == 3 && !is_outlier) {
      held_out.push_back(sim.measurements[static_cast<std::size_t>(k)]);
    } else if (k % 4 == 1 && is_outlier) {
      held_out_gross.push_back(sim.measurements[static_cast<std::size_t>(k)]);
    } else {
      if (is_outlier) fit_outliers.push_back(static_cast<int>(fit.size()));
      fit.push_back(sim.measurements[static_cast<std::size_t>(k)]);
    }
  }
  ASSERT_EQ(fit_outliers.size() + held_out_gross.size(), 3u);
  ASSERT_GE(held_out_gross.size(), 1u);
  CalibrationOptions options;
  options.free = free48;
  options.sigma_position = sim.mean_position_sigma;
  options.sigma_orientation = sim_options.orientation_sigma;
  options.sigma_actuator = sim_options.actuator_sigma;
  const CalibrationResult result = calibrate(design, nominal, fit, options);
  EXPECT_EQ(result.outliers, fit_outliers);

  const auto held = all_indices(held_out.size());
  const CalibrationErrors before = calibration_errors(design, nominal, held_out, held);
  const CalibrationErrors after = calibration_errors(design, result.estimate, held_out, held);
  EXPECT_EQ(after.fk_failures, 0);
  // Nominal misses by millimetres; calibrated within a few times the instrument noise.
  EXPECT_GT(before.tcp_position_rms, 5e-4);
  EXPECT_LT(after.tcp_position_rms, 3.0 * std::sqrt(3.0) * sim.mean_position_sigma);
  EXPECT_LT(after.tcp_position_rms, 0.05 * before.tcp_position_rms);
  EXPECT_LT(result.chi2_per_dof, 1.5);
  EXPECT_GT(result.chi2_per_dof, 0.5);

  // Held-out screening with the calibrated machine: the clean held-out poses pass, the gross
  // ones (1 mm against ~20 um noise) are flagged.
  const std::vector<double> clean_chi2 =
      fixed_machine_chi2(design.tcp, result.estimate, held_out, held, options);
  ASSERT_EQ(clean_chi2.size(), held_out.size());
  for (double chi2 : clean_chi2) EXPECT_LT(chi2, options.outlier_chi2);
  const std::vector<double> gross_chi2 = fixed_machine_chi2(
      design.tcp, result.estimate, held_out_gross, all_indices(held_out_gross.size()), options);
  for (double chi2 : gross_chi2) EXPECT_GT(chi2, options.outlier_chi2);
}

// On noise-free data the screening chi^2 of a pose on the true machine is zero. Shifting a
// measured position by 3 sigma along x gives, to first order, chi^2 = r^T (I - P_B) r with r the
// residual at the true pose (3 in the x-position row) and P_B the projection onto the pose
// Jacobian's columns: the fitted pose absorbs the part of the shift the legs allow.
TEST(Calibration, HeldOutScreeningChi2OnExactAndShiftedPoses) {
  const HexapodDesign design = sample_hexapod();
  const CalibrationVector nominal = sample_nominal(design);
  const SimulatedMeasurements sim = simulate_measurements(
      design, nominal, model_free_mask(CalibrationModelKind::k48), noise_free(13, 5));
  CalibrationOptions options;
  const auto all = all_indices(sim.measurements.size());
  for (double chi2 : fixed_machine_chi2(design.tcp, sim.truth, sim.measurements, all, options)) {
    EXPECT_LT(chi2, 1e-12);
  }
  std::vector<CalibrationMeasurement> shifted = sim.measurements;
  for (auto& m : shifted) m.pose.position.x() += 3.0 * options.sigma_position;
  const std::vector<double> chi2 = fixed_machine_chi2(design.tcp, sim.truth, shifted, all, options);
  for (std::size_t k = 0; k < shifted.size(); ++k) {
    const Eigen::Matrix<double, 12, 1> r =
        calibration_residuals(sim.truth, design.tcp, shifted[k], sim.true_poses[k], options);
    const Eigen::Matrix<double, 12, 6> B =
        calibration_pose_jacobian(sim.truth, design.tcp, shifted[k], sim.true_poses[k], options);
    const Eigen::Matrix<double, 12, 1> projected =
        B * (B.transpose() * B).ldlt().solve(B.transpose() * r);
    const double predicted = (r - projected).squaredNorm();
    EXPECT_NEAR(r.squaredNorm(), 9.0, 1e-9);
    EXPECT_NEAR(chi2[k], predicted, 1e-3 * predicted) << "pose " << k;
    EXPECT_LT(chi2[k], 9.0);
  }
}

TEST(Calibration, TooFewPosesIsAnError) {
  const HexapodDesign design = sample_hexapod();
  const CalibrationVector nominal = sample_nominal(design);
  const SimulatedMeasurements sim = simulate_measurements(
      design, nominal, model_free_mask(CalibrationModelKind::k48), noise_free(3, 7));
  CalibrationOptions options;
  try {
    calibrate(design, nominal, sim.measurements, options);
    FAIL() << "expected CalibrationError";
  } catch (const CalibrationError& e) {
    EXPECT_NE(std::string(e.what()).find("too few poses"), std::string::npos) << e.what();
  }
}

// Pure translations cannot separate a_i from b_i: the error names the joints.
TEST(Calibration, NonIdentifiableParametersAreNamed) {
  const HexapodDesign design = sample_hexapod();
  const CalibrationVector nominal = sample_nominal(design);
  MeasurementSimulationOptions sim_options = noise_free(4, 20);
  sim_options.angle_range = 0.0;
  const SimulatedMeasurements sim = simulate_measurements(
      design, nominal, model_free_mask(CalibrationModelKind::k42), sim_options);
  CalibrationOptions options;
  options.free = model_free_mask(CalibrationModelKind::k42);
  try {
    calibrate(design, nominal, sim.measurements, options);
    FAIL() << "expected CalibrationError";
  } catch (const CalibrationError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("rank 24"), std::string::npos) << message;
    EXPECT_NE(message.find("a1.x"), std::string::npos) << message;
    EXPECT_NE(message.find("b1.x"), std::string::npos) << message;
  }
}

// With the instrument and target transforms free, 12 frame freedoms exist: left free they are
// detected; fixed by choose_gauge_fixing the calibration reproduces the measurements exactly.
TEST(Calibration, GaugeFreedomDetectedAndFixed) {
  const HexapodDesign design = sample_hexapod();
  const CalibrationVector nominal = nominal_calibration_vector(
      design, Vec6<double>::Constant(0.7), Pose{{2.5, 0.5, 0.4}, {0.0, 0.0, 0.3}},
      Pose{{0.0, 0.0, 0.05}, {0.0, 0.0, 0.0}});
  CalibrationMask free = model_free_mask(CalibrationModelKind::k48);
  for (int i = kCalibrationInstrumentIndex; i < kCalibrationParameters; ++i) {
    free[static_cast<std::size_t>(i)] = true;
  }
  const SimulatedMeasurements sim = simulate_measurements(design, nominal, free, noise_free(9, 40));
  CalibrationOptions options;
  options.free = free;
  options.loss = CalibrationLoss::kNone;
  try {
    calibrate(design, nominal, sim.measurements, options);
    FAIL() << "expected CalibrationError";
  } catch (const CalibrationError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("rank 48 for 60"), std::string::npos) << message;
    EXPECT_NE(message.find("instrument.x"), std::string::npos) << message;
    EXPECT_NE(message.find("target.x"), std::string::npos) << message;
  }
  const std::vector<int> gauge =
      choose_gauge_fixing(nominal, design.tcp, sim.measurements, options);
  ASSERT_EQ(gauge.size(), 12u);
  int base_fixed = 0, platform_fixed = 0;
  for (int index : gauge) {
    ASSERT_LT(index, kCalibrationMachineParameters);
    ASSERT_LT(index % 8, 6);
    (index % 8 < 3 ? base_fixed : platform_fixed) += 1;
    options.free[static_cast<std::size_t>(index)] = false;
  }
  EXPECT_EQ(base_fixed, 6);
  EXPECT_EQ(platform_fixed, 6);
  const CalibrationResult result = calibrate(design, nominal, sim.measurements, options);
  EXPECT_EQ(result.identification.rank, 48);
  for (int index : gauge) EXPECT_EQ(result.estimate(index), nominal(index));
  const auto all = all_indices(sim.measurements.size());
  const CalibrationErrors after =
      calibration_errors(design, result.estimate, sim.measurements, all);
  EXPECT_LT(after.leg_rms.maxCoeff(), 1e-9);
  EXPECT_LT(after.tcp_position_max, 1e-9);
}

TEST(PoseSelection, DOptimalBeatsFirstPosesAndIdentifies) {
  const HexapodDesign design = sample_hexapod();
  const CalibrationVector nominal = sample_nominal(design);
  const SimulatedMeasurements candidates =
      simulate_measurements(design, nominal, CalibrationMask{}, noise_free(21, 120));
  CalibrationOptions options;
  const int count = 15;
  const PoseSelection selection =
      select_calibration_poses(nominal, design.tcp, candidates.true_poses, count, options);
  ASSERT_EQ(selection.selected.size(), static_cast<std::size_t>(count));
  EXPECT_EQ(selection.identification.rank, 48);
  // The first `count` candidates (a random design) identify less.
  std::vector<CalibrationMeasurement> first(candidates.measurements.begin(),
                                            candidates.measurements.begin() + count);
  std::vector<Pose> first_poses(candidates.true_poses.begin(),
                                candidates.true_poses.begin() + count);
  const Identification random_design = identify(nominal, design.tcp, first, first_poses, options);
  const Eigen::VectorXd& s = selection.identification.singular_values;
  EXPECT_NEAR(selection.log_det, 2.0 * s.array().log().sum(), 1e-6 * std::abs(selection.log_det));
  EXPECT_GT(selection.log_det, 2.0 * random_design.singular_values.array().log().sum());
  EXPECT_GT(selection.identification.O1, random_design.O1);
  EXPECT_THROW(select_calibration_poses(nominal, design.tcp, candidates.true_poses, 8, options),
               CalibrationError);
}

TEST(Simulation, IsDeterministicForASeed) {
  const HexapodDesign design = sample_hexapod();
  const CalibrationVector nominal = sample_nominal(design);
  MeasurementSimulationOptions sim_options;
  sim_options.num_poses = 10;
  const auto a = simulate_measurements(design, nominal, model_free_mask(CalibrationModelKind::k48),
                                       sim_options);
  const auto b = simulate_measurements(design, nominal, model_free_mask(CalibrationModelKind::k48),
                                       sim_options);
  EXPECT_EQ(a.truth, b.truth);
  for (int k = 0; k < 10; ++k) {
    EXPECT_EQ(a.measurements[k].pose.position, b.measurements[k].pose.position);
    EXPECT_EQ(a.measurements[k].stroke, b.measurements[k].stroke);
  }
  EXPECT_EQ(a.outliers.size(), 3u);
}

// Pose selection on a machine with a non-finite parameter (a zero length of nan) is refused,
// never an out-of-range index.
TEST(Calibration, PoseSelectionRefusesNonFiniteParameters) {
  const HexapodDesign design = sample_hexapod();
  const CalibrationVector nominal =
      nominal_calibration_vector(design, Vec6<double>::Constant(std::nan("")));
  const SimulatedMeasurements sim =
      simulate_measurements(design, sample_nominal(design),
                            model_free_mask(CalibrationModelKind::k42), noise_free(3, 20));
  CalibrationOptions options;
  options.free = model_free_mask(CalibrationModelKind::k42);
  EXPECT_THROW(select_calibration_poses(nominal, design.tcp, sim.true_poses, 10, options),
               CalibrationError);
}

// Two measurement campaigns a day apart: the second re-homed its legs, so its readings start
// from other zeros (shifts up to 1.9 mm). Labelled as a campaign, the shifts are estimated with
// one geometry: exactly on noise-free data, within their sigmas with noise (the held-out poses
// of the second campaign then at the noise floor); unlabelled, no geometry fits both.
std::vector<CalibrationMeasurement> rehomed(const SimulatedMeasurements& sim,
                                            const Vec6<double>& shift, bool labelled) {
  std::vector<CalibrationMeasurement> measurements = sim.measurements;
  for (std::size_t k = measurements.size() / 2; k < measurements.size(); ++k) {
    for (int i = 0; i < 6; ++i)
      measurements[k].stroke(i) -= shift(i) / (1.0 + sim.truth(kCalibrationLegParameters * i + 7));
    if (labelled) measurements[k].campaign = 1;
  }
  return measurements;
}

TEST(Calibration, CampaignShiftsAreRecovered) {
  const HexapodDesign design = sample_hexapod();
  const CalibrationVector nominal = sample_nominal(design);
  const CalibrationMask free = model_free_mask(CalibrationModelKind::k48);
  Vec6<double> shift;
  shift << 1.9e-3, -0.7e-3, 0.4e-3, 0.0, -1.2e-3, 0.8e-3;
  {
    const SimulatedMeasurements sim =
        simulate_measurements(design, nominal, free, noise_free(21, 60));
    CalibrationOptions options;
    options.free = free;
    options.estimate_noise = false;
    const CalibrationResult r = calibrate(design, nominal, rehomed(sim, shift, true), options);
    ASSERT_EQ(r.campaign_shifts.size(), 1u);
    for (int i = 0; i < 6; ++i) EXPECT_NEAR(r.campaign_shifts[0](i), shift(i), 1e-9) << i;
    for (int i = 0; i < kCalibrationMachineParameters; ++i)
      EXPECT_NEAR(r.estimate(i), sim.truth(i), 1e-9) << calibration_parameter_name(i);
    EXPECT_TRUE(r.outliers.empty());
  }
  MeasurementSimulationOptions noisy = noise_free(22, 80);
  noisy.tracker_sigma = 15e-6;
  noisy.orientation_sigma = 5e-5;
  noisy.actuator_sigma = 1e-6;
  const SimulatedMeasurements sim = simulate_measurements(design, nominal, free, noisy);
  CalibrationOptions options;
  options.free = free;
  // Sigmas guessed wrong by 5 and 10 times: the noise comes from the data.
  options.sigma_position = 3e-6;
  options.sigma_orientation = 5e-4;
  std::vector<CalibrationMeasurement> labelled = rehomed(sim, shift, true);
  // Every 4th row of each campaign held out.
  std::vector<CalibrationMeasurement> fit;
  std::vector<int> held;
  for (std::size_t k = 0; k < labelled.size(); ++k) {
    if (k % 4 == 3) {
      held.push_back(static_cast<int>(k));
    } else {
      fit.push_back(labelled[k]);
    }
  }
  const CalibrationResult r = calibrate(design, nominal, fit, options);
  ASSERT_EQ(r.campaign_shifts.size(), 1u);
  for (int i = 0; i < 6; ++i) {
    EXPECT_GT(r.campaign_shift_sigma[0](i), 0.0);
    EXPECT_NEAR(r.campaign_shifts[0](i), shift(i), 4.0 * r.campaign_shift_sigma[0](i)) << i;
  }
  EXPECT_LE(r.outliers.size(), 1u);
  const std::vector<CalibrationMeasurement> shifted = with_campaign_shifts(labelled, r);
  std::vector<int> held_second;
  for (int k : held)
    if (labelled[static_cast<std::size_t>(k)].campaign == 1) held_second.push_back(k);
  const CalibrationErrors errors = calibration_errors(design, r.estimate, shifted, held_second);
  EXPECT_GT(errors.count, 5);
  EXPECT_EQ(errors.fk_failures, 0);
  // The noise floor sqrt(3) sigma is 26 um here; a 1.9 mm zero error would show as ~1 mm.
  EXPECT_LT(errors.tcp_position_rms, 2.0 * std::sqrt(3.0) * 15e-6);
  // Unlabelled, the same data cannot be fitted by one geometry: most poses are rejected, so many
  // that the fit is refused.
  std::size_t rejected = 0;
  try {
    rejected = calibrate(design, nominal, rehomed(sim, shift, false), options).outliers.size();
  } catch (const CalibrationError&) {
    rejected = sim.measurements.size();
  }
  EXPECT_GT(rejected, 20u);
  // Without fitted poses of the reference campaign, or with fewer than 3 of another, the shifts
  // cannot be told from the offsets: refused.
  std::vector<CalibrationMeasurement> no_reference = labelled;
  for (CalibrationMeasurement& m : no_reference) m.campaign = 1;
  EXPECT_THROW(calibrate(design, nominal, no_reference, options), CalibrationError);
  std::vector<CalibrationMeasurement> two = rehomed(sim, shift, false);
  two[0].campaign = two[1].campaign = 1;
  EXPECT_THROW(calibrate(design, nominal, two, options), CalibrationError);
}

}  // namespace
}  // namespace pkmopt
