// Tests of `pkmopt run` (benchmark and design studies: outputs, strict study files, journal,
// SIGKILL and --resume, thread independence) and of `pkmopt validate`.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>

namespace {

namespace fs = std::filesystem;

struct CommandResult {
  int status;
  std::string err;
};

CommandResult run_pkmopt(const std::string& args, const fs::path& work) {
  const fs::path err_file = work / "stderr.txt";
  const std::string command =
      std::string(PKMOPT_CLI) + " run " + args + " 2> " + err_file.string() + " > /dev/null";
  const int raw = std::system(command.c_str());
  std::ifstream in(err_file);
  std::stringstream text;
  text << in.rdbuf();
  return {WEXITSTATUS(raw), text.str()};
}

fs::path fresh_dir(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / ("pkmopt_run_test_" + name);
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

TEST(RunCommand, WritesFrontAndSummary) {
  const fs::path dir = fresh_dir("ok");
  std::ofstream(dir / "study.yaml")
      << "study: small\n"
         "problem: {benchmark: zdt1, variables: 5}\n"
         "optimizer: {algorithm: nsga2, population: 20, generations: 10, seed: 3}\n";
  const CommandResult r =
      run_pkmopt((dir / "study.yaml").string() + " --out " + (dir / "out").string(), dir);
  ASSERT_EQ(r.status, 0) << r.err;
  std::ifstream csv(dir / "out" / "pareto.csv");
  std::string header;
  std::getline(csv, header);
  EXPECT_EQ(header, "x_1,x_2,x_3,x_4,x_5,f_1,f_2");
  std::ifstream summary_file(dir / "out" / "summary.json");
  std::stringstream summary;
  summary << summary_file.rdbuf();
  EXPECT_NE(summary.str().find("\"evaluations\": 220"), std::string::npos) << summary.str();
  EXPECT_NE(summary.str().find("\"hypervolume\""), std::string::npos);
  EXPECT_NE(summary.str().find("\"seed\": 3"), std::string::npos);
}

TEST(RunCommand, UnknownKeyIsAnErrorWithLocation) {
  const fs::path dir = fresh_dir("bad_key");
  std::ofstream(dir / "study.yaml") << "study: bad\n"
                                       "problem: {benchmark: zdt1}\n"
                                       "optimizer: {algorithm: nsga2, populaton: 20}\n";
  const CommandResult r =
      run_pkmopt((dir / "study.yaml").string() + " --out " + (dir / "out").string(), dir);
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("study.yaml:3:"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("populaton"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir / "out" / "pareto.csv"));
}

TEST(RunCommand, UnsupportedAlgorithmIsAnError) {
  const fs::path dir = fresh_dir("unsupported");
  std::ofstream(dir / "study.yaml") << "study: bad\n"
                                       "problem: {benchmark: hs71}\n"
                                       "optimizer: {algorithm: \"nlopt:BOBYQA\"}\n";
  const CommandResult r =
      run_pkmopt((dir / "study.yaml").string() + " --out " + (dir / "out").string(), dir);
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("equality constraints"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir / "out" / "summary.json"));
}

TEST(RunCommand, UnknownBenchmarkIsAnError) {
  const fs::path dir = fresh_dir("unknown");
  std::ofstream(dir / "study.yaml") << "study: bad\n"
                                       "problem: {benchmark: zdt5}\n"
                                       "optimizer: {algorithm: nsga2}\n";
  const CommandResult r =
      run_pkmopt((dir / "study.yaml").string() + " --out " + (dir / "out").string(), dir);
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("zdt5"), std::string::npos) << r.err;
}

}  // namespace

// ---- pkmopt run: journal, kill and resume, threads; pkmopt validate ----

namespace {

namespace fs = std::filesystem;

std::string file_text(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

std::size_t lines_in(const fs::path& path) {
  const std::string text = file_text(path);
  return static_cast<std::size_t>(std::count(text.begin(), text.end(), '\n'));
}

// hexapod-quick with a shorter NSGA-II run (40 x 40: 1640 evaluations, about 1 s on one core).
std::string quick_study_text() {
  std::string text = file_text(fs::path(PKMOPT_SOURCE_DIR) / "studies" / "hexapod-quick.yaml");
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

int run_quiet(const std::string& args) {
  const std::string command = std::string(PKMOPT_CLI) + " " + args + " > /dev/null 2>&1";
  const int raw = std::system(command.c_str());
  return WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
}

TEST(RunResume, KilledRunResumesToTheSameFront) {
  const fs::path dir = fresh_dir("resume");
  const fs::path study = dir / "quick.yaml";
  std::ofstream(study) << quick_study_text();
  // Uninterrupted runs with 1 and 2 threads.
  ASSERT_EQ(run_quiet("run " + study.string() + " --out " + (dir / "t1").string() + " --threads 1"),
            0);
  ASSERT_EQ(run_quiet("run " + study.string() + " --out " + (dir / "t2").string() + " --threads 2"),
            0);
  const std::string front = file_text(dir / "t1" / "pareto.csv");
  EXPECT_GT(std::count(front.begin(), front.end(), '\n'), 2);
  EXPECT_EQ(file_text(dir / "t2" / "pareto.csv"), front);
  EXPECT_EQ(file_text(dir / "t2" / "journal.txt"), file_text(dir / "t1" / "journal.txt"));
  const std::size_t full_lines = lines_in(dir / "t1" / "journal.txt");

  // A run killed with SIGKILL once its journal holds a few generations.
  const fs::path killed = dir / "killed";
  const pid_t child = fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    std::freopen("/dev/null", "w", stdout);
    std::freopen("/dev/null", "w", stderr);
    execl(PKMOPT_CLI, "pkmopt", "run", study.c_str(), "--out", killed.c_str(), "--threads", "1",
          static_cast<char*>(nullptr));
    _exit(127);
  }
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
  EXPECT_EQ(run_quiet("run " + study.string() + " --out " + killed.string()), 2);
  ASSERT_EQ(
      run_quiet("run " + study.string() + " --out " + killed.string() + " --threads 2 --resume"),
      0);
  EXPECT_EQ(file_text(killed / "pareto.csv"), front);
  EXPECT_EQ(file_text(killed / "pareto.json"), file_text(dir / "t1" / "pareto.json"));
  EXPECT_EQ(lines_in(killed / "journal.txt"), full_lines);
  EXPECT_EQ(file_text(killed / "journal.txt"), file_text(dir / "t1" / "journal.txt"));
  EXPECT_EQ(file_text(killed / "evaluations.csv"), file_text(dir / "t1" / "evaluations.csv"));
  const std::string summary = file_text(killed / "summary.json");
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

TEST(RunResume, ChangedStudyIsRefused) {
  const fs::path dir = fresh_dir("changed");
  std::ofstream(dir / "study.yaml")
      << "study: small\n"
         "problem: {benchmark: zdt1, variables: 5}\n"
         "optimizer: {algorithm: nsga2, population: 8, generations: 2, seed: 3}\n";
  ASSERT_EQ(run_quiet("run " + (dir / "study.yaml").string() + " --out " + (dir / "out").string()),
            0);
  EXPECT_EQ(lines_in(dir / "out" / "evaluations.csv"), 1u + 24u);
  std::ofstream(dir / "study.yaml")
      << "study: small\n"
         "problem: {benchmark: zdt1, variables: 5}\n"
         "optimizer: {algorithm: nsga2, population: 8, generations: 2, seed: 4}\n";
  const CommandResult r = run_pkmopt(
      (dir / "study.yaml").string() + " --out " + (dir / "out").string() + " --resume", dir);
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("the study file changed since the run started"), std::string::npos) << r.err;
  // --force starts over.
  EXPECT_EQ(run_quiet("run " + (dir / "study.yaml").string() + " --out " + (dir / "out").string() +
                      " --force"),
            0);
}

CommandResult validate(const std::string& text, const fs::path& dir) {
  std::ofstream(dir / "study.yaml") << text;
  const fs::path err_file = dir / "stderr.txt";
  const std::string command = std::string(PKMOPT_CLI) + " validate " +
                              (dir / "study.yaml").string() + " 2> " + err_file.string() + " > " +
                              (dir / "stdout.txt").string();
  const int raw = std::system(command.c_str());
  return {WEXITSTATUS(raw), file_text(err_file) + file_text(dir / "stdout.txt")};
}

TEST(Validate, PrintsASummaryOfAValidStudy) {
  const fs::path dir = fresh_dir("validate_ok");
  const CommandResult r =
      validate(file_text(fs::path(PKMOPT_SOURCE_DIR) / "studies" / "hexapod-quick.yaml"), dir);
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.err.find("design study 'hexapod-quick' (model hexapod) is valid"), std::string::npos)
      << r.err;
  EXPECT_NE(r.err.find("free parameters (7):"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("objectives (2): maximize stiffness_min minimize machine_size"),
            std::string::npos)
      << r.err;
  EXPECT_NE(r.err.find("constraints (2): task_reachable leg_force_max <= 10500"), std::string::npos)
      << r.err;
  // 2 x 2 x 2 positions x (1 + 7) orientations: the rim of a 20 deg cone sampled every 20 deg
  // holds max(4, ceil(2 pi sin(20 deg) / 20 deg)) = ceil(6.16) = 7 azimuths.
  EXPECT_NE(r.err.find("task: 64 poses (8 positions x 8 orientations)"), std::string::npos)
      << r.err;
  EXPECT_NE(r.err.find("optimizer: nsga2 (population 60, generations 80, seed 1: 4860 "
                       "evaluations), aggregate formulation"),
            std::string::npos)
      << r.err;
  EXPECT_FALSE(fs::exists(dir / "out"));
}

TEST(Validate, SchemaErrorsAreExact) {
  const fs::path dir = fresh_dir("validate_bad");
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
  ASSERT_EQ(validate(quick, dir).status, 0);
  const std::string file = (dir / "study.yaml").string();
  auto with = [&](const std::string& from, const std::string& to) {
    std::string text = quick;
    const std::size_t at = text.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    return text.replace(at, from.size(), to);
  };
  // Unknown key.
  CommandResult r = validate(with("  tool: {tcp:", "  tools: {tcp:"), dir);
  EXPECT_EQ(r.status, 2);
  EXPECT_EQ(r.err, "pkmopt: error: " + file +
                       ":8:3: machine.tools: unknown key 'tools'; allowed keys here: model, "
                       "parameters, legs, joints, tool, actuator_error\n");
  // Wrong type.
  r = validate(with("wrench: [300, 300, -3000, 0, 0, 0]", "wrench: [300, 300, heavy, 0, 0, 0]"),
               dir);
  EXPECT_EQ(r.status, 2);
  EXPECT_EQ(r.err, "pkmopt: error: " + file +
                       ":11:22: task.wrench[2]: expected a finite number, found 'heavy'\n");
  // Out-of-range bound (max <= min).
  r = validate(with("stroke: {min: 0.35, max: 0.70}", "stroke: {min: 0.35, max: 0.35}"), dir);
  EXPECT_EQ(r.status, 2);
  EXPECT_EQ(r.err, "pkmopt: error: " + file +
                       ":6:30: machine.parameters.stroke.max: expected max > min, found "
                       "'0.35'\n");
  // Missing section.
  std::string no_task = quick;
  const std::size_t task_at = no_task.find("task:\n");
  const std::size_t objectives_at = no_task.find("objectives:\n");
  no_task.erase(task_at, objectives_at - task_at);
  r = validate(no_task, dir);
  EXPECT_EQ(r.status, 2);
  EXPECT_EQ(r.err, "pkmopt: error: " + file + ":1:1: missing required key 'task'\n");
}

}  // namespace
