#include "models/core/linalg.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

namespace pkmopt {
namespace {

constexpr int n = 6;

// Householder reduction of the symmetric matrix a (full storage, overwritten) to tridiagonal
// form: diagonal d, sub-diagonal e with e[i] coupling d[i] and d[i + 1], e[N - 1] = 0.
// Step k annihilates a(k + 2 .. N - 1, k) with H = I - v v^T / h, v = x - alpha e_(k+1),
// h = v^T v / 2, applied to the whole matrix (v is zero in its first k + 1 entries, so the
// fixed-size vector operations below leave the rows already reduced unchanged).
template <int N>
void tridiagonalize(Eigen::Matrix<double, N, N>& a, double (&d)[N], double (&e)[N]) {
  using Vector = Eigen::Matrix<double, N, 1>;
  for (int k = 0; k < N - 2; ++k) {
    double below = 0.0;  // squared norm of a(k + 2 .. N - 1, k)
    for (int i = k + 2; i < N; ++i) below += a(i, k) * a(i, k);
    const double x0 = a(k + 1, k);
    if (below == 0.0) {  // already tridiagonal in this column: H = I
      e[k] = x0;
      continue;
    }
    const double norm = std::sqrt(x0 * x0 + below);
    const double alpha = x0 >= 0.0 ? -norm : norm;
    Vector v = a.col(k);
    for (int i = 0; i <= k; ++i) v(i) = 0.0;
    v(k + 1) = x0 - alpha;  // no cancellation: x0 and alpha have opposite signs
    const double inv_h = 1.0 / (norm * norm - x0 * alpha);
    Vector p;
    p.noalias() = a * v;  // a is symmetric: a v = a^T v
    p *= inv_h;
    const Vector q = p - (0.5 * inv_h * v.dot(p)) * v;
    a.noalias() -= v * q.transpose();
    a.noalias() -= q * v.transpose();
    e[k] = alpha;
  }
  for (int i = 0; i < N; ++i) d[i] = a(i, i);
  e[N - 2] = a(N - 1, N - 2);
  e[N - 1] = 0.0;
  // QL converges fastest with the larger entries at the bottom (LAPACK dsteqr chooses between
  // QL and QR the same way); reversing the order of a tridiagonal keeps its eigenvalues.
  if (std::abs(d[N - 1]) < std::abs(d[0])) {
    std::reverse(d, d + N);
    std::reverse(e, e + N - 1);
  }
}

// Implicit QL with Wilkinson shifts on the tridiagonal (d, e); eigenvalues left in d (tql1).
// Returns false if an eigenvalue needed more than 60 iterations.
template <int N>
bool tridiagonal_ql(double (&d)[N], double (&e)[N]) {
  constexpr double eps = std::numeric_limits<double>::epsilon();
  for (int l = 0; l < N; ++l) {
    int iterations = 0;
    int m = l;
    do {
      for (m = l; m < N - 1; ++m) {
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

// Eigenvalues of the symmetric 2x2 matrix [a b; b c] (LAPACK dlae2): rt1 has the larger
// absolute value; rt2 is formed from det / rt1 to keep its relative accuracy.
void eigenvalues2(double a, double b, double c, double& rt1, double& rt2) {
  const double sm = a + c;
  const double df = a - c;
  const double rt = std::sqrt(df * df + 4.0 * b * b);
  const double acmx = std::abs(a) > std::abs(c) ? a : c;
  const double acmn = std::abs(a) > std::abs(c) ? c : a;
  if (sm != 0.0) {
    rt1 = 0.5 * (sm < 0.0 ? sm - rt : sm + rt);
    rt2 = (acmx / rt1) * acmn - (b / rt1) * b;
  } else {
    rt1 = 0.5 * rt;
    rt2 = -0.5 * rt;
  }
}

// The root-free (Pal-Walker-Kahan) variant of implicit QL with Wilkinson shifts, eigenvalues
// only: it works on the squared off-diagonals and needs no square root per rotation (LAPACK
// dsterf, QL branch). A trailing 2x2 block is solved in closed form. Eigenvalues left in d;
// returns false after 30 N iterations without convergence.
template <int N>
bool tridiagonal_ql_root_free(double (&d)[N], const double (&e)[N]) {
  constexpr double eps = std::numeric_limits<double>::epsilon();
  double e2[N];
  for (int i = 0; i < N; ++i) e2[i] = e[i] * e[i];
  int iterations = 0;
  int l = 0;
  while (l < N) {
    int m = l;
    for (; m < N - 1; ++m) {
      const double dd = std::abs(d[m]) + std::abs(d[m + 1]);
      if (e2[m] <= (eps * dd) * (eps * dd)) break;
    }
    if (m == l) {  // d[l] is an eigenvalue
      ++l;
      continue;
    }
    if (m == l + 1) {  // an isolated 2x2 block
      double rt1, rt2;
      eigenvalues2(d[l], std::sqrt(e2[l]), d[l + 1], rt1, rt2);
      d[l] = rt1;
      d[l + 1] = rt2;
      l += 2;
      continue;
    }
    if (++iterations > 30 * N) return false;
    // Wilkinson shift: the eigenvalue of the leading 2x2 block nearer d[l],
    // d[l] - e^2 / (delta + sign(delta) sqrt(delta^2 + e^2)), delta = (d[l + 1] - d[l]) / 2.
    const double delta = 0.5 * (d[l + 1] - d[l]);
    const double sigma =
        d[l] - e2[l] / (delta + std::copysign(std::sqrt(delta * delta + e2[l]), delta));
    double c = 1.0, s = 0.0;
    double gamma = d[m] - sigma;
    double p = gamma * gamma;
    for (int i = m - 1; i >= l; --i) {
      // gamma^2 / c = gamma^2 * rr / p: both reciprocals start as soon as p is known, which
      // shortens the chain of dependent divisions from one rotation to the next.
      const double inv_p = 1.0 / p;
      const double bb = e2[i];
      const double rr = p + bb;
      const double inv_rr = 1.0 / rr;
      if (i != m - 1) e2[i + 1] = s * rr;
      const double old_c = c;
      c = p * inv_rr;
      s = bb * inv_rr;
      const double old_gamma = gamma;
      const double alpha = d[i];
      gamma = c * (alpha - sigma) - s * old_gamma;
      d[i + 1] = old_gamma + (alpha - gamma);
      p = c != 0.0 ? (gamma * gamma) * (rr * inv_p) : old_c * bb;
    }
    e2[l] = s * p;
    d[l] = sigma + gamma;
  }
  return true;
}

// Eigen's general solver (dynamic size), ascending; the fallback if QL fails to converge.
Eigen::VectorXd eigenvalues_by_eigen(const Eigen::MatrixXd& A) {
  const Eigen::MatrixXd full = A.selfadjointView<Eigen::Lower>();
  return Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(full, Eigen::EigenvaluesOnly).eigenvalues();
}

// Eigenvalues of the symmetric N x N matrix whose lower triangle is read, ascending.
template <int N>
void symmetric_eigenvalues(const Eigen::Matrix<double, N, N>& A,
                           Eigen::Matrix<double, N, 1>& eigenvalues) {
  Eigen::Matrix<double, N, N> a = A.template selfadjointView<Eigen::Lower>();
  double d[N], e[N];
  tridiagonalize<N>(a, d, e);
  double d_copy[N], e_copy[N];
  std::copy(d, d + N, d_copy);
  std::copy(e, e + N, e_copy);
  if (!tridiagonal_ql_root_free<N>(d, e)) {
    // Never seen in practice: retry with the classic QL, then Eigen's general solver.
    std::copy(d_copy, d_copy + N, d);
    if (!tridiagonal_ql<N>(d, e_copy)) {
      eigenvalues = eigenvalues_by_eigen(A);
      return;
    }
  }
  std::sort(d, d + N);
  for (int i = 0; i < N; ++i) eigenvalues(i) = d[i];
}

}  // namespace

void symmetric_eigenvalues6(const Eigen::Matrix<double, 6, 6>& A,
                            Eigen::Matrix<double, 6, 1>& eigenvalues) {
  symmetric_eigenvalues<6>(A, eigenvalues);
}

void symmetric_eigenvalues3(const Eigen::Matrix<double, 3, 3>& A,
                            Eigen::Matrix<double, 3, 1>& eigenvalues) {
  symmetric_eigenvalues<3>(A, eigenvalues);
}

bool solve_transposed6x4(const Eigen::Matrix<double, 6, 6>& J, const Eigen::Matrix<double, 6, 4>& B,
                         Eigen::Matrix<double, 6, 4>& X, double& det) {
  constexpr int width = n + 4;
  // Row i of the augmented system: row i of J^T (column i of J), then row i of B.
  double a[n][width];
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) a[i][j] = J(j, i);
    for (int j = 0; j < 4; ++j) a[i][n + j] = B(i, j);
  }
  det = 1.0;
  for (int k = 0; k < n; ++k) {
    int pivot = k;
    double best = std::abs(a[k][k]);
    for (int i = k + 1; i < n; ++i) {
      if (std::abs(a[i][k]) > best) {
        best = std::abs(a[i][k]);
        pivot = i;
      }
    }
    if (pivot != k) {
      for (int j = 0; j < width; ++j) std::swap(a[k][j], a[pivot][j]);
      det = -det;
    }
    const double diagonal = a[k][k];
    if (diagonal == 0.0) {
      det = 0.0;
      return false;
    }
    det *= diagonal;
    for (int i = k + 1; i < n; ++i) {
      const double factor = a[i][k] / diagonal;
      // Full-length row update (the entries left of k are never read again).
      for (int j = 0; j < width; ++j) a[i][j] -= factor * a[k][j];
    }
  }
  double x[n][4];
  for (int i = n - 1; i >= 0; --i) {
    double sum[4];
    for (int c = 0; c < 4; ++c) sum[c] = a[i][n + c];
    for (int j = i + 1; j < n; ++j) {
      for (int c = 0; c < 4; ++c) sum[c] -= a[i][j] * x[j][c];
    }
    for (int c = 0; c < 4; ++c) x[i][c] = sum[c] / a[i][i];
  }
  for (int i = 0; i < n; ++i) {
    for (int c = 0; c < 4; ++c) X(i, c) = x[i][c];
  }
  return true;
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

double max_norm_over_sign_vectors(
    const Eigen::Ref<const Eigen::Matrix<double, 3, Eigen::Dynamic>>& columns) {
  const int n = static_cast<int>(columns.cols());
  if (n == 0) return 0.0;
  double best = 0.0;
  const unsigned vertices = 1u << (n - 1);
  for (unsigned g = 0; g < vertices; ++g) {
    Eigen::Vector3d v = columns.col(0);
    for (int j = 1; j < n; ++j) v += ((g >> (j - 1)) & 1u ? -1.0 : 1.0) * columns.col(j);
    best = std::max(best, v.squaredNorm());
  }
  return std::sqrt(best);
}

}  // namespace pkmopt
