// The HTML report of a design study's front (report_html, report/pareto_report.hpp): the page's
// skeleton, the pictures made here (parallel coordinates, convergence, knee slice, drawings) and
// the data the page's script (report/assets/report.js) renders the scatter, the tables and the
// comparison from.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <memory>
#include <nlohmann/json.hpp>

#include "io/machine/machine_file.hpp"
#include "optimizer/indicators.hpp"
#include "pkmopt/report_assets.hpp"
#include "report/display_units.hpp"
#include "report/machine_drawing.hpp"
#include "report/pareto_report.hpp"
#include "report/pareto_report_detail.hpp"
#include "report/raster_image.hpp"
#include "report/workspace_export.hpp"

namespace pkmopt {
namespace {

using namespace report_detail;
using nlohmann::json;

// A fixed parameter's unit: pareto.json lists fixed parameters by name and value in file units
// (degrees for names ending in _deg, metres otherwise).
std::string fixed_parameter_unit(const std::string& name) {
  return name.ends_with("_deg") ? "deg" : "m";
}

// A quantity for the page: its name, display unit and scale (the unit from `unit_name`, the
// metric a constraint bounds, or the quantity itself).
json quantity_json(const std::string& name, const std::string& unit_name, const std::string& unit) {
  const EngineeringUnit e = engineering_unit(unit_name, unit);
  return {{"name", name}, {"unit", e.unit}, {"scale", e.scale}};
}

json finite_or_null(double v) { return std::isfinite(v) ? json(v) : json(nullptr); }

// What the page's script needs: the front in file units with each quantity's display unit.
json report_data(const ParetoFront& front, const std::map<std::string, std::string>& drawings) {
  json data;
  data["study"] = front.study;
  data["knee"] = front.knee ? json(*front.knee) : json(nullptr);
  data["compromise"] = front.compromise ? json(*front.compromise) : json(nullptr);
  data["high_trade_off"] = front.high_trade_off;
  data["home_free"] = front.home_height_is_parameter();
  data["home"] = quantity_json("home_height", "home_height", "m");
  data["parameters"] = json::array();
  for (const ParetoParameter& p : front.parameters) {
    json j = quantity_json(p.name, p.name, p.unit);
    j["min"] = p.min;
    j["max"] = p.max;
    data["parameters"].push_back(j);
  }
  data["fixed"] = json::array();
  for (const auto& [name, value] : front.fixed_parameters) {
    json j = quantity_json(name, name, fixed_parameter_unit(name));
    j["value"] = value;
    data["fixed"].push_back(j);
  }
  data["objectives"] = json::array();
  for (const ParetoObjective& o : front.objectives) {
    json j = quantity_json(o.name, o.name, o.unit);
    j["sense"] = o.sense;
    data["objectives"].push_back(j);
  }
  data["constraints"] = json::array();
  for (const ParetoConstraint& c : front.constraints) {
    json j = quantity_json(c.name, c.metric, c.unit);
    j["metric"] = c.metric;
    j["kind"] = c.kind;
    j["bound"] = c.bound;
    data["constraints"].push_back(j);
  }
  data["designs"] = json::array();
  for (const ParetoDesign& d : front.designs) {
    json j;
    j["id"] = d.id;
    j["parameters"] = json::array();
    for (double v : d.parameters) j["parameters"].push_back(finite_or_null(v));
    j["home_height"] = finite_or_null(d.home_height);
    j["objectives"] = json::array();
    for (double v : d.objectives) j["objectives"].push_back(finite_or_null(v));
    j["constraints"] = json::array();
    for (double v : d.constraints) j["constraints"].push_back(finite_or_null(v));
    j["feasible"] = d.feasible;
    if (front.actuator_catalog)
      j["actuator"] = d.actuator
                          ? json{{"name", d.actuator->name},
                                 {"max_force", d.actuator->max_force},
                                 {"stroke", d.actuator->stroke},
                                 {"force_reserve", finite_or_null(d.actuator->force_reserve)}}
                          : json(nullptr);
    if (d.machine_file) j["machine_file"] = *d.machine_file;
    data["designs"].push_back(j);
  }
  data["drawings"] = drawings;
  return data;
}

// The study's settings: free parameters with their ranges, fixed ones, the task, the constraints.
std::string study_table(const ParetoFront& front) {
  std::string out = "<table class=\"study\">\n";
  auto row = [&](const std::string& name, const std::string& value) {
    out += fmt::format("<tr><th>{}</th><td>{}</td></tr>\n", xml_escape(name), value);
  };
  auto shown = [](const std::string& name, const std::string& unit, double v) {
    const EngineeringUnit e = engineering_unit(name, unit);
    return fmt::format("{:.5g}{}{}", e.scale * v, e.unit.empty() ? "" : " ", xml_escape(e.unit));
  };
  for (const ParetoParameter& p : front.parameters) {
    const EngineeringUnit e = engineering_unit(p.name, p.unit);
    row(p.name, fmt::format("free, {:.5g} .. {:.5g}{}{}", e.scale * p.min, e.scale * p.max,
                            e.unit.empty() ? "" : " ", xml_escape(e.unit)));
  }
  for (const auto& [name, value] : front.fixed_parameters)
    row(name, "fixed, " + shown(name, fixed_parameter_unit(name), value));
  const Eigen::Vector3d& c = front.task.centre;
  row("task centre", fmt::format("({:.5g}, {:.5g}, {:.5g}) mm, before each design's home_height "
                                 "lift",
                                 1e3 * c.x(), 1e3 * c.y(), 1e3 * c.z()));
  if (const auto& p = front.task.positions)
    row("task positions",
        fmt::format("x {:.5g} .. {:.5g}, y {:.5g} .. {:.5g}, z {:.5g} .. {:.5g} mm",
                    1e3 * p->first.x(), 1e3 * p->second.x(), 1e3 * p->first.y(),
                    1e3 * p->second.y(), 1e3 * p->first.z(), 1e3 * p->second.z()));
  const auto& w = front.task.wrench;
  row("task wrench", fmt::format("force ({:.5g}, {:.5g}, {:.5g}) kN, moment ({:.5g}, {:.5g}, "
                                 "{:.5g}) N&middot;m",
                                 1e-3 * w[0], 1e-3 * w[1], 1e-3 * w[2], w[3], w[4], w[5]));
  row("task tilt, yaw",
      fmt::format("{:.5g}&deg;, &plusmn;{:.5g}&deg;", front.task.tilt_deg, front.task.yaw_deg));
  for (const ParetoConstraint& k : front.constraints)
    row(k.name, k.kind == "reachable" ? std::string("every task pose reachable")
                                      : fmt::format("{} {} {}", xml_escape(k.metric),
                                                    k.kind == "max" ? "&le;" : "&ge;",
                                                    shown(k.metric, k.unit, k.bound)));
  if (front.actuator_catalog)
    row("actuators", fmt::format("each design's cheapest entry of catalog {} that carries its legs",
                                 xml_escape(*front.actuator_catalog)));
  if (const auto& sel = front.selection)
    row("front", fmt::format("{} ({} of {:.0f} evaluated designs feasible, {:.0f} non-dominated, "
                             "{} shown)",
                             xml_escape(sel->rule), sel->feasible_evaluations, sel->evaluations,
                             sel->archive_size, front.designs.size()));
  return out + "</table>\n";
}

// Choosing a design: the rule, its inputs and the chosen design (filled in by the script).
std::string choose_section() {
  return "<h2>Choose a design</h2>\n<p id=\"look-first\"></p>\n<p>A rule picks one feasible "
         "design (inside the brushes, if any) and marks it orange everywhere: the <b>knee</b> "
         "(smallest sum of normalised objectives), the <b>compromise</b> (nearest the ideal "
         "point), <b>weights</b> (the design whose pseudo-weights, the importance it gives each "
         "objective, are nearest yours; Deb 2001) or an <b>aspiration level</b> per objective "
         "(the achievement scalarizing function of Wierzbicki 1980: the design where moving "
         "every objective away from its aspiration by the same normalised amount meets the "
         "front). Normalised: 0 is the best feasible value of an objective, 1 the worst.</p>\n"
         "<div class=\"controls\">rule <select id=\"rule\"><option value=\"knee\">knee</option>"
         "<option value=\"compromise\">compromise</option><option value=\"weights\" selected>"
         "weights</option><option value=\"reference\">aspiration levels</option></select></div>\n"
         "<table id=\"choose-inputs\"></table>\n<div id=\"chosen\"></div>\n";
}

// The knee section: the honest text, the table (by the script) and the slice.
std::string knee_section(const ParetoFront& front, const WorkspaceSlice* knee_slice) {
  if (!front.knee) return "<h2>Knee design</h2>\n<p>None: the front is empty.</p>\n";
  const ParetoDesign& knee =
      front.designs[static_cast<std::size_t>(front.design_index(*front.knee))];
  std::string out =
      fmt::format("<h2>Knee design {}</h2>\n<p>{}", xml_escape(knee.id), knee_text(front));
  if (knee.machine_file)
    out += fmt::format(
        " Machine file: <code>{}</code> (for <code>pkmopt analyze</code>, "
        "<code>pkmopt workspace</code> and <code>pkmopt draw</code>).",
        xml_escape(*knee.machine_file));
  out += "</p>\n<div id=\"knee-table\"></div>\n";
  if (!knee_slice) {
    out +=
        "<p>No workspace slice: the knee design has no machine file (<code>output: {designs: "
        "true}</code> in the study writes them).</p>\n";
    return out;
  }
  SliceOverlay overlay;
  if (const auto& p = front.task.positions)
    overlay.task_rect = std::make_pair(Eigen::Vector2d(p->first.x(), p->first.y()),
                                       Eigen::Vector2d(p->second.x(), p->second.y()));
  const double z = front.task.centre(2) + knee.home_height;
  out += fmt::format(
      "<h3>Workspace slice of {}</h3>\n<p>The plane z = {:.5g} mm in the machine's base frame "
      "(the task centre's height {:.5g} mm plus home_height {:.5g} mm) at constant orientation "
      "(rx = ry = rz = 0), coloured by singularity_margin (1/cond of the Jacobian, 0..1, low = "
      "dark); grey: not reachable; red: the task's positions in this plane.</p>\n"
      "<img alt=\"workspace slice of {}\" src=\"data:image/png;base64,{}\">\n",
      xml_escape(knee.id), 1e3 * z, 1e3 * front.task.centre(2), 1e3 * knee.home_height,
      xml_escape(knee.id),
      base64(slice_png(*knee_slice, SliceMetric::kSingularityMargin, overlay)));
  return out;
}

}  // namespace

std::string knee_text(const ParetoFront& front) {
  if (!front.knee) return "The front is empty: there is no knee.";
  const std::size_t m = front.objectives.size();
  std::vector<std::vector<double>> f;  // minimised
  for (const ParetoDesign& d : front.designs) {
    std::vector<double> v(m);
    for (std::size_t k = 0; k < m; ++k)
      v[k] = front.objectives[k].sense == "maximize" ? -d.objectives[k] : d.objectives[k];
    f.push_back(v);
  }
  const std::size_t knee = static_cast<std::size_t>(front.design_index(*front.knee));
  if (m < 2 || front.designs.size() < 3)
    return fmt::format("{} is the knee by default: with {} the front has no trade-off to bend.",
                       *front.knee, m < 2 ? "one objective" : "fewer than three designs");
  double sum = 0.0;
  for (std::size_t k = 0; k < m; ++k) {
    double lo = INFINITY, hi = -INFINITY;
    for (const auto& v : f) {
      lo = std::min(lo, v[k]);
      hi = std::max(hi, v[k]);
    }
    sum += hi > lo ? (f[knee][k] - lo) / (hi - lo) : 0.0;
  }
  const double depth = (1.0 - sum) / std::sqrt(static_cast<double>(m));
  std::string text = fmt::format(
      "The knee is the design whose objectives, each scaled from 0 (the best value on this front) "
      "to 1 (the worst), have the smallest sum: the point farthest below the plane through the "
      "front's extremes (Das 1999). {} lies {:.3f} below that plane, in scaled units. ",
      *front.knee, depth);
  if (depth < 0.05)
    text +=
        "That is little: this front has no pronounced knee, and the knee design is only "
        "marginally better balanced than its neighbours. ";
  else
    text += "Near it, improving any objective costs clearly more of the others than it gains. ";
  text +=
      "The scaling weighs every objective equally over the front's range; if one matters more "
      "to you, choose along the scatter instead.";
  return text;
}

std::map<std::string, std::string> design_drawings(const ParetoFront& front,
                                                   const std::string& results_dir) {
  struct Drawn {
    std::string id;
    MachineSketch sketch;
    Eigen::AlignedBox3d task;
  };
  std::vector<Drawn> drawn;
  Eigen::AlignedBox3d bounds;
  for (const ParetoDesign& d : front.designs) {
    if (!d.machine_file || !std::isfinite(d.home_height)) continue;
    std::unique_ptr<Machine> machine;
    try {
      machine = load_machine_file((std::filesystem::path(results_dir) / *d.machine_file).string());
    } catch (const std::exception&) {
      continue;  // the report says which designs have no drawing
    }
    const Eigen::Vector3d lift(0.0, 0.0, d.home_height);
    const Pose pose{front.task.centre + lift, Eigen::Vector3d::Zero()};
    Drawn item{d.id, {}, {}};
    if (!machine->sketch(*machine->make_data(), pose, item.sketch)) continue;
    if (const auto& p = front.task.positions)
      item.task = Eigen::AlignedBox3d(p->first + lift, p->second + lift);
    bounds.extend(sketch_bounds(item.sketch));
    if (!item.task.isEmpty()) bounds.extend(item.task);
    drawn.push_back(std::move(item));
  }
  std::map<std::string, std::string> out;
  for (const Drawn& d : drawn)
    out[d.id] = machine_svg(d.sketch, {.title = d.id,
                                       .bounds = bounds,
                                       .task_box = d.task,
                                       .view_pixels = 190,
                                       .standalone = false});
  return out;
}

std::string convergence_svg(const ParetoFront& front) {
  if (!front.convergence || front.convergence->evaluations.empty()) return {};
  const ParetoConvergence& c = *front.convergence;
  raster::PlotAxes axes;
  axes.left = 90;
  axes.top = 30;
  axes.plot_width = 520;
  axes.plot_height = 220;
  axes.x_low = 0.0;
  axes.x_high = c.evaluations.back();
  axes.y_low = 0.0;
  axes.y_high = *std::max_element(c.hypervolume.begin(), c.hypervolume.end());
  raster::padded_range(axes.x_low, axes.x_high);
  raster::padded_range(axes.y_low, axes.y_high);
  axes.x_low = 0.0;
  axes.y_low = 0.0;
  axes.x_ticks = raster::nice_ticks(axes.x_low, axes.x_high, 6);
  axes.y_ticks = raster::nice_ticks(axes.y_low, axes.y_high, 5);
  const int width = axes.left + axes.plot_width + 30, height = axes.top + axes.plot_height + 55;
  std::string out = fmt::format(
      "<svg id=\"convergence\" width=\"{0}\" height=\"{1}\" viewBox=\"0 0 {0} {1}\" "
      "font-family=\"sans-serif\" font-size=\"13\">\n<rect width=\"{0}\" height=\"{1}\" "
      "fill=\"#fff\"/>\n",
      width, height);
  out += raster::svg_axes(axes);
  std::string points;
  for (std::size_t k = 0; k < c.evaluations.size(); ++k)
    points += fmt::format("{:.1f},{:.1f} ", axes.screen_x(c.evaluations[k]),
                          axes.screen_y(c.hypervolume[k]));
  out += fmt::format(
      "<polyline points=\"{}\" fill=\"none\" stroke=\"#1f77b4\" stroke-width=\"2\"/>\n", points);
  out += fmt::format(
      "<text x=\"{}\" y=\"{}\" text-anchor=\"middle\">evaluations</text>\n"
      "<text x=\"{}\" y=\"{}\">hypervolume of the feasible non-dominated designs found so "
      "far</text>\n</svg>\n",
      axes.left + axes.plot_width / 2, height - 8, axes.left, axes.top - 10);
  return out;
}

std::string report_html(const ParetoFront& file_front, const WorkspaceSlice* knee_slice,
                        const std::map<std::string, std::string>& drawings) {
  const ParetoFront front = in_display_units(file_front);
  std::string data = report_data(file_front, drawings).dump();
  // Inside <script>, "</" could end the element: JSON allows "\/" for "/".
  for (std::size_t at = data.find("</"); at != std::string::npos; at = data.find("</", at + 3))
    data.replace(at, 2, "<\\/");
  std::string out = fmt::format(
      "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n"
      "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n"
      "<title>pkmopt report: {0}</title>\n<style>{1}</style>\n</head>\n<body>\n<h1>{0}</h1>\n",
      xml_escape(front.study), assets::kReportCss);
  if (!front.description.empty()) out += "<p>" + xml_escape(front.description) + "</p>\n";
  int feasible = 0;
  for (const ParetoDesign& d : front.designs) feasible += d.feasible ? 1 : 0;
  out += fmt::format(
      "<p class=\"meta\">model {} &middot; {} Pareto designs ({} feasible){} &middot; written by "
      "pkmopt {} from {}</p>\n",
      xml_escape(front.model), front.designs.size(), feasible,
      front.selection
          ? fmt::format(", the non-dominated set of the {:.0f} feasible among {:.0f} "
                        "evaluated designs",
                        front.selection->feasible_evaluations, front.selection->evaluations)
          : std::string(),
      xml_escape(front.pkmopt_version), xml_escape(front.file));
  out +=
      "<h2>Pareto front</h2>\n<p>Choose the objectives on the axes; click a point, a line or a "
      "table row to pin a design (up to four) and compare them below. Filled blue: feasible; open "
      "grey: infeasible; red: the knee; orange: the design chosen below. Drag along an axis of "
      "the parallel coordinates to keep only the designs inside the range (the scatter, the "
      "table and the choice follow); click the axis to clear it.</p>\n"
      "<div class=\"controls\">x <select id=\"x-axis\"></select> y <select id=\"y-axis\">"
      "</select> <label><input type=\"checkbox\" id=\"normalised\"> normalised axes (0 = the "
      "best feasible value, 1 = the worst)</label> <button id=\"clear-brushes\">clear "
      "brushes</button></div>\n<div class=\"plots\">\n<div id=\"scatter-box\">" +
      scatter_svg(front, 0, front.objectives.size() > 1 ? 1 : 0, false) + "</div>\n";
  if (front.objectives.size() >= 3) out += parallel_svg(front);
  out += "</div>\n<div id=\"tip\"></div>\n";
  out +=
      "<h2>Pinned designs</h2>\n<div id=\"pinned\"><p class=\"hint\">No design pinned yet: "
      "click a point, a line or a row.</p></div>\n";
  out += choose_section();
  out += knee_section(file_front, knee_slice);
  if (const std::string svg = convergence_svg(front); !svg.empty())
    out +=
        "<h2>Convergence</h2>\n<p>How the front grew during the run: the hypervolume (up to "
        "the reference point of summary.json) of the feasible non-dominated designs found "
        "after each number of evaluations. A curve still rising at the end says more "
        "generations would still improve the front.</p>\n" +
        svg;
  out +=
      "<h2>All Pareto designs</h2>\n<p><input id=\"filter\" size=\"60\" placeholder=\"filter, "
      "e.g. workspace_volume > 500 leg_force_max < 9 (display units)\"> <span id=\"shown\">"
      "</span> &middot; click a heading to sort; &#9650;/&#9660; marks a parameter at its "
      "upper/lower bound.</p>\n<div id=\"designs-box\"></div>\n";
  out += "<h2>Study</h2>\n" + study_table(file_front);
  out += "<script type=\"application/json\" id=\"report-data\">\n" + data + "\n</script>\n";
  out += fmt::format(
      "<script>{}</script>\n<script>{}</script>\n<script>{}</script>\n</body>\n"
      "</html>\n",
      assets::kReportDecisionJs, assets::kReportParallelJs, assets::kReportJs);
  return out;
}

}  // namespace pkmopt
