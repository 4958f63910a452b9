// Tests of optimizer/decision: each rule on hand-made fronts whose answer is known, and the
// answers' independence of the objectives' units.
#include "optimizer/decision.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <vector>

#include "optimizer/archive.hpp"
#include "optimizer/random.hpp"

namespace pkmopt {
namespace {

// The line f_1 + f_2 = 1 at f_1 = 0, 0.1, ..., 1 (index k is f_1 = k / 10).
ObjectiveSet line_front() {
  ObjectiveSet front;
  for (int k = 0; k <= 10; ++k) front.push_back({0.1 * k, 1.0 - 0.1 * k});
  return front;
}

TEST(KneeAndWeights, TwoObjectives) {
  // Extremes (0, 1) and (1, 0); (0.2, 0.2) is farthest from the line joining them.
  const ObjectiveSet front{{0.0, 1.0}, {0.5, 0.45}, {0.2, 0.2}, {1.0, 0.0}};
  EXPECT_EQ(knee_point(front), 2u);
  const ObjectiveSet weights = pseudo_weights(front);
  EXPECT_NEAR(weights[0][0], 1.0, 1e-12);  // best in f_1: all weight on f_1
  EXPECT_NEAR(weights[3][1], 1.0, 1e-12);
  EXPECT_NEAR(weights[2][0], 0.5, 1e-12);
  // (0.5, 0.45): (1 - 0.5, 1 - 0.45) / 1.05.
  EXPECT_NEAR(weights[1][0], 0.5 / 1.05, 1e-12);
  for (const auto& w : weights) EXPECT_NEAR(w[0] + w[1], 1.0, 1e-12);
  EXPECT_EQ(choose_by_weights(front, {1.0, 0.0}), 0u);
  EXPECT_EQ(choose_by_weights(front, {0.0, 1.0}), 3u);
  EXPECT_EQ(choose_by_weights(front, {3.0, 3.0}), 2u);  // scaled to (0.5, 0.5)
  EXPECT_THROW(choose_by_weights(front, {-1.0, 2.0}), std::invalid_argument);
  EXPECT_THROW(choose_by_weights(front, {0.0, 0.0}), std::invalid_argument);
  EXPECT_THROW(choose_by_weights(front, {1.0}), std::invalid_argument);
}

TEST(PseudoWeights, ThreeObjectivesByHand) {
  // Ideal (0, 0, 0), nadir (1, 2, 4): (0.5, 1, 1) is f^ = (0.5, 0.5, 0.25), so the weights are
  // (0.5, 0.5, 0.75) / 1.75.
  const ObjectiveSet front{{0.0, 2.0, 4.0}, {1.0, 0.0, 4.0}, {1.0, 2.0, 0.0}, {0.5, 1.0, 1.0}};
  const std::vector<double> w = pseudo_weights(front)[3];
  EXPECT_NEAR(w[0], 0.5 / 1.75, 1e-12);
  EXPECT_NEAR(w[1], 0.5 / 1.75, 1e-12);
  EXPECT_NEAR(w[2], 0.75 / 1.75, 1e-12);
  EXPECT_EQ(choose_by_weights(front, {0.0, 0.0, 1.0}), 2u);
}

TEST(Compromise, NearestTheIdealOnAQuarterCircle) {
  // f = (1 - cos t, 1 - sin t), t = 0, 5, ..., 90 degrees: ideal (0, 0), nadir (1, 1); the
  // point nearest the ideal is t = 45 degrees (index 9).
  ObjectiveSet front;
  for (int k = 0; k <= 18; ++k) {
    const double t = k * 5.0 * std::numbers::pi / 180.0;
    front.push_back({1.0 - std::cos(t), 1.0 - std::sin(t)});
  }
  EXPECT_EQ(compromise_point(front), 9u);
  // Add (3, 0): now ideal (0, 0), nadir (3, 1), so f^_1 shrinks threefold and a step in f_1
  // costs less: the nearest point moves to larger t.
  front.push_back({3.0, 0.0});
  const std::size_t k = compromise_point(front);
  EXPECT_GT(k, 9u);
  // By hand: minimise ((1 - cos t) / 3)^2 + (1 - sin t)^2 over the grid.
  std::size_t best = 0;
  double best_value = 1e300;
  for (std::size_t j = 0; j + 1 < front.size(); ++j) {
    const double v = std::pow(front[j][0] / 3.0, 2) + std::pow(front[j][1], 2);
    if (v < best_value) {
      best_value = v;
      best = j;
    }
  }
  EXPECT_EQ(k, best);
}

TEST(AchievementScalarizing, TheRayFromTheReferenceMeetsTheFront) {
  const ObjectiveSet front = line_front();
  // Unattainable (0.3, 0.3): the ray along (1, 1) meets the line at (0.5, 0.5).
  EXPECT_EQ(choose_by_reference(front, {0.3, 0.3}), 5u);
  // (0.1, 0.5) + s (1, 1) on the line at s = 0.2: (0.3, 0.7).
  EXPECT_EQ(choose_by_reference(front, {0.1, 0.5}), 3u);
  // Attainable and beyond the front, (0.9, 0.9): back along the ray to (0.5, 0.5).
  EXPECT_EQ(choose_by_reference(front, {0.9, 0.9}), 5u);
  // Weights (1, 2): the ray runs along (1, 1/2) and meets the line at f_1 = 0.5667; on the grid
  // s = max(f_1 - 0.3, 2 (f_2 - 0.3)) is 0.3 at f_1 = 0.6 and 0.4 at f_1 = 0.5.
  EXPECT_EQ(choose_by_reference(front, {0.3, 0.3}, {1.0, 2.0}), 6u);
  // The achievement by hand: f^ = f here.
  const FrontScale scale = front_scale(front);
  EXPECT_NEAR(achievement(scale, {0.6, 0.4}, {0.3, 0.3}, {1.0, 2.0}), 0.3 + 1e-6 * 0.5, 1e-15);
  EXPECT_THROW(choose_by_reference(front, {0.3}), std::invalid_argument);
  EXPECT_THROW(choose_by_reference(front, {0.3, 0.3}, {1.0, 0.0}), std::invalid_argument);
  EXPECT_THROW(choose_by_reference(front, {NAN, 0.3}), std::invalid_argument);
}

TEST(AchievementScalarizing, TheAugmentationPrefersTheParetoOptimalOfATie) {
  // For z = (0, 0.5) the max term of (0.2, 0.6) and of (0.2, 0.5) is 0.2 alike; the first is
  // weakly optimal only (the second dominates it) and must not be chosen.
  const ObjectiveSet set{{0.2, 0.6}, {0.2, 0.5}, {0.0, 1.0}, {1.0, 0.0}};
  EXPECT_EQ(choose_by_reference(set, {0.0, 0.5}), 1u);
}

TEST(HighTradeOff, TheCornerOfTwoBranches) {
  // A steep branch (t, 1 - 9t), t in [0, 0.1], and a flat one (0.1 + s, 0.1 - s/9), s in
  // [0, 0.9]. Leaving the corner (0.1, 0.1) costs 9 units per unit gained either way; leaving
  // any other point costs 1/9 of a unit one way.
  ObjectiveSet front;
  for (int k = 0; k <= 10; ++k) front.push_back({0.01 * k, 1.0 - 0.09 * k});
  for (int k = 1; k <= 10; ++k) front.push_back({0.1 + 0.09 * k, 0.1 - 0.01 * k});
  const TradeOffs t = high_trade_off_points(front);
  ASSERT_EQ(t.points.size(), 1u);
  EXPECT_EQ(t.points[0], 10u);
  EXPECT_NEAR(t.mu[10], 9.0, 1e-9);
  for (std::size_t i = 0; i < front.size(); ++i) {
    if (i == 10) continue;
    EXPECT_NEAR(t.mu[i], 1.0 / 9.0, 1e-9) << i;
  }
  EXPECT_EQ(knee_point(front), 10u);
}

TEST(HighTradeOff, AStraightFrontHasNone) {
  const TradeOffs t = high_trade_off_points(line_front());
  for (double mu : t.mu) EXPECT_NEAR(mu, 1.0, 1e-12);
  EXPECT_TRUE(t.points.empty());
  // One point: no neighbour, no trade-off.
  const TradeOffs single = high_trade_off_points({{1.0, 2.0}});
  EXPECT_TRUE(std::isinf(single.mu[0]));
  EXPECT_TRUE(single.points.empty());
}

TEST(HighTradeOff, AgreesWithABruteForceOnRandomFronts) {
  // An independent reading of the definition: all pairs, neighbourhoods by explicit count.
  Random rng(7);
  ObjectiveSet cloud;
  for (int k = 0; k < 300; ++k) {
    const double a = rng.uniform(0.0, 1.0), b = rng.uniform(0.0, 1.0);
    const double c = 1.0 - a - b < 0.0 ? 0.0 : 1.0 - a - b;
    cloud.push_back({a, b, c + 0.3 * rng.uniform(0.0, 1.0)});
  }
  ObjectiveSet front;
  for (std::size_t i : non_dominated_indices(cloud)) front.push_back(cloud[i]);
  ASSERT_GT(front.size(), 20u);
  const TradeOffs t = high_trade_off_points(front, 0.2);
  const FrontScale scale = front_scale(front);
  for (std::size_t i = 0; i < front.size(); ++i) {
    const std::vector<double> fi = scale.normalised(front[i]);
    std::vector<double> distances;
    for (std::size_t j = 0; j < front.size(); ++j) {
      if (j == i) continue;
      const std::vector<double> fj = scale.normalised(front[j]);
      distances.push_back(std::hypot(fj[0] - fi[0], fj[1] - fi[1], fj[2] - fi[2]));
    }
    std::vector<double> sorted = distances;
    std::sort(sorted.begin(), sorted.end());
    const double cut = std::max(0.2, sorted[5]);  // at least the 2m = 6 nearest
    double mu = INFINITY;
    for (std::size_t j = 0, q = 0; j < front.size(); ++j) {
      if (j == i) continue;
      if (distances[q++] > cut) continue;
      const std::vector<double> fj = scale.normalised(front[j]);
      double sacrifice = 0.0, gain = 0.0;
      for (int k = 0; k < 3; ++k) {
        sacrifice += std::max(fj[k] - fi[k], 0.0);
        gain += std::max(fi[k] - fj[k], 0.0);
      }
      if (gain > 0.0) mu = std::min(mu, sacrifice / gain);
    }
    EXPECT_NEAR(t.mu[i], mu, 1e-12) << i;
  }
}

TEST(Decision, EveryRuleIgnoresTheObjectivesUnits) {
  Random rng(11);
  ObjectiveSet cloud;
  for (int k = 0; k < 200; ++k) {
    const double a = rng.uniform(0.0, 1.0), b = rng.uniform(0.0, 1.0);
    cloud.push_back(
        {a, b, std::sqrt(std::max(0.0, 1.5 - a * a - b * b)) + 0.2 * rng.uniform(0.0, 1.0)});
  }
  ObjectiveSet front;
  for (std::size_t i : non_dominated_indices(cloud)) front.push_back(cloud[i]);
  const std::vector<double> scale{1e3, 1e-6, 5.0}, shift{-2.0, 7.0, 0.5};
  ObjectiveSet units = front;
  for (auto& p : units)
    for (int i = 0; i < 3; ++i) p[i] = scale[i] * p[i] + shift[i];
  const std::vector<double> z{0.2, 0.2, 0.2};
  std::vector<double> z_units(3);
  for (int i = 0; i < 3; ++i) z_units[i] = scale[i] * z[i] + shift[i];
  EXPECT_EQ(knee_point(front), knee_point(units));
  EXPECT_EQ(compromise_point(front), compromise_point(units));
  EXPECT_EQ(choose_by_weights(front, {0.2, 0.5, 0.3}), choose_by_weights(units, {0.2, 0.5, 0.3}));
  EXPECT_EQ(choose_by_reference(front, z), choose_by_reference(units, z_units));
  EXPECT_EQ(high_trade_off_points(front).points, high_trade_off_points(units).points);
}

}  // namespace
}  // namespace pkmopt
