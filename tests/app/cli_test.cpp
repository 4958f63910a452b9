// Tests of the pkmopt binary: analyze and fk end to end, and every kind of bad input giving
// one clear message, exit status 2 and no output file.
#include <fmt/format.h>
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "io/format/csv.hpp"
#include "io/machine/machine_file.hpp"
#include "models/core/pose_analysis.hpp"
#include "models/hexapod/hexapod.hpp"
#include "tests/cli_runner.hpp"
#include "tests/sample_machines.hpp"
#include "tests/scratch_dir.hpp"

namespace {

namespace fs = std::filesystem;

using cli_runner::CliRun;
using cli_runner::read_text;

class Cli : public scratch::ScratchDirTest {
 protected:
  void SetUp() override {
    machine_ =
        write("machine.yaml", read_text(fs::path(PKMOPT_SOURCE_DIR) / "examples/hexapod.yaml"));
    poses_ = write("poses.csv",
                   "x,y,z,rx,ry,rz,label\n0,0,0.9,0,0,0,home\n0.1,-0.05,0.85,5,-3,10,\"a,b\"\n");
  }

  CliRun run(const std::string& args) { return run_cli(args); }

  // A bad-input run: status 2, one line on stderr containing `fragment`, no output file and
  // no temporary left in the folder.
  void expect_input_error(const std::string& args, const std::string& fragment) {
    const std::string out_file = (dir_ / "result.csv").string();
    const CliRun r = run(args + " --out " + out_file);
    EXPECT_EQ(r.status, 2) << args << "\n" << r.err;
    EXPECT_NE(r.err.find(fragment), std::string::npos) << "stderr: " << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_FALSE(fs::exists(out_file));
    for (const auto& entry : fs::directory_iterator(dir_)) {
      EXPECT_EQ(entry.path().filename().string().find(".tmp."), std::string::npos);
    }
  }

  std::string machine_, poses_;
};

TEST_F(Cli, AnalyzeWritesTheConventionColumns) {
  const CliRun r = run("analyze " + machine_ + " --poses " + poses_ + " --wrench 0,0,-1000,0,0,0");
  ASSERT_EQ(r.status, 0) << r.err;
  const pkmopt::CsvTable t = pkmopt::parse_csv(r.out, "out");
  const std::string expected_header =
      "x,y,z,rx,ry,rz,reachable,q_1,q_2,q_3,q_4,q_5,q_6,tau_1,tau_2,tau_3,tau_4,tau_5,tau_6,"
      "stiffness_min,singularity_margin,det_j,tcp_error_max,tcp_deflection,"
      "tcp_rotation_deflection_deg,stiffness_min_loaded,stiffness_dir_x,stiffness_dir_y,"
      "stiffness_dir_z,label";
  EXPECT_EQ(r.out.substr(0, r.out.find('\n')), expected_header);
  ASSERT_EQ(t.rows.size(), 2u);
  EXPECT_EQ(t.rows[1].cells.back(), "a,b");
  EXPECT_EQ(t.rows[0].cells[t.column("reachable")], "1");
  // Values agree with the library.
  const pkmopt::Hexapod hexapod(sample_machines::conventions_hexapod_design());
  const pkmopt::Pose pose{{0.1, -0.05, 0.85}, pkmopt::deg_to_rad(Eigen::Vector3d(5, -3, 10))};
  const auto q = hexapod.inverse_kinematics(pose);
  for (int i = 0; i < 6; ++i) {
    EXPECT_DOUBLE_EQ(t.number(t.rows[1], t.column("q_" + std::to_string(i + 1))), q(i));
  }
  // --out writes the same text, atomically.
  const std::string out_file = (dir_ / "a.csv").string();
  const CliRun r2 = run("analyze " + machine_ + " --poses " + poses_ +
                        " --wrench 0,0,-1000,0,0,0 --out " + out_file);
  ASSERT_EQ(r2.status, 0) << r2.err;
  EXPECT_EQ(read_text(out_file), r.out);
  EXPECT_TRUE(r2.out.empty());
}

// A machine file with masses: six natural frequencies per pose (Hz, ascending, finite), the
// values of the library.
TEST_F(Cli, AnalyzeWithMassesAddsTheNaturalFrequencies) {
  const std::string file = (fs::path(PKMOPT_SOURCE_DIR) / "examples/hexapod_masses.yaml").string();
  const CliRun r = run("analyze " + file + " --poses " + poses_);
  ASSERT_EQ(r.status, 0) << r.err;
  const pkmopt::CsvTable t = pkmopt::parse_csv(r.out, "out");
  ASSERT_EQ(t.rows.size(), 2u);
  const std::unique_ptr<pkmopt::Machine> machine = pkmopt::load_machine_file(file);
  const std::vector<pkmopt::PoseMetrics> metrics = pkmopt::analyze_poses(
      *machine, std::vector<pkmopt::Pose>{{{0, 0, 0.9}, {0, 0, 0}}}, pkmopt::Wrench::Zero());
  ASSERT_EQ(metrics[0].natural_frequencies.size(), 6);
  for (int j = 1; j <= 6; ++j) {
    const double f = t.number(t.rows[0], t.column("natural_frequency_" + std::to_string(j)));
    EXPECT_DOUBLE_EQ(f, metrics[0].natural_frequencies(j - 1));
    EXPECT_GT(f, 1.0);
    if (j > 1) {
      EXPECT_GE(f, t.number(t.rows[0], t.column("natural_frequency_" + std::to_string(j - 1))));
    }
  }
  EXPECT_EQ(t.column("label"), t.column("natural_frequency_6") + 1);
}

// --mode-shapes: six columns per mode after the frequencies, the library's shapes; refused (exit
// 2) for a machine without masses.
TEST_F(Cli, AnalyzeModeShapesWritesEveryModesTwist) {
  const std::string file = (fs::path(PKMOPT_SOURCE_DIR) / "examples/hexapod_masses.yaml").string();
  const CliRun r = run("analyze " + file + " --poses " + poses_ + " --mode-shapes");
  ASSERT_EQ(r.status, 0) << r.err;
  const pkmopt::CsvTable t = pkmopt::parse_csv(r.out, "out");
  ASSERT_EQ(t.rows.size(), 2u);
  const std::unique_ptr<pkmopt::Machine> machine = pkmopt::load_machine_file(file);
  const std::vector<pkmopt::PoseModes> modes =
      pkmopt::mode_shapes_of_poses(*machine, std::vector<pkmopt::Pose>{{{0, 0, 0.9}, {0, 0, 0}}});
  ASSERT_EQ(modes[0].shapes.cols(), 6);
  EXPECT_EQ(t.column("mode_1_dx"), t.column("natural_frequency_6") + 1);
  EXPECT_EQ(t.column("label"), t.column("mode_6_drz") + 1);
  const char* names[] = {"dx", "dy", "dz", "drx", "dry", "drz"};
  for (int k = 1; k <= 6; ++k) {
    for (int c = 0; c < 6; ++c) {
      const std::string column = "mode_" + std::to_string(k) + "_" + names[c];
      EXPECT_DOUBLE_EQ(t.number(t.rows[0], t.column(column)), modes[0].shapes(c, k - 1) + 0.0)
          << column;
    }
  }
  // A hybrid machine: the serial axis first in every mode, seven modes.
  const std::string hybrid =
      (fs::path(PKMOPT_SOURCE_DIR) / "examples/hybrid_long_axis_masses.yaml").string();
  const CliRun h = run("analyze " + hybrid + " --poses " + poses_ + " --mode-shapes");
  ASSERT_EQ(h.status, 0) << h.err;
  const pkmopt::CsvTable th = pkmopt::parse_csv(h.out, "out");
  EXPECT_EQ(th.column("mode_1_axis_1"), th.column("natural_frequency_7") + 1);
  EXPECT_EQ(th.column("mode_1_dx"), th.column("mode_1_axis_1") + 1);
  EXPECT_EQ(th.column("label"), th.column("mode_7_drz") + 1);
  const CliRun bare = run("analyze " + machine_ + " --poses " + poses_ + " --mode-shapes");
  EXPECT_EQ(bare.status, 2);
  EXPECT_NE(bare.err.find("--mode-shapes needs a mass model"), std::string::npos) << bare.err;
  EXPECT_TRUE(bare.out.empty());
}

TEST_F(Cli, AnalyzeWithoutAnglesDefaultsToZeroAndWritesInfAtSingularPoses) {
  const std::string similar =
      write("similar.yaml",
            "model: hexapod\nbase: {radius: 0.6, pair_separation_deg: 60}\n"
            "platform: {radius: 0.3, pair_separation_deg: 60}\n"
            "legs: {min_length: 0.5, max_length: 1.5, axial_stiffness: 1e8}\n");
  const std::string poses = write("p.csv", "z,y,x\n0.9,0,0\n");
  const CliRun r = run("analyze " + similar + " --poses " + poses + " --wrench 1,2,3,4,5,6");
  ASSERT_EQ(r.status, 0) << r.err;
  const pkmopt::CsvTable t = pkmopt::parse_csv(r.out, "out");
  ASSERT_EQ(t.rows.size(), 1u);
  EXPECT_EQ(t.rows[0].cells[t.column("x")], "0");
  EXPECT_EQ(t.rows[0].cells[t.column("z")], "0.9");
  EXPECT_EQ(t.rows[0].cells[t.column("rz")], "0");
  EXPECT_EQ(t.rows[0].cells[t.column("singularity_margin")], "0");
  EXPECT_EQ(t.rows[0].cells[t.column("stiffness_min")], "0");
  EXPECT_EQ(t.rows[0].cells[t.column("tau_1")], "inf");
  EXPECT_EQ(t.rows[0].cells[t.column("tcp_error_max")], "inf");
  EXPECT_EQ(r.out.find("nan"), std::string::npos);
}

TEST_F(Cli, FkRecoversThePose) {
  const pkmopt::Hexapod hexapod(sample_machines::conventions_hexapod_design());
  const pkmopt::Pose pose{{0.05, 0.02, 0.88}, pkmopt::deg_to_rad(Eigen::Vector3d(3, -4, 12))};
  const auto q = hexapod.inverse_kinematics(pose);
  std::string qs;
  for (int i = 0; i < 6; ++i) qs += (i ? "," : "") + pkmopt::format_number(q(i));
  const CliRun r = run("fk " + machine_ + " --q " + qs);
  ASSERT_EQ(r.status, 0) << r.err;
  const pkmopt::CsvTable t = pkmopt::parse_csv(r.out, "out");
  EXPECT_EQ(r.out.substr(0, r.out.find('\n')), "x,y,z,rx,ry,rz,converged,iterations,residual");
  ASSERT_EQ(t.rows.size(), 1u);
  EXPECT_EQ(t.rows[0].cells[6], "1");
  EXPECT_NEAR(t.number(t.rows[0], 0), 0.05, 1e-12);
  EXPECT_NEAR(t.number(t.rows[0], 2), 0.88, 1e-12);
  EXPECT_NEAR(t.number(t.rows[0], 5), 12.0, 1e-9);
  const CliRun guessed = run("fk " + machine_ + " --q " + qs + " --guess 0.04,0.03,0.9,2,-3,10");
  ASSERT_EQ(guessed.status, 0);
  EXPECT_EQ(pkmopt::parse_csv(guessed.out, "o").rows[0].cells[6], "1");
}

// --all: every real assembly mode, the pose the lengths came from first (nearest the guess);
// each row solves the lengths, modes below the base are there (the base is planar), the
// counts add up to 40 paths, and a model without the solver is refused with one line.
TEST_F(Cli, FkAllListsEveryAssemblyMode) {
  const pkmopt::Hexapod hexapod(sample_machines::conventions_hexapod_design());
  const pkmopt::Pose pose{{0.05, 0.02, 0.88}, pkmopt::deg_to_rad(Eigen::Vector3d(3, -4, 12))};
  const auto q = hexapod.inverse_kinematics(pose);
  std::string qs;
  for (int i = 0; i < 6; ++i) qs += (i ? "," : "") + pkmopt::format_number(q(i));
  const CliRun r = run("fk " + machine_ + " --q " + qs + " --all --guess 0.05,0.02,0.9,0,0,0");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(r.out.substr(0, r.out.find('\n')),
            "mode,x,y,z,rx,ry,rz,residual,det_j,reachable,nearest_other,to_reference");
  const pkmopt::CsvTable t = pkmopt::parse_csv(r.out, "out");
  ASSERT_GE(t.rows.size(), 2u);
  EXPECT_EQ(t.rows.size() % 2, 0u);
  EXPECT_NEAR(t.number(t.rows[0], t.require_column("x")), 0.05, 1e-9);
  EXPECT_NEAR(t.number(t.rows[0], t.require_column("z")), 0.88, 1e-9);
  EXPECT_NEAR(t.number(t.rows[0], t.require_column("rz")), 12.0, 1e-7);
  EXPECT_EQ(t.rows[0].cells[t.require_column("reachable")], "1");
  bool mirrored = false;
  for (const auto& row : t.rows) {
    const pkmopt::Pose p{
        {t.number(row, 1), t.number(row, 2), t.number(row, 3)},
        pkmopt::deg_to_rad(Eigen::Vector3d(t.number(row, 4), t.number(row, 5), t.number(row, 6)))};
    EXPECT_LT((hexapod.inverse_kinematics(p) - q).cwiseAbs().maxCoeff(), 1e-9);
    mirrored = mirrored || p.position.z() < 0.0;
  }
  EXPECT_TRUE(mirrored) << r.out;
  EXPECT_NE(r.err.find("of 40 paths"), std::string::npos) << r.err;
  const CliRun delta =
      run("fk " + std::string(PKMOPT_SOURCE_DIR) + "/examples/delta.yaml --q 10,20,30 --all");
  EXPECT_EQ(delta.status, 2);
  EXPECT_NE(delta.err.find("--all: expected a hexapod machine file"), std::string::npos)
      << delta.err;
}

// A machine whose platform is its base scaled by 1/2 (similar planar hexagons) is singular at
// every pose: --all says its solutions are curves, not a finite set, and exits 3.
TEST_F(Cli, FkAllSaysWhenTheSolutionsAreCurves) {
  std::string base = "[", platform = "[";
  for (int i = 0; i < 6; ++i) {
    const double angle = (i / 2) * 2.0 * M_PI / 3.0 + (i % 2 ? 0.17 : -0.17);
    base +=
        fmt::format("{}[{}, {}, 0]", i ? ", " : "", 0.6 * std::cos(angle), 0.6 * std::sin(angle));
    platform +=
        fmt::format("{}[{}, {}, 0]", i ? ", " : "", 0.3 * std::cos(angle), 0.3 * std::sin(angle));
  }
  const fs::path file = dir_ / "similar.yaml";
  std::ofstream(file) << "model: hexapod\nbase_joints: " << base
                      << "]\nplatform_joints: " << platform
                      << "]\nlegs: {min_length: 0.3, max_length: 1.5, axial_stiffness: 1e8}\n";
  // The leg lengths at a pose, from the machine as loaded.
  const auto machine = pkmopt::load_machine_file(file.string());
  const auto& hexapod = dynamic_cast<const pkmopt::Hexapod&>(*machine);
  const auto q = hexapod.inverse_kinematics(pkmopt::Pose{{0.02, -0.01, 0.8}, {0.05, 0.0, 0.1}});
  std::string qs;
  for (int i = 0; i < 6; ++i) qs += (i ? "," : "") + pkmopt::format_number(q(i));
  const CliRun r = run("fk " + file.string() + " --q " + qs + " --all");
  EXPECT_EQ(r.status, 3) << r.err;
  EXPECT_NE(r.err.find("singular at every pose"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("not a finite set of assembly modes"), std::string::npos) << r.err;
}

// The row is written (converged = 0) and the exit status is 3: a result that is probably wrong.
TEST_F(Cli, FkThatCannotConvergeIsAResultNotACrash) {
  const CliRun r = run("fk " + machine_ + " --q 0.01,0.01,0.01,0.01,0.01,0.01");
  EXPECT_EQ(r.status, 3);
  EXPECT_EQ(r.err.rfind("pkmopt: warning: fk: ", 0), 0u) << r.err;
  const pkmopt::CsvTable t = pkmopt::parse_csv(r.out, "out");
  EXPECT_EQ(t.rows[0].cells[6], "0");
  EXPECT_EQ(r.out.find("nan"), std::string::npos);
  EXPECT_NE(r.err.find("did not converge"), std::string::npos);
}

TEST_F(Cli, VersionAndHelp) {
  CliRun r = run("--version");
  EXPECT_EQ(r.status, 0);
  EXPECT_EQ(r.out.rfind("pkmopt ", 0), 0u);
  for (const char* cmd : {"--help", "analyze --help", "fk --help"}) {
    r = run(cmd);
    EXPECT_EQ(r.status, 0) << cmd;
    EXPECT_NE(r.out.find("Usage"), std::string::npos) << cmd;
  }
  EXPECT_EQ(run("").status, 2);
  EXPECT_EQ(run("frobnicate").status, 2);
  EXPECT_EQ(run("analyze " + machine_).status, 2);  // --poses is required
}

TEST_F(Cli, BadMachineFiles) {
  const std::string args = " --poses " + poses_;
  expect_input_error("analyze " + (dir_ / "missing.yaml").string() + args,
                     "missing.yaml: cannot open the file");
  expect_input_error("analyze " + write("bad.yaml", "model: hexapod\nbase: [1, 2\n") + args,
                     "bad.yaml:3:1: malformed YAML");
  const std::string good = read_text(machine_);
  auto variant = [&](const std::string& from, const std::string& to) {
    std::string text = good;
    text.replace(text.find(from), from.size(), to);
    return write("variant.yaml", text);
  };
  expect_input_error("analyze " + variant("tool:", "tools:") + args,
                     "variant.yaml:7:1: tools: unknown key 'tools'");
  expect_input_error("analyze " +
                         write("joints.yaml",
                               "model: hexapod\nbase_joints: [[0,0,0],[1,0,0],[0,1,0]]\n"
                               "platform: {radius: 0.2, pair_separation_deg: 20}\n"
                               "legs: {min_length: 0.5, max_length: 1, axial_stiffness: 1e7}\n") +
                         args,
                     "joints.yaml:2:14: base_joints: expected a list of 6, found a list of 3");
  expect_input_error("analyze " + variant("area: 3.0e-4", "area: .inf") + args,
                     "legs.area: expected a finite number, found '.inf'");
  expect_input_error("analyze " + variant("max_length: 1.15", "max_length: 0.70") + args,
                     "legs.max_length: expected a number > legs.min_length (0.7), found '0.70'");
  expect_input_error("analyze " + variant("model: hexapod", "model: delta9") + args,
                     "model: expected a known model");
  expect_input_error("analyze " + variant("E: 2.1e11", "E: -2.1e11") + args,
                     "legs.E: expected a number > 0, found '-2.1e11'");
}

TEST_F(Cli, BadPoseFilesAndOptions) {
  expect_input_error("analyze " + machine_ + " --poses " + write("nox.csv", "a,y,z\n1,2,3\n"),
                     "nox.csv:1: expected a column 'x' in the header, found 'a,y,z'");
  expect_input_error(
      "analyze " + machine_ + " --poses " + write("text.csv", "x,y,z\n0,0,0.9\n0,zero,0.9\n"),
      "text.csv:3: column 2 'y': expected a finite number, found 'zero'");
  expect_input_error(
      "analyze " + machine_ + " --poses " + write("nan.csv", "x,y,z,rx\n0,0,0.9,nan\n"),
      "nan.csv:2: column 4 'rx': expected a finite number, found 'nan'");
  expect_input_error("analyze " + machine_ + " --poses " + write("ragged.csv", "x,y,z\n0,0\n"),
                     "ragged.csv:2: expected 3 fields as in the header, found 2");
  expect_input_error("analyze " + machine_ + " --poses " + (dir_ / "none.csv").string(),
                     "none.csv: cannot open the file");
  expect_input_error("analyze " + machine_ + " --poses " + poses_ + " --wrench 1,2,3",
                     "--wrench: expected 6 comma-separated finite numbers, found '1,2,3'");
  expect_input_error("analyze " + machine_ + " --poses " + poses_ + " --wrench 1,2,3,4,5,x",
                     "--wrench: expected 6 comma-separated finite numbers");
  // An output folder that does not exist.
  const CliRun r = run("analyze " + machine_ + " --poses " + poses_ + " --out " +
                       (dir_ / "no/such/dir/out.csv").string());
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("cannot write the output file"), std::string::npos);
}

TEST_F(Cli, BadFkInput) {
  CliRun r = run("fk " + machine_ + " --q 1,1,1");
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("--q: expected 6 comma-separated finite numbers, found '1,1,1'"),
            std::string::npos);
  r = run("fk " + machine_ + " --q 1,1,1,1,1,-1");
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("leg lengths > 0"), std::string::npos);
  r = run("fk " + machine_ + " --q 1,1,1,1,1,1 --guess 0,0,inf,0,0,0");
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("--guess"), std::string::npos);
  EXPECT_TRUE(r.out.empty());
}

}  // namespace

namespace {

// An error message that cannot be written (stderr on a full device) still ends in the exit
// status of the error, never an abort.
TEST(CliErrors, UnwritableStderrKeepsTheExitStatus) {
  const std::string command =
      std::string(PKMOPT_CLI) + " describe /nonexistent/machine.yaml >/dev/null 2>/dev/full";
  const int raw = std::system(command.c_str());
  ASSERT_TRUE(WIFEXITED(raw)) << raw;
  EXPECT_EQ(WEXITSTATUS(raw), 2);
}

}  // namespace
