// Tests of optimizer/reference_directions: the Das–Dennis counts C(H+M-1, M-1) and the two-layer
// sizes Deb & Jain 2014 tabulate (91, 210, 156, 275, 135), every direction on the unit simplex
// with components k/H, no direction twice, the vertices present, neighbours sqrt(2)/H apart, the
// inside layer strictly inside, and the refusals.
#include "optimizer/reference_directions.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>
#include <stdexcept>

namespace pkmopt {
namespace {

void expect_on_simplex(const std::vector<std::vector<double>>& w, std::size_t m) {
  for (const std::vector<double>& v : w) {
    ASSERT_EQ(v.size(), m);
    double sum = 0.0;
    for (double x : v) {
      EXPECT_GE(x, 0.0);
      sum += x;
    }
    EXPECT_NEAR(sum, 1.0, 1e-12);
  }
}

TEST(ReferenceDirections, DasDennisCountsAndTheSimplexLattice) {
  EXPECT_EQ(das_dennis_count(3, 12), 91u);
  EXPECT_EQ(das_dennis_count(5, 6), 210u);
  EXPECT_EQ(das_dennis_count(8, 3), 120u);
  EXPECT_EQ(das_dennis_count(2, 99), 100u);
  for (const auto& [m, h] : {std::pair<std::size_t, std::size_t>{3, 12}, {5, 6}, {4, 1}, {2, 7}}) {
    const auto w = das_dennis_directions(m, h);
    ASSERT_EQ(w.size(), das_dennis_count(m, h));
    expect_on_simplex(w, m);
    // Components are k/H; the integer vectors are all distinct.
    std::set<std::vector<long>> seen;
    for (const auto& v : w) {
      std::vector<long> k;
      for (double x : v) {
        const double scaled = x * static_cast<double>(h);
        EXPECT_NEAR(scaled, std::round(scaled), 1e-12);
        k.push_back(std::lround(scaled));
      }
      EXPECT_TRUE(seen.insert(k).second);
    }
    // The vertices are among them, the first is e_1.
    EXPECT_EQ(w.front()[0], 1.0);
    for (std::size_t i = 0; i < m; ++i)
      EXPECT_TRUE(std::any_of(w.begin(), w.end(), [&](const auto& v) { return v[i] == 1.0; }));
    // Nearest neighbours sqrt(2)/H apart.
    double closest = std::numeric_limits<double>::infinity();
    for (std::size_t a = 0; a < w.size(); ++a)
      for (std::size_t b = a + 1; b < w.size(); ++b) {
        double d = 0.0;
        for (std::size_t i = 0; i < m; ++i) d += (w[a][i] - w[b][i]) * (w[a][i] - w[b][i]);
        closest = std::min(closest, std::sqrt(d));
      }
    EXPECT_NEAR(closest, std::sqrt(2.0) / static_cast<double>(h), 1e-12);
  }
}

TEST(ReferenceDirections, TwoLayersOfDebAndJain) {
  EXPECT_EQ(two_layer_directions(8, 3, 2).size(), 156u);
  EXPECT_EQ(two_layer_directions(10, 3, 2).size(), 275u);
  EXPECT_EQ(two_layer_directions(15, 2, 1).size(), 135u);
  const auto w = two_layer_directions(8, 3, 2);
  expect_on_simplex(w, 8);
  // The inside layer (after the 120 boundary ones) keeps every component >= (1 - 1/2)/8 > 0.
  for (std::size_t k = 120; k < w.size(); ++k)
    for (double x : w[k]) EXPECT_GE(x, 0.5 / 8.0 - 1e-15);
  // A boundary direction of H = 3 in 8 objectives has at least five zero components.
  for (std::size_t k = 0; k < 120; ++k) EXPECT_GE(std::count(w[k].begin(), w[k].end(), 0.0), 5);
  EXPECT_EQ(two_layer_directions(3, 4, 0).size(), 15u);
}

TEST(ReferenceDirections, Refusals) {
  EXPECT_THROW(das_dennis_directions(3, 0), std::invalid_argument);
  EXPECT_THROW(das_dennis_count(0, 3), std::invalid_argument);
  EXPECT_THROW(das_dennis_count(20, 40), std::invalid_argument);  // C(59, 19), about 5e15
}

}  // namespace
}  // namespace pkmopt
