// Tests of models/core/interval.hpp: every operation's result holds the exact result of every
// point of its operands (checked on random points, in long double), sin and cos reach their
// extrema inside an interval, the enclosures stay tight, and the derivatives of IntervalGradient
// hold the central differences of random points of the box.
#include "models/core/interval.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <numbers>
#include <random>

namespace pkmopt {
namespace {

constexpr double kPi = std::numbers::pi;

Interval random_interval(std::mt19937_64& engine, double scale) {
  std::uniform_real_distribution<double> u(-scale, scale);
  const double a = u(engine), b = u(engine);
  return {std::min(a, b), std::max(a, b)};
}

double random_in(std::mt19937_64& engine, const Interval& x) {
  return x.lo + std::uniform_real_distribution<double>(0.0, 1.0)(engine) * (x.hi - x.lo);
}

// The exact value, as long double, lies in the enclosure.
void expect_inside(const Interval& r, long double exact, const char* what) {
  EXPECT_LE(static_cast<long double>(r.lo), exact) << what;
  EXPECT_GE(static_cast<long double>(r.hi), exact) << what;
}

TEST(Interval, ArithmeticHoldsEveryPointsResult) {
  std::mt19937_64 engine(3);
  for (int trial = 0; trial < 2000; ++trial) {
    const Interval a = random_interval(engine, 3.0), b = random_interval(engine, 3.0);
    const Interval positive{0.5 + std::abs(b.lo), 0.5 + std::abs(b.lo) + b.width()};
    for (int k = 0; k < 20; ++k) {
      const long double x = random_in(engine, a), y = random_in(engine, b),
                        z = random_in(engine, positive);
      expect_inside(a + b, x + y, "+");
      expect_inside(a - b, x - y, "-");
      expect_inside(a * b, x * y, "*");
      expect_inside(a / positive, x / z, "/");
      expect_inside(square(a), x * x, "square");
      expect_inside(sqrt(positive), std::sqrt(z), "sqrt");
      expect_inside(sin(a), std::sin(x), "sin");
      expect_inside(cos(a), std::cos(x), "cos");
    }
  }
}

TEST(Interval, EndpointsOfExactlyRepresentableResultsMoveOutward) {
  // 0.1 + 0.2 is not 0.3 in doubles: the enclosure holds the exact sum of the two doubles.
  const Interval s = Interval(0.1) + Interval(0.2);
  const long double exact = static_cast<long double>(0.1) + static_cast<long double>(0.2);
  EXPECT_LT(static_cast<long double>(s.lo), exact);
  EXPECT_GT(static_cast<long double>(s.hi), exact);
  EXPECT_LT(s.width(), 1e-15);
  // Products with an exact 0 stay exactly 0 (no spurious tiny widths).
  const Interval z = Interval(0.0) * Interval(-2.0, 3.0);
  EXPECT_EQ(z.lo, 0.0);
  EXPECT_EQ(z.hi, 0.0);
  EXPECT_EQ((Interval(0.0, 2.0) * Interval(0.0, 3.0)).lo, 0.0);
}

TEST(Interval, SinAndCosReachTheirExtremaInside) {
  const Interval across_max = sin(Interval(1.0, 2.0));  // pi/2 inside
  EXPECT_EQ(across_max.hi, 1.0);
  EXPECT_NEAR(across_max.lo, std::sin(1.0), 1e-14);
  const Interval across_min = cos(Interval(3.0, 3.5));  // pi inside
  EXPECT_EQ(across_min.lo, -1.0);
  EXPECT_NEAR(across_min.hi, std::cos(3.5), 1e-14);  // the larger end
  // Far from the extrema: the values at the ends, tight.
  const Interval c = cos(Interval(0.2, 0.3));
  EXPECT_NEAR(c.lo, std::cos(0.3), 2e-15);
  EXPECT_NEAR(c.hi, std::cos(0.2), 2e-15);
  EXPECT_EQ(sin(Interval(0.0, 7.0)).lo, -1.0);
  EXPECT_EQ(sin(Interval(-kPi, kPi)).hi, 1.0);
  const Interval wrap = cos(Interval(6.0, 6.5));  // 2 pi inside
  EXPECT_EQ(wrap.hi, 1.0);
}

TEST(Interval, GradientHoldsTheDerivativesOverTheBox) {
  // f(x, y) = sin(x) y^2 / sqrt(1 + x^2) + cos(x y); its gradient at random points of the box,
  // by central differences, lies in the enclosure.
  using G = IntervalGradient<2>;
  auto f = [](const auto& x, const auto& y) {
    using std::cos, std::sin, std::sqrt;
    using T = std::decay_t<decltype(x)>;
    return sin(x) * square(y) / sqrt(T(1.0) + square(x)) + cos(x * y);
  };
  auto square_of = [](double v) { return v * v; };
  auto fd = [&](double x, double y) {
    return std::sin(x) * square_of(y) / std::sqrt(1.0 + square_of(x)) + std::cos(x * y);
  };
  std::mt19937_64 engine(11);
  for (int trial = 0; trial < 200; ++trial) {
    const Interval X = random_interval(engine, 2.0), Y = random_interval(engine, 2.0);
    const G r = f(G::coordinate(X, 0), G::coordinate(Y, 1));
    for (int k = 0; k < 10; ++k) {
      const double x = random_in(engine, X), y = random_in(engine, Y), h = 1e-6;
      EXPECT_TRUE(r.v.contains(fd(x, y)));
      const double dx = (fd(x + h, y) - fd(x - h, y)) / (2 * h);
      const double dy = (fd(x, y + h) - fd(x, y - h)) / (2 * h);
      // The differences err by about h^2 |f'''| + eps / h: 1e-9 covers both.
      EXPECT_LE(r.d[0].lo, dx + 1e-9);
      EXPECT_GE(r.d[0].hi, dx - 1e-9);
      EXPECT_LE(r.d[1].lo, dy + 1e-9);
      EXPECT_GE(r.d[1].hi, dy - 1e-9);
    }
  }
}

}  // namespace
}  // namespace pkmopt
