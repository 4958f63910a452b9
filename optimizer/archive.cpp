#include "optimizer/archive.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>

namespace pkmopt {

bool dominates(std::span<const double> a, std::span<const double> b) {
  if (a.size() != b.size())
    throw std::invalid_argument("dominates: objective vectors differ in size");
  bool strictly_better = false;
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (!(a[i] <= b[i])) return false;
    if (a[i] < b[i]) strictly_better = true;
  }
  return strictly_better;
}

namespace {

bool has_nan(const std::vector<double>& point) {
  return std::any_of(point.begin(), point.end(), [](double v) { return std::isnan(v); });
}

bool weakly_dominates(const std::vector<double>& a, const std::vector<double>& b) {
  for (std::size_t i = 0; i < a.size(); ++i)
    if (!(a[i] <= b[i])) return false;
  return true;
}

}  // namespace

std::vector<std::size_t> non_dominated_indices(const std::vector<std::vector<double>>& points) {
  std::vector<std::size_t> order;
  order.reserve(points.size());
  for (std::size_t k = 0; k < points.size(); ++k) {
    if (!points[k].empty() && points[k].size() != points.front().size())
      throw std::invalid_argument("non_dominated_indices: objective vectors differ in size");
    if (!has_nan(points[k])) order.push_back(k);
  }
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return std::lexicographical_compare(points[a].begin(), points[a].end(), points[b].begin(),
                                        points[b].end());
  });
  std::vector<std::size_t> kept;
  if (order.empty()) return kept;
  const std::size_t m = points[order.front()].size();
  if (m == 1) {
    kept.push_back(order.front());
  } else if (m == 2) {
    double best_second = INFINITY;
    bool first = true;
    for (std::size_t k : order) {
      if (first || points[k][1] < best_second) {
        kept.push_back(k);
        best_second = points[k][1];
        first = false;
      }
    }
  } else {
    // Lexicographic order: only an earlier point can dominate (or equal) a later one.
    for (std::size_t k : order) {
      const bool covered = std::any_of(kept.begin(), kept.end(), [&](std::size_t j) {
        return weakly_dominates(points[j], points[k]);
      });
      if (!covered) kept.push_back(k);
    }
  }
  std::sort(kept.begin(), kept.end());
  return kept;
}

bool ParetoArchive::insert(std::vector<double> x, std::vector<double> objectives) {
  if (has_nan(objectives)) return false;
  for (const Entry& entry : entries_)
    if (weakly_dominates(entry.objectives, objectives)) return false;
  std::erase_if(entries_,
                [&](const Entry& entry) { return dominates(objectives, entry.objectives); });
  entries_.push_back({std::move(x), std::move(objectives)});
  return true;
}

void ParetoArchive::insert_all(const std::vector<std::vector<double>>& xs,
                               const std::vector<std::vector<double>>& objectives) {
  if (xs.size() != objectives.size())
    throw std::invalid_argument(
        "ParetoArchive::insert_all: designs and objectives differ in count");
  std::vector<std::vector<double>> all = objective_vectors();
  all.insert(all.end(), objectives.begin(), objectives.end());
  const std::size_t old_size = entries_.size();
  const std::vector<std::size_t> keep = non_dominated_indices(all);
  std::vector<Entry> next;
  next.reserve(keep.size());
  for (std::size_t k : keep) {
    if (k < old_size)
      next.push_back(std::move(entries_[k]));
    else
      next.push_back({xs[k - old_size], objectives[k - old_size]});
  }
  entries_ = std::move(next);
}

std::vector<std::vector<double>> ParetoArchive::objective_vectors() const {
  std::vector<std::vector<double>> result;
  result.reserve(entries_.size());
  for (const Entry& entry : entries_) result.push_back(entry.objectives);
  return result;
}

std::vector<std::vector<double>> ParetoArchive::designs() const {
  std::vector<std::vector<double>> result;
  result.reserve(entries_.size());
  for (const Entry& entry : entries_) result.push_back(entry.x);
  return result;
}

void ParetoArchive::sort() {
  std::sort(entries_.begin(), entries_.end(),
            [](const Entry& a, const Entry& b) { return a.objectives < b.objectives; });
}

}  // namespace pkmopt
