// The comparison page and plot: the fronts of every run in one scatter (SVG and PNG), the runs,
// reference and task tables and each run's knee design, in one self-contained HTML page.
#include "report/compare_report.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "io/format/csv.hpp"
#include "pkmopt/report_assets.hpp"
#include "report/compare_detail.hpp"
#include "report/raster_image.hpp"

namespace pkmopt {
namespace {

using detail::run_label;
using raster::Rgb;

// matplotlib's "tab10" colours and six marker shapes; run r gets colour r % 10, shape r % 6.
constexpr std::array<Rgb, 10> kRunColours{{{31, 119, 180},
                                           {255, 127, 14},
                                           {44, 160, 44},
                                           {214, 39, 40},
                                           {148, 103, 189},
                                           {140, 86, 75},
                                           {227, 119, 194},
                                           {127, 127, 127},
                                           {188, 189, 34},
                                           {23, 190, 207}}};
enum class Marker { kCircle, kSquare, kTriangleUp, kDiamond, kTriangleDown, kPlus };
constexpr std::array<Marker, 6> kMarkers{Marker::kCircle,       Marker::kSquare,
                                         Marker::kTriangleUp,   Marker::kDiamond,
                                         Marker::kTriangleDown, Marker::kPlus};
constexpr double kMarkerRadius = 5.0, kKneeRadius = 8.0;

Rgb run_colour(std::size_t run) { return kRunColours[run % kRunColours.size()]; }
Marker run_marker(std::size_t run) { return kMarkers[run % kMarkers.size()]; }

std::string short_number(double v) { return std::isfinite(v) ? fmt::format("{:.4g}", v) : "-"; }
std::string exact_number(double v) { return std::isfinite(v) ? format_number(v) : "null"; }

// ---------------------------------------------------------------------------------------------
// Markers: SVG path of radius r about (0, 0) (moved by a transform) and a pixel test for the PNG.

std::string marker_path(Marker marker, double r) {
  switch (marker) {
    case Marker::kCircle:
      return fmt::format(
          "M{0:.2f},0A{1:.2f},{1:.2f} 0 1,0 {2:.2f},0A{1:.2f},{1:.2f} 0 1,0 {3:.2f},0Z", -r, r, r,
          -r);
    case Marker::kSquare:
      return fmt::format("M{0:.2f},{0:.2f}H{1:.2f}V{1:.2f}H{0:.2f}Z", -0.85 * r, 0.85 * r);
    case Marker::kTriangleUp:
      return fmt::format("M0,{:.2f}L{:.2f},{:.2f}L{:.2f},{:.2f}Z", -r, 0.95 * r, 0.75 * r,
                         -0.95 * r, 0.75 * r);
    case Marker::kDiamond:
      return fmt::format("M0,{0:.2f}L{1:.2f},0L0,{1:.2f}L{0:.2f},0Z", -1.1 * r, 1.1 * r);
    case Marker::kTriangleDown:
      return fmt::format("M0,{:.2f}L{:.2f},{:.2f}L{:.2f},{:.2f}Z", r, 0.95 * r, -0.75 * r,
                         -0.95 * r, -0.75 * r);
    case Marker::kPlus: {
      const double a = 0.35 * r;
      return fmt::format(
          "M{0:.2f},{1:.2f}H{2:.2f}V{0:.2f}H{3:.2f}V{2:.2f}H{2:.2f}V{3:.2f}H{0:.2f}V{2:.2f}H{1:.2f}"
          "V{0:.2f}H{0:.2f}Z",
          -a, -r, a, r);
    }
  }
  return {};
}

// True when the offset (dx, dy) from the marker's centre lies inside the marker of radius r.
bool inside_marker(Marker marker, double dx, double dy, double r) {
  if (r <= 0.0) return false;
  switch (marker) {
    case Marker::kCircle:
      return dx * dx + dy * dy <= r * r;
    case Marker::kSquare:
      return std::abs(dx) <= 0.85 * r && std::abs(dy) <= 0.85 * r;
    case Marker::kTriangleUp:
      return dy >= -r && dy <= 0.75 * r && std::abs(dx) <= 0.95 * r * (dy + r) / (1.75 * r);
    case Marker::kDiamond:
      return std::abs(dx) + std::abs(dy) <= 1.1 * r;
    case Marker::kTriangleDown:
      return inside_marker(Marker::kTriangleUp, dx, -dy, r);
    case Marker::kPlus:
      return (std::abs(dx) <= 0.35 * r && std::abs(dy) <= r) ||
             (std::abs(dy) <= 0.35 * r && std::abs(dx) <= r);
  }
  return false;
}

// Paints a marker; `open` draws only a 1.6-pixel outline.
void paint_marker(raster::RgbImage& image, Marker marker, double cx, double cy, double r, Rgb c,
                  bool open) {
  const int x0 = static_cast<int>(std::floor(cx - 1.2 * r)),
            x1 = static_cast<int>(std::ceil(cx + 1.2 * r));
  const int y0 = static_cast<int>(std::floor(cy - 1.2 * r)),
            y1 = static_cast<int>(std::ceil(cy + 1.2 * r));
  for (int y = y0; y <= y1; ++y) {
    for (int x = x0; x <= x1; ++x) {
      const double dx = x + 0.5 - cx, dy = y + 0.5 - cy;
      if (inside_marker(marker, dx, dy, r) && !(open && inside_marker(marker, dx, dy, r - 1.6))) {
        image.set(x, y, c);
      }
    }
  }
}

// ---------------------------------------------------------------------------------------------
// The scatter's geometry, shared by the SVG and the PNG.

struct CompareLayout : raster::PlotAxes {
  int width = 760, right = 30;  // right: margin
  int legend_top = 0, legend_row = 20, height = 0;
  std::string title, x_label, y_label;
  struct Point {
    std::size_t run, design;
    double x, y;  // screen
    bool feasible, knee;
  };
  std::vector<Point> points;  // run by run, every run's knee last of all

  CompareLayout() {
    left = 100;
    top = 60;
    plot_width = 630;
    plot_height = 420;
  }
};

CompareLayout make_layout(const RunComparison& c) {
  CompareLayout L;
  L.legend_top = L.frame_bottom() + 62;
  L.height = L.legend_top + L.legend_row * static_cast<int>(c.runs.size()) + 12;
  double x_low = std::numeric_limits<double>::infinity(), x_high = -x_low;
  double y_low = x_low, y_high = -x_low;
  std::vector<CompareLayout::Point> knees;
  for (std::size_t r = 0; r < c.runs.size(); ++r) {
    const ParetoFront& front = c.runs[r].front;
    const int knee = front.knee ? front.design_index(*front.knee) : -1;
    for (std::size_t d = 0; d < front.designs.size(); ++d) {
      const double x = c.value(r, d, c.x_objective), y = c.value(r, d, c.y_objective);
      if (!std::isfinite(x) || !std::isfinite(y)) continue;
      x_low = std::min(x_low, x);
      x_high = std::max(x_high, x);
      y_low = std::min(y_low, y);
      y_high = std::max(y_high, y);
      const bool is_knee = static_cast<int>(d) == knee;
      (is_knee ? knees : L.points).push_back({r, d, x, y, front.designs[d].feasible, is_knee});
    }
  }
  L.points.insert(L.points.end(), knees.begin(), knees.end());
  raster::padded_range(x_low, x_high);
  raster::padded_range(y_low, y_high);
  L.x_low = x_low;
  L.x_high = x_high;
  L.y_low = y_low;
  L.y_high = y_high;
  for (auto& p : L.points) {
    p.x = L.screen_x(p.x);
    p.y = L.screen_y(p.y);
  }
  L.x_ticks = raster::nice_ticks(x_low, x_high, 6);
  L.y_ticks = raster::nice_ticks(y_low, y_high, 6);
  L.title = fmt::format("pareto fronts of {} runs", c.runs.size());
  L.x_label = objective_axis_label(c.shared_objectives[c.x_objective]);
  L.y_label = objective_axis_label(c.shared_objectives[c.y_objective]);
  return L;
}

std::string scatter_svg(const RunComparison& c, bool standalone) {
  const CompareLayout L = make_layout(c);
  std::string out = fmt::format(
      "<svg {}id=\"compare-scatter\" width=\"{}\" height=\"{}\" viewBox=\"0 0 {} {}\" "
      "font-family=\"sans-serif\" font-size=\"13\">\n"
      "<rect width=\"{}\" height=\"{}\" fill=\"#ffffff\"/>\n"
      "<text x=\"{}\" y=\"30\" font-size=\"15\">{}</text>\n",
      standalone ? "xmlns=\"http://www.w3.org/2000/svg\" " : "", L.width, L.height, L.width,
      L.height, L.width, L.height, L.left, html_escape(L.title));
  const int bottom = L.frame_bottom();
  out += raster::svg_axes(L);
  out += fmt::format("<text x=\"{}\" y=\"{}\" text-anchor=\"middle\">{}</text>\n",
                     L.left + L.plot_width / 2, bottom + 42, html_escape(L.x_label));
  out += fmt::format(
      "<text transform=\"translate({},{}) rotate(-90)\" text-anchor=\"middle\">{}</text>\n", 22,
      L.top + L.plot_height / 2, html_escape(L.y_label));
  // One group per run (the legend toggles it); knees last so they are drawn on top.
  for (std::size_t r = 0; r < c.runs.size(); ++r) {
    const std::string colour = raster::hex(run_colour(r));
    out += fmt::format("<g class=\"run\" data-run=\"{}\">\n", r);
    for (bool knees : {false, true}) {
      for (const auto& p : L.points) {
        if (p.run != r || p.knee != knees) continue;
        const double radius = p.knee ? kKneeRadius : kMarkerRadius;
        out += fmt::format(
            "<path class=\"mk{}\" data-run=\"{}\" data-id=\"{}\" transform=\"translate({:.2f},"
            "{:.2f})\" d=\"{}\" fill=\"{}\" stroke=\"{}\" stroke-width=\"{}\"/>\n",
            p.knee ? " knee" : "", r, html_escape(c.runs[r].front.designs[p.design].id), p.x, p.y,
            marker_path(run_marker(r), radius), p.feasible || p.knee ? colour : "#ffffff",
            p.knee ? "#000000" : colour, p.knee ? 2 : 1.5);
      }
    }
    out += "</g>\n";
  }
  for (const auto& p : L.points) {
    if (!p.knee) continue;
    out += fmt::format(
        "<text class=\"knee-label\" data-run=\"{}\" x=\"{:.1f}\" y=\"{:.1f}\" fill=\"{}\" "
        "font-size=\"12\">knee</text>\n",
        p.run, p.x + 10, p.y - 9, raster::hex(run_colour(p.run)));
  }
  if (L.points.empty()) {
    out += fmt::format("<text x=\"{}\" y=\"{}\" text-anchor=\"middle\">no finite values</text>\n",
                       L.left + L.plot_width / 2, L.top + L.plot_height / 2);
  }
  // Legend below the axes: marker, "study (model)", designs shown.
  for (std::size_t r = 0; r < c.runs.size(); ++r) {
    const double y = L.legend_top + L.legend_row * static_cast<double>(r) + 8;
    out += fmt::format(
        "<g class=\"legend\" data-run=\"{}\" style=\"cursor:pointer\">"
        "<path transform=\"translate({},{:.1f})\" d=\"{}\" fill=\"{}\" stroke=\"{}\"/>"
        "<text x=\"{}\" y=\"{:.1f}\">{} &#8212; {} designs shown, {} feasible</text></g>\n",
        r, L.left + 8, y, marker_path(run_marker(r), kMarkerRadius), raster::hex(run_colour(r)),
        raster::hex(run_colour(r)), L.left + 22, y + 4, html_escape(run_label(c.runs[r])),
        c.runs[r].shown, c.runs[r].feasible);
  }
  out += "</svg>\n";
  return out;
}

// ---------------------------------------------------------------------------------------------
// HTML

// Hover a marker: that design of that run; click a legend entry: hide or show the run.

// The designs of every run for the hover box, as JSON ("</" escaped for a <script> element).
std::string embedded_data(const RunComparison& c) {
  auto number = [](double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(); };
  nlohmann::json runs = nlohmann::json::array();
  for (const ComparedRun& run : c.runs) {
    nlohmann::json r;
    r["label"] = run_label(run);
    r["knee"] = run.front.knee ? nlohmann::json(*run.front.knee) : nlohmann::json();
    r["objectives"] = nlohmann::json::array();
    for (const auto& o : run.front.objectives) {
      r["objectives"].push_back({{"name", o.name}, {"sense", o.sense}, {"unit", o.unit}});
    }
    r["parameters"] = nlohmann::json::array();
    for (const auto& p : run.front.parameters) {
      r["parameters"].push_back({{"name", p.name}, {"unit", p.unit}});
    }
    r["designs"] = nlohmann::json::array();
    for (const ParetoDesign& d : run.front.designs) {
      nlohmann::json design{{"id", d.id}, {"feasible", d.feasible}};
      design["home_height"] = number(d.home_height);
      design["objectives"] = nlohmann::json::array();
      for (double v : d.objectives) design["objectives"].push_back(number(v));
      design["parameters"] = nlohmann::json::array();
      for (double v : d.parameters) design["parameters"].push_back(number(v));
      r["designs"].push_back(design);
    }
    runs.push_back(r);
  }
  std::string text = nlohmann::json{{"runs", runs}}.dump();
  for (std::size_t at = text.find("</"); at != std::string::npos; at = text.find("</", at + 3)) {
    text.replace(at, 2, "<\\/");
  }
  return text;
}

std::string swatch(std::size_t run) {
  return fmt::format(
      "<svg width=\"16\" height=\"16\" viewBox=\"-8 -8 16 16\"><path d=\"{}\" fill=\"{}\"/></svg>",
      marker_path(run_marker(run), kMarkerRadius), raster::hex(run_colour(run)));
}

std::string runs_table(const RunComparison& c) {
  std::string out =
      "<table id=\"runs\">\n<tr><th>run</th><th>model</th><th>results folder</th>"
      "<th>algorithm</th><th>evaluations</th><th>designs</th><th>feasible</th>"
      "<th>in hypervolume</th><th>hypervolume</th><th>hypervolume fraction</th><th>knee</th>";
  for (const auto& o : c.shared_objectives) {
    out += fmt::format("<th>knee {}</th>", html_escape(objective_axis_label(o)));
  }
  out += "</tr>\n";
  for (std::size_t r = 0; r < c.runs.size(); ++r) {
    const ComparedRun& run = c.runs[r];
    const ParetoFront& front = run.front;
    out += fmt::format(
        "<tr class=\"run-row\" data-run=\"{}\"><td>{} {}</td><td>{}</td><td><code>{}</code></td>"
        "<td>{}</td><td class=\"num\">{}</td><td class=\"num\">{}</td><td class=\"num\">{}</td>"
        "<td class=\"num\">{}</td><td class=\"num\" data-hv=\"{}\">{}</td>"
        "<td class=\"num\" data-hv-fraction=\"{}\">{}</td><td>{}</td>",
        r, swatch(r), html_escape(front.study), html_escape(front.model), html_escape(run.dir),
        html_escape(run.algorithm.value_or("-")),
        run.evaluations ? short_number(*run.evaluations) : "-", front.designs.size(), run.feasible,
        run.counted, exact_number(run.hypervolume), short_number(run.hypervolume),
        exact_number(run.hypervolume_fraction), short_number(run.hypervolume_fraction),
        front.knee ? html_escape(*front.knee) : "none");
    const int knee = front.knee ? front.design_index(*front.knee) : -1;
    for (std::size_t k = 0; k < c.shared_objectives.size(); ++k) {
      out += fmt::format(
          "<td class=\"num\">{}</td>",
          knee >= 0 ? short_number(c.value(r, static_cast<std::size_t>(knee), k)) : "-");
    }
    out += "</tr>\n";
  }
  out += "</table>\n";
  return out;
}

std::string reference_text(const RunComparison& c) {
  if (c.reference_point.empty()) {
    return "<p>No run has a feasible design with finite values of every shared objective: no "
           "hypervolume.</p>\n";
  }
  std::string out =
      "<p>Hypervolume of each run's feasible designs over the shared objectives, all runs "
      "against the same reference point: the worst value of each objective over the feasible "
      "designs of all runs, moved 10&nbsp;% of the range of all runs further away (units: the "
      "product of the objectives' units; larger is better). The fraction is the hypervolume "
      "divided by the volume of the box between the best values of all runs and the reference "
      "point.</p>\n<table id=\"reference\">\n<tr><th>objective</th><th>best of all runs</th>"
      "<th>reference point</th></tr>\n";
  for (std::size_t k = 0; k < c.shared_objectives.size(); ++k) {
    out += fmt::format(
        "<tr><td>{}</td><td class=\"num\">{}</td><td class=\"num\" data-ref=\"{}\">{}</td></tr>\n",
        html_escape(objective_axis_label(c.shared_objectives[k])), short_number(c.ideal_point[k]),
        exact_number(c.reference_point[k]), short_number(c.reference_point[k]));
  }
  return out + "</table>\n";
}

std::string tasks_table(const RunComparison& c) {
  std::string out =
      "<table id=\"tasks\">\n<tr><th>run</th><th>task centre [m]</th><th>wrench [N, N&middot;m]"
      "</th><th>tilt [&deg;]</th><th>yaw [&deg;]</th></tr>\n";
  for (std::size_t r = 0; r < c.runs.size(); ++r) {
    const ParetoTask& t = c.runs[r].front.task;
    out += fmt::format(
        "<tr><td>{} {}</td><td>[{}, {}, {}]</td><td>[{}]</td><td class=\"num\">{}</td>"
        "<td class=\"num\">{}</td></tr>\n",
        swatch(r), html_escape(run_label(c.runs[r])), short_number(t.centre(0)),
        short_number(t.centre(1)), short_number(t.centre(2)), fmt::join(t.wrench, ", "),
        short_number(t.tilt_deg), short_number(t.yaw_deg));
  }
  return out + "</table>\n";
}

}  // namespace

std::string comparison_html(const RunComparison& c) {
  std::string title;
  for (const ComparedRun& run : c.runs) {
    title += (title.empty() ? "" : " vs. ") + run.front.study;
  }
  std::string shared;
  for (const auto& o : c.shared_objectives) {
    shared += (shared.empty() ? "" : ", ") + html_escape(objective_axis_label(o));
  }
  std::string out = fmt::format(
      "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n"
      "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n"
      "<title>pkmopt comparison: {0}</title>\n<style>{1}</style>\n</head>\n<body>\n"
      "<h1>Comparison: {0}</h1>\n<p class=\"meta\">{2} runs &middot; shared objectives: {3} "
      "&middot; values in the user's sign and units</p>\n",
      html_escape(title), assets::kCompareCss, c.runs.size(), shared);
  for (const std::string& note : c.notes) {
    out += "<p class=\"note\">" + html_escape(note) + "</p>\n";
  }
  out += fmt::format(
      "<h2>Pareto fronts</h2>\n<p>{} against {}. One colour and marker per run; filled: feasible "
      "designs, open: infeasible ones; large with a black outline: each run's knee design. "
      "Hover a marker to see its design; click a legend entry to hide or show its run.</p>\n",
      html_escape(objective_axis_label(c.shared_objectives[c.y_objective])),
      html_escape(objective_axis_label(c.shared_objectives[c.x_objective])));
  out += scatter_svg(c, false);
  out += "<div id=\"tip\"></div>\n<h2>Runs</h2>\n" + runs_table(c) + reference_text(c);
  out += "<h2>Tasks</h2>\n" + tasks_table(c);
  out += "<h2>Knee designs</h2>\n";
  for (std::size_t r = 0; r < c.runs.size(); ++r) {
    const ParetoFront& front = c.runs[r].front;
    if (!front.knee) {
      out += fmt::format("<h3>{} {}</h3>\n<p>No knee design named by the run.</p>\n", swatch(r),
                         html_escape(run_label(c.runs[r])));
      continue;
    }
    const ParetoDesign& knee =
        front.designs[static_cast<std::size_t>(front.design_index(*front.knee))];
    out += fmt::format("<h3 class=\"knee-design\" data-run=\"{}\">{} {}: knee design {}</h3>\n", r,
                       swatch(r), html_escape(run_label(c.runs[r])), html_escape(knee.id));
    if (knee.machine_file) {
      out += fmt::format("<p>Machine file: <code>{}/{}</code></p>\n", html_escape(c.runs[r].dir),
                         html_escape(*knee.machine_file));
    }
    out += design_table_html(front, knee);
  }
  out += "<script type=\"application/json\" id=\"compare-data\">\n" + embedded_data(c) +
         "\n</script>\n";
  out += fmt::format("<script>{}</script>\n</body>\n</html>\n", assets::kCompareJs);
  return out;
}

std::string comparison_plot_svg(const RunComparison& c) { return scatter_svg(c, true); }

std::string comparison_plot_png(const RunComparison& c) {
  const CompareLayout L = make_layout(c);
  using raster::kGlyphHeight;
  using raster::kInk;
  raster::RgbImage image(L.width, L.height, raster::kWhite);
  const int bottom = L.frame_bottom();
  raster::draw_axes(image, L);
  image.text(L.left, 14, L.title, kInk);
  image.text(L.left + L.plot_width / 2 - image.text_width(L.x_label) / 2, bottom + 34, L.x_label,
             kInk);
  image.text(std::max(4, L.left - 60), L.top - 10 - kGlyphHeight, L.y_label, kInk);
  for (const auto& p : L.points) {
    const Rgb colour = run_colour(p.run);
    const Marker marker = run_marker(p.run);
    if (p.knee) {
      paint_marker(image, marker, p.x, p.y, kKneeRadius + 1.5, kInk, false);
      paint_marker(image, marker, p.x, p.y, kKneeRadius - 0.5, colour, false);
      image.text(static_cast<int>(p.x) + 10, static_cast<int>(p.y) - 8 - kGlyphHeight, "knee",
                 colour);
    } else {
      paint_marker(image, marker, p.x, p.y, kMarkerRadius, colour, !p.feasible);
    }
  }
  for (std::size_t r = 0; r < c.runs.size(); ++r) {
    const int y = L.legend_top + L.legend_row * static_cast<int>(r);
    paint_marker(image, run_marker(r), L.left + 8, y + kGlyphHeight / 2.0, kMarkerRadius,
                 run_colour(r), false);
    image.text(L.left + 22, y, run_label(c.runs[r]), kInk);
  }
  return image.encode_png();
}

}  // namespace pkmopt
