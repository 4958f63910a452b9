// workspace_summary_json, workspace_kind and workspace_files (report/workspace_export.hpp) for a
// WorkspaceResult built by hand: every summary.json field against the value it must hold.
#include "report/workspace_export.hpp"

#include <gtest/gtest.h>

#include <limits>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace {

using pkmopt::OrientationSet;
using pkmopt::WorkspaceResult;
using pkmopt::WorkspaceSlice;

WorkspaceResult hand_made_workspace() {
  WorkspaceResult ws;
  ws.volume = 0.08;
  ws.surface_volume = 0.08;
  ws.convex_hull_volume = 0.1;
  ws.voxel_volume = 0.075;
  ws.envelope_volume = 0.4;
  ws.envelope_ratio = 5.0;
  ws.maps.global_conditioning_index = 0.5;
  ws.maps.singularity_margin_min = 0.0;
  ws.maps.stiffness_min_min = std::numeric_limits<double>::infinity();  // -> null
  ws.maps.stiffness_min_mean = 2e7;
  ws.maps.max_leg_force = 1500.0;
  ws.maps.tcp_error_max = 1e-5;
  ws.boundary.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  ws.boundary.triangles = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  ws.search_box = Eigen::AlignedBox3d(Eigen::Vector3d(-1, -1, 0), Eigen::Vector3d(1, 1, 2));
  ws.bounding_box = Eigen::AlignedBox3d(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 1, 1));
  ws.grid_nodes = Eigen::Vector3i(101, 101, 101);
  ws.resolution = 0.02;
  ws.orientation_count = 13;
  ws.inside_nodes = 10000;
  ws.touches_search_box = false;
  return ws;
}

WorkspaceSlice hand_made_slice() {
  WorkspaceSlice slice;
  slice.normal_axis = 'y';
  slice.offset = 0.25;
  slice.pixel = 0.005;
  slice.width = 3;
  slice.height = 2;
  slice.origin = Eigen::Vector2d(0, 0);
  slice.inside.assign(6, 1);
  slice.metrics.assign(6, pkmopt::WorkspacePointMetrics{0.5, 1e7, 100.0, 1e-6});
  return slice;
}

pkmopt::WorkspaceRequest hand_made_request() {
  pkmopt::WorkspaceRequest request;
  request.machine_file = "examples/hexapod.yaml";
  request.model = "hexapod";
  request.options.orientations.nominal_angles = Eigen::Vector3d(0, 0, 0);
  request.options.orientations.tilt = 0.1;
  request.options.orientations.mode = OrientationSet::Mode::kSome;
  request.options.min_stiffness = 1e6;
  request.options.wrench << 1, 2, 3, 4, 5, 6;
  request.tilt_deg = 5.7;  // written as given, not converted back from radians
  request.yaw_range_deg = 0.0;
  request.orientation_step_deg = 2.5;
  return request;
}

TEST(WorkspaceKind, NamesTheThreeKinds) {
  OrientationSet set;
  EXPECT_EQ(pkmopt::workspace_kind(set), "constant_orientation");
  set.yaw_range = 0.2;
  EXPECT_EQ(pkmopt::workspace_kind(set), "all_orientations");
  set.mode = OrientationSet::Mode::kSome;
  EXPECT_EQ(pkmopt::workspace_kind(set), "some_orientation");
}

TEST(WorkspaceSummaryJson, EveryFieldInOrder) {
  const std::string text =
      pkmopt::workspace_summary_json(hand_made_request(), hand_made_workspace(), hand_made_slice(),
                                     pkmopt::SliceMetric::kStiffnessMin, 1.5);
  ASSERT_FALSE(text.empty());
  EXPECT_EQ(text.back(), '\n');
  EXPECT_EQ(text.rfind("{\n  \"machine\": \"examples/hexapod.yaml\",\n", 0), 0u) << text;
  const auto j = nlohmann::ordered_json::parse(text);
  const std::vector<std::string> keys = {"machine",
                                         "model",
                                         "kind",
                                         "orientation_deg",
                                         "tilt_deg",
                                         "yaw_range_deg",
                                         "orientation_step_deg",
                                         "orientation_count",
                                         "min_singularity_margin",
                                         "min_stiffness",
                                         "wrench",
                                         "volume",
                                         "surface_volume",
                                         "convex_hull_volume",
                                         "voxel_volume",
                                         "convexity",
                                         "global_conditioning_index",
                                         "singularity_margin_min",
                                         "stiffness_min_min",
                                         "stiffness_min_mean",
                                         "max_leg_force",
                                         "tcp_error_max",
                                         "tcp_deflection_max",
                                         "stiffness_min_loaded_min",
                                         "envelope_volume",
                                         "envelope_ratio",
                                         "resolution",
                                         "volume_error_estimate",
                                         "volume_relative_error_estimate",
                                         "resolution_chosen_for_tolerance",
                                         "tolerance_met",
                                         "grid_nodes",
                                         "inside_nodes",
                                         "boundary_vertices",
                                         "boundary_triangles",
                                         "search_box",
                                         "bounding_box",
                                         "touches_search_box",
                                         "slice",
                                         "seconds"};
  std::vector<std::string> found;
  for (const auto& item : j.items()) found.push_back(item.key());
  EXPECT_EQ(found, keys);

  EXPECT_EQ(j["model"], "hexapod");
  EXPECT_EQ(j["kind"], "some_orientation");
  EXPECT_EQ(j["orientation_deg"], nlohmann::ordered_json::parse("[0.0, 0.0, 0.0]"));
  EXPECT_EQ(j["tilt_deg"], 5.7);
  EXPECT_EQ(j["orientation_step_deg"], 2.5);
  EXPECT_EQ(j["orientation_count"], 13);
  EXPECT_TRUE(j["min_singularity_margin"].is_null());
  EXPECT_EQ(j["min_stiffness"], 1e6);
  EXPECT_EQ(j["wrench"], nlohmann::ordered_json::parse("[1.0, 2.0, 3.0, 4.0, 5.0, 6.0]"));
  EXPECT_DOUBLE_EQ(j["convexity"].get<double>(), 0.8);  // 0.08 / 0.1
  EXPECT_EQ(j["global_conditioning_index"], 0.5);
  EXPECT_TRUE(j["stiffness_min_min"].is_null());  // infinite
  EXPECT_EQ(j["envelope_ratio"], 5.0);
  EXPECT_EQ(j["grid_nodes"], nlohmann::ordered_json::parse("[101, 101, 101]"));
  EXPECT_EQ(j["boundary_vertices"], 4);
  EXPECT_EQ(j["boundary_triangles"], 4);
  EXPECT_EQ(j["search_box"].dump(), R"({"min":[-1.0,-1.0,0.0],"max":[1.0,1.0,2.0]})");
  EXPECT_EQ(j["bounding_box"].dump(), R"({"min":[0.0,0.0,0.0],"max":[1.0,1.0,1.0]})");
  EXPECT_EQ(j["touches_search_box"], false);
  EXPECT_EQ(j["slice"].dump(),
            R"({"axis":"y","offset":0.25,"metric":"stiffness_min","pixel":0.005,"width":3,)"
            R"("height":2})");
  EXPECT_EQ(j["seconds"], 1.5);
  // A fixed resolution: an error estimate, no tolerance.
  EXPECT_EQ(j["volume_error_estimate"], 0.0);
  EXPECT_TRUE(j["resolution_chosen_for_tolerance"].is_null());
  EXPECT_TRUE(j["tolerance_met"].is_null());
  pkmopt::WorkspaceRequest chosen = hand_made_request();
  chosen.accuracy = {.resolution = 0.02,
                     .volume = 0.1,
                     .coarse_volume = 0.1004,
                     .error = 0.0004,
                     .tolerance = 0.005,
                     .met = true,
                     .grids = 3};
  const auto k = nlohmann::ordered_json::parse(pkmopt::workspace_summary_json(
      chosen, hand_made_workspace(), hand_made_slice(), pkmopt::SliceMetric::kStiffnessMin, 1.5));
  EXPECT_EQ(k["volume_error_estimate"], 0.0004);
  EXPECT_DOUBLE_EQ(k["volume_relative_error_estimate"].get<double>(), 0.004);
  EXPECT_EQ(k["resolution_chosen_for_tolerance"], 0.005);
  EXPECT_EQ(k["tolerance_met"], true);
}

TEST(WorkspaceSummaryJson, NoWorkspaceGivesNulls) {
  WorkspaceResult ws = hand_made_workspace();
  ws.bounding_box.setEmpty();
  ws.convex_hull_volume = 0.0;
  ws.envelope_ratio.reset();
  const auto j = nlohmann::ordered_json::parse(pkmopt::workspace_summary_json(
      hand_made_request(), ws, hand_made_slice(), pkmopt::SliceMetric::kSingularityMargin, 0.0));
  EXPECT_TRUE(j["bounding_box"].is_null());
  EXPECT_TRUE(j["convexity"].is_null());
  EXPECT_TRUE(j["envelope_ratio"].is_null());
  EXPECT_EQ(j["envelope_volume"], 0.4);
  EXPECT_EQ(j["slice"]["metric"], "singularity_margin");
}

TEST(WorkspaceFiles, NamesAndContentsInWritingOrder) {
  const WorkspaceResult ws = hand_made_workspace();
  const WorkspaceSlice slice = hand_made_slice();
  const auto files =
      pkmopt::workspace_files(ws, slice, pkmopt::SliceMetric::kMaxLegForce, "{ \"x\": 1 }\n");
  std::vector<std::string> names;
  for (const auto& [name, bytes] : files) names.push_back(name);
  EXPECT_EQ(names, (std::vector<std::string>{"boundary.ply", "boundary.stl", "points.csv",
                                             "slice_y.svg", "slice_y.png", "summary.json"}));
  EXPECT_EQ(files[0].second, pkmopt::boundary_ply(ws.boundary));
  EXPECT_EQ(files[1].second.size(), 84u + 50u * 4u);  // binary STL: header, count, 4 triangles
  EXPECT_EQ(files[3].second, pkmopt::slice_svg(slice, pkmopt::SliceMetric::kMaxLegForce));
  EXPECT_EQ(files[5].second, "{ \"x\": 1 }\n");
}

}  // namespace
