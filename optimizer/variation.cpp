#include "optimizer/variation.hpp"

#include <algorithm>
#include <cmath>

namespace pkmopt {
namespace {

// Spread factor for one side: beta is the distance to the bound in units of half the parents'
// gap, plus 1.
double spread_factor(double beta, double eta, double u) {
  const double alpha = 2.0 - std::pow(beta, -(eta + 1.0));
  return u <= 1.0 / alpha ? std::pow(u * alpha, 1.0 / (eta + 1.0))
                          : std::pow(1.0 / (2.0 - u * alpha), 1.0 / (eta + 1.0));
}

}  // namespace

std::pair<double, double> sbx_children(double y1, double y2, double lower, double upper, double eta,
                                       double u) {
  const double gap = y2 - y1;
  const double beta_low = 1.0 + 2.0 * (y1 - lower) / gap;
  const double beta_high = 1.0 + 2.0 * (upper - y2) / gap;
  const double c1 = 0.5 * ((y1 + y2) - spread_factor(beta_low, eta, u) * gap);
  const double c2 = 0.5 * ((y1 + y2) + spread_factor(beta_high, eta, u) * gap);
  return {std::clamp(c1, lower, upper), std::clamp(c2, lower, upper)};
}

double polynomial_mutation_value(double y, double lower, double upper, double eta, double u) {
  const double range = upper - lower;
  const double delta1 = (y - lower) / range;
  const double delta2 = (upper - y) / range;
  const double power = 1.0 / (eta + 1.0);
  double deltaq;
  if (u <= 0.5) {
    const double value = 2.0 * u + (1.0 - 2.0 * u) * std::pow(1.0 - delta1, eta + 1.0);
    deltaq = std::pow(value, power) - 1.0;
  } else {
    const double value = 2.0 * (1.0 - u) + 2.0 * (u - 0.5) * std::pow(1.0 - delta2, eta + 1.0);
    deltaq = 1.0 - std::pow(value, power);
  }
  return std::clamp(y + deltaq * range, lower, upper);
}

void sbx_crossover(std::vector<double>& child1, std::vector<double>& child2, const Bounds& bounds,
                   double eta, Random& rng) {
  for (std::size_t i = 0; i < child1.size(); ++i) {
    if (!rng.bernoulli(0.5)) continue;
    const double lower = bounds.lower[i];
    const double upper = bounds.upper[i];
    if (!(std::abs(child1[i] - child2[i]) > 1e-14) || !(upper > lower)) continue;
    const double y1 = std::min(child1[i], child2[i]);
    const double y2 = std::max(child1[i], child2[i]);
    auto [c1, c2] = sbx_children(y1, y2, lower, upper, eta, rng.uniform01());
    if (rng.bernoulli(0.5)) std::swap(c1, c2);
    child1[i] = c1;
    child2[i] = c2;
  }
}

void polynomial_mutation(std::vector<double>& x, const Bounds& bounds, double probability,
                         double eta, Random& rng) {
  for (std::size_t i = 0; i < x.size(); ++i) {
    if (!rng.bernoulli(probability)) continue;
    const double lower = bounds.lower[i];
    const double upper = bounds.upper[i];
    if (!(upper > lower)) continue;
    x[i] = polynomial_mutation_value(x[i], lower, upper, eta, rng.uniform01());
  }
}

}  // namespace pkmopt
