// Interval arithmetic with outward rounding, enough to enclose a machine's Jacobian over a box of
// poses (models/workspace/mode_certificate.hpp).
//
// Every operation rounds to nearest and then moves each end at least one floating-point number
// outward (not where the result is exact: a product with 0, a sum that is 0): IEEE 754 +, -, *,
// / and sqrt are correctly rounded, so the exact result of every point of the operands lies
// inside. sin and cos come from the C library, which is not
// correctly rounded but within 1 ulp (glibc's documented bound for them); their ends move 4 ulp
// and 1e-15 outward, and the extrema inside the interval are found from the multiples of pi/2.
// No rounding-mode switching is needed (unlike Boost.Interval's exact policies, which need
// -frounding-math for the whole translation unit and do not bound sin and cos rigorously).
//
// Example:
//   const Interval x{0.1, 0.2};
//   const Interval y = x * x + sin(x);  // contains t * t + sin(t) for every t in [0.1, 0.2]
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <limits>
#include <numbers>

namespace pkmopt {

struct Interval {
  double lo = 0.0;
  double hi = 0.0;

  Interval() = default;
  constexpr Interval(double point) : lo(point), hi(point) {}  // NOLINT: a point is an interval
  constexpr Interval(double lower, double upper) : lo(lower), hi(upper) {}

  double mid() const { return 0.5 * lo + 0.5 * hi; }
  double width() const { return hi - lo; }
  /// The largest |x| over the interval.
  double magnitude() const { return std::max(std::abs(lo), std::abs(hi)); }
  bool contains(double x) const { return lo <= x && x <= hi; }
};

namespace interval_detail {
constexpr double kEps = std::numeric_limits<double>::epsilon();  // 2^-52
constexpr double kTiny = std::numeric_limits<double>::min();     // 2^-1022, normal
constexpr double kInf = std::numeric_limits<double>::infinity();

// A sum or difference rounded to nearest, moved outward: |x| 2^-52 is at least one unit in the
// last place of a normal x, and a sum that is 0 or subnormal is exact (no underflow in addition),
// so the exact value lies inside. No subnormal numbers are made (they are slow on x86).
inline double sum_down(double x) { return std::isfinite(x) ? x - std::abs(x) * kEps : x; }
inline double sum_up(double x) { return std::isfinite(x) ? x + std::abs(x) * kEps : x; }
// A product or quotient of a and b rounded to nearest, moved outward: exact when a is 0 (or b,
// for a product); else the smallest normal number covers an underflow.
inline double product_down(double x, bool exact) {
  return exact || !std::isfinite(x) ? x : x - (std::abs(x) * kEps + kTiny);
}
inline double product_up(double x, bool exact) {
  return exact || !std::isfinite(x) ? x : x + (std::abs(x) * kEps + kTiny);
}
}  // namespace interval_detail

inline Interval operator+(const Interval& a, const Interval& b) {
  return {interval_detail::sum_down(a.lo + b.lo), interval_detail::sum_up(a.hi + b.hi)};
}
inline Interval operator-(const Interval& a, const Interval& b) {
  return {interval_detail::sum_down(a.lo - b.hi), interval_detail::sum_up(a.hi - b.lo)};
}
inline Interval operator-(const Interval& a) { return {-a.hi, -a.lo}; }
inline Interval operator*(const Interval& a, const Interval& b) {
  using namespace interval_detail;
  double lo = kInf, hi = -kInf;
  for (const double x : {a.lo, a.hi})
    for (const double y : {b.lo, b.hi}) {
      const double p = x * y;
      const bool exact = x == 0.0 || y == 0.0;
      lo = std::min(lo, product_down(p, exact));
      hi = std::max(hi, product_up(p, exact));
    }
  return {lo, hi};
}
/// a / b for b > 0 or b < 0 (b must not contain 0: the result would be unbounded).
inline Interval operator/(const Interval& a, const Interval& b) {
  using namespace interval_detail;
  if (b.contains(0.0)) return {-kInf, kInf};
  double lo = kInf, hi = -kInf;
  for (const double x : {a.lo, a.hi})
    for (const double y : {b.lo, b.hi}) {
      const double q = x / y;
      lo = std::min(lo, product_down(q, x == 0.0));
      hi = std::max(hi, product_up(q, x == 0.0));
    }
  return {lo, hi};
}
inline Interval& operator+=(Interval& a, const Interval& b) { return a = a + b; }
inline Interval& operator-=(Interval& a, const Interval& b) { return a = a - b; }

/// x^2, tighter than x * x when x contains 0.
inline Interval square(const Interval& x) {
  using namespace interval_detail;
  const double m = x.magnitude();
  if (x.contains(0.0)) return {0.0, product_up(m * m, m == 0.0)};
  const double a = std::min(std::abs(x.lo), std::abs(x.hi));
  return {std::max(0.0, product_down(a * a, false)), product_up(m * m, false)};
}
/// sqrt of the non-negative part of x.
inline Interval sqrt(const Interval& x) {
  using namespace interval_detail;
  return {std::max(0.0, sum_down(std::sqrt(std::max(0.0, x.lo)))),
          sum_up(std::sqrt(std::max(0.0, x.hi)))};
}

namespace interval_detail {
// A value of the C library's sin or cos moved outward by its error bound.
inline double lower_value(double v) { return std::max(-1.0, v - 4e-16 * std::abs(v) - 1e-15); }
inline double upper_value(double v) { return std::min(1.0, v + 4e-16 * std::abs(v) + 1e-15); }
// Whether [lo, hi] holds offset + 2 k pi for some integer k.
inline bool holds_phase(double lo, double hi, double offset) {
  const double two_pi = 2.0 * std::numbers::pi;
  const double k = std::ceil((lo - offset) / two_pi - 1e-12);  // the first candidate at or after lo
  return offset + k * two_pi <= hi + 1e-12;
}
}  // namespace interval_detail

/// sin over x (rad).
inline Interval sin(const Interval& x) {
  using namespace interval_detail;
  if (!(x.width() < 2.0 * std::numbers::pi)) return {-1.0, 1.0};
  const double a = std::sin(x.lo), b = std::sin(x.hi);
  Interval r{lower_value(std::min(a, b)), upper_value(std::max(a, b))};
  if (holds_phase(x.lo, x.hi, 0.5 * std::numbers::pi)) r.hi = 1.0;
  if (holds_phase(x.lo, x.hi, -0.5 * std::numbers::pi)) r.lo = -1.0;
  return r;
}
/// cos over x (rad).
inline Interval cos(const Interval& x) {
  using namespace interval_detail;
  if (!(x.width() < 2.0 * std::numbers::pi)) return {-1.0, 1.0};
  const double a = std::cos(x.lo), b = std::cos(x.hi);
  Interval r{lower_value(std::min(a, b)), upper_value(std::max(a, b))};
  if (holds_phase(x.lo, x.hi, 0.0)) r.hi = 1.0;
  if (holds_phase(x.lo, x.hi, std::numbers::pi)) r.lo = -1.0;
  return r;
}

/// An interval value with interval enclosures of its partial derivatives with respect to the
/// N coordinates of a box (forward-mode differentiation in interval arithmetic): evaluated over
/// the whole box, `d[k]` holds every value the derivative takes there, for the mean-value form
///     f(x) in f(x_mid) + sum_k d[k] (X_k - x_mid,k)   for every x in the box X.
template <int N>
struct IntervalGradient {
  Interval v;
  std::array<Interval, N> d{};

  IntervalGradient() = default;
  IntervalGradient(double point) : v(point) {}           // NOLINT: a constant
  IntervalGradient(const Interval& value) : v(value) {}  // NOLINT: a constant
  /// The box's coordinate `k` over `range`.
  static IntervalGradient coordinate(const Interval& range, int k) {
    IntervalGradient x(range);
    x.d[static_cast<std::size_t>(k)] = 1.0;
    return x;
  }
};

template <int N>
IntervalGradient<N> operator+(const IntervalGradient<N>& a, const IntervalGradient<N>& b) {
  IntervalGradient<N> r(a.v + b.v);
  for (int k = 0; k < N; ++k) r.d[k] = a.d[k] + b.d[k];
  return r;
}
template <int N>
IntervalGradient<N> operator-(const IntervalGradient<N>& a, const IntervalGradient<N>& b) {
  IntervalGradient<N> r(a.v - b.v);
  for (int k = 0; k < N; ++k) r.d[k] = a.d[k] - b.d[k];
  return r;
}
template <int N>
IntervalGradient<N> operator-(const IntervalGradient<N>& a) {
  IntervalGradient<N> r(-a.v);
  for (int k = 0; k < N; ++k) r.d[k] = -a.d[k];
  return r;
}
template <int N>
IntervalGradient<N> operator*(const IntervalGradient<N>& a, const IntervalGradient<N>& b) {
  IntervalGradient<N> r(a.v * b.v);
  for (int k = 0; k < N; ++k) r.d[k] = a.d[k] * b.v + a.v * b.d[k];
  return r;
}
template <int N>
IntervalGradient<N> operator/(const IntervalGradient<N>& a, const IntervalGradient<N>& b) {
  const Interval q = a.v / b.v;
  IntervalGradient<N> r(q);
  for (int k = 0; k < N; ++k) r.d[k] = (a.d[k] - q * b.d[k]) / b.v;
  return r;
}
template <int N>
IntervalGradient<N> square(const IntervalGradient<N>& a) {
  IntervalGradient<N> r(square(a.v));
  for (int k = 0; k < N; ++k) r.d[k] = Interval(2.0) * a.v * a.d[k];
  return r;
}
/// sqrt of a positive value (its derivative is unbounded at 0).
template <int N>
IntervalGradient<N> sqrt(const IntervalGradient<N>& a) {
  const Interval s = sqrt(a.v);
  IntervalGradient<N> r(s);
  for (int k = 0; k < N; ++k) r.d[k] = a.d[k] / (Interval(2.0) * s);
  return r;
}
template <int N>
IntervalGradient<N> sin(const IntervalGradient<N>& a) {
  const Interval c = cos(a.v);
  IntervalGradient<N> r(sin(a.v));
  for (int k = 0; k < N; ++k) r.d[k] = c * a.d[k];
  return r;
}
template <int N>
IntervalGradient<N> cos(const IntervalGradient<N>& a) {
  const Interval s = sin(a.v);
  IntervalGradient<N> r(cos(a.v));
  for (int k = 0; k < N; ++k) r.d[k] = -(s * a.d[k]);
  return r;
}

}  // namespace pkmopt
