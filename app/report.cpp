#include "app/report.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <memory>
#include <nlohmann/json.hpp>
#include <set>

#include "app/csv.hpp"
#include "app/input_error.hpp"
#include "app/machine_file.hpp"
#include "app/raster_image.hpp"
#include "app/workspace_export.hpp"

namespace pkmopt {
namespace {

using nlohmann::json;
using raster::Rgb;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// ---------------------------------------------------------------------------------------------
// Reading pareto.json

std::string describe(const json& v) {
  switch (v.type()) {
    case json::value_t::null:
      return "null";
    case json::value_t::boolean:
      return v.get<bool>() ? "true" : "false";
    case json::value_t::number_integer:
    case json::value_t::number_unsigned:
    case json::value_t::number_float:
      return "the number " + v.dump();
    case json::value_t::string:
      return "the string " + quote_found(v.get<std::string>());
    case json::value_t::array:
      return fmt::format("an array of {} elements", v.size());
    case json::value_t::object:
      return "an object";
    default:
      return "an unsupported value";
  }
}

class ParetoReader {
 public:
  explicit ParetoReader(std::string file) : file_(std::move(file)) {}

  [[noreturn]] void fail(const std::string& key, std::string_view expected,
                         const std::string& found) const {
    throw InputError(fmt::format("{}: {}: expected {}, found {}", file_, key, expected, found));
  }

  const json& member(const json& object, const std::string& path, const std::string& key,
                     std::string_view expected) const {
    const std::string where = path.empty() ? key : path + "." + key;
    const auto it = object.find(key);
    if (it == object.end()) fail(where, expected, "no such key");
    return *it;
  }

  const json& object(const json& parent, const std::string& path, const std::string& key) const {
    const json& v = member(parent, path, key, "an object");
    if (!v.is_object()) fail(join(path, key), "an object", describe(v));
    return v;
  }

  const json& array(const json& parent, const std::string& path, const std::string& key) const {
    const json& v = member(parent, path, key, "an array");
    if (!v.is_array()) fail(join(path, key), "an array", describe(v));
    return v;
  }

  std::string string(const json& parent, const std::string& path, const std::string& key) const {
    const json& v = member(parent, path, key, "a string");
    if (!v.is_string()) fail(join(path, key), "a string", describe(v));
    return v.get<std::string>();
  }

  /// A number; null becomes NaN when `null_allowed`.
  double number(const json& parent, const std::string& path, const std::string& key,
                bool null_allowed) const {
    const std::string expected = null_allowed ? "a number or null" : "a number";
    const json& v = member(parent, path, key, expected);
    return number_value(v, join(path, key), null_allowed);
  }

  double number_value(const json& v, const std::string& where, bool null_allowed) const {
    if (v.is_null() && null_allowed) return kNaN;
    if (!v.is_number()) fail(where, null_allowed ? "a number or null" : "a number", describe(v));
    return v.get<double>();
  }

  bool boolean(const json& parent, const std::string& path, const std::string& key) const {
    const json& v = member(parent, path, key, "true or false");
    if (!v.is_boolean()) fail(join(path, key), "true or false", describe(v));
    return v.get<bool>();
  }

  static std::string join(const std::string& path, const std::string& key) {
    return path.empty() ? key : path + "." + key;
  }
  static std::string index(const std::string& path, std::size_t i) {
    return fmt::format("{}[{}]", path, i);
  }

  const std::string& file() const { return file_; }

 private:
  std::string file_;
};

json parse_json_text(const std::string& text, const std::string& file) {
  try {
    return json::parse(text);
  } catch (const json::parse_error& e) {
    // e.byte: 1-based index of the last byte read.
    const std::size_t end = std::min<std::size_t>(e.byte > 0 ? e.byte - 1 : 0, text.size());
    int line = 1, column = 1;
    for (std::size_t i = 0; i < end; ++i) {
      if (text[i] == '\n') {
        ++line;
        column = 1;
      } else {
        ++column;
      }
    }
    std::string detail = e.what();
    const auto colon = detail.find(": ", detail.find("column"));
    if (colon != std::string::npos) detail = detail.substr(colon + 2);
    throw InputError(fmt::format("{}expected JSON, found a syntax error ({})",
                                 location_prefix(file, line, column), detail));
  }
}

// Reads {"name": number|null, ...} for exactly the names given, in that order.
std::vector<double> named_values(const ParetoReader& r, const json& parent, const std::string& path,
                                 const std::string& key, const std::vector<std::string>& names) {
  const json& values = r.object(parent, path, key);
  const std::string where = ParetoReader::join(path, key);
  std::vector<double> out;
  for (const std::string& name : names) out.push_back(r.number(values, where, name, true));
  for (const auto& [name, value] : values.items()) {
    if (std::find(names.begin(), names.end(), name) == names.end()) {
      r.fail(ParetoReader::join(where, name), "one of the names listed at the top of the file",
             quote_found(name));
    }
  }
  return out;
}

json number_or_null(double v) { return std::isfinite(v) ? json(v) : json(nullptr); }

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

constexpr std::string_view kStyle = R"(
body{font-family:sans-serif;margin:24px;color:#141414;max-width:1400px}
h1{margin-bottom:4px}.meta{color:#555}
.plots{display:flex;flex-wrap:wrap;gap:16px;align-items:flex-start}
table{border-collapse:collapse;font-size:13px}
td,th{border:1px solid #ddd;padding:3px 8px;text-align:left}
td.num{text-align:right;font-variant-numeric:tabular-nums}
tr.hl td{background:#ffe9a8}
circle.pt{cursor:pointer}
circle.hl{stroke:#000;stroke-width:3px}
polyline.hl{stroke:#000;stroke-width:3.5px;stroke-opacity:1}
#tip{position:absolute;display:none;background:#fff;border:1px solid #888;padding:6px;
 box-shadow:2px 2px 6px rgba(0,0,0,.25);font-size:12px;pointer-events:none;z-index:10}
#tip td,#tip th{border:none;padding:1px 6px}
#tip .sec{font-weight:bold;padding-top:4px}
.bad{color:#b00}
)";

// Hover: every element with data-id shows that design; all of its elements are highlighted.
constexpr std::string_view kScript = R"(
(function () {
  const data = JSON.parse(document.getElementById('report-data').textContent);
  const byId = {};
  data.designs.forEach(function (d) { byId[d.id] = d; });
  const homeIsParameter = data.parameters.some(function (p) { return p.name === 'home_height'; });
  const tip = document.getElementById('tip');
  function esc(s) {
    return String(s).replace(/[&<>"]/g, function (c) {
      return {'&': '&amp;', '<': '&lt;', '>': '&gt;', '"': '&quot;'}[c];
    });
  }
  function num(v) {
    if (v === null || v === undefined) return '-';
    const a = Math.abs(v);
    return (a !== 0 && (a >= 1e5 || a < 1e-3)) ? v.toExponential(4) : String(+v.toPrecision(6));
  }
  function row(name, value, unit) {
    return '<tr><th>' + esc(name) + '</th><td>' + num(value) + (unit ? ' ' + esc(unit) : '') +
        '</td></tr>';
  }
  function section(title) { return '<tr><td colspan="2" class="sec">' + title + '</td></tr>'; }
  function describe(d) {
    let h = '<b>' + esc(d.id) + '</b>' + (d.id === data.knee ? ' (knee)' : '') +
        (d.feasible ? '' : ' <span class="bad">infeasible</span>') + '<table>';
    h += section('parameters');
    data.parameters.forEach(function (p) { h += row(p.name, d.parameters[p.name], p.unit); });
    if (!homeIsParameter) h += row('home_height', d.home_height, 'm');
    h += section('objectives');
    data.objectives.forEach(function (o) {
      h += row(o.name + ' (' + (o.sense === 'maximize' ? 'max' : 'min') + ')',
               d.objectives[o.name], o.unit);
    });
    if (data.constraints.length > 0) {
      h += section('constraints (g &le; 0 satisfied)');
      data.constraints.forEach(function (c) { h += row(c.name, d.constraints[c.name], c.unit); });
    }
    if (d.actuator !== undefined) {
      h += section('actuator');
      h += d.actuator ? '<tr><th>' + esc(d.actuator.name) + '</th><td>' +
              num(d.actuator.max_force) + ' N, ' + num(d.actuator.stroke) + ' m</td></tr>'
                      : '<tr><td colspan="2" class="bad">no entry carries the legs</td></tr>';
    }
    return h + '</table>';
  }
  function mark(id, on) {
    document.querySelectorAll('[data-id="' + id + '"]').forEach(function (e) {
      e.classList.toggle('hl', on);
    });
  }
  document.querySelectorAll('[data-id]').forEach(function (e) {
    const id = e.getAttribute('data-id');
    e.addEventListener('mouseenter', function () {
      if (!byId[id]) return;
      tip.innerHTML = describe(byId[id]);
      tip.style.display = 'block';
      mark(id, true);
    });
    e.addEventListener('mousemove', function (ev) {
      tip.style.left = (ev.pageX + 14) + 'px';
      tip.style.top = (ev.pageY + 14) + 'px';
    });
    e.addEventListener('mouseleave', function () {
      tip.style.display = 'none';
      mark(id, false);
    });
  });
})();
)";

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

std::string designs_table(const ParetoFront& front) {
  std::string out = "<table id=\"designs\">\n<tr><th>id</th>";
  for (const auto& p : front.parameters) {
    out += fmt::format("<th>{}</th>",
                       xml_escape(p.name + unit_suffix(p.unit.empty() ? "" : "[" + p.unit + "]")));
  }
  if (!front.home_height_is_parameter()) out += "<th>home_height [m]</th>";
  for (const auto& o : front.objectives)
    out += fmt::format("<th>{}</th>", xml_escape(objective_label(o)));
  for (const auto& c : front.constraints) out += fmt::format("<th>{}</th>", xml_escape(c.name));
  if (front.actuator_catalog) out += "<th>actuator</th>";
  out += "<th>feasible</th></tr>\n";
  for (const ParetoDesign& d : front.designs) {
    out += fmt::format("<tr data-id=\"{0}\"><td>{0}{1}</td>", xml_escape(d.id),
                       front.knee && *front.knee == d.id ? " (knee)" : "");
    for (double v : d.parameters) out += fmt::format("<td class=\"num\">{}</td>", html_number(v));
    if (!front.home_height_is_parameter()) {
      out += fmt::format("<td class=\"num\">{}</td>", html_number(d.home_height));
    }
    for (double v : d.objectives) out += fmt::format("<td class=\"num\">{}</td>", html_number(v));
    for (double v : d.constraints) out += fmt::format("<td class=\"num\">{}</td>", html_number(v));
    if (front.actuator_catalog)
      out += fmt::format("<td>{}</td>", d.actuator ? xml_escape(d.actuator->name) : "-");
    out += fmt::format("<td>{}</td></tr>\n", d.feasible ? "yes" : "<span class=\"bad\">no</span>");
  }
  out += "</table>\n";
  return out;
}

}  // namespace

int ParetoFront::design_index(const std::string& id) const {
  for (std::size_t d = 0; d < designs.size(); ++d) {
    if (designs[d].id == id) return static_cast<int>(d);
  }
  return -1;
}

bool ParetoFront::home_height_is_parameter() const {
  return std::any_of(parameters.begin(), parameters.end(),
                     [](const ParetoParameter& p) { return p.name == "home_height"; });
}

ParetoFront read_pareto_json(const std::string& path) {
  const std::string text = read_input_file(path);
  const json root = parse_json_text(text, path);
  const ParetoReader r(path);
  if (!root.is_object()) r.fail("(top level)", "an object", describe(root));
  ParetoFront front;
  front.file = path;
  front.format = r.string(root, "", "format");
  if (front.format != "pkmopt-pareto-1") {
    r.fail("format", "'pkmopt-pareto-1'", quote_found(front.format));
  }
  front.pkmopt_version = r.string(root, "", "pkmopt_version");
  front.study = r.string(root, "", "study");
  front.description = r.string(root, "", "description");
  front.model = r.string(root, "", "model");

  std::set<std::string> names;  // every column name must be unique
  auto unique = [&](const std::string& where, const std::string& name) {
    if (name.empty()) r.fail(where, "a non-empty name", "''");
    if (!names.insert(name).second) r.fail(where, "a name used once", quote_found(name));
  };
  const json& parameters = r.array(root, "", "parameters");
  for (std::size_t i = 0; i < parameters.size(); ++i) {
    const std::string where = ParetoReader::index("parameters", i);
    const json& p = parameters[i];
    if (!p.is_object()) r.fail(where, "an object", describe(p));
    ParetoParameter par;
    par.name = r.string(p, where, "name");
    unique(where + ".name", par.name);
    par.unit = r.string(p, where, "unit");
    par.min = r.number(p, where, "min", false);
    par.max = r.number(p, where, "max", false);
    front.parameters.push_back(par);
  }
  const json& fixed = r.object(root, "", "fixed_parameters");
  for (const auto& [name, value] : fixed.items()) {
    front.fixed_parameters.emplace_back(
        name, r.number_value(value, ParetoReader::join("fixed_parameters", name), false));
  }
  const json& objectives = r.array(root, "", "objectives");
  for (std::size_t i = 0; i < objectives.size(); ++i) {
    const std::string where = ParetoReader::index("objectives", i);
    const json& o = objectives[i];
    if (!o.is_object()) r.fail(where, "an object", describe(o));
    ParetoObjective obj;
    obj.name = r.string(o, where, "name");
    unique(where + ".name", obj.name);
    obj.sense = r.string(o, where, "sense");
    if (obj.sense != "minimize" && obj.sense != "maximize") {
      r.fail(where + ".sense", "'minimize' or 'maximize'", quote_found(obj.sense));
    }
    obj.unit = r.string(o, where, "unit");
    front.objectives.push_back(obj);
  }
  if (front.objectives.empty()) r.fail("objectives", "at least one objective", "an empty array");
  const json& constraints = r.array(root, "", "constraints");
  for (std::size_t i = 0; i < constraints.size(); ++i) {
    const std::string where = ParetoReader::index("constraints", i);
    const json& c = constraints[i];
    if (!c.is_object()) r.fail(where, "an object", describe(c));
    ParetoConstraint con;
    con.name = r.string(c, where, "name");
    unique(where + ".name", con.name);
    con.metric = r.string(c, where, "metric");
    con.kind = r.string(c, where, "kind");
    if (con.kind != "max" && con.kind != "min" && con.kind != "reachable") {
      r.fail(where + ".kind", "'max', 'min' or 'reachable'", quote_found(con.kind));
    }
    con.bound = r.number(c, where, "bound", false);
    con.unit = r.string(c, where, "unit");
    front.constraints.push_back(con);
  }
  const json& task = r.object(root, "", "task");
  const json& centre = r.array(task, "task", "centre");
  if (centre.size() != 3) r.fail("task.centre", "3 numbers", describe(centre));
  for (int k = 0; k < 3; ++k) {
    front.task.centre(k) = r.number_value(centre[static_cast<std::size_t>(k)],
                                          ParetoReader::index("task.centre", k), false);
  }
  const json& wrench = r.array(task, "task", "wrench");
  if (wrench.size() != 6) r.fail("task.wrench", "6 numbers", describe(wrench));
  for (std::size_t k = 0; k < 6; ++k) {
    front.task.wrench[k] = r.number_value(wrench[k], ParetoReader::index("task.wrench", k), false);
  }
  front.task.tilt_deg = r.number(task, "task", "tilt_deg", false);
  front.task.yaw_deg = r.number(task, "task", "yaw_deg", false);

  if (root.contains("actuator_catalog") && !root["actuator_catalog"].is_null())
    front.actuator_catalog =
        r.string(r.object(root, "", "actuator_catalog"), "actuator_catalog", "name");
  std::vector<std::string> parameter_names, objective_names, constraint_names;
  for (const auto& p : front.parameters) parameter_names.push_back(p.name);
  for (const auto& o : front.objectives) objective_names.push_back(o.name);
  for (const auto& c : front.constraints) constraint_names.push_back(c.name);
  const json& designs = r.array(root, "", "designs");
  for (std::size_t i = 0; i < designs.size(); ++i) {
    const std::string where = ParetoReader::index("designs", i);
    const json& d = designs[i];
    if (!d.is_object()) r.fail(where, "an object", describe(d));
    ParetoDesign design;
    design.id = r.string(d, where, "id");
    if (design.id.empty()) r.fail(where + ".id", "a non-empty id", "''");
    if (front.design_index(design.id) >= 0) {
      r.fail(where + ".id", "an id used once", quote_found(design.id));
    }
    design.parameters = named_values(r, d, where, "parameters", parameter_names);
    design.home_height = r.number(d, where, "home_height", false);
    design.objectives = named_values(r, d, where, "objectives", objective_names);
    design.constraints = named_values(r, d, where, "constraints", constraint_names);
    design.feasible = r.boolean(d, where, "feasible");
    if (d.contains("actuator") && !d["actuator"].is_null()) {
      const std::string a = where + ".actuator";
      const json& actuator = r.object(d, where, "actuator");
      design.actuator =
          ParetoActuator{.name = r.string(actuator, a, "name"),
                         .max_force = r.number(actuator, a, "max_force", false),
                         .stroke = r.number(actuator, a, "stroke", false),
                         .cost = r.number(actuator, a, "cost", false),
                         .force_reserve = r.number(actuator, a, "force_reserve", true)};
    }
    if (d.contains("machine_file")) {
      const std::string file = r.string(d, where, "machine_file");
      if (file.empty() || std::filesystem::path(file).is_absolute()) {
        r.fail(where + ".machine_file", "a path relative to the results folder", quote_found(file));
      }
      design.machine_file = file;
    }
    front.designs.push_back(std::move(design));
  }
  const json& knee = r.member(root, "", "knee", "a design id or null");
  if (!knee.is_null()) {
    if (!knee.is_string()) r.fail("knee", "a design id or null", describe(knee));
    const std::string id = knee.get<std::string>();
    if (front.design_index(id) < 0)
      r.fail("knee", "the id of a design in `designs`", quote_found(id));
    front.knee = id;
  }
  return front;
}

std::string pareto_csv(const ParetoFront& front) {
  std::vector<std::string> header{"id"};
  for (const auto& p : front.parameters) header.push_back(p.name);
  const bool home_column = !front.home_height_is_parameter();
  if (home_column) header.push_back("home_height");
  for (const auto& o : front.objectives) header.push_back(o.name);
  for (const auto& c : front.constraints) header.push_back(c.name);
  if (front.actuator_catalog) header.push_back("actuator");
  header.push_back("feasible");
  header.push_back("knee");
  std::string out;
  for (std::size_t k = 0; k < header.size(); ++k) out += (k ? "," : "") + csv_field(header[k]);
  out += '\n';
  auto cell = [](double v) { return std::isfinite(v) ? format_number(v) : std::string(); };
  for (const ParetoDesign& d : front.designs) {
    out += csv_field(d.id);
    for (double v : d.parameters) out += ',' + cell(v);
    if (home_column) out += ',' + cell(d.home_height);
    for (double v : d.objectives) out += ',' + cell(v);
    for (double v : d.constraints) out += ',' + cell(v);
    if (front.actuator_catalog) out += ',' + (d.actuator ? csv_field(d.actuator->name) : "");
    out += d.feasible ? ",1" : ",0";
    out += front.knee && *front.knee == d.id ? ",1" : ",0";
    out += '\n';
  }
  return out;
}

std::string pareto_json(const ParetoFront& front) {
  nlohmann::ordered_json root;
  root["format"] = front.format;
  root["pkmopt_version"] = front.pkmopt_version;
  root["study"] = front.study;
  root["description"] = front.description;
  root["model"] = front.model;
  root["parameters"] = nlohmann::ordered_json::array();
  for (const auto& p : front.parameters) {
    root["parameters"].push_back(
        {{"name", p.name}, {"unit", p.unit}, {"min", p.min}, {"max", p.max}});
  }
  root["fixed_parameters"] = nlohmann::ordered_json::object();
  for (const auto& [name, value] : front.fixed_parameters) root["fixed_parameters"][name] = value;
  root["objectives"] = nlohmann::ordered_json::array();
  for (const auto& o : front.objectives) {
    root["objectives"].push_back({{"name", o.name}, {"sense", o.sense}, {"unit", o.unit}});
  }
  root["constraints"] = nlohmann::ordered_json::array();
  for (const auto& c : front.constraints) {
    root["constraints"].push_back({{"name", c.name},
                                   {"metric", c.metric},
                                   {"kind", c.kind},
                                   {"bound", c.bound},
                                   {"unit", c.unit}});
  }
  if (front.actuator_catalog) root["actuator_catalog"] = {{"name", *front.actuator_catalog}};
  root["task"] = {{"centre", {front.task.centre(0), front.task.centre(1), front.task.centre(2)}},
                  {"wrench", front.task.wrench},
                  {"tilt_deg", front.task.tilt_deg},
                  {"yaw_deg", front.task.yaw_deg}};
  root["designs"] = nlohmann::ordered_json::array();
  for (const ParetoDesign& d : front.designs) {
    nlohmann::ordered_json design;
    design["id"] = d.id;
    design["parameters"] = nlohmann::ordered_json::object();
    for (std::size_t k = 0; k < d.parameters.size(); ++k) {
      design["parameters"][front.parameters[k].name] = number_or_null(d.parameters[k]);
    }
    design["home_height"] = d.home_height;
    design["objectives"] = nlohmann::ordered_json::object();
    for (std::size_t k = 0; k < d.objectives.size(); ++k) {
      design["objectives"][front.objectives[k].name] = number_or_null(d.objectives[k]);
    }
    design["constraints"] = nlohmann::ordered_json::object();
    for (std::size_t k = 0; k < d.constraints.size(); ++k) {
      design["constraints"][front.constraints[k].name] = number_or_null(d.constraints[k]);
    }
    if (front.actuator_catalog) {
      design["actuator"] = nullptr;
      if (const auto& a = d.actuator)
        design["actuator"] = {{"name", a->name},
                              {"max_force", a->max_force},
                              {"stroke", a->stroke},
                              {"cost", a->cost},
                              {"force_reserve", number_or_null(a->force_reserve)}};
    }
    design["feasible"] = d.feasible;
    if (d.machine_file) design["machine_file"] = *d.machine_file;
    root["designs"].push_back(design);
  }
  root["knee"] = front.knee ? nlohmann::ordered_json(*front.knee) : nlohmann::ordered_json();
  return root.dump(2) + "\n";
}

std::string pareto_plot_svg(const ParetoFront& front, int x_objective, int y_objective) {
  return scatter_svg(front, x_objective, y_objective, true);
}

std::string pareto_plot_png(const ParetoFront& front, int x_objective, int y_objective) {
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

std::string report_html(const ParetoFront& front, const WorkspaceSlice* knee_slice) {
  int feasible = 0;
  for (const auto& d : front.designs) feasible += d.feasible ? 1 : 0;
  std::string data = pareto_json(front);
  // Inside <script>, "</" could end the element: JSON allows "\/" for "/".
  for (std::size_t at = data.find("</"); at != std::string::npos; at = data.find("</", at + 3)) {
    data.replace(at, 2, "<\\/");
  }
  std::string out = fmt::format(
      "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n"
      "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n"
      "<title>pkmopt report: {0}</title>\n<style>{1}</style>\n</head>\n<body>\n"
      "<h1>{0}</h1>\n",
      xml_escape(front.study), kStyle);
  if (!front.description.empty()) out += "<p>" + xml_escape(front.description) + "</p>\n";
  std::string objective_list;
  for (const auto& o : front.objectives) {
    objective_list += (objective_list.empty() ? "" : ", ") + xml_escape(objective_label(o));
  }
  out += fmt::format(
      "<p class=\"meta\">model {} &middot; {} Pareto designs ({} feasible) &middot; objectives: "
      "{} &middot; written by pkmopt {} from {}</p>\n",
      xml_escape(front.model), front.designs.size(), feasible, objective_list,
      xml_escape(front.pkmopt_version), xml_escape(front.file));
  out +=
      "<h2>Pareto front</h2>\n<p>Hover a point, a line or a table row to see its design. "
      "Filled blue: feasible; open grey: infeasible; red: the knee design.";
  if (front.objectives.size() >= 3) {
    out += fmt::format(
        " The scatter shows the first two objectives; the parallel coordinates "
        "all {}.",
        front.objectives.size());
  }
  out += "</p>\n<div class=\"plots\">\n";
  out += scatter_svg(front, 0, 1, false);
  if (front.objectives.size() >= 3) out += parallel_svg(front);
  out += "</div>\n<div id=\"tip\"></div>\n";

  if (front.knee) {
    const ParetoDesign& knee =
        front.designs[static_cast<std::size_t>(front.design_index(*front.knee))];
    out += fmt::format("<h2>Knee design {}</h2>\n", xml_escape(knee.id));
    out +=
        "<p>The knee of the front as chosen by <code>pkmopt run</code> (the design with the "
        "best balance of the objectives).";
    if (knee.machine_file) {
      out += fmt::format(
          " Machine file: <code>{}</code> (for <code>pkmopt analyze</code> and "
          "<code>pkmopt workspace</code>).",
          xml_escape(*knee.machine_file));
    }
    out += "</p>\n" + knee_table(front, knee);
    if (knee_slice) {
      const double z = front.task.centre(2) + knee.home_height;
      out += fmt::format(
          "<h3>Workspace slice of {}</h3>\n<p>Plane z = {} mm in the machine's base frame (the "
          "task centre's height: task z {} mm + home_height {} mm), constant orientation "
          "(rx = ry = rz = 0), coloured by singularity_margin (1/cond of the Jacobian, "
          "0..1, low = dark); grey: not reachable.</p>\n"
          "<img alt=\"workspace slice of {}\" src=\"data:image/png;base64,{}\">\n",
          xml_escape(knee.id), short_number(1e3 * z), short_number(1e3 * front.task.centre(2)),
          short_number(1e3 * knee.home_height), xml_escape(knee.id),
          base64(slice_png(*knee_slice, SliceMetric::kSingularityMargin)));
    } else {
      out +=
          "<p>No workspace slice: the knee design has no machine file "
          "(<code>output: {designs: true}</code> in the study writes them).</p>\n";
    }
  } else {
    out += "<h2>Knee design</h2>\n<p>None: the run named no knee design.</p>\n";
  }

  out += "<h2>All Pareto designs</h2>\n" + designs_table(front);
  out += "<h2>Study</h2>\n<table>\n";
  auto row = [&](const std::string& name, const std::string& value) {
    out += fmt::format("<tr><th>{}</th><td>{}</td></tr>\n", xml_escape(name), value);
  };
  for (const auto& p : front.parameters) {
    row(p.name, fmt::format("free, {} .. {}{}", short_number(p.min), short_number(p.max),
                            xml_escape(unit_suffix(p.unit))));
  }
  for (const auto& [name, value] : front.fixed_parameters) {
    row(name, "fixed, " + html_number(value));
  }
  row("task centre",
      fmt::format("[{}, {}, {}] m", html_number(front.task.centre(0)),
                  html_number(front.task.centre(1)), html_number(front.task.centre(2))));
  row("task wrench", fmt::format("[{}] N, N&middot;m", fmt::join(front.task.wrench, ", ")));
  row("task tilt, yaw", fmt::format("{}&deg;, {}&deg;", html_number(front.task.tilt_deg),
                                    html_number(front.task.yaw_deg)));
  for (const auto& c : front.constraints) {
    row(c.name,
        c.kind == "reachable"
            ? "every task pose reachable"
            : fmt::format("{} {} {}{}", xml_escape(c.metric), c.kind == "max" ? "&le;" : "&ge;",
                          html_number(c.bound), xml_escape(unit_suffix(c.unit))));
  }
  if (front.actuator_catalog)
    row("actuators", fmt::format("each design's cheapest entry of catalog {} that carries its legs",
                                 xml_escape(*front.actuator_catalog)));
  out += "</table>\n";
  out += "<script type=\"application/json\" id=\"report-data\">\n" + data + "</script>\n";
  out += fmt::format("<script>{}</script>\n</body>\n</html>\n", kScript);
  return out;
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
