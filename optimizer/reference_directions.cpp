#include "optimizer/reference_directions.hpp"

#include <fmt/format.h>

#include <cmath>
#include <stdexcept>

namespace pkmopt {
namespace {

constexpr std::size_t kMaxDirections = 10'000'000;

// Appends every (k_i, ..., k_M) with sum `left`, k_i descending first, to `out` as k / H.
void fill(std::size_t i, std::size_t left, std::size_t divisions, std::vector<double>& current,
          std::vector<std::vector<double>>& out) {
  const std::size_t m = current.size();
  if (i + 1 == m) {
    current[i] = static_cast<double>(left) / static_cast<double>(divisions);
    out.push_back(current);
    return;
  }
  for (std::size_t k = left + 1; k-- > 0;) {
    current[i] = static_cast<double>(k) / static_cast<double>(divisions);
    fill(i + 1, left - k, divisions, current, out);
  }
}

}  // namespace

std::size_t das_dennis_count(std::size_t objectives, std::size_t divisions) {
  if (objectives < 1)
    throw std::invalid_argument("das_dennis_count: expected at least one objective, found 0");
  // C(H + M - 1, M - 1) by the product formula, stopping past the cap.
  double count = 1.0;
  for (std::size_t j = 1; j < objectives; ++j) {
    count = count * static_cast<double>(divisions + j) / static_cast<double>(j);
    if (count > static_cast<double>(kMaxDirections))
      throw std::invalid_argument(fmt::format(
          "das_dennis_count: {} objectives with {} divisions give more than {} directions",
          objectives, divisions, kMaxDirections));
  }
  return static_cast<std::size_t>(count + 0.5);
}

std::vector<std::vector<double>> das_dennis_directions(std::size_t objectives,
                                                       std::size_t divisions) {
  if (divisions < 1)
    throw std::invalid_argument("das_dennis_directions: expected divisions >= 1, found 0");
  const std::size_t count = das_dennis_count(objectives, divisions);
  std::vector<std::vector<double>> out;
  out.reserve(count);
  std::vector<double> current(objectives, 0.0);
  fill(0, divisions, divisions, current, out);
  return out;
}

std::vector<std::vector<double>> two_layer_directions(std::size_t objectives,
                                                      std::size_t outer_divisions,
                                                      std::size_t inner_divisions) {
  std::vector<std::vector<double>> out = das_dennis_directions(objectives, outer_divisions);
  if (inner_divisions == 0) return out;
  const double tau = 0.5;
  const double centre = (1.0 - tau) / static_cast<double>(objectives);
  for (std::vector<double> w : das_dennis_directions(objectives, inner_divisions)) {
    for (double& v : w) v = centre + tau * v;
    out.push_back(std::move(w));
  }
  return out;
}

void check_given_directions(const std::vector<std::vector<double>>& directions,
                            std::size_t objectives, std::string_view who, std::string_view what) {
  for (const std::vector<double>& w : directions) {
    double sum = 0.0;
    bool ok = w.size() == objectives;
    for (double v : w) {
      ok = ok && std::isfinite(v) && v >= 0.0;
      sum += v;
    }
    if (!ok || !(sum > 0.0))
      throw std::invalid_argument(fmt::format(
          "{}: expected {} of {} finite components >= 0, not all 0", who, what, objectives));
  }
}

}  // namespace pkmopt
