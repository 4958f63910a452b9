// Tests of optimizer/variation: SBX and polynomial mutation against Deb's reference formulas
// (nsga2r crossover.c `realcross` and mutation.c `real_mutate_ind`; Deb & Agrawal 1995,
// Deb & Goyal 1996) for fixed draws, and the distributions they sample.
#include "optimizer/variation.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <vector>

#include "optimizer/random.hpp"

namespace pkmopt {
namespace {

// nsga2r's realcross for one variable and one draw `rand` (Deb's variable names), before the
// random swap of the children.
std::pair<double, double> deb_realcross(double parent1, double parent2, double yl, double yu,
                                        double eta_c, double rand) {
  const double y1 = std::min(parent1, parent2);
  const double y2 = std::max(parent1, parent2);
  double beta = 1.0 + (2.0 * (y1 - yl) / (y2 - y1));
  double alpha = 2.0 - std::pow(beta, -(eta_c + 1.0));
  double betaq = rand <= (1.0 / alpha)
                     ? std::pow((rand * alpha), (1.0 / (eta_c + 1.0)))
                     : std::pow((1.0 / (2.0 - rand * alpha)), (1.0 / (eta_c + 1.0)));
  double c1 = 0.5 * ((y1 + y2) - betaq * (y2 - y1));
  beta = 1.0 + (2.0 * (yu - y2) / (y2 - y1));
  alpha = 2.0 - std::pow(beta, -(eta_c + 1.0));
  betaq = rand <= (1.0 / alpha) ? std::pow((rand * alpha), (1.0 / (eta_c + 1.0)))
                                : std::pow((1.0 / (2.0 - rand * alpha)), (1.0 / (eta_c + 1.0)));
  double c2 = 0.5 * ((y1 + y2) + betaq * (y2 - y1));
  c1 = std::clamp(c1, yl, yu);
  c2 = std::clamp(c2, yl, yu);
  return {c1, c2};
}

// nsga2r's real_mutate_ind for one variable and one draw `rnd`.
double deb_real_mutate(double y, double yl, double yu, double eta_m, double rnd) {
  const double delta1 = (y - yl) / (yu - yl);
  const double delta2 = (yu - y) / (yu - yl);
  const double mut_pow = 1.0 / (eta_m + 1.0);
  double deltaq;
  if (rnd <= 0.5) {
    const double xy = 1.0 - delta1;
    const double val = 2.0 * rnd + (1.0 - 2.0 * rnd) * (std::pow(xy, (eta_m + 1.0)));
    deltaq = std::pow(val, mut_pow) - 1.0;
  } else {
    const double xy = 1.0 - delta2;
    const double val = 2.0 * (1.0 - rnd) + 2.0 * (rnd - 0.5) * (std::pow(xy, (eta_m + 1.0)));
    deltaq = 1.0 - (std::pow(val, mut_pow));
  }
  return std::clamp(y + deltaq * (yu - yl), yl, yu);
}

const std::vector<double> kDraws{0.0,    1e-9, 0.01, 0.1, 0.25, 0.49,           0.5,
                                 0.5102, 0.51, 0.75, 0.9, 0.99, 1.0 - 0x1.0p-53};

TEST(Sbx, MatchesDebReferenceForFixedDraws) {
  struct Parents {
    double a, b, lower, upper;
  };
  const std::vector<Parents> cases{{0.4, 0.6, 0.0, 1.0},   {0.6, 0.4, 0.0, 1.0},
                                   {0.0, 0.05, 0.0, 1.0},  {0.97, 1.0, 0.0, 1.0},
                                   {-3.0, 2.0, -5.0, 5.0}, {0.1, 0.100001, 0.0, 1.0}};
  for (const Parents& p : cases)
    for (double eta : {1.0, 2.0, 15.0, 30.0})
      for (double u : kDraws) {
        const auto [c1, c2] =
            sbx_children(std::min(p.a, p.b), std::max(p.a, p.b), p.lower, p.upper, eta, u);
        const auto [r1, r2] = deb_realcross(p.a, p.b, p.lower, p.upper, eta, u);
        EXPECT_DOUBLE_EQ(c1, r1) << p.a << " " << p.b << " eta " << eta << " u " << u;
        EXPECT_DOUBLE_EQ(c2, r2) << p.a << " " << p.b << " eta " << eta << " u " << u;
        EXPECT_GE(c1, p.lower);
        EXPECT_LE(c2, p.upper);
        EXPECT_LE(c1, c2);
      }
}

TEST(Sbx, HandComputedValuesAndBoundaryLimits) {
  // y = (0.4, 0.6) in [0, 1], eta = 1, u = 0.5: beta_1 = 1 + 2 * 0.4 / 0.2 = 5,
  // alpha = 2 - 5^-2 = 1.96, u <= 1 / alpha, beta_q = sqrt(0.5 * 1.96) = sqrt(0.98);
  // c1 = (1 - 0.2 sqrt(0.98)) / 2, and by symmetry c2 = (1 + 0.2 sqrt(0.98)) / 2.
  const auto [c1, c2] = sbx_children(0.4, 0.6, 0.0, 1.0, 1.0, 0.5);
  EXPECT_NEAR(c1, 0.5 * (1.0 - 0.2 * std::sqrt(0.98)), 1e-15);
  EXPECT_NEAR(c2, 0.5 * (1.0 + 0.2 * std::sqrt(0.98)), 1e-15);
  // u -> 1 reaches beta_q = beta: the children land on the bounds themselves. (The limit is
  // ill-conditioned when beta^-(eta+1) nears 2^-53, so small eta and near bounds here.)
  const double last = 1.0 - 0x1.0p-53;
  for (double eta : {1.0, 2.0}) {
    const auto [low, high] = sbx_children(0.3, 0.45, 0.0, 1.0, eta, last);
    EXPECT_NEAR(low, 0.0, 1e-12);
    EXPECT_NEAR(high, 1.0, 1e-12);
  }
  // u = 0: both children at the parents' mean.
  const auto [m1, m2] = sbx_children(0.3, 0.45, 0.0, 1.0, 15.0, 0.0);
  EXPECT_DOUBLE_EQ(m1, 0.375);
  EXPECT_DOUBLE_EQ(m2, 0.375);
}

TEST(PolynomialMutation, MatchesDebReferenceForFixedDraws) {
  for (double y : {0.0, 0.2, 0.5, 0.93, 1.0})
    for (double eta : {1.0, 5.0, 20.0, 50.0})
      for (double u : kDraws) {
        const double ours = polynomial_mutation_value(2.0 * y - 1.0, -1.0, 1.0, eta, u);
        EXPECT_DOUBLE_EQ(ours, deb_real_mutate(2.0 * y - 1.0, -1.0, 1.0, eta, u))
            << "y " << y << " eta " << eta << " u " << u;
        EXPECT_GE(ours, -1.0);
        EXPECT_LE(ours, 1.0);
      }
  // u = 1/2 leaves y unchanged; u -> 0 and u -> 1 reach the bounds.
  EXPECT_DOUBLE_EQ(polynomial_mutation_value(0.3, 0.0, 1.0, 20.0, 0.5), 0.3);
  EXPECT_NEAR(polynomial_mutation_value(0.5, 0.0, 1.0, 5.0, 0.0), 0.0, 1e-15);
  EXPECT_NEAR(polynomial_mutation_value(0.5, 0.0, 1.0, 5.0, 1.0 - 0x1.0p-53), 1.0, 1e-12);
}

// Kolmogorov-Smirnov distance between a sample and a continuous CDF.
double ks_distance(std::vector<double> sample, const std::function<double(double)>& cdf) {
  std::sort(sample.begin(), sample.end());
  const double n = static_cast<double>(sample.size());
  double distance = 0.0;
  for (std::size_t i = 0; i < sample.size(); ++i) {
    const double f = cdf(sample[i]);
    distance = std::max({distance, std::abs(static_cast<double>(i + 1) / n - f),
                         std::abs(static_cast<double>(i) / n - f)});
  }
  return distance;
}

// 20,000 draws: the KS critical distance at significance 0.001 is 1.95 / sqrt(n) = 0.0138.
constexpr std::size_t kSamples = 20000;
const double kCritical = 1.95 / std::sqrt(static_cast<double>(kSamples));

// Deb & Agrawal's spread CDF: b^(eta+1) / 2 for b <= 1, 1 - b^-(eta+1) / 2 above.
double spread_cdf(double b, double eta) {
  return b <= 1.0 ? 0.5 * std::pow(b, eta + 1.0) : 1.0 - 0.5 * std::pow(b, -(eta + 1.0));
}

TEST(Sbx, UnboundedSpreadFollowsDebAgrawalDensity) {
  const double eta = 10.0;
  const Bounds bounds{{-1e6}, {1e6}};  // so far away that alpha = 2 to rounding
  Random rng(11);
  std::vector<double> spread;
  std::size_t crossed = 0, draws = 0;
  while (spread.size() < kSamples) {
    std::vector<double> a{0.0}, b{1.0};
    sbx_crossover(a, b, bounds, eta, rng);
    ++draws;
    if (a[0] == 0.0 && b[0] == 1.0) continue;  // not crossed (probability 1/2)
    ++crossed;
    spread.push_back(std::abs(b[0] - a[0]));  // beta_q, the parents being 1 apart
  }
  EXPECT_LT(ks_distance(spread, [eta](double x) { return spread_cdf(x, eta); }), kCritical);
  // Each variable is crossed with probability 1/2: 4 standard deviations of a binomial.
  EXPECT_NEAR(static_cast<double>(crossed) / static_cast<double>(draws), 0.5,
              4.0 * 0.5 / std::sqrt(static_cast<double>(draws)));
}

TEST(Sbx, BoundedSpreadIsTruncatedAtTheBounds) {
  // Parents 0.1 and 0.3 in [0, 1]: beta_1 = 2, beta_2 = 8. The lower child's spread follows
  // F(b) / F(beta_1), the upper child's F(b) / F(beta_2).
  const double eta = 2.0, y1 = 0.1, y2 = 0.3;
  const double beta_low = 1.0 + 2.0 * y1 / (y2 - y1);
  const double beta_high = 1.0 + 2.0 * (1.0 - y2) / (y2 - y1);
  const Bounds bounds{{0.0}, {1.0}};
  Random rng(12);
  std::vector<double> low, high;
  while (low.size() < kSamples) {
    std::vector<double> a{y1}, b{y2};
    sbx_crossover(a, b, bounds, eta, rng);
    if (a[0] == y1 && b[0] == y2) continue;
    const double c1 = std::min(a[0], b[0]), c2 = std::max(a[0], b[0]);
    EXPECT_GE(c1, 0.0);
    EXPECT_LE(c2, 1.0);
    low.push_back((y1 + y2 - 2.0 * c1) / (y2 - y1));
    high.push_back((2.0 * c2 - y1 - y2) / (y2 - y1));
  }
  EXPECT_LT(ks_distance(low,
                        [&](double x) {
                          return std::min(1.0, spread_cdf(x, eta) / spread_cdf(beta_low, eta));
                        }),
            kCritical);
  EXPECT_LT(ks_distance(high,
                        [&](double x) {
                          return std::min(1.0, spread_cdf(x, eta) / spread_cdf(beta_high, eta));
                        }),
            kCritical);
}

TEST(PolynomialMutation, StepFollowsBoundedPolynomialDistribution) {
  // y = 0.2 in [0, 1] (delta_1 = 0.2, delta_2 = 0.8), eta = 20, probability 1.
  const double eta = 20.0, y = 0.2;
  const double a = std::pow(1.0 - 0.2, eta + 1.0), b = std::pow(1.0 - 0.8, eta + 1.0);
  auto cdf = [&](double d) {
    return d <= 0.0 ? (std::pow(1.0 + d, eta + 1.0) - a) / (2.0 * (1.0 - a))
                    : 1.0 - (std::pow(1.0 - d, eta + 1.0) - b) / (2.0 * (1.0 - b));
  };
  Random rng(13);
  std::vector<double> steps;
  for (std::size_t k = 0; k < kSamples; ++k) {
    std::vector<double> x{y};
    polynomial_mutation(x, Bounds{{0.0}, {1.0}}, 1.0, eta, rng);
    steps.push_back(x[0] - y);
  }
  EXPECT_LT(ks_distance(steps, cdf), kCritical);
  // Probability p_m per variable: 30 variables at p = 0.1 change 3 on average.
  std::vector<double> x(30, 0.5);
  std::size_t changed = 0;
  const std::size_t trials = 2000;
  for (std::size_t k = 0; k < trials; ++k) {
    std::vector<double> z = x;
    polynomial_mutation(z, Bounds{std::vector<double>(30, 0.0), std::vector<double>(30, 1.0)}, 0.1,
                        eta, rng);
    for (double v : z) changed += v != 0.5 ? 1 : 0;
  }
  const double total = 30.0 * static_cast<double>(trials);
  EXPECT_NEAR(static_cast<double>(changed) / total, 0.1, 4.0 * std::sqrt(0.09 / total));
}

}  // namespace
}  // namespace pkmopt
