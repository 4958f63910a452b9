#include "models/compliance_metrics.hpp"

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <Eigen/LU>
#include <cmath>
#include <limits>

namespace pkmopt {
namespace {

Eigen::Matrix3d cross_matrix(const Eigen::Vector3d& v) {
  Eigen::Matrix3d m;
  m << 0.0, -v.z(), v.y(), v.z(), 0.0, -v.x(), -v.y(), v.x(), 0.0;
  return m;
}

}  // namespace

Matrix6d geometric_stiffness(double tension, const Eigen::Vector3d& s, const Eigen::Vector3d& r,
                             double length) {
  const Eigen::Matrix3d Pi_l = (Eigen::Matrix3d::Identity() - s * s.transpose()) / length;
  const Eigen::Matrix3d rx = cross_matrix(r);
  Matrix6d K;
  K.topLeftCorner<3, 3>() = Pi_l;
  K.topRightCorner<3, 3>() = -Pi_l * rx;
  K.bottomLeftCorner<3, 3>() = rx * Pi_l;
  K.bottomRightCorner<3, 3>() = cross_matrix(s) * rx - rx * Pi_l * rx;
  return tension * K;
}

Matrix6d constraint_geometric_stiffness(double force, const Eigen::Vector3d& n,
                                        const Eigen::Vector3d& r) {
  Matrix6d K = Matrix6d::Zero();
  K.bottomRightCorner<3, 3>() = force * cross_matrix(n) * cross_matrix(r);
  return K;
}

void fill_compliance_metrics(const Matrix6d& C, const Wrench& w, PoseMetrics& out) {
  out.compliance = C;
  const Vec6<double> dx = C * w;
  out.tcp_deflection = dx.head<3>().norm();
  out.tcp_rotation_deflection = dx.tail<3>().norm();
  const Eigen::Matrix3d Ctt = 0.5 * (C.topLeftCorner<3, 3>() + C.topLeftCorner<3, 3>().transpose());
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig;
  eig.computeDirect(Ctt);
  Eigen::Vector3d v = eig.eigenvectors().col(2);
  Eigen::Index largest = 0;
  v.cwiseAbs().maxCoeff(&largest);
  if (v(largest) < 0.0) v = -v;
  out.stiffness_min_direction = v.allFinite() ? v : Eigen::Vector3d::Zero();
}

double loaded_stiffness_min(const DofMatrix& C, const DofMatrix& G, const TwistMap& T,
                            Eigen::Matrix3d* loaded_tt) {
  constexpr double kInf = std::numeric_limits<double>::infinity();
  if (loaded_tt) loaded_tt->setConstant(kInf);
  const Eigen::Index m = C.rows();
  // Stability: x^T K_T x > 0 for all x  <=>  y^T (C + C G C) y > 0 for all y (x = C y).
  const DofMatrix CGC = C + C * G * C;
  const DofMatrix sym = 0.5 * (CGC + CGC.transpose());
  const Eigen::LLT<DofMatrix> llt(sym);
  if (llt.info() != Eigen::Success) return 0.0;
  const DofMatrix M = DofMatrix::Identity(m, m) + C * G;
  const Eigen::FullPivLU<DofMatrix> lu(M);
  if (!lu.isInvertible()) return 0.0;
  const DofMatrix CT = lu.solve(C);
  const Eigen::Matrix3d Ctt = (T.topRows(3) * CT * T.topRows(3).transpose());
  if (loaded_tt) *loaded_tt = Ctt;
  return loaded_stiffness_of(Ctt);
}

double loaded_stiffness_of(const Eigen::Matrix3d& loaded_tt) {
  if (!loaded_tt.allFinite()) return 0.0;
  const Eigen::Vector3d sv = Eigen::JacobiSVD<Eigen::Matrix3d>(loaded_tt).singularValues();
  if (!(sv(0) > 0.0) || !std::isfinite(sv(0))) return 0.0;
  return 1.0 / sv(0);
}

void set_singular_compliance_metrics(PoseMetrics& out) {
  constexpr double kInf = std::numeric_limits<double>::infinity();
  out.compliance = Matrix6d::Constant(kInf);
  out.tcp_deflection = kInf;
  out.tcp_rotation_deflection = kInf;
  out.stiffness_min_direction.setZero();
  out.stiffness_min_loaded = 0.0;
  out.loaded_compliance_tt.setConstant(kInf);
}

}  // namespace pkmopt
