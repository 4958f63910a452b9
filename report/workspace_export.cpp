#include "report/workspace_export.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <map>
#include <nlohmann/json.hpp>
#include <stdexcept>

#include "io/format/csv.hpp"
#include "report/raster_image.hpp"

namespace pkmopt {
namespace {

using raster::hex;
using raster::kGlyphHeight;
using raster::kInk;
using raster::kWhite;
using raster::nice_ticks;
using raster::Rgb;
using raster::RgbImage;
using raster::viridis;

constexpr Rgb kOutsideColour{225, 225, 225};
constexpr Rgb kInfiniteColour{0, 0, 0};

std::string short_number(double v) { return fmt::format("{:.3g}", v); }

char axis_name(char normal, int which) {
  // In-plane axes u, v in the order used by compute_workspace_slice.
  if (normal == 'x') return which == 0 ? 'y' : 'z';
  if (normal == 'y') return which == 0 ? 'x' : 'z';
  return which == 0 ? 'x' : 'y';
}

// Geometry shared by the SVG and the PNG picture (screen pixels, y down).
struct SliceLayout {
  int scale = 1;  // screen pixels per slice pixel
  int left = 90, top = 50, plot_width = 0, plot_height = 0;
  int bar_left = 0, bar_width = 22;
  int width = 0, height = 0;
  double low = 0.0, high = 0.0;  // colour range
  bool has_values = false;
  std::vector<double> ticks_u, ticks_v, ticks_bar;
  std::string title, label_u, label_v;

  double screen_x(const WorkspaceSlice& s, double u) const {
    return left + scale * ((u - s.origin(0)) / s.pixel + 0.5);
  }
  double screen_y(const WorkspaceSlice& s, double v) const {
    return top + plot_height - scale * ((v - s.origin(1)) / s.pixel + 0.5);
  }
  double bar_y(double value) const {
    const double t = high > low ? (value - low) / (high - low) : 0.5;
    return top + plot_height * (1.0 - t);
  }
};

SliceLayout make_layout(const WorkspaceSlice& slice, SliceMetric metric) {
  SliceLayout layout;
  layout.scale = std::max(1, 640 / std::max(slice.width, slice.height));
  layout.plot_width = slice.width * layout.scale;
  layout.plot_height = slice.height * layout.scale;
  layout.bar_left = layout.left + layout.plot_width + 30;
  // Room right of the colour bar for its tick labels and, above it, the metric's name.
  const int name_width =
      static_cast<int>(slice_metric_name(metric).size()) * raster::kGlyphAdvance + 10;
  layout.width = layout.bar_left + std::max(layout.bar_width + 100, name_width);
  layout.height = layout.top + layout.plot_height + 60;
  double low = std::numeric_limits<double>::infinity(), high = -low;
  for (std::size_t p = 0; p < slice.inside.size(); ++p) {
    if (!slice.inside[p]) continue;
    const double v = slice_metric_value(slice.metrics[p], metric);
    if (!std::isfinite(v)) continue;
    low = std::min(low, v);
    high = std::max(high, v);
  }
  layout.has_values = low <= high;
  layout.low = layout.has_values ? low : 0.0;
  layout.high = layout.has_values ? high : 1.0;
  const double pad = 0.5 * slice.pixel;
  const double u0 = slice.origin(0) - pad,
               u1 = slice.origin(0) + (slice.width - 1) * slice.pixel + pad;
  const double v0 = slice.origin(1) - pad,
               v1 = slice.origin(1) + (slice.height - 1) * slice.pixel + pad;
  for (double t : nice_ticks(1e3 * u0, 1e3 * u1, 6)) layout.ticks_u.push_back(t / 1e3);
  for (double t : nice_ticks(1e3 * v0, 1e3 * v1, 6)) layout.ticks_v.push_back(t / 1e3);
  layout.ticks_bar = layout.high > layout.low ? nice_ticks(layout.low, layout.high, 5)
                                              : std::vector<double>{layout.low};
  layout.title = fmt::format("{}, {} = {} mm", slice_metric_label(metric), slice.normal_axis,
                             short_number(1e3 * slice.offset));
  layout.label_u = fmt::format("{} [mm]", axis_name(slice.normal_axis, 0));
  layout.label_v = fmt::format("{} [mm]", axis_name(slice.normal_axis, 1));
  return layout;
}

Rgb pixel_colour(const WorkspaceSlice& slice, const SliceLayout& layout, SliceMetric metric,
                 std::size_t p) {
  if (!slice.inside[p]) return kOutsideColour;
  const double v = slice_metric_value(slice.metrics[p], metric);
  if (!std::isfinite(v)) return kInfiniteColour;
  const double t = layout.high > layout.low ? (v - layout.low) / (layout.high - layout.low) : 0.5;
  // 64 colour levels, as in the colour bar (and long runs of equal colour in the SVG).
  return viridis((std::min(63.0, std::floor(64.0 * t)) + 0.5) / 64.0);
}

void append_float(std::string& out, float value) {
  char bytes[4];
  std::memcpy(bytes, &value, 4);  // STL is little-endian, as is every target we build for
  out.append(bytes, 4);
}

}  // namespace

std::optional<SliceMetric> parse_slice_metric(std::string_view name) {
  if (name == "singularity_margin") return SliceMetric::kSingularityMargin;
  if (name == "stiffness_min") return SliceMetric::kStiffnessMin;
  if (name == "max_leg_force") return SliceMetric::kMaxLegForce;
  if (name == "tcp_error_max") return SliceMetric::kTcpErrorMax;
  if (name == "tcp_deflection") return SliceMetric::kTcpDeflection;
  if (name == "stiffness_min_loaded") return SliceMetric::kStiffnessMinLoaded;
  if (name == "natural_frequency_1") return SliceMetric::kNaturalFrequency1;
  return std::nullopt;
}

std::string slice_metric_name(SliceMetric metric) {
  switch (metric) {
    case SliceMetric::kSingularityMargin:
      return "singularity_margin";
    case SliceMetric::kStiffnessMin:
      return "stiffness_min";
    case SliceMetric::kMaxLegForce:
      return "max_leg_force";
    case SliceMetric::kTcpErrorMax:
      return "tcp_error_max";
    case SliceMetric::kTcpDeflection:
      return "tcp_deflection";
    case SliceMetric::kStiffnessMinLoaded:
      return "stiffness_min_loaded";
    case SliceMetric::kNaturalFrequency1:
      return "natural_frequency_1";
  }
  return "";
}

std::string slice_metric_label(SliceMetric metric) {
  switch (metric) {
    case SliceMetric::kSingularityMargin:
      return "singularity_margin";
    case SliceMetric::kStiffnessMin:
      return "stiffness_min [N/m]";
    case SliceMetric::kMaxLegForce:
      return "max_leg_force [N]";
    case SliceMetric::kTcpErrorMax:
      return "tcp_error_max [m]";
    case SliceMetric::kTcpDeflection:
      return "tcp_deflection [m]";
    case SliceMetric::kStiffnessMinLoaded:
      return "stiffness_min_loaded [N/m]";
    case SliceMetric::kNaturalFrequency1:
      return "natural_frequency_1 [Hz]";
  }
  return "";
}

double slice_metric_value(const WorkspacePointMetrics& m, SliceMetric metric) {
  switch (metric) {
    case SliceMetric::kSingularityMargin:
      return m.singularity_margin;
    case SliceMetric::kStiffnessMin:
      return m.stiffness_min;
    case SliceMetric::kMaxLegForce:
      return m.max_leg_force;
    case SliceMetric::kTcpErrorMax:
      return m.tcp_error_max;
    case SliceMetric::kTcpDeflection:
      return m.tcp_deflection;
    case SliceMetric::kStiffnessMinLoaded:
      return m.stiffness_min_loaded;
    case SliceMetric::kNaturalFrequency1:
      return m.natural_frequency_1;
  }
  return 0.0;
}

std::string boundary_ply(const TriangleMesh& mesh) {
  std::string out = fmt::format(
      "ply\nformat ascii 1.0\ncomment pkmopt workspace boundary, metres, outward normals\n"
      "element vertex {}\nproperty double x\nproperty double y\nproperty double z\n"
      "element face {}\nproperty list uchar int vertex_indices\nend_header\n",
      mesh.vertices.size(), mesh.triangles.size());
  for (const auto& v : mesh.vertices) {
    out += format_number(v.x()) + ' ' + format_number(v.y()) + ' ' + format_number(v.z()) + '\n';
  }
  for (const auto& t : mesh.triangles) out += fmt::format("3 {} {} {}\n", t[0], t[1], t[2]);
  return out;
}

std::string boundary_stl(const TriangleMesh& mesh) {
  std::string out(80, ' ');
  const std::string header = "pkmopt workspace boundary (metres, outward normals)";
  out.replace(0, header.size(), header);
  const auto count = static_cast<std::uint32_t>(mesh.triangles.size());
  char count_bytes[4];
  std::memcpy(count_bytes, &count, 4);
  out.append(count_bytes, 4);
  out.reserve(out.size() + 50 * mesh.triangles.size());
  for (const auto& t : mesh.triangles) {
    const Eigen::Vector3d& a = mesh.vertices[static_cast<std::size_t>(t[0])];
    const Eigen::Vector3d& b = mesh.vertices[static_cast<std::size_t>(t[1])];
    const Eigen::Vector3d& c = mesh.vertices[static_cast<std::size_t>(t[2])];
    Eigen::Vector3d outward = (b - a).cross(c - a);
    if (outward.norm() > 0.0) outward.normalize();
    const Eigen::Vector3d& normal = outward;
    for (const Eigen::Vector3d* v : {&normal, &a, &b, &c}) {
      for (int k = 0; k < 3; ++k) append_float(out, static_cast<float>((*v)(k)));
    }
    out.append(2, '\0');
  }
  return out;
}

std::string point_cloud_csv(const std::vector<WorkspacePoint>& points, bool natural_frequencies) {
  std::string out =
      "x,y,z,singularity_margin,stiffness_min,max_leg_force,tcp_error_max,tcp_deflection,"
      "stiffness_min_loaded";
  out += natural_frequencies ? ",natural_frequency_1\n" : "\n";
  for (const auto& p : points) {
    for (int k = 0; k < 3; ++k) out += format_number(p.position(k)) + ',';
    out += format_number(p.metrics.singularity_margin) + ',' +
           format_number(p.metrics.stiffness_min) + ',' + format_number(p.metrics.max_leg_force) +
           ',' + format_number(p.metrics.tcp_error_max) + ',' +
           format_number(p.metrics.tcp_deflection) + ',' +
           format_number(p.metrics.stiffness_min_loaded);
    if (natural_frequencies) out += ',' + format_number(p.metrics.natural_frequency_1);
    out += '\n';
  }
  return out;
}

std::string slice_svg(const WorkspaceSlice& slice, SliceMetric metric,
                      const SliceOverlay& overlay) {
  const SliceLayout L = make_layout(slice, metric);
  std::string out = fmt::format(
      "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{0}\" height=\"{1}\" "
      "viewBox=\"0 0 {0} {1}\" font-family=\"sans-serif\" font-size=\"13\">\n"
      "<rect width=\"{0}\" height=\"{1}\" fill=\"#ffffff\"/>\n",
      L.width, L.height);
  out += fmt::format("<text x=\"{}\" y=\"{}\" font-size=\"15\">{}</text>\n", L.left, L.top - 22,
                     L.title);
  // Pixels, as runs of equal colour along each row.
  out += "<g shape-rendering=\"crispEdges\">\n";
  for (int j = 0; j < slice.height; ++j) {
    const int y = L.top + (slice.height - 1 - j) * L.scale;
    int i = 0;
    while (i < slice.width) {
      const Rgb c = pixel_colour(slice, L, metric, static_cast<std::size_t>(j) * slice.width + i);
      int run = 1;
      while (i + run < slice.width) {
        const Rgb d =
            pixel_colour(slice, L, metric, static_cast<std::size_t>(j) * slice.width + i + run);
        if (d.r != c.r || d.g != c.g || d.b != c.b) break;
        ++run;
      }
      out += fmt::format("<rect x=\"{}\" y=\"{}\" width=\"{}\" height=\"{}\" fill=\"{}\"/>\n",
                         L.left + i * L.scale, y, run * L.scale, L.scale, hex(c));
      i += run;
    }
  }
  out += "</g>\n";
  out += fmt::format(
      "<rect x=\"{}\" y=\"{}\" width=\"{}\" height=\"{}\" fill=\"none\" stroke=\"#141414\"/>\n",
      L.left, L.top, L.plot_width, L.plot_height);
  if (overlay.task_rect) {
    const auto& [lo, hi] = *overlay.task_rect;
    const double x0 = L.screen_x(slice, lo.x()), x1 = L.screen_x(slice, hi.x());
    const double y0 = L.screen_y(slice, hi.y()), y1 = L.screen_y(slice, lo.y());
    out += fmt::format(
        "<rect x=\"{:.1f}\" y=\"{:.1f}\" width=\"{:.1f}\" height=\"{:.1f}\" fill=\"none\" "
        "stroke=\"#e8112d\" stroke-width=\"2\"/><text x=\"{:.1f}\" y=\"{:.1f}\" "
        "fill=\"#e8112d\">task</text>\n",
        x0, y0, x1 - x0, y1 - y0, x0 + 3, y0 - 4);
  }
  out += fmt::format("<text x=\"{}\" y=\"{}\">{}</text>\n", L.bar_left, L.top - 6,
                     slice_metric_name(metric));
  const int bottom = L.top + L.plot_height;
  for (double u : L.ticks_u) {
    const double x = L.screen_x(slice, u);
    out += fmt::format(
        "<line x1=\"{0:.1f}\" y1=\"{1}\" x2=\"{0:.1f}\" y2=\"{2}\" stroke=\"#141414\"/>\n"
        "<text x=\"{0:.1f}\" y=\"{3}\" text-anchor=\"middle\">{4}</text>\n",
        x, bottom, bottom + 6, bottom + 20, fmt::format("{:g}", 1e3 * u));
  }
  for (double v : L.ticks_v) {
    const double y = L.screen_y(slice, v);
    out += fmt::format(
        "<line x1=\"{0}\" y1=\"{1:.1f}\" x2=\"{2}\" y2=\"{1:.1f}\" stroke=\"#141414\"/>\n"
        "<text x=\"{3}\" y=\"{4:.1f}\" text-anchor=\"end\">{5}</text>\n",
        L.left - 6, y, L.left, L.left - 9, y + 4, fmt::format("{:g}", 1e3 * v));
  }
  out += fmt::format("<text x=\"{}\" y=\"{}\" text-anchor=\"middle\">{}</text>\n",
                     L.left + L.plot_width / 2, bottom + 42, L.label_u);
  out += fmt::format("<text x=\"{}\" y=\"{}\" text-anchor=\"end\">{}</text>\n", L.left - 9,
                     L.top - 6, L.label_v);
  // Colour bar: 64 bands, low at the bottom.
  const int bands = 64;
  for (int b = 0; b < bands; ++b) {
    const double y0 = L.top + L.plot_height * (1.0 - (b + 1.0) / bands);
    out +=
        fmt::format("<rect x=\"{}\" y=\"{:.2f}\" width=\"{}\" height=\"{:.2f}\" fill=\"{}\"/>\n",
                    L.bar_left, y0, L.bar_width, L.plot_height / static_cast<double>(bands) + 0.5,
                    hex(viridis((b + 0.5) / bands)));
  }
  out += fmt::format(
      "<rect x=\"{}\" y=\"{}\" width=\"{}\" height=\"{}\" fill=\"none\" stroke=\"#141414\"/>\n",
      L.bar_left, L.top, L.bar_width, L.plot_height);
  if (L.has_values) {
    for (double t : L.ticks_bar) {
      const double y = L.bar_y(t);
      out += fmt::format(
          "<line x1=\"{0}\" y1=\"{1:.1f}\" x2=\"{2}\" y2=\"{1:.1f}\" stroke=\"#141414\"/>\n"
          "<text x=\"{3}\" y=\"{4:.1f}\">{5}</text>\n",
          L.bar_left + L.bar_width, y, L.bar_left + L.bar_width + 5, L.bar_left + L.bar_width + 8,
          y + 4, short_number(t));
    }
  } else {
    out += fmt::format("<text x=\"{}\" y=\"{}\">no workspace</text>\n", L.bar_left,
                       L.top + L.plot_height / 2);
  }
  out += "</svg>\n";
  return out;
}

std::string slice_png(const WorkspaceSlice& slice, SliceMetric metric,
                      const SliceOverlay& overlay) {
  const SliceLayout L = make_layout(slice, metric);
  RgbImage image(L.width, L.height, kWhite);
  for (int j = 0; j < slice.height; ++j) {
    for (int i = 0; i < slice.width; ++i) {
      const Rgb c = pixel_colour(slice, L, metric, static_cast<std::size_t>(j) * slice.width + i);
      const int x = L.left + i * L.scale, y = L.top + (slice.height - 1 - j) * L.scale;
      image.fill(x, y, x + L.scale, y + L.scale, c);
    }
  }
  image.frame(L.left - 1, L.top - 1, L.left + L.plot_width + 1, L.top + L.plot_height + 1, kInk);
  image.text(L.left, L.top - 22 - kGlyphHeight / 2, L.title, kInk);
  image.text(L.bar_left, L.top - 8 - kGlyphHeight, slice_metric_name(metric), kInk);
  if (overlay.task_rect) {
    const Rgb red{232, 17, 45};
    const auto& [lo, hi] = *overlay.task_rect;
    const int x0 = static_cast<int>(std::lround(L.screen_x(slice, lo.x())));
    const int x1 = static_cast<int>(std::lround(L.screen_x(slice, hi.x())));
    const int y0 = static_cast<int>(std::lround(L.screen_y(slice, hi.y())));
    const int y1 = static_cast<int>(std::lround(L.screen_y(slice, lo.y())));
    image.frame(x0, y0, x1, y1, red);
    image.frame(x0 + 1, y0 + 1, x1 - 1, y1 - 1, red);
    image.text(x0 + 3, y0 - 3 - kGlyphHeight, "task", red);
  }
  const int bottom = L.top + L.plot_height;
  for (double u : L.ticks_u) {
    const int x = static_cast<int>(std::lround(L.screen_x(slice, u)));
    image.fill(x, bottom, x + 1, bottom + 6, kInk);
    const std::string label = fmt::format("{:g}", 1e3 * u);
    image.text(x - image.text_width(label) / 2, bottom + 9, label, kInk);
  }
  for (double v : L.ticks_v) {
    const int y = static_cast<int>(std::lround(L.screen_y(slice, v)));
    image.fill(L.left - 6, y, L.left, y + 1, kInk);
    const std::string label = fmt::format("{:g}", 1e3 * v);
    image.text(L.left - 9 - image.text_width(label), y - kGlyphHeight / 2, label, kInk);
  }
  image.text(L.left + L.plot_width / 2 - image.text_width(L.label_u) / 2, bottom + 30, L.label_u,
             kInk);
  image.text(L.left - 9 - image.text_width(L.label_v), L.top - 6 - kGlyphHeight, L.label_v, kInk);
  for (int y = L.top; y < bottom; ++y) {
    const double t = 1.0 - (y - L.top + 0.5) / L.plot_height;
    image.fill(L.bar_left, y, L.bar_left + L.bar_width, y + 1, viridis(t));
  }
  image.frame(L.bar_left - 1, L.top - 1, L.bar_left + L.bar_width + 1, bottom + 1, kInk);
  if (L.has_values) {
    for (double t : L.ticks_bar) {
      const int y = static_cast<int>(std::lround(L.bar_y(t)));
      image.fill(L.bar_left + L.bar_width, y, L.bar_left + L.bar_width + 5, y + 1, kInk);
      image.text(L.bar_left + L.bar_width + 8, y - kGlyphHeight / 2, short_number(t), kInk);
    }
  }
  return image.encode_png();
}

namespace {

nlohmann::json number_or_null(double v) {
  return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr);
}

nlohmann::json vector_json(const Eigen::Vector3d& v) {
  return nlohmann::json::array({number_or_null(v(0)), number_or_null(v(1)), number_or_null(v(2))});
}

nlohmann::json optional_json(const std::optional<double>& v) {
  return v ? nlohmann::json(*v) : nlohmann::json(nullptr);
}

nlohmann::ordered_json box_json(const Eigen::AlignedBox3d& box) {
  return {{"min", vector_json(box.min())}, {"max", vector_json(box.max())}};
}

}  // namespace

std::string workspace_kind(const OrientationSet& set) {
  if (set.constant()) return "constant_orientation";
  return set.mode == OrientationSet::Mode::kAll ? "all_orientations" : "some_orientation";
}

std::string workspace_summary_json(const WorkspaceRequest& request, const WorkspaceResult& ws,
                                   const WorkspaceSlice& slice, SliceMetric metric,
                                   double seconds) {
  const WorkspaceOptions& options = request.options;
  const OrientationSet& set = options.orientations;
  nlohmann::ordered_json summary;
  summary["machine"] = request.machine_file;
  summary["model"] = request.model;
  summary["kind"] = workspace_kind(set);
  summary["orientation_deg"] = vector_json(rad_to_deg(set.nominal_angles));
  summary["tilt_deg"] = request.tilt_deg;
  summary["yaw_range_deg"] = request.yaw_range_deg;
  summary["orientation_step_deg"] = request.orientation_step_deg;
  summary["orientation_count"] = ws.orientation_count;
  summary["min_singularity_margin"] = optional_json(options.min_singularity_margin);
  summary["min_stiffness"] = optional_json(options.min_stiffness);
  summary["wrench"] = std::vector<double>(options.wrench.data(), options.wrench.data() + 6);
  summary["volume"] = ws.volume;
  summary["surface_volume"] = ws.surface_volume;
  summary["convex_hull_volume"] = ws.convex_hull_volume;
  summary["voxel_volume"] = ws.voxel_volume;
  summary["convexity"] =
      ws.convex_hull_volume > 0.0 ? nlohmann::json(ws.volume / ws.convex_hull_volume) : nullptr;
  summary["global_conditioning_index"] = number_or_null(ws.maps.global_conditioning_index);
  summary["singularity_margin_min"] = number_or_null(ws.maps.singularity_margin_min);
  summary["stiffness_min_min"] = number_or_null(ws.maps.stiffness_min_min);
  summary["stiffness_min_mean"] = number_or_null(ws.maps.stiffness_min_mean);
  summary["max_leg_force"] = number_or_null(ws.maps.max_leg_force);
  summary["tcp_error_max"] = number_or_null(ws.maps.tcp_error_max);
  summary["tcp_deflection_max"] = number_or_null(ws.maps.tcp_deflection_max);
  summary["stiffness_min_loaded_min"] = number_or_null(ws.maps.stiffness_min_loaded_min);
  if (ws.maps.natural_frequencies)
    summary["natural_frequency_min"] = number_or_null(ws.maps.natural_frequency_min);
  summary["envelope_volume"] = optional_json(ws.envelope_volume);
  summary["envelope_ratio"] = optional_json(ws.envelope_ratio);
  summary["resolution"] = ws.resolution;
  // The error estimate from the grid at twice the spacing (models/workspace/
  // volume_accuracy.hpp); a tolerance when the resolution was chosen to meet it.
  summary["volume_error_estimate"] = request.accuracy.error;
  summary["volume_relative_error_estimate"] = request.accuracy.relative_error();
  summary["resolution_chosen_for_tolerance"] =
      request.accuracy.tolerance > 0.0 ? nlohmann::json(request.accuracy.tolerance) : nullptr;
  summary["tolerance_met"] =
      request.accuracy.tolerance > 0.0 ? nlohmann::json(request.accuracy.met) : nullptr;
  summary["grid_nodes"] = {ws.grid_nodes(0), ws.grid_nodes(1), ws.grid_nodes(2)};
  summary["inside_nodes"] = ws.inside_nodes;
  summary["boundary_vertices"] = ws.boundary.vertices.size();
  summary["boundary_triangles"] = ws.boundary.triangles.size();
  summary["search_box"] = box_json(ws.search_box);
  summary["bounding_box"] = ws.bounding_box.isEmpty() ? nullptr : box_json(ws.bounding_box);
  summary["touches_search_box"] = ws.touches_search_box;
  summary["slice"] = {{"axis", std::string(1, slice.normal_axis)},
                      {"offset", slice.offset},
                      {"metric", slice_metric_name(metric)},
                      {"pixel", slice.pixel},
                      {"width", slice.width},
                      {"height", slice.height}};
  summary["seconds"] = seconds;
  return summary.dump(2) + "\n";
}

std::vector<std::pair<std::string, std::string>> workspace_files(const WorkspaceResult& ws,
                                                                 const WorkspaceSlice& slice,
                                                                 SliceMetric metric,
                                                                 const std::string& summary_json) {
  const std::string slice_name = fmt::format("slice_{}", slice.normal_axis);
  std::vector<std::pair<std::string, std::string>> files;
  files.emplace_back("boundary.ply", boundary_ply(ws.boundary));
  files.emplace_back("boundary.stl", boundary_stl(ws.boundary));
  files.emplace_back("points.csv", point_cloud_csv(ws.points, ws.maps.natural_frequencies));
  files.emplace_back(slice_name + ".svg", slice_svg(slice, metric));
  files.emplace_back(slice_name + ".png", slice_png(slice, metric));
  files.emplace_back("summary.json", summary_json);
  return files;
}

}  // namespace pkmopt
