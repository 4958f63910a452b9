#include "report/pareto_export.hpp"

#include <stdexcept>

#include "io/format/csv.hpp"
#include "models/workspace/workspace.hpp"
#include "report/display_units.hpp"
#include "report/pareto_report.hpp"
#include "report/workspace_export.hpp"

namespace pkmopt {

std::optional<ExportFormat> parse_export_format(std::string_view name) {
  if (name == "csv") return ExportFormat::kCsv;
  if (name == "json") return ExportFormat::kJson;
  if (name == "html") return ExportFormat::kHtml;
  return std::nullopt;
}

std::string default_export_name(ExportFormat format) {
  switch (format) {
    case ExportFormat::kCsv:
      return "pareto_export.csv";
    case ExportFormat::kJson:
      return "pareto_export.json";
    case ExportFormat::kHtml:
      break;
  }
  return "report.html";
}

std::optional<CsvUnits> parse_csv_units(std::string_view name) {
  if (name == "row") return CsvUnits::kRow;
  if (name == "suffix") return CsvUnits::kSuffix;
  return std::nullopt;
}

std::string pareto_csv_with_units(const ParetoFront& front, CsvUnits units) {
  if (units == CsvUnits::kNone) return pareto_csv(front);
  // The front in engineering units, and the unit of every column of pareto_csv in its order.
  ParetoFront shown = in_display_units(front);
  std::vector<std::string> column_units = {""};  // id
  for (std::size_t k = 0; k < shown.parameters.size(); ++k) {
    ParetoParameter& p = shown.parameters[k];
    const EngineeringUnit e = engineering_unit(p.name, p.unit);
    for (ParetoDesign& d : shown.designs) d.parameters[k] *= e.scale;
    p.unit = e.unit;
    column_units.push_back(e.unit);
  }
  if (!shown.home_height_is_parameter()) {
    const EngineeringUnit e = engineering_unit("home_height", "m");
    for (ParetoDesign& d : shown.designs) d.home_height *= e.scale;
    column_units.push_back(e.unit);
  }
  for (const ParetoObjective& o : shown.objectives) column_units.push_back(o.unit);
  for (const ParetoConstraint& c : shown.constraints) column_units.push_back(c.unit);
  if (shown.actuator_catalog) column_units.push_back("");
  column_units.push_back("0/1");  // feasible
  column_units.push_back("0/1");  // knee
  const std::string csv = pareto_csv(shown);
  const std::size_t eol = csv.find('\n');
  const std::vector<std::string> header = parse_csv(csv.substr(0, eol + 1), "pareto_csv").header;
  if (header.size() != column_units.size())
    throw std::logic_error("pareto_csv_with_units: the columns of pareto_csv changed");
  std::string first;
  for (std::size_t k = 0; k < header.size(); ++k) {
    const bool suffix = units == CsvUnits::kSuffix && !column_units[k].empty();
    first +=
        (k ? "," : "") + csv_field(suffix ? header[k] + " [" + column_units[k] + "]" : header[k]);
  }
  if (units == CsvUnits::kRow) {
    first += '\n';
    for (std::size_t k = 0; k < column_units.size(); ++k)
      first += (k ? "," : "") + csv_field(column_units[k]);
  }
  return first + csv.substr(eol);
}

std::vector<std::pair<std::filesystem::path, std::string>> pareto_export_files(
    const ParetoFront& front, const std::string& results_dir, ExportFormat format,
    const std::filesystem::path& out_file, const std::filesystem::path& plot_dir, bool plots,
    CsvUnits csv_units) {
  plots = plots || format == ExportFormat::kHtml;
  std::optional<WorkspaceSlice> slice;
  if (plots) slice = knee_workspace_slice(front, results_dir);
  std::vector<std::pair<std::filesystem::path, std::string>> files;
  switch (format) {
    case ExportFormat::kCsv:
      files.emplace_back(out_file, pareto_csv_with_units(front, csv_units));
      break;
    case ExportFormat::kJson:
      files.emplace_back(out_file, pareto_json(front));
      break;
    case ExportFormat::kHtml:
      files.emplace_back(out_file, report_html(front, slice ? &*slice : nullptr,
                                               design_drawings(front, results_dir)));
      break;
  }
  if (plots) {
    files.emplace_back(plot_dir / "pareto.svg", pareto_plot_svg(front));
    files.emplace_back(plot_dir / "pareto.png", pareto_plot_png(front));
    if (slice) {
      SliceOverlay overlay;  // the task's positions in the slice plane
      if (const auto& p = front.task.positions)
        overlay.task_rect = std::make_pair(Eigen::Vector2d(p->first.x(), p->first.y()),
                                           Eigen::Vector2d(p->second.x(), p->second.y()));
      files.emplace_back(plot_dir / "knee_slice.svg",
                         slice_svg(*slice, SliceMetric::kSingularityMargin, overlay));
      files.emplace_back(plot_dir / "knee_slice.png",
                         slice_png(*slice, SliceMetric::kSingularityMargin, overlay));
    }
  }
  return files;
}

}  // namespace pkmopt
