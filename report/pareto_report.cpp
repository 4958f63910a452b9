#include "report/pareto_report.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <memory>
#include <nlohmann/json.hpp>
#include <set>

#include "io/format/csv.hpp"
#include "io/format/input_error.hpp"
#include "io/machine/machine_file.hpp"
#include "pkmopt/report_assets.hpp"
#include "report/display_units.hpp"
#include "report/pareto_report_detail.hpp"
#include "report/raster_image.hpp"
#include "report/workspace_export.hpp"

namespace pkmopt {
namespace report_detail {

using nlohmann::json;
using raster::Rgb;

// ---------------------------------------------------------------------------------------------
// Plots

std::string short_number(double v) { return fmt::format("{:.4g}", v); }

std::string xml_escape(std::string_view text) {
  std::string out;
  for (char c : text) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

std::string objective_label(const ParetoObjective& o) {
  std::string label = o.name;
  if (!o.unit.empty()) label += " [" + o.unit + "]";
  label += o.sense == "maximize" ? " (max)" : " (min)";
  return label;
}

constexpr Rgb kFeasibleColour{31, 119, 180};
constexpr Rgb kInfeasibleColour{140, 140, 140};
constexpr Rgb kKneeColour{214, 39, 40};

// The scatter's geometry, shared by the SVG and the PNG. Axis -1 is the design number (for a
// front with one objective).
struct ScatterLayout : raster::PlotAxes {
  int width = 680, height = 520, right = 30, bottom = 70;  // right, bottom: margins
  std::string title, x_label, y_label;
  struct Point {
    std::size_t design;
    double x, y;  // screen
  };
  std::vector<Point> points;  // designs with finite coordinates, knee last (drawn on top)

  ScatterLayout() {
    left = 100;
    top = 70;
  }
};

double axis_value(const ParetoFront& front, std::size_t design, int axis) {
  if (axis < 0) return static_cast<double>(design);
  return front.designs[design].objectives[static_cast<std::size_t>(axis)];
}

ScatterLayout make_scatter(const ParetoFront& front, int x_axis, int y_axis) {
  const int count = static_cast<int>(front.objectives.size());
  if (count == 0) throw std::invalid_argument("a Pareto plot needs at least one objective");
  if (count == 1) {
    x_axis = -1;
    y_axis = 0;
  }
  if (x_axis >= count || y_axis >= count || y_axis < 0 || x_axis < -1) {
    throw std::invalid_argument("a Pareto plot axis is not an objective");
  }
  ScatterLayout L;
  L.plot_width = L.width - L.left - L.right;
  L.plot_height = L.height - L.top - L.bottom;
  double x_low = std::numeric_limits<double>::infinity(), x_high = -x_low;
  double y_low = x_low, y_high = -x_low;
  std::vector<std::size_t> shown;
  const int knee = front.knee ? front.design_index(*front.knee) : -1;
  for (std::size_t d = 0; d < front.designs.size(); ++d) {
    const double x = axis_value(front, d, x_axis), y = axis_value(front, d, y_axis);
    if (!std::isfinite(x) || !std::isfinite(y)) continue;
    x_low = std::min(x_low, x);
    x_high = std::max(x_high, x);
    y_low = std::min(y_low, y);
    y_high = std::max(y_high, y);
    if (static_cast<int>(d) != knee) shown.push_back(d);
  }
  if (knee >= 0 && std::isfinite(axis_value(front, static_cast<std::size_t>(knee), x_axis)) &&
      std::isfinite(axis_value(front, static_cast<std::size_t>(knee), y_axis))) {
    shown.push_back(static_cast<std::size_t>(knee));
  }
  raster::padded_range(x_low, x_high);
  raster::padded_range(y_low, y_high);
  L.x_low = x_low;
  L.x_high = x_high;
  L.y_low = y_low;
  L.y_high = y_high;
  L.x_ticks = raster::nice_ticks(x_low, x_high, 6);
  L.y_ticks = raster::nice_ticks(y_low, y_high, 6);
  for (std::size_t d : shown) {
    L.points.push_back(
        {d, L.screen_x(axis_value(front, d, x_axis)), L.screen_y(axis_value(front, d, y_axis))});
  }
  L.title = fmt::format("{}: pareto front, {} designs", front.study, front.designs.size());
  L.x_label = x_axis < 0 ? "design number"
                         : objective_label(front.objectives[static_cast<std::size_t>(x_axis)]);
  L.y_label = objective_label(front.objectives[static_cast<std::size_t>(y_axis)]);
  return L;
}

// The scatter as SVG; `standalone` adds the XML namespace (an inline SVG in HTML needs none).
std::string scatter_svg(const ParetoFront& front, int x_axis, int y_axis, bool standalone) {
  const ScatterLayout L = make_scatter(front, x_axis, y_axis);
  std::string out = fmt::format(
      "<svg {}id=\"scatter\" width=\"{}\" height=\"{}\" viewBox=\"0 0 {} {}\" "
      "font-family=\"sans-serif\" font-size=\"13\">\n"
      "<rect width=\"{}\" height=\"{}\" fill=\"#ffffff\"/>\n",
      standalone ? "xmlns=\"http://www.w3.org/2000/svg\" " : "", L.width, L.height, L.width,
      L.height, L.width, L.height);
  out += fmt::format("<text x=\"{}\" y=\"{}\" font-size=\"15\">{}</text>\n", L.left, 26,
                     xml_escape(L.title));
  const int bottom = L.frame_bottom();
  out += raster::svg_axes(L);
  out += fmt::format("<text x=\"{}\" y=\"{}\" text-anchor=\"middle\">{}</text>\n",
                     L.left + L.plot_width / 2, bottom + 45, xml_escape(L.x_label));
  out += fmt::format(
      "<text transform=\"translate({},{}) rotate(-90)\" text-anchor=\"middle\">{}</text>\n", 22,
      L.top + L.plot_height / 2, xml_escape(L.y_label));
  const int knee = front.knee ? front.design_index(*front.knee) : -1;
  for (const auto& p : L.points) {
    const ParetoDesign& d = front.designs[p.design];
    const bool is_knee = static_cast<int>(p.design) == knee;
    const Rgb colour = is_knee ? kKneeColour : (d.feasible ? kFeasibleColour : kInfeasibleColour);
    const bool filled = d.feasible || is_knee;
    out += fmt::format(
        "<circle class=\"pt{}\" data-id=\"{}\" cx=\"{:.2f}\" cy=\"{:.2f}\" r=\"{}\" fill=\"{}\" "
        "stroke=\"{}\" stroke-width=\"1.5\"/>\n",
        is_knee ? " knee" : "", xml_escape(d.id), p.x, p.y, is_knee ? 6.5 : 4.5,
        filled ? raster::hex(colour) : "#ffffff", raster::hex(colour));
    if (is_knee) {
      const std::string label = "knee " + d.id;
      const bool left = p.x + 9 + 8 * static_cast<double>(label.size()) > L.width - 4;
      out +=
          fmt::format("<text x=\"{:.1f}\" y=\"{:.1f}\" fill=\"{}\" text-anchor=\"{}\">{}</text>\n",
                      left ? p.x - 9 : p.x + 9, p.y - 8, raster::hex(kKneeColour),
                      left ? "end" : "start", xml_escape(label));
    }
  }
  if (L.points.empty()) {
    out += fmt::format("<text x=\"{}\" y=\"{}\" text-anchor=\"middle\">no finite values</text>\n",
                       L.left + L.plot_width / 2, L.top + L.plot_height / 2);
  }
  out += "</svg>\n";
  return out;
}

// Parallel coordinates of all objectives (each axis from worst at the bottom to best at the top).
std::string parallel_svg(const ParetoFront& front) {
  const std::size_t m = front.objectives.size();
  const int width = std::max(680, static_cast<int>(150 * m)), height = 420;
  const int left = 80, right = 80, top = 60, bottom = 60;
  const double spacing = (width - left - right) / static_cast<double>(m - 1);
  std::vector<double> low(m, std::numeric_limits<double>::infinity()),
      high(m, -std::numeric_limits<double>::infinity());
  for (const ParetoDesign& d : front.designs) {
    for (std::size_t k = 0; k < m; ++k) {
      if (!std::isfinite(d.objectives[k])) continue;
      low[k] = std::min(low[k], d.objectives[k]);
      high[k] = std::max(high[k], d.objectives[k]);
    }
  }
  auto screen_y = [&](std::size_t k, double v) {
    double t = high[k] > low[k] ? (v - low[k]) / (high[k] - low[k]) : 0.5;
    if (front.objectives[k].sense != "maximize") t = 1.0 - t;  // best at the top
    return top + (height - top - bottom) * (1.0 - t);
  };
  std::string out = fmt::format(
      "<svg id=\"parallel\" width=\"{0}\" height=\"{1}\" viewBox=\"0 0 {0} {1}\" "
      "font-family=\"sans-serif\" font-size=\"12\">\n"
      "<rect width=\"{0}\" height=\"{1}\" fill=\"#ffffff\"/>\n"
      "<text x=\"{2}\" y=\"20\" font-size=\"15\">parallel coordinates: every objective, best at "
      "the top</text>\n",
      width, height, left);
  const int knee = front.knee ? front.design_index(*front.knee) : -1;
  std::vector<std::size_t> order;
  for (std::size_t d = 0; d < front.designs.size(); ++d) {
    if (static_cast<int>(d) != knee) order.push_back(d);
  }
  if (knee >= 0) order.push_back(static_cast<std::size_t>(knee));
  for (std::size_t d : order) {
    const ParetoDesign& design = front.designs[d];
    std::string points;
    bool complete = true;
    for (std::size_t k = 0; k < m; ++k) {
      if (!std::isfinite(design.objectives[k])) complete = false;
      points +=
          fmt::format("{:.1f},{:.1f} ", left + spacing * k, screen_y(k, design.objectives[k]));
    }
    if (!complete) continue;
    const bool is_knee = static_cast<int>(d) == knee;
    const Rgb colour =
        is_knee ? kKneeColour : (design.feasible ? kFeasibleColour : kInfeasibleColour);
    out += fmt::format(
        "<polyline class=\"pc{}\" data-id=\"{}\" points=\"{}\" fill=\"none\" stroke=\"{}\" "
        "stroke-width=\"{}\" stroke-opacity=\"{}\"/>\n",
        is_knee ? " knee" : "", xml_escape(design.id), points, raster::hex(colour),
        is_knee ? 3 : 1.5, is_knee ? 1.0 : 0.55);
  }
  for (std::size_t k = 0; k < m; ++k) {
    const double x = left + spacing * k;
    const ParetoObjective& o = front.objectives[k];
    const bool maximize = o.sense == "maximize";
    const double best = maximize ? high[k] : low[k], worst = maximize ? low[k] : high[k];
    out += fmt::format(
        "<line x1=\"{0:.1f}\" y1=\"{1}\" x2=\"{0:.1f}\" y2=\"{2}\" stroke=\"#141414\"/>\n"
        "<text x=\"{0:.1f}\" y=\"{3}\" text-anchor=\"middle\" font-weight=\"bold\">{4}</text>\n"
        "<text x=\"{0:.1f}\" y=\"{5}\" text-anchor=\"middle\">{6}</text>\n"
        "<text x=\"{0:.1f}\" y=\"{7}\" text-anchor=\"middle\">{8}</text>\n",
        x, top, height - bottom, top - 22, xml_escape(o.name), top - 8,
        std::isfinite(best) ? short_number(best) : "", height - bottom + 16,
        std::isfinite(worst) ? short_number(worst) : "");
    out += fmt::format("<text x=\"{:.1f}\" y=\"{}\" text-anchor=\"middle\">{}{}</text>\n", x,
                       height - bottom + 32, o.unit.empty() ? "" : "[" + xml_escape(o.unit) + "] ",
                       maximize ? "max" : "min");
  }
  out += "</svg>\n";
  return out;
}

// ---------------------------------------------------------------------------------------------
// HTML

// Hover: every element with data-id shows that design; all of its elements are highlighted.

std::string html_number(double v) { return std::isfinite(v) ? format_number(v) : "-"; }

std::string unit_suffix(const std::string& unit) { return unit.empty() ? "" : " " + unit; }

std::string knee_table(const ParetoFront& front, const ParetoDesign& d) {
  std::string out = "<table>\n<tr><th>quantity</th><th>value</th><th>unit</th><th></th></tr>\n";
  auto row = [&](const std::string& name, double value, const std::string& unit,
                 const std::string& note) {
    out += fmt::format("<tr><td>{}</td><td class=\"num\">{}</td><td>{}</td><td>{}</td></tr>\n",
                       xml_escape(name), html_number(value), xml_escape(unit), note);
  };
  for (std::size_t p = 0; p < front.parameters.size(); ++p) {
    const ParetoParameter& par = front.parameters[p];
    row(par.name, d.parameters[p], par.unit,
        fmt::format("free, {} .. {}", short_number(par.min), short_number(par.max)));
  }
  if (!front.home_height_is_parameter()) row("home_height", d.home_height, "m", "");
  for (const auto& [name, value] : front.fixed_parameters) row(name, value, "", "fixed");
  for (std::size_t k = 0; k < front.objectives.size(); ++k) {
    const ParetoObjective& o = front.objectives[k];
    row(o.name, d.objectives[k], o.unit, "objective, " + o.sense);
  }
  for (std::size_t k = 0; k < front.constraints.size(); ++k) {
    const ParetoConstraint& c = front.constraints[k];
    const double g = d.constraints[k];
    std::string note = c.kind == "reachable"
                           ? "constraint: task reachable"
                           : fmt::format("constraint: {} {} {}", xml_escape(c.metric),
                                         c.kind == "max" ? "&le;" : "&ge;", short_number(c.bound));
    note += std::isfinite(g) && g <= 0.0 ? ", satisfied" : ", <span class=\"bad\">violated</span>";
    row(c.name, g, c.unit, note);
  }
  if (front.actuator_catalog) {
    if (d.actuator) {
      const ParetoActuator& a = *d.actuator;
      out += fmt::format(
          "<tr><td>actuator</td><td>{}</td><td></td><td>the cheapest entry of catalog {} that "
          "carries the legs: {} N, stroke {} m, cost {}, force reserve {}</td></tr>\n",
          xml_escape(a.name), xml_escape(*front.actuator_catalog), short_number(a.max_force),
          short_number(a.stroke), short_number(a.cost), html_number(a.force_reserve));
    } else {
      out +=
          "<tr><td>actuator</td><td>-</td><td></td><td><span class=\"bad\">no catalog entry "
          "carries the legs</span></td></tr>\n";
    }
  }
  out += "</table>\n";
  return out;
}

}  // namespace report_detail

using namespace report_detail;

std::string pareto_plot_svg(const ParetoFront& file_front, int x_objective, int y_objective) {
  return scatter_svg(in_display_units(file_front), x_objective, y_objective, true);
}

std::string pareto_plot_png(const ParetoFront& file_front, int x_objective, int y_objective) {
  const ParetoFront front = in_display_units(file_front);
  const ScatterLayout L = make_scatter(front, x_objective, y_objective);
  using raster::kGlyphHeight;
  using raster::kInk;
  raster::RgbImage image(L.width, L.height, raster::kWhite);
  const int bottom = L.frame_bottom();
  raster::draw_axes(image, L);
  image.text(L.left, 12, L.title, kInk);
  image.text(L.left + L.plot_width / 2 - image.text_width(L.x_label) / 2, bottom + 36, L.x_label,
             kInk);
  image.text(std::max(4, L.left - 60), L.top - 12 - kGlyphHeight, L.y_label, kInk);
  const int knee = front.knee ? front.design_index(*front.knee) : -1;
  for (const auto& p : L.points) {
    const ParetoDesign& d = front.designs[p.design];
    if (static_cast<int>(p.design) == knee) {
      image.disc(p.x, p.y, 6.5, kKneeColour);
      const std::string label = "knee " + d.id;
      const int width = image.text_width(label);
      const int x = static_cast<int>(p.x) + 9 + width > L.width - 4
                        ? static_cast<int>(p.x) - 9 - width
                        : static_cast<int>(p.x) + 9;
      image.text(x, static_cast<int>(p.y) - 8 - kGlyphHeight, label, kKneeColour);
    } else if (d.feasible) {
      image.disc(p.x, p.y, 4.5, kFeasibleColour);
    } else {
      image.ring(p.x, p.y, 4.5, 1.5, kInfeasibleColour);
    }
  }
  return image.encode_png();
}

std::optional<WorkspaceSlice> knee_workspace_slice(const ParetoFront& front,
                                                   const std::string& results_dir, int pixels) {
  if (!front.knee) return std::nullopt;
  const ParetoDesign& knee =
      front.designs[static_cast<std::size_t>(front.design_index(*front.knee))];
  if (!knee.machine_file) return std::nullopt;
  const std::string path = (std::filesystem::path(results_dir) / *knee.machine_file).string();
  const std::unique_ptr<Machine> machine = load_machine_file(path);
  WorkspaceOptions options;
  for (int k = 0; k < 6; ++k) options.wrench(k) = front.task.wrench[static_cast<std::size_t>(k)];
  const double z = front.task.centre(2) + knee.home_height;
  const auto search = workspace_search_box(*machine, {Eigen::Matrix3d::Identity()});
  Eigen::AlignedBox3d box;
  if (search && !search->isEmpty()) {
    box = *search;
  } else {  // nothing reachable: show the neighbourhood of the task
    const Eigen::Vector3d centre(front.task.centre(0), front.task.centre(1), z);
    box = Eigen::AlignedBox3d(centre - Eigen::Vector3d::Constant(0.5),
                              centre + Eigen::Vector3d::Constant(0.5));
  }
  const Eigen::Vector3d pad = 0.05 * box.sizes() + Eigen::Vector3d::Constant(0.01);
  box = Eigen::AlignedBox3d(box.min() - pad, box.max() + pad);
  const double pixel = std::max(box.sizes()(0), box.sizes()(1)) / std::max(pixels, 8);
  return compute_workspace_slice(*machine, options, box, 'z', z, pixel);
}

std::string html_escape(std::string_view text) { return xml_escape(text); }

std::string objective_axis_label(const ParetoObjective& objective) {
  return objective_label(objective);
}

std::string design_table_html(const ParetoFront& front, const ParetoDesign& design) {
  return knee_table(front, design);
}

std::string base64(const std::string& bytes) {
  static constexpr char kAlphabet[] =
      "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  out.reserve((bytes.size() + 2) / 3 * 4);
  std::size_t i = 0;
  for (; i + 2 < bytes.size(); i += 3) {
    const unsigned v = (static_cast<unsigned char>(bytes[i]) << 16) |
                       (static_cast<unsigned char>(bytes[i + 1]) << 8) |
                       static_cast<unsigned char>(bytes[i + 2]);
    out += kAlphabet[(v >> 18) & 63];
    out += kAlphabet[(v >> 12) & 63];
    out += kAlphabet[(v >> 6) & 63];
    out += kAlphabet[v & 63];
  }
  if (i < bytes.size()) {
    unsigned v = static_cast<unsigned char>(bytes[i]) << 16;
    if (i + 1 < bytes.size()) v |= static_cast<unsigned char>(bytes[i + 1]) << 8;
    out += kAlphabet[(v >> 18) & 63];
    out += kAlphabet[(v >> 12) & 63];
    out += i + 1 < bytes.size() ? kAlphabet[(v >> 6) & 63] : '=';
    out += '=';
  }
  return out;
}

}  // namespace pkmopt
