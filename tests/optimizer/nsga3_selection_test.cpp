// Tests of optimizer/nsga3_selection (Deb & Jain 2014, Algorithms 2-4): normalisation recovers
// the intercepts of a front on a known plane (shifted and scaled), falls back to the worst values
// when the extreme points are degenerate; association against a hand computation of the
// perpendicular distances; niching fills empty niches first with their nearest members, then
// at random, and is the same for the same seed.
#include "optimizer/nsga3_selection.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <set>
#include <stdexcept>

#include "optimizer/reference_directions.hpp"

namespace pkmopt {
namespace {

TEST(Nsga3Selection, NormalisationRecoversThePlanesIntercepts) {
  // Points z + a (.) u with u on the unit simplex: the plane's intercepts are a, the ideal z.
  const std::vector<double> z = {1.0, -2.0, 0.5}, a = {2.0, 0.5, 10.0};
  std::vector<std::vector<double>> f;
  for (const std::vector<double>& u : das_dennis_directions(3, 5)) {
    std::vector<double> v(3);
    for (std::size_t j = 0; j < 3; ++j) v[j] = z[j] + a[j] * u[j];
    f.push_back(v);
  }
  const Normalization n = normalize_objectives(f);
  EXPECT_TRUE(n.from_hyperplane);
  for (std::size_t j = 0; j < 3; ++j) {
    EXPECT_NEAR(n.ideal[j], z[j], 1e-15);
    EXPECT_NEAR(n.intercepts[j], a[j], 1e-12 * a[j]);
  }
  // Normalised, the points lie on the unit simplex.
  for (const std::vector<double>& v : normalized(n, f)) {
    double sum = 0.0;
    for (double x : v) sum += x;
    EXPECT_NEAR(sum, 1.0, 1e-12);
  }
}

TEST(Nsga3Selection, TheMemoryKeepsTheIdealAndTheExtremesOfEarlierGenerations) {
  const std::vector<double> a = {2.0, 0.5, 10.0};
  std::vector<std::vector<double>> first, interior;
  for (const std::vector<double>& u : das_dennis_directions(3, 4)) {
    std::vector<double> v(3);
    for (std::size_t j = 0; j < 3; ++j) v[j] = a[j] * u[j];
    first.push_back(v);
    if (std::all_of(u.begin(), u.end(), [](double x) { return x > 0.0; })) interior.push_back(v);
  }
  NormalizationMemory memory;
  (void)normalize_objectives(first, &memory);
  EXPECT_EQ(memory.ideal, (std::vector<double>{0.0, 0.0, 0.0}));
  ASSERT_EQ(memory.extremes.size(), 3u);
  // The interior points alone have another ideal point and other extremes; remembered, the first
  // generation's plane stays.
  const Normalization alone = normalize_objectives(interior);
  EXPECT_GT(alone.ideal[0], 0.0);
  const Normalization remembered = normalize_objectives(interior, &memory);
  for (std::size_t j = 0; j < 3; ++j) {
    EXPECT_EQ(remembered.ideal[j], 0.0);
    EXPECT_NEAR(remembered.intercepts[j], a[j], 1e-12 * a[j]);
  }
}

TEST(Nsga3Selection, DegenerateExtremesFallBackToTheWorstValues) {
  // Every point on one line: the three extreme points are not independent.
  std::vector<std::vector<double>> f;
  for (int k = 0; k <= 4; ++k) f.push_back({1.0 + k, 5.0 - k, 3.0});
  const Normalization n = normalize_objectives(f);
  EXPECT_FALSE(n.from_hyperplane);
  EXPECT_EQ(n.ideal, (std::vector<double>{1.0, 1.0, 3.0}));
  EXPECT_EQ(n.intercepts, (std::vector<double>{4.0, 4.0, 1.0}));  // objective 3 is constant
  EXPECT_THROW(normalize_objectives({}), std::invalid_argument);
}

TEST(Nsga3Selection, AssociationIsTheNearestLine) {
  const std::vector<std::vector<double>> w = {{1, 0}, {0.5, 0.5}, {0, 1}};
  const std::vector<std::vector<double>> points = {{0.9, 0.1}, {0.3, 0.35}, {0.0, 2.0}};
  const std::vector<Association> a = associate(points, w);
  EXPECT_EQ(a[0].direction, 0u);
  EXPECT_NEAR(a[0].distance, 0.1, 1e-15);
  EXPECT_EQ(a[1].direction, 1u);  // distance |(0.3, 0.35) - 0.325 (1, 1)| = 0.025 sqrt 2
  EXPECT_NEAR(a[1].distance, 0.025 * std::sqrt(2.0), 1e-15);
  EXPECT_EQ(a[2].direction, 2u);
  EXPECT_EQ(a[2].distance, 0.0);
}

TEST(Nsga3Selection, NichingFillsEmptyNichesWithTheirNearestMembersFirst) {
  // Direction 0 holds one selected member already; 1 and 2 none.
  const std::vector<Association> last = {{0, 0.1}, {1, 0.3}, {1, 0.1}, {2, 0.2}};
  for (std::uint64_t seed = 1; seed <= 20; ++seed) {
    Random rng(seed);
    std::vector<std::size_t> rho = {1, 0, 0};
    std::vector<std::size_t> two = niche_select(2, rho, last, rng);
    std::sort(two.begin(), two.end());
    EXPECT_EQ(two, (std::vector<std::size_t>{2, 3})) << seed;  // the nearest of niche 1, niche 2
    EXPECT_EQ(rho, (std::vector<std::size_t>{1, 1, 1}));
    // A third: every niche has one; niche 2 has no member left; so 0 or 1.
    std::vector<std::size_t> rho3 = {1, 0, 0};
    Random again(seed);
    const std::vector<std::size_t> three = niche_select(3, rho3, last, again);
    ASSERT_EQ(three.size(), 3u);
    EXPECT_TRUE(three[2] == 0 || three[2] == 1) << seed;
  }
  // More places than members: all of them; the same seed gives the same order.
  std::vector<std::size_t> rho_a = {0, 0, 0}, rho_b = {0, 0, 0};
  Random a(7), b(7);
  const auto all_a = niche_select(9, rho_a, last, a);
  const auto all_b = niche_select(9, rho_b, last, b);
  EXPECT_EQ(all_a, all_b);
  EXPECT_EQ(std::set<std::size_t>(all_a.begin(), all_a.end()).size(), 4u);
}

}  // namespace
}  // namespace pkmopt
