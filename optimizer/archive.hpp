// Pareto dominance and a non-dominated archive of designs (all objectives minimised).
//
// a dominates b  <=>  a_i <= b_i for every objective i and a_i < b_i for at least one.
// A set is non-dominated when no member dominates another; of several identical objective
// vectors the first one given is kept. Points with a NaN objective are never kept.
//
// Filtering is O(N log N) for two objectives (sort by f_1, then one sweep keeping each point
// whose f_2 is below every f_2 seen so far) and O(N log N + N K) for more (lexicographic sort:
// a point can only be dominated by one sorted before it; K is the size of the result).
//
// Example:
//   pkmopt::ParetoArchive archive;
//   archive.insert({0.1, 0.2}, {1.0, 3.0});  // (x, objectives): kept
//   archive.insert({0.4, 0.0}, {2.0, 4.0});  // dominated by the first: rejected
//   std::vector<std::size_t> keep = pkmopt::non_dominated_indices({{1, 3}, {2, 4}, {3, 1}});
//   // keep == {0, 2}
#pragma once

#include <cstddef>
#include <span>
#include <vector>

namespace pkmopt {

/// True when a Pareto-dominates b (minimisation). Sizes must match.
bool dominates(std::span<const double> a, std::span<const double> b);

/// Indices (ascending) of the non-dominated points of a set of objective vectors.
std::vector<std::size_t> non_dominated_indices(const std::vector<std::vector<double>>& points);

/// A set of mutually non-dominated designs with their objective vectors.
class ParetoArchive {
 public:
  struct Entry {
    std::vector<double> x;           ///< the design variables
    std::vector<double> objectives;  ///< its objective vector (minimised)
  };

  /// Adds a design unless an archived one dominates or equals it; removes the ones it
  /// dominates. Returns true when the design was kept. O(size) per call.
  bool insert(std::vector<double> x, std::vector<double> objectives);
  /// Adds many designs at once (one filtering pass, O(N log N) for two objectives).
  void insert_all(const std::vector<std::vector<double>>& xs,
                  const std::vector<std::vector<double>>& objectives);

  const std::vector<Entry>& entries() const { return entries_; }
  std::size_t size() const { return entries_.size(); }
  bool empty() const { return entries_.empty(); }
  std::vector<std::vector<double>> objective_vectors() const;
  std::vector<std::vector<double>> designs() const;
  /// Sorts the entries by their objective vectors (lexicographically), for stable output.
  void sort();

 private:
  std::vector<Entry> entries_;
};

}  // namespace pkmopt
