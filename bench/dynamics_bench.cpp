// Natural frequencies of a hexapod (models/dynamics/machine_dynamics.hpp, docs/dynamics.md): the
// cost of the TCP mass matrix and the generalized eigenproblem per pose on the scalar path, of a
// whole scalar analyze with a mass model, and of the SIMD batch (models/hexapod/hexapod_batch.hpp)
// over 10^6 poses on one core: every metric and the six frequencies. Items = poses.
#include <benchmark/benchmark.h>

#include <vector>

#include "bench/hexapod_poses.hpp"
#include "models/dynamics/machine_dynamics.hpp"
#include "models/hexapod/hexapod.hpp"
#include "models/hexapod/hexapod_batch.hpp"
#include "models/sample_machines.hpp"

namespace {

// The conventions hexapod with the masses of examples/hexapod_masses.yaml.
pkmopt::Hexapod hexapod_with_masses() {
  pkmopt::HexapodDesign d = pkmopt::sample_machines::conventions_hexapod_design();
  d.masses = pkmopt::sample_machines::milling_hexapod_masses();
  return pkmopt::Hexapod(d);
}

std::vector<pkmopt::Pose> poses(std::size_t n) {
  return pkmopt::sample_machines::hexapod_bench_poses(n);
}

// The frequency step alone: M at the pose and the eigenproblem from the pose's compliance.
void BM_HexapodNaturalFrequencies(benchmark::State& state) {
  const pkmopt::Hexapod hexapod = hexapod_with_masses();
  const std::vector<pkmopt::Pose> p = poses(1024);
  std::vector<pkmopt::Matrix6d> compliance;
  pkmopt::HexapodData data(hexapod);
  for (const pkmopt::Pose& pose : p) {
    pkmopt::PoseMetrics m;
    hexapod.analyze(data, pose, pkmopt::Wrench::Zero(), m);
    compliance.emplace_back(data.matrices.compliance);
  }
  std::size_t i = 0;
  for (auto _ : state) {
    const std::size_t k = i++ & 1023;
    const pkmopt::NaturalModes modes =
        pkmopt::natural_frequencies6(compliance[k], hexapod.mass_matrix(p[k]));
    benchmark::DoNotOptimize(modes.frequencies.data());
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_HexapodNaturalFrequencies);

// analyze with the mass model: every metric and the six frequencies.
void BM_HexapodAnalyzeWithMassesOneThread(benchmark::State& state) {
  const pkmopt::Hexapod hexapod = hexapod_with_masses();
  const std::vector<pkmopt::Pose> p = poses(1024);
  pkmopt::HexapodData data(hexapod);
  pkmopt::PoseMetrics m;
  std::size_t i = 0;
  for (auto _ : state) {
    hexapod.analyze(data, p[i++ & 1023], pkmopt::Wrench::Constant(100), m);
    benchmark::DoNotOptimize(m.natural_frequencies.data());
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_HexapodAnalyzeWithMassesOneThread);

// The SIMD batch with the mass model on one core: 10^6 poses, metrics and frequencies.
void BM_HexapodBatchNaturalFrequenciesOneCore(benchmark::State& state) {
  const pkmopt::Hexapod hexapod = hexapod_with_masses();
  const std::size_t n = static_cast<std::size_t>(state.range(0));
  const std::vector<pkmopt::Pose> p = poses(n);
  std::vector<pkmopt::PoseMetrics> metrics(n);
  const pkmopt::Wrench wrench = (pkmopt::Wrench() << 100, -200, -1500, 10, 20, 5).finished();
  std::size_t scalar_poses = 0;
  for (auto _ : state) {
    scalar_poses = pkmopt::analyze_hexapod_batch(hexapod, p.data(), n, wrench, metrics.data());
    benchmark::DoNotOptimize(metrics.data());
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()) *
                          static_cast<std::int64_t>(n));
  state.counters["avx2"] = pkmopt::hexapod_batch_uses_avx2() ? 1 : 0;
  state.counters["scalar_share"] = static_cast<double>(scalar_poses) / static_cast<double>(n);
}
BENCHMARK(BM_HexapodBatchNaturalFrequenciesOneCore)
    ->Arg(1000000)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

}  // namespace
