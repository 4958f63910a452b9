#include "optimizer/front_thinning.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

#include "optimizer/archive.hpp"

namespace pkmopt {
namespace {

using Points = std::vector<std::vector<double>>;

// The rule of front_thinning.hpp written out the slow way: every step recomputes every distance.
std::vector<std::size_t> reference_thinning(const Points& points, std::size_t size) {
  const std::size_t n = points.size(), m = points.front().size();
  std::vector<double> lo(m), hi(m);
  for (std::size_t i = 0; i < m; ++i) {
    lo[i] = hi[i] = points[0][i];
    for (const auto& p : points) {
      lo[i] = std::min(lo[i], p[i]);
      hi[i] = std::max(hi[i], p[i]);
    }
  }
  auto dist = [&](std::size_t a, std::size_t b) {
    double s = 0;
    for (std::size_t i = 0; i < m; ++i) {
      const double r = hi[i] > lo[i] ? hi[i] - lo[i] : 1.0;
      const double d = (points[a][i] - points[b][i]) / r;
      s += d * d;
    }
    return std::sqrt(s);
  };
  std::vector<bool> keep_always(n, false);
  std::size_t kept = 0;
  for (std::size_t i = 0; i < m && kept < size; ++i) {
    const auto it = std::min_element(points.begin(), points.end(),
                                     [i](const auto& a, const auto& b) { return a[i] < b[i]; });
    const auto k = static_cast<std::size_t>(it - points.begin());
    if (!keep_always[k]) ++kept;
    keep_always[k] = true;
  }
  std::vector<std::size_t> alive(n);
  for (std::size_t k = 0; k < n; ++k) alive[k] = k;
  while (alive.size() > size) {
    double best1 = 0, best2 = 0;
    std::size_t victim = n;
    for (std::size_t a : alive) {
      if (keep_always[a]) continue;
      std::vector<double> d;
      for (std::size_t b : alive)
        if (b != a) d.push_back(dist(a, b));
      std::sort(d.begin(), d.end());
      d.push_back(std::numeric_limits<double>::infinity());
      d.push_back(std::numeric_limits<double>::infinity());
      if (victim == n || d[0] < best1 || (d[0] == best1 && d[1] <= best2)) {
        victim = a;
        best1 = d[0];
        best2 = d[1];
      }
    }
    std::erase(alive, victim);
  }
  return alive;
}

Points random_front(std::mt19937_64& rng, std::size_t n, std::size_t m) {
  // Points on the simplex sum f = 1 (mutually non-dominated), scaled per objective.
  std::uniform_real_distribution<double> u(0.0, 1.0);
  Points points;
  for (std::size_t k = 0; k < n; ++k) {
    std::vector<double> p(m);
    double s = 0;
    for (double& v : p) s += v = -std::log(1.0 - u(rng));
    for (std::size_t i = 0; i < m; ++i) p[i] = p[i] / s * std::pow(10.0, static_cast<double>(i));
    points.push_back(p);
  }
  return points;
}

TEST(FrontThinning, KeepsEverythingWhenSmallEnough) {
  const Points p = {{0, 1}, {1, 0}, {0.5, 0.5}};
  EXPECT_EQ(thin_front(p, 3), (std::vector<std::size_t>{0, 1, 2}));
  EXPECT_EQ(thin_front(p, 10), (std::vector<std::size_t>{0, 1, 2}));
  EXPECT_TRUE(thin_front({}, 4).empty());
  EXPECT_TRUE(thin_front(p, 0).empty());
}

TEST(FrontThinning, RemovesOneOfTwoClosePoints) {
  const Points p = {{0, 1}, {0.5, 0.5}, {0.51, 0.49}, {1, 0}};
  const std::vector<std::size_t> keep = thin_front(p, 3);
  ASSERT_EQ(keep.size(), 3u);
  EXPECT_EQ(keep.front(), 0u);  // the extremes stay
  EXPECT_EQ(keep.back(), 3u);
  // Both middle points are each other's nearest; the tie is broken by the second-nearest
  // distance: {0.51, 0.49} is nearer to {1, 0} than {0.5, 0.5} is to {0, 1}, so it goes.
  EXPECT_EQ(keep[1], 1u);
}

TEST(FrontThinning, ProtectsTheExtremesAndThinsTheCluster) {
  // Ten evenly spaced points and a cluster of ten around the middle: thinning to ten removes
  // the cluster (the evenly spaced points are 1/9 apart, the cluster points 1e-3).
  Points p;
  for (int k = 0; k < 10; ++k) p.push_back({k / 9.0, 1.0 - k / 9.0});
  for (int k = 0; k < 10; ++k) p.push_back({0.3 + 1e-3 * k, 0.7 - 1e-3 * k});
  const std::vector<std::size_t> keep = thin_front(p, 10);
  ASSERT_EQ(keep.size(), 10u);
  // The survivors are spread: no two closer than a quarter of the even spacing.
  for (std::size_t a = 0; a < keep.size(); ++a)
    for (std::size_t b = a + 1; b < keep.size(); ++b)
      EXPECT_GT(std::hypot(p[keep[a]][0] - p[keep[b]][0], p[keep[a]][1] - p[keep[b]][1]),
                0.25 / 9.0);
  EXPECT_EQ(keep.front(), 0u);
  EXPECT_NE(std::find(keep.begin(), keep.end(), 9u), keep.end());
}

TEST(FrontThinning, AgreesWithTheSlowReference) {
  std::mt19937_64 rng(20261206);
  for (std::size_t m : {2u, 3u, 5u}) {
    for (int trial = 0; trial < 6; ++trial) {
      const Points p = random_front(rng, 40 + 7 * static_cast<std::size_t>(trial), m);
      for (std::size_t size : {1u, 2u, 7u, 25u}) {
        const std::vector<std::size_t> keep = thin_front(p, size);
        EXPECT_EQ(keep, reference_thinning(p, size)) << "m " << m << " size " << size;
        EXPECT_EQ(keep.size(), size);
        EXPECT_TRUE(std::is_sorted(keep.begin(), keep.end()));
      }
    }
  }
}

TEST(FrontThinning, NeverKeepsADominatedPointAndIgnoresUnits) {
  std::mt19937_64 rng(7);
  const Points p = random_front(rng, 200, 3);
  // The input is non-dominated, so is every subset; the rule scales each objective by its
  // range, so a change of unit (here x 1e6 on the second objective) keeps the same points.
  ASSERT_EQ(non_dominated_indices(p).size(), p.size());
  Points scaled = p;
  for (auto& q : scaled) q[1] *= 1e6;
  const std::vector<std::size_t> keep = thin_front(p, 30);
  EXPECT_EQ(thin_front(scaled, 30), keep);
  Points kept;
  for (std::size_t k : keep) kept.push_back(p[k]);
  EXPECT_EQ(non_dominated_indices(kept).size(), kept.size());
}

TEST(FrontThinning, RefusesPointsOfDifferentLengths) {
  EXPECT_THROW(thin_front({{0, 1}, {1}}, 1), std::invalid_argument);
}

}  // namespace
}  // namespace pkmopt
