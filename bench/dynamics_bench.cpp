// Natural frequencies of a hexapod (models/machine_dynamics.hpp, docs/dynamics.md): the cost of
// the TCP mass matrix and the generalized eigenproblem per pose, and of a whole analyze with a
// mass model. Items = poses, one thread.
#include <benchmark/benchmark.h>

#include <vector>

#include "bench/hexapod_poses.hpp"
#include "models/hexapod.hpp"
#include "models/machine_dynamics.hpp"
#include "models/sample_machines.hpp"

namespace {

// The conventions hexapod with the masses of examples/hexapod_masses.yaml.
pkmopt::Hexapod hexapod_with_masses() {
  pkmopt::HexapodDesign d = pkmopt::sample_machines::conventions_hexapod_design();
  d.masses.present = true;
  d.masses.platform.mass = 45.0;
  d.masses.platform.centre_of_mass = {0, 0, -0.04};
  d.masses.platform.inertia = Eigen::Vector3d(1.3, 1.3, 2.0).asDiagonal();
  d.masses.legs.cylinder = {.mass = 6.0, .centre = 0.2, .inertia = 0.125};
  d.masses.legs.rod = {.mass = 3.0, .centre = 0.3, .inertia = 0.0625};
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

}  // namespace
