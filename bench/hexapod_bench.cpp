// Hexapod benchmarks: the full per-pose metric set (everything `pkmopt analyze` writes) over a
// batch of poses, OpenMP-parallel with one HexapodData per thread.
#include <benchmark/benchmark.h>
#include <omp.h>

#include <Eigen/Eigenvalues>
#include <Eigen/LU>
#include <Eigen/SVD>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include "bench/hexapod_poses.hpp"
#include "bench/uniform_stream.hpp"
#include "models/hexapod/hexapod.hpp"
#include "models/hexapod/hexapod_batch.hpp"
#include "models/sample_machines.hpp"

namespace {

pkmopt::Hexapod sample_hexapod() {
  return pkmopt::Hexapod(pkmopt::sample_machines::conventions_hexapod_design());
}

std::vector<pkmopt::Pose> sample_poses(std::size_t n) {
  return pkmopt::sample_machines::hexapod_bench_poses(n);
}

// Output storage for n poses, allocated once, outside the timed loops.
std::vector<pkmopt::PoseMetrics> sized_metrics(std::size_t n) {
  std::vector<pkmopt::PoseMetrics> metrics(n);
  for (auto& m : metrics) {
    m.q.resize(6);
    m.tau.resize(6);
  }
  return metrics;
}

// The SIMD batch path (models/hexapod/hexapod_batch.hpp) on one thread: the 4096 poses of
// BM_HexapodMetricsOneThread per iteration, items = poses.
void run_batch_one_thread(benchmark::State& state, pkmopt::HexapodBatchKernel kernel) {
  const pkmopt::Hexapod hexapod = sample_hexapod();
  const auto poses = sample_poses(4096);
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
  run_batch_one_thread(state, pkmopt::HexapodBatchKernel::automatic);
  state.counters["avx2"] = pkmopt::hexapod_batch_uses_avx2() ? 1 : 0;
}
BENCHMARK(BM_HexapodMetricsBatchSimdOneThread)->Unit(benchmark::kMicrosecond);

void BM_HexapodMetricsBatchBaselineOneThread(benchmark::State& state) {
  run_batch_one_thread(state, pkmopt::HexapodBatchKernel::baseline);
}
BENCHMARK(BM_HexapodMetricsBatchBaselineOneThread)->Unit(benchmark::kMicrosecond);

// What `pkmopt analyze` runs on a hexapod: the SIMD batch path (models/hexapod/hexapod_batch.hpp)
// on slices of 1024 poses with OpenMP. Args: {poses, threads (0: all), matrices (1: also write the
// 6x6 compliance and the loaded 3x3 block, as analyze --compliance), legs (1: 80 mm legs, the
// interference check of models/geometry/leg_interference.hpp)}; items = poses, real time.
void BM_HexapodAnalyzeBatch(benchmark::State& state) {
  pkmopt::HexapodDesign design = sample_hexapod().design();
  if (state.range(3) != 0) design.leg_shape.diameter = 0.08;
  // 2: cylinder-and-rod legs with the platform and base plates and a spindle (the solids are
  // checked pose by pose after the SIMD kernel).
  if (state.range(3) == 2) {
    design.leg_shape = {};
    design.leg_shape.cylinder_diameter = 0.09;
    design.leg_shape.cylinder_length = 0.6;
    design.leg_shape.rod_diameter = 0.05;
    design.bodies.platform.radius = 0.28;
    design.bodies.platform.z_max = 0.03;
    design.bodies.base.radius = 0.68;
    design.bodies.base.z_min = -0.04;
    design.bodies.tool = {0.14, {0, 0, 0}, {0, 0, -0.08}};
  }
  const pkmopt::Hexapod hexapod(design);
  const std::size_t n = static_cast<std::size_t>(state.range(0));
  const int threads = state.range(1) > 0 ? static_cast<int>(state.range(1)) : omp_get_max_threads();
  // 1: also the compliance matrices (what analyze --compliance writes)
  std::vector<pkmopt::PoseCompliance> matrices(state.range(2) != 0 ? n : 0);
  const std::vector<pkmopt::Pose> poses = sample_poses(n);
  std::vector<pkmopt::PoseMetrics> metrics = sized_metrics(n);
  const pkmopt::Wrench wrench = (pkmopt::Wrench() << 100, -200, -1500, 10, 20, 5).finished();
  constexpr std::size_t kSlice = 1024;
  std::size_t scalar_poses = 0;
  for (auto _ : state) {
    scalar_poses = 0;
#pragma omp parallel for schedule(static) num_threads(threads) reduction(+ : scalar_poses)
    for (std::size_t start = 0; start < n; start += kSlice) {
      scalar_poses += pkmopt::analyze_hexapod_batch(
          hexapod, poses.data() + start, std::min(kSlice, n - start), wrench,
          metrics.data() + start, pkmopt::HexapodBatchKernel::automatic,
          matrices.empty() ? nullptr : matrices.data() + start);
    }
    benchmark::DoNotOptimize(metrics.data());
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()) *
                          static_cast<std::int64_t>(n));
  state.counters["threads"] = threads;
  state.counters["avx2"] = pkmopt::hexapod_batch_uses_avx2() ? 1 : 0;
  // The share of poses the kernel handed to the scalar path (near-singular, heavy loads).
  state.counters["scalar_share"] = static_cast<double>(scalar_poses) / static_cast<double>(n);
}
BENCHMARK(BM_HexapodAnalyzeBatch)
    ->Args({1000000, 0, 0, 0})
    ->Args({1000000, 1, 0, 0})
    ->Args({1000000, 1, 1, 0})
    ->Args({1000000, 1, 0, 1})
    ->Args({1000000, 1, 0, 2})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

// The same with the scalar fast path (Hexapod::compute_metrics) pose by pose.
void BM_HexapodAnalyzeBatchScalar(benchmark::State& state) {
  const pkmopt::Hexapod hexapod = sample_hexapod();
  const std::size_t n = static_cast<std::size_t>(state.range(0));
  const std::vector<pkmopt::Pose> poses = sample_poses(n);
  std::vector<pkmopt::PoseMetrics> metrics = sized_metrics(n);
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
BENCHMARK(BM_HexapodAnalyzeBatchScalar)->Arg(1000000)->Unit(benchmark::kMillisecond)->UseRealTime();

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

// The same metric set written plainly with Eigen's fixed-size general solvers (JacobiSVD for
// cond(J_h), PartialPivLU for det J and J^-1, SelfAdjointEigenSolver for C_tt, all 64 vertices
// of the error box): the yardstick the fast path is measured against.
void plain_eigen_metrics(const pkmopt::Hexapod& hexapod, pkmopt::HexapodData& data,
                         const pkmopt::Pose& pose, const pkmopt::Wrench& wrench,
                         pkmopt::PoseMetrics& out) {
  using pkmopt::Matrix6d;
  using Vector6d = Eigen::Matrix<double, 6, 1>;
  Vector6d q;
  Matrix6d J;
  pkmopt::hexapod_legs<double>(hexapod.design().base_joints, hexapod.platform_rel_tcp(),
                               pose.position, pose.angles, &q, &J);
  out.reachable = hexapod.reachable(data, pose);
  out.q = q;
  Vector6d compliance;
  for (int i = 0; i < 6; ++i) compliance(i) = 1.0 / hexapod.leg_stiffness(q(i));
  Matrix6d Jh = J;
  Jh.rightCols<3>() /= hexapod.characteristic_length();
  const Vector6d sigma = Eigen::JacobiSVD<Matrix6d>(Jh).singularValues();
  const double rcond = sigma(0) > 0.0 ? sigma(5) / sigma(0) : 0.0;
  const Eigen::PartialPivLU<Matrix6d> lu(J);
  out.det_j = lu.determinant();
  out.singular = !(rcond >= pkmopt::kSingularRcond);
  if (out.singular) {
    out.singularity_margin = out.stiffness_min = 0.0;
    out.tau = Vector6d::Constant(std::numeric_limits<double>::infinity());
    out.tcp_error_max = std::numeric_limits<double>::infinity();
    return;
  }
  out.singularity_margin = rcond;
  const Matrix6d Jinv = lu.inverse();
  out.tau = Jinv.transpose() * wrench;
  const Eigen::Matrix3d Ctt =
      Jinv.topRows<3>() * compliance.asDiagonal() * Jinv.topRows<3>().transpose();
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(Ctt, Eigen::EigenvaluesOnly);
  out.stiffness_min = 1.0 / eig.eigenvalues()(2);
  double best = 0.0;
  for (int mask = 0; mask < 64; ++mask) {
    Vector6d dq;
    for (int i = 0; i < 6; ++i) dq(i) = (mask >> i & 1) ? 1.0 : -1.0;
    best = std::max(best, (Jinv.topRows<3>() * dq).squaredNorm());
  }
  out.tcp_error_max = hexapod.design().actuator_error * std::sqrt(best);
}

void BM_HexapodPlainEigenOneThread(benchmark::State& state) {
  const pkmopt::Hexapod hexapod = sample_hexapod();
  const auto poses = sample_poses(4096);
  pkmopt::HexapodData data(hexapod);
  pkmopt::PoseMetrics m;
  const pkmopt::Wrench wrench = pkmopt::Wrench::Constant(100);
  std::size_t i = 0;
  for (auto _ : state) {
    plain_eigen_metrics(hexapod, data, poses[i++ & 4095], wrench, m);
    benchmark::DoNotOptimize(m.tcp_error_max);
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_HexapodPlainEigenOneThread);

}  // namespace
