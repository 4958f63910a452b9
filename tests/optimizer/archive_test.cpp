// Tests of optimizer/archive: dominance, non-dominated filtering (against brute force), archive.
#include "optimizer/archive.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "optimizer/random.hpp"

namespace pkmopt {
namespace {

std::vector<std::size_t> brute_force_non_dominated(const std::vector<std::vector<double>>& points) {
  std::vector<std::size_t> kept;
  for (std::size_t a = 0; a < points.size(); ++a) {
    bool keep = true;
    for (std::size_t b = 0; b < points.size() && keep; ++b) {
      if (a == b) continue;
      if (dominates(points[b], points[a])) keep = false;
      if (b < a && points[b] == points[a]) keep = false;  // first duplicate wins
    }
    if (keep) kept.push_back(a);
  }
  return kept;
}

TEST(Dominance, Definition) {
  const std::vector<double> a{1, 2}, b{2, 2}, c{1, 2}, d{0, 3};
  EXPECT_TRUE(dominates(a, b));
  EXPECT_FALSE(dominates(b, a));
  EXPECT_FALSE(dominates(a, c));  // equal: no strict improvement
  EXPECT_FALSE(dominates(a, d));
  EXPECT_FALSE(dominates(d, a));
}

TEST(NonDominated, MatchesBruteForceInTwoToFourObjectives) {
  Random rng(21);
  for (std::size_t m = 2; m <= 4; ++m) {
    for (int trial = 0; trial < 20; ++trial) {
      std::vector<std::vector<double>> points(60, std::vector<double>(m));
      // Coarse values make ties and duplicates frequent.
      for (auto& p : points)
        for (double& v : p) v = static_cast<double>(rng.below(6));
      EXPECT_EQ(non_dominated_indices(points), brute_force_non_dominated(points)) << "m = " << m;
    }
  }
}

TEST(NonDominated, SkipsNaN) {
  const std::vector<std::vector<double>> points{{NAN, 0.0}, {1.0, 1.0}};
  EXPECT_EQ(non_dominated_indices(points), (std::vector<std::size_t>{1}));
}

TEST(ParetoArchive, InsertKeepsOnlyNonDominated) {
  ParetoArchive archive;
  EXPECT_TRUE(archive.insert({0.0}, {1.0, 3.0}));
  EXPECT_FALSE(archive.insert({1.0}, {2.0, 4.0}));  // dominated
  EXPECT_FALSE(archive.insert({2.0}, {1.0, 3.0}));  // duplicate
  EXPECT_TRUE(archive.insert({3.0}, {3.0, 1.0}));
  EXPECT_TRUE(archive.insert({4.0}, {0.5, 0.5}));  // dominates both
  ASSERT_EQ(archive.size(), 1u);
  EXPECT_EQ(archive.entries()[0].x, std::vector<double>{4.0});
}

TEST(ParetoArchive, InsertAllEqualsRepeatedInsert) {
  Random rng(4);
  std::vector<std::vector<double>> xs, fs;
  for (int k = 0; k < 200; ++k) {
    xs.push_back({static_cast<double>(k)});
    fs.push_back({rng.uniform01(), rng.uniform01(), rng.uniform01()});
  }
  ParetoArchive one_by_one, bulk;
  for (std::size_t k = 0; k < xs.size(); ++k) one_by_one.insert(xs[k], fs[k]);
  bulk.insert_all(xs, fs);
  one_by_one.sort();
  bulk.sort();
  EXPECT_EQ(one_by_one.objective_vectors(), bulk.objective_vectors());
  EXPECT_EQ(one_by_one.designs(), bulk.designs());
}

}  // namespace
}  // namespace pkmopt
