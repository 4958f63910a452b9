// An independent linear finite-element frame model for the stiffness tests
// (tests/models/stiffness/virtual_joint_test.cpp, tests/models/leg_chain/leg_chain_vjm_test.cpp):
// nodes with 6 DOF [u; theta] (base axes), 3D Euler-Bernoulli frame elements (the textbook 12x12
// local stiffness, e.g. Przemieniecki, Theory of Matrix Structural Analysis, 1968, ch. 5), 6x6
// springs between nodes or to the ground, and joints as exact linear constraints C u = 0
// (eliminated with an orthonormal null-space basis). It shares no code with
// models/stiffness/virtual_joint.
//
// Example (a cantilever loaded at a point rigidly attached to its tip):
//   FrameModel fe;
//   const int base = fe.node(a);
//   for (int k = 0; k < 6; ++k) fe.fix_along(base, k >= 3, Eigen::Vector3d::Unit(k % 3));
//   const int tip = fe_beam(fe, base, b, 4, section, y);
//   const int r = fe.node(ref);
//   fe.rigid(tip, r);
//   Matrix6d C = fe.compliance(r);   // [u; theta] at r per unit [f; m] at r
#pragma once

#include <gtest/gtest.h>

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <Eigen/QR>
#include <utility>
#include <vector>

#include "models/core/pose.hpp"
#include "models/stiffness/virtual_joint.hpp"

namespace pkmopt::frame_fe {

using Eigen::Vector3d;

// Relative difference of two 6x6 stiffness (compliance) matrices after scaling the rotational
// rows and columns by 1/L (by L) so that every block has the unit N/m (m/N).
inline double rel_diff(const Matrix6d& A, const Matrix6d& B, bool compliance, double L = 0.5) {
  const double r = compliance ? L : 1.0 / L;
  const Vector6d d = (Vector6d() << 1, 1, 1, r, r, r).finished();
  return (d.asDiagonal() * (A - B) * d.asDiagonal()).norm() /
         (d.asDiagonal() * B * d.asDiagonal()).norm();
}

// The frame model (see the header comment).
class FrameModel {
 public:
  static constexpr int kGround = -1;
  int node(const Vector3d& p) {
    nodes_.push_back(p);
    return static_cast<int>(nodes_.size()) - 1;
  }
  const Vector3d& position(int n) const { return nodes_[static_cast<std::size_t>(n)]; }

  void beam(int a, int b, const BeamSection& s, const Vector3d& y_dir) {
    const Vector3d d = position(b) - position(a);
    const double L = d.norm();
    const Vector3d x = d / L, y = (y_dir - y_dir.dot(x) * x).normalized(), z = x.cross(y);
    Eigen::Matrix<double, 12, 12> k = Eigen::Matrix<double, 12, 12>::Zero();
    auto sym = [&k](int i, int j, double v) { k(i, j) = k(j, i) = v; };
    sym(0, 0, s.E * s.A / L), sym(6, 6, s.E * s.A / L), sym(0, 6, -s.E * s.A / L);
    sym(3, 3, s.G * s.J / L), sym(9, 9, s.G * s.J / L), sym(3, 9, -s.G * s.J / L);
    // bending in the local x-y plane: v (1, 7), theta_z (5, 11), Iz
    double a1 = 12 * s.E * s.Iz / (L * L * L), b1 = 6 * s.E * s.Iz / (L * L);
    double c1 = 4 * s.E * s.Iz / L, d1 = 2 * s.E * s.Iz / L;
    sym(1, 1, a1), sym(1, 5, b1), sym(1, 7, -a1), sym(1, 11, b1), sym(5, 5, c1), sym(5, 7, -b1);
    sym(5, 11, d1), sym(7, 7, a1), sym(7, 11, -b1), sym(11, 11, c1);
    // bending in the local x-z plane: w (2, 8), theta_y (4, 10), Iy
    a1 = 12 * s.E * s.Iy / (L * L * L), b1 = 6 * s.E * s.Iy / (L * L);
    c1 = 4 * s.E * s.Iy / L, d1 = 2 * s.E * s.Iy / L;
    sym(2, 2, a1), sym(2, 4, -b1), sym(2, 8, -a1), sym(2, 10, -b1), sym(4, 4, c1), sym(4, 8, b1);
    sym(4, 10, d1), sym(8, 8, a1), sym(8, 10, b1), sym(10, 10, c1);
    Eigen::Matrix3d lambda;  // rows: the local axes in base axes
    lambda << x.transpose(), y.transpose(), z.transpose();
    Eigen::Matrix<double, 12, 12> T = Eigen::Matrix<double, 12, 12>::Zero();
    for (int i = 0; i < 4; ++i) T.block<3, 3>(3 * i, 3 * i) = lambda;
    elements_.push_back({a, b, T.transpose() * k * T});
  }
  // Energy 1/2 d^T Ks d with d = x_b - x_a (b = kGround: d = -x_a).
  void spring(int a, int b, const Matrix6d& Ks) {
    Eigen::Matrix<double, 12, 12> k;
    k << Ks, -Ks, -Ks, Ks;
    elements_.push_back({a, b, k});
  }
  // A row sum_k coef_k * dof_k = 0; dof = 6 node + component (3..5: rotations).
  void constrain(std::vector<std::pair<int, double>> row) { rows_.push_back(std::move(row)); }
  void fix_along(int n, bool rotation, const Vector3d& dir) { tie_along(n, -1, rotation, dir); }
  // dir . (x_a - x_b) = 0 for the translations or rotations (b = -1: dir . x_a = 0).
  void tie_along(int a, int b, bool rotation, const Vector3d& dir) {
    std::vector<std::pair<int, double>> row;
    for (int k = 0; k < 3; ++k) {
      row.emplace_back(6 * a + (rotation ? 3 : 0) + k, dir(k));
      if (b >= 0) row.emplace_back(6 * b + (rotation ? 3 : 0) + k, -dir(k));
    }
    constrain(std::move(row));
  }
  void tie_translations(int a, int b) {
    for (int k = 0; k < 3; ++k) tie_along(a, b, false, Vector3d::Unit(k));
  }
  // A revolute joint: shared translations and the rotations across the axis.
  void revolute(int a, int b, const Vector3d& axis) {
    tie_translations(a, b);
    const Vector3d e1 = axis.unitOrthogonal(), e2 = axis.normalized().cross(e1);
    tie_along(a, b, true, e1);
    tie_along(a, b, true, e2);
  }
  // Node s moves rigidly with node m: u_s = u_m + theta_m x (p_s - p_m), theta_s = theta_m.
  void rigid(int m, int s) {
    const Vector3d r = position(s) - position(m);
    for (int k = 0; k < 3; ++k) {                      // row k of u_s - u_m + r x theta_m = 0
      const Vector3d rk = Vector3d::Unit(k).cross(r);  // (r x theta)_k = (e_k x r) . theta
      constrain({{6 * s + k, 1.0},
                 {6 * m + k, -1.0},
                 {6 * m + 3, rk.x()},
                 {6 * m + 4, rk.y()},
                 {6 * m + 5, rk.z()}});
      tie_along(s, m, true, Vector3d::Unit(k));
    }
  }
  // Displacements [u; theta] of node n under unit forces and moments at node n (6 load cases).
  Matrix6d compliance(int n) const {
    const int dofs = 6 * static_cast<int>(nodes_.size());
    Eigen::MatrixXd K = Eigen::MatrixXd::Zero(dofs, dofs);
    for (const Element& e : elements_) {
      const int idx[2] = {e.a, e.b};
      for (int i = 0; i < 2; ++i) {
        for (int j = 0; j < 2; ++j) {
          if (idx[i] == kGround || idx[j] == kGround) continue;
          K.block<6, 6>(6 * idx[i], 6 * idx[j]) += e.k.block<6, 6>(6 * i, 6 * j);
        }
      }
    }
    Eigen::MatrixXd Ct = Eigen::MatrixXd::Zero(dofs, static_cast<Eigen::Index>(rows_.size()));
    for (std::size_t r = 0; r < rows_.size(); ++r) {
      for (const auto& [dof, c] : rows_[r]) Ct(dof, static_cast<Eigen::Index>(r)) += c;
    }
    const Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(Ct);
    const Eigen::MatrixXd Q = qr.householderQ();
    const Eigen::MatrixXd Z = Q.rightCols(dofs - qr.rank());
    const Eigen::MatrixXd Kr = Z.transpose() * K * Z;
    const Eigen::VectorXd s = Kr.diagonal().cwiseSqrt().cwiseInverse();  // Jacobi scaling
    const Eigen::LLT<Eigen::MatrixXd> llt(s.asDiagonal() * Kr * s.asDiagonal());
    EXPECT_EQ(llt.info(), Eigen::Success) << "FE model has a mechanism";
    const Eigen::MatrixXd F = Z.middleRows(6 * n, 6).transpose();  // Z^T (unit loads at n)
    const Eigen::MatrixXd U = Z * (s.asDiagonal() * llt.solve(s.asDiagonal() * F));
    return U.middleRows(6 * n, 6);
  }

 private:
  struct Element {
    int a, b;
    Eigen::Matrix<double, 12, 12> k;
  };
  std::vector<Vector3d> nodes_;
  std::vector<Element> elements_;
  std::vector<std::vector<std::pair<int, double>>> rows_;
};

// A chain of n frame elements from node a to the new end node at b; returns the end node.
inline int fe_beam(FrameModel& fe, int a, const Vector3d& b, int n, const BeamSection& s,
                   const Vector3d& y) {
  const Vector3d pa = fe.position(a);
  int prev = a;
  for (int i = 1; i <= n; ++i) {
    const int next = fe.node(pa + (b - pa) * (static_cast<double>(i) / n));
    fe.beam(prev, next, s, y);
    prev = next;
  }
  return prev;
}

// A rod with ball joints at both ends (a: node of the previous body, b: of the next), as two frame
// elements whose end rotations are free; its spin about its own axis is fixed at one end.
inline void fe_rod(FrameModel& fe, int a, int b, const BeamSection& s) {
  const Vector3d pa = fe.position(a), pb = fe.position(b), axis = (pb - pa).normalized();
  const int start = fe.node(pa);
  const int end = fe_beam(fe, start, pb, 2, s, axis.unitOrthogonal());
  fe.tie_translations(a, start);
  fe.tie_translations(end, b);
  fe.fix_along(start, true, axis);
}

// A joint between nodes a and b: the translations across s tied, along s a spring k (0: tied).
inline void fe_axial_joint(FrameModel& fe, int a, int b, const Vector3d& s, double k) {
  if (!(k > 0.0)) {
    fe.tie_translations(a, b);
    return;
  }
  const Vector3d e1 = s.unitOrthogonal(), e2 = s.cross(e1);
  fe.tie_along(a, b, false, e1);
  fe.tie_along(a, b, false, e2);
  Matrix6d ks = Matrix6d::Zero();
  ks.topLeftCorner<3, 3>() = k * s * s.transpose();
  fe.spring(a, b, ks);
}

}  // namespace pkmopt::frame_fe
