// pkmopt export DIR --format csv|json|html [--out FILE] [--units row|suffix] [--plots]
// Reads DIR/pareto.json (written by `pkmopt run`) and writes the Pareto front as CSV, normalised
// JSON or one self-contained HTML report; --plots (always with html) also writes pareto.svg,
// pareto.png and, when the knee design has a machine file, knee_slice.svg/.png next to the
// output file. See docs/export.md.
#include <fmt/format.h>

#include <filesystem>
#include <memory>
#include <optional>
#include <string>

#include "app/cli_args.hpp"
#include "app/commands.hpp"
#include "io/format/input_error.hpp"
#include "io/format/output_file.hpp"
#include "report/synthesis_report.hpp"
#include "io/results/pareto_json.hpp"
#include "report/pareto_export.hpp"

namespace pkmopt::cli {
namespace {

struct ExportCommandOptions {
  std::string results_dir;
  std::string format;
  std::string out;
  std::string units;
  bool plots = false;
};

void run_export(const ExportCommandOptions& opt) {
  namespace fs = std::filesystem;
  const std::optional<ExportFormat> format = parse_export_format(opt.format);
  if (!format) {
    throw InputError(
        fmt::format("--format: expected csv, json or html, found {}", quote_found(opt.format)));
  }
  const fs::path dir(opt.results_dir);
  require_results_folder(opt.results_dir);
  require_not_a_folder("--out", opt.out);
  CsvUnits csv_units = CsvUnits::kNone;
  if (!opt.units.empty()) {
    const std::optional<CsvUnits> units = parse_csv_units(opt.units);
    if (!units)
      throw InputError(
          fmt::format("--units: expected row or suffix, found {}", quote_found(opt.units)));
    if (*format != ExportFormat::kCsv)
      throw InputError(
          fmt::format("--units: expected --format csv (the {} export has its units "
                      "in it), found --format {}",
                      opt.format, opt.format));
    csv_units = *units;
  }
  if (is_synthesis_folder(dir.string())) {
    // A synthesis: its merged front is DIR/pareto.csv and pareto.json already; the page shows
    // every structure's front, the candidates and one drawing per structure.
    if (*format != ExportFormat::kHtml)
      throw InputError(fmt::format(
          "--format: expected html for the synthesis folder '{}' (its merged front is "
          "pareto.csv and pareto.json; each structure's own folder candidates/NAME exports as a "
          "design study), found {}",
          dir.string(), opt.format));
    const fs::path out_file = opt.out.empty() ? dir / "report.html" : fs::path(opt.out);
    write_files_together({{out_file.string(), synthesis_report_html(dir.string())}});
    fmt::print("export: synthesis report -> {}\n", out_file.string());
    std::fflush(stdout);
    return;
  }
  const ParetoFront front = read_pareto_json((dir / "pareto.json").string());
  const fs::path out_file =
      opt.out.empty() ? dir / default_export_name(*format) : fs::path(opt.out);
  const fs::path plot_dir = out_file.has_parent_path() ? out_file.parent_path() : fs::path(".");

  // Everything is rendered before the first file is written.
  const bool plots = opt.plots || *format == ExportFormat::kHtml;
  const auto files =
      pareto_export_files(front, dir.string(), *format, out_file, plot_dir, plots, csv_units);
  std::vector<std::pair<std::string, std::string>> named;
  for (const auto& [path, content] : files) named.emplace_back(path.string(), content);
  write_files_together(named);  // the report and its plots, all of them or none
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
  cmd->add_option("--units", opt->units,
                  "csv: label the columns in engineering units (mm, µm, N/µm, l, kN): 'row' adds a "
                  "units row, 'suffix' puts the unit in each header");
  cmd->add_flag("--plots", opt->plots,
                "Also write pareto.svg, pareto.png and knee_slice.svg/.png next to the output "
                "file (always done for html)");
  cmd->callback([opt] { run_export(*opt); });
}

}  // namespace pkmopt::cli
