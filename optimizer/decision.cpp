#include "optimizer/decision.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <stdexcept>
#include <string>

namespace pkmopt {
namespace {

constexpr double kAugmentation = 1e-6;  // rho of the augmented achievement function

void check_front(const ObjectiveSet& front, const char* what) {
  if (front.empty()) throw std::invalid_argument(std::string(what) + ": empty front");
  const std::size_t m = front.front().size();
  for (const auto& p : front)
    if (p.size() != m)
      throw std::invalid_argument(std::string(what) + ": objective vectors differ in size");
}

ObjectiveSet normalised_front(const ObjectiveSet& front) {
  const FrontScale scale = front_scale(front);
  ObjectiveSet result;
  result.reserve(front.size());
  for (const auto& p : front) result.push_back(scale.normalised(p));
  return result;
}

std::size_t index_of_smallest(const std::vector<double>& values) {
  return static_cast<std::size_t>(std::min_element(values.begin(), values.end()) - values.begin());
}

double squared_distance(const std::vector<double>& a, const std::vector<double>& b) {
  double sum = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) sum += (a[i] - b[i]) * (a[i] - b[i]);
  return sum;
}

// The neighbours of point i: all within `radius`, at least the `minimum` nearest (ties by index).
std::vector<std::size_t> neighbours(const ObjectiveSet& scaled, std::size_t i, double radius,
                                    std::size_t minimum) {
  std::vector<std::pair<double, std::size_t>> by_distance;
  for (std::size_t j = 0; j < scaled.size(); ++j)
    if (j != i) by_distance.emplace_back(std::sqrt(squared_distance(scaled[i], scaled[j])), j);
  std::sort(by_distance.begin(), by_distance.end());
  std::vector<std::size_t> result;
  for (std::size_t k = 0; k < by_distance.size(); ++k)
    if (k < minimum || by_distance[k].first <= radius) result.push_back(by_distance[k].second);
  return result;
}

}  // namespace

std::vector<double> FrontScale::normalised(const std::vector<double>& f) const {
  std::vector<double> result(f.size());
  for (std::size_t i = 0; i < f.size(); ++i) {
    const double range = nadir[i] - ideal[i];
    result[i] = range > 0.0 ? (f[i] - ideal[i]) / range : 0.0;
  }
  return result;
}

FrontScale front_scale(const ObjectiveSet& front) {
  check_front(front, "front_scale");
  return {ideal_point(front), nadir_point(front)};
}

std::size_t knee_point(const ObjectiveSet& front) {
  check_front(front, "knee_point");
  std::vector<double> sums;
  for (const auto& p : normalised_front(front))
    sums.push_back(std::accumulate(p.begin(), p.end(), 0.0));
  return index_of_smallest(sums);
}

std::size_t compromise_point(const ObjectiveSet& front) {
  check_front(front, "compromise_point");
  const std::vector<double> origin(front.front().size(), 0.0);
  std::vector<double> distances;
  for (const auto& p : normalised_front(front)) distances.push_back(squared_distance(p, origin));
  return index_of_smallest(distances);
}

ObjectiveSet pseudo_weights(const ObjectiveSet& front) {
  check_front(front, "pseudo_weights");
  ObjectiveSet weights;
  weights.reserve(front.size());
  for (const auto& p : normalised_front(front)) {
    std::vector<double> w(p.size());
    double total = 0.0;
    for (std::size_t i = 0; i < p.size(); ++i) {
      w[i] = 1.0 - p[i];
      total += w[i];
    }
    for (double& value : w)
      value = total > 0.0 ? value / total : 1.0 / static_cast<double>(p.size());
    weights.push_back(std::move(w));
  }
  return weights;
}

std::size_t choose_by_weights(const ObjectiveSet& front, const std::vector<double>& preference) {
  check_front(front, "choose_by_weights");
  if (preference.size() != front.front().size())
    throw std::invalid_argument("choose_by_weights: preference size differs from the objectives");
  double total = 0.0;
  for (double p : preference) {
    if (!(p >= 0.0) || !std::isfinite(p))
      throw std::invalid_argument("choose_by_weights: preferences must be finite and >= 0");
    total += p;
  }
  if (!(total > 0.0)) throw std::invalid_argument("choose_by_weights: preferences are all 0");
  std::vector<double> scaled = preference;
  for (double& p : scaled) p /= total;
  std::vector<double> distances;
  for (const auto& w : pseudo_weights(front)) distances.push_back(squared_distance(w, scaled));
  return index_of_smallest(distances);
}

double achievement(const FrontScale& scale, const std::vector<double>& f,
                   const std::vector<double>& reference, const std::vector<double>& weights) {
  const std::vector<double> fn = scale.normalised(f);
  const std::vector<double> zn = scale.normalised(reference);
  double worst = -std::numeric_limits<double>::infinity();
  double sum = 0.0;
  for (std::size_t i = 0; i < fn.size(); ++i) {
    const double w = weights.empty() ? 1.0 : weights[i];
    const double term = w * (fn[i] - zn[i]);
    worst = std::max(worst, term);
    sum += term;
  }
  return worst + kAugmentation * sum;
}

std::size_t choose_by_reference(const ObjectiveSet& front, const std::vector<double>& reference,
                                const std::vector<double>& weights) {
  check_front(front, "choose_by_reference");
  const std::size_t m = front.front().size();
  if (reference.size() != m)
    throw std::invalid_argument("choose_by_reference: reference size differs from the objectives");
  for (double z : reference)
    if (!std::isfinite(z)) throw std::invalid_argument("choose_by_reference: reference not finite");
  if (!weights.empty()) {
    if (weights.size() != m)
      throw std::invalid_argument("choose_by_reference: weights size differs from the objectives");
    for (double w : weights)
      if (!(w > 0.0) || !std::isfinite(w))
        throw std::invalid_argument("choose_by_reference: weights must be finite and > 0");
  }
  const FrontScale scale = front_scale(front);
  std::vector<double> values;
  for (const auto& p : front) values.push_back(achievement(scale, p, reference, weights));
  return index_of_smallest(values);
}

TradeOffs high_trade_off_points(const ObjectiveSet& front, double radius) {
  check_front(front, "high_trade_off_points");
  const ObjectiveSet scaled = normalised_front(front);
  const std::size_t n = scaled.size();
  const std::size_t m = scaled.front().size();
  TradeOffs result;
  result.mu.assign(n, std::numeric_limits<double>::infinity());
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t j : neighbours(scaled, i, radius, 2 * m)) {
      double sacrifice = 0.0, gain = 0.0;
      for (std::size_t k = 0; k < m; ++k) {
        const double d = scaled[j][k] - scaled[i][k];
        (d > 0.0 ? sacrifice : gain) += std::abs(d);
      }
      if (gain > 0.0) result.mu[i] = std::min(result.mu[i], sacrifice / gain);
    }
  }
  std::vector<std::size_t> finite;
  for (std::size_t i = 0; i < n; ++i)
    if (std::isfinite(result.mu[i])) finite.push_back(i);
  if (finite.size() < 2) return result;
  double mean = 0.0;
  for (std::size_t i : finite) mean += result.mu[i];
  mean /= static_cast<double>(finite.size());
  double variance = 0.0;
  for (std::size_t i : finite) variance += (result.mu[i] - mean) * (result.mu[i] - mean);
  const double sigma = std::sqrt(variance / static_cast<double>(finite.size()));
  if (!(sigma > 0.0)) return result;
  for (std::size_t i : finite)
    if (result.mu[i] >= mean + 2.0 * sigma) result.points.push_back(i);
  if (result.points.empty()) {
    const std::size_t top = *std::max_element(
        finite.begin(), finite.end(),
        [&](std::size_t a, std::size_t b) { return result.mu[a] < result.mu[b]; });
    if (result.mu[top] >= mean + sigma) result.points.push_back(top);
  }
  std::stable_sort(result.points.begin(), result.points.end(),
                   [&](std::size_t a, std::size_t b) { return result.mu[a] > result.mu[b]; });
  return result;
}

}  // namespace pkmopt
