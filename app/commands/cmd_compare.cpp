// pkmopt compare DIR1 DIR2 ... [--out FILE.html] [--png FILE.png] [--svg FILE.svg]
//                [--x OBJECTIVE] [--y OBJECTIVE]
// Reads DIR/pareto.json (and summary.json) of several `pkmopt run` results folders and writes
// one self-contained HTML page with their Pareto fronts in the same axes, a table per run with
// its hypervolume against a common reference point, and every run's knee design; optionally
// the scatter alone as PNG and SVG. See report/compare_report.hpp and docs/export.md.
#include <fmt/format.h>

#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "app/cli_args.hpp"
#include "app/commands.hpp"
#include "io/format/input_error.hpp"
#include "io/format/output_file.hpp"
#include "report/compare_report.hpp"

namespace pkmopt::cli {
namespace {

struct CompareCommandOptions {
  std::vector<std::string> results_dirs;
  std::string out = "compare.html";
  std::string png, svg;
  std::string x_objective, y_objective;
};

void run_compare(const CompareCommandOptions& opt) {
  namespace fs = std::filesystem;
  std::vector<std::pair<std::string, std::string>> targets{{"--out", opt.out}};
  if (!opt.png.empty()) targets.emplace_back("--png", opt.png);
  if (!opt.svg.empty()) targets.emplace_back("--svg", opt.svg);
  for (std::size_t i = 0; i < targets.size(); ++i) {
    const auto& [option, path] = targets[i];
    require_not_a_folder(option, path);
    const fs::path parent = fs::path(path).parent_path();
    if (!parent.empty() && !fs::is_directory(parent)) {
      throw InputError(fmt::format("{}: expected a file in an existing folder, found {}", option,
                                   quote_found(path)));
    }
    for (std::size_t j = 0; j < i; ++j) {
      if (fs::path(path).lexically_normal() == fs::path(targets[j].second).lexically_normal()) {
        throw InputError(fmt::format("{}: expected a file other than that of {}, found {}", option,
                                     targets[j].first, quote_found(path)));
      }
    }
  }
  const RunComparison comparison =
      load_run_comparison(opt.results_dirs, opt.x_objective, opt.y_objective);

  // Everything is rendered before the first file is written.
  std::vector<std::pair<std::string, std::string>> files;
  files.emplace_back(opt.out, comparison_html(comparison));
  if (!opt.png.empty()) files.emplace_back(opt.png, comparison_plot_png(comparison));
  if (!opt.svg.empty()) files.emplace_back(opt.svg, comparison_plot_svg(comparison));
  write_files_together(files);  // all of them or none

  std::string runs;
  for (const ComparedRun& run : comparison.runs) {
    runs += fmt::format("{}{} ({}, {} designs)", runs.empty() ? "" : ", ", run.front.study,
                        run.front.model, run.front.designs.size());
  }
  fmt::print("compare: {} on {} x {} -> {}{}\n", runs,
             comparison.shared_objectives[comparison.x_objective].name,
             comparison.shared_objectives[comparison.y_objective].name, opt.out,
             files.size() > 1 ? fmt::format(" (+ {} plot files)", files.size() - 1) : "");
  std::fflush(stdout);
}

}  // namespace

void add_compare_command(CLI::App& app) {
  auto opt = std::make_shared<CompareCommandOptions>();
  CLI::App* cmd = app.add_subcommand(
      "compare",
      "Compare the Pareto fronts of several design studies (results folders of `pkmopt run`) "
      "in one self-contained HTML page");
  cmd->add_option("dirs", opt->results_dirs, "Results folders of `pkmopt run` (two or more)")
      ->required();
  cmd->add_option("--out", opt->out, "Output HTML file (default compare.html)");
  cmd->add_option("--png", opt->png, "Also write the scatter plot as this PNG file");
  cmd->add_option("--svg", opt->svg, "Also write the scatter plot as this SVG file");
  cmd->add_option("--x", opt->x_objective,
                  "Objective on the x axis (default: the first objective every run has)");
  cmd->add_option("--y", opt->y_objective,
                  "Objective on the y axis (default: the next objective every run has)");
  cmd->callback([opt] { run_compare(*opt); });
}

}  // namespace pkmopt::cli
