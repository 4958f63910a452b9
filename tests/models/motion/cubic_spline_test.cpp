// Tests of models/motion/cubic_spline: a cubic polynomial reproduced exactly with its derivatives
// on uneven samples (the not-a-knot property), two samples giving the line and three the parabola,
// the derivatives against differences of the spline's own values, continuity of the second
// derivative at the samples, fourth- and second-order convergence to sin t, and bad input.
#include "models/motion/cubic_spline.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>
#include <vector>

namespace pkmopt {
namespace {

// Two cubics in t, one per column: y = c0 + c1 t + c2 t^2 + c3 t^3.
Eigen::Vector2d cubic(double t, int derivative) {
  const double a[4] = {0.3, -1.2, 0.7, 2.5}, b[4] = {-2.0, 0.4, -3.1, -0.6};
  auto eval = [&](const double* c) {
    switch (derivative) {
      case 0:
        return c[0] + c[1] * t + c[2] * t * t + c[3] * t * t * t;
      case 1:
        return c[1] + 2 * c[2] * t + 3 * c[3] * t * t;
      default:
        return 2 * c[2] + 6 * c[3] * t;
    }
  };
  return {eval(a), eval(b)};
}

TEST(CubicSpline, ReproducesACubicOnUnevenSamples) {
  const std::vector<double> times = {-0.4, 0.1, 0.15, 0.6, 1.3, 1.35, 2.0};
  Eigen::MatrixXd values(7, 2);
  for (int k = 0; k < 7; ++k) values.row(k) = cubic(times[k], 0).transpose();
  const CubicSpline spline(times, values);
  Eigen::VectorXd y, dy, ddy;
  for (double t = -0.4; t <= 2.0; t += 0.037) {
    spline.evaluate(t, y, dy, ddy);
    EXPECT_LT((y - cubic(t, 0)).cwiseAbs().maxCoeff(), 1e-12) << "t " << t;
    EXPECT_LT((dy - cubic(t, 1)).cwiseAbs().maxCoeff(), 1e-11) << "t " << t;
    EXPECT_LT((ddy - cubic(t, 2)).cwiseAbs().maxCoeff(), 1e-10) << "t " << t;
  }
}

TEST(CubicSpline, TwoSamplesGiveTheLineThreeTheParabola) {
  Eigen::MatrixXd two(2, 1);
  two << 1.0, 4.0;
  const CubicSpline line({1.0, 3.0}, two);
  Eigen::VectorXd y, dy, ddy;
  line.evaluate(2.5, y, dy, ddy);
  EXPECT_DOUBLE_EQ(y(0), 3.25);
  EXPECT_DOUBLE_EQ(dy(0), 1.5);
  EXPECT_EQ(ddy(0), 0.0);
  // y = 2 - t + 3 t^2 through t = 0, 0.5, 2.
  Eigen::MatrixXd three(3, 1);
  three << 2.0, 2.25, 12.0;
  const CubicSpline parabola({0.0, 0.5, 2.0}, three);
  for (double t : {0.2, 0.9, 1.7}) {
    parabola.evaluate(t, y, dy, ddy);
    EXPECT_NEAR(y(0), 2 - t + 3 * t * t, 1e-13);
    EXPECT_NEAR(dy(0), -1 + 6 * t, 1e-12);
    EXPECT_NEAR(ddy(0), 6.0, 1e-12);
  }
}

// Rate and acceleration are the derivatives of the value; the second derivative is continuous
// across every sample, the first too.
TEST(CubicSpline, DerivativesAndContinuityAtTheSamples) {
  std::vector<double> times;
  Eigen::MatrixXd values(12, 1);
  for (int k = 0; k < 12; ++k) {
    times.push_back(0.3 * k + 0.05 * std::sin(3.0 * k));
    values(k, 0) = std::cos(1.3 * times.back()) + 0.2 * k;
  }
  const CubicSpline spline(times, values);
  Eigen::VectorXd y0, y1, d0, d1, a0, a1, y, dy, ddy;
  const double h = 1e-6;
  for (double t = 0.1; t < 3.2; t += 0.23) {
    spline.evaluate(t + h, y1, d1, a1);
    spline.evaluate(t - h, y0, d0, a0);
    spline.evaluate(t, y, dy, ddy);
    EXPECT_NEAR(dy(0), (y1(0) - y0(0)) / (2 * h), 1e-7);
    EXPECT_NEAR(ddy(0), (d1(0) - d0(0)) / (2 * h), 1e-6);
  }
  for (std::size_t k = 1; k + 1 < times.size(); ++k) {
    spline.evaluate(times[k] - 1e-12, y0, d0, a0);
    spline.evaluate(times[k] + 1e-12, y1, d1, a1);
    EXPECT_NEAR(y0(0), values(static_cast<Eigen::Index>(k), 0), 1e-10);
    EXPECT_NEAR(d0(0), d1(0), 1e-9);
    EXPECT_NEAR(a0(0), a1(0), 1e-8);
  }
}

// Interpolating sin t on [0, 3] with n samples: the value error falls as h^4, the acceleration
// error as h^2 (halving h: at least 12x and 3.5x smaller).
TEST(CubicSpline, ConvergesToASmoothFunction) {
  auto errors = [](int n) {
    std::vector<double> times;
    Eigen::MatrixXd values(n, 1);
    for (int k = 0; k < n; ++k) {
      times.push_back(3.0 * k / (n - 1));
      values(k, 0) = std::sin(times.back());
    }
    const CubicSpline spline(times, values);
    double value = 0.0, acceleration = 0.0;
    Eigen::VectorXd y, dy, ddy;
    for (double t = 0.0; t <= 3.0; t += 0.0101) {
      spline.evaluate(t, y, dy, ddy);
      value = std::max(value, std::abs(y(0) - std::sin(t)));
      acceleration = std::max(acceleration, std::abs(ddy(0) + std::sin(t)));
    }
    return std::pair{value, acceleration};
  };
  const auto coarse = errors(21), fine = errors(41);
  EXPECT_GT(coarse.first / fine.first, 12.0);
  EXPECT_GT(coarse.second / fine.second, 3.5);
  EXPECT_LT(fine.second, 1e-3);
}

TEST(CubicSpline, ClampsOutsideTheSpan) {
  Eigen::MatrixXd values(4, 1);
  values << 0.0, 1.0, 8.0, 27.0;  // t^3
  const CubicSpline spline({0.0, 1.0, 2.0, 3.0}, values);
  Eigen::VectorXd y, dy, ddy;
  spline.evaluate(5.0, y, dy, ddy);
  EXPECT_NEAR(y(0), 27.0, 1e-12);
  EXPECT_NEAR(ddy(0), 18.0, 1e-11);
  spline.evaluate(-1.0, y, dy, ddy);
  EXPECT_NEAR(y(0), 0.0, 1e-12);
}

TEST(CubicSpline, RejectsBadSamples) {
  Eigen::MatrixXd one(1, 1), three(3, 1);
  one << 1.0;
  three << 1.0, 2.0, 3.0;
  EXPECT_THROW(CubicSpline({0.0}, one), std::invalid_argument);
  EXPECT_THROW(CubicSpline({0.0, 1.0}, three), std::invalid_argument);
  EXPECT_THROW(CubicSpline({0.0, 1.0, 1.0}, three), std::invalid_argument);
  EXPECT_THROW(CubicSpline({0.0, std::nan(""), 2.0}, three), std::invalid_argument);
  three(1, 0) = std::numeric_limits<double>::infinity();
  EXPECT_THROW(CubicSpline({0.0, 1.0, 2.0}, three), std::invalid_argument);
}

}  // namespace
}  // namespace pkmopt
