// Hexapod benchmarks: the full per-pose metric set (everything `pkmopt analyze` writes) over a
// batch of poses, OpenMP-parallel with one HexapodData per thread.
#include <benchmark/benchmark.h>
#include <omp.h>

#include <cstdint>
#include <vector>

#include "models/hexapod.hpp"
#include "models/sample_machines.hpp"

namespace {

pkmopt::Hexapod sample_hexapod() {
  return pkmopt::Hexapod(pkmopt::sample_machines::conventions_hexapod_design());
}

// Deterministic poses spread over the working region (splitmix64).
std::vector<pkmopt::Pose> sample_poses(std::size_t n) {
  std::uint64_t state = 12345;
  auto uniform = [&state](double lo, double hi) {
    std::uint64_t z = (state += 0x9e3779b97f4a7c15ULL);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    z ^= z >> 31;
    return lo + (hi - lo) * static_cast<double>(z >> 11) * 0x1.0p-53;
  };
  std::vector<pkmopt::Pose> poses(n);
  for (auto& p : poses) {
    p.position = {uniform(-0.15, 0.15), uniform(-0.15, 0.15), uniform(0.75, 0.95)};
    p.angles =
        pkmopt::deg_to_rad(Eigen::Vector3d(uniform(-15, 15), uniform(-15, 15), uniform(-20, 20)));
  }
  return poses;
}

void BM_HexapodAnalyzeBatch(benchmark::State& state) {
  const pkmopt::Hexapod hexapod = sample_hexapod();
  const std::size_t n = static_cast<std::size_t>(state.range(0));
  const std::vector<pkmopt::Pose> poses = sample_poses(n);
  std::vector<pkmopt::PoseMetrics> metrics(n);
  for (auto& m : metrics) {  // output storage is allocated once, outside the timed loop
    m.q.resize(6);
    m.tau.resize(6);
  }
  const pkmopt::Wrench wrench = (pkmopt::Wrench() << 100, -200, -1500, 10, 20, 5).finished();
  for (auto _ : state) {
#pragma omp parallel
    {
      pkmopt::HexapodData data(hexapod);
#pragma omp for schedule(static)
      for (std::size_t i = 0; i < n; ++i)
        hexapod.compute_metrics(data, poses[i], wrench, metrics[i]);
    }
    benchmark::DoNotOptimize(metrics.data());
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()) *
                          static_cast<std::int64_t>(n));
  state.counters["threads"] = omp_get_max_threads();
}
BENCHMARK(BM_HexapodAnalyzeBatch)->Arg(1000000)->Unit(benchmark::kMillisecond)->UseRealTime();

// Single-thread cost of each stage, to see where the time goes.
void BM_HexapodKinematicsOnly(benchmark::State& state) {
  const pkmopt::Hexapod hexapod = sample_hexapod();
  const auto poses = sample_poses(4096);
  pkmopt::HexapodData data(hexapod);
  std::size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(hexapod.compute_kinematics(data, poses[i++ & 4095]));
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_HexapodKinematicsOnly);

void BM_HexapodMetricsOneThread(benchmark::State& state) {
  const pkmopt::Hexapod hexapod = sample_hexapod();
  const auto poses = sample_poses(4096);
  pkmopt::HexapodData data(hexapod);
  pkmopt::PoseMetrics m;
  const pkmopt::Wrench wrench = pkmopt::Wrench::Constant(100);
  std::size_t i = 0;
  for (auto _ : state) {
    hexapod.compute_metrics(data, poses[i++ & 4095], wrench, m);
    benchmark::DoNotOptimize(m.tcp_error_max);
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_HexapodMetricsOneThread);

}  // namespace
