// Workspace volume of the docs/conventions.md hexapod (constant orientation R = I) against
// the grid resolution. Goal: within 0.5 % of the reference in under 100 ms on 2 cores.
//
// Counters: volume (m^3), rel_error = (volume - reference) / reference, where the reference is a
// 1e7-sample Monte Carlo estimate over the search box (relative standard error about 0.06 %),
// computed once, and its standard error ref_std_error (relative).
//
//   build/bin/pkmopt_bench --benchmark_filter=Workspace
#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdint>
#include <vector>

#include "models/hexapod/hexapod.hpp"
#include "models/sample_machines.hpp"
#include "models/workspace/workspace.hpp"

namespace {

pkmopt::Hexapod sample_hexapod() {
  return pkmopt::Hexapod(pkmopt::sample_machines::conventions_hexapod_design());
}

// splitmix64 uniform doubles in [0, 1), one independent stream per chunk (reproducible for any
// thread count).
double uniform(std::uint64_t& state) {
  std::uint64_t z = (state += 0x9e3779b97f4a7c15ULL);
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  z ^= z >> 31;
  return static_cast<double>(z >> 11) * 0x1.0p-53;
}

struct Reference {
  double volume = 0.0;
  double relative_std_error = 0.0;
};

const Reference& monte_carlo_reference() {
  static const Reference reference = [] {
    const pkmopt::Hexapod hexapod = sample_hexapod();
    const auto box = pkmopt::workspace_search_box(
        hexapod, pkmopt::sample_orientations(pkmopt::OrientationSet{}));
    const std::int64_t chunks = 1000, per_chunk = 10'000;  // 1e7 samples
    std::int64_t hits = 0;
#pragma omp parallel reduction(+ : hits)
    {
      const auto data = hexapod.make_data();
      pkmopt::Pose pose;
#pragma omp for schedule(static)
      for (std::int64_t c = 0; c < chunks; ++c) {
        std::uint64_t state = 0x5eed0000ULL + static_cast<std::uint64_t>(c);
        for (std::int64_t s = 0; s < per_chunk; ++s) {
          for (int a = 0; a < 3; ++a) {
            pose.position(a) = box->min()(a) + (box->max()(a) - box->min()(a)) * uniform(state);
          }
          hits += hexapod.reachable(*data, pose) ? 1 : 0;
        }
      }
    }
    const double n = static_cast<double>(chunks * per_chunk);
    const double p = static_cast<double>(hits) / n;
    return Reference{p * box->volume(), std::sqrt((1 - p) / (p * n))};
  }();
  return reference;
}

// Argument: the grid spacing in mm.
void BM_HexapodWorkspaceVolume(benchmark::State& state) {
  const pkmopt::Hexapod hexapod = sample_hexapod();
  const Reference& reference = monte_carlo_reference();
  pkmopt::WorkspaceOptions options;
  options.resolution = static_cast<double>(state.range(0)) / 1000.0;
  double volume = 0.0;
  for (auto _ : state) {
    volume = pkmopt::workspace_volume(hexapod, options);
    benchmark::DoNotOptimize(volume);
  }
  state.counters["volume"] = volume;
  state.counters["rel_error"] = (volume - reference.volume) / reference.volume;
  state.counters["ref_std_error"] = reference.relative_std_error;
}
BENCHMARK(BM_HexapodWorkspaceVolume)
    ->Arg(40)
    ->Arg(30)
    ->Arg(20)
    ->Arg(15)
    ->Arg(10)
    ->Unit(benchmark::kMillisecond);

// The full analysis (maps, convex hull) at 20 mm, as the CLI runs it.
void BM_HexapodWorkspaceFull(benchmark::State& state) {
  const pkmopt::Hexapod hexapod = sample_hexapod();
  pkmopt::WorkspaceOptions options;
  options.resolution = 0.02;
  for (auto _ : state) {
    const pkmopt::WorkspaceResult result = pkmopt::compute_workspace(hexapod, options);
    benchmark::DoNotOptimize(result.volume);
  }
}
BENCHMARK(BM_HexapodWorkspaceFull)->Unit(benchmark::kMillisecond);

}  // namespace
