// Tests of `pkmopt run` (benchmark and design studies: outputs, strict study files, journal,
// SIGKILL and --resume, thread independence) and of `pkmopt validate`.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>

#include "tests/cli_runner.hpp"
#include "tests/scratch_dir.hpp"

namespace {

namespace fs = std::filesystem;
using cli_runner::CliRun;
using cli_runner::read_text;

// Every test has its own scratch folder dir_.
class RunCommand : public scratch::ScratchDirTest {};
class RunResume : public scratch::ScratchDirTest {};
class Validate : public scratch::ScratchDirTest {
 protected:
  // `pkmopt validate` of a study with this text; err holds standard error then standard output.
  CliRun validate(const std::string& text) {
    write("study.yaml", text);
    CliRun r = run_cli("validate " + path("study.yaml"));
    r.err += r.out;
    return r;
  }
};

std::size_t lines_in(const fs::path& path) {
  const std::string text = read_text(path);
  return static_cast<std::size_t>(std::count(text.begin(), text.end(), '\n'));
}

// hexapod-quick with a shorter NSGA-II run (40 x 40: 1640 evaluations, about 1 s on one core).
std::string quick_study_text() {
  std::string text =
      read_text(fs::path(PKMOPT_SOURCE_DIR) / "studies" / "library" / "hexapod-quick.yaml");
  const std::string from =
      "optimizer: {algorithm: nsga2, population: 60, generations: 80, seed: 1}";
  const std::size_t at = text.find(from);
  EXPECT_NE(at, std::string::npos);
  return text.replace(at, from.size(),
                      "optimizer: {algorithm: nsga2, population: 40, generations: 40, seed: 1}");
}

std::string fmt_number_key(const std::string& key, std::size_t value) {
  return "\"" + key + "\": " + std::to_string(value);
}

TEST_F(RunCommand, WritesFrontAndSummary) {
  write("study.yaml",
        "study: small\n"
        "problem: {benchmark: zdt1, variables: 5}\n"
        "optimizer: {algorithm: nsga2, population: 20, generations: 10, seed: 3}\n");
  const CliRun r = run_cli("run " + path("study.yaml") + " --out " + path("out"));
  ASSERT_EQ(r.status, 0) << r.err;
  std::ifstream csv(dir_ / "out" / "pareto.csv");
  std::string header;
  std::getline(csv, header);
  EXPECT_EQ(header, "x_1,x_2,x_3,x_4,x_5,f_1,f_2");
  const std::string summary = read_text(dir_ / "out" / "summary.json");
  // NSGA-II evaluates the initial population and one offspring population per generation:
  // 20 x (10 + 1) = 220.
  EXPECT_NE(summary.find("\"evaluations\": 220"), std::string::npos) << summary;
  EXPECT_NE(summary.find("\"hypervolume\""), std::string::npos);
  EXPECT_NE(summary.find("\"seed\": 3"), std::string::npos);
}

// The optimizer-section errors of a study file (an unknown key, an algorithm that cannot take
// the problem) are tested in tests/studies/optimizer_spec_test.cpp, an unknown benchmark in
// tests/studies/benchmark_study_test.cpp, and that a refused study writes nothing in
// tests/studies/run_study_test.cpp.

TEST_F(RunResume, KilledRunResumesToTheSameFront) {
  const fs::path& dir = dir_;
  const fs::path study = write("quick.yaml", quick_study_text());
  // Uninterrupted runs with 1 and 2 threads.
  ASSERT_EQ(
      run_cli("run " + study.string() + " --out " + (dir / "t1").string() + " --threads 1").status,
      0);
  ASSERT_EQ(
      run_cli("run " + study.string() + " --out " + (dir / "t2").string() + " --threads 2").status,
      0);
  const std::string front = read_text(dir / "t1" / "pareto.csv");
  EXPECT_GT(std::count(front.begin(), front.end(), '\n'), 2);
  EXPECT_EQ(read_text(dir / "t2" / "pareto.csv"), front);
  EXPECT_EQ(read_text(dir / "t2" / "journal.txt"), read_text(dir / "t1" / "journal.txt"));
  const std::size_t full_lines = lines_in(dir / "t1" / "journal.txt");

  // A run killed with SIGKILL once its journal holds a few generations.
  const fs::path killed = dir / "killed";
  const pid_t child =
      cli_runner::spawn_cli({"run", study.string(), "--out", killed.string(), "--threads", "1"});
  ASSERT_GE(child, 0);
  const auto give_up = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  while (std::chrono::steady_clock::now() < give_up &&
         (!fs::exists(killed / "journal.txt") || lines_in(killed / "journal.txt") < 200))
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  int status = 0;
  const bool still_running = waitpid(child, &status, WNOHANG) == 0;
  kill(child, SIGKILL);
  waitpid(child, &status, 0);
  ASSERT_TRUE(still_running) << "the run ended before it could be killed";
  const std::size_t killed_lines = lines_in(killed / "journal.txt");
  EXPECT_LT(killed_lines, full_lines);
  EXPECT_FALSE(fs::exists(killed / "pareto.csv"));

  // Without --resume the folder is refused; with it the run completes.
  EXPECT_EQ(run_cli("run " + study.string() + " --out " + killed.string()).status, 2);
  ASSERT_EQ(run_cli("run " + study.string() + " --out " + killed.string() + " --threads 2 --resume")
                .status,
            0);
  EXPECT_EQ(read_text(killed / "pareto.csv"), front);
  EXPECT_EQ(read_text(killed / "pareto.json"), read_text(dir / "t1" / "pareto.json"));
  EXPECT_EQ(lines_in(killed / "journal.txt"), full_lines);
  EXPECT_EQ(read_text(killed / "journal.txt"), read_text(dir / "t1" / "journal.txt"));
  EXPECT_EQ(read_text(killed / "evaluations.csv"), read_text(dir / "t1" / "evaluations.csv"));
  const std::string summary = read_text(killed / "summary.json");
  // Only the evaluations missing from the journal were computed again.
  const std::size_t loaded = killed_lines - 1;  // header line
  EXPECT_NE(summary.find(fmt_number_key("evaluations_loaded_from_journal", loaded)),
            std::string::npos)
      << summary;
  EXPECT_NE(summary.find(fmt_number_key("evaluations_new", full_lines - 1 - loaded)),
            std::string::npos)
      << summary;
  EXPECT_NE(summary.find("\"resumed\": true"), std::string::npos);
}

TEST_F(RunResume, ChangedStudyIsRefused) {
  const fs::path& dir = dir_;
  write("study.yaml",
        "study: small\n"
        "problem: {benchmark: zdt1, variables: 5}\n"
        "optimizer: {algorithm: nsga2, population: 8, generations: 2, seed: 3}\n");
  ASSERT_EQ(
      run_cli("run " + (dir / "study.yaml").string() + " --out " + (dir / "out").string()).status,
      0);
  // The header and one row per evaluation: 8 x (2 + 1) = 24.
  EXPECT_EQ(lines_in(dir / "out" / "evaluations.csv"), 1u + 24u);
  write("study.yaml",
        "study: small\n"
        "problem: {benchmark: zdt1, variables: 5}\n"
        "optimizer: {algorithm: nsga2, population: 8, generations: 2, seed: 4}\n");
  const CliRun r = run_cli("run " + (dir / "study.yaml").string() + " --out " +
                           (dir / "out").string() + " --resume");
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("the study file changed since the run started"), std::string::npos) << r.err;
  // --force starts over.
  EXPECT_EQ(run_cli("run " + (dir / "study.yaml").string() + " --out " + (dir / "out").string() +
                    " --force")
                .status,
            0);
}

TEST_F(Validate, PrintsASummaryOfAValidStudy) {
  const fs::path& dir = dir_;
  const CliRun r = validate(
      read_text(fs::path(PKMOPT_SOURCE_DIR) / "studies" / "library" / "hexapod-quick.yaml"));
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.err.find("design study 'hexapod-quick' (model hexapod) is valid"), std::string::npos)
      << r.err;
  EXPECT_NE(r.err.find("design space: 7 free of 7 parameters"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("    base_pair_separation_deg               10 .. 40         deg\n"),
            std::string::npos)
      << r.err;
  EXPECT_NE(r.err.find("objectives (2):\n    maximize stiffness_min (N/m)\n    minimize "
                       "machine_size (m^3)\n"),
            std::string::npos)
      << r.err;
  EXPECT_NE(r.err.find("constraints (2):\n    task_reachable (every task pose within the strokes "
                       "and joint limits)\n    leg_force_max <= 10500 N\n"),
            std::string::npos)
      << r.err;
  // 2 x 2 x 2 positions x (1 + 7) orientations: the rim of a 20 deg cone sampled every 20 deg
  // holds max(4, ceil(2 pi sin(20 deg) / 20 deg)) = ceil(6.16) = 7 azimuths.
  EXPECT_NE(r.err.find("task: box region centred at (0, 0, 0.9) m; 64 poses = 8 positions x 8 "
                       "orientations (tilt <= 20 deg, yaw +-0 deg)"),
            std::string::npos)
      << r.err;
  // The box 0.3 x 0.3 x 0.2 m about (0, 0, 0.9). The angle extents are a regression pin of the
  // sampled cone's rx, ry (R = Rz Ry Rx), from `pkmopt validate studies/library/hexapod-quick.yaml`
  // (the 20 deg bound itself is checked in tests/app/task_poses_cli_test.cpp).
  EXPECT_NE(r.err.find("x -0.15 .. 0.15, y -0.15 .. 0.15, z 0.8 .. 1 m\n    angles: rx -18.16 .. "
                       "20, ry -19.48 .. 19.48"),
            std::string::npos)
      << r.err;
  EXPECT_NE(r.err.find("wrench at the TCP (base axes): force [300, 300, -3000] N, moment [0, 0, 0] "
                       "N*m; as typed"),
            std::string::npos)
      << r.err;
  // 60 x (80 + 1) = 4860 evaluations.
  EXPECT_NE(r.err.find("optimizer: nsga2 (population 60, generations 80, seed 1: 4860 "
                       "evaluations), aggregate formulation"),
            std::string::npos)
      << r.err;
  EXPECT_FALSE(fs::exists(dir / "out"));
}

TEST_F(Validate, SchemaErrorsAreExact) {
  const fs::path& dir = dir_;
  const std::string quick =
      "study: hexapod-quick\n"
      "machine:\n"
      "  model: hexapod\n"
      "  parameters:\n"
      "    base_radius: {min: 0.45, max: 0.75}\n"
      "    stroke: {min: 0.35, max: 0.70}\n"
      "  legs: {E: 2.1e11, area: 3.0e-4, actuator_stiffness: 2.0e8}\n"
      "  tool: {tcp: [0, 0, -0.10]}\n"
      "task:\n"
      "  region: {shape: box, centre: [0, 0, 0.90], size: [0.30, 0.30, 0.20]}\n"
      "  wrench: [300, 300, -3000, 0, 0, 0]\n"
      "objectives:\n"
      "  - maximize: stiffness_min\n"
      "  - minimize: machine_size\n"
      "optimizer: {algorithm: nsga2, population: 8, generations: 2, seed: 1}\n";
  ASSERT_EQ(validate(quick).status, 0);
  const std::string file = (dir / "study.yaml").string();
  auto with = [&](const std::string& from, const std::string& to) {
    std::string text = quick;
    const std::size_t at = text.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    return text.replace(at, from.size(), to);
  };
  // Unknown key.
  CliRun r = validate(with("  tool: {tcp:", "  tools: {tcp:"));
  EXPECT_EQ(r.status, 2);
  EXPECT_EQ(r.err, "pkmopt: error: " + file +
                       ":8:3: machine.tools: unknown key 'tools'; allowed keys here: model, "
                       "parameters, legs, min_clearance, bodies, joints, tool, actuator_error, "
                       "masses, gravity\n");
  // Wrong type.
  r = validate(with("wrench: [300, 300, -3000, 0, 0, 0]", "wrench: [300, 300, heavy, 0, 0, 0]"));
  EXPECT_EQ(r.status, 2);
  EXPECT_EQ(r.err, "pkmopt: error: " + file +
                       ":11:22: task.wrench[2]: expected a finite number, found 'heavy'\n");
  // Out-of-range bound (max <= min).
  r = validate(with("stroke: {min: 0.35, max: 0.70}", "stroke: {min: 0.35, max: 0.35}"));
  EXPECT_EQ(r.status, 2);
  EXPECT_EQ(r.err, "pkmopt: error: " + file +
                       ":6:30: machine.parameters.stroke.max: expected max > min, found "
                       "'0.35'\n");
  // Missing section.
  std::string no_task = quick;
  const std::size_t task_at = no_task.find("task:\n");
  const std::size_t objectives_at = no_task.find("objectives:\n");
  no_task.erase(task_at, objectives_at - task_at);
  r = validate(no_task);
  EXPECT_EQ(r.status, 2);
  EXPECT_EQ(r.err, "pkmopt: error: " + file + ":1:1: missing required key 'task'\n");
}

}  // namespace
