// Choosing one design from a Pareto front: the rules a decision maker applies to a front once it
// is found. All objectives are minimised; a "front" is a non-empty list of objective vectors of
// equal length m (optimizer/indicators.hpp). Every rule works in normalised coordinates
//   f^_i = (f_i - ideal_i) / (nadir_i - ideal_i)
// with the front's own ideal and nadir points (an objective of zero range maps to 0), so the
// answer does not depend on the objectives' units.
//
// - knee_point: the point farthest below the hyperplane through the unit vectors, i.e. the
//   smallest sum of f^_i (Das 1999; with two objectives the point farthest from the line joining
//   the extreme points).
// - compromise_point: the point nearest the ideal point (f^ = 0) in the Euclidean norm, the
//   compromise solution of compromise programming (Zeleny 1973, p = 2).
// - pseudo_weights / choose_by_weights: Deb's pseudo-weights (Deb 2001, sec. 8.3),
//   w_i = (1 - f^_i) / sum_j (1 - f^_j), the relative importance each point gives each objective;
//   the rule returns the point whose pseudo-weight vector is nearest (Euclidean) to the user's
//   preference vector (scaled to sum 1).
// - choose_by_reference: the achievement scalarizing function of Wierzbicki (1980) for a
//   reference (aspiration) point z in objective units, augmented to avoid weakly optimal answers:
//     s(f) = max_i w_i (f^_i - z^_i) + rho sum_i w_i (f^_i - z^_i),   rho = 1e-6,
//   minimised over the front. Weights default to 1 (every objective alike in normalised units).
//   The answer is where the ray from z along (1/w_1, ..., 1/w_m) meets the front, whether z is
//   attainable or not.
// - high_trade_off_points: Rachmawati & Srinivasan (2009), as in pymoo's HighTradeoffPoints. For
//   each point i and each neighbour j (the points within a normalised distance of `radius`, and
//   at least the 2m nearest ones), leaving i for j sacrifices sum_k max(f^_jk - f^_ik, 0) and
//   gains sum_k max(f^_ik - f^_jk, 0); mu_i is the smallest sacrifice per unit gain over the
//   neighbours. A point is a high-trade-off point when mu_i >= mean + 2 sigma of all mu (the
//   standard deviation of the population); when none is, the largest mu if it is at least
//   mean + sigma; otherwise there is no such point (a front without a pronounced bulge).
//
// Example:
//   const pkmopt::ObjectiveSet front{{0.0, 1.0}, {0.2, 0.2}, {1.0, 0.0}};
//   std::size_t knee = pkmopt::knee_point(front);                         // 1
//   std::size_t near = pkmopt::choose_by_reference(front, {0.0, 0.5});    // 1
//   std::size_t cheap = pkmopt::choose_by_weights(front, {1.0, 0.0});     // 0
#pragma once

#include <cstddef>
#include <vector>

#include "optimizer/indicators.hpp"

namespace pkmopt {

/// The ideal and nadir points of a front, the frame of every rule here.
struct FrontScale {
  std::vector<double> ideal, nadir;
  /// f^ of one objective vector (see header comment).
  std::vector<double> normalised(const std::vector<double>& f) const;
};

FrontScale front_scale(const ObjectiveSet& front);

/// Index of the knee point (see header comment).
std::size_t knee_point(const ObjectiveSet& front);

/// Index of the point nearest the ideal point in normalised coordinates.
std::size_t compromise_point(const ObjectiveSet& front);

/// Pseudo-weight vector of every point (each sums to 1; a front of one point: 1/m each).
ObjectiveSet pseudo_weights(const ObjectiveSet& front);

/// Index of the point whose pseudo-weights are nearest `preference` (m values >= 0, not all 0;
/// scaled to sum 1). Throws std::invalid_argument otherwise.
std::size_t choose_by_weights(const ObjectiveSet& front, const std::vector<double>& preference);

/// Index of the point minimising the augmented achievement scalarizing function for the
/// reference point `reference` (objective units) and `weights` (m values > 0; empty: all 1).
/// Throws std::invalid_argument on wrong sizes or weights.
std::size_t choose_by_reference(const ObjectiveSet& front, const std::vector<double>& reference,
                                const std::vector<double>& weights = {});

/// The achievement s(f) of one objective vector (see header comment).
double achievement(const FrontScale& scale, const std::vector<double>& f,
                   const std::vector<double>& reference, const std::vector<double>& weights);

/// High-trade-off points and every point's trade-off mu (see header comment).
struct TradeOffs {
  std::vector<double> mu;           ///< per point; +inf when no neighbour offers a gain
  std::vector<std::size_t> points;  ///< the high-trade-off points, by decreasing mu
};
TradeOffs high_trade_off_points(const ObjectiveSet& front, double radius = 0.125);

}  // namespace pkmopt
