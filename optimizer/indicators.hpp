// Quality indicators of a Pareto front approximation (choosing one design from a front:
// optimizer/decision.hpp).
// All objectives are minimised; a "front" is a list of objective vectors of equal length m.
//
// - hypervolume(A, r): the Lebesgue measure of the region dominated by A and bounded by the
//   reference point r, { y : a <= y <= r for some a in A } (larger is better). Points with any
//   a_i >= r_i add nothing. Exact: m = 2 by one sweep (O(N log N)); m = 3 by the dimension
//   sweep of Beume, Fonseca, Lopez-Ibanez, Paquete & Vahrenhold (2009, IEEE TEC 13(5)): in
//   increasing f_3, the (f_1, f_2) staircase of the points seen so far is kept in a balanced
//   tree (nodes from one arena) with its area updated incrementally, O(N log N); both sweeps
//   skip dominated points and duplicates themselves (no O(N^2) pre-filtering). m >= 4 by WFG's
//   slicing recursion (While, Bradstreet & Barone 2012) down to the 3-D case.
// - igd_plus(A, Z): IGD+ of Ishibuchi et al. (2015), the mean over reference points z in Z of
//   min_{a in A} sqrt( sum_i max(a_i - z_i, 0)^2 ) (smaller is better; 0 when A covers Z).
// - spacing(A): Schott's spacing, the standard deviation (divisor N - 1) of the L1 distance of
//   each point to its nearest neighbour in A (0 for an evenly spread front).
// Units are those of the objectives (hypervolume: their product).
//
// Example:
//   double hv = pkmopt::hypervolume({{0.0, 1.0}, {0.5, 0.5}, {1.0, 0.0}}, {1.0, 1.0});  // 0.25
//   double igd = pkmopt::igd_plus(front, zdt1.reference_front(500));
#pragma once

#include <cstddef>
#include <vector>

namespace pkmopt {

using ObjectiveSet = std::vector<std::vector<double>>;

/// Exact hypervolume dominated by `points` up to `reference` (see header comment).
double hypervolume(const ObjectiveSet& points, const std::vector<double>& reference);

/// IGD+ of `approximation` with respect to `reference_front` (both non-empty).
double igd_plus(const ObjectiveSet& approximation, const ObjectiveSet& reference_front);

/// Schott's spacing (0 for fewer than 2 points).
double spacing(const ObjectiveSet& front);

/// Component-wise minimum and maximum of a non-empty set.
std::vector<double> ideal_point(const ObjectiveSet& front);
std::vector<double> nadir_point(const ObjectiveSet& front);

/// A reference point for the hypervolume: nadir + margin * (nadir - ideal) per objective
/// (a range of 0 is replaced by 1).
std::vector<double> reference_point_from(const ObjectiveSet& front, double margin = 0.1);

}  // namespace pkmopt
