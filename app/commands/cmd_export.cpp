// pkmopt export DIR --format csv|json|html [--out FILE] [--plots]
// Reads DIR/pareto.json (written by `pkmopt run`) and writes the Pareto front as CSV, normalised
// JSON or one self-contained HTML report; --plots (always with html) also writes pareto.svg,
// pareto.png and, when the knee design has a machine file, knee_slice.svg/.png next to the
// output file. See docs/export.md.
#include <fmt/format.h>

#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "app/commands.hpp"
#include "io/input_error.hpp"
#include "io/output_file.hpp"
#include "report/pareto_report.hpp"
#include "report/workspace_export.hpp"

namespace pkmopt::cli {
namespace {

struct ExportCommandOptions {
  std::string results_dir;
  std::string format;
  std::string out;
  bool plots = false;
};

void run_export(const ExportCommandOptions& opt) {
  namespace fs = std::filesystem;
  std::string default_name;
  if (opt.format == "csv") {
    default_name = "pareto_export.csv";
  } else if (opt.format == "json") {
    default_name = "pareto_export.json";
  } else if (opt.format == "html") {
    default_name = "report.html";
  } else {
    throw InputError(
        fmt::format("--format: expected csv, json or html, found {}", quote_found(opt.format)));
  }
  const fs::path dir(opt.results_dir);
  if (!fs::is_directory(dir)) {
    throw InputError(fmt::format("{}: expected a results folder of `pkmopt run`, found {}",
                                 opt.results_dir, fs::exists(dir) ? "a file" : "no such folder"));
  }
  if (!opt.out.empty() && fs::is_directory(fs::path(opt.out))) {
    throw InputError(
        fmt::format("--out: expected a file name, found the folder {}", quote_found(opt.out)));
  }
  const ParetoFront front = read_pareto_json((dir / "pareto.json").string());
  const fs::path out_file = opt.out.empty() ? dir / default_name : fs::path(opt.out);
  const fs::path plot_dir = out_file.has_parent_path() ? out_file.parent_path() : fs::path(".");

  // Everything is rendered before the first file is written.
  std::vector<std::pair<fs::path, std::string>> files;
  const bool plots = opt.plots || opt.format == "html";
  std::optional<WorkspaceSlice> slice;
  if (plots || opt.format == "html") slice = knee_workspace_slice(front, dir.string());
  if (opt.format == "csv") {
    files.emplace_back(out_file, pareto_csv(front));
  } else if (opt.format == "json") {
    files.emplace_back(out_file, pareto_json(front));
  } else {
    files.emplace_back(out_file, report_html(front, slice ? &*slice : nullptr));
  }
  if (plots) {
    files.emplace_back(plot_dir / "pareto.svg", pareto_plot_svg(front));
    files.emplace_back(plot_dir / "pareto.png", pareto_plot_png(front));
    if (slice) {
      files.emplace_back(plot_dir / "knee_slice.svg",
                         slice_svg(*slice, SliceMetric::kSingularityMargin));
      files.emplace_back(plot_dir / "knee_slice.png",
                         slice_png(*slice, SliceMetric::kSingularityMargin));
    }
  }
  for (const auto& [path, content] : files) write_file_atomically(path.string(), content);
  fmt::print(
      "export: {} Pareto designs{} -> {}{}\n", front.designs.size(),
      front.knee ? ", knee " + *front.knee : "", out_file.string(),
      plots ? fmt::format(" (+ {} plot files in {})", files.size() - 1, plot_dir.string()) : "");
  std::fflush(stdout);
}

}  // namespace

void add_export_command(CLI::App& app) {
  auto opt = std::make_shared<ExportCommandOptions>();
  CLI::App* cmd = app.add_subcommand(
      "export",
      "Export a design study's Pareto front (DIR/pareto.json of `pkmopt run`) as CSV, JSON or a "
      "self-contained HTML report with plots");
  cmd->add_option("dir", opt->results_dir, "Results folder of `pkmopt run`")->required();
  cmd->add_option("--format", opt->format, "csv, json or html")->required();
  cmd->add_option("--out", opt->out,
                  "Output file (default DIR/pareto_export.csv, DIR/pareto_export.json or "
                  "DIR/report.html)");
  cmd->add_flag("--plots", opt->plots,
                "Also write pareto.svg, pareto.png and knee_slice.svg/.png next to the output "
                "file (always done for html)");
  cmd->callback([opt] { run_export(*opt); });
}

}  // namespace pkmopt::cli
