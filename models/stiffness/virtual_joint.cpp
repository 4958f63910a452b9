// Virtual-joint stiffness of legs; the formulas are in models/stiffness/virtual_joint.hpp.
#include "models/stiffness/virtual_joint.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>
#include <utility>

namespace pkmopt {
namespace {

// A scaled passive twist whose remaining norm (of a unit column, after the columns chosen before
// it are projected out) is below this is taken as dependent: about the sine of its angle to their
// span.
constexpr double kRankTolerance = 1e-10;
// A pivot of N^T S N below this times the largest diagonal entry counts as zero compliance.
constexpr double kRigidTolerance = 1e-13;

Eigen::Vector3d unit_axis(const Eigen::Vector3d& v, const char* what) {
  const double n = v.norm();
  if (!(n > 0.0) || !std::isfinite(n)) {
    throw std::invalid_argument(std::string("VjmLeg: ") + what + " is zero or not finite");
  }
  return v / n;
}

void require_positive(double value, const char* what) {
  if (!(value > 0.0) || !std::isfinite(value)) {
    throw std::invalid_argument(std::string("VjmLeg: ") + what + " must be positive and finite");
  }
}

// Twist of a unit joint motion at the reference point, translational part divided by L.
Vector6d scaled_twist(const Eigen::Vector3d& point, const Eigen::Vector3d& axis, bool rotational,
                      const Eigen::Vector3d& reference, double inv_length) {
  Vector6d t;
  if (rotational) {
    t.head<3>() = (point - reference).cross(axis) * inv_length;
    t.tail<3>() = axis;
  } else {
    t.head<3>() = axis * inv_length;
    t.tail<3>().setZero();
  }
  return t;
}

// Householder QR of the first n columns of the 6 x MaxCols matrix A, with column pivoting when
// `pivot`: A P = Q [R; 0]. Stops at the first column whose remaining norm is <= tol (columns
// assumed of unit norm when pivoting); returns the rank r. On return the upper triangle of A's
// first r columns holds R (in pivoted order), perm the column order, Q the 6x6 orthogonal factor.
template <int MaxCols>
int householder_qr6(Eigen::Matrix<double, 6, MaxCols>& A, int n, bool pivot, double tol,
                    Matrix6d& Q, std::array<int, static_cast<std::size_t>(MaxCols)>& perm) {
  std::array<Vector6d, 6> v;
  std::array<double, 6> beta{};
  for (int j = 0; j < n; ++j) perm[static_cast<std::size_t>(j)] = j;
  int rank = 0;
  for (int k = 0; k < 6 && k < n; ++k) {
    int best = k;
    double best_norm2 = A.col(k).tail(6 - k).squaredNorm();
    if (pivot) {
      for (int j = k + 1; j < n; ++j) {
        const double n2 = A.col(j).tail(6 - k).squaredNorm();
        if (n2 > best_norm2) {
          best_norm2 = n2;
          best = j;
        }
      }
    }
    if (!(std::sqrt(best_norm2) > tol)) break;
    if (best != k) {
      A.col(k).swap(A.col(best));
      std::swap(perm[static_cast<std::size_t>(k)], perm[static_cast<std::size_t>(best)]);
    }
    const double x0 = A(k, k);
    const double alpha = x0 >= 0.0 ? -std::sqrt(best_norm2) : std::sqrt(best_norm2);
    Vector6d& vk = v[static_cast<std::size_t>(k)];
    vk.setZero();
    vk.tail(6 - k) = A.col(k).tail(6 - k);
    vk(k) -= alpha;
    const double b = 2.0 / vk.squaredNorm();  // > 0: |v|^2 = 2 |x| (|x| + |x0|) > 0
    beta[static_cast<std::size_t>(k)] = b;
    A.col(k).tail(6 - k).setZero();
    A(k, k) = alpha;
    for (int j = k + 1; j < n; ++j) {
      const double s = b * vk.tail(6 - k).dot(A.col(j).tail(6 - k));
      A.col(j).tail(6 - k) -= s * vk.tail(6 - k);
    }
    ++rank;
  }
  // Q = H_0 H_1 ... H_{r-1}, applied to the identity from the right-most reflector.
  Q.setIdentity();
  for (int k = rank - 1; k >= 0; --k) {
    const Vector6d& vk = v[static_cast<std::size_t>(k)];
    const double b = beta[static_cast<std::size_t>(k)];
    for (int j = 0; j < 6; ++j) {
      const double s = b * vk.tail(6 - k).dot(Q.col(j).tail(6 - k));
      Q.col(j).tail(6 - k) -= s * vk.tail(6 - k);
    }
  }
  return rank;
}

}  // namespace

double shear_modulus(double E, double poisson) { return E / (2.0 * (1.0 + poisson)); }

BeamSection tube_section(double E, double G, double outer_diameter, double inner_diameter) {
  if (!(E > 0.0) || !(G > 0.0) || !(outer_diameter > 0.0) || !(inner_diameter >= 0.0) ||
      !(inner_diameter < outer_diameter) || !std::isfinite(E) || !std::isfinite(G) ||
      !std::isfinite(outer_diameter)) {
    throw std::invalid_argument(
        "tube_section: need E > 0, G > 0 and 0 <= inner_diameter < outer_diameter");
  }
  const double D2 = outer_diameter * outer_diameter, d2 = inner_diameter * inner_diameter;
  BeamSection s;
  s.E = E;
  s.G = G;
  s.A = std::numbers::pi * (D2 - d2) / 4.0;
  s.Iy = s.Iz = std::numbers::pi * (D2 * D2 - d2 * d2) / 64.0;
  s.J = 2.0 * s.Iy;
  return s;
}

Matrix6d beam_compliance(const BeamSection& s, double L) {
  Matrix6d C = Matrix6d::Zero();
  C(0, 0) = L / (s.E * s.A);
  C(1, 1) = L * L * L / (3.0 * s.E * s.Iz);
  C(2, 2) = L * L * L / (3.0 * s.E * s.Iy);
  C(3, 3) = L / (s.G * s.J);
  C(4, 4) = L / (s.E * s.Iy);
  C(5, 5) = L / (s.E * s.Iz);
  C(1, 5) = C(5, 1) = L * L / (2.0 * s.E * s.Iz);
  C(2, 4) = C(4, 2) = -L * L / (2.0 * s.E * s.Iy);
  return C;
}

Eigen::Matrix3d cross_product_matrix(const Eigen::Vector3d& v) {
  Eigen::Matrix3d m;
  m << 0.0, -v.z(), v.y(), v.z(), 0.0, -v.x(), -v.y(), v.x(), 0.0;
  return m;
}

Matrix6d twist_transform(const Eigen::Vector3d& from, const Eigen::Vector3d& to) {
  Matrix6d X = Matrix6d::Identity();
  X.topRightCorner<3, 3>() =
      -cross_product_matrix(to - from);  // v_to = v_from + omega x (to - from)
  return X;
}

Matrix6d wrench_transform(const Eigen::Vector3d& from, const Eigen::Vector3d& to) {
  Matrix6d X = Matrix6d::Identity();
  X.bottomLeftCorner<3, 3>() = -cross_product_matrix(to - from);  // m_to = m_from + (from - to) x f
  return X;
}

Matrix6d move_stiffness(const Matrix6d& K, const Eigen::Vector3d& from, const Eigen::Vector3d& to) {
  const Matrix6d W = wrench_transform(from, to);
  return W * K * W.transpose();
}

Matrix6d move_compliance(const Matrix6d& C, const Eigen::Vector3d& from,
                         const Eigen::Vector3d& to) {
  const Matrix6d X = twist_transform(from, to);
  return X * C * X.transpose();
}

Matrix6d rotate_6x6(const Matrix6d& M, const Eigen::Matrix3d& R) {
  Matrix6d B = Matrix6d::Zero();
  B.topLeftCorner<3, 3>() = R;
  B.bottomRightCorner<3, 3>() = R;
  return B * M * B.transpose();
}

Matrix6d ball_joint_compliance(const Eigen::Vector3d& axis, double axial_stiffness,
                               double radial_stiffness) {
  if (!(axial_stiffness >= 0.0) || !(radial_stiffness >= 0.0)) {
    throw std::invalid_argument("ball_joint_compliance: stiffness must be >= 0");
  }
  const Eigen::Vector3d n = unit_axis(axis, "ball joint axis");
  const Eigen::Matrix3d along = n * n.transpose();
  Matrix6d C = Matrix6d::Zero();
  if (axial_stiffness > 0.0) C.topLeftCorner<3, 3>() += along / axial_stiffness;
  if (radial_stiffness > 0.0) {
    C.topLeftCorner<3, 3>() += (Eigen::Matrix3d::Identity() - along) / radial_stiffness;
  }
  return C;
}

Matrix6d compliance_from_stiffness(const Matrix6d& K) {
  const Eigen::SelfAdjointEigenSolver<Matrix6d> eig(0.5 * (K + K.transpose()));
  const Vector6d lambda = eig.eigenvalues();
  const double tol = 1e-12 * lambda.cwiseAbs().maxCoeff();
  Vector6d inv = Vector6d::Zero();
  for (int i = 0; i < 6; ++i) {
    if (lambda(i) > tol) inv(i) = 1.0 / lambda(i);
  }
  return eig.eigenvectors() * inv.asDiagonal() * eig.eigenvectors().transpose();
}

Matrix6d two_force_member_stiffness(const Eigen::Vector3d& a, const Eigen::Vector3d& b, double k,
                                    const Eigen::Vector3d& reference) {
  const Eigen::Vector3d s = unit_axis(b - a, "two-force member");
  Vector6d zeta;
  zeta << s, (b - reference).cross(s);
  return k * zeta * zeta.transpose();
}

Matrix6d platform_stiffness(std::span<const LegCompliance> legs, const Eigen::Vector3d& reference) {
  Matrix6d K = Matrix6d::Zero();
  for (const LegCompliance& leg : legs) {
    K += move_stiffness(leg.stiffness, leg.reference, reference);
  }
  return K;
}

// ---------------------------------------------------------------------------------------------
// VjmLeg

void VjmLeg::clear() { num_springs_ = num_passive_ = num_elastic_ = num_rod_groups_ = 0; }

void VjmLeg::add_spring(const Eigen::Vector3d& point, const Eigen::Vector3d& axis, bool rotational,
                        double compliance) {
  if (!(compliance >= 0.0) || !std::isfinite(compliance)) {
    throw std::invalid_argument("VjmLeg: a spring's compliance must be >= 0 and finite");
  }
  if (num_springs_ == kMaxSprings) throw std::length_error("VjmLeg: more than kMaxSprings");
  springs_[static_cast<std::size_t>(num_springs_++)] =
      Axis{point, unit_axis(axis, "spring axis"), rotational, compliance};
}

void VjmLeg::add_beam(const BeamSection& s, double length, const Eigen::Vector3d& start,
                      const Eigen::Vector3d& x_axis, const Eigen::Vector3d& y_axis) {
  require_positive(length, "beam length");
  require_positive(s.E, "beam E");
  require_positive(s.G, "beam G");
  require_positive(s.A, "beam A");
  require_positive(s.Iy, "beam Iy");
  require_positive(s.Iz, "beam Iz");
  require_positive(s.J, "beam J");
  if (num_springs_ + 6 > kMaxSprings) throw std::length_error("VjmLeg: more than kMaxSprings");
  const Eigen::Vector3d x = unit_axis(x_axis, "beam x axis");
  const Eigen::Vector3d y = unit_axis(y_axis - y_axis.dot(x) * x, "beam y axis (across x)");
  const Eigen::Vector3d z = x.cross(y);
  const Eigen::Vector3d mid = start + 0.5 * length * x;
  const double L = length, L3 = L * L * L;
  // Six independent virtual springs with the beam's tip compliance (header comment).
  springs_[static_cast<std::size_t>(num_springs_++)] = Axis{start, x, false, L / (s.E * s.A)};
  springs_[static_cast<std::size_t>(num_springs_++)] = Axis{start, x, true, L / (s.G * s.J)};
  springs_[static_cast<std::size_t>(num_springs_++)] = Axis{mid, y, true, L / (s.E * s.Iy)};
  springs_[static_cast<std::size_t>(num_springs_++)] = Axis{mid, z, false, L3 / (12 * s.E * s.Iy)};
  springs_[static_cast<std::size_t>(num_springs_++)] = Axis{mid, z, true, L / (s.E * s.Iz)};
  springs_[static_cast<std::size_t>(num_springs_++)] = Axis{mid, y, false, L3 / (12 * s.E * s.Iz)};
}

void VjmLeg::add_actuated_prismatic(const Eigen::Vector3d& point, const Eigen::Vector3d& axis,
                                    double stiffness) {
  if (!(stiffness >= 0.0)) throw std::invalid_argument("VjmLeg: actuator stiffness must be >= 0");
  if (stiffness > 0.0) add_spring(point, axis, false, 1.0 / stiffness);
}

void VjmLeg::add_actuated_revolute(const Eigen::Vector3d& point, const Eigen::Vector3d& axis,
                                   double stiffness) {
  if (!(stiffness >= 0.0)) throw std::invalid_argument("VjmLeg: actuator stiffness must be >= 0");
  if (stiffness > 0.0) add_spring(point, axis, true, 1.0 / stiffness);
}

void VjmLeg::add_prismatic(const Eigen::Vector3d& point, const Eigen::Vector3d& axis) {
  if (num_passive_ == kMaxPassive) throw std::length_error("VjmLeg: more than kMaxPassive");
  passive_[static_cast<std::size_t>(num_passive_++)] =
      Axis{point, unit_axis(axis, "prismatic axis"), false, 0.0};
}

void VjmLeg::add_revolute(const Eigen::Vector3d& point, const Eigen::Vector3d& axis) {
  if (num_passive_ == kMaxPassive) throw std::length_error("VjmLeg: more than kMaxPassive");
  passive_[static_cast<std::size_t>(num_passive_++)] =
      Axis{point, unit_axis(axis, "revolute axis"), true, 0.0};
}

void VjmLeg::add_universal(const Eigen::Vector3d& point, const Eigen::Vector3d& axis1,
                           const Eigen::Vector3d& axis2) {
  if (num_passive_ + 2 > kMaxPassive) throw std::length_error("VjmLeg: more than kMaxPassive");
  add_revolute(point, axis1);
  add_revolute(point, axis2);
}

void VjmLeg::add_spherical(const Eigen::Vector3d& point) {
  if (num_passive_ + 3 > kMaxPassive) throw std::length_error("VjmLeg: more than kMaxPassive");
  for (int k = 0; k < 3; ++k) add_revolute(point, Eigen::Vector3d::Unit(k));
}

void VjmLeg::add_elastic_joint(const Eigen::Vector3d& point, const Matrix6d& compliance) {
  if (num_elastic_ == kMaxElasticJoints) {
    throw std::length_error("VjmLeg: more than kMaxElasticJoints");
  }
  elastic_[static_cast<std::size_t>(num_elastic_++)] =
      ElasticJoint{point, 0.5 * (compliance + compliance.transpose())};
}

void VjmLeg::add_two_force_members(std::span<const TwoForceMember> rods) {
  if (num_rod_groups_ == kMaxRodGroups) throw std::length_error("VjmLeg: more than kMaxRodGroups");
  if (rods.empty() || rods.size() > static_cast<std::size_t>(kMaxRodsPerGroup)) {
    throw std::length_error("VjmLeg: a rod group needs 1 to kMaxRodsPerGroup rods");
  }
  RodGroup& g = rod_groups_[static_cast<std::size_t>(num_rod_groups_)];
  g.count = 0;
  for (const TwoForceMember& r : rods) {
    unit_axis(r.b - r.a, "two-force member");
    if (!(r.stiffness >= 0.0)) throw std::invalid_argument("VjmLeg: rod stiffness must be >= 0");
    g.rods[static_cast<std::size_t>(g.count++)] = r;
  }
  ++num_rod_groups_;
}

void VjmLeg::add_two_force_member(const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                  double stiffness) {
  const TwoForceMember rod{a, b, stiffness};
  add_two_force_members(std::span<const TwoForceMember>(&rod, 1));
}

double VjmLeg::length_scale(const Eigen::Vector3d& reference) const {
  double L2 = 0.0;
  for (int i = 0; i < num_passive_; ++i) {
    L2 = std::max(L2, (passive_[static_cast<std::size_t>(i)].point - reference).squaredNorm());
  }
  for (int g = 0; g < num_rod_groups_; ++g) {
    const RodGroup& group = rod_groups_[static_cast<std::size_t>(g)];
    for (int j = 0; j < group.count; ++j) {
      L2 = std::max(L2, (group.rods[static_cast<std::size_t>(j)].a - reference).squaredNorm());
    }
  }
  return L2 > 0.0 ? std::sqrt(L2) : 1.0;
}

void VjmLeg::assemble(const Eigen::Vector3d& reference, double inv_length, Matrix6d& S,
                      Eigen::Matrix<double, 6, kMaxPassiveColumns>& P, int& num_columns) const {
  S.setZero();
  for (int i = 0; i < num_springs_; ++i) {
    const Axis& sp = springs_[static_cast<std::size_t>(i)];
    const Vector6d t = scaled_twist(sp.point, sp.axis, sp.rotational, reference, inv_length);
    S.noalias() += (sp.compliance * t) * t.transpose();
  }
  if (num_elastic_ > 0) {
    const Vector6d d = (Vector6d() << inv_length, inv_length, inv_length, 1, 1, 1).finished();
    for (int i = 0; i < num_elastic_; ++i) {
      const ElasticJoint& e = elastic_[static_cast<std::size_t>(i)];
      S += d.asDiagonal() * move_compliance(e.compliance, e.point, reference) * d.asDiagonal();
    }
  }
  num_columns = 0;
  for (int i = 0; i < num_passive_; ++i) {
    const Axis& p = passive_[static_cast<std::size_t>(i)];
    const Vector6d t = scaled_twist(p.point, p.axis, p.rotational, reference, inv_length);
    P.col(num_columns++) = t / t.norm();
  }
  // Rod groups: scaled wrench lines zeta~_j = [L s_j; (a_j - ref) x s_j] normalised, Z^ = Q1 R.
  // The group lets every twist with Z^T t = 0 through (Q's last 6 - m columns become passive
  // twists) and adds the compliance Z^ (Z^T Z^)^-1 diag(c) (Z^T Z^)^-1 Z^T = X diag(c) X^T,
  // X = Q1 R^-T, with c_j = 1 / (k_j |zeta~_j|^2) (0 for a rigid rod).
  for (int g = 0; g < num_rod_groups_; ++g) {
    const RodGroup& group = rod_groups_[static_cast<std::size_t>(g)];
    const int m = group.count;
    Eigen::Matrix<double, 6, kMaxRodsPerGroup> Z;
    std::array<double, kMaxRodsPerGroup> c{};
    for (int j = 0; j < m; ++j) {
      const TwoForceMember& r = group.rods[static_cast<std::size_t>(j)];
      const Eigen::Vector3d s = (r.b - r.a).normalized();
      Vector6d zeta;
      zeta << s / inv_length, (r.a - reference).cross(s);
      const double n2 = zeta.squaredNorm();
      Z.col(j) = zeta / std::sqrt(n2);
      c[static_cast<std::size_t>(j)] = r.stiffness > 0.0 ? 1.0 / (r.stiffness * n2) : 0.0;
    }
    Matrix6d Q;
    std::array<int, kMaxRodsPerGroup> perm{};
    if (householder_qr6(Z, m, false, kRankTolerance, Q, perm) < m) {
      throw std::domain_error("VjmLeg: the rods of a two-force member group are dependent");
    }
    // X R^T = Q1 with R upper triangular (in Z): column j of X R^T is sum_{i >= j} R(j, i) X_i,
    // so back-substitution from the last column.
    Eigen::Matrix<double, 6, kMaxRodsPerGroup> X;
    for (int j = m - 1; j >= 0; --j) {
      Vector6d x = Q.col(j);
      for (int i = j + 1; i < m; ++i) x -= Z(j, i) * X.col(i);
      X.col(j) = x / Z(j, j);
      S.noalias() += (c[static_cast<std::size_t>(j)] * X.col(j)) * X.col(j).transpose();
    }
    for (int j = m; j < 6; ++j) P.col(num_columns++) = Q.col(j);
  }
}

LegCompliance VjmLeg::stiffness(const Eigen::Vector3d& reference) const {
  const double L = length_scale(reference);
  Matrix6d S;
  Eigen::Matrix<double, 6, kMaxPassiveColumns> P;
  int num_columns = 0;
  assemble(reference, 1.0 / L, S, P, num_columns);

  // N: orthonormal basis of null(P^T), the wrenches the passive joints do not relieve.
  Matrix6d Q;
  std::array<int, kMaxPassiveColumns> perm{};
  const int rank = householder_qr6(P, num_columns, true, kRankTolerance, Q, perm);
  const int n = 6 - rank;
  LegCompliance out;
  out.reference = reference;
  if (n == 0) return out;
  const auto N = Q.rightCols(n);

  // M = N^T S N, pivoted Cholesky P M P^T = L L^T (stops at a zero pivot: rigid directions).
  Matrix6d M = Matrix6d::Zero();
  M.topLeftCorner(n, n).noalias() = N.transpose() * S * N;
  const Matrix6d M0 = M;
  std::array<int, 6> order{0, 1, 2, 3, 4, 5};
  double max_diag = 0.0;
  for (int i = 0; i < n; ++i) max_diag = std::max(max_diag, M(i, i));
  int r = 0;
  for (; r < n; ++r) {
    int best = r;
    for (int i = r + 1; i < n; ++i) {
      if (M(i, i) > M(best, best)) best = i;
    }
    if (!(M(best, best) > kRigidTolerance * max_diag)) break;
    if (best != r) {  // symmetric swap of rows/columns r and best (full storage)
      M.row(r).swap(M.row(best));
      M.col(r).swap(M.col(best));
      std::swap(order[static_cast<std::size_t>(r)], order[static_cast<std::size_t>(best)]);
    }
    const double d = std::sqrt(M(r, r));
    M(r, r) = d;
    for (int i = r + 1; i < n; ++i) M(i, r) /= d;
    // Trailing update; kept symmetric (full storage) so that later swaps stay consistent. Column r
    // below the diagonal now holds L; the strict upper part of rows < r is stale and never read.
    for (int j = r + 1; j < n; ++j) {
      for (int i = j; i < n; ++i) {
        M(i, j) -= M(i, r) * M(j, r);
        M(j, i) = M(i, j);
      }
    }
  }
  out.constrained_dim = n;
  out.rigid = r < n;

  Matrix6d Ks;
  if (!out.rigid) {
    // Y = N_perm L^-T: rows solve L y = (row of N_perm)^T; K~ = Y Y^T.
    Matrix6d Y = Matrix6d::Zero();
    for (int row = 0; row < 6; ++row) {
      for (int j = 0; j < n; ++j) {
        double v = N(row, order[static_cast<std::size_t>(j)]);
        for (int i = 0; i < j; ++i) v -= M(j, i) * Y(row, i);
        Y(row, j) = v / M(j, j);
      }
    }
    Ks.noalias() = Y.leftCols(n) * Y.leftCols(n).transpose();
  } else {
    // Some transmitted wrench meets no compliance (rare: a chain modelled without an elastic
    // element along it). K~ = N M^+ N^T: the stiffness for the twists that do not deform the
    // rigid directions, independent of the choice of N (the rigid reactions are undetermined).
    // M0 is n x n in the top-left corner, zero elsewhere: block-diagonal, so the eigenvectors
    // of its nonzero eigenvalues lie in the first n coordinates.
    const Eigen::SelfAdjointEigenSolver<Matrix6d> eig(M0);
    const Vector6d& lambda = eig.eigenvalues();
    const double tol = kRigidTolerance * std::max(max_diag, lambda(5));
    Matrix6d Npad = Matrix6d::Zero();
    Npad.leftCols(n) = N;
    Matrix6d Y = Matrix6d::Zero();
    int cols = 0;
    for (int j = 0; j < 6; ++j) {
      if (lambda(j) > tol) Y.col(cols++) = Npad * eig.eigenvectors().col(j) / std::sqrt(lambda(j));
    }
    Ks.noalias() = Y.leftCols(cols) * Y.leftCols(cols).transpose();
  }
  // Back to SI units: K = D K~ D, D = diag(1/L, 1/L, 1/L, 1, 1, 1).
  const Vector6d d = (Vector6d() << 1 / L, 1 / L, 1 / L, 1, 1, 1).finished();
  out.stiffness = d.asDiagonal() * Ks * d.asDiagonal();
  out.stiffness = 0.5 * (out.stiffness + out.stiffness.transpose());
  return out;
}

LegCompliance VjmLeg::stiffness_for_wrenches(const Eigen::Vector3d& reference,
                                             const TransmittedWrenches& wrenches) const {
  const auto& W = wrenches.basis;
  const int m = static_cast<int>(W.cols());
  if (m > 6) throw std::length_error("VjmLeg: more than 6 transmitted wrenches");
  LegCompliance out;
  out.reference = reference;
  out.constrained_dim = m;
  if (m == 0) return out;
  // M = W^T S W + O, lower triangle: each spring adds c (W^T t)(W^T t)^T.
  double M[6][6] = {};
  if (wrenches.compliance.size() > 0) {
    if (wrenches.compliance.rows() != m || wrenches.compliance.cols() != m) {
      throw std::invalid_argument("VjmLeg: the transmitted wrenches' compliance must be m x m");
    }
    for (int a = 0; a < m; ++a)
      for (int b = 0; b <= a; ++b) M[a][b] = wrenches.compliance(a, b);
  }
  for (int i = 0; i < num_springs_; ++i) {
    const Axis& sp = springs_[static_cast<std::size_t>(i)];
    const Vector6d t = scaled_twist(sp.point, sp.axis, sp.rotational, reference, 1.0);
    double u[6];
    for (int a = 0; a < m; ++a) u[a] = W.col(a).dot(t);
    for (int a = 0; a < m; ++a)
      for (int b = 0; b <= a; ++b) M[a][b] += sp.compliance * u[a] * u[b];
  }
  for (int i = 0; i < num_elastic_; ++i) {
    const ElasticJoint& e = elastic_[static_cast<std::size_t>(i)];
    const Eigen::Matrix<double, 6, Eigen::Dynamic, 0, 6, 6> CW =
        move_compliance(e.compliance, e.point, reference) * W;
    for (int a = 0; a < m; ++a)
      for (int b = 0; b <= a; ++b) M[a][b] += W.col(a).dot(CW.col(b));
  }
  // Cholesky M = L L^T in place (lower triangle); a pivot below kRigidTolerance times the largest
  // diagonal entry: a transmitted wrench meets no compliance.
  double max_diag = 0.0;
  for (int a = 0; a < m; ++a) max_diag = std::max(max_diag, M[a][a]);
  for (int j = 0; j < m; ++j) {
    double d = M[j][j];
    for (int k = 0; k < j; ++k) d -= M[j][k] * M[j][k];
    if (!(d > kRigidTolerance * max_diag) || !std::isfinite(d)) {
      out.rigid = true;
      return out;
    }
    M[j][j] = std::sqrt(d);
    for (int i = j + 1; i < m; ++i) {
      double v = M[i][j];
      for (int k = 0; k < j; ++k) v -= M[i][k] * M[j][k];
      M[i][j] = v / M[j][j];
    }
  }
  // Y = W L^-T (rows solve L y = row of W); K = Y Y^T, each pair of rows once: exactly symmetric.
  double Y[6][6];
  for (int row = 0; row < 6; ++row) {
    for (int j = 0; j < m; ++j) {
      double v = W(row, j);
      for (int k = 0; k < j; ++k) v -= M[j][k] * Y[row][k];
      Y[row][j] = v / M[j][j];
    }
  }
  for (int c = 0; c < 6; ++c) {
    for (int r = c; r < 6; ++r) {
      double sum = 0.0;
      for (int j = 0; j < m; ++j) sum += Y[r][j] * Y[c][j];
      out.stiffness(r, c) = out.stiffness(c, r) = sum;
    }
  }
  return out;
}

Matrix6d VjmLeg::locked_compliance(const Eigen::Vector3d& reference) const {
  Matrix6d S;
  Eigen::Matrix<double, 6, kMaxPassiveColumns> P;
  int num_columns = 0;
  assemble(reference, 1.0, S, P, num_columns);
  return S;
}

void VjmLeg::passive_twists(const Eigen::Vector3d& reference, PassiveTwists& Jq) const {
  Matrix6d S;
  Eigen::Matrix<double, 6, kMaxPassiveColumns> P;
  int num_columns = 0;
  assemble(reference, 1.0, S, P, num_columns);
  Jq = P.leftCols(num_columns);
}

}  // namespace pkmopt
