// Tests of models/hexapod/hexapod_batch: the SIMD batch path against an independent reference of
// the metric set (the rules of the HexapodFastPath harness in hexapod_test.cpp: 1e-10 relative, or
// 64 eps cond(J) where J is too ill-conditioned for that; within a factor 2 of the singularity
// threshold either answer) and against Hexapod::analyze, on random general geometries, symmetric
// poses (repeated eigenvalues), near-singular and singular poses, batch sizes that are not
// multiples of 4, and for bit-identical results however a batch is split. The compliance metrics
// (compliance, deflections, worst direction, loaded stiffness) are checked against
// Hexapod::analyze by the same rules (expect_compliance_matches_scalar).
#include "models/hexapod/hexapod_batch.hpp"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <Eigen/LU>
#include <Eigen/SVD>
#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "tests/hexapod_reference.hpp"
#include "tests/sample_machines.hpp"

namespace pkmopt {
namespace {

using sample_machines::Uniform;

using hexapod_reference::random_wrench;

constexpr double kInf = std::numeric_limits<double>::infinity();
using hexapod_reference::reference_metrics;

bool same_bits(double a, double b) {
  return std::bit_cast<std::uint64_t>(a) == std::bit_cast<std::uint64_t>(b);
}

// A pose's metrics with its compliance matrices (PoseCompliance).
struct Result {
  PoseMetrics m;
  PoseCompliance c;
};

// Hexapod::analyze with the matrices it leaves in its data.
Result scalar_result(const Hexapod& hexapod, HexapodData& data, const Pose& pose, const Wrench& w) {
  Result r;
  hexapod.analyze(data, pose, w, r.m);
  r.c = data.matrices;
  return r;
}

// The batch over poses[0..n) with the matrices; `scalar` counts the poses of the scalar path.
struct Batch {
  std::vector<PoseMetrics> metrics;
  std::vector<PoseCompliance> matrices;
  std::size_t scalar = 0;
  Result operator[](std::size_t i) const { return {metrics[i], matrices[i]}; }
};
Batch run_batch(const Hexapod& hexapod, const Pose* poses, std::size_t n, const Wrench& w,
                HexapodBatchKernel kernel = HexapodBatchKernel::automatic) {
  Batch b;
  b.metrics.resize(n);
  b.matrices.resize(n);
  b.scalar =
      analyze_hexapod_batch(hexapod, poses, n, w, b.metrics.data(), kernel, b.matrices.data());
  return b;
}

void expect_identical(const Result& ra, const Result& rb, const std::string& where) {
  const PoseMetrics &a = ra.m, &b = rb.m;
  EXPECT_EQ(a.reachable, b.reachable) << where;
  EXPECT_EQ(a.singular, b.singular) << where;
  for (int i = 0; i < 6; ++i) {
    EXPECT_TRUE(same_bits(a.q(i), b.q(i))) << where;
    EXPECT_TRUE(same_bits(a.tau(i), b.tau(i))) << where;
  }
  EXPECT_TRUE(same_bits(a.stiffness_min, b.stiffness_min)) << where;
  EXPECT_TRUE(same_bits(a.singularity_margin, b.singularity_margin)) << where;
  EXPECT_TRUE(same_bits(a.det_j, b.det_j)) << where;
  EXPECT_TRUE(same_bits(a.tcp_error_max, b.tcp_error_max)) << where;
  for (int i = 0; i < 6; ++i) {
    for (int j = 0; j < 6; ++j) {
      EXPECT_TRUE(same_bits(ra.c.compliance(i, j), rb.c.compliance(i, j))) << where;
    }
  }
  EXPECT_TRUE(same_bits(a.tcp_deflection, b.tcp_deflection)) << where;
  EXPECT_TRUE(same_bits(a.tcp_rotation_deflection, b.tcp_rotation_deflection)) << where;
  for (int c = 0; c < 3; ++c) {
    EXPECT_TRUE(same_bits(a.stiffness_min_direction(c), b.stiffness_min_direction(c))) << where;
  }
  EXPECT_TRUE(same_bits(a.stiffness_min_loaded, b.stiffness_min_loaded)) << where;
  ASSERT_EQ(a.natural_frequencies.size(), b.natural_frequencies.size()) << where;
  for (Eigen::Index i = 0; i < a.natural_frequencies.size(); ++i) {
    EXPECT_TRUE(same_bits(a.natural_frequencies(i), b.natural_frequencies(i))) << where;
  }
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      EXPECT_TRUE(same_bits(ra.c.loaded_compliance_tt(i, j), rb.c.loaded_compliance_tt(i, j)))
          << where;
    }
  }
}

// The compliance metrics of a non-singular batch result m against the scalar result s of the
// same pose, with tol = max(1e-10, 64 eps cond(J)) as for the other metrics: the entries of C
// relative to |C| (Frobenius), the deflections relative to |C| |w|, the loaded stiffness
// relative to itself and its block loaded_compliance_tt relative to its norm. The direction is
// fixed only up to |dC_tt| / gap (gap: the distance of the largest eigenvalue of C_tt from the
// next): it must be a unit vector with C_tt v = lambda v to |dC_tt|, equal to the scalar one where
// the gap makes that meaningful, with the same sign where the sign rule (largest component
// positive) is decided.
void expect_compliance_matches_scalar(const Result& rm, const Result& rs, const Wrench& w,
                                      double cond, const std::string& where) {
  const PoseMetrics &m = rm.m, &s = rs.m;
  const Matrix6d &mC = rm.c.compliance, &sC = rs.c.compliance;
  const Eigen::Matrix3d &m_loaded = rm.c.loaded_compliance_tt,
                        &s_loaded = rs.c.loaded_compliance_tt;
  const double tol = std::max(1e-10, 64.0 * std::numeric_limits<double>::epsilon() * cond);
  const double c_norm = sC.norm();
  EXPECT_LE((mC - mC.transpose()).cwiseAbs().maxCoeff(), tol * c_norm) << where;
  EXPECT_LE((mC - sC).cwiseAbs().maxCoeff(), tol * c_norm) << where;
  EXPECT_NEAR(m.tcp_deflection, s.tcp_deflection, tol * c_norm * w.norm()) << where;
  EXPECT_NEAR(m.tcp_rotation_deflection, s.tcp_rotation_deflection, tol * c_norm * w.norm())
      << where;
  EXPECT_NEAR(m.stiffness_min_loaded, s.stiffness_min_loaded, tol * s.stiffness_min_loaded)
      << where;
  // The natural frequencies (with masses): each relative to itself.
  ASSERT_EQ(m.natural_frequencies.size(), s.natural_frequencies.size()) << where;
  for (Eigen::Index i = 0; i < s.natural_frequencies.size(); ++i) {
    EXPECT_NEAR(m.natural_frequencies(i), s.natural_frequencies(i), tol * s.natural_frequencies(i))
        << where << " frequency " << i;
  }
  if (s_loaded.allFinite()) {
    EXPECT_LE((m_loaded - s_loaded).cwiseAbs().maxCoeff(), tol * s_loaded.norm()) << where;
  } else {  // unstable under the load: the batch answers with the scalar path
    EXPECT_EQ(m.stiffness_min_loaded, 0.0) << where;
    EXPECT_TRUE(m_loaded.cwiseAbs().minCoeff() == kInf) << where;
  }

  const Eigen::Matrix3d Ctt =
      0.5 * (sC.topLeftCorner<3, 3>() + sC.topLeftCorner<3, 3>().transpose());
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(Ctt);
  const Eigen::Vector3d lambda = eig.eigenvalues();  // ascending
  const Eigen::Vector3d v = m.stiffness_min_direction;
  const Eigen::Vector3d vs = s.stiffness_min_direction;
  const double dC = tol * c_norm;  // bound of |dC_tt| between the two paths
  EXPECT_NEAR(v.norm(), 1.0, 1e-13) << where;
  EXPECT_LE((Ctt * v - lambda(2) * v).norm(), 2.0 * dC) << where;
  const double angle_tol = 2.0 * dC / (lambda(2) - lambda(1));

  if (angle_tol < 1e-3) {
    EXPECT_LE(std::min((v - vs).norm(), (v + vs).norm()), angle_tol) << where;
    Eigen::Vector3d sorted = vs.cwiseAbs();
    std::sort(sorted.data(), sorted.data() + 3);
    if (sorted(2) - sorted(1) > 2.0 * angle_tol) {
      EXPECT_LE((v - vs).norm(), angle_tol) << where;
    }
  }
}

// Checks one batch result against the reference and against analyze. Returns 1 when the pose
// was checked as non-singular.
int expect_batch_pose_matches(const Hexapod& hexapod, const Pose& pose, const Wrench& w,
                              const Result& r, const std::string& where) {
  HexapodData data(hexapod);
  const Result scalar = scalar_result(hexapod, data, pose, w);
  EXPECT_EQ(r.m.reachable, scalar.m.reachable) << where;
  if (r.m.singular) {  // singular answers come from the scalar path, unchanged
    expect_identical(r, scalar, where);
  }
  const hexapod_reference::ReferenceMetrics ref = reference_metrics(hexapod, pose, w);
  const int checked = hexapod_reference::expect_metrics_match_reference(r.m, ref, where);
  if (checked == 1 && !scalar.m.singular) {
    expect_compliance_matches_scalar(r, scalar, w, ref.cond, where);
  }
  return checked;
}

struct BatchCheck {
  int checked = 0;         // poses checked as non-singular
  std::size_t scalar = 0;  // poses the batch recomputed with the scalar path
};

// Runs the batch with every available kernel and checks each pose.
BatchCheck expect_batch_matches(const Hexapod& hexapod, const std::vector<Pose>& poses,
                                const Wrench& w, const std::string& where) {
  BatchCheck result;
  for (HexapodBatchKernel kernel : {HexapodBatchKernel::automatic, HexapodBatchKernel::baseline}) {
    const Batch batch = run_batch(hexapod, poses.data(), poses.size(), w, kernel);
    result.scalar = batch.scalar;
    result.checked = 0;
    for (std::size_t i = 0; i < poses.size(); ++i) {
      result.checked += expect_batch_pose_matches(
          hexapod, poses[i], w, batch[i],
          where + " pose " + std::to_string(i) +
              (kernel == HexapodBatchKernel::baseline ? " (baseline kernel)" : ""));
    }
  }
  return result;
}

TEST(HexapodBatch, MatchesReferenceOnRandomGeometriesAndPoses) {
  Uniform u(31);
  int checked = 0;
  std::size_t scalar = 0, total = 0;
  for (int g = 0; g < 200; ++g) {
    const Hexapod hexapod(sample_machines::random_hexapod_design(u));
    std::vector<Pose> poses(11);  // two blocks of four and a partial one
    for (Pose& p : poses) p = sample_machines::random_pose(u);
    const BatchCheck c =
        expect_batch_matches(hexapod, poses, random_wrench(u), "geometry " + std::to_string(g));
    checked += c.checked;
    scalar += c.scalar;
    total += poses.size();
  }
  EXPECT_GT(checked, 2150);
  EXPECT_LT(scalar, total / 20);  // the SIMD kernel answers almost every pose
}

// With masses the kernel gives the natural frequencies too: random geometries and masses (the
// platform's inertia turned, its centre of mass off the TCP, leg bodies of random sizes).
TEST(HexapodBatch, NaturalFrequenciesMatchTheScalarPath) {
  Uniform u(33);
  int checked = 0;
  std::size_t scalar = 0, total = 0;
  for (int g = 0; g < 60; ++g) {
    HexapodDesign design = sample_machines::random_hexapod_design(u);
    design.masses = sample_machines::random_hexapod_masses(u);
    const Hexapod hexapod(design);
    std::vector<Pose> poses(11);
    for (Pose& p : poses) p = sample_machines::random_pose(u);
    const Wrench w = random_wrench(u);
    const BatchCheck c = expect_batch_matches(hexapod, poses, w, "masses " + std::to_string(g));
    HexapodDesign bare = design;
    bare.masses = MassModel{};
    // The frequencies send no pose to the scalar path that the metrics without masses do not.
    EXPECT_EQ(c.scalar,
              run_batch(Hexapod(bare), poses.data(), poses.size(), w, HexapodBatchKernel::baseline)
                  .scalar)
        << "masses " << g;
    checked += c.checked;
    scalar += c.scalar;
    total += poses.size();
  }
  EXPECT_GT(checked, 600);
  EXPECT_LT(scalar, total / 10);  // the SIMD kernel answers almost every pose
  // The symmetric milling hexapod at its home pose: the two sway modes are equal.
  HexapodDesign design = sample_machines::conventions_hexapod_design();
  design.masses = sample_machines::milling_hexapod_masses();
  const Hexapod symmetric(design);
  const std::vector<Pose> home(4, Pose{{0, 0, 0.9}, {0, 0, 0}});
  const BatchCheck c = expect_batch_matches(symmetric, home, Wrench::Zero(), "home");
  EXPECT_EQ(c.scalar, 0u);
  const Batch b = run_batch(symmetric, home.data(), home.size(), Wrench::Zero());
  EXPECT_NEAR(b.metrics[0].natural_frequencies(0), b.metrics[0].natural_frequencies(1),
              1e-9 * b.metrics[0].natural_frequencies(0));
}

// Symmetric poses of semi-regular designs: repeated eigenvalues of J_h^T J_h and of C_tt.
TEST(HexapodBatch, MatchesReferenceAtSymmetricPoses) {
  Uniform u(32);
  std::size_t scalar = 0;
  for (int g = 0; g < 100; ++g) {
    HexapodDesign d =
        semi_regular_hexapod(u(0.4, 0.9), deg_to_rad(u(5, 50)), u(0.15, 0.4), deg_to_rad(u(5, 50)));
    d.min_length = 0.3;
    d.max_length = 2.0;
    d.stiffness.axial_stiffness = u(1e7, 1e8);
    if (g % 2) d.tcp = {0, 0, u(-0.2, 0.0)};
    if (g % 3 == 0) d.characteristic_length = u(0.1, 0.6);
    const Hexapod hexapod(d);
    std::vector<Pose> poses;
    for (int k = 0; k < 10; ++k) {
      poses.push_back(Pose{{0, 0, u(0.5, 1.2)}, {0, 0, deg_to_rad(60.0 * (k % 3))}});
    }
    scalar +=
        expect_batch_matches(hexapod, poses, random_wrench(u), "geometry " + std::to_string(g))
            .scalar;
  }
  EXPECT_LT(scalar, 100u);  // repeated eigenvalues are handled by the SIMD Jacobi, not the fallback
}

// Similar hexagons with joints moved by 1e-9 .. 1e-2 m, and Fichter's 90 deg yaw singularity
// approached to 1e-10 .. 1e-2 rad.
TEST(HexapodBatch, MatchesReferenceNearSingularities) {
  Uniform u(33);
  std::size_t scalar = 0;
  for (int g = 0; g < 150; ++g) {
    const Hexapod hexapod(hexapod_reference::near_similar_hexapod(u, g % 2 == 1));
    std::vector<Pose> poses(5);
    for (Pose& p : poses) p = sample_machines::random_pose(u);
    scalar += expect_batch_matches(hexapod, poses, random_wrench(u), "similar " + std::to_string(g))
                  .scalar;
  }
  for (int g = 0; g < 60; ++g) {
    HexapodDesign d =
        semi_regular_hexapod(u(0.4, 0.9), deg_to_rad(u(5, 50)), u(0.15, 0.4), deg_to_rad(u(5, 50)));
    d.min_length = 0.2;
    d.max_length = 2.0;
    d.stiffness.axial_stiffness = 1e8;
    const Hexapod hexapod(d);
    std::vector<Pose> poses;
    const double z = u(0.5, 1.2);
    for (int k = 0; k < 7; ++k) {
      const double offset = (k % 2 ? 1.0 : -1.0) * std::pow(10.0, u(-10, -1));
      poses.push_back(Pose{{0, 0, z}, {0, 0, deg_to_rad(g % 2 ? 90.0 : -90.0) + offset}});
    }
    scalar += expect_batch_matches(hexapod, poses, random_wrench(u), "fichter " + std::to_string(g))
                  .scalar;
  }
  EXPECT_GT(scalar, 200u);  // the ill-conditioned ones went through the scalar path
}

// Architecturally singular designs: every pose singular, with exactly the scalar outputs.
TEST(HexapodBatch, SingularPosesGiveTheScalarSingularOutputs) {
  Uniform u(34);
  for (double base_sep : {60.0, 20.0, 45.0}) {
    HexapodDesign d =
        semi_regular_hexapod(0.6, deg_to_rad(base_sep), 0.3, deg_to_rad(120.0 - base_sep));
    d.min_length = 0.2;
    d.max_length = 2.0;
    d.stiffness.axial_stiffness = 1e8;
    const Hexapod hexapod(d);
    std::vector<Pose> poses(9);
    for (Pose& p : poses) p = sample_machines::random_pose(u);
    const Wrench w = Wrench::Constant(10.0);
    const Batch batch = run_batch(hexapod, poses.data(), poses.size(), w);
    EXPECT_EQ(batch.scalar, poses.size());
    HexapodData data(hexapod);
    for (std::size_t i = 0; i < poses.size(); ++i) {
      EXPECT_TRUE(batch.metrics[i].singular);
      expect_identical(batch[i], scalar_result(hexapod, data, poses[i], w),
                       "pose " + std::to_string(i));
    }
  }
}

// Bench poses of the docs/conventions.md hexapod: the SIMD kernel answers every one; a pose's
// result does not depend on the batch it is in (blocks padded, never mixed with the scalar path).
TEST(HexapodBatch, BitIdenticalHoweverTheBatchIsSplit) {
  const Hexapod hexapod(sample_machines::conventions_hexapod_design());
  Uniform u(35);
  std::vector<Pose> poses(203);
  for (Pose& p : poses) {
    p = Pose{{u(-0.15, 0.15), u(-0.15, 0.15), u(0.75, 0.95)},
             deg_to_rad(Eigen::Vector3d(u(-15, 15), u(-15, 15), u(-20, 20)))};
  }
  const Wrench w = random_wrench(u);
  const Batch whole = run_batch(hexapod, poses.data(), poses.size(), w);
  // With AVX2 the SIMD kernel answers every one; without it every pose takes the scalar path.
  EXPECT_EQ(whole.scalar, hexapod_batch_uses_avx2() ? 0u : poses.size());
  EXPECT_EQ(run_batch(hexapod, poses.data(), poses.size(), w, HexapodBatchKernel::baseline).scalar,
            0u);
  for (std::size_t chunk : {1u, 2u, 3u, 5u, 7u, 64u}) {
    Batch split;
    split.metrics.resize(poses.size());
    split.matrices.resize(poses.size());
    for (std::size_t start = 1; start < poses.size(); start += chunk) {  // offset by one pose
      const std::size_t count = std::min(chunk, poses.size() - start);
      analyze_hexapod_batch(hexapod, poses.data() + start, count, w, split.metrics.data() + start,
                            HexapodBatchKernel::automatic, split.matrices.data() + start);
    }
    analyze_hexapod_batch(hexapod, poses.data(), 1, w, split.metrics.data(),
                          HexapodBatchKernel::automatic, split.matrices.data());
    for (std::size_t i = 0; i < poses.size(); ++i) {
      expect_identical(whole[i], split[i],
                       "chunk " + std::to_string(chunk) + " pose " + std::to_string(i));
    }
  }
  // The same poses shuffled into other lanes.
  std::vector<Pose> reversed(poses.rbegin(), poses.rend());
  const Batch reversed_batch = run_batch(hexapod, reversed.data(), reversed.size(), w);
  for (std::size_t i = 0; i < poses.size(); ++i) {
    expect_identical(whole[i], reversed_batch[poses.size() - 1 - i],
                     "reversed pose " + std::to_string(i));
  }
  // Without the matrices the metrics are the same, bit for bit.
  std::vector<PoseMetrics> lean(poses.size());
  analyze_hexapod_batch(hexapod, poses.data(), poses.size(), w, lean.data());
  for (std::size_t i = 0; i < poses.size(); ++i) {
    expect_identical({lean[i], whole.matrices[i]}, whole[i], "lean pose " + std::to_string(i));
  }
}

// Heavy wrenches (up to 50 kN and 5 kN m): the geometric term of the leg forces makes the loaded
// stiffness differ from stiffness_min, and the batch still answers (nearly) every pose.
TEST(HexapodBatch, LoadedStiffnessUnderAHeavyWrenchMatchesTheScalarPath) {
  const Hexapod hexapod(sample_machines::conventions_hexapod_design());
  Uniform u(36);
  std::vector<Pose> poses(41);
  for (Pose& p : poses) {
    p = Pose{{u(-0.15, 0.15), u(-0.15, 0.15), u(0.75, 0.95)},
             deg_to_rad(Eigen::Vector3d(u(-15, 15), u(-15, 15), u(-20, 20)))};
  }
  for (double force : {5e3, 5e4}) {
    Wrench w = random_wrench(u);
    w.head<3>() *= force / w.head<3>().norm();
    w.tail<3>() *= 0.1 * force / w.tail<3>().norm();
    const BatchCheck c = expect_batch_matches(hexapod, poses, w, "force " + std::to_string(force));
    EXPECT_EQ(c.checked, static_cast<int>(poses.size()));
    // The baseline kernel (checked last) keeps every pose; the automatic choice is the AVX2
    // kernel, which keeps them too, or, on a CPU or compiler without it, the scalar path.
    EXPECT_EQ(c.scalar, 0u);
    EXPECT_EQ(run_batch(hexapod, poses.data(), poses.size(), w).scalar,
              hexapod_batch_uses_avx2() ? 0u : poses.size());
    std::vector<PoseMetrics> metrics(poses.size());
    analyze_hexapod_batch(hexapod, poses.data(), poses.size(), w, metrics.data());
    for (const PoseMetrics& m : metrics) {
      // Far above the tolerances: the load changes the stiffness by 1e-6 or more.
      EXPECT_GT(std::abs(m.stiffness_min_loaded - m.stiffness_min), 1e-6 * m.stiffness_min);
      EXPECT_GT(m.stiffness_min_loaded, 0.0);
    }
  }
}

// Loads near and beyond the stability limit of the loaded mechanism (K_T not positive definite:
// stiffness_min_loaded = 0) go through the scalar path and give exactly its answers.
TEST(HexapodBatch, LoadsNearTheStabilityLimitGiveTheScalarAnswers) {
  const Hexapod hexapod(sample_machines::conventions_hexapod_design());
  Uniform u(37);
  std::vector<Pose> poses(13);
  for (Pose& p : poses) {
    p = Pose{{u(-0.15, 0.15), u(-0.15, 0.15), u(0.75, 0.95)},
             deg_to_rad(Eigen::Vector3d(u(-15, 15), u(-15, 15), u(-20, 20)))};
  }
  int unstable = 0;
  HexapodData data(hexapod);
  for (double force : {1e6, 3e6, 1e7, 3e7, 1e8}) {
    Wrench w = Wrench::Zero();
    w(2) = -force;  // compresses every leg
    w(0) = 0.1 * force;
    const BatchCheck c = expect_batch_matches(hexapod, poses, w, "force " + std::to_string(force));
    EXPECT_GE(c.checked, 1);
    const Batch batch = run_batch(hexapod, poses.data(), poses.size(), w);
    for (std::size_t i = 0; i < poses.size(); ++i) {
      const Result scalar = scalar_result(hexapod, data, poses[i], w);
      if (scalar.m.stiffness_min_loaded == 0.0 && !scalar.m.singular) {
        ++unstable;
        expect_identical(batch[i], scalar, "unstable pose " + std::to_string(i));
      }
    }
  }
  EXPECT_GT(unstable, 5);
}

TEST(HexapodBatch, EmptyBatchAndUnsizedOutputs) {
  const Hexapod hexapod(sample_machines::conventions_hexapod_design());
  EXPECT_EQ(analyze_hexapod_batch(hexapod, nullptr, 0, Wrench::Zero(), nullptr), 0u);
  const Pose pose{{0.05, -0.02, 0.85}, deg_to_rad(Eigen::Vector3d(5, -3, 10))};
  Result r;  // q and tau empty: the batch sizes them
  analyze_hexapod_batch(hexapod, &pose, 1, Wrench::Constant(20.0), &r.m,
                        HexapodBatchKernel::automatic, &r.c);
  ASSERT_EQ(r.m.q.size(), 6);
  ASSERT_EQ(r.m.tau.size(), 6);
  expect_batch_pose_matches(hexapod, pose, Wrench::Constant(20.0), r, "single pose");
}

}  // namespace
}  // namespace pkmopt
