// Serial 5-axis machines (models/serial/serial_machine.hpp): one tilted pose of the 641236
// example machine. Run: build/bin/pkmopt_bench --benchmark_filter=Serial
//   SerialAnalyzeOneThread            every metric under a wrench (the loaded compliance's K_g
//                                     included)
//   SerialAnalyzeNoComplianceOneThread  q, tau, stiffness_min, margin, tcp_error_max (a design
//                                     problem's call)
//   SerialReachableOneThread          the closed-form IK and the range check (the workspace's call)
#include <benchmark/benchmark.h>

#include "io/format/yaml_reader.hpp"
#include "io/machine/machine_file_serial.hpp"
#include "models/serial/serial_machine.hpp"

namespace {

pkmopt::SerialMachine example_machine() {
  return pkmopt::SerialMachine(pkmopt::read_serial_design(pkmopt::YamlValue::load_file(
      std::string(PKMOPT_SOURCE_DIR) + "/examples/serial_641236.yaml")));
}

const pkmopt::Pose kTilted{{0.1, 0.05, 0.2}, {0.3, -0.2, 0.1}};

void analyze(benchmark::State& state, bool compliance) {
  const pkmopt::SerialMachine machine = example_machine();
  const auto data = machine.make_data();
  data->compliance_metrics = compliance;
  pkmopt::PoseMetrics m;
  const pkmopt::Wrench wrench = pkmopt::Wrench::Constant(100);
  for (auto _ : state) {
    machine.analyze(*data, kTilted, wrench, m);
    benchmark::DoNotOptimize(m.tcp_error_max);
  }
  state.SetItemsProcessed(state.iterations());
}

void BM_SerialAnalyzeOneThread(benchmark::State& state) { analyze(state, true); }
BENCHMARK(BM_SerialAnalyzeOneThread);

void BM_SerialAnalyzeNoComplianceOneThread(benchmark::State& state) { analyze(state, false); }
BENCHMARK(BM_SerialAnalyzeNoComplianceOneThread);

void BM_SerialReachableOneThread(benchmark::State& state) {
  const pkmopt::SerialMachine machine = example_machine();
  const auto data = machine.make_data();
  for (auto _ : state) benchmark::DoNotOptimize(machine.reachable(*data, kTilted));
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_SerialReachableOneThread);

}  // namespace
