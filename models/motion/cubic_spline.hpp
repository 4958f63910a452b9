// A twice continuously differentiable interpolation of samples y_k (vectors) given at strictly
// increasing times t_k: the not-a-knot cubic spline (de Boor, "A Practical Guide to Splines",
// 1978, ch. IV). On [t_k, t_k+1], with h = t_k+1 - t_k and the knot second derivatives m_k,
//   S(t) = m_k (t_k+1 - t)^3 / 6h + m_k+1 (t - t_k)^3 / 6h
//          + (y_k / h - m_k h / 6) (t_k+1 - t) + (y_k+1 / h - m_k+1 h / 6) (t - t_k),
// continuous with its first and second derivatives at every sample; the third derivative is also
// continuous at t_1 and t_n-2 (not-a-knot), so a cubic polynomial is reproduced exactly (its
// accelerations too, unlike the natural spline, which forces S'' = 0 at both ends). The m_k solve
// the tridiagonal system of the interior conditions plus the two end conditions (Eigen's
// SparseLU). Two samples give the straight line, three the parabola through them.
//
// At a sample time the value is the sample itself, bit for bit. Outside [t_0, t_n-1] the spline
// is evaluated at the nearest end (clamped).
//
// Example:
//   Eigen::MatrixXd y(4, 2);  // 4 samples of a 2-vector, one per row
//   pkmopt::CubicSpline spline({0.0, 1.0, 2.0, 3.0}, y);
//   Eigen::VectorXd value, rate, acceleration;
//   spline.evaluate(1.5, value, rate, acceleration);
#pragma once

#include <Eigen/Core>
#include <vector>

namespace pkmopt {

class CubicSpline {
 public:
  /// `values` holds one sample per row (values.rows() == times.size() >= 2). Throws
  /// std::invalid_argument when the sizes differ, there are fewer than 2 samples, or a time or a
  /// value is not finite, or the times do not increase strictly.
  CubicSpline(std::vector<double> times, Eigen::MatrixXd values);

  /// The value and its first and second time derivatives at t (clamped to the sample span).
  void evaluate(double t, Eigen::VectorXd& value, Eigen::VectorXd& rate,
                Eigen::VectorXd& acceleration) const;

  const std::vector<double>& times() const { return times_; }

 private:
  std::vector<double> times_;
  Eigen::MatrixXd values_;  // samples by row
  Eigen::MatrixXd second_;  // second derivatives at the samples, by row
};

}  // namespace pkmopt
