// Tests of the hexamech-long-axis study (studies/library/hexamech-long-axis/) in its reduced form
// through the CLI: a hexapod alone against the same hexapod on a +-1 m X axis
// (examples/hybrid_long_axis_hexapod.yaml). Pins the structure classes, the workspace relations
// of the follow rule, the statics and the series stiffness along the bed, the clamped axis past
// its travel, and the helix the axis carries out of the bare hexapod's reach.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <string>

#include "io/format/csv.hpp"
#include "tests/cli_runner.hpp"
#include "tests/scratch_dir.hpp"

namespace pkmopt {
namespace {

namespace fs = std::filesystem;

class HexamechStudy : public ::testing::Test {
 protected:
  // The study runs once for the suite, into the suite's scratch folder.
  static void SetUpTestSuite() {
    out_ = std::make_unique<scratch::ScratchDir>("HexamechStudy");
    run_ = cli_runner::run_script(out_->path(), "studies/library/hexamech-long-axis/run.sh",
                                  (*out_ / "r").string() + " 0.04 61");
  }
  static void TearDownTestSuite() { out_.reset(); }
  void SetUp() override { ASSERT_EQ(run_.status, 0) << run_.out << run_.err; }
  static fs::path result(const std::string& name) { return *out_ / "r" / name; }
  static double cell(const CsvTable& t, std::size_t row, const std::string& column) {
    return t.number(t.rows[row], t.require_column(column));
  }

  static inline std::unique_ptr<scratch::ScratchDir> out_;
  static inline cli_runner::CliRun run_;
};

TEST_F(HexamechStudy, StructureClasses) {
  EXPECT_NE(cli_runner::read_text(result("describe-hexapod.txt")).find("structure_class: P0З6"),
            std::string::npos);
  const std::string hybrid = cli_runner::read_text(result("describe-hybrid.txt"));
  EXPECT_NE(hybrid.find("structure_class: P1З6"), std::string::npos) << hybrid;
  EXPECT_NE(hybrid.find("dof: 7 (4 translations, 3 rotations), redundant"), std::string::npos)
      << hybrid;
}

// With the follow rule a position is reachable exactly when the hexapod reaches
// (x - clamp(x, -1, 1), y, z): the x extent grows by the travel on either side, the volume by
// 2 m times the area of a section (positive).
TEST_F(HexamechStudy, TheAxisAddsItsTravelToTheWorkspace) {
  const CsvTable t = read_csv_file(result("workspaces.csv").string());
  auto row = [&](const std::string& name) {
    for (std::size_t r = 0; r < t.rows.size(); ++r)
      if (t.rows[r].cells[0] == name) return r;
    ADD_FAILURE() << "no row " << name;
    return std::size_t{0};
  };
  for (const std::string orientation : {"level", "tilt15"}) {
    const std::size_t bare = row("hexapod-" + orientation), hybrid = row("hybrid-" + orientation);
    // The summary's extents are printed to 0.1 mm.
    EXPECT_NEAR(cell(t, hybrid, "x_min"), cell(t, bare, "x_min") - 1.0, 1.5e-4) << orientation;
    EXPECT_NEAR(cell(t, hybrid, "x_max"), cell(t, bare, "x_max") + 1.0, 1.5e-4) << orientation;
    EXPECT_GT(cell(t, hybrid, "volume"), cell(t, bare, "volume") + 0.01) << orientation;
  }
}

// Along the bed at z = 0.9 m under (1000, 0, -2000) N.
TEST_F(HexamechStudy, AlongTheBed) {
  const CsvTable h = read_csv_file(result("line-hybrid.csv").string());
  const CsvTable b = read_csv_file(result("line-hexapod.csv").string());
  ASSERT_EQ(h.rows.size(), 29u);  // run.sh: x = 0.1 i m for i = -14 .. 14
  ASSERT_EQ(b.rows.size(), 29u);
  std::size_t home = 0;
  for (std::size_t r = 0; r < h.rows.size(); ++r)
    if (cell(h, r, "x") == 0.0) home = r;
  const double k_x = 1.5e8;  // the X drive, N/m
  const double k_bare = cell(b, home, "stiffness_min");
  const double k_hybrid = cell(h, home, "stiffness_min");
  // Compliances in series: a rank-one addition along x bounds the result; the hexapod at home
  // is three-fold symmetric with its weakest direction along x, so the bound is attained.
  EXPECT_LE(k_hybrid, k_bare);
  EXPECT_GE(k_hybrid, 1.0 / (1.0 / k_bare + 1.0 / k_x) * (1.0 - 1e-12));
  EXPECT_NEAR(k_hybrid, 1.0 / (1.0 / k_bare + 1.0 / k_x), 1e-9 * k_hybrid);
  // The X drive's 5 um error adds at most 5 um to the worst TCP error.
  EXPECT_GT(cell(h, home, "tcp_error_max"), cell(b, home, "tcp_error_max"));
  EXPECT_LE(cell(h, home, "tcp_error_max"), cell(b, home, "tcp_error_max") + 5e-6 + 1e-15);

  for (std::size_t r = 0; r < h.rows.size(); ++r) {
    const double x = cell(h, r, "x");
    EXPECT_EQ(cell(h, r, "tau_1"), 1000.0) << x;  // the X drive carries f_x
    if (std::abs(x) <= 1.0 + 1e-12) {
      // Inside the travel the axis follows: the hexapod stays at its home.
      EXPECT_EQ(cell(h, r, "q_1"), x);
      EXPECT_EQ(cell(h, r, "reachable"), 1.0) << x;
      for (const std::string c :
           {"q_2", "q_7", "tau_2", "tau_7", "stiffness_min", "tcp_error_max", "singularity_margin"})
        EXPECT_EQ(cell(h, r, c), cell(h, home, c)) << x << " " << c;
    } else {
      // Past it the axis stops at its limit and the hexapod sees x - limit: the bare
      // hexapod's legs at that x (a row of the same line 1 m away).
      const double limit = x > 0 ? 1.0 : -1.0;
      EXPECT_EQ(cell(h, r, "q_1"), limit);
      const std::size_t bare_row = r - static_cast<std::size_t>(std::lround(10.0 * limit));
      ASSERT_NEAR(cell(b, bare_row, "x"), x - limit, 1e-12);
      for (int leg = 1; leg <= 6; ++leg)
        EXPECT_NEAR(cell(h, r, "q_" + std::to_string(leg + 1)),
                    cell(b, bare_row, "q_" + std::to_string(leg)), 1e-12)
            << x << " leg " << leg;
      EXPECT_EQ(cell(h, r, "reachable"), cell(b, bare_row, "reachable")) << x;
    }
  }
}

// The helix at x = 0.8 m: out of the bare hexapod's reach, every sample reachable on the
// hybrid, the X axis following the path's x exactly.
TEST_F(HexamechStudy, HelixOutOfTheHexapodsReach) {
  const std::string summary = cli_runner::read_text(result("helix-hybrid.txt"));
  EXPECT_NE(summary.find("61 samples"), std::string::npos) << summary;
  EXPECT_NE(summary.find("61 reachable"), std::string::npos) << summary;
  EXPECT_NE(summary.find("singular poses: 0"), std::string::npos) << summary;
  const CsvTable t = read_csv_file(result("helix-hybrid.csv").string());
  ASSERT_EQ(t.rows.size(), 61u);
  double max_rate_error = 0.0;
  for (std::size_t r = 0; r < t.rows.size(); ++r) {
    EXPECT_EQ(cell(t, r, "q_1"), cell(t, r, "x"));
    EXPECT_EQ(cell(t, r, "q_dot_1"), cell(t, r, "vx"));
    if (r > 0 && r + 1 < t.rows.size())
      for (int j = 1; j <= 7; ++j)
        max_rate_error =
            std::max(max_rate_error, std::abs(cell(t, r, "q_dot_" + std::to_string(j)) -
                                              cell(t, r, "q_dot_fd_" + std::to_string(j))));
  }
  // Central differences over 61 samples of one turn: O(h^2) with h = 2 pi / 60.
  EXPECT_LT(max_rate_error, 5e-4);  // 1.6e-4 measured; a wrong row would be O(0.01)
}

}  // namespace
}  // namespace pkmopt
