// Tests of io/results/analyze_csv, the output of `pkmopt analyze`: the header of
// docs/conventions.md for a hexapod (6 prismatic actuators, q in m) and a delta (3 revolute
// actuators, q in degrees), the pose columns as the pose file gave them, the metrics in their
// shortest round-trip text, and every other column of the pose file passed through unchanged. The
// metrics are set by hand so that each expected cell is known exactly.
#include "io/results/analyze_csv.hpp"

#include <gtest/gtest.h>

#include <limits>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include "models/hexapod/hexapod.hpp"
#include "models/leg_chain/leg_chain.hpp"
#include "models/sample_machines.hpp"
#include "tests/scratch_dir.hpp"

namespace pkmopt {
namespace {

class AnalyzeCsv : public scratch::ScratchDirTest {};

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

TEST_F(AnalyzeCsv, HexapodHeaderAndRows) {
  const Hexapod hexapod(sample_machines::conventions_hexapod_design());
  const PoseTable poses = read_pose_csv(write(
      "poses.csv", "label,x,y,z,rx,ry,rz\nhome,0,0,0.9,0,0,0\n\"a,b\",0.1,-0.05,0.85,5,-3,0.1\n"));
  std::vector<PoseMetrics> metrics(2);
  for (int p = 0; p < 2; ++p) {
    PoseMetrics& m = metrics[static_cast<std::size_t>(p)];
    m.reachable = p == 0;
    m.q.resize(6);
    m.tau.resize(6);
    for (int i = 0; i < 6; ++i) {
      m.q(i) = 0.75 + 0.125 * i + p;  // exact binary fractions
      m.tau(i) = -250.5 * (i + 1);
    }
    m.stiffness_min = 2.5e7;
    m.singularity_margin = 0.375;
    m.det_j = -0.0625;
    m.tcp_error_max = 1e-5;
    m.tcp_deflection = 1.25e-5;
    m.tcp_rotation_deflection = std::numbers::pi / 180 * 0.5;  // written as 0.5 degrees
    m.stiffness_min_loaded = 2e7;
    m.stiffness_min_direction = Eigen::Vector3d(0, 0.6, 0.8);
  }
  std::vector<PoseCompliance> matrices(metrics.size());
  for (PoseCompliance& c : matrices)
    for (int a = 0; a < 6; ++a)
      for (int b = 0; b < 6; ++b) c.compliance(a, b) = 0.25 * (10 * a + b);
  metrics[1].tau(5) = std::numeric_limits<double>::infinity();
  const std::vector<std::string> lines = lines_of(analyze_csv(hexapod, poses, metrics));
  ASSERT_EQ(lines.size(), 3u);
  EXPECT_EQ(lines[0],
            "x,y,z,rx,ry,rz,reachable,q_1,q_2,q_3,q_4,q_5,q_6,tau_1,tau_2,tau_3,tau_4,tau_5,tau_6,"
            "stiffness_min,singularity_margin,det_j,tcp_error_max,tcp_deflection,"
            "tcp_rotation_deflection_deg,stiffness_min_loaded,stiffness_dir_x,stiffness_dir_y,"
            "stiffness_dir_z,label");
  EXPECT_EQ(lines[1],
            "0,0,0.9,0,0,0,1,0.75,0.875,1,1.125,1.25,1.375,-250.5,-501,-751.5,-1002,-1252.5,-1503,"
            "25000000,0.375,-0.0625,1e-05,1.25e-05,0.5,20000000,0,0.6,0.8,home");
  // Angles as the file gave them (degrees, not converted back from radians); the label quoted.
  EXPECT_EQ(lines[2],
            "0.1,-0.05,0.85,5,-3,0.1,0,1.75,1.875,2,2.125,2.25,2.375,-250.5,-501,-751.5,-1002,"
            "-1252.5,inf,25000000,0.375,-0.0625,1e-05,1.25e-05,0.5,20000000,0,0.6,0.8,\"a,b\"");
  // --compliance: C_11..C_66 row by row after the metric columns.
  const std::vector<std::string> with_c =
      lines_of(analyze_csv(hexapod, poses, metrics, {.compliance = &matrices}));
  const CsvTable table = parse_csv(with_c[0] + "\n" + with_c[1] + "\n", "out.csv");
  EXPECT_EQ(table.column("C_11"), table.column("stiffness_dir_z") + 1);
  EXPECT_EQ(table.column("label"), table.column("C_66") + 1);
  EXPECT_EQ(table.number(table.rows[0], table.column("C_11")), 0.0);
  EXPECT_EQ(table.number(table.rows[0], table.column("C_23")), 0.25 * 12);
  EXPECT_EQ(table.number(table.rows[0], table.column("C_61")), 0.25 * 50);
}

// A revolute delta: q_i in degrees (the metrics hold radians), tau_i in N*m; columns after the
// pose and metric columns in the pose file's order.
TEST_F(AnalyzeCsv, RevoluteDeltaWritesDegreesAndPassesColumnsThrough) {
  const LegChainMachine delta(delta_design(DeltaDesign{}));
  ASSERT_TRUE(delta.revolute_actuators());
  ASSERT_EQ(delta.num_actuators(), 3);
  const PoseTable poses =
      read_pose_csv(write("poses.csv", "id,z,note,x,y,t\n7,-1,first,0.1,0,0.5\n"));
  std::vector<PoseMetrics> metrics(1);
  PoseMetrics& m = metrics[0];
  m.reachable = true;
  m.q = Eigen::Vector3d(std::numbers::pi / 2, -std::numbers::pi / 4, 0.0);
  m.tau = Eigen::Vector3d(1.5, -2.0, 0.25);
  m.stiffness_min = 1e6;
  m.singularity_margin = 0.5;
  m.det_j = 2.0;
  m.tcp_error_max = 3e-5;
  const std::vector<std::string> lines = lines_of(analyze_csv(delta, poses, metrics));
  ASSERT_EQ(lines.size(), 2u);
  EXPECT_EQ(lines[0],
            "x,y,z,rx,ry,rz,reachable,q_1,q_2,q_3,tau_1,tau_2,tau_3,stiffness_min,"
            "singularity_margin,det_j,tcp_error_max,tcp_deflection,tcp_rotation_deflection_deg,"
            "stiffness_min_loaded,stiffness_dir_x,stiffness_dir_y,stiffness_dir_z,id,note,t");
  const CsvTable table = parse_csv(lines[0] + "\n" + lines[1] + "\n", "out.csv");
  const CsvRow& row = table.rows[0];
  EXPECT_EQ(row.cells[0], "0.1");
  EXPECT_EQ(row.cells[2], "-1");
  EXPECT_EQ(row.cells[3], "0");  // rx absent from the file: 0
  EXPECT_NEAR(table.number(row, table.column("q_1")), 90.0, 1e-12);
  EXPECT_NEAR(table.number(row, table.column("q_2")), -45.0, 1e-12);
  EXPECT_EQ(table.number(row, table.column("q_3")), 0.0);
  EXPECT_EQ(row.cells[static_cast<std::size_t>(table.column("tau_1"))], "1.5");  // not scaled
  EXPECT_EQ(row.cells[static_cast<std::size_t>(table.column("tcp_error_max"))], "3e-05");
  EXPECT_EQ(row.cells[static_cast<std::size_t>(table.column("id"))], "7");
  EXPECT_EQ(row.cells[static_cast<std::size_t>(table.column("note"))], "first");
  EXPECT_EQ(row.cells[static_cast<std::size_t>(table.column("t"))], "0.5");
}

// analyze_value_columns names the numeric columns after x..rz in file order, and analyze_values
// gives the numbers written under them (revolute q in degrees).
TEST_F(AnalyzeCsv, ValueColumnsAreTheNumbersOfTheFile) {
  const LegChainMachine delta(delta_design(DeltaDesign{}));
  const std::vector<std::string> names = analyze_value_columns(delta, false, true);
  ASSERT_EQ(names.size(), 1u + 3 + 3 + 10 + 36);
  EXPECT_EQ(names[0], "reachable");
  EXPECT_EQ(names[1], "q_1");
  EXPECT_EQ(names[4], "tau_1");
  EXPECT_EQ(names[7], "stiffness_min");
  EXPECT_EQ(names[12], "tcp_rotation_deflection_deg");
  EXPECT_EQ(names[16], "stiffness_dir_z");
  EXPECT_EQ(names[17], "C_11");
  EXPECT_EQ(names.back(), "C_66");
  const PoseTable poses = read_pose_csv(write("p.csv", "x,y,z\n0.05,0,-1\n"));
  std::vector<PoseCompliance> compliance;
  const auto data = delta.make_data();
  std::vector<PoseMetrics> metrics(1);
  delta.analyze(*data, poses.poses[0], Wrench::Zero(), metrics[0]);
  compliance.push_back(data->matrices);
  std::vector<double> values(names.size());
  analyze_values(delta, metrics[0], nullptr, &compliance[0], values.data());
  EXPECT_EQ(values[0], metrics[0].reachable ? 1.0 : 0.0);
  EXPECT_EQ(values[1], metrics[0].q(0) * kRadToDeg);
  EXPECT_EQ(values[12], metrics[0].tcp_rotation_deflection * kRadToDeg);
  EXPECT_EQ(values[17 + 6 * 2 + 1], compliance[0].compliance(2, 1));
  const std::vector<std::string> lines =
      lines_of(analyze_csv(delta, poses, metrics, {.compliance = &compliance}));
  const CsvTable table = parse_csv(lines[0] + "\n" + lines[1] + "\n", "out.csv");
  for (std::size_t c = 1; c < names.size(); ++c)
    EXPECT_EQ(table.number(table.rows[0], table.column(names[c])), values[c]) << names[c];
}

}  // namespace
}  // namespace pkmopt
