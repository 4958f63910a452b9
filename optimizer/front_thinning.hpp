// Thinning a non-dominated set to a requested size, keeping its spread.
//
// A study's front is the non-dominated set of every feasible design it evaluated; a long run can
// find thousands. `thin_front` keeps `size` of them by the truncation rule of SPEA2 (Zitzler,
// Laumanns & Thiele, "SPEA2: Improving the Strength Pareto Evolutionary Algorithm", TIK report
// 103, ETH Zürich, 2001), with the extremes protected:
//
//  1. every objective is scaled by the set's range (f - min) / (max - min) (a range of 0: 1);
//  2. the extreme points (the first point, in input order, with the lowest value of each
//     objective) are kept whenever `size` allows;
//  3. while more than `size` points are left, the point nearest to another one (Euclidean
//     distance in the scaled space) is removed; of equal nearest distances the one with the
//     smaller second-nearest distance goes, then the one with the higher index.
//
// Every point kept is a point of the input, so a subset of a non-dominated set stays
// non-dominated: thinning never keeps a dominated design. The result depends only on the
// points and their order (no random numbers, no threads).
//
// Example:
//   std::vector<std::size_t> keep = pkmopt::thin_front({{0, 1}, {0.5, 0.5}, {0.51, 0.49},
//                                                       {1, 0}}, 3);
//   // keep == {0, 1, 3} or {0, 2, 3}: one of the two close middle points goes
#pragma once

#include <cstddef>
#include <vector>

namespace pkmopt {

/// Indices (ascending) of the `size` points kept by the rule above; all indices when the set has
/// at most `size` points. Points must have equal lengths (std::invalid_argument otherwise) and
/// finite values.
std::vector<std::size_t> thin_front(const std::vector<std::vector<double>>& points,
                                    std::size_t size);

/// The front of a set of candidates (all feasible, objectives minimised): indices of the
/// non-dominated points (optimizer/archive.hpp; of identical objective vectors the first),
/// thinned to `size` by thin_front when `size` > 0, in ascending order of their objective
/// vectors (lexicographic; equal vectors cannot both be kept). Points with a NaN objective are
/// never kept. `non_dominated_count` (optional) receives the size of the non-dominated set
/// before thinning.
std::vector<std::size_t> select_front(const std::vector<std::vector<double>>& objectives,
                                      std::size_t size, std::size_t* non_dominated_count = nullptr);

}  // namespace pkmopt
