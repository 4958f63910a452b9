#include "report/pareto_export.hpp"

#include "models/workspace/workspace.hpp"
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

std::vector<std::pair<std::filesystem::path, std::string>> pareto_export_files(
    const ParetoFront& front, const std::string& results_dir, ExportFormat format,
    const std::filesystem::path& out_file, const std::filesystem::path& plot_dir, bool plots) {
  plots = plots || format == ExportFormat::kHtml;
  std::optional<WorkspaceSlice> slice;
  if (plots) slice = knee_workspace_slice(front, results_dir);
  std::vector<std::pair<std::filesystem::path, std::string>> files;
  switch (format) {
    case ExportFormat::kCsv:
      files.emplace_back(out_file, pareto_csv(front));
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
