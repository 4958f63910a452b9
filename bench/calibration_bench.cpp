// Calibration of the 48-parameter hexapod model from 100 simulated laser-tracker poses
// (robust fit, outlier rejection, inlier refit, covariance, identification). Goal: < 50 ms.
// Variants: without covariance, and with Ceres' own covariance (SPARSE_QR on the full problem)
// instead of the one from the identification SVD.
#include <benchmark/benchmark.h>

#include "models/sample_machines.hpp"
#include "problems/calibration/calibration.hpp"

namespace {

pkmopt::HexapodDesign bench_hexapod() {
  return pkmopt::sample_machines::conventions_hexapod_design();
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
