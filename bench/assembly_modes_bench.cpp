// All assembly modes of a Gough–Stewart platform (models/hexapod/assembly_modes.hpp): one solve
// (40 paths from the random complex start geometry) for the example hexapod at a pose 0.9 m above
// its base, on one core, and the solver of one geometry solved again and again. The anchor: about
// 12 ms per solve for published elimination-template code in Python; the goal is 2 ms.
//   build/bin/pkmopt_bench --benchmark_filter=AssemblyMode
#include <benchmark/benchmark.h>

#include <Eigen/Geometry>

#include "models/hexapod/assembly_modes.hpp"
#include "models/hexapod/hexapod.hpp"
#include "models/sample_machines.hpp"

namespace pkmopt {
namespace {

void BM_AllAssemblyModes(benchmark::State& state) {
  const Hexapod hexapod(sample_machines::conventions_hexapod_design());
  const Pose pose{{0.01, -0.02, 0.9}, {0.05, -0.03, 0.02}};
  const Eigen::Matrix<double, 6, 1> lengths = hexapod.inverse_kinematics(pose);
  const Eigen::Matrix<double, 3, 6> base = hexapod.design().base_joints;
  const Eigen::Matrix<double, 3, 6> platform = hexapod.platform_rel_tcp();
  all_assembly_modes(base, platform, lengths);  // the one-time start outside the timing
  std::size_t real = 0;
  for (auto _ : state) {
    const AssemblyModes modes = all_assembly_modes(base, platform, lengths);
    real = modes.real.size();
    benchmark::DoNotOptimize(real);
  }
  state.counters["real_modes"] = static_cast<double>(real);
}
BENCHMARK(BM_AllAssemblyModes)->Unit(benchmark::kMillisecond);

// One geometry solved again and again (AssemblyModeSolver, as Hexapod::all_forward_kinematics
// and a trajectory use it): the sample hexapod (planar base and platform: 28 finite solutions,
// 12 at infinity) and a general geometry with 40 finite solutions, at poses 0.2 m and 0.3 rad
// from the start.
void BM_AssemblyModeSolver(benchmark::State& state) {
  const Hexapod hexapod(sample_machines::conventions_hexapod_design());
  Eigen::Matrix<double, 3, 6> base = hexapod.design().base_joints;
  Eigen::Matrix<double, 3, 6> platform = hexapod.platform_rel_tcp();
  if (state.range(0) == 1) {  // joints off the planes: a general geometry
    const double lift[6] = {0.05, -0.03, 0.08, -0.06, 0.02, -0.07};
    for (int i = 0; i < 6; ++i) {
      base(2, i) += lift[i];
      platform(2, i) -= 0.5 * lift[(i + 3) % 6];
    }
  }
  auto lengths_at = [&](const Eigen::Vector3d& p, const Eigen::Vector3d& angles) {
    const Eigen::Matrix3d R = rotation_zyx(angles);
    Eigen::Matrix<double, 6, 1> lengths;
    for (int i = 0; i < 6; ++i) lengths(i) = (p + R * platform.col(i) - base.col(i)).norm();
    return lengths;
  };
  const AssemblyModeSolver solver(base, platform, lengths_at({0.0, 0.0, 0.9}, {0.0, 0.0, 0.0}));
  const Eigen::Matrix<double, 6, 1> lengths = lengths_at({0.1, -0.15, 0.95}, {0.2, -0.15, 0.15});
  std::size_t real = 0;
  for (auto _ : state) {
    const AssemblyModes modes = solver.solve(lengths);
    real = modes.real.size();
    benchmark::DoNotOptimize(real);
  }
  state.counters["real_modes"] = static_cast<double>(real);
  state.counters["finite"] = static_cast<double>(solver.finite_solutions());
}
BENCHMARK(BM_AssemblyModeSolver)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace pkmopt
