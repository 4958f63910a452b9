// Design-study benchmarks: the cost of one design evaluation (aggregate formulation: every
// task pose's metrics, reductions, reachability; and the workspace volume when the study asks
// for it), for the shipped studies (hexapod and leg-chain models). One thread.
#include <benchmark/benchmark.h>

#include <string>
#include <vector>

#include "bench/middle_design.hpp"
#include "studies/design_study.hpp"

namespace {

void evaluate_study_design(benchmark::State& state, const std::string& study_file) {
  const pkmopt::DesignStudy study =
      pkmopt::load_design_study(std::string(PKMOPT_SOURCE_DIR) + "/" + study_file);
  pkmopt_bench::evaluate_middle_design(state, study.optimization_problem());
  state.counters["task_poses"] = static_cast<double>(study.task().poses.size());
  state.SetItemsProcessed(state.iterations());
}

// hexapod-quick: 64 task poses, stiffness, leg forces, machine size, reachability.
void BM_DesignEvaluationHexapodQuick(benchmark::State& state) {
  evaluate_study_design(state, "studies/library/hexapod-quick.yaml");
}
BENCHMARK(BM_DesignEvaluationHexapodQuick)->Unit(benchmark::kMillisecond);

// hexapod-milling (the default study): 64 task poses plus a 50 mm workspace volume.
void BM_DesignEvaluationHexapodMilling(benchmark::State& state) {
  evaluate_study_design(state, "studies/library/hexapod-milling.yaml");
}
BENCHMARK(BM_DesignEvaluationHexapodMilling)->Unit(benchmark::kMillisecond);

// The comparison studies (studies/library/compare-300): 27 task poses each, stiffness, machine
// size, singularity margin, reachability; the leg chains through the generic Machine interface.
void BM_DesignEvaluationCompareHexapod(benchmark::State& state) {
  evaluate_study_design(state, "studies/library/compare-300/hexapod.yaml");
}
BENCHMARK(BM_DesignEvaluationCompareHexapod)->Unit(benchmark::kMicrosecond);

void BM_DesignEvaluationCompareHexaglide(benchmark::State& state) {
  evaluate_study_design(state, "studies/library/compare-300/hexaglide.yaml");
}
BENCHMARK(BM_DesignEvaluationCompareHexaglide)->Unit(benchmark::kMicrosecond);

void BM_DesignEvaluationCompareLinearDelta(benchmark::State& state) {
  evaluate_study_design(state, "studies/library/compare-300/linear-delta.yaml");
}
BENCHMARK(BM_DesignEvaluationCompareLinearDelta)->Unit(benchmark::kMicrosecond);

}  // namespace
