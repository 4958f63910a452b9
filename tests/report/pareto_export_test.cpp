// The files of `pkmopt export` (report/pareto_export.hpp) for a small front built in memory.
#include "report/pareto_export.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

#include "io/format/csv.hpp"
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

TEST(ParetoCsvWithUnits, RowOrSuffixInEngineeringUnits) {
  const pkmopt::ParetoFront front = pkmopt::read_pareto_json(
      (fs::path(PKMOPT_SOURCE_DIR) / "tests/io/data/pareto_json/two/pareto.json").string());
  EXPECT_EQ(pkmopt::pareto_csv_with_units(front, pkmopt::CsvUnits::kNone),
            pkmopt::pareto_csv(front));
  const std::string row = pkmopt::pareto_csv_with_units(front, pkmopt::CsvUnits::kRow);
  const pkmopt::CsvTable table = pkmopt::parse_csv(row, "row.csv");
  // The header as pareto_csv has it, then the units row, then the designs.
  EXPECT_EQ(table.header, pkmopt::parse_csv(pkmopt::pareto_csv(front), "si.csv").header);
  ASSERT_EQ(table.rows.size(), front.designs.size() + 1);
  const std::vector<std::string>& units = table.rows[0].cells;
  auto unit_of = [&](const std::string& column) {
    return units[static_cast<std::size_t>(table.column(column))];
  };
  EXPECT_EQ(unit_of("id"), "");
  EXPECT_EQ(unit_of("base_radius"), "mm");
  EXPECT_EQ(unit_of("platform_pair_separation_deg"), "deg");
  EXPECT_EQ(unit_of("home_height"), "mm");
  EXPECT_EQ(unit_of("stiffness_min"), "N/µm");
  EXPECT_EQ(unit_of("machine_size"), "l");
  EXPECT_EQ(unit_of("g_leg_force_max_max"), "kN");
  EXPECT_EQ(unit_of("feasible"), "0/1");
  // d0000: base radius 0.45 m, stiffness 1.2345678901234567e7 N/m, 0.3 m^3, g -4321.5 N.
  const pkmopt::CsvRow& d0 = table.rows[1];
  EXPECT_NEAR(table.number(d0, table.column("base_radius")), 450.0, 1e-9);
  EXPECT_NEAR(table.number(d0, table.column("stiffness_min")), 12.345678901234567, 1e-12);
  EXPECT_NEAR(table.number(d0, table.column("machine_size")), 300.0, 1e-9);
  EXPECT_NEAR(table.number(d0, table.column("g_leg_force_max_max")), -4.3215, 1e-12);
  EXPECT_EQ(table.number(d0, table.column("platform_pair_separation_deg")), 12.345678901234567);
  // Suffixed headers, no units row.
  const std::string suffix = pkmopt::pareto_csv_with_units(front, pkmopt::CsvUnits::kSuffix);
  const pkmopt::CsvTable t2 = pkmopt::parse_csv(suffix, "suffix.csv");
  EXPECT_EQ(t2.rows.size(), front.designs.size());
  EXPECT_GE(t2.column("base_radius [mm]"), 0);
  EXPECT_GE(t2.column("stiffness_min [N/µm]"), 0);
  EXPECT_GE(t2.column("id"), 0);
  EXPECT_GE(t2.column("g_task_reachable"), 0);  // no unit: no suffix
  EXPECT_EQ(pkmopt::parse_csv_units("row"), pkmopt::CsvUnits::kRow);
  EXPECT_EQ(pkmopt::parse_csv_units("suffix"), pkmopt::CsvUnits::kSuffix);
  EXPECT_FALSE(pkmopt::parse_csv_units("si").has_value());
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
