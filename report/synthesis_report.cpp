#include "report/synthesis_report.hpp"

#include <fmt/format.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <memory>
#include <nlohmann/json.hpp>
#include <sstream>
#include <vector>

#include "io/format/input_error.hpp"
#include "io/machine/machine_file.hpp"
#include "models/core/machine_sketch.hpp"
#include "report/compare_report.hpp"
#include "report/machine_drawing.hpp"

namespace pkmopt {
namespace {

namespace fs = std::filesystem;

std::string escape(const std::string& text) {
  std::string out;
  for (char c : text) {
    switch (c) {
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '&': out += "&amp;"; break;
      case '"': out += "&quot;"; break;
      default: out += c;
    }
  }
  return out;
}

nlohmann::json read_json(const fs::path& path) {
  std::ifstream in(path);
  if (!in)
    throw InputError(fmt::format("{}: expected the file a synthesis run writes, found no such file",
                                 path.string()));
  try {
    return nlohmann::json::parse(in);
  } catch (const nlohmann::json::exception& e) {
    throw InputError(fmt::format("{}: expected JSON, found a parse error ({})", path.string(),
                                 e.what()));
  }
}

std::string number(const nlohmann::json& v) {
  return v.is_number() ? fmt::format("{:.4g}", v.get<double>()) : "–";
}

// A structure's knee design drawn at its model's drawing pose; "" when it cannot be drawn.
std::string knee_drawing(const fs::path& folder, const std::string& name) {
  try {
    const nlohmann::json pareto = read_json(folder / "pareto.json");
    if (!pareto.contains("knee") || !pareto["knee"].is_string()) return "";
    const std::string knee = pareto["knee"].get<std::string>();
    const fs::path file = folder / "designs" / (knee + ".yaml");
    if (!fs::exists(file)) return "";
    const std::unique_ptr<Machine> machine = load_machine_file(file.string());
    const std::optional<Pose> pose = drawing_pose(*machine);
    if (!pose) return "";
    const std::unique_ptr<MachineData> data = machine->make_data();
    MachineSketch sketch;
    if (!machine->sketch(*data, *pose, sketch)) return "";
    MachineDrawingOptions options;
    options.title = name + ", knee design " + knee;
    options.standalone = false;
    return "<figure>" + machine_svg(sketch, options) + "</figure>\n";
  } catch (const std::exception&) {
    return "";
  }
}

}  // namespace

bool is_synthesis_folder(const std::string& dir) {
  return fs::exists(fs::path(dir) / "candidates.json");
}

std::string synthesis_report_html(const std::string& dir) {
  const fs::path root(dir);
  const nlohmann::json candidates = read_json(root / "candidates.json");
  const nlohmann::json summary = read_json(root / "summary.json");
  const nlohmann::json objectives = summary.value("objectives", nlohmann::json::array());
  std::vector<std::string> fronts;
  for (const nlohmann::json& c : candidates.value("candidates", nlohmann::json::array()))
    if (c.value("status", "") == "searched" && c.value("own_front", 0) > 0)
      fronts.push_back((root / c.value("folder", "")).string());

  std::string page;
  if (fronts.size() >= 2) {
    page = comparison_html(load_run_comparison(fronts, "", ""));
  } else {
    page = fmt::format(
        "<!DOCTYPE html>\n<html lang=\"en\">\n<head><meta charset=\"utf-8\"><title>{}</title>"
        "</head>\n<body>\n<p>Fewer than two structures have feasible designs: no scatter.</p>\n"
        "</body>\n</html>\n",
        escape(summary.value("study", std::string("synthesis"))));
  }

  std::string section = fmt::format(
      "<section id=\"synthesis\">\n<h2>Candidate structures of {}</h2>\n<p>Task motion type {}; "
      "{} evaluations; the merged front holds {} designs (DIR/pareto.csv, column "
      "architecture).</p>\n<table>\n<tr><th>candidate</th><th>structure</th><th>status</th>"
      "<th>generations</th><th>merged front</th>",
      escape(summary.value("study", std::string())), escape(candidates.value("task_motion", "")),
      summary.value("evaluations", 0), summary.value("points", 0));
  for (const nlohmann::json& o : objectives)
    section += fmt::format("<th>best {} ({})</th>", escape(o.value("name", "")),
                           escape(o.value("unit", "")));
  section += "<th>binding constraints, bounds / failures / reason</th></tr>\n";
  for (const nlohmann::json& c : candidates.value("candidates", nlohmann::json::array())) {
    const bool searched = c.value("status", "") == "searched";
    section += fmt::format("<tr><td>{}</td><td>{}</td><td>{}</td>", escape(c.value("candidate", "")),
                           escape(c.value("structure", "")),
                           searched ? (c.value("kept_to_the_end", false) ? "searched to the end"
                                                                         : "dropped by budget")
                                    : "dropped");
    if (!searched) {
      section += "<td>–</td><td>–</td>";
      for (std::size_t k = 0; k < objectives.size(); ++k) section += "<td>–</td>";
      section += "<td>" + escape(c.value("reason", "")) + "</td></tr>\n";
      continue;
    }
    section += fmt::format("<td>{}</td><td>{} ({:.0f}%)</td>", c.value("generations", 0),
                           c.value("merged_front", 0), 100.0 * c.value("merged_share", 0.0));
    for (const nlohmann::json& o : objectives)
      section += "<td>" + number(c["best"].value(o.value("name", ""), nlohmann::json())) + "</td>";
    std::string note;
    for (const nlohmann::json& b : c.value("constraints", nlohmann::json::array()))
      if (b.value("binding", false)) note += (note.empty() ? "" : "; ") + b.value("constraint", "");
    for (const nlohmann::json& b : c.value("at_bounds", nlohmann::json::array()))
      note += fmt::format("{}{} at its {} bound {}", note.empty() ? "" : "; ",
                          b.value("parameter", ""), b.value("bound", "") == "min" ? "lower" : "upper",
                          number(b["value"]));
    if (c.value("own_front", 0) == 0) {
      note = "no feasible design";
      for (const nlohmann::json& f : c.value("failures", nlohmann::json::array()))
        note += fmt::format("; {}: {:.0f}%", f.value("reason", ""), f.value("percent", 0.0));
    }
    section += "<td>" + escape(note.empty() ? "–" : note) + "</td></tr>\n";
  }
  section += "</table>\n<h2>One design per structure (its knee)</h2>\n";
  for (const nlohmann::json& c : candidates.value("candidates", nlohmann::json::array()))
    if (c.value("status", "") == "searched" && c.value("own_front", 0) > 0)
      section += knee_drawing(root / c.value("folder", ""), c.value("candidate", ""));
  section += "</section>\n";
  const std::size_t body_end = page.rfind("<script>");
  const std::size_t at = body_end == std::string::npos ? page.rfind("</body>") : body_end;
  page.insert(at == std::string::npos ? page.size() : at, section);
  return page;
}

}  // namespace pkmopt
