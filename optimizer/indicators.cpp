#include "optimizer/indicators.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <iterator>
#include <limits>
#include <map>
#include <memory_resource>
#include <numeric>
#include <stdexcept>

#include "optimizer/archive.hpp"

namespace pkmopt {
namespace {

void check_dimensions(const ObjectiveSet& points, std::size_t m, const char* what) {
  for (const auto& p : points)
    if (p.size() != m)
      throw std::invalid_argument(std::string(what) + ": objective vectors differ in size");
}

// Two objectives, points flattened as (f_1, f_2) pairs strictly inside the reference box, not
// necessarily non-dominated: sorted lexicographically, a point adds a slab only when its f_2
// is below every f_2 seen before (dominated points and duplicates add nothing).
double hypervolume_2d_flat(std::vector<std::array<double, 2>>& points, const double* reference) {
  std::sort(points.begin(), points.end());
  double volume = 0.0;
  double previous_second = reference[1];
  for (const auto& p : points) {
    if (p[1] < previous_second) {
      volume += (reference[0] - p[0]) * (previous_second - p[1]);
      previous_second = p[1];
    }
  }
  return volume;
}

// Three objectives: the dimension sweep of Beume, Fonseca, Lopez-Ibanez, Paquete & Vahrenhold
// (2009, IEEE TEC 13(5)), O(N log N). Points (strictly inside the reference box, dominated ones
// and duplicates allowed) are visited in increasing f_3 (ties: lexicographic in f_1, f_2, so a
// point that weakly dominates another comes first). The 2-D staircase of the (f_1, f_2)
// projections seen so far is a balanced tree f_1 -> f_2 (f_2 strictly decreasing in f_1) whose
// dominated area A is updated incrementally; between consecutive f_3 values the volume grows
// by A times the f_3 step. A point whose projection the staircase weakly dominates is skipped;
// otherwise the entries it dominates are removed and A grows by the uncovered part of the box
// [p_1, r_1] x [p_2, r_2]. Tree nodes come from one arena (no allocation per point).
double hypervolume_3d_flat(std::vector<std::array<double, 3>>& points, const double* reference) {
  if (points.empty()) return 0.0;
  std::sort(points.begin(), points.end(), [](const auto& a, const auto& b) {
    if (a[2] != b[2]) return a[2] < b[2];
    if (a[0] != b[0]) return a[0] < b[0];
    return a[1] < b[1];
  });
  // Each tree node holds two doubles plus the red-black links: 64 bytes covers it.
  std::pmr::monotonic_buffer_resource arena(points.size() * 64 + 256);
  std::pmr::map<double, double> staircase(&arena);
  double area = 0.0;
  double volume = 0.0;
  double previous_third = points.front()[2];
  for (const auto& p : points) {
    volume += area * (p[2] - previous_third);
    previous_third = p[2];
    const double x = p[0];
    const double y = p[1];
    auto it = staircase.lower_bound(x);  // first entry with f_1 >= x
    if (it != staircase.end() && it->first == x && it->second <= y) continue;  // covered
    double height = reference[1];  // staircase height just left of x
    if (it != staircase.begin()) {
      const auto before = std::prev(it);
      if (before->second <= y) continue;  // weakly dominated
      height = before->second;
    }
    // Entries with f_1 >= x and f_2 >= y are now dominated: remove them, adding the area
    // between their steps and the new height y.
    double left = x;
    while (it != staircase.end() && it->second >= y) {
      area += (it->first - left) * (height - y);
      left = it->first;
      height = it->second;
      it = staircase.erase(it);
    }
    const double right = it == staircase.end() ? reference[0] : it->first;
    area += (right - left) * (height - y);
    staircase.emplace_hint(it, x, y);
  }
  volume += area * (reference[2] - previous_third);
  return volume;
}

double hypervolume_3d(const ObjectiveSet& points, const std::vector<double>& reference) {
  std::vector<std::array<double, 3>> flat(points.size());
  for (std::size_t k = 0; k < points.size(); ++k)
    flat[k] = {points[k][0], points[k][1], points[k][2]};
  return hypervolume_3d_flat(flat, reference.data());
}

double hypervolume_2d(const ObjectiveSet& points, const std::vector<double>& reference) {
  std::vector<std::array<double, 2>> flat(points.size());
  for (std::size_t k = 0; k < points.size(); ++k) flat[k] = {points[k][0], points[k][1]};
  return hypervolume_2d_flat(flat, reference.data());
}

double hypervolume_nondominated(ObjectiveSet points, const std::vector<double>& reference);

// WFG slicing: sorted by the last objective, worst first; each point's exclusive volume with
// respect to the points after it is a slab (reference_m - p_m) times an (m-1)-dimensional
// exclusive area.
double hypervolume_wfg(ObjectiveSet points, const std::vector<double>& reference) {
  const std::size_t m = reference.size();
  std::sort(points.begin(), points.end(),
            [m](const auto& a, const auto& b) { return a[m - 1] > b[m - 1]; });
  const std::vector<double> reduced_reference(reference.begin(), reference.end() - 1);
  double volume = 0.0;
  for (std::size_t k = 0; k < points.size(); ++k) {
    const auto& p = points[k];
    const double depth = reference[m - 1] - p[m - 1];
    if (depth <= 0.0) continue;
    double box = 1.0;
    for (std::size_t i = 0; i + 1 < m; ++i) box *= reference[i] - p[i];
    ObjectiveSet limited;
    limited.reserve(points.size() - k - 1);
    for (std::size_t j = k + 1; j < points.size(); ++j) {
      std::vector<double> q(m - 1);
      for (std::size_t i = 0; i + 1 < m; ++i) q[i] = std::max(p[i], points[j][i]);
      limited.push_back(std::move(q));
    }
    ObjectiveSet filtered;
    for (std::size_t index : non_dominated_indices(limited)) filtered.push_back(limited[index]);
    volume += depth * (box - hypervolume_nondominated(std::move(filtered), reduced_reference));
  }
  return volume;
}

double hypervolume_nondominated(ObjectiveSet points, const std::vector<double>& reference) {
  if (points.empty()) return 0.0;
  switch (reference.size()) {
    case 1:
      return reference[0] - points.front()[0];
    case 2:
      return hypervolume_2d(points, reference);
    case 3:
      return hypervolume_3d(points, reference);
    default:
      return hypervolume_wfg(std::move(points), reference);
  }
}

}  // namespace

double hypervolume(const ObjectiveSet& points, const std::vector<double>& reference) {
  const std::size_t m = reference.size();
  if (m == 0) throw std::invalid_argument("hypervolume: empty reference point");
  check_dimensions(points, m, "hypervolume");
  for (double r : reference)
    if (!std::isfinite(r)) throw std::invalid_argument("hypervolume: non-finite reference point");
  // Two and three objectives: straight to the sweeps, which skip dominated points and
  // duplicates themselves (no O(N^2) filtering).
  auto strictly_inside = [&](const std::vector<double>& p) {
    for (std::size_t i = 0; i < m; ++i)
      if (!(p[i] < reference[i])) return false;  // also drops NaN
    return true;
  };
  if (m == 2) {
    std::vector<std::array<double, 2>> flat;
    flat.reserve(points.size());
    for (const auto& p : points)
      if (strictly_inside(p)) flat.push_back({p[0], p[1]});
    return hypervolume_2d_flat(flat, reference.data());
  }
  if (m == 3) {
    std::vector<std::array<double, 3>> flat;
    flat.reserve(points.size());
    for (const auto& p : points)
      if (strictly_inside(p)) flat.push_back({p[0], p[1], p[2]});
    return hypervolume_3d_flat(flat, reference.data());
  }
  ObjectiveSet inside;
  for (const auto& p : points)
    if (strictly_inside(p)) inside.push_back(p);
  if (m == 1) {
    if (inside.empty()) return 0.0;
    double best = inside.front()[0];
    for (const auto& p : inside) best = std::min(best, p[0]);
    return reference[0] - best;
  }
  ObjectiveSet front;
  for (std::size_t index : non_dominated_indices(inside)) front.push_back(inside[index]);
  return hypervolume_nondominated(std::move(front), reference);
}

double igd_plus(const ObjectiveSet& approximation, const ObjectiveSet& reference_front) {
  if (approximation.empty() || reference_front.empty())
    throw std::invalid_argument("igd_plus: empty approximation or reference front");
  const std::size_t m = reference_front.front().size();
  check_dimensions(approximation, m, "igd_plus");
  check_dimensions(reference_front, m, "igd_plus");
  double total = 0.0;
  for (const auto& z : reference_front) {
    double nearest = INFINITY;
    for (const auto& a : approximation) {
      double squared = 0.0;
      for (std::size_t i = 0; i < m; ++i) {
        const double d = std::max(a[i] - z[i], 0.0);
        squared += d * d;
      }
      nearest = std::min(nearest, squared);
    }
    total += std::sqrt(nearest);
  }
  return total / static_cast<double>(reference_front.size());
}

double spacing(const ObjectiveSet& front) {
  const std::size_t n = front.size();
  if (n < 2) return 0.0;
  const std::size_t m = front.front().size();
  check_dimensions(front, m, "spacing");
  std::vector<double> nearest(n, INFINITY);
  for (std::size_t a = 0; a < n; ++a)
    for (std::size_t b = 0; b < n; ++b) {
      if (a == b) continue;
      double distance = 0.0;
      for (std::size_t i = 0; i < m; ++i) distance += std::abs(front[a][i] - front[b][i]);
      nearest[a] = std::min(nearest[a], distance);
    }
  const double mean = std::accumulate(nearest.begin(), nearest.end(), 0.0) / static_cast<double>(n);
  double sum_squares = 0.0;
  for (double d : nearest) sum_squares += (d - mean) * (d - mean);
  return std::sqrt(sum_squares / static_cast<double>(n - 1));
}

std::vector<double> ideal_point(const ObjectiveSet& front) {
  if (front.empty()) throw std::invalid_argument("ideal_point: empty front");
  std::vector<double> ideal = front.front();
  for (const auto& p : front)
    for (std::size_t i = 0; i < ideal.size(); ++i) ideal[i] = std::min(ideal[i], p[i]);
  return ideal;
}

std::vector<double> nadir_point(const ObjectiveSet& front) {
  if (front.empty()) throw std::invalid_argument("nadir_point: empty front");
  std::vector<double> nadir = front.front();
  for (const auto& p : front)
    for (std::size_t i = 0; i < nadir.size(); ++i) nadir[i] = std::max(nadir[i], p[i]);
  return nadir;
}

std::vector<double> reference_point_from(const ObjectiveSet& front, double margin) {
  const std::vector<double> ideal = ideal_point(front);
  std::vector<double> reference = nadir_point(front);
  for (std::size_t i = 0; i < reference.size(); ++i) {
    const double range = reference[i] - ideal[i];
    reference[i] += margin * (range > 0.0 ? range : 1.0);
  }
  return reference;
}

}  // namespace pkmopt
