#include "models/stiffness/compliance_metrics.hpp"

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <limits>

#include "models/core/linalg.hpp"

namespace pkmopt {
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

void fill_compliance_metrics(const Matrix6d& C, const Wrench& w, PoseMetrics& out,
                             PoseCompliance& matrices) {
  matrices.compliance = C;
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

namespace {

// The loaded stiffness for a fixed-size (6x6) or a capped dynamic-size DOF matrix type.
template <class Mat, class Map>
double loaded_stiffness(const Mat& C, const Mat& G, const Map& T, Eigen::Matrix3d* loaded_tt) {
  constexpr double kInf = std::numeric_limits<double>::infinity();
  if (loaded_tt) loaded_tt->setConstant(kInf);
  // Stability: x^T K_T x > 0 for all x  <=>  y^T (C + C G C) y > 0 for all y (x = C y).
  const Mat CG = C * G;
  const Mat CGC = C + CG * C;
  const Mat sym = 0.5 * (CGC + CGC.transpose());
  const Eigen::LLT<Mat> llt(sym);
  if (llt.info() != Eigen::Success) return 0.0;
  // C_T = (I + C G)^-1 C; I + C G = C K_T is invertible when both are positive definite.
  Mat M = CG;
  M.diagonal().array() += 1.0;
  const Eigen::PartialPivLU<Mat> lu(M);
  const Mat CT = lu.solve(C);
  const Eigen::Matrix3d Ctt = T.topRows(3) * CT * T.topRows(3).transpose();
  if (!Ctt.allFinite()) return 0.0;
  if (loaded_tt) *loaded_tt = Ctt;
  return loaded_stiffness_of(Ctt);
}

}  // namespace

double loaded_stiffness_min(const DofMatrix& C, const DofMatrix& G, const TwistMap& T,
                            Eigen::Matrix3d* loaded_tt) {
  if (C.rows() == 6 && T.cols() == 6 && T.isIdentity(0.0))
    return loaded_stiffness_min(Matrix6d(C), Matrix6d(G), loaded_tt);
  return loaded_stiffness(C, G, T, loaded_tt);
}

double loaded_stiffness_min(const Matrix6d& C, const Matrix6d& G, Eigen::Matrix3d* loaded_tt) {
  return loaded_stiffness(C, G, Matrix6d::Identity(), loaded_tt);
}

double loaded_stiffness_of(const Eigen::Matrix3d& loaded_tt) {
  if (!loaded_tt.allFinite()) return 0.0;
  // sigma_max^2 = lambda_max(B^T B) (the iterative solver: accurate to eps relative to it).
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig;
  eig.compute(loaded_tt.transpose() * loaded_tt, Eigen::EigenvaluesOnly);
  const double sigma_max = std::sqrt(std::max(eig.eigenvalues()(2), 0.0));
  if (!(sigma_max > 0.0) || !std::isfinite(sigma_max)) return 0.0;
  return 1.0 / sigma_max;
}

void set_singular_compliance_metrics(PoseMetrics& out, PoseCompliance& matrices) {
  constexpr double kInf = std::numeric_limits<double>::infinity();
  matrices.compliance = Matrix6d::Constant(kInf);
  out.tcp_deflection = kInf;
  out.tcp_rotation_deflection = kInf;
  out.stiffness_min_direction.setZero();
  out.stiffness_min_loaded = 0.0;
  matrices.loaded_compliance_tt.setConstant(kInf);
}

void set_singular_metrics(PoseMetrics& out, bool compliance_metrics, PoseCompliance& matrices) {
  out.singularity_margin = 0.0;
  out.stiffness_min = 0.0;
  out.tau.setConstant(std::numeric_limits<double>::infinity());
  out.tcp_error_max = std::numeric_limits<double>::infinity();
  if (compliance_metrics) set_singular_compliance_metrics(out, matrices);
}

}  // namespace pkmopt
