#include "models/dynamics/machine_dynamics.hpp"

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <cmath>
#include <limits>
#include <numbers>

#include "models/core/linalg.hpp"

namespace pkmopt {
Matrix6d tcp_mass_matrix(const MassModel& model, const Eigen::Matrix3d& R,
                         const Eigen::Vector3d& tcp, const std::vector<LegPoints>& legs,
                         const Eigen::Vector3d& tcp_position) {
  const RigidBody& body = model.platform;
  const Eigen::Vector3d rho = R * (body.centre_of_mass - tcp);
  const Eigen::Matrix3d X = cross_matrix(rho);
  const Eigen::Matrix3d I_R = R * body.inertia * R.transpose();
  Matrix6d M;
  M.topLeftCorner<3, 3>() = body.mass * Eigen::Matrix3d::Identity();
  M.topRightCorner<3, 3>() = -body.mass * X;
  M.bottomLeftCorner<3, 3>() = body.mass * X;
  M.bottomRightCorner<3, 3>() = I_R - body.mass * X * X;
  if (!model.legs.any()) return M;
  for (const LegPoints& leg : legs) {
    const Eigen::Matrix3d M_P = leg_mass_matrix(leg, model.legs);
    const Eigen::Matrix3d Xr = cross_matrix(leg.platform - tcp_position);
    // T = [I, -Xr]: T^T M_P T = [M_P, -M_P Xr; Xr M_P, -Xr M_P Xr] (Xr^T = -Xr).
    const Eigen::Matrix3d MX = M_P * Xr;
    M.topLeftCorner<3, 3>() += M_P;
    M.topRightCorner<3, 3>() -= MX;
    M.bottomLeftCorner<3, 3>() -= MX.transpose();
    M.bottomRightCorner<3, 3>() -= Xr * MX;
  }
  return 0.5 * (M + M.transpose());
}

Wrench dynamic_wrench(const MassModel& model, const Eigen::Matrix3d& R, const Eigen::Vector3d& tcp,
                      const std::vector<LegPoints>& legs, const Eigen::Vector3d& tcp_position,
                      const Vector6d& xi, const Vector6d& xi_dot) {
  return dynamic_wrench(model, R, tcp, legs, tcp_position, xi, xi_dot, model.gravity);
}

Wrench dynamic_wrench(const MassModel& model, const Eigen::Matrix3d& R, const Eigen::Vector3d& tcp,
                      const std::vector<LegPoints>& legs, const Eigen::Vector3d& tcp_position,
                      const Vector6d& xi, const Vector6d& xi_dot, const Eigen::Vector3d& gravity) {
  const Eigen::Vector3d v = xi.head<3>(), omega = xi.tail<3>();
  const Eigen::Vector3d a = xi_dot.head<3>(), alpha = xi_dot.tail<3>();
  const RigidBody& body = model.platform;
  const Eigen::Vector3d rho = R * (body.centre_of_mass - tcp);
  const Eigen::Matrix3d I_R = R * body.inertia * R.transpose();
  const Eigen::Vector3d a_c = a + alpha.cross(rho) + omega.cross(omega.cross(rho));
  const Eigen::Vector3d f = body.mass * (gravity - a_c);
  Wrench w;
  w.head<3>() = f;
  w.tail<3>() = rho.cross(f) - I_R * alpha - omega.cross(I_R * omega);
  if (!model.legs.any()) return w;
  for (const LegPoints& leg : legs) {
    const Eigen::Vector3d r = leg.platform - tcp_position;
    const Eigen::Vector3d v_P = v + omega.cross(r);
    const Eigen::Vector3d a_P = a + alpha.cross(r) + omega.cross(omega.cross(r));
    const Eigen::Vector3d f_P = leg_dynamic_force(leg, model.legs, v_P, a_P, gravity);
    w.head<3>() += f_P;
    w.tail<3>() += r.cross(f_P);
  }
  return w;
}

Eigen::Vector3d net_dynamic_force(const MassModel& model, const Eigen::Matrix3d& R,
                                  const Eigen::Vector3d& tcp, const std::vector<LegPoints>& legs,
                                  const Eigen::Vector3d& tcp_position, const Vector6d& xi,
                                  const Vector6d& xi_dot, const Eigen::Vector3d& gravity) {
  const Eigen::Vector3d v = xi.head<3>(), omega = xi.tail<3>();
  const Eigen::Vector3d a = xi_dot.head<3>(), alpha = xi_dot.tail<3>();
  const RigidBody& body = model.platform;
  const Eigen::Vector3d rho = R * (body.centre_of_mass - tcp);
  const Eigen::Vector3d a_c = a + alpha.cross(rho) + omega.cross(omega.cross(rho));
  Eigen::Vector3d f = body.mass * (gravity - a_c);
  if (!model.legs.any()) return f;
  for (const LegPoints& leg : legs) {
    const Eigen::Vector3d r = leg.platform - tcp_position;
    const Eigen::Vector3d v_P = v + omega.cross(r);
    const Eigen::Vector3d a_P = a + alpha.cross(r) + omega.cross(omega.cross(r));
    LegBody bodies[2];
    if (!leg_bodies(leg, model.legs, v_P, a_P, bodies)) continue;
    for (const LegBody& b : bodies) f += b.mass * (gravity - b.acceleration);
  }
  return f;
}

Eigen::Matrix<double, 9, 9> carried_mass_matrix(const MassModel& model, const Eigen::Matrix3d& R,
                                                const Eigen::Vector3d& tcp,
                                                const std::vector<LegPoints>& legs,
                                                const Eigen::Vector3d& tcp_position) {
  Eigen::Matrix<double, 9, 9> Q = Eigen::Matrix<double, 9, 9>::Zero();
  Q.bottomRightCorner<6, 6>() = tcp_mass_matrix(model, R, tcp, legs, tcp_position);
  if (!model.legs.any()) return Q;
  Eigen::Matrix3d Q_dd = Eigen::Matrix3d::Zero();
  Eigen::Matrix<double, 3, 6> Q_dxi = Eigen::Matrix<double, 3, 6>::Zero();
  for (const LegPoints& leg : legs) {
    LegBody bodies[2];
    if (!leg_bodies(leg, model.legs, Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero(), bodies)) {
      continue;
    }
    Eigen::Matrix3d M_P = Eigen::Matrix3d::Zero(), N_P = Eigen::Matrix3d::Zero();
    double mass = 0.0;
    for (const LegBody& b : bodies) {
      M_P += b.mass * b.A.transpose() * b.A + b.W.transpose() * b.inertia * b.W;
      N_P += b.mass * b.A;
      mass += b.mass;
    }
    Eigen::Matrix<double, 3, 6> T;
    T << Eigen::Matrix3d::Identity(), -cross_matrix(leg.platform - tcp_position);
    Q_dd += M_P - N_P - N_P.transpose() + mass * Eigen::Matrix3d::Identity();
    Q_dxi += (N_P - M_P) * T;
  }
  Q.topLeftCorner<3, 3>() = 0.5 * (Q_dd + Q_dd.transpose());
  Q.topRightCorner<3, 6>() = Q_dxi;
  Q.bottomLeftCorner<6, 3>() = Q_dxi.transpose();
  return Q;
}

namespace {

// The modes for a dynamic-size or a fixed-size (6x6) matrix type.
template <class Mat>
NaturalModes modes_of(const Mat& C, const Mat& M, bool shapes) {
  NaturalModes out;
  const Eigen::Index n = M.rows();
  out.frequencies = Eigen::VectorXd::Constant(n, std::numeric_limits<double>::infinity());
  if (!C.allFinite() || !M.allFinite() || C.rows() != n) return out;
  const Eigen::LLT<Mat> llt(M);
  if (llt.info() != Eigen::Success) return out;
  const Mat L = llt.matrixL();
  Mat S = L.transpose() * C * L;
  S = (0.5 * (S + S.transpose())).eval();
  const Eigen::SelfAdjointEigenSolver<Mat> eig(
      S, shapes ? Eigen::ComputeEigenvectors : Eigen::EigenvaluesOnly);
  if (eig.info() != Eigen::Success) return out;
  // Ascending eigenvalues mu = 1 / omega^2: the frequencies descend; reverse them.
  const double scale = S.diagonal().cwiseAbs().maxCoeff();
  if (shapes) out.shapes.resize(n, n);
  for (Eigen::Index k = 0; k < n; ++k) {
    const Eigen::Index j = n - 1 - k;
    const double mu = eig.eigenvalues()(j);
    // mu <= 0 (to rounding): a rigid direction.
    out.frequencies(k) = mu > 1e-14 * scale ? 1.0 / (2.0 * std::numbers::pi * std::sqrt(mu))
                                            : std::numeric_limits<double>::infinity();
    if (shapes) {
      Eigen::VectorXd x = L.transpose().template triangularView<Eigen::Upper>().solve(
          eig.eigenvectors().col(j));  // unit M-norm: y^T y = 1
      Eigen::Index lead = 0;
      x.cwiseAbs().maxCoeff(&lead);
      if (x(lead) < 0.0) x = -x;
      out.shapes.col(k) = x;
    }
  }
  out.ok = true;
  return out;
}

}  // namespace

NaturalModes natural_modes(const Eigen::MatrixXd& C, const Eigen::MatrixXd& M, bool shapes) {
  return modes_of(C, M, shapes);
}

NaturalModes natural_frequencies6(const Matrix6d& C, const Matrix6d& M) {
  return modes_of(C, M, false);
}

}  // namespace pkmopt
