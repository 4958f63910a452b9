// Calibration of the 48-parameter hexapod model from 100 simulated laser-tracker poses
// (robust fit, outlier rejection, inlier refit, covariance, identification). Goal: < 50 ms.
// Variants: without covariance, and with Ceres' own covariance (SPARSE_QR on the full problem)
// instead of the one from the identification SVD.
#include <benchmark/benchmark.h>

#include "problems/calibration.hpp"

namespace {

pkmopt::HexapodDesign bench_hexapod() {
  using pkmopt::deg_to_rad;
  pkmopt::HexapodDesign design =
      pkmopt::semi_regular_hexapod(0.60, deg_to_rad(20.0), 0.25, deg_to_rad(20.0));
  design.min_length = 0.70;
  design.max_length = 1.15;
  design.stiffness.E = 2.1e11;
  design.stiffness.area = 3e-4;
  design.stiffness.actuator_stiffness = 2e8;
  design.joints.base_max_angle = deg_to_rad(45.0);
  design.joints.platform_max_angle = deg_to_rad(45.0);
  design.tcp = Eigen::Vector3d(0, 0, -0.10);
  return design;
}

void run(benchmark::State& state, bool covariance,
         pkmopt::CalibrationCovarianceMethod method =
             pkmopt::CalibrationCovarianceMethod::kReducedInformation) {
  const pkmopt::HexapodDesign design = bench_hexapod();
  const pkmopt::CalibrationVector nominal =
      pkmopt::nominal_calibration_vector(design, pkmopt::Vec6<double>::Constant(0.7));
  const auto free48 = pkmopt::model_free_mask(pkmopt::CalibrationModelKind::k48);
  pkmopt::MeasurementSimulationOptions sim;
  sim.seed = 42;
  sim.num_poses = static_cast<int>(state.range(0));
  sim.num_outliers = 3;
  const auto data = pkmopt::simulate_measurements(design, nominal, free48, sim);
  pkmopt::CalibrationOptions options;
  options.free = free48;
  options.sigma_position = data.mean_position_sigma;
  options.compute_covariance = covariance;
  options.covariance_method = method;
  int iterations = 0;
  for (auto _ : state) {
    const auto result = pkmopt::calibrate(design, nominal, data.measurements, options);
    iterations = result.iterations;
    benchmark::DoNotOptimize(result.estimate.data());
  }
  state.counters["solver_iterations"] = iterations;
}

void BM_Calibrate48(benchmark::State& state) { run(state, true); }
void BM_Calibrate48NoCovariance(benchmark::State& state) { run(state, false); }
void BM_Calibrate48CeresCovariance(benchmark::State& state) {
  run(state, true, pkmopt::CalibrationCovarianceMethod::kCeres);
}

BENCHMARK(BM_Calibrate48)->Arg(100)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Calibrate48NoCovariance)->Arg(100)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Calibrate48CeresCovariance)->Arg(100)->Unit(benchmark::kMillisecond);

}  // namespace
