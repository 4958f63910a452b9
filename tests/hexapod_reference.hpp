// An independent reference of the hexapod metric set and the rules the fast paths are held to,
// shared by the HexapodFastPath harness (tests/models/hexapod/hexapod_test.cpp) and the batch tests
// (tests/models/hexapod/hexapod_batch_test.cpp).
//
// reference_metrics: Eigen's general solvers, nothing of the library's kernels: JacobiSVD for
// cond(J_h) and cond(J), FullPivLU for det J, J^-1 and the leg forces, the iterative
// SelfAdjointEigenSolver for lambda_max(C_tt), all 64 vertices of the error box.
// expect_metrics_match_reference: relative tolerance 1e-10; where cond(J) is so large that no
// backward-stable method (the reference included) fixes the result to 1e-10, 64 eps cond(J);
// within a factor 2 of the singularity threshold either answer, and a singular answer must be
// the exact singular outputs.
#pragma once

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <Eigen/LU>
#include <Eigen/SVD>
#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "models/hexapod/hexapod.hpp"
#include "tests/sample_machines.hpp"

namespace pkmopt::hexapod_reference {

/// A semi-regular hexapod with similar hexagons (architecturally singular: platform separation
/// 120 deg minus the base's) whose platform joints are then moved by 1e-9 .. 1e-2 m (log-uniform
/// amplitude): designs at every distance from the singularity. Legs 0.2 .. 2 m, steel 3 cm^2,
/// an actuator stiffness of 2e8 N/m when asked.
inline HexapodDesign near_similar_hexapod(sample_machines::Uniform& u, bool actuator_stiffness) {
  const double base_sep = u(10, 60);
  HexapodDesign d = semi_regular_hexapod(u(0.4, 0.9), deg_to_rad(base_sep), u(0.15, 0.4),
                                         deg_to_rad(120.0 - base_sep));
  const double amplitude = std::pow(10.0, u(-9, -2));
  for (int i = 0; i < 6; ++i) {
    for (int c = 0; c < 3; ++c) d.platform_joints(c, i) += amplitude * u(-1, 1);
  }
  d.min_length = 0.2;
  d.max_length = 2.0;
  d.stiffness.E = 2.1e11;
  d.stiffness.area = 3e-4;
  d.stiffness.actuator_stiffness = actuator_stiffness ? 2e8 : 0.0;
  return d;
}

/// An independent rotation: fixed-axis x, then y, then z.
inline Eigen::Matrix3d rotation(const Eigen::Vector3d& a) {
  return (Eigen::AngleAxisd(a(2), Eigen::Vector3d::UnitZ()) *
          Eigen::AngleAxisd(a(1), Eigen::Vector3d::UnitY()) *
          Eigen::AngleAxisd(a(0), Eigen::Vector3d::UnitX()))
      .toRotationMatrix();
}

struct ReferenceMetrics {
  Vec6<double> q;
  Vec6<double> tau;
  double stiffness_min = 0.0;
  double rcond = 0.0;  // sigma_min / sigma_max of J_h
  double det_j = 0.0;
  double tcp_error_max = 0.0;
  double cond = 0.0;  // cond(J) (2-norm), for the error bound of ill-conditioned poses
};

inline ReferenceMetrics reference_metrics(const Hexapod& hexapod, const Pose& pose,
                                          const Wrench& w) {
  const HexapodDesign& d = hexapod.design();
  const Eigen::Matrix3d R = rotation(pose.angles);
  ReferenceMetrics ref;
  Matrix6d J;
  Vec6<double> k;
  for (int i = 0; i < 6; ++i) {
    const Eigen::Vector3d r = R * (d.platform_joints.col(i) - d.tcp);
    const Eigen::Vector3d l = pose.position + r - d.base_joints.col(i);
    ref.q(i) = l.norm();
    const Eigen::Vector3d s = l / ref.q(i);
    J.block<1, 3>(i, 0) = s.transpose();
    J.block<1, 3>(i, 3) = r.cross(s).transpose();
    double compliance = d.stiffness.axial_stiffness > 0.0
                            ? 1.0 / d.stiffness.axial_stiffness
                            : ref.q(i) / (d.stiffness.E * d.stiffness.area);
    if (d.stiffness.actuator_stiffness > 0.0) compliance += 1.0 / d.stiffness.actuator_stiffness;
    k(i) = 1.0 / compliance;
  }
  Matrix6d Jh = J;
  Jh.rightCols<3>() /= hexapod.characteristic_length();
  const Vec6<double> sigma_h = Eigen::JacobiSVD<Matrix6d>(Jh).singularValues();
  ref.rcond = sigma_h(5) / sigma_h(0);
  const Vec6<double> sigma = Eigen::JacobiSVD<Matrix6d>(J).singularValues();
  ref.cond = sigma(0) / sigma(5);
  const Eigen::FullPivLU<Matrix6d> lu(J);
  ref.det_j = lu.determinant();
  const Matrix6d Jinv = lu.inverse();
  ref.tau = J.transpose().fullPivLu().solve(w);
  const Matrix6d C = Jinv * k.cwiseInverse().asDiagonal() * Jinv.transpose();
  const Eigen::Matrix3d Ctt = C.topLeftCorner<3, 3>();
  ref.stiffness_min = 1.0 / Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(Ctt).eigenvalues()(2);
  for (int mask = 0; mask < 64; ++mask) {
    Vec6<double> dq;
    for (int i = 0; i < 6; ++i) dq(i) = (mask >> i & 1) ? d.actuator_error : -d.actuator_error;
    ref.tcp_error_max = std::max(ref.tcp_error_max, (Jinv * dq).head<3>().norm());
  }
  return ref;
}

/// Checks metrics m of a pose against its reference (rules in the header comment); returns 1
/// when the pose was checked as non-singular, else 0.
inline int expect_metrics_match_reference(const PoseMetrics& m, const ReferenceMetrics& ref,
                                          const std::string& where) {
  for (int i = 0; i < 6; ++i) EXPECT_NEAR(m.q(i), ref.q(i), 1e-14 * ref.q(i)) << where;
  EXPECT_FALSE(std::isnan(m.det_j) || std::isnan(m.stiffness_min) ||
               std::isnan(m.singularity_margin) || std::isnan(m.tcp_error_max) || m.tau.hasNaN())
      << where;
  if (ref.rcond < 0.5 * kSingularRcond) {
    EXPECT_TRUE(m.singular) << where;
  }
  if (ref.rcond < 2.0 * kSingularRcond) {  // at the singularity threshold either answer is right
    if (m.singular) {
      EXPECT_EQ(m.singularity_margin, 0.0) << where;
      EXPECT_EQ(m.stiffness_min, 0.0) << where;
      EXPECT_TRUE(std::isinf(m.tcp_error_max)) << where;
      for (int i = 0; i < 6; ++i) EXPECT_TRUE(std::isinf(m.tau(i))) << where;
    }
    return 0;
  }
  EXPECT_FALSE(m.singular) << where << " rcond " << ref.rcond;
  if (m.singular) return 0;
  const double tol = std::max(1e-10, 64.0 * std::numeric_limits<double>::epsilon() * ref.cond);
  EXPECT_NEAR(m.singularity_margin, ref.rcond, tol * ref.rcond) << where;
  EXPECT_NEAR(m.det_j, ref.det_j, tol * std::abs(ref.det_j)) << where;
  EXPECT_NEAR(m.stiffness_min, ref.stiffness_min, tol * ref.stiffness_min) << where;
  EXPECT_NEAR(m.tcp_error_max, ref.tcp_error_max, tol * ref.tcp_error_max) << where;
  const double tau_scale = ref.tau.cwiseAbs().maxCoeff();
  for (int i = 0; i < 6; ++i) EXPECT_NEAR(m.tau(i), ref.tau(i), tol * tau_scale) << where;
  return 1;
}

/// A wrench with every component uniform in [-1000, 1000] (N, N*m).
inline Wrench random_wrench(sample_machines::Uniform& u) {
  Wrench w;
  for (int i = 0; i < 6; ++i) w(i) = u(-1000, 1000);
  return w;
}

}  // namespace pkmopt::hexapod_reference
