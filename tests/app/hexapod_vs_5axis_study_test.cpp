// Tests of the hexapod-vs-5axis study (studies/hexapod-vs-5axis/) in its reduced form through the
// CLI: the default study's knee hexapod against the 641236 5-axis machine on one milling task.
// Pins the structure classes, the reach of the task, the statics at the vertical tool by hand,
// the comparison the README reads (stiffness, deflection, tilted workspace), and the C axis
// racing near the tilting table's singular pose.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <memory>
#include <string>

#include "io/format/csv.hpp"
#include "tests/cli_runner.hpp"
#include "tests/scratch_dir.hpp"

namespace pkmopt {
namespace {

namespace fs = std::filesystem;

class HexapodVs5AxisStudy : public ::testing::Test {
 protected:
  // The study runs once for the suite, into the suite's scratch folder.
  static void SetUpTestSuite() {
    out_ = std::make_unique<scratch::ScratchDir>("HexapodVs5AxisStudy");
    run_ = cli_runner::run_script(out_->path(), "studies/hexapod-vs-5axis/run.sh",
                                  (*out_ / "r").string() + " 0.05 61");
  }
  static void TearDownTestSuite() { out_.reset(); }
  void SetUp() override { ASSERT_EQ(run_.status, 0) << run_.out << run_.err; }
  static fs::path result(const std::string& name) { return *out_ / "r" / name; }
  static double cell(const CsvTable& t, std::size_t row, const std::string& column) {
    return t.number(t.rows[row], t.require_column(column));
  }
  // The comparison row of a machine ("hexapod" or "5axis").
  static std::size_t row_of(const CsvTable& t, const std::string& machine) {
    for (std::size_t r = 0; r < t.rows.size(); ++r)
      if (t.rows[r].cells[0] == machine) return r;
    ADD_FAILURE() << "no row " << machine;
    return 0;
  }

  static inline std::unique_ptr<scratch::ScratchDir> out_;
  static inline cli_runner::CliRun run_;
};

TEST_F(HexapodVs5AxisStudy, StructureClasses) {
  EXPECT_NE(cli_runner::read_text(result("describe-hexapod.txt")).find("structure_class: P0З6"),
            std::string::npos);
  EXPECT_NE(cli_runner::read_text(result("describe-5axis.txt")).find("structure_class: P5З0"),
            std::string::npos);
}

TEST_F(HexapodVs5AxisStudy, BothReachTheWholeTask) {
  for (const char* machine : {"hexapod", "5axis"}) {
    const CsvTable t = read_csv_file(result(std::string("analyze-") + machine + ".csv").string());
    ASSERT_EQ(t.rows.size(), 81u) << machine;
    for (std::size_t r = 0; r < t.rows.size(); ++r)
      EXPECT_EQ(cell(t, r, "reachable"), 1.0) << machine << " pose " << r;
  }
}

// The tool vertical (A = 0): X, Y, Z carry the force components, C the moment about z of the
// force at the tool tip plus the load's own moment, and the pose is the table's singular one.
TEST_F(HexapodVs5AxisStudy, FiveAxisStaticsAtTheVerticalToolByHand) {
  const CsvTable t = read_csv_file(result("analyze-5axis.csv").string());
  const double f[3] = {-2454.45, 981.782, 1227.23}, mz = -77.3153;
  int vertical = 0;
  for (std::size_t r = 0; r < t.rows.size(); ++r) {
    if (cell(t, r, "rx") != 0.0 || cell(t, r, "ry") != 0.0) continue;
    ++vertical;
    const double x = cell(t, r, "x"), y = cell(t, r, "y");
    EXPECT_NEAR(cell(t, r, "q_2"), 0.0, 1e-9);
    EXPECT_NEAR(cell(t, r, "tau_1"), x * f[1] - y * f[0] + mz, 1e-6);
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(cell(t, r, "tau_" + std::to_string(k + 3)), f[k], 1e-6);
    EXPECT_EQ(cell(t, r, "singularity_margin"), 0.0);
  }
  EXPECT_EQ(vertical, 9);
}

TEST_F(HexapodVs5AxisStudy, TheComparisonTheReadmeReads) {
  const CsvTable t = read_csv_file(result("comparison.csv").string());
  const std::size_t h = row_of(t, "hexapod"), s = row_of(t, "5axis");
  EXPECT_EQ(t.rows[h].cells[1], "81/81");
  EXPECT_EQ(t.rows[s].cells[1], "81/81");
  EXPECT_GT(cell(t, s, "stiffness_min_N_per_um"), 3 * cell(t, h, "stiffness_min_N_per_um"));
  EXPECT_LT(3 * cell(t, s, "tcp_deflection_max_um"), cell(t, h, "tcp_deflection_max_um"));
  EXPECT_GT(cell(t, s, "workspace_tilt20_m3"), 3 * cell(t, h, "workspace_tilt20_m3"));
  EXPECT_GT(cell(t, h, "workspace_tilt20_m3"), 0.0);
  EXPECT_GT(cell(t, h, "singularity_margin_min"), 0.1);
  EXPECT_EQ(cell(t, s, "singularity_margin_min"), 0.0);
}

TEST_F(HexapodVs5AxisStudy, TheTableRacesNearTheVerticalTool) {
  const CsvTable cone = read_csv_file(result("helix-5axis.csv").string());
  const CsvTable near = read_csv_file(result("near-vertical-5axis.csv").string());
  const CsvTable legs = read_csv_file(result("near-vertical-hexapod.csv").string());
  auto fastest = [&](const CsvTable& t, const std::string& column) {
    double v = 0;
    for (std::size_t r = 0; r < t.rows.size(); ++r) v = std::max(v, std::abs(cell(t, r, column)));
    return v;
  };
  EXPECT_NEAR(fastest(cone, "q_dot_1"), 57.3, 2.0);  // deg/s: one turn of C per turn of the helix
  EXPECT_GT(fastest(near, "q_dot_1"), 1000.0);
  for (int leg = 1; leg <= 6; ++leg)
    EXPECT_LT(fastest(legs, "q_dot_" + std::to_string(leg)), 0.1);  // m/s
}

}  // namespace
}  // namespace pkmopt
