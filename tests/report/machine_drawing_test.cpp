// Tests of report/machine_drawing: the two views of a sketch as SVG, one scale for several
// drawings, the default drawing pose.
#include "report/machine_drawing.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <regex>
#include <string>

#include "io/machine/machine_file.hpp"

namespace pkmopt {
namespace {

std::size_t count(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

std::unique_ptr<Machine> hexapod() {
  return load_machine_file(
      (std::filesystem::path(PKMOPT_SOURCE_DIR) / "examples" / "hexapod.yaml").string());
}

// The length (px) of the scale bar and the millimetres it stands for.
std::pair<double, double> scale_bar(const std::string& svg) {
  std::smatch m;
  const std::regex bar(
      "<line x1=\"4\" y1=\"[0-9]+\" x2=\"([0-9.]+)\" y2=\"[0-9]+\" stroke=\"#000\" "
      "stroke-width=\"2\"/><text [^>]*>([0-9.]+) mm</text>");
  EXPECT_TRUE(std::regex_search(svg, m, bar)) << svg;
  return {std::stod(m[1]) - 4.0, std::stod(m[2])};
}

TEST(MachineDrawing, TwoViewsOfEveryLineJointAndOutline) {
  const auto machine = hexapod();
  const auto pose = drawing_pose(*machine);
  ASSERT_TRUE(pose.has_value());
  MachineSketch sketch;
  ASSERT_TRUE(machine->sketch(*machine->make_data(), *pose, sketch));
  const std::string svg = machine_svg(sketch, {.title = "hexapod"});
  EXPECT_EQ(svg.rfind("<?xml", 0), 0u);
  EXPECT_NE(svg.find("xmlns=\"http://www.w3.org/2000/svg\""), std::string::npos);
  EXPECT_NE(svg.find(">hexapod</text>"), std::string::npos);
  EXPECT_NE(svg.find("front (x right, z up)"), std::string::npos);
  EXPECT_NE(svg.find("top (x right, y up)"), std::string::npos);
  // Six legs and the tool in each view, and the scale bar.
  EXPECT_EQ(count(svg, "<line "), 2 * 7 + 1u);
  // Base and platform outlines in each view; 12 joints and the TCP in each view.
  EXPECT_EQ(count(svg, "<polygon "), 4u);
  EXPECT_EQ(count(svg, "<circle "), 2 * 13u);
  // Seen from above the six base joints of a semi-regular hexapod are all on the outline.
  const std::regex polygon("<polygon points=\"([^\"]*)\"");
  std::vector<std::size_t> corners;
  for (auto it = std::sregex_iterator(svg.begin(), svg.end(), polygon);
       it != std::sregex_iterator(); ++it)
    corners.push_back(count((*it)[1].str(), ","));
  ASSERT_EQ(corners.size(), 4u);
  EXPECT_EQ(corners[2], 6u);  // top view, base
  EXPECT_EQ(corners[3], 6u);  // top view, platform
  EXPECT_EQ(svg.find("pose not reachable"), std::string::npos);
}

TEST(MachineDrawing, SharedBoundsGiveOneScale) {
  const auto machine = hexapod();
  const Pose low = *drawing_pose(*machine);
  Pose high = low;
  high.position.z() += 0.1;
  MachineSketch a, b;
  ASSERT_TRUE(machine->sketch(*machine->make_data(), low, a));
  ASSERT_TRUE(machine->sketch(*machine->make_data(), high, b));
  Eigen::AlignedBox3d bounds = sketch_bounds(a);
  bounds.extend(sketch_bounds(b));
  const auto [px_a, mm_a] = scale_bar(machine_svg(a, {.bounds = bounds}));
  const auto [px_b, mm_b] = scale_bar(machine_svg(b, {.bounds = bounds}));
  EXPECT_EQ(px_a / mm_a, px_b / mm_b);
  // Larger bounds, a smaller scale.
  Eigen::AlignedBox3d larger = bounds;
  larger.extend(bounds.max() + Eigen::Vector3d::Constant(1.0));
  const auto [px_d, mm_d] = scale_bar(machine_svg(a, {.bounds = larger}));
  EXPECT_LT(px_d / mm_d, px_a / mm_a);
  const auto [px_c, mm_c] = scale_bar(machine_svg(a, {}));
  // The scale bar is true: the view's longer side (220 px by default) spans the padded extent.
  const Eigen::AlignedBox3d own = sketch_bounds(a);
  const double padded = own.sizes().maxCoeff() * 1.12;
  EXPECT_NEAR(px_c / mm_c, 220.0 / (1e3 * padded), 1e-3);
}

TEST(MachineDrawing, OutOfReachAndTaskBox) {
  const auto machine = hexapod();
  MachineSketch s;
  ASSERT_TRUE(machine->sketch(*machine->make_data(), Pose{{0, 0, 2.0}, {0, 0, 0}}, s));
  const std::string svg =
      machine_svg(s, {.task_box = Eigen::AlignedBox3d(Eigen::Vector3d(-0.15, -0.15, 1.9),
                                                      Eigen::Vector3d(0.15, 0.15, 2.1)),
                      .standalone = false});
  EXPECT_NE(svg.find("pose not reachable"), std::string::npos);
  EXPECT_EQ(count(svg, "<title>task box</title>"), 2u);
  EXPECT_EQ(svg.find("xmlns"), std::string::npos);
}

TEST(MachineDrawing, DrawingPoseIsReachableAndLevel) {
  const auto machine = hexapod();
  const auto pose = drawing_pose(*machine);
  ASSERT_TRUE(pose.has_value());
  EXPECT_TRUE(machine->reachable(*machine->make_data(), *pose));
  EXPECT_EQ(pose->angles, Eigen::Vector3d::Zero());
  EXPECT_NEAR(pose->position.x(), 0.0, 1e-9);  // the search box of a symmetric hexapod
  EXPECT_NEAR(pose->position.y(), 0.0, 1e-9);
}

}  // namespace
}  // namespace pkmopt
