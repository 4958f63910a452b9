// Benchmarks of the leg-chain family: analyze over a batch of delta poses (OpenMP, like
// BM_HexapodAnalyzeBatch) and the single-thread cost per pose.
#include <benchmark/benchmark.h>
#include <omp.h>

#include <cstdint>
#include <memory>
#include <vector>

#include "bench/uniform_stream.hpp"
#include "models/leg_chain/leg_chain.hpp"

namespace {

// Poses spread over the delta's working region (seeded splitmix64, reproducible).
std::vector<pkmopt::Pose> delta_poses(std::size_t n) {
  std::vector<pkmopt::Pose> poses(n);
  pkmopt::sample_machines::Uniform uniform(42);
  for (auto& p : poses) {
    p.position = {uniform(-0.4, 0.4), uniform(-0.4, 0.4), uniform(-1.2, -0.8)};
  }
  return poses;
}

void BM_DeltaAnalyzeBatch(benchmark::State& state) {
  const pkmopt::LegChainMachine delta(pkmopt::delta_design(pkmopt::DeltaDesign{}));
  const std::size_t n = static_cast<std::size_t>(state.range(0));
  const std::vector<pkmopt::Pose> poses = delta_poses(n);
  std::vector<pkmopt::PoseMetrics> metrics(n);
  for (auto& m : metrics) {  // output storage is allocated once, outside the timed loop
    m.q.resize(3);
    m.tau.resize(3);
  }
  const pkmopt::Wrench wrench = (pkmopt::Wrench() << 10, -20, -50, 0, 0, 0).finished();
  for (auto _ : state) {
#pragma omp parallel
    {
      const std::unique_ptr<pkmopt::MachineData> data = delta.make_data();
#pragma omp for schedule(static)
      for (std::size_t i = 0; i < n; ++i) delta.analyze(*data, poses[i], wrench, metrics[i]);
    }
    benchmark::DoNotOptimize(metrics.data());
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()) *
                          static_cast<std::int64_t>(n));
  state.counters["threads"] = omp_get_max_threads();
}
BENCHMARK(BM_DeltaAnalyzeBatch)->Arg(1000000)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_DeltaAnalyzeOneThread(benchmark::State& state) {
  const pkmopt::LegChainMachine delta(pkmopt::delta_design(pkmopt::DeltaDesign{}));
  const auto poses = delta_poses(4096);
  const auto data = delta.make_data();
  pkmopt::PoseMetrics m;
  const pkmopt::Wrench wrench = pkmopt::Wrench::Constant(10);
  std::size_t i = 0;
  for (auto _ : state) {
    delta.analyze(*data, poses[i++ & 4095], wrench, m);
    benchmark::DoNotOptimize(m.tcp_error_max);
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_DeltaAnalyzeOneThread);

void BM_HexaglideAnalyzeOneThread(benchmark::State& state) {
  const pkmopt::LegChainMachine glide(pkmopt::hexaglide_design(pkmopt::HexaglideDesign{}));
  const auto data = glide.make_data();
  pkmopt::PoseMetrics m;
  const pkmopt::Wrench wrench = pkmopt::Wrench::Constant(10);
  pkmopt::Pose pose;
  pose.position = {0.02, -0.03, 0.6};
  pose.angles = {0.02, -0.03, 0.05};
  for (auto _ : state) {
    glide.analyze(*data, pose, wrench, m);
    benchmark::DoNotOptimize(m.tcp_error_max);
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_HexaglideAnalyzeOneThread);

// A tilted 3-PRS head: the parasitic solve (Newton, 3x3) and T = -G_p^-1 G_d on top of analyze.
void BM_Tripod3PrsAnalyzeOneThread(benchmark::State& state) {
  const pkmopt::LegChainMachine tripod(pkmopt::tripod_3prs_design(pkmopt::Tripod3PrsDesign{}));
  const auto data = tripod.make_data();
  pkmopt::PoseMetrics m;
  const pkmopt::Wrench wrench = pkmopt::Wrench::Constant(10);
  pkmopt::Pose pose;
  pose.position = {0.0, 0.0, 1.2};
  pose.angles = {0.3, -0.2, 0.0};
  for (auto _ : state) {
    tripod.analyze(*data, pose, wrench, m);
    benchmark::DoNotOptimize(m.tcp_error_max);
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_Tripod3PrsAnalyzeOneThread);

}  // namespace
