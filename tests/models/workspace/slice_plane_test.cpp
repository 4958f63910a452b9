// choose_slice_plane: the slice box, plane and pixel of a workspace, checked against values
// worked out by hand for a workspace whose boxes are set directly.
#include "models/workspace/slice_plane.hpp"

#include <gtest/gtest.h>

#include <stdexcept>

namespace {

using pkmopt::choose_slice_plane;
using pkmopt::SlicePlane;
using pkmopt::WorkspaceResult;

// Bounding box [0, 1] x [0, 2] x [0, 4] m; search box [-1, 2] x [-1, 3] x [-1, 5] m.
WorkspaceResult boxes() {
  WorkspaceResult ws;
  ws.bounding_box = Eigen::AlignedBox3d(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 2, 4));
  ws.search_box = Eigen::AlignedBox3d(Eigen::Vector3d(-1, -1, -1), Eigen::Vector3d(2, 3, 5));
  return ws;
}

TEST(SlicePlane, PadsTheBoundingBoxAndCutsThroughItsMiddle) {
  // pad = 5 % of (1, 2, 4) + 0.1 = (0.15, 0.2, 0.3): box [-0.15, 1.15] x [-0.2, 2.2] x [-0.3, 4.3].
  const SlicePlane p = choose_slice_plane(boxes(), 0.1, 'z');
  EXPECT_EQ(p.normal_axis, 'z');
  EXPECT_NEAR(p.box.min()(0), -0.15, 1e-12);
  EXPECT_NEAR(p.box.min()(1), -0.2, 1e-12);
  EXPECT_NEAR(p.box.min()(2), -0.3, 1e-12);
  EXPECT_NEAR(p.box.max()(0), 1.15, 1e-12);
  EXPECT_NEAR(p.box.max()(1), 2.2, 1e-12);
  EXPECT_NEAR(p.box.max()(2), 4.3, 1e-12);
  EXPECT_NEAR(p.offset, 2.0, 1e-12);                // middle of [-0.3, 4.3]
  EXPECT_NEAR(p.pixel, 2.4 / 300.0, 1e-15);         // larger in-plane side: y, 2.4 m
  EXPECT_NEAR(p.pixel_count, 162.5 * 300.0, 1e-6);  // (1.3 / 0.008) * (2.4 / 0.008)
}

TEST(SlicePlane, XNormalUsesYAndZInPlane) {
  const SlicePlane p = choose_slice_plane(boxes(), 0.1, 'x');
  EXPECT_NEAR(p.offset, 0.5, 1e-12);         // middle of [-0.15, 1.15]
  EXPECT_NEAR(p.pixel, 4.6 / 300.0, 1e-15);  // z side 4.6 m beats y side 2.4 m
  EXPECT_NEAR(p.pixel_count, 2.4 * 4.6 / (p.pixel * p.pixel), 1e-6);
}

TEST(SlicePlane, GivenOffsetAndPixelAreKept) {
  const SlicePlane p = choose_slice_plane(boxes(), 0.1, 'y', 0.3, 0.01);
  EXPECT_EQ(p.normal_axis, 'y');
  EXPECT_EQ(p.offset, 0.3);
  EXPECT_EQ(p.pixel, 0.01);
  EXPECT_NEAR(p.pixel_count, 130.0 * 460.0, 1e-6);  // x side 1.3 m, z side 4.6 m
}

TEST(SlicePlane, EmptyWorkspaceFallsBackToTheSearchBox) {
  WorkspaceResult ws = boxes();
  ws.bounding_box.setEmpty();
  // Search box sizes (3, 4, 6), pad (0.15, 0.2, 0.3) + 0.02.
  const SlicePlane p = choose_slice_plane(ws, 0.02, 'z');
  EXPECT_NEAR(p.box.min()(0), -1.17, 1e-12);
  EXPECT_NEAR(p.box.max()(1), 3.22, 1e-12);
  EXPECT_NEAR(p.offset, 2.0, 1e-12);
  EXPECT_NEAR(p.pixel, 4.44 / 300.0, 1e-15);
}

TEST(SlicePlane, RejectsAnEmptyWorkspaceInAnEmptySearchBox) {
  // A machine whose legs have no common reach: both boxes empty (once a slice of 0 m pixels).
  WorkspaceResult ws = boxes();
  ws.bounding_box.setEmpty();
  ws.search_box.setEmpty();
  EXPECT_THROW(choose_slice_plane(ws, 0.02, 'z'), std::invalid_argument);
}

TEST(SlicePlane, RejectsAnAxisOtherThanXYZ) {
  EXPECT_THROW(choose_slice_plane(boxes(), 0.1, 'w'), std::invalid_argument);
}

}  // namespace
