// The compliance metrics of a leg-chain machine (models/leg_chain/leg_chain.hpp): the 6x6
// compliance T C T^T with C = A^-1 diag(1/k) A^-T on the platform DOF, the TCP deflection under the
// wrench, and the loaded (tangent) stiffness.
//
// Loaded stiffness. Each leg is a rod of axial stiffness k_r (link and joints; the current length
// l = |P_i - c_i|) from the actuated point c_i(q~_i) to the platform point P_i, and an actuator
// spring k_a in the actuator coordinate (1 / actuator_compliance; q~_i = q_i + its deflection).
// Under the rod tension f_i the small-motion equations are, with dP_i = G_i dx (G_i = [I, -[r]x] T,
// dx the DOF twist), Pi = I - s s^T, c' = dc/dq, c'' = d2c/dq2 (0 for PUS, -(c - o) for RUS):
//   dl = a_i dx - B_i dq~,  df = k_r dl,
//   ds = Pi/l (G_i dx - c' dq~),
//   k_a dq~ = d(f B) = B df + f (c'.ds + (s.c'') dq~)        (the actuator's balance)
//   => dq~ = g_i^T dx / D_i,  D_i = k_a + B^2 k_r + f c'^T Pi c'/l - f s.c'',
//                             g_i^T = B k_r a_i + f c'^T Pi G_i / l,
// and the platform's generalised force changes by
//   dw_i = a_i^T df + f T^T [ds; [s]x[r]x T_r dx + [r]x ds]     (T_r: rotational rows of T).
// UPS legs (the actuator along the rod) add k_i a_i^T a_i + T^T K_g T (models/
// compliance_metrics.hpp). Planar legs add the geometric term of the plane constraints' reaction
// forces lambda_j n_j (from the full equilibrium w = sum f_i [s_i; r_i x s_i] + sum lambda_j
// [n_j; r_j x n_j]); the parallelograms of translational and Schoenflies platforms carry pure
// moments about fixed directions, which add nothing. K_T = sum dw_i/dx (+ constraints) and the
// loaded compliance (I + C G)^-1 C with G = K_T - A^T diag(k) A.
//
// With link compliance (models/leg_chain/leg_chain_vjm.cpp) the loaded stiffness is the VJM
// stiffness plus
// full_twist_geometric_stiffness: the terms above on the full twist with every actuated point
// fixed (f K_g per rod, and the plane constraints' reactions), docs/stiffness.md.
#include <Eigen/LU>
#include <cmath>

#include "models/core/linalg.hpp"
#include "models/leg_chain/leg_chain.hpp"
#include "models/leg_chain/leg_chain_detail.hpp"
#include "models/stiffness/compliance_metrics.hpp"

namespace pkmopt {

using detail::MatM;
using detail::VecM;

namespace {

// Planar legs: the reaction forces of the plane constraints, G_c^T lambda = w - rod wrench (least
// squares; the DOF part of the residual is zero at equilibrium), and their geometric terms added
// to geometric6.
void add_plane_constraint_terms(const LegChainDesign& design, const LegChainData& d, int n,
                                const Wrench& wrench, const Vec6<double>& rod_wrench,
                                Matrix6d& geometric6) {
  Eigen::Matrix<double, 6, Eigen::Dynamic, 0, 6, 6> Gc(6, n);
  for (int j = 0; j < n; ++j) {
    const Eigen::Vector3d nj = design.legs[static_cast<std::size_t>(j)].plane_normal.normalized();
    Gc.col(j).head<3>() = nj;
    Gc.col(j).tail<3>() = d.r.col(j).cross(nj);
  }
  const VecM lambda = (Gc.transpose() * Gc).ldlt().solve(Gc.transpose() * (wrench - rod_wrench));
  for (int j = 0; j < n; ++j)
    geometric6 += constraint_geometric_stiffness(
        lambda(j), design.legs[static_cast<std::size_t>(j)].plane_normal.normalized(), d.r.col(j));
}

}  // namespace

void LegChainMachine::compute_compliance_metrics(LegChainData& d, const VecM& f,
                                                 const Wrench& wrench, PoseMetrics& out) const {
  const int n = num_actuators();
  const Eigen::PartialPivLU<MatM> lu(d.A);
  const MatM Ainv = lu.inverse();
  const MatM C = Ainv * d.k.cwiseInverse().asDiagonal() * Ainv.transpose();
  const Matrix6d C6 = d.T * C * d.T.transpose();
  fill_compliance_metrics(C6, wrench, out, d.matrices);

  // The loaded stiffness on the DOF.
  const Eigen::Matrix<double, 3, Eigen::Dynamic, 0, 3, 6> Tr = d.T.bottomRows(3);
  MatM KT = MatM::Zero(n, n);
  Matrix6d geometric6 = Matrix6d::Zero();  // UPS legs and constraints, on the full twist
  Vec6<double> rod_wrench = Vec6<double>::Zero();
  for (int i = 0; i < n; ++i) {
    const LegChainLeg& leg = design_.legs[static_cast<std::size_t>(i)];
    const Eigen::Vector3d s = d.s.col(i), r = d.r.col(i);
    const Eigen::Matrix<double, 1, Eigen::Dynamic, 1, 1, 6> a = d.A.row(i);
    rod_wrench.head<3>() += f(i) * s;
    rod_wrench.tail<3>() += f(i) * r.cross(s);
    if (leg.kind == LegKind::kUPS) {
      KT += d.k(i) * a.transpose() * a;
      geometric6 += geometric_stiffness(f(i), s, r, d.q(i));
      continue;
    }
    Eigen::Vector3d c, dc;
    actuated_point(i, d.q(i), c, dc);
    const Eigen::Vector3d ddc = leg.kind == LegKind::kRUS ? Eigen::Vector3d(-(c - leg.base_point))
                                                          : Eigen::Vector3d::Zero();
    const double l = (d.position + r - c).norm();
    const double kr = 1.0 / d.link_compliance(i);
    const double B = d.B(i);
    const Eigen::Matrix3d Pi_l = (Eigen::Matrix3d::Identity() - s * s.transpose()) / l;
    Eigen::Matrix<double, 3, Eigen::Dynamic, 0, 3, 6> G(3, n);
    G = d.T.topRows(3) - cross_matrix(r) * Tr;
    // dq~ = g^T dx / D (0 for a rigid actuator).
    Eigen::Matrix<double, 1, Eigen::Dynamic, 1, 1, 6> dq = Eigen::Matrix<double, 1, 6>::Zero(1, n);
    if (d.actuator_compliance(i) > 0.0) {
      const double ka = 1.0 / d.actuator_compliance(i);
      const double D = ka + B * B * kr + f(i) * dc.dot(Pi_l * dc) - f(i) * s.dot(ddc);
      dq = (B * kr * a + f(i) * dc.transpose() * Pi_l * G) / D;
    }
    const Eigen::Matrix<double, 1, Eigen::Dynamic, 1, 1, 6> dl = a - B * dq;
    KT += kr * a.transpose() * dl;
    const Eigen::Matrix<double, 3, Eigen::Dynamic, 0, 3, 6> ds = Pi_l * (G - dc * dq);
    Eigen::Matrix<double, 6, Eigen::Dynamic, 0, 6, 6> dwrench(6, n);
    dwrench.topRows(3) = ds;
    dwrench.bottomRows(3) = cross_matrix(s) * cross_matrix(r) * Tr + cross_matrix(r) * ds;
    KT += f(i) * d.T.transpose() * dwrench;
  }
  if (design_.mobility == PlatformMobility::kPlanarLegs)
    add_plane_constraint_terms(design_, d, n, wrench, rod_wrench, geometric6);
  KT += d.T.transpose() * geometric6 * d.T;
  const MatM K = d.A.transpose() * d.k.asDiagonal() * d.A;
  out.stiffness_min_loaded = loaded_stiffness_min(C, KT - K, d.T, &d.matrices.loaded_compliance_tt);
}

Matrix6d LegChainMachine::full_twist_geometric_stiffness(const LegChainData& d, const VecM& f,
                                                         const Wrench& wrench) const {
  const int n = num_actuators();
  Matrix6d geometric6 = Matrix6d::Zero();
  Vec6<double> rod_wrench = Vec6<double>::Zero();
  for (int i = 0; i < n; ++i) {
    const LegChainLeg& leg = design_.legs[static_cast<std::size_t>(i)];
    const Eigen::Vector3d s = d.s.col(i), r = d.r.col(i);
    rod_wrench.head<3>() += f(i) * s;
    rod_wrench.tail<3>() += f(i) * r.cross(s);
    const double l = leg.kind == LegKind::kUPS ? d.q(i) : (d.position + r - d.c.col(i)).norm();
    geometric6 += geometric_stiffness(f(i), s, r, l);
  }
  if (design_.mobility == PlatformMobility::kPlanarLegs)
    add_plane_constraint_terms(design_, d, n, wrench, rod_wrench, geometric6);
  return geometric6;
}

}  // namespace pkmopt
