// Tests of `pkmopt trajectory`: the hexapod-450 study in its reduced form through the CLI (its
// numbers checked against an independent computation or labelled as regression pins), a path
// file giving the same rates as the built-in helix, and bad input exiting with status 2.
// The library (models/motion/trajectory) is tested in tests/models/motion/trajectory_test.cpp.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <string>
#include <vector>

#include "io/format/csv.hpp"
#include "io/machine/machine_file.hpp"
#include "models/hexapod/hexapod.hpp"
#include "models/motion/trajectory.hpp"
#include "tests/cli_runner.hpp"
#include "tests/hexapod_reference.hpp"
#include "tests/scratch_dir.hpp"

namespace {

namespace fs = std::filesystem;
using namespace pkmopt;
using cli_runner::CliRun;

constexpr double kPi = std::numbers::pi;

std::string source_path(const std::string& relative) {
  return (fs::path(PKMOPT_SOURCE_DIR) / relative).string();
}

// The seeds' helix (as in tests/models/motion/trajectory_test.cpp).
HelixParameters seeds_helix() {
  HelixParameters h;
  h.centre = {0.0, 0.0, 0.70};
  h.angle_amplitudes = deg_to_rad(Eigen::Vector3d(5, 5, 5));
  return h;
}

class TrajectoryCli : public scratch::ScratchDirTest {
 protected:
  void SetUp() override { machine_ = source_path("studies/library/hexapod-450/hexapod-450.yaml"); }

  CliRun run(const std::string& args) { return run_cli(args); }

  void expect_input_error(const std::string& args, const std::string& fragment) {
    const fs::path out = dir_ / "out.csv";
    const CliRun r = run("trajectory " + args + " --out " + out.string());
    EXPECT_EQ(r.status, 2) << args << "\n" << r.err;
    EXPECT_NE(r.err.find(fragment), std::string::npos) << args << "\nstderr: " << r.err;
    EXPECT_FALSE(fs::exists(out)) << args;
  }

  std::string machine_;
};

// The study in its reduced form: studies/library/hexapod-450/run.sh with 20 mm workspaces and 61
// helix samples. Every helix pose reachable and regular, the file's q columns equal to the IK, and
// the study's numbers pinned (README.md of the study quotes them at full resolution).
TEST_F(TrajectoryCli, Hexapod450StudyReducedForm) {
  const fs::path out = dir_ / "study";
  const CliRun study =
      cli_runner::run_script(dir_, "studies/library/hexapod-450/run.sh", out.string() + " 0.02 61");
  ASSERT_EQ(study.status, 0) << study.out << study.err;
  const std::string level_summary = cli_runner::read_text(out / "helix-level.txt");
  EXPECT_NE(level_summary.find("61 reachable"), std::string::npos) << level_summary;
  EXPECT_NE(level_summary.find("singular poses: 0"), std::string::npos) << level_summary;

  const CsvTable table = read_csv_file((out / "helix-level.csv").string());
  ASSERT_EQ(table.rows.size(), 61u);
  EXPECT_EQ(table.header.size(), 21u + 4 * 6 + 2 + 36);  // no masses: no tau_dyn
  EXPECT_EQ(read_csv_file((out / "helix-level-singular.csv").string()).rows.size(), 0u);
  const Hexapod hexapod(read_hexapod_design(YamlValue::load_file(machine_)));
  Eigen::VectorXd q_min = Eigen::VectorXd::Constant(6, 1e9), q_max = -q_min;
  double q_dot_max = 0.0;
  for (const CsvRow& row : table.rows) {
    EXPECT_EQ(table.number(row, table.column("reachable")), 1.0);
    EXPECT_EQ(table.number(row, table.column("singular")), 0.0);
    Pose pose;
    pose.position = {table.number(row, 1), table.number(row, 2), table.number(row, 3)};
    pose.angles = deg_to_rad(
        Eigen::Vector3d(table.number(row, 4), table.number(row, 5), table.number(row, 6)));
    const Vec6<double> q = hexapod.inverse_kinematics(pose);
    for (int i = 0; i < 6; ++i) {
      const double qi = table.number(row, table.column("q_" + std::to_string(i + 1)));
      EXPECT_NEAR(qi, q(i), 1e-12);
      q_min(i) = std::min(q_min(i), qi);
      q_max(i) = std::max(q_max(i), qi);
      q_dot_max = std::max(
          q_dot_max, std::abs(table.number(row, table.column("q_dot_" + std::to_string(i + 1)))));
    }
  }
  // The study's numbers (leg lengths along the path, m; largest leg rate, m/s), each checked
  // twice: the program's output against the number, and the number against an independent
  // computation below.
  const double pinned_min[] = {0.8862244946703823, 0.8872466401016851, 0.9048626874035955,
                               0.8944034026417963, 0.894772376010191,  0.901138047948807};
  const double pinned_max[] = {0.9493480749070337, 0.9498780705533946, 0.9420710700564493,
                               0.9553694837455221, 0.9563738753609948, 0.9419858925305947};
  for (int i = 0; i < 6; ++i) {
    EXPECT_NEAR(q_min(i), pinned_min[i], 1e-9) << "leg " << i + 1;
    EXPECT_NEAR(q_max(i), pinned_max[i], 1e-9) << "leg " << i + 1;
  }
  EXPECT_NEAR(q_dot_max, 0.04607295905449005, 1e-9);
  // Independent derivation of the pinned numbers: the helix of HelixFormulaAtPinnedTimes about
  // (0, 0, 0.70) with 5 deg amplitudes at the 61 times 2 pi k / 60; leg lengths
  // |p + R (b_i - tcp) - a_i| with R = Rz Ry Rx from Eigen's angle-axis products
  // (hexapod_reference::rotation) and the machine file's joints; leg rates by central
  // differences in t (h = 1e-5: truncation ~1e-12 m/s, rounding ~1e-11 m/s).
  const HexapodDesign& d = hexapod.design();
  auto legs_at = [&](double t) {
    const double amp = 0.01 + 0.02 * t / (2 * kPi);
    const Eigen::Vector3d p(amp * std::cos(t), amp * std::sin(t),
                            0.70 + 0.01 + 0.01 * t * t / (4 * kPi * kPi));
    const Eigen::Vector3d angles =
        Eigen::Vector3d(5 * std::sin(t), 5 * std::cos(t), 5 * std::sin(2 * t)) * (kPi / 180);
    const Eigen::Matrix3d R = hexapod_reference::rotation(angles);
    Vec6<double> l;
    for (int i = 0; i < 6; ++i)
      l(i) = (p + R * (d.platform_joints.col(i) - d.tcp) - d.base_joints.col(i)).norm();
    return l;
  };
  Vec6<double> l_min = Vec6<double>::Constant(1e9), l_max = -l_min;
  double l_dot_max = 0.0;
  for (int k = 0; k <= 60; ++k) {
    const double t = 2 * kPi * k / 60, h = 1e-5;
    const Vec6<double> l = legs_at(t);
    l_min = l_min.cwiseMin(l);
    l_max = l_max.cwiseMax(l);
    l_dot_max =
        std::max(l_dot_max, ((legs_at(t + h) - legs_at(t - h)) / (2 * h)).cwiseAbs().maxCoeff());
  }
  for (int i = 0; i < 6; ++i) {
    EXPECT_NEAR(l_min(i), pinned_min[i], 1e-9) << "leg " << i + 1 << " (independent)";
    EXPECT_NEAR(l_max(i), pinned_max[i], 1e-9) << "leg " << i + 1 << " (independent)";
  }
  EXPECT_NEAR(l_dot_max, 0.04607295905449005, 1e-9);

  // The workspaces (20 mm grid): level and at a constant 40 deg tilt, pinned; the tilted one
  // far smaller and shifted off the axis; empty with 45 deg platform joints.
  const CsvTable ws = read_csv_file((out / "workspaces.csv").string());
  auto value = [&](const std::string& name, const std::string& column) {
    for (const CsvRow& row : ws.rows) {
      if (row.cells[0] == name) return ws.number(row, ws.require_column(column));
    }
    ADD_FAILURE() << "no workspace " << name;
    return 0.0;
  };
  const double level = value("level", "volume");
  const double tilted = value("tilt-y40", "volume");
  // Regression pin (not an independent check): value from
  // `PKMOPT=build/bin/pkmopt bash studies/library/hexapod-450/run.sh OUT 0.02 61`, row level,
  // column volume of OUT/workspaces.csv.
  EXPECT_NEAR(level, 0.10492625779098329, 1e-9);
  // Regression pin (not an independent check): value from
  // `PKMOPT=build/bin/pkmopt bash studies/library/hexapod-450/run.sh OUT 0.02 61`, row tilt-y40,
  // column volume of OUT/workspaces.csv.
  EXPECT_NEAR(tilted, 0.00024610712626390126, 1e-11);
  // Regression pin (not an independent check): value from
  // `PKMOPT=build/bin/pkmopt bash studies/library/hexapod-450/run.sh OUT 0.02 61`, row tilt-x40,
  // column volume of OUT/workspaces.csv.
  EXPECT_NEAR(value("tilt-x40", "volume"), 0.00036170388042771544, 1e-11);
  EXPECT_LT(tilted, 0.01 * level);
  // The level workspace is symmetric about x = 0 (three-fold symmetric machine, level platform).
  EXPECT_NEAR(value("level", "centroid_x"), 0.0, 1e-3);
  // Regression pin (not an independent check): value from
  // `PKMOPT=build/bin/pkmopt bash studies/library/hexapod-450/run.sh OUT 0.02 61`, row tilt-y40,
  // column centroid_x of OUT/workspaces.csv.
  EXPECT_NEAR(value("tilt-y40", "centroid_x"), 0.1838, 1e-4);
  // Regression pin (not an independent check): value from
  // `PKMOPT=build/bin/pkmopt bash studies/library/hexapod-450/run.sh OUT 0.02 61`, row tilt-y40,
  // column centroid_y of OUT/workspaces.csv.
  EXPECT_NEAR(value("tilt-y40", "centroid_y"), 0.0025, 1e-4);
  // Regression pin (not an independent check): value from
  // `PKMOPT=build/bin/pkmopt bash studies/library/hexapod-450/run.sh OUT 0.02 61`, row
  // joints-45-45-tilt-y40, column volume of OUT/workspaces.csv (README: 45 deg joints cannot
  // hold the 40 deg tilt anywhere).
  EXPECT_EQ(value("joints-45-45-tilt-y40", "volume"), 0.0);
  // Regression pin (not an independent check): value from
  // `PKMOPT=build/bin/pkmopt bash studies/library/hexapod-450/run.sh OUT 0.02 61`, row
  // joints-89-89-tilt-y40, column volume of OUT/workspaces.csv.
  EXPECT_NEAR(value("joints-89-89-tilt-y40", "volume"), 0.03551649237824182, 1e-9);
}

TEST_F(TrajectoryCli, PathFileGivesTheSameRatesAsTheHelix) {
  const fs::path path = dir_ / "path.csv", out = dir_ / "out.csv";
  {
    const HelixPath helix(seeds_helix());
    std::string text = "t,x,y,z,rx,ry,rz,label\n";
    for (double t : uniform_times(0, 2 * kPi, 201)) {
      const Pose p = helix.at(t).pose;
      text += format_number(t);
      for (int k = 0; k < 3; ++k) text += ',' + format_number(p.position(k));
      for (int k = 0; k < 3; ++k) text += ',' + format_number(rad_to_deg(p.angles(k)));
      text += ",a\n";
    }
    std::ofstream(path) << text;
  }
  const CliRun r =
      run("trajectory " + machine_ + " --path " + path.string() + " --out " + out.string());
  ASSERT_EQ(r.status, 0) << r.err;
  const CsvTable table = read_csv_file(out.string());
  ASSERT_EQ(table.rows.size(), 201u);
  for (std::size_t k = 1; k + 1 < table.rows.size(); ++k) {
    for (int i = 1; i <= 6; ++i) {
      const double q_dot = table.number(table.rows[k], table.column("q_dot_" + std::to_string(i)));
      const double fd = table.number(table.rows[k], table.column("q_dot_fd_" + std::to_string(i)));
      EXPECT_NEAR(q_dot, fd, 2e-5) << "row " << k << " leg " << i;
    }
  }
}

// A machine with masses: the file's tau_dyn columns are the library's inverse dynamics (checked
// against the bodies' momenta in tests/models/motion/trajectory_test.cpp), the summary gives peak
// and RMS forces, and the drive check names the limit a path exceeds.
TEST_F(TrajectoryCli, MassesGiveDynamicForcesAndTheDriveCheck) {
  const std::string masses = source_path("examples/hexapod_masses.yaml");
  const std::string catalog = source_path("studies/library/catalogs/sew-cms.yaml");
  const fs::path out = dir_ / "out.csv";
  const std::string helix =
      " --helix --helix-centre 0,0,0.85 --helix-radius 0.02,0.08 --helix-height 0,0.05 "
      "--helix-frequency 6 --t-end 1.0471975511965976 --samples 61 --wrench 500,0,-300,0,0,0";
  const CliRun r = run("trajectory " + masses + helix + " --catalog " + catalog +
                       " --drive CMS50S/150 --out " + out.string());
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("61 reachable"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("with gravity and inertia: peak"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("CMS50S/150 carries every actuator along this path"), std::string::npos)
      << r.out;

  HelixParameters hp;
  hp.centre = {0, 0, 0.85};
  hp.radius_start = 0.02;
  hp.radius_growth = 0.08;
  hp.height_start = 0.0;
  hp.height_growth = 0.05;
  hp.angular_frequency = 6;
  const auto machine = load_machine_file(masses);
  const Wrench w = (Wrench() << 500, 0, -300, 0, 0, 0).finished();
  const TrajectoryResult library =
      evaluate_trajectory(*machine, HelixPath(hp), uniform_times(0, 1.0471975511965976, 61), w);
  const CsvTable table = read_csv_file(out.string());
  ASSERT_EQ(table.rows.size(), 61u);
  for (std::size_t k = 0; k < table.rows.size(); ++k) {
    for (int i = 1; i <= 6; ++i) {
      EXPECT_EQ(table.number(table.rows[k], table.column("tau_dyn_" + std::to_string(i))),
                library.samples[k].tau_dyn(i - 1));
      EXPECT_EQ(table.number(table.rows[k], table.column("tau_" + std::to_string(i))),
                library.samples[k].metrics.tau(i - 1));
    }
    EXPECT_EQ(table.number(table.rows[k], table.column("ax")), library.samples[k].twist_rate(0));
  }

  // The short CMS50S/70 lacks the stroke; the run still succeeds and says so.
  const CliRun shorter = run_cli("trajectory " + masses + helix + " --catalog " + catalog +
                                 " --drive CMS50S/70 --out " + out.string());
  ASSERT_EQ(shorter.status, 0) << shorter.err;
  EXPECT_NE(shorter.out.find("stroke 0.0916 m EXCEEDED"), std::string::npos) << shorter.out;
  EXPECT_NE(shorter.out.find("WARNING: CMS50S/70 does NOT carry this path"), std::string::npos)
      << shorter.out;

  // Without masses there is no tau_dyn, and the summary says why.
  const CliRun still = run("trajectory " + machine_ + " --helix --out " + out.string());
  ASSERT_EQ(still.status, 0) << still.err;
  EXPECT_NE(still.out.find("no masses in the machine file"), std::string::npos) << still.out;
  EXPECT_EQ(read_csv_file(out.string()).header.size(), 21u + 4 * 6 + 2);
}

// Legs with a diameter: a path whose yaw swings to 110 degrees crosses legs (beyond about 92
// degrees for the sample hexapod with 80 mm legs, no joint limits and a long stroke); the summary
// gives the smallest clearance and the first sample where legs intersect, those samples are
// unreachable, and the CSV carries leg_clearance per sample.
TEST_F(TrajectoryCli, LegInterferenceIsReportedAlongThePath) {
  const std::string legs =
      write("legs.yaml",
            "model: hexapod\nbase: {radius: 0.60, pair_separation_deg: 20}\n"
            "platform: {radius: 0.25, pair_separation_deg: 20}\n"
            "legs: {min_length: 0.70, max_length: 1.40, axial_stiffness: 8e7, diameter: 0.08}\n"
            "tool: {tcp: [0, 0, -0.10]}\n");
  const fs::path out = dir_ / "out.csv";
  const CliRun r = run("trajectory " + legs +
                       " --helix --helix-centre 0,0,0.9 --helix-radius 0.0,0.0 --helix-height 0,0 "
                       "--helix-angles 0,0,110 --samples 41 --out " +
                       out.string());
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("legs: min clearance -"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("intersect first at sample"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("leg interference"), std::string::npos) << r.out;
  const CsvTable table = read_csv_file(out.string());
  const int clearance = table.column("leg_clearance");
  ASSERT_GE(clearance, 0);
  int intersecting = 0;
  for (const CsvRow& row : table.rows) {
    if (table.number(row, clearance) < 0.0) {
      ++intersecting;
      EXPECT_EQ(table.number(row, table.column("reachable")), 0.0);
    }
  }
  EXPECT_GT(intersecting, 0);
}

TEST_F(TrajectoryCli, BadInputExitsWithStatus2AndWritesNothing) {
  const fs::path path = dir_ / "path.csv";
  std::ofstream(path) << "t,x,y,z\n0,0,0,0.7\n0.5,0,0,0.71\n0.4,0,0,0.72\n";
  expect_input_error(machine_ + " --path " + path.string(),
                     "path.csv:4: column 1 't': expected a time greater than");
  expect_input_error(machine_, "expected --path PATH.csv or --helix, found neither");
  expect_input_error(machine_ + " --helix --path " + path.string(), "found both");
  expect_input_error(machine_ + " --helix --samples 1", "--samples: expected");
  expect_input_error(machine_ + " --helix --samples 10 --dt 0.1", "--samples and --dt");
  expect_input_error(machine_ + " --helix --t-end -1", "--t-end: expected");
  expect_input_error(machine_ + " --helix --helix-radius 0.01", "--helix-radius: expected 2");
  expect_input_error(machine_ + " --path " + path.string() + " --samples 5", "only with --helix");
  expect_input_error(source_path("examples/missing.yaml") + " --helix", "missing.yaml");
  const fs::path no_t = dir_ / "no_t.csv";
  std::ofstream(no_t) << "x,y,z\n0,0,0.7\n0,0,0.71\n";
  expect_input_error(machine_ + " --path " + no_t.string(), "'t'");
  const std::string catalog = source_path("studies/library/catalogs/sew-cms.yaml");
  expect_input_error(machine_ + " --helix --drive CMS50S/70", "--drive: expected --catalog");
  expect_input_error(machine_ + " --helix --catalog " + catalog, "--catalog: expected --drive");
  expect_input_error(machine_ + " --helix --catalog " + catalog + " --drive CMS99",
                     "--drive: expected an entry of");
  expect_input_error(
      source_path("examples/delta.yaml") + " --helix --catalog " + catalog + " --drive CMS50S/70",
      "found " + source_path("examples/delta.yaml") + " with revolute ones");
  expect_input_error(machine_ + " --helix --wrench 1,2,3", "--wrench: expected 6");
  expect_input_error(machine_ + " --helix --mode-warning 0.01",
                     "--mode-warning: expected only together with --assembly-modes");
  expect_input_error(machine_ + " --helix --assembly-modes --mode-warning -1",
                     "--mode-warning: expected a pose distance");
  expect_input_error(source_path("examples/delta.yaml") + " --helix --assembly-modes",
                     "--assembly-modes: expected a machine whose forward kinematics can be solved "
                     "completely");
}

// --assembly-modes: the sample hexapod turning toward Fichter's singularity (rz = 90 deg). The
// distance column is the library's (tests/models/motion/trajectory_modes_test.cpp checks it
// against the mirror mode found by hand); here: the columns, the summary and its warning.
TEST_F(TrajectoryCli, AssemblyModesAlongAPathAndAWarningNearASingularity) {
  const fs::path path = dir_ / "turn.csv", out = dir_ / "out.csv";
  {
    std::string text = "t,x,y,z,rx,ry,rz\n";
    for (int k = 0; k <= 20; ++k) text += fmt::format("{},0,0,0.9,0,0,{}\n", k, 60 + 1.5 * k);
    std::ofstream(path) << text;
  }
  const std::string args =
      "trajectory " + source_path("examples/hexapod.yaml") + " --path " + path.string();
  CliRun r = run(args + " --assembly-modes --out " + out.string());
  ASSERT_EQ(r.status, 0) << r.err;
  const CsvTable table = read_csv_file(out.string());
  ASSERT_EQ(table.rows.size(), 21u);
  const int distance = table.require_column("mode_distance");
  double previous = INFINITY;
  for (const CsvRow& row : table.rows) {
    const double d = table.number(row, distance);
    EXPECT_LT(d, previous);  // the mirror mode comes nearer with every degree
    previous = d;
    EXPECT_EQ(table.number(row, table.require_column("failed_paths")), 0.0);
    EXPECT_GE(table.number(row, table.require_column("real_modes")), 2.0);
  }
  EXPECT_EQ(previous, 0.0);  // rz = 90 deg: the modes meet
  // The default threshold is rho / 10 = 0.0269 m: the last two samples (d = 0.0153 m at
  // 88.5 deg, 0 at 90 deg) are below it, the one before (0.0307 m at 87 deg) is not.
  EXPECT_NE(r.out.find("assembly modes: "), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("WARNING: another assembly mode comes within 0 m of the tracked pose "
                       "(below 0.02693 m) at 2 samples, first at t = 19 s"),
            std::string::npos)
      << r.out;
  // A threshold of 0 warns of nothing; without the option there are no mode columns.
  r = run(args + " --assembly-modes --mode-warning 0 --out " + out.string());
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(r.out.find("WARNING: another assembly mode"), std::string::npos) << r.out;
  r = run(args + " --out " + out.string());
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(read_csv_file(out.string()).column("mode_distance"), -1);
}

}  // namespace
