// The hexapod metric set for many poses at once: a SIMD batch path behind Hexapod::analyze.
//
// analyze_hexapod_batch(hexapod, poses, n, wrench, out) writes into out[i] what
// hexapod.analyze(data, poses[i], wrench, out[i]) writes (the metric set of docs/conventions.md:
// reachable, q, tau, stiffness_min, singularity_margin, det_j, tcp_error_max, singular),
// to within the accuracy rules of the fast path (docs/performance.md, "Accuracy"): 1e-10
// relative, or 64 eps cond(J) where J is too ill-conditioned for that.
//
// How: the poses go four at a time through one kernel on packs of four doubles (structure of
// arrays, lane l = pose l of the block). Every step is branch-free per lane:
//   - R = Rz Ry Rx (sin/cos per lane), the legs q_i, s_i, r_i, the rows of J, reachability,
//     the leg compliances 1/k_i;
//   - the eigenvalues of the Gram matrix J_h^T J_h by the cyclic Jacobi method (parallel
//     round-robin order, rotation skipped per lane when |a_pq| <= eps sqrt(a_pp a_qq),
//     sweeps until every lane has converged); singularity_margin = sqrt(lambda_min/lambda_max);
//   - Gaussian elimination with partial pivoting per lane (row swaps by blends) on
//     [J^T | e_1 e_2 e_3 w]: det J, tau = J^-T w and the translational rows P of J^-1;
//   - C_tt = P diag(1/k) P^T and its largest eigenvalue by the same Jacobi method (3x3);
//     stiffness_min = 1 / lambda_max(C_tt);
//   - tcp_error_max = actuator_error * max |P s| over the 32 sign vectors (4 x 8 sums).
// A lane goes through the scalar Hexapod::analyze instead when the fast path would not be
// accurate or the pose is unusual: 1/cond(J_h) < 1e-2 (the scalar path then uses an SVD), a
// zero-length leg, an exactly zero pivot, a Jacobi iteration that did not converge, or any
// non-finite intermediate result. Singular poses therefore get exactly the scalar outputs.
// A last partial block is padded with copies of its last pose, so the result for a pose does
// not depend on where it sits in the batch nor on how a batch is split.
//
// The kernel is compiled twice: for AVX2 + FMA (chosen at run time when the CPU has both) and
// for the x86-64 baseline (SSE2, each pack split in two halves by the compiler). The baseline
// kernel is slower than the scalar path, so on a CPU without AVX2 the automatic choice runs
// Hexapod::analyze pose by pose.
//
// Units: as Hexapod (metres, radians, newtons).
//
// Example:
//   const pkmopt::Hexapod hexapod(design);
//   std::vector<pkmopt::Pose> poses = ...;
//   std::vector<pkmopt::PoseMetrics> metrics(poses.size());
//   pkmopt::analyze_hexapod_batch(hexapod, poses.data(), poses.size(), wrench, metrics.data());
//   // OpenMP: give each thread a contiguous slice, e.g. blocks of 256 poses.
#pragma once

#include <cstddef>

#include "models/hexapod.hpp"

namespace pkmopt {

/// Which code analyze_hexapod_batch runs.
enum class HexapodBatchKernel {
  /// The AVX2 + FMA kernel when the CPU has both; otherwise Hexapod::analyze pose by pose
  /// (quicker than the baseline kernel, which has half-width packs and no FMA).
  automatic,
  /// The kernel compiled for the x86-64 baseline (SSE2), on any CPU (tests use it).
  baseline,
};

/// The metric set of hexapod.analyze for poses[0..n) under one wrench, into out[0..n).
/// out[i].q and out[i].tau are resized to 6 when needed. Returns how many poses were
/// recomputed by the scalar path (see the header comment). Thread-safe for disjoint outputs.
std::size_t analyze_hexapod_batch(const Hexapod& hexapod, const Pose* poses, std::size_t n,
                                  const Wrench& wrench, PoseMetrics* out,
                                  HexapodBatchKernel kernel = HexapodBatchKernel::automatic);

/// True when the automatic choice runs the AVX2 + FMA kernel on this CPU.
bool hexapod_batch_uses_avx2();

}  // namespace pkmopt
