// Benchmarks of hybrid machines (models/hybrid/hybrid_machine.hpp): the cost per pose of analyze on
// a long X axis carrying the sample hexapod (follow rule, series compliance, 2^6 error vertices)
// against the bare hexapod, and on a gantry X/Y carrying a 3-PRS head (parasitic compensation).
#include <benchmark/benchmark.h>

#include <cstdint>
#include <memory>
#include <vector>

#include "bench/uniform_stream.hpp"
#include "models/hexapod/hexapod.hpp"
#include "models/hybrid/hybrid_machine.hpp"
#include "models/leg_chain/leg_chain.hpp"
#include "models/sample_machines.hpp"

namespace {

// Poses about a centre (seeded splitmix64, reproducible).
std::vector<pkmopt::Pose> poses_about(const Eigen::Vector3d& centre, const Eigen::Vector3d& spread,
                                      double max_angle_deg, std::size_t n) {
  std::vector<pkmopt::Pose> poses(n);
  pkmopt::sample_machines::Uniform uniform(7);
  for (auto& p : poses) {
    for (int k = 0; k < 3; ++k) p.position(k) = centre(k) + uniform(-spread(k), spread(k));
    p.angles = pkmopt::deg_to_rad(Eigen::Vector3d(uniform(-max_angle_deg, max_angle_deg),
                                                  uniform(-max_angle_deg, max_angle_deg), 0.0));
  }
  return poses;
}

void run(benchmark::State& state, const pkmopt::Machine& machine,
         const std::vector<pkmopt::Pose>& poses) {
  auto data = machine.make_data();
  pkmopt::PoseMetrics metrics;
  const pkmopt::Wrench wrench = (pkmopt::Wrench() << 100, -200, -500, 0, 0, 0).finished();
  std::size_t i = 0;
  for (auto _ : state) {
    machine.analyze(*data, poses[i], wrench, metrics);
    benchmark::DoNotOptimize(metrics.stiffness_min);
    i = (i + 1) % poses.size();
  }
  state.SetItemsProcessed(state.iterations());
}

pkmopt::HybridMachine long_axis_hexapod() {
  pkmopt::HybridDesign d;
  d.chain = pkmopt::SerialChain::from_code("1");
  d.axes = {{-1.0, 1.0, 1.5e8, 5e-6}};
  d.module =
      std::make_shared<pkmopt::Hexapod>(pkmopt::sample_machines::conventions_hexapod_design());
  d.home = {0, 0, 0.9};
  return pkmopt::HybridMachine(d);
}

void BM_HybridBaselineBareHexapodAnalyze(benchmark::State& state) {
  const pkmopt::Hexapod hexapod(pkmopt::sample_machines::conventions_hexapod_design());
  run(state, hexapod, poses_about({0, 0, 0.9}, {0.1, 0.1, 0.05}, 10, 1024));
}
BENCHMARK(BM_HybridBaselineBareHexapodAnalyze);

void BM_HybridLongAxisHexapodAnalyze(benchmark::State& state) {
  const pkmopt::HybridMachine hybrid = long_axis_hexapod();
  run(state, hybrid, poses_about({0, 0, 0.9}, {1.1, 0.1, 0.05}, 10, 1024));
}
BENCHMARK(BM_HybridLongAxisHexapodAnalyze);

void BM_HybridGantryTripodAnalyze(benchmark::State& state) {
  pkmopt::HybridDesign d;
  d.chain = pkmopt::SerialChain::from_code("12");
  d.axes = {{-1.5, 1.5, 1.5e8, 5e-6}, {-1.0, 1.0, 1.5e8, 5e-6}};
  d.module = pkmopt::make_tripod_3prs(pkmopt::Tripod3PrsDesign{});
  d.home = {0, 0, 1.2};
  const pkmopt::HybridMachine hybrid(d);
  run(state, hybrid, poses_about({0, 0, 1.2}, {1.2, 0.8, 0.1}, 20, 1024));
}
BENCHMARK(BM_HybridGantryTripodAnalyze);

}  // namespace
