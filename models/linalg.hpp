// Small fixed-size linear algebra that the per-pose metrics need fast.
//
// These routines are written for n = 6 with plain loops: Eigen's general paths for
// eigenvalues, LU solves and rank updates go through dynamic-size blocked kernels whose
// bookkeeping costs more than the arithmetic at this size.
//
// symmetric_eigenvalues6: all eigenvalues of a symmetric 6x6 matrix, ascending, by Householder
// tridiagonalisation followed by the implicit QL iteration with Wilkinson shifts, eigenvalues
// only (EISPACK tred1/tql1; Press et al., Numerical Recipes 3rd ed., 11.3-11.4). Backward
// stable: each eigenvalue has an absolute error of a few eps * |A|.
//
// Lu6: LU factorisation with partial pivoting P J = L U of a 6x6 matrix, its determinant, and
// solves with J or J^T.
//
//   Eigen::Matrix<double, 6, 1> lambda;
//   pkmopt::symmetric_eigenvalues6(A, lambda);   // lambda(0) smallest, lambda(5) largest
//   pkmopt::Lu6 lu(J);
//   double det = lu.determinant();
//   Eigen::Matrix<double, 6, 1> x = lu.solve_transposed(b);   // J^T x = b
#pragma once

#include <Eigen/Core>

namespace pkmopt {

/// Eigenvalues of the symmetric matrix A (only its lower triangle is read), ascending.
void symmetric_eigenvalues6(const Eigen::Matrix<double, 6, 6>& A,
                            Eigen::Matrix<double, 6, 1>& eigenvalues);

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
