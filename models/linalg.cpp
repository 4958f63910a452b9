#include "models/linalg.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

namespace pkmopt {
namespace {

constexpr int n = 6;

// Householder reduction of the symmetric matrix z (lower triangle) to tridiagonal form:
// diagonal d, sub-diagonal e with e[i] coupling d[i] and d[i+1], e[n-1] = 0 (tred1).
void tridiagonalize(double z[n][n], double d[n], double e[n]) {
  for (int i = n - 1; i > 0; --i) {
    const int l = i - 1;
    double h = 0.0;
    if (l > 0) {
      double scale = 0.0;
      for (int k = 0; k < i; ++k) scale += std::abs(z[i][k]);
      if (scale == 0.0) {
        e[i] = z[i][l];
      } else {
        for (int k = 0; k < i; ++k) {
          z[i][k] /= scale;
          h += z[i][k] * z[i][k];
        }
        double f = z[i][l];
        double g = f >= 0.0 ? -std::sqrt(h) : std::sqrt(h);
        e[i] = scale * g;
        h -= f * g;
        z[i][l] = f - g;
        f = 0.0;
        for (int j = 0; j < i; ++j) {
          g = 0.0;
          for (int k = 0; k <= j; ++k) g += z[j][k] * z[i][k];
          for (int k = j + 1; k < i; ++k) g += z[k][j] * z[i][k];
          e[j] = g / h;
          f += e[j] * z[i][j];
        }
        const double hh = f / (h + h);
        for (int j = 0; j < i; ++j) {
          f = z[i][j];
          e[j] = g = e[j] - hh * f;
          for (int k = 0; k <= j; ++k) z[j][k] -= (f * e[k] + g * z[i][k]);
        }
      }
    } else {
      e[i] = z[i][l];
    }
    d[i] = h;
  }
  e[0] = 0.0;
  for (int i = 0; i < n; ++i) d[i] = z[i][i];
  // Shift so that e[i] couples d[i] and d[i + 1].
  for (int i = 1; i < n; ++i) e[i - 1] = e[i];
  e[n - 1] = 0.0;
}

// Implicit QL with Wilkinson shifts on the tridiagonal (d, e); eigenvalues left in d (tql1).
// Returns false if an eigenvalue needed more than 60 iterations.
bool tridiagonal_ql(double d[n], double e[n]) {
  constexpr double eps = std::numeric_limits<double>::epsilon();
  for (int l = 0; l < n; ++l) {
    int iterations = 0;
    int m = l;
    do {
      for (m = l; m < n - 1; ++m) {
        const double dd = std::abs(d[m]) + std::abs(d[m + 1]);
        if (std::abs(e[m]) <= eps * dd) break;
      }
      if (m != l) {
        if (++iterations > 60) return false;
        double g = (d[l + 1] - d[l]) / (2.0 * e[l]);
        double r = std::sqrt(g * g + 1.0);
        g = d[m] - d[l] + e[l] / (g + std::copysign(r, g));
        double s = 1.0, c = 1.0, p = 0.0;
        bool deflated = false;
        for (int i = m - 1; i >= l; --i) {
          const double f = s * e[i];
          const double b = c * e[i];
          r = std::sqrt(f * f + g * g);
          e[i + 1] = r;
          if (r == 0.0) {
            d[i + 1] -= p;
            e[m] = 0.0;
            deflated = true;
            break;
          }
          s = f / r;
          c = g / r;
          g = d[i + 1] - p;
          r = (d[i] - g) * s + 2.0 * c * b;
          p = s * r;
          d[i + 1] = g + p;
          g = c * r - b;
        }
        if (deflated) continue;
        d[l] -= p;
        e[l] = g;
        e[m] = 0.0;
      }
    } while (m != l);
  }
  return true;
}

}  // namespace

void symmetric_eigenvalues6(const Eigen::Matrix<double, 6, 6>& A,
                            Eigen::Matrix<double, 6, 1>& eigenvalues) {
  double z[n][n];
  for (int i = 0; i < n; ++i) {
    for (int k = 0; k <= i; ++k) z[i][k] = A(i, k);
  }
  double d[n], e[n];
  tridiagonalize(z, d, e);
  if (!tridiagonal_ql(d, e)) {
    // Never seen in practice; fall back to Eigen's solver rather than return garbage.
    Eigen::Matrix<double, 6, 6> full = A.selfadjointView<Eigen::Lower>();
    eigenvalues =
        Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, 6, 6>>(full, Eigen::EigenvaluesOnly)
            .eigenvalues();
    return;
  }
  std::sort(d, d + n);
  for (int i = 0; i < n; ++i) eigenvalues(i) = d[i];
}

Lu6::Lu6(const Eigen::Matrix<double, 6, 6>& J) {
  for (int i = 0; i < n; ++i) {
    perm_[i] = i;
    for (int j = 0; j < n; ++j) lu_[i][j] = J(i, j);
  }
  for (int k = 0; k < n; ++k) {
    int pivot = k;
    double best = std::abs(lu_[k][k]);
    for (int i = k + 1; i < n; ++i) {
      if (std::abs(lu_[i][k]) > best) {
        best = std::abs(lu_[i][k]);
        pivot = i;
      }
    }
    if (pivot != k) {
      for (int j = 0; j < n; ++j) std::swap(lu_[k][j], lu_[pivot][j]);
      std::swap(perm_[k], perm_[pivot]);
      determinant_ = -determinant_;
    }
    const double diagonal = lu_[k][k];
    determinant_ *= diagonal;
    if (diagonal == 0.0) {
      exactly_singular_ = true;
      continue;
    }
    for (int i = k + 1; i < n; ++i) {
      const double factor = lu_[i][k] / diagonal;
      lu_[i][k] = factor;
      for (int j = k + 1; j < n; ++j) lu_[i][j] -= factor * lu_[k][j];
    }
  }
}

Eigen::Matrix<double, 6, 1> Lu6::solve(const Eigen::Matrix<double, 6, 1>& b) const {
  // P J = L U: L y = P b, U x = y.
  double y[n];
  for (int i = 0; i < n; ++i) {
    double sum = b(perm_[i]);
    for (int j = 0; j < i; ++j) sum -= lu_[i][j] * y[j];
    y[i] = sum;
  }
  Eigen::Matrix<double, 6, 1> x;
  for (int i = n - 1; i >= 0; --i) {
    double sum = y[i];
    for (int j = i + 1; j < n; ++j) sum -= lu_[i][j] * x(j);
    x(i) = sum / lu_[i][i];
  }
  return x;
}

Eigen::Matrix<double, 6, 1> Lu6::solve_transposed(const Eigen::Matrix<double, 6, 1>& b) const {
  // J^T = U^T L^T P: U^T y = b, L^T w = y, x = P^T w (x[perm[i]] = w[i]).
  double y[n];
  for (int i = 0; i < n; ++i) {
    double sum = b(i);
    for (int j = 0; j < i; ++j) sum -= lu_[j][i] * y[j];
    y[i] = sum / lu_[i][i];
  }
  double w[n];
  for (int i = n - 1; i >= 0; --i) {
    double sum = y[i];
    for (int j = i + 1; j < n; ++j) sum -= lu_[j][i] * w[j];
    w[i] = sum;
  }
  Eigen::Matrix<double, 6, 1> x;
  for (int i = 0; i < n; ++i) x(perm_[i]) = w[i];
  return x;
}

}  // namespace pkmopt
