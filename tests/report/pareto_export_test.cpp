// The files of `pkmopt export` (report/pareto_export.hpp) for a small front built in memory.
#include "report/pareto_export.hpp"

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "report/pareto_report.hpp"

namespace {

namespace fs = std::filesystem;
using pkmopt::ExportFormat;

// Two designs, two objectives, no knee machine file (so no knee slice).
pkmopt::ParetoFront small_front() {
  pkmopt::ParetoFront front;
  front.file = "results/pareto.json";
  front.pkmopt_version = "test";
  front.study = "small";
  front.model = "hexapod";
  front.parameters = {{"base_radius", "m", 0.4, 0.8}};
  front.objectives = {{"workspace_volume", "maximize", "m^3"}, {"leg_force_max", "minimize", "N"}};
  pkmopt::ParetoDesign a;
  a.id = "d0001";
  a.parameters = {0.5};
  a.home_height = 0.9;
  a.objectives = {0.1, 2000};
  a.feasible = true;
  pkmopt::ParetoDesign b = a;
  b.id = "d0002";
  b.parameters = {0.7};
  b.objectives = {0.2, 3000};
  front.designs = {a, b};
  front.knee = "d0001";
  return front;
}

TEST(ExportFormat, NamesAndDefaultFiles) {
  EXPECT_EQ(pkmopt::parse_export_format("csv"), ExportFormat::kCsv);
  EXPECT_EQ(pkmopt::parse_export_format("json"), ExportFormat::kJson);
  EXPECT_EQ(pkmopt::parse_export_format("html"), ExportFormat::kHtml);
  EXPECT_FALSE(pkmopt::parse_export_format("HTML"));
  EXPECT_FALSE(pkmopt::parse_export_format(""));
  EXPECT_EQ(pkmopt::default_export_name(ExportFormat::kCsv), "pareto_export.csv");
  EXPECT_EQ(pkmopt::default_export_name(ExportFormat::kJson), "pareto_export.json");
  EXPECT_EQ(pkmopt::default_export_name(ExportFormat::kHtml), "report.html");
}

std::vector<std::string> paths(const std::vector<std::pair<fs::path, std::string>>& files) {
  std::vector<std::string> out;
  for (const auto& [path, bytes] : files) out.push_back(path.string());
  return out;
}

TEST(ParetoExportFiles, CsvAloneOrWithPlots) {
  const pkmopt::ParetoFront front = small_front();
  const auto alone =
      pkmopt::pareto_export_files(front, "results", ExportFormat::kCsv, "out/f.csv", "out", false);
  EXPECT_EQ(paths(alone), (std::vector<std::string>{"out/f.csv"}));
  EXPECT_EQ(alone[0].second, pkmopt::pareto_csv(front));
  const auto plots =
      pkmopt::pareto_export_files(front, "results", ExportFormat::kCsv, "out/f.csv", "out", true);
  EXPECT_EQ(paths(plots),
            (std::vector<std::string>{"out/f.csv", "out/pareto.svg", "out/pareto.png"}));
  EXPECT_EQ(plots[1].second, pkmopt::pareto_plot_svg(front));
  EXPECT_EQ(plots[2].second, pkmopt::pareto_plot_png(front));
}

TEST(ParetoExportFiles, JsonIsTheNormalisedFront) {
  const pkmopt::ParetoFront front = small_front();
  const auto files =
      pkmopt::pareto_export_files(front, "results", ExportFormat::kJson, "p.json", ".", false);
  ASSERT_EQ(files.size(), 1u);
  EXPECT_EQ(files[0].second, pkmopt::pareto_json(front));
}

TEST(ParetoExportFiles, HtmlAlwaysComesWithThePlots) {
  const pkmopt::ParetoFront front = small_front();
  const auto files = pkmopt::pareto_export_files(front, "results", ExportFormat::kHtml,
                                                 "r/report.html", "r", false);
  EXPECT_EQ(paths(files),
            (std::vector<std::string>{"r/report.html", "r/pareto.svg", "r/pareto.png"}));
  EXPECT_EQ(files[0].second, pkmopt::report_html(front, nullptr));  // no knee machine file
}

}  // namespace
