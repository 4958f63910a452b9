// Tests of models/core/pose_analysis: analyze_poses(machine, poses, wrench) gives, pose by pose,
// what machine.analyze gives, with 1 and 3 OpenMP threads and over more poses than one slice of the
// hexapod batch path (1024):
//   - a leg-chain machine (a delta) goes through machine.analyze: bit-identical results;
//   - a hexapod goes through the SIMD batch path (models/hexapod/hexapod_batch.hpp), compared as
//     tests/models/hexapod/hexapod_batch_test.cpp compares it: reachable and singular exactly,
//     singular
//     poses bit-identical (the batch answers them with the scalar path), the other metrics within
//     the batch path's documented accuracy (1e-10 relative, or 64 eps cond(J) where J is too
//     ill-conditioned for that; cond(J) from the independent reference of tests/hexapod_reference)
//     of the scalar path, which is itself held to the same bound: twice the bound between the two.
// The result of a pose depends neither on the thread count nor on the slice it falls in.
#include "models/core/pose_analysis.hpp"

#include <gtest/gtest.h>
#include <omp.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "models/hexapod/hexapod.hpp"
#include "models/hexapod/hexapod_batch.hpp"
#include "models/leg_chain/leg_chain.hpp"
#include "models/sample_machines.hpp"
#include "tests/hexapod_reference.hpp"
#include "tests/sample_machines.hpp"

namespace pkmopt {
namespace {

bool same_bits(double a, double b) {
  return std::bit_cast<std::uint64_t>(a) == std::bit_cast<std::uint64_t>(b);
}

void expect_identical(const PoseMetrics& a, const PoseMetrics& b, const std::string& where) {
  EXPECT_EQ(a.reachable, b.reachable) << where;
  EXPECT_EQ(a.singular, b.singular) << where;
  ASSERT_EQ(a.q.size(), b.q.size()) << where;
  ASSERT_EQ(a.tau.size(), b.tau.size()) << where;
  for (Eigen::Index i = 0; i < a.q.size(); ++i) {
    EXPECT_TRUE(same_bits(a.q(i), b.q(i))) << where << " q_" << i + 1;
    EXPECT_TRUE(same_bits(a.tau(i), b.tau(i))) << where << " tau_" << i + 1;
  }
  EXPECT_TRUE(same_bits(a.stiffness_min, b.stiffness_min)) << where;
  EXPECT_TRUE(same_bits(a.singularity_margin, b.singularity_margin)) << where;
  EXPECT_TRUE(same_bits(a.det_j, b.det_j)) << where;
  EXPECT_TRUE(same_bits(a.tcp_error_max, b.tcp_error_max)) << where;
}

// analyze_poses with `threads` OpenMP threads (restoring the previous setting).
std::vector<PoseMetrics> analyze_with_threads(const Machine& machine,
                                              const std::vector<Pose>& poses, const Wrench& w,
                                              int threads) {
  const int before = omp_get_max_threads();
  omp_set_num_threads(threads);
  std::vector<PoseMetrics> metrics = analyze_poses(machine, poses, w);
  omp_set_num_threads(before);
  return metrics;
}

// Poses over (and past) the working region of the docs/conventions.md hexapod: some unreachable.
std::vector<Pose> hexapod_poses(std::size_t n) {
  sample_machines::Uniform u(2024);
  std::vector<Pose> poses(n);
  for (Pose& p : poses) {
    p.position = {u(-0.25, 0.25), u(-0.25, 0.25), u(0.65, 1.05)};
    p.angles = deg_to_rad(Eigen::Vector3d(u(-25, 25), u(-25, 25), u(-40, 40)));
  }
  return poses;
}

TEST(PoseAnalysis, HexapodMatchesAnalyzeWithinTheBatchAccuracy) {
  const Hexapod hexapod(sample_machines::conventions_hexapod_design());
  const std::vector<Pose> poses = hexapod_poses(2500);  // slices of 1024, 1024 and 452 poses
  const Wrench w = (Wrench() << 100, -200, -1500, 10, 20, 5).finished();
  const std::vector<PoseMetrics> one = analyze_with_threads(hexapod, poses, w, 1);
  const std::vector<PoseMetrics> three = analyze_with_threads(hexapod, poses, w, 3);
  ASSERT_EQ(one.size(), poses.size());
  ASSERT_EQ(three.size(), poses.size());
  HexapodData data(hexapod);
  std::size_t reachable = 0, unreachable = 0;
  for (std::size_t i = 0; i < poses.size(); ++i) {
    const std::string where = "pose " + std::to_string(i);
    expect_identical(three[i], one[i], where + " (3 threads against 1)");
    PoseMetrics scalar;
    hexapod.analyze(data, poses[i], w, scalar);
    const PoseMetrics& m = one[i];
    EXPECT_EQ(m.reachable, scalar.reachable) << where;
    (m.reachable ? reachable : unreachable) += 1;
    EXPECT_EQ(m.singular, scalar.singular) << where;
    if (scalar.singular) {
      expect_identical(m, scalar, where);
      continue;
    }
    const hexapod_reference::ReferenceMetrics ref =
        hexapod_reference::reference_metrics(hexapod, poses[i], w);
    const double tol =
        2.0 * std::max(1e-10, 64.0 * std::numeric_limits<double>::epsilon() * ref.cond);
    for (int k = 0; k < 6; ++k) EXPECT_NEAR(m.q(k), scalar.q(k), 2e-14 * scalar.q(k)) << where;
    const double tau_scale = scalar.tau.cwiseAbs().maxCoeff();
    for (int k = 0; k < 6; ++k) EXPECT_NEAR(m.tau(k), scalar.tau(k), tol * tau_scale) << where;
    EXPECT_NEAR(m.stiffness_min, scalar.stiffness_min, tol * scalar.stiffness_min) << where;
    EXPECT_NEAR(m.singularity_margin, scalar.singularity_margin, tol * scalar.singularity_margin)
        << where;
    EXPECT_NEAR(m.det_j, scalar.det_j, tol * std::abs(scalar.det_j)) << where;
    EXPECT_NEAR(m.tcp_error_max, scalar.tcp_error_max, tol * scalar.tcp_error_max) << where;
  }
  // The poses test both answers of reachability.
  EXPECT_GT(reachable, 100u);
  EXPECT_GT(unreachable, 100u);

  // The hexapod takes the batch path: bit for bit what analyze_hexapod_batch gives per slice.
  std::vector<PoseMetrics> batch(poses.size());
  for (std::size_t start = 0; start < poses.size(); start += 1024) {
    analyze_hexapod_batch(hexapod, poses.data() + start,
                          std::min<std::size_t>(1024, poses.size() - start), w,
                          batch.data() + start);
  }
  for (std::size_t i = 0; i < poses.size(); ++i)
    expect_identical(one[i], batch[i], "pose " + std::to_string(i) + " (batch path)");
}

TEST(PoseAnalysis, LegChainIsBitIdenticalToAnalyze) {
  const LegChainMachine delta(delta_design(DeltaDesign{}));
  sample_machines::Uniform u(42);
  std::vector<Pose> poses(1500);
  for (Pose& p : poses) p.position = {u(-0.6, 0.6), u(-0.6, 0.6), u(-1.4, -0.6)};
  const Wrench w = (Wrench() << 10, -20, -50, 0, 0, 0).finished();
  const std::vector<PoseMetrics> one = analyze_with_threads(delta, poses, w, 1);
  const std::vector<PoseMetrics> three = analyze_with_threads(delta, poses, w, 3);
  ASSERT_EQ(one.size(), poses.size());
  ASSERT_EQ(three.size(), poses.size());
  const auto data = delta.make_data();
  std::size_t reachable = 0;
  for (std::size_t i = 0; i < poses.size(); ++i) {
    PoseMetrics scalar;
    delta.analyze(*data, poses[i], w, scalar);
    expect_identical(one[i], scalar, "pose " + std::to_string(i) + " (1 thread)");
    expect_identical(three[i], scalar, "pose " + std::to_string(i) + " (3 threads)");
    reachable += scalar.reachable;
  }
  EXPECT_GT(reachable, 100u);
  EXPECT_LT(reachable, poses.size());
}

TEST(PoseAnalysis, NoPosesGiveNoMetrics) {
  const Hexapod hexapod(sample_machines::conventions_hexapod_design());
  EXPECT_TRUE(analyze_poses(hexapod, {}, Wrench::Zero()).empty());
  const LegChainMachine delta(delta_design(DeltaDesign{}));
  EXPECT_TRUE(analyze_poses(delta, {}, Wrench::Zero()).empty());
}

// analyze_pose_slices hands every pose over once, in slices of kPoseSlice, and gives back what
// analyze_poses gives, whatever the thread count; an exception in a callback reaches the caller.
TEST(PoseAnalysis, SlicesGiveTheMetricsOfAnalyzePoses) {
  const Hexapod hexapod(sample_machines::conventions_hexapod_design());
  const LegChainMachine delta(delta_design(DeltaDesign{}));
  const std::vector<Pose> poses = hexapod_poses(2 * kPoseSlice + 77);
  const Wrench w = (Wrench() << 100, -200, -1500, 10, 20, 5).finished();
  for (const Machine* machine :
       {static_cast<const Machine*>(&hexapod), static_cast<const Machine*>(&delta)}) {
    std::vector<PoseCompliance> matrices;
    const std::vector<PoseMetrics> whole = analyze_poses(*machine, poses, w, &matrices);
    for (int threads : {1, 2, 3}) {
      std::vector<PoseMetrics> sliced(poses.size());
      std::vector<Matrix6d> compliance(poses.size());
      std::vector<int> filled(poses.size(), 0), consumed(poses.size(), 0);
      analyze_pose_slices(
          *machine, poses.size(), w, true, threads,
          [&](const PoseSlice& s) {
            EXPECT_EQ(s.start % kPoseSlice, 0u);
            EXPECT_EQ(s.poses.size(), std::min(kPoseSlice, poses.size() - s.start));
            for (std::size_t k = 0; k < s.poses.size(); ++k) {
              s.poses[k] = poses[s.start + k];
              ++filled[s.start + k];
            }
          },
          [&](const PoseSlice& s) {
            ASSERT_EQ(s.metrics.size(), s.poses.size());
            ASSERT_EQ(s.matrices.size(), s.poses.size());
            for (std::size_t k = 0; k < s.metrics.size(); ++k) {
              sliced[s.start + k] = s.metrics[k];
              compliance[s.start + k] = s.matrices[k].compliance;
              ++consumed[s.start + k];
            }
          });
      for (std::size_t i = 0; i < poses.size(); ++i) {
        ASSERT_EQ(filled[i], 1) << i;
        ASSERT_EQ(consumed[i], 1) << i;
        expect_identical(sliced[i], whole[i],
                         std::string(machine->model()) + " pose " + std::to_string(i) + ", " +
                             std::to_string(threads) + " threads");
        for (int a = 0; a < 36; ++a)
          ASSERT_TRUE(same_bits(compliance[i](a), matrices[i].compliance(a))) << i;
      }
    }
  }
  EXPECT_THROW(analyze_pose_slices(
                   hexapod, poses.size(), w, false, 2,
                   [](const PoseSlice& s) {
                     if (s.start == kPoseSlice) throw std::runtime_error("fill failed");
                     for (Pose& p : s.poses) p.position = {0, 0, 0.9};
                   },
                   [](const PoseSlice&) {}),
               std::runtime_error);
}

}  // namespace
}  // namespace pkmopt
