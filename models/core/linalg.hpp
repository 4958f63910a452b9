// Small fixed-size linear algebra that the per-pose metrics need fast.
//
// These routines are written for n = 3 and n = 6 with plain fixed-length loops: Eigen's general
// paths for eigenvalues, LU solves and rank updates go through dynamic-size blocked kernels whose
// bookkeeping costs more than the arithmetic at this size.
//
// symmetric_eigenvalues6 / symmetric_eigenvalues3: all eigenvalues of a symmetric matrix,
// ascending. Householder tridiagonalisation H_k A H_k (H_k = I - v v^T / h, applied to the full
// matrix as the symmetric rank-2 update A - v q^T - q v^T with p = A v / h, q = p - (v^T p / 2h) v;
// Golub & Van Loan, Matrix Computations 4th ed., 8.3.1), followed by the root-free
// (Pal-Walker-Kahan) implicit QL iteration with Wilkinson shifts on the squared off-diagonals,
// eigenvalues only, with a closed-form 2x2 end (LAPACK dsterf, dlae2; Parlett, The Symmetric
// Eigenvalue Problem, 8.15); should it ever fail to converge, the classic QL (EISPACK tql1) and
// then Eigen's solver take over. Backward stable: each eigenvalue has an absolute error of a few
// eps * |A|, also for repeated and clustered eigenvalues (unlike closed-form cubic roots). Entries
// must lie within about 1e-150 .. 1e150 in magnitude (squares are formed without scaling).
//
// Lu6: LU factorisation with partial pivoting P J = L U of a 6x6 matrix, its determinant, and
// solves with J or J^T.
//
// solve_transposed6x4: J^T X = B for a 6x6 J and four right-hand sides at once, by Gaussian
// elimination with partial pivoting on the augmented rows [J^T | B], with det J as a by-product.
//
// cross_matrix: [v]x, the matrix of the cross product, [v]x u = v x u.
//
// max_norm_over_sign_vectors: max over s in {-1, +1}^n of |C s| for a 3 x n C, the largest TCP
// error over an error box |dq_j| <= 1 mapped by C (the maximum of a convex function over a box
// is at a vertex; s and -s give the same norm, so 2^(n-1) vertices with s_0 = +1).
//
//   Eigen::Matrix<double, 6, 1> lambda;
//   pkmopt::symmetric_eigenvalues6(A, lambda);   // lambda(0) smallest, lambda(5) largest
//   pkmopt::Lu6 lu(J);
//   double det = lu.determinant();
//   Eigen::Matrix<double, 6, 1> x = lu.solve_transposed(b);   // J^T x = b
//   Eigen::Matrix<double, 6, 4> X;
//   bool ok = pkmopt::solve_transposed6x4(J, B, X, det);      // J^T X = B
#pragma once

#include <Eigen/Core>

namespace pkmopt {

/// [v]x: cross_matrix(v) * u = v x u.
inline Eigen::Matrix3d cross_matrix(const Eigen::Vector3d& v) {
  Eigen::Matrix3d m;
  m << 0.0, -v.z(), v.y(), v.z(), 0.0, -v.x(), -v.y(), v.x(), 0.0;
  return m;
}

/// max over s in {-1, +1}^n of |columns * s| (0 for no columns); n <= 31.
double max_norm_over_sign_vectors(
    const Eigen::Ref<const Eigen::Matrix<double, 3, Eigen::Dynamic>>& columns);

/// Eigenvalues of the symmetric matrix A (only its lower triangle is read), ascending.
void symmetric_eigenvalues6(const Eigen::Matrix<double, 6, 6>& A,
                            Eigen::Matrix<double, 6, 1>& eigenvalues);

/// Eigenvalues of the symmetric 3x3 matrix A (only its lower triangle is read), ascending.
void symmetric_eigenvalues3(const Eigen::Matrix<double, 3, 3>& A,
                            Eigen::Matrix<double, 3, 1>& eigenvalues);

/// Solves J^T X = B (partial pivoting) and sets det = det J. Returns false, with det = 0 and X
/// unspecified, when a pivot is exactly 0.
bool solve_transposed6x4(const Eigen::Matrix<double, 6, 6>& J, const Eigen::Matrix<double, 6, 4>& B,
                         Eigen::Matrix<double, 6, 4>& X, double& det);

/// LU factorisation with partial pivoting of a 6x6 matrix.
class Lu6 {
 public:
  explicit Lu6(const Eigen::Matrix<double, 6, 6>& J);
  /// det J (0 if a pivot is exactly 0).
  double determinant() const { return determinant_; }
  /// True when a pivot is exactly 0 (then the solves are not defined).
  bool exactly_singular() const { return exactly_singular_; }
  /// x with J x = b.
  Eigen::Matrix<double, 6, 1> solve(const Eigen::Matrix<double, 6, 1>& b) const;
  /// x with J^T x = b.
  Eigen::Matrix<double, 6, 1> solve_transposed(const Eigen::Matrix<double, 6, 1>& b) const;

 private:
  double lu_[6][6];  // row-major; strict lower part L (unit diagonal), upper part U
  int perm_[6];      // row i of P J is row perm_[i] of J
  double determinant_ = 1.0;
  bool exactly_singular_ = false;
};

}  // namespace pkmopt
