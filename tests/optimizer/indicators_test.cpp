// Tests of optimizer/indicators: exact hypervolume against brute force, IGD+, spacing.
#include "optimizer/indicators.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include "optimizer/random.hpp"

namespace pkmopt {
namespace {

// Brute force: the union of boxes [p, r] measured on the grid of all point coordinates.
double grid_hypervolume(const ObjectiveSet& points, const std::vector<double>& reference) {
  const std::size_t m = reference.size();
  std::vector<std::vector<double>> axes(m);
  for (std::size_t i = 0; i < m; ++i) {
    axes[i].push_back(reference[i]);
    for (const auto& p : points)
      if (p[i] < reference[i]) axes[i].push_back(p[i]);
    std::sort(axes[i].begin(), axes[i].end());
    axes[i].erase(std::unique(axes[i].begin(), axes[i].end()), axes[i].end());
  }
  std::vector<std::size_t> cell(m, 0);
  double volume = 0.0;
  while (true) {
    bool empty_axis = false;
    for (std::size_t i = 0; i < m; ++i) empty_axis = empty_axis || axes[i].size() < 2;
    if (empty_axis) return 0.0;
    double cell_volume = 1.0;
    std::vector<double> corner(m);
    for (std::size_t i = 0; i < m; ++i) {
      corner[i] = axes[i][cell[i]];
      cell_volume *= axes[i][cell[i] + 1] - axes[i][cell[i]];
    }
    const bool covered = std::any_of(points.begin(), points.end(), [&](const auto& p) {
      for (std::size_t i = 0; i < m; ++i)
        if (!(p[i] <= corner[i])) return false;
      return true;
    });
    if (covered) volume += cell_volume;
    std::size_t axis = 0;
    while (axis < m && ++cell[axis] + 1 == axes[axis].size()) cell[axis++] = 0;
    if (axis == m) break;
  }
  return volume;
}

ObjectiveSet random_set(Random& rng, std::size_t n, std::size_t m, bool on_sphere) {
  ObjectiveSet points(n, std::vector<double>(m));
  for (auto& p : points) {
    double norm = 0.0;
    for (double& v : p) {
      v = rng.uniform01();
      norm += v * v;
    }
    if (on_sphere)
      for (double& v : p) v /= std::sqrt(norm);  // mutually non-dominated, like a front
  }
  return points;
}

TEST(Hypervolume, KnownValues) {
  EXPECT_DOUBLE_EQ(hypervolume({{0.0, 1.0}, {0.5, 0.5}, {1.0, 0.0}}, {1.0, 1.0}), 0.25);
  EXPECT_DOUBLE_EQ(hypervolume({{0.5, 0.5, 0.5}}, {1.0, 1.0, 1.0}), 0.125);
  EXPECT_DOUBLE_EQ(hypervolume({{0.5, 0.5, 0.5, 0.5}}, {1.0, 1.0, 1.0, 1.0}), 0.0625);
  EXPECT_DOUBLE_EQ(hypervolume({{2.0, 0.0}}, {1.0, 1.0}), 0.0);  // outside the box
  EXPECT_DOUBLE_EQ(hypervolume({}, {1.0, 1.0}), 0.0);
  EXPECT_DOUBLE_EQ(hypervolume({{0.25}, {0.5}}, {1.0}), 0.75);
}

TEST(Hypervolume, MatchesBruteForceOnRandomSets) {
  Random rng(2024);
  for (std::size_t m = 2; m <= 5; ++m) {
    const std::size_t n = m <= 3 ? 40 : (m == 4 ? 15 : 8);
    const std::vector<double> reference(m, 1.1);
    for (int trial = 0; trial < 10; ++trial) {
      const ObjectiveSet points = random_set(rng, n, m, trial % 2 == 0);
      const double exact = grid_hypervolume(points, reference);
      EXPECT_NEAR(hypervolume(points, reference), exact, 1e-12 * std::max(1.0, exact))
          << "m = " << m << ", trial " << trial;
    }
  }
}

TEST(Hypervolume, ThreeDimensionalWithTies) {
  // Repeated coordinates exercise equal keys in the 3-D sweep.
  Random rng(9);
  for (int trial = 0; trial < 20; ++trial) {
    ObjectiveSet points(30, std::vector<double>(3));
    for (auto& p : points)
      for (double& v : p) v = 0.25 * static_cast<double>(rng.below(4));
    const std::vector<double> reference{1.0, 1.0, 1.0};
    EXPECT_NEAR(hypervolume(points, reference), grid_hypervolume(points, reference), 1e-12);
  }
}

// Independent 3-D reference for larger sets: slices between consecutive distinct f_3 values,
// each slice's area the 2-D hypervolume (staircase of sorted points) of the points below it.
double sliced_hypervolume_3d(const ObjectiveSet& points, const std::vector<double>& reference) {
  std::vector<double> levels{reference[2]};
  for (const auto& p : points)
    if (p[2] < reference[2]) levels.push_back(p[2]);
  std::sort(levels.begin(), levels.end());
  levels.erase(std::unique(levels.begin(), levels.end()), levels.end());
  double volume = 0.0;
  for (std::size_t k = 0; k + 1 < levels.size(); ++k) {
    std::vector<std::pair<double, double>> below;
    for (const auto& p : points)
      if (p[2] <= levels[k] && p[0] < reference[0] && p[1] < reference[1])
        below.emplace_back(p[0], p[1]);
    std::sort(below.begin(), below.end());
    double area = 0.0, lowest = reference[1];
    for (const auto& [x, y] : below)
      if (y < lowest) {
        area += (reference[0] - x) * (lowest - y);
        lowest = y;
      }
    volume += area * (levels[k + 1] - levels[k]);
  }
  return volume;
}

// A 3-D set mixing a front (points on the unit sphere), dominated points, exact duplicates,
// points on the reference boundary (add nothing) and beyond it, and values on a coarse grid
// (ties in every coordinate).
ObjectiveSet awkward_set_3d(Random& rng, std::size_t n) {
  ObjectiveSet points = random_set(rng, n, 3, true);
  for (std::size_t k = 0; k < n; ++k) {
    auto& p = points[k];
    switch (rng.below(6)) {
      case 0:  // dominated: pushed away from the ideal point
        for (double& v : p) v += 0.2 * rng.uniform01();
        break;
      case 1:  // duplicate of an earlier point
        if (k > 0) p = points[rng.below(k)];
        break;
      case 2:  // one coordinate exactly on the reference boundary, or beyond it
        p[rng.below(3)] = rng.bernoulli(0.5) ? 1.0 : 1.5;
        break;
      case 3:  // snapped to a grid of quarters
        for (double& v : p) v = 0.25 * std::floor(4.0 * v);
        break;
      default:
        break;
    }
  }
  return points;
}

TEST(Hypervolume, ThreeDimensionalSweepOnAwkwardSets) {
  Random rng(31);
  const std::vector<double> reference{1.0, 1.0, 1.0};
  for (int trial = 0; trial < 20; ++trial) {
    const ObjectiveSet points = awkward_set_3d(rng, 40);
    const double exact = grid_hypervolume(points, reference);
    EXPECT_NEAR(hypervolume(points, reference), exact, 1e-12) << "trial " << trial;
    EXPECT_NEAR(sliced_hypervolume_3d(points, reference), exact, 1e-12) << "trial " << trial;
  }
  for (int trial = 0; trial < 3; ++trial) {
    const ObjectiveSet points = awkward_set_3d(rng, 1000);
    const double sliced = sliced_hypervolume_3d(points, reference);
    EXPECT_NEAR(hypervolume(points, reference), sliced, 1e-12) << "trial " << trial;
    // The order of the input does not matter.
    ObjectiveSet reversed(points.rbegin(), points.rend());
    EXPECT_NEAR(hypervolume(reversed, reference), sliced, 1e-12);
  }
}

TEST(Hypervolume, ThreeDimensionalAgreesWithWfgSlicing) {
  // Lifting a 3-D set to 4-D with f_4 = 0 and r_4 = 1 gives the same volume through WFG's
  // slicing (which filters dominated points before recursing).
  Random rng(77);
  const std::vector<double> reference{1.0, 1.0, 1.0};
  for (int trial = 0; trial < 5; ++trial) {
    const ObjectiveSet points = awkward_set_3d(rng, 60);
    ObjectiveSet lifted;
    for (const auto& p : points) lifted.push_back({p[0], p[1], p[2], 0.0});
    EXPECT_NEAR(hypervolume(points, reference), hypervolume(lifted, {1.0, 1.0, 1.0, 1.0}), 1e-12);
  }
}

TEST(Hypervolume, TwoDimensionalWithDominatedAndDuplicates) {
  Random rng(5);
  const std::vector<double> reference{1.0, 1.0};
  for (int trial = 0; trial < 20; ++trial) {
    ObjectiveSet points = random_set(rng, 30, 2, true);
    points.push_back(points[3]);                           // duplicate
    points.push_back({points[4][0] + 0.1, points[4][1]});  // dominated
    points.push_back({1.0, 0.0});                          // on the boundary
    points.push_back({0.25 * std::floor(4.0 * points[5][0]), 0.75});
    EXPECT_NEAR(hypervolume(points, reference), grid_hypervolume(points, reference), 1e-12);
  }
}

TEST(IgdPlus, KnownValues) {
  const ObjectiveSet reference{{0.0, 1.0}, {1.0, 0.0}};
  EXPECT_DOUBLE_EQ(igd_plus(reference, reference), 0.0);
  // A point dominating the reference costs nothing; a point behind costs its excess only.
  EXPECT_DOUBLE_EQ(igd_plus({{-1.0, -1.0}}, reference), 0.0);
  EXPECT_DOUBLE_EQ(igd_plus({{0.0, 1.5}}, {{0.0, 1.0}}), 0.5);
  // For z = (1, 0) and a = (0, 1.5): d+ = sqrt(0 + 1.5^2).
  EXPECT_DOUBLE_EQ(igd_plus({{0.0, 1.5}}, reference), (0.5 + 1.5) / 2.0);
}

TEST(Spacing, EvenFrontHasZeroSpacing) {
  ObjectiveSet even;
  for (int k = 0; k <= 10; ++k) even.push_back({0.1 * k, 1.0 - 0.1 * k});
  EXPECT_NEAR(spacing(even), 0.0, 1e-12);
  // Nearest L1 distances 1, 1, 3 (points 0, 1, 4): mean 5/3, sample deviation sqrt(4/3).
  EXPECT_NEAR(spacing({{0.0, 0.0}, {1.0, 0.0}, {4.0, 0.0}}), std::sqrt(4.0 / 3.0), 1e-12);
}

TEST(ReferencePoint, NadirPlusMargin) {
  const std::vector<double> r = reference_point_from({{0.0, 2.0}, {1.0, 0.0}}, 0.1);
  EXPECT_DOUBLE_EQ(r[0], 1.1);
  EXPECT_DOUBLE_EQ(r[1], 2.2);
}

}  // namespace
}  // namespace pkmopt
