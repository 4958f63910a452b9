// Tests of optimizer/aspiration_directions: the local sets sum to 1, are centred on the
// aspiration point's diagonal projection and as wide as `spread` says; clipping at the simplex's
// border; the axis directions last; the default divisions; refusals.
#include "optimizer/aspiration_directions.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <vector>

#include "optimizer/reference_directions.hpp"

namespace pkmopt {
namespace {

TEST(AspirationDirections, ALocalSetAroundTheProjection) {
  // z^ = (0.1, 0.2, 0.4): sum 0.7, so p = z^ + 0.1 (1, 1, 1) = (0.2, 0.3, 0.5).
  const auto w = aspiration_directions({{0.1, 0.2, 0.4}}, 4, 0.1);
  ASSERT_EQ(w.size(), 15u + 3u);
  std::vector<double> centroid(3, 0.0);
  for (std::size_t k = 0; k < 15; ++k) {
    double sum = 0.0;
    for (int i = 0; i < 3; ++i) {
      sum += w[k][i];
      centroid[i] += w[k][i] / 15.0;
      EXPECT_GE(w[k][i], 0.0);
    }
    EXPECT_NEAR(sum, 1.0, 1e-12);
  }
  EXPECT_NEAR(centroid[0], 0.2, 1e-12);
  EXPECT_NEAR(centroid[1], 0.3, 1e-12);
  EXPECT_NEAR(centroid[2], 0.5, 1e-12);
  // The set's vertices are spread (1, 0, 0) etc. from the centroid's corner: (0.2 + 0.1 - 0.1/3,
  // 0.3 - 0.1/3, 0.5 - 0.1/3) is the first Das–Dennis direction (1, 0, 0) moved.
  EXPECT_NEAR(w[0][0], 0.2 + 0.1 - 0.1 / 3, 1e-12);
  EXPECT_NEAR(w[0][1], 0.3 - 0.1 / 3, 1e-12);
  // Neighbours are spread * sqrt(2) / H apart.
  const auto dd = das_dennis_directions(3, 4);
  EXPECT_NEAR(std::hypot(w[0][0] - w[1][0], w[0][1] - w[1][1], w[0][2] - w[1][2]),
              0.1 * std::hypot(dd[0][0] - dd[1][0], dd[0][1] - dd[1][1], dd[0][2] - dd[1][2]),
              1e-12);
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < 3; ++i) EXPECT_EQ(w[15 + j][i], i == j ? 1.0 : 0.0);
}

TEST(AspirationDirections, BeyondTheIdealAndAtTheBorder) {
  // z^ = (-1, -1): beyond the ideal point, on the diagonal: p = (0.5, 0.5).
  const auto w = aspiration_directions({{-1.0, -1.0}}, 2, 0.2);
  ASSERT_EQ(w.size(), 3u + 2u);
  EXPECT_NEAR(w[1][0], 0.5, 1e-12);  // the middle one of (1, 0), (0.5, 0.5), (0, 1)
  EXPECT_NEAR(w[0][0], 0.6, 1e-12);
  // z^ = (1, 0): p = (1, 0), half the local set falls outside and is clipped to the border.
  const auto edge = aspiration_directions({{1.0, 0.0}}, 2, 0.2);
  EXPECT_NEAR(edge[0][0], 1.0, 1e-12);  // (1.1, -0.1) clipped: (1, 0)
  EXPECT_NEAR(edge[1][0], 1.0, 1e-12);
  EXPECT_NEAR(edge[2][0], 0.9, 1e-12);
  EXPECT_NEAR(edge[2][1], 0.1, 1e-12);
  // Two aspiration points: two local sets, then the axes.
  EXPECT_EQ(aspiration_directions({{0.2, 0.8}, {0.7, 0.3}}, 2, 0.1).size(), 3u + 3u + 2u);
}

TEST(AspirationDirections, DefaultDivisionsAndRefusals) {
  EXPECT_EQ(default_aspiration_divisions(2), 29u);  // 30 directions
  EXPECT_EQ(default_aspiration_divisions(3), 6u);   // 28
  EXPECT_EQ(default_aspiration_divisions(4), 3u);   // 20 (H = 4 gives 35)
  EXPECT_EQ(default_aspiration_divisions(5), 2u);   // 15
  EXPECT_EQ(default_aspiration_divisions(8), 1u);   // 8
  EXPECT_THROW(aspiration_directions({}, 2, 0.1), std::invalid_argument);
  EXPECT_THROW(aspiration_directions({{0.1, 0.2}, {0.1}}, 2, 0.1), std::invalid_argument);
  EXPECT_THROW(aspiration_directions({{0.1, NAN}}, 2, 0.1), std::invalid_argument);
  EXPECT_THROW(aspiration_directions({{0.1, 0.2}}, 2, 0.0), std::invalid_argument);
  EXPECT_THROW(aspiration_directions({{0.1, 0.2}}, 0, 0.1), std::invalid_argument);
}

}  // namespace
}  // namespace pkmopt
