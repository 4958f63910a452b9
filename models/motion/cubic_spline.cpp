#include "models/motion/cubic_spline.hpp"

#include <Eigen/SparseCore>
#include <Eigen/SparseLU>
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace pkmopt {

CubicSpline::CubicSpline(std::vector<double> times, Eigen::MatrixXd values)
    : times_(std::move(times)), values_(std::move(values)) {
  const Eigen::Index n = static_cast<Eigen::Index>(times_.size());
  if (n < 2) {
    throw std::invalid_argument("CubicSpline: at least 2 samples needed, found " +
                                std::to_string(n));
  }
  if (values_.rows() != n) {
    throw std::invalid_argument("CubicSpline: " + std::to_string(values_.rows()) +
                                " value rows for " + std::to_string(n) + " times");
  }
  if (!values_.allFinite()) throw std::invalid_argument("CubicSpline: a value is not finite");
  for (Eigen::Index k = 0; k < n; ++k) {
    const double t = times_[static_cast<std::size_t>(k)];
    if (!std::isfinite(t)) {
      throw std::invalid_argument("CubicSpline: time " + std::to_string(k) + " is not finite");
    }
    if (k > 0 && !(t > times_[static_cast<std::size_t>(k - 1)])) {
      throw std::invalid_argument("CubicSpline: times must increase strictly (time " +
                                  std::to_string(k) + ")");
    }
  }
  second_ = Eigen::MatrixXd::Zero(n, values_.cols());
  if (n == 2) return;  // the straight line
  auto h = [&](Eigen::Index k) {
    return times_[static_cast<std::size_t>(k + 1)] - times_[static_cast<std::size_t>(k)];
  };
  std::vector<Eigen::Triplet<double>> entries;
  Eigen::MatrixXd rhs = Eigen::MatrixXd::Zero(n, values_.cols());
  // Interior rows: h_k-1 m_k-1 + 2 (h_k-1 + h_k) m_k + h_k m_k+1 = 6 (slope_k - slope_k-1).
  for (Eigen::Index k = 1; k + 1 < n; ++k) {
    entries.emplace_back(k, k - 1, h(k - 1));
    entries.emplace_back(k, k, 2.0 * (h(k - 1) + h(k)));
    entries.emplace_back(k, k + 1, h(k));
    rhs.row(k) = 6.0 * ((values_.row(k + 1) - values_.row(k)) / h(k) -
                        (values_.row(k) - values_.row(k - 1)) / h(k - 1));
  }
  if (n == 3) {  // the parabola: one second derivative
    entries.emplace_back(0, 0, 1.0);
    entries.emplace_back(0, 1, -1.0);
    entries.emplace_back(2, 1, 1.0);
    entries.emplace_back(2, 2, -1.0);
  } else {
    // Not-a-knot: the third derivative (m_k+1 - m_k) / h_k is the same on both sides of t_1 and
    // of t_n-2.
    entries.emplace_back(0, 0, h(1));
    entries.emplace_back(0, 1, -(h(0) + h(1)));
    entries.emplace_back(0, 2, h(0));
    entries.emplace_back(n - 1, n - 3, h(n - 2));
    entries.emplace_back(n - 1, n - 2, -(h(n - 3) + h(n - 2)));
    entries.emplace_back(n - 1, n - 1, h(n - 3));
  }
  Eigen::SparseMatrix<double> A(n, n);
  A.setFromTriplets(entries.begin(), entries.end());
  Eigen::SparseLU<Eigen::SparseMatrix<double>> lu;
  lu.compute(A);
  if (lu.info() != Eigen::Success) {
    throw std::invalid_argument("CubicSpline: the spline system is singular");
  }
  second_ = lu.solve(rhs);
  if (lu.info() != Eigen::Success || !second_.allFinite()) {
    throw std::invalid_argument("CubicSpline: the spline system could not be solved");
  }
}

void CubicSpline::evaluate(double t, Eigen::VectorXd& value, Eigen::VectorXd& rate,
                           Eigen::VectorXd& acceleration) const {
  const std::size_t n = times_.size();
  t = std::clamp(t, times_.front(), times_.back());
  const auto upper = std::upper_bound(times_.begin(), times_.end(), t);
  std::size_t k =
      upper == times_.begin() ? 0 : static_cast<std::size_t>(upper - times_.begin()) - 1;
  k = std::min(k, n - 2);
  const Eigen::Index i = static_cast<Eigen::Index>(k);
  const double h = times_[k + 1] - times_[k];
  const double a = times_[k + 1] - t, b = t - times_[k];  // a + b = h
  const auto m0 = second_.row(i).transpose(), m1 = second_.row(i + 1).transpose();
  const auto y0 = values_.row(i).transpose(), y1 = values_.row(i + 1).transpose();
  const Eigen::VectorXd c0 = y0 / h - m0 * (h / 6.0), c1 = y1 / h - m1 * (h / 6.0);
  // At a sample the sample itself (the formula would round it).
  if (b == 0.0) {
    value = y0;
  } else if (a == 0.0) {
    value = y1;
  } else {
    value = m0 * (a * a * a / (6.0 * h)) + m1 * (b * b * b / (6.0 * h)) + c0 * a + c1 * b;
  }
  rate = -m0 * (a * a / (2.0 * h)) + m1 * (b * b / (2.0 * h)) - c0 + c1;
  acceleration = m0 * (a / h) + m1 * (b / h);
}

}  // namespace pkmopt
