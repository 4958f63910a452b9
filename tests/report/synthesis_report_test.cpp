// The page of a synthesis folder: every structure with a feasible design in the scatter, the
// candidates table with the dropped ones and why, a drawing per structure; `pkmopt export` of a
// synthesis folder.
#include "report/synthesis_report.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "io/format/input_error.hpp"
#include "tests/scratch_dir.hpp"

namespace pkmopt {
namespace {

namespace fs = std::filesystem;

class SynthesisReport : public scratch::ScratchDirTest {};

const char* kStudy = R"(study: small
candidates: [hexapod, linear_delta, tripod_3prs, serial_head_ca]
task:
  region: {shape: box, centre: [0, 0, 0], size: [0.3, 0.3, 0.2], points: [2, 2, 2]}
  wrench: [300, 300, -1000, 0, 0, 0]
objectives:
  - minimize: tcp_deflection_max
  - minimize: swept_volume
constraints:
  - task_reachable
optimizer: {algorithm: nsga2, population: 12, generations: 6, seed: 2}
)";

TEST_F(SynthesisReport, PageHoldsFrontsCandidatesAndDrawings) {
  const fs::path out = dir_ / "out";
  const cli_runner::CliRun run =
      run_cli("run " + write("small.yaml", kStudy) + " --out " + out.string());
  ASSERT_EQ(run.status, 0) << run.err;
  ASSERT_TRUE(is_synthesis_folder(out.string()));
  EXPECT_FALSE(is_synthesis_folder((out / "candidates" / "hexapod").string()));
  const std::string html = synthesis_report_html(out.string());
  const nlohmann::json candidates =
      nlohmann::json::parse(cli_runner::read_text(out / "candidates.json"));
  int with_front = 0;
  for (const nlohmann::json& c : candidates["candidates"]) {
    const std::string name = c["candidate"];
    EXPECT_NE(html.find("<td>" + name + "</td>"), std::string::npos) << name;
    if (c["status"] == "dropped") {
      EXPECT_NE(html.find(c["reason"].get<std::string>().substr(0, 20)), std::string::npos);
      continue;
    }
    if (c["own_front"].get<int>() > 0) {
      ++with_front;
      // In the scatter's legend and drawn once, its knee design.
      EXPECT_NE(html.find("small/" + name), std::string::npos) << name;
      EXPECT_NE(html.find(name + ", knee design d"), std::string::npos) << name;
    }
  }
  EXPECT_GE(with_front, 2);
  EXPECT_NE(html.find("no x, y: the task needs x, y, z (3T0R)"), std::string::npos);
  EXPECT_NE(html.find("Candidate structures of small"), std::string::npos);
  EXPECT_EQ(html.find("</html>"), html.size() - 8);

  // pkmopt export: html writes DIR/report.html; csv and json are refused (exit 2, nothing
  // written).
  const cli_runner::CliRun exported = run_cli("export " + out.string() + " --format html");
  ASSERT_EQ(exported.status, 0) << exported.err;
  EXPECT_TRUE(fs::exists(out / "report.html"));
  const cli_runner::CliRun csv = run_cli("export " + out.string() + " --format csv");
  EXPECT_EQ(csv.status, 2);
  EXPECT_NE(csv.err.find("--format: expected html for the synthesis folder"), std::string::npos)
      << csv.err;
  EXPECT_FALSE(fs::exists(out / "pareto_export.csv"));
  EXPECT_THROW(synthesis_report_html((dir_ / "nothing").string()), InputError);
}

}  // namespace
}  // namespace pkmopt
