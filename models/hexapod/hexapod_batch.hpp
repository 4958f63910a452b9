// The hexapod metric set for many poses at once: a SIMD batch path behind Hexapod::analyze.
//
// analyze_hexapod_batch(hexapod, poses, n, wrench, out) writes into out[i] what
// hexapod.analyze(data, poses[i], wrench, out[i]) writes (the metric set of docs/conventions.md:
// reachable, q, tau, stiffness_min, singularity_margin, det_j, tcp_error_max, singular, and the
// compliance metrics of models/core/machine.hpp: tcp_deflection, tcp_rotation_deflection,
// stiffness_min_direction, stiffness_min_loaded, and on request the matrices compliance and
// loaded_compliance_tt), to within the accuracy
// rules of the fast path (docs/performance.md, "Accuracy"): 1e-10 relative, or 64 eps cond(J)
// where J is too ill-conditioned for that (compliance entries relative to |C|, the direction to
// within |dC_tt| / gap where the two largest eigenvalues of C_tt are close).
//
// How: the poses go four at a time through one kernel on packs of four doubles (structure of
// arrays, lane l = pose l of the block). Every step is branch-free per lane:
//   - R = Rz Ry Rx (sin/cos per lane), the legs q_i, s_i, r_i, the rows of J, reachability,
//     the leg compliances 1/k_i;
//   - Gaussian elimination with partial pivoting per lane (row swaps by blends) on
//     [J^T | e_1 .. e_6 w]: det J, tau = J^-T w and J^-1 (P: its translational rows);
//   - C = J^-1 diag(1/k) J^-T (lower triangle; C_tt = P diag(1/k) P^T) and C w = J^-1 (tau / k):
//     tcp_deflection = |(C w)_t|, tcp_rotation_deflection = |(C w)_r|;
//   - the loaded stiffness K_T = K + G, K = J^T diag(k) J and G = sum_i tau_i K_g(s_i, r_i, q_i)
//     (the geometric stiffness of models/stiffness/compliance_metrics.hpp), assembled together from
//     the
//     dyads s s^T, s m^T, r s^T, r r^T, m m^T with m_i = r_i x s_i; Gaussian elimination without
//     pivoting of its three rotational columns leaves the Schur complement S of the rotational
//     block, and loaded_compliance_tt = B = S^-1 (the adjugate). A lane is answered only when
//     beta = tr(D C D) sum_i |tau_i| ((1 + |r_i|^2/L^2) / q_i + |r_i| / L^2) < 1/2
//     (D = diag(1, 1, 1, L, L, L)): beta bounds |D C D|_2 |D^-1 G D^-1|_2, which proves that the
//     symmetric part of K_T is positive definite (the loaded machine is stable, as the scalar
//     path's Cholesky test finds) and that the elimination needs no pivoting;
//   - the eigenvalues of the Gram matrix J_h^T J_h and of C_tt by the cyclic Jacobi method
//     (parallel round-robin order for the 6x6, rotation skipped per lane when
//     |a_pq| <= eps sqrt(a_pp a_qq), sweeps until every lane has converged; the two iterations
//     interleaved; lower triangles only), with the rotations of C_tt accumulated into its
//     eigenvectors: singularity_margin = sqrt(lambda_min / lambda_max), stiffness_min =
//     1 / lambda_max(C_tt), stiffness_min_direction = the eigenvector of lambda_max(C_tt) (the
//     first of equal largest eigenvalues; sign: largest component positive);
//   - stiffness_min_loaded = 1 / sigma_max(B) = 1 / sqrt(lambda_max(N)), N = B^T B: in the
//     eigenbasis of C_tt, N is nearly diagonal (B differs from C_tt by the geometric term), and
//     lambda_max(N) is the fixed point of lambda = a + b^T (lambda I - D)^-1 b (a, b, D: the
//     entries of N in that basis, the top eigenvector first), three steps from a where the
//     contraction factor |b|^2 / gap^2 is proven < 1e-4 (error < 1e-16 lambda); where it is not
//     (the two largest eigenvalues of C_tt close, or a heavy load) by the Jacobi method on N,
//     run for a block only when one of its lanes needs it;
//   - tcp_error_max = actuator_error * max |P s| over the 32 sign vectors (4 x 8 sums);
//   - with a mass model, the natural frequencies (models/hexapod/hexapod_batch_dynamics.inc): the
//   TCP
//     mass matrix M of the platform and the legs in closed form, M = L L^T, the eigenvalues
//     mu = 1 / omega^2 of S = L^T C L by the cyclic Jacobi method, sorted.
// A lane goes through the scalar Hexapod::analyze instead when the fast path would not be
// accurate or the pose is unusual: 1/cond(J_h) < 1e-2 (the scalar path then uses an SVD), a
// zero-length leg, an exactly zero pivot, a Jacobi iteration that did not converge, a load that
// the bound beta above does not prove stable (beta >= 1/2: near or beyond the stability limit,
// where the scalar path's stiffness_min_loaded may be 0), or any non-finite intermediate
// result, or (with masses) a mass matrix that is not positive definite or a nearly rigid
// direction (mu_min <= 1e-12 mu_max). Singular poses therefore get exactly the scalar outputs.
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

#include "models/hexapod/hexapod.hpp"

namespace pkmopt {

/// Which code analyze_hexapod_batch runs.
enum class HexapodBatchKernel {
  /// The AVX2 + FMA kernel when the CPU has both; otherwise Hexapod::analyze pose by pose
  /// (quicker than the baseline kernel, which has half-width packs and no FMA).
  automatic,
  /// The kernel compiled for the x86-64 baseline (SSE2), on any CPU (tests use it).
  baseline,
};

/// The metric set of hexapod.analyze for poses[0..n) under one wrench, into out[0..n), and,
/// when `matrices` is given, the compliance matrices (what hexapod.analyze leaves in
/// data.matrices) into matrices[0..n). out[i].q and out[i].tau are resized to 6 when needed.
/// Returns how many poses were recomputed by the scalar path (see the header comment).
/// Thread-safe for disjoint outputs.
std::size_t analyze_hexapod_batch(const Hexapod& hexapod, const Pose* poses, std::size_t n,
                                  const Wrench& wrench, PoseMetrics* out,
                                  HexapodBatchKernel kernel = HexapodBatchKernel::automatic,
                                  PoseCompliance* matrices = nullptr);

/// True when the automatic choice runs the AVX2 + FMA kernel on this CPU.
bool hexapod_batch_uses_avx2();

}  // namespace pkmopt
