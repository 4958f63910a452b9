// Tests of `pkmopt fk`, `analyze`, `trajectory`, `workspace` and `describe` on the serial 5-axis
// example (examples/serial_641236.yaml): rotary axes in degrees and linear ones in metres in
// every file, the drive loads against a hand computation, a round trip fk -> analyze, the C axis
// racing near the vertical tool, and bad input with exit 2 and one line.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>

#include "io/format/csv.hpp"
#include "tests/cli_runner.hpp"
#include "tests/scratch_dir.hpp"

namespace pkmopt {
namespace {

namespace fs = std::filesystem;
using cli_runner::CliRun;

const std::string kMachine =
    (fs::path(PKMOPT_SOURCE_DIR) / "examples" / "serial_641236.yaml").string();

// The value of column `name` in data row `row` (0 = the first) of a CSV text.
double cell(const std::string& csv, const std::string& name, std::size_t row = 0) {
  const CsvTable t = parse_csv(csv, "output");
  return t.number(t.rows.at(row), t.require_column(name));
}

class SerialCli : public scratch::ScratchDirTest {
 protected:
  void expect_input_error(const CliRun& r, const std::string& fragment) {
    EXPECT_EQ(r.status, 2) << r.err;
    EXPECT_NE(r.err.find(fragment), std::string::npos) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  }
};

TEST_F(SerialCli, FkThenAnalyzeGivesTheAxesBackInTheirUnits) {
  const CliRun fk = run_cli("fk " + kMachine + " --q 30,-20,0.1,0.05,0.2");
  ASSERT_EQ(fk.status, 0) << fk.err;
  const std::string pose =
      fmt::format("x,y,z,rx,ry,rz\n{},{},{},{},{},{}\n", cell(fk.out, "x"), cell(fk.out, "y"),
                  cell(fk.out, "z"), cell(fk.out, "rx"), cell(fk.out, "ry"), cell(fk.out, "rz"));
  // The tool axis seen from the workpiece: Rz(C) Rx(A) e_z.
  const double C = 30 * M_PI / 180, A = -20 * M_PI / 180;
  const double rx = cell(fk.out, "rx") * M_PI / 180, ry = cell(fk.out, "ry") * M_PI / 180,
               rz = cell(fk.out, "rz") * M_PI / 180;
  const double ax = std::cos(rz) * std::sin(ry) * std::cos(rx) + std::sin(rz) * std::sin(rx);
  const double ay = std::sin(rz) * std::sin(ry) * std::cos(rx) - std::cos(rz) * std::sin(rx);
  EXPECT_NEAR(ax, std::sin(C) * std::sin(A), 1e-12);
  EXPECT_NEAR(ay, -std::cos(C) * std::sin(A), 1e-12);
  const CliRun analyze = run_cli("analyze " + kMachine + " --poses " + write("p.csv", pose));
  ASSERT_EQ(analyze.status, 0) << analyze.err;
  EXPECT_EQ(cell(analyze.out, "reachable"), 1.0);
  EXPECT_NEAR(cell(analyze.out, "q_1"), 30.0, 1e-9);  // C, degrees
  EXPECT_NEAR(cell(analyze.out, "q_2"), -20.0, 1e-9);
  EXPECT_NEAR(cell(analyze.out, "q_3"), 0.1, 1e-12);  // X, metres
  EXPECT_NEAR(cell(analyze.out, "q_4"), 0.05, 1e-12);
  EXPECT_NEAR(cell(analyze.out, "q_5"), 0.2, 1e-12);
}

TEST_F(SerialCli, DriveLoadsByHandAtTheVerticalTool) {
  // A = C = 0: X, Y, Z carry the force components; C the moment about z and A the moment about
  // x of the force at the tool tip r = (0.1, 0.05, 0.2) m.
  const CliRun r = run_cli("analyze " + kMachine + " --poses " +
                           write("p.csv", "x,y,z,rx,ry,rz\n0.1,0.05,0.2,0,0,0\n") +
                           " --wrench 100,-200,300,0,0,0");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NEAR(cell(r.out, "tau_1"), 0.1 * -200 - 0.05 * 100, 1e-9);  // C: (r x f)_z = -25 N*m
  EXPECT_NEAR(cell(r.out, "tau_2"), 0.05 * 300 - 0.2 * -200, 1e-9);  // A: (r x f)_x = 55 N*m
  EXPECT_NEAR(cell(r.out, "tau_3"), 100, 1e-9);
  EXPECT_NEAR(cell(r.out, "tau_4"), -200, 1e-9);
  EXPECT_NEAR(cell(r.out, "tau_5"), 300, 1e-9);
  // The vertical tool is the table's singular pose: C turns without moving the tool axis.
  EXPECT_EQ(cell(r.out, "singularity_margin"), 0.0);
  EXPECT_GT(cell(r.out, "stiffness_min"), 0.0);
}

TEST_F(SerialCli, TrajectoryAroundAConeTurnsCOnceAndRacesNearTheVertical) {
  // The tool axis on a 20 degree cone: C turns at the helix's 1 rad/s, A stays at -20 degrees.
  const CliRun cone =
      run_cli("trajectory " + kMachine +
              " --helix --helix-centre 0,0,0.1 --helix-angles 20,20,0 --out " + path("t.csv"));
  ASSERT_EQ(cone.status, 0) << cone.err;
  EXPECT_NE(cone.out.find("q_1: "), std::string::npos);
  // C about 57.3 deg/s (1 rad/s; the harmonic rx, ry make the cone slightly uneven), A fixed.
  const auto at = cone.out.find("q_1: -178.274 .. 180 deg, max |q_dot| ");
  ASSERT_NE(at, std::string::npos) << cone.out;
  const double c_max = std::stod(cone.out.substr(at + 37));
  EXPECT_GT(c_max, 55.0);
  EXPECT_LT(c_max, 60.0);
  EXPECT_NE(cone.out.find("q_2: -20 .. -19.8974 deg"), std::string::npos) << cone.out;
  // The axis passes 0.1 degree from the vertical: C must turn hundreds of times faster.
  const CliRun near = run_cli("trajectory " + kMachine +
                              " --helix --helix-centre 0,0,0.1 --helix-angles 3,3,0 "
                              "--helix-orientation 2.9,0,0 --samples 2001 --out " +
                              path("n.csv"));
  ASSERT_EQ(near.status, 0) << near.err;
  const CsvTable t = read_csv_file(path("n.csv"));
  double c_rate = 0;
  for (const auto& row : t.rows)
    c_rate = std::max(c_rate, std::abs(t.number(row, t.require_column("q_dot_1"))));
  EXPECT_GT(c_rate, 1000.0);  // deg/s, against 57.3 on the wide cone
}

TEST_F(SerialCli, WorkspaceAtATiltAndDescribe) {
  const CliRun w =
      run_cli("workspace " + kMachine + " --tilt 20 --resolution 0.08 --orientation-step 10");
  ASSERT_EQ(w.status, 0) << w.err;
  EXPECT_NE(w.out.find("volume "), std::string::npos) << w.out;
  const CliRun d = run_cli("describe " + kMachine);
  ASSERT_EQ(d.status, 0) << d.err;
  EXPECT_NE(d.out.find("structure_class: P5"), std::string::npos) << d.out;
}

TEST_F(SerialCli, BadInputIsOneLine) {
  expect_input_error(run_cli("fk " + kMachine + " --q 30,-20,0.1,0.05"), "--q");
  expect_input_error(run_cli("fk " + kMachine + " --q 30,-20,0.1,0.05,2000"),
                     "--q: expected value 5 (a linear axis) within +-1000 m");
  expect_input_error(run_cli("trajectory " + kMachine + " --helix --catalog x.yaml --drive d"),
                     "--catalog: expected a machine with linear actuators");
}

}  // namespace
}  // namespace pkmopt
