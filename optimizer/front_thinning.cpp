#include "optimizer/front_thinning.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "optimizer/archive.hpp"

namespace pkmopt {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// The two nearest living neighbours of a point.
struct Neighbours {
  double d1 = kInf, d2 = kInf;
  std::size_t i1 = 0, i2 = 0;
};

}  // namespace

std::vector<std::size_t> thin_front(const std::vector<std::vector<double>>& points,
                                    std::size_t size) {
  const std::size_t n = points.size();
  std::vector<std::size_t> all(n);
  for (std::size_t k = 0; k < n; ++k) all[k] = k;
  if (n == 0) return all;
  const std::size_t m = points.front().size();
  for (const auto& p : points)
    if (p.size() != m)
      throw std::invalid_argument("thin_front: points of different lengths (" + std::to_string(m) +
                                  " and " + std::to_string(p.size()) + ")");
  if (n <= size) return all;
  if (size == 0) return {};

  // 1. Scaled copies.
  std::vector<double> lo(m, kInf), hi(m, -kInf);
  for (const auto& p : points)
    for (std::size_t i = 0; i < m; ++i) {
      lo[i] = std::min(lo[i], p[i]);
      hi[i] = std::max(hi[i], p[i]);
    }
  std::vector<double> scaled(n * m);
  for (std::size_t k = 0; k < n; ++k)
    for (std::size_t i = 0; i < m; ++i) {
      const double range = hi[i] - lo[i];
      scaled[k * m + i] = (points[k][i] - lo[i]) / (range > 0.0 ? range : 1.0);
    }
  auto distance = [&](std::size_t a, std::size_t b) {
    double s = 0.0;
    for (std::size_t i = 0; i < m; ++i) {
      const double d = scaled[a * m + i] - scaled[b * m + i];
      s += d * d;
    }
    return std::sqrt(s);
  };

  // 2. The extremes, as many as `size` allows.
  std::vector<char> is_protected(n, 0);
  std::size_t protected_count = 0;
  for (std::size_t i = 0; i < m && protected_count < size; ++i) {
    std::size_t best = 0;
    for (std::size_t k = 1; k < n; ++k)
      if (points[k][i] < points[best][i]) best = k;
    if (!is_protected[best]) {
      is_protected[best] = 1;
      ++protected_count;
    }
  }

  // 3. Truncation by nearest, then second-nearest distance.
  std::vector<char> alive(n, 1);
  std::vector<Neighbours> nb(n);
  auto refresh = [&](std::size_t a) {
    Neighbours r;
    for (std::size_t b = 0; b < n; ++b) {
      if (b == a || !alive[b]) continue;
      const double d = distance(a, b);
      if (d < r.d1) {
        r.d2 = r.d1;
        r.i2 = r.i1;
        r.d1 = d;
        r.i1 = b;
      } else if (d < r.d2) {
        r.d2 = d;
        r.i2 = b;
      }
    }
    nb[a] = r;
  };
  for (std::size_t a = 0; a < n; ++a) refresh(a);
  for (std::size_t left = n; left > size; --left) {
    std::size_t victim = n;
    for (std::size_t a = 0; a < n; ++a) {
      if (!alive[a] || is_protected[a]) continue;
      if (victim == n || nb[a].d1 < nb[victim].d1 ||
          (nb[a].d1 == nb[victim].d1 && nb[a].d2 <= nb[victim].d2))
        victim = a;  // later indices win ties: the higher index goes
    }
    alive[victim] = 0;
    for (std::size_t a = 0; a < n; ++a)
      if (alive[a] && (nb[a].i1 == victim || nb[a].i2 == victim)) refresh(a);
  }
  std::vector<std::size_t> keep;
  keep.reserve(size);
  for (std::size_t a = 0; a < n; ++a)
    if (alive[a]) keep.push_back(a);
  return keep;
}

std::vector<std::size_t> select_front(const std::vector<std::vector<double>>& objectives,
                                      std::size_t size, std::size_t* non_dominated_count) {
  const std::vector<std::size_t> non_dominated = non_dominated_indices(objectives);
  if (non_dominated_count) *non_dominated_count = non_dominated.size();
  std::vector<std::vector<double>> front;
  front.reserve(non_dominated.size());
  for (std::size_t k : non_dominated) front.push_back(objectives[k]);
  std::vector<std::size_t> keep;
  if (size > 0) {
    for (std::size_t k : thin_front(front, size)) keep.push_back(non_dominated[k]);
  } else {
    keep = non_dominated;
  }
  std::stable_sort(keep.begin(), keep.end(),
                   [&](std::size_t a, std::size_t b) { return objectives[a] < objectives[b]; });
  return keep;
}

}  // namespace pkmopt
