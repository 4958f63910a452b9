// The SIMD batch path of the hexapod metric set (models/hexapod_batch.hpp), on the same poses
// and wrench as BM_HexapodMetricsOneThread in hexapod_bench.cpp so the two compare directly.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cstdint>
#include <vector>

#include "models/hexapod_batch.hpp"
#include "models/sample_machines.hpp"

namespace {

// The poses of hexapod_bench.cpp (splitmix64, seed 12345).
std::vector<pkmopt::Pose> bench_poses(std::size_t n) {
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

std::vector<pkmopt::PoseMetrics> sized_metrics(std::size_t n) {
  std::vector<pkmopt::PoseMetrics> metrics(n);
  for (auto& m : metrics) {
    m.q.resize(6);
    m.tau.resize(6);
  }
  return metrics;
}

// One thread, the 4096 poses of BM_HexapodMetricsOneThread per iteration; items = poses.
void run_one_thread(benchmark::State& state, pkmopt::HexapodBatchKernel kernel) {
  const pkmopt::Hexapod hexapod(pkmopt::sample_machines::conventions_hexapod_design());
  const auto poses = bench_poses(4096);
  auto metrics = sized_metrics(poses.size());
  const pkmopt::Wrench wrench = pkmopt::Wrench::Constant(100);
  std::size_t scalar_poses = 0;
  for (auto _ : state) {
    scalar_poses = pkmopt::analyze_hexapod_batch(hexapod, poses.data(), poses.size(), wrench,
                                                 metrics.data(), kernel);
    benchmark::DoNotOptimize(metrics.data());
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()) *
                          static_cast<std::int64_t>(poses.size()));
  state.counters["scalar_poses"] = static_cast<double>(scalar_poses);
}

void BM_HexapodMetricsBatchSimdOneThread(benchmark::State& state) {
  run_one_thread(state, pkmopt::HexapodBatchKernel::automatic);
  state.counters["avx2"] = pkmopt::hexapod_batch_uses_avx2() ? 1 : 0;
}
BENCHMARK(BM_HexapodMetricsBatchSimdOneThread)->Unit(benchmark::kMicrosecond);

void BM_HexapodMetricsBatchBaselineOneThread(benchmark::State& state) {
  run_one_thread(state, pkmopt::HexapodBatchKernel::baseline);
}
BENCHMARK(BM_HexapodMetricsBatchBaselineOneThread)->Unit(benchmark::kMicrosecond);

// The 1e6-pose batch with OpenMP is BM_HexapodAnalyzeBatch (hexapod_bench.cpp).

}  // namespace
