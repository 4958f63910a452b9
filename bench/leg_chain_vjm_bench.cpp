// Benchmarks of the leg-chain models with link compliance (models/leg_chain/leg_chain_vjm.cpp): the
// full `analyze` of a 3-PRS tripod (Sprint Z3-like, steel tube struts) and of a delta (elastic
// cranks, parallelogram pairs with a width) per pose, single thread, over random poses of their
// working regions, against the same machines with the axial model. The VJM path must stay above
// 200k tripod poses/s per core (docs/stiffness.md).
#include <benchmark/benchmark.h>

#include <cstdint>
#include <vector>

#include "bench/uniform_stream.hpp"
#include "models/leg_chain/leg_chain.hpp"

namespace {

pkmopt::Tripod3PrsDesign tripod(bool sections) {
  pkmopt::Tripod3PrsDesign t;
  if (sections) t.stiffness.section = pkmopt::tube_section(2.1e11, 8.1e10, 0.08, 0.06);
  return t;
}

pkmopt::DeltaDesign delta(bool sections) {
  pkmopt::DeltaDesign d;
  d.stiffness.actuator_stiffness = 1.5e5;
  if (sections) {
    d.crank_section = pkmopt::BeamSection{7e10, 2.6e10, 6e-4, 1.2e-7, 3.0e-7, 2.0e-7};
    d.stiffness.parallelogram_width = 0.1;
  }
  return d;
}

// Tripod poses: z in [0.9, 1.5] m, rx, ry within +-30 deg (the parasitic x, y, rz solved).
std::vector<pkmopt::Pose> tripod_poses(std::size_t n) {
  pkmopt::sample_machines::Uniform u(11);
  std::vector<pkmopt::Pose> poses(n);
  for (auto& p : poses) {
    p.position = {0.0, 0.0, u(0.9, 1.5)};
    p.angles = {u(-0.52, 0.52), u(-0.52, 0.52), 0.0};
  }
  return poses;
}

std::vector<pkmopt::Pose> delta_poses(std::size_t n) {
  pkmopt::sample_machines::Uniform u(13);
  std::vector<pkmopt::Pose> poses(n);
  for (auto& p : poses) p.position = {u(-0.3, 0.3), u(-0.3, 0.3), u(-1.2, -0.9)};
  return poses;
}

// Arg 0: sections (1, the VJM) or the axial model (0); arg 1: with the compliance metrics (1) or
// only stiffness_min (0, as design studies evaluate).
void run(benchmark::State& state, const pkmopt::LegChainDesign& design,
         const std::vector<pkmopt::Pose>& poses) {
  const pkmopt::LegChainMachine machine(design);
  const auto data = machine.make_data();
  data->compliance_metrics = state.range(1) != 0;
  pkmopt::PoseMetrics m;
  m.q.resize(machine.num_actuators());  // output storage allocated once, outside the loop
  m.tau.resize(machine.num_actuators());
  const pkmopt::Wrench wrench = (pkmopt::Wrench() << 2000, 0, -3000, 0, 0, 0).finished();
  std::size_t i = 0;
  for (auto _ : state) {
    machine.analyze(*data, poses[i++ & 4095], wrench, m);
    benchmark::DoNotOptimize(m.stiffness_min_loaded);
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()));
}

void BM_Tripod3PrsVjmAnalyzeOneThread(benchmark::State& state) {
  run(state, pkmopt::tripod_3prs_design(tripod(state.range(0) != 0)), tripod_poses(4096));
}
BENCHMARK(BM_Tripod3PrsVjmAnalyzeOneThread)
    ->ArgNames({"sections", "metrics"})
    ->ArgsProduct({{0, 1}, {1, 0}});

void BM_DeltaVjmAnalyzeOneThread(benchmark::State& state) {
  run(state, pkmopt::delta_design(delta(state.range(0) != 0)), delta_poses(4096));
}
BENCHMARK(BM_DeltaVjmAnalyzeOneThread)
    ->ArgNames({"sections", "metrics"})
    ->ArgsProduct({{0, 1}, {1, 0}});

}  // namespace
