#include "report/machine_drawing.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "report/pareto_report.hpp"

namespace pkmopt {
namespace {

// One orthographic view: which base axes run right and up.
struct View {
  const char* name;
  int right;  // 0 x, 1 y, 2 z
  int up;
};
constexpr std::array<View, 2> kViews = {
    {{"front (x right, z up)", 0, 2}, {"top (x right, y up)", 0, 1}}};

// The convex hull (counter-clockwise) of points in the plane: Andrew's monotone chain.
std::vector<Eigen::Vector2d> convex_hull(std::vector<Eigen::Vector2d> p) {
  std::sort(p.begin(), p.end(), [](const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
    return a.x() < b.x() || (a.x() == b.x() && a.y() < b.y());
  });
  if (p.size() < 3) return p;
  auto cross = [](const Eigen::Vector2d& o, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
    return (a - o).x() * (b - o).y() - (a - o).y() * (b - o).x();
  };
  std::vector<Eigen::Vector2d> hull(2 * p.size());
  std::size_t k = 0;
  for (const Eigen::Vector2d& q : p) {
    while (k >= 2 && cross(hull[k - 2], hull[k - 1], q) <= 0) --k;
    hull[k++] = q;
  }
  for (std::size_t i = p.size() - 1, lower = k + 1; i-- > 0;) {
    while (k >= lower && cross(hull[k - 2], hull[k - 1], p[i]) <= 0) --k;
    hull[k++] = p[i];
  }
  hull.resize(k - 1);
  return hull;
}

const char* line_style(MachineSketch::Part part) {
  switch (part) {
    case MachineSketch::Part::kGuide:
      return "stroke=\"#8a8a8a\" stroke-width=\"1.5\" stroke-dasharray=\"5 3\"";
    case MachineSketch::Part::kActuator:
      return "stroke=\"#e07b00\" stroke-width=\"3\"";
    case MachineSketch::Part::kLink:
      return "stroke=\"#333\" stroke-width=\"2\"";
    case MachineSketch::Part::kTool:
      return "stroke=\"#c00\" stroke-width=\"2\"";
  }
  return "";
}

// One view of the machine (base and platform outlines, the task box, the lines, the joints and
// the TCP) in the w x h pixel rectangle at (x0, y0), px pixels per metre from the corner of box.
std::string view_svg(const MachineSketch& sketch, const MachineDrawingOptions& options,
                     const View& v, const Eigen::AlignedBox3d& box, double px, int x0, int y0,
                     int w, int h) {
  std::string out;
  auto X = [&](const Eigen::Vector3d& p) { return x0 + (p(v.right) - box.min()(v.right)) * px; };
  auto Y = [&](const Eigen::Vector3d& p) { return y0 + h - (p(v.up) - box.min()(v.up)) * px; };
  out += fmt::format("<g class=\"view\"><text x=\"{}\" y=\"{}\" fill=\"#555\">{}</text>\n", x0,
                     y0 - 4, v.name);
  out += fmt::format(
      "<rect x=\"{}\" y=\"{}\" width=\"{}\" height=\"{}\" fill=\"#fafafa\" stroke=\"#ddd\"/>\n", x0,
      y0, w, h);
  // Outlines: the convex hull of the joints projected on the view.
  auto outline = [&](const std::vector<Eigen::Vector3d>& joints, const char* fill,
                     const char* stroke) {
    std::vector<Eigen::Vector2d> flat;
    for (const auto& p : joints) flat.emplace_back(X(p), Y(p));
    const std::vector<Eigen::Vector2d> hull = convex_hull(flat);
    if (hull.size() < 2) return;
    std::string points;
    for (const auto& q : hull) points += fmt::format("{:.1f},{:.1f} ", q.x(), q.y());
    out += fmt::format(
        "<polygon points=\"{}\" fill=\"{}\" fill-opacity=\"0.5\" stroke=\"{}\" "
        "stroke-width=\"1.5\"/>\n",
        points, fill, stroke);
  };
  outline(sketch.base_joints, "#cfcfcf", "#777");
  if (!options.task_box.isEmpty()) {
    const Eigen::AlignedBox3d& t = options.task_box;
    out += fmt::format(
        "<rect x=\"{:.1f}\" y=\"{:.1f}\" width=\"{:.1f}\" height=\"{:.1f}\" fill=\"none\" "
        "stroke=\"#2a8a2a\" stroke-dasharray=\"4 3\"><title>task box</title></rect>\n",
        X(t.min()), Y(t.max()), t.sizes()(v.right) * px, t.sizes()(v.up) * px);
  }
  for (const MachineSketch::Line& l : sketch.lines)
    out += fmt::format("<line x1=\"{:.1f}\" y1=\"{:.1f}\" x2=\"{:.1f}\" y2=\"{:.1f}\" {}/>\n",
                       X(l.from), Y(l.from), X(l.to), Y(l.to), line_style(l.part));
  outline(sketch.platform_joints, "#7fa8e0", "#2a5ba8");
  for (const auto& p : sketch.base_joints)
    out +=
        fmt::format("<circle cx=\"{:.1f}\" cy=\"{:.1f}\" r=\"2.5\" fill=\"#555\"/>\n", X(p), Y(p));
  for (const auto& p : sketch.platform_joints)
    out += fmt::format("<circle cx=\"{:.1f}\" cy=\"{:.1f}\" r=\"2.5\" fill=\"#2a5ba8\"/>\n", X(p),
                       Y(p));
  out += fmt::format(
      "<circle cx=\"{:.1f}\" cy=\"{:.1f}\" r=\"3.5\" fill=\"#c00\"><title>TCP ({:.1f}, "
      "{:.1f}, {:.1f}) mm</title></circle>\n",
      X(sketch.tcp), Y(sketch.tcp), 1e3 * sketch.tcp.x(), 1e3 * sketch.tcp.y(),
      1e3 * sketch.tcp.z());
  out += "</g>\n";
  return out;
}

// A scale bar of 100 mm (or 10 mm or 1 m, whichever fits the first view of `first_width` pixels
// best) at the bottom of a drawing `height` pixels high.
std::string scale_bar_svg(double px, int first_width, int height) {
  double bar = 0.1;
  if (bar * px > first_width * 0.6) bar = 0.01;
  if (bar * px < 20) bar = 1.0;
  return fmt::format(
      "<line x1=\"4\" y1=\"{0}\" x2=\"{1:.1f}\" y2=\"{0}\" stroke=\"#000\" stroke-width=\"2\"/>"
      "<text x=\"{2:.1f}\" y=\"{3}\">{4:g} mm</text>\n",
      height - 7, 4 + bar * px, 8 + bar * px, height - 3, bar * 1e3);
}

}  // namespace

Eigen::AlignedBox3d sketch_bounds(const MachineSketch& sketch) {
  Eigen::AlignedBox3d box;
  for (const auto& l : sketch.lines) {
    box.extend(l.from);
    box.extend(l.to);
  }
  for (const auto& p : sketch.base_joints) box.extend(p);
  for (const auto& p : sketch.platform_joints) box.extend(p);
  box.extend(sketch.tcp);
  return box;
}

std::string machine_svg(const MachineSketch& sketch, const MachineDrawingOptions& options) {
  Eigen::AlignedBox3d box = options.bounds;
  if (box.isEmpty()) {
    box = sketch_bounds(sketch);
    if (!options.task_box.isEmpty()) box.extend(options.task_box);
  }
  const double extent = std::max(box.sizes().maxCoeff(), 1e-3);
  box = Eigen::AlignedBox3d(box.min() - Eigen::Vector3d::Constant(0.06 * extent),
                            box.max() + Eigen::Vector3d::Constant(0.06 * extent));
  const double px = options.view_pixels / box.sizes().maxCoeff();  // px per m, both views
  const int title_height = options.title.empty() ? 0 : 18;
  const int label_height = 16;
  int width = 0, height = 0;
  std::vector<std::pair<int, int>> sizes;
  for (const View& v : kViews) {
    const int w = static_cast<int>(std::ceil(box.sizes()(v.right) * px));
    const int h = static_cast<int>(std::ceil(box.sizes()(v.up) * px));
    sizes.emplace_back(w, h);
    width += w + 12;
    height = std::max(height, h);
  }
  height += title_height + label_height + 18;  // the views, then the scale bar
  std::string out;
  if (options.standalone) out += "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n";
  out += fmt::format(
      "<svg {}width=\"{}\" height=\"{}\" viewBox=\"0 0 {} {}\" class=\"machine\" "
      "font-family=\"sans-serif\" font-size=\"11\">\n",
      options.standalone ? "xmlns=\"http://www.w3.org/2000/svg\" " : "", width, height, width,
      height);
  if (!options.title.empty())
    out += fmt::format("<text x=\"2\" y=\"13\" font-weight=\"bold\">{}</text>\n",
                       html_escape(options.title));
  if (!sketch.reachable)
    out += fmt::format(
        "<text x=\"{}\" y=\"13\" fill=\"#b00\" text-anchor=\"end\">pose not "
        "reachable</text>\n",
        width - 4);
  int x0 = 0;
  for (std::size_t k = 0; k < kViews.size(); ++k) {
    const View& v = kViews[k];
    const int w = sizes[k].first;
    const int h = sizes[k].second;
    const int y0 = title_height + label_height;
    out += view_svg(sketch, options, v, box, px, x0, y0, w, h);
    x0 += w + 12;
  }
  out += scale_bar_svg(px, sizes[0].first, height);
  out += "</svg>\n";
  return out;
}

std::optional<Pose> drawing_pose(const Machine& machine) {
  const auto box = machine.workspace_search_box({Eigen::Matrix3d::Identity()});
  if (!box || box->isEmpty() || !box->sizes().allFinite()) return std::nullopt;
  const auto data = machine.make_data();
  // The middle of the reachable part of a vertical line, or NaN.
  auto middle_height = [&](double x, double y) {
    constexpr int kSamples = 400;
    double low = NAN, high = NAN;
    for (int k = 0; k <= kSamples; ++k) {
      const double z = box->min().z() + box->sizes().z() * k / kSamples;
      if (!machine.reachable(*data, Pose{{x, y, z}, Eigen::Vector3d::Zero()})) continue;
      if (std::isnan(low)) low = z;
      high = z;
    }
    return 0.5 * (low + high);
  };
  // Above the centroid of the base joints (the machine's axis for a symmetric machine), else
  // the middle of the search box.
  Eigen::Vector2d centre = box->center().head<2>();
  MachineSketch sketch;
  const Pose probe{box->center(), Eigen::Vector3d::Zero()};
  if (machine.sketch(*data, probe, sketch) && !sketch.base_joints.empty()) {
    Eigen::Vector2d sum = Eigen::Vector2d::Zero();
    for (const Eigen::Vector3d& p : sketch.base_joints) sum += p.head<2>();
    const Eigen::Vector2d axis = sum / static_cast<double>(sketch.base_joints.size());
    if (!std::isnan(middle_height(axis.x(), axis.y()))) centre = axis;
  }
  const double z = middle_height(centre.x(), centre.y());
  if (std::isnan(z)) return std::nullopt;
  return Pose{{centre.x(), centre.y(), z}, Eigen::Vector3d::Zero()};
}

}  // namespace pkmopt
