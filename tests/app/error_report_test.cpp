// Tests of app/error_report and the error contract of every command: hostile input gives one
// line "pkmopt: error: ..." and exit status 2 (never a crash, a hang, a NaN, exit 1 or an output
// file), a result that is probably wrong exits 3, and every command's exit statuses are the
// documented ones (docs/conventions.md, "Exit status"). Each regression test is named after the
// input that once crashed, hung, wrote NaN or exited 1.
#include "app/error_report.hpp"

#include <gtest/gtest.h>
#include <sys/stat.h>
#include <sys/wait.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "tests/cli_runner.hpp"
#include "tests/scratch_dir.hpp"

namespace {

namespace fs = std::filesystem;
using cli_runner::CliRun;
using cli_runner::read_text;

class ErrorContract : public scratch::ScratchDirTest {
 protected:
  static std::string example(const std::string& name) {
    return (fs::path(PKMOPT_SOURCE_DIR) / "examples" / name).string();
  }
  static std::string library(const std::string& name) {
    return (fs::path(PKMOPT_SOURCE_DIR) / "studies/library" / name).string();
  }
  // pkmopt with a 120 s limit (a hang shows as status 124) and its stdout/stderr captured.
  CliRun run(const std::string& args) const {
    return cli_runner::run_command(dir_, "timeout 120 " + std::string(PKMOPT_CLI) + " " + args);
  }
  // Status 2, one line "pkmopt: error: ..." holding `fragment`, and the folder holding nothing
  // it did not hold before (no output file, no temporary).
  void expect_refused(const std::string& args, const std::string& fragment) const {
    std::vector<fs::path> before;
    for (const auto& e : fs::recursive_directory_iterator(dir_)) before.push_back(e.path());
    const CliRun r = run(args);
    EXPECT_EQ(r.status, 2) << args << "\n" << r.err;
    EXPECT_EQ(r.err.rfind("pkmopt: error: ", 0), 0u) << args << "\n" << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << args << "\n" << r.err;
    EXPECT_NE(r.err.find(fragment), std::string::npos) << args << "\n" << r.err;
    for (const auto& e : fs::recursive_directory_iterator(dir_))
      EXPECT_NE(std::find(before.begin(), before.end(), e.path()), before.end())
          << args << " left " << e.path();
  }
  // examples/hexapod.yaml with another tool line.
  static std::string with_tool(const std::string& tool) {
    std::string machine = read_text(example("hexapod.yaml"));
    const std::string line = "tool: {tcp: [0, 0, -0.10]}";
    machine.replace(machine.find(line), line.size(), "tool: {" + tool + "}");
    return machine;
  }
  // pkmopt with its standard output (or error) sent where `redirect` says, e.g. ">/dev/full";
  // returns the exit status and what reached the other stream.
  CliRun run_redirected(const std::string& args, const std::string& redirect) const {
    const fs::path other = dir_ / "other.txt";
    const bool stdout_redirected = redirect.find('>') == 0;
    const std::string cmd = "timeout 120 " + std::string(PKMOPT_CLI) + " " + args + " " + redirect +
                            (stdout_redirected ? " 2>" : " >") + other.string() + " </dev/null";
    const int raw = std::system(cmd.c_str());
    CliRun r;
    r.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
    (stdout_redirected ? r.err : r.out) = read_text(other);
    fs::remove(other);
    return r;
  }
  std::string tiny_study() const {
    return write("tiny.yaml",
                 "study: tiny\nproblem: {benchmark: zdt1, variables: 4}\n"
                 "optimizer: {algorithm: nsga2, population: 8, generations: 2, seed: 1}\n");
  }
};

// ---- Crashes ----------------------------------------------------------------------------------

TEST_F(ErrorContract, CalibrationPosesWithNanZeroLengthOrTinySigma) {
  for (const char* value : {"nan", "inf", "1e308", "1e-320"})
    expect_refused("calibration-poses " + example("hexapod.yaml") +
                       " --count 10 --grid --steps 2 --zero-length " + value,
                   "--zero-length");
  expect_refused("calibration-poses " + example("hexapod.yaml") +
                     " --count 10 --grid --steps 2 --sigma-actuator 1e-320",
                 "--sigma-actuator");
}

TEST_F(ErrorContract, RunWithHundredThousandThreads) {
  for (const char* threads : {"100000", "2147483647", "-1"})
    expect_refused(
        "run " + tiny_study() + " --out " + path("out") + " --threads " + threads,
        "--threads: expected an integer in [0, 512] (0: all cores), found " + std::string(threads));
}

TEST_F(ErrorContract, DescribeWithStderrOnAFullDisk) {
  const CliRun r = run_redirected("describe " + path("missing.yaml"), "2>/dev/full");
  EXPECT_EQ(r.status, 2);
}

// ---- Hangs ------------------------------------------------------------------------------------

TEST_F(ErrorContract, FkWithATcpFarBeyondTheMachine) {
  const std::string machine = with_tool("tcp: [0, 0, -1e16]");
  expect_refused("fk " + write("far.yaml", machine) + " --q 0.9,0.9,0.9,0.9,0.9,0.9", "tool.tcp");
  // Within the input limits (a 900 m tool): an answer, not a hang.
  const std::string reach = with_tool("tcp: [0, 0, -900]");
  const CliRun r = run("fk " + write("reach.yaml", reach) + " --q 0.9,0.9,0.9,0.9,0.9,0.9");
  EXPECT_TRUE(r.status == 0 || r.status == 3) << r.status << "\n" << r.err;
  EXPECT_EQ(r.out.find("nan"), std::string::npos) << r.out;
}

TEST_F(ErrorContract, SpecialFilesAsInput) {
  ASSERT_EQ(::mkfifo(path("fifo.yaml").c_str(), 0644), 0);
  expect_refused("describe " + path("fifo.yaml"), "expected a regular file, found a FIFO");
  expect_refused("describe /dev/zero", "/dev/zero: expected a regular file, found a character");
  expect_refused("describe /dev/urandom", "expected a regular file");
  fs::create_directories(dir_ / "folder.yaml");
  expect_refused("describe " + path("folder.yaml"), "expected a regular file, found a directory");
  expect_refused("analyze " + example("hexapod.yaml") + " --poses " + path("fifo.yaml"),
                 "expected a regular file, found a FIFO");
}

TEST_F(ErrorContract, ProcSelfMemAsInput) {
  const CliRun r = run("describe /proc/self/mem");
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_EQ(r.err.find("(null)"), std::string::npos) << r.err;
}

// ---- NaN in output ----------------------------------------------------------------------------

TEST_F(ErrorContract, AnalyzeWithAWrenchOf1e308) {
  const std::string poses = write("p.csv", "x,y,z\n0,0,0.9\n");
  expect_refused("analyze " + example("hexapod.yaml") + " --poses " + poses +
                     " --wrench 1.7e308,0,0,0,0,0 --out " + path("a.csv"),
                 "--wrench");
  expect_refused("analyze " + example("hexapod.yaml") + " --poses " + poses +
                     " --wrench 2e9,0,0,0,0,0 --out " + path("a.csv"),
                 "--wrench");
}

TEST_F(ErrorContract, TrajectoryWithHugeHelixNumbers) {
  const std::string machine = example("hexapod.yaml");
  expect_refused("trajectory " + machine + " --helix --helix-height 0.01,-1e308", "--helix-height");
  expect_refused("trajectory " + machine + " --helix --helix-frequency 1e308", "--helix-frequency");
  expect_refused("trajectory " + machine + " --helix --t-start -1e308", "--t-start");
  expect_refused("trajectory " + machine + " --helix --samples 1e308", "--samples");
  // Large but allowed numbers give big finite values and no NaN (a helix that keeps its radius
  // and height: a growing one leaves +-1000 m at this frequency and is refused).
  const CliRun r = run("trajectory " + machine +
                       " --helix --samples 21 --helix-frequency 1e14 --helix-radius 0.01,0 "
                       "--helix-height 0.01,0");
  EXPECT_TRUE(r.status == 0 || r.status == 3) << r.err;
  EXPECT_EQ(r.out.find("nan"), std::string::npos);
}

TEST_F(ErrorContract, TrajectoryWithAFolderAsSingularOut) {  // left traj.csv behind
  expect_refused("trajectory " + example("hexapod.yaml") + " --helix --samples 21 --out " +
                     path("traj.csv") + " --singular-out " + dir_.string(),
                 dir_.string());
}

TEST_F(ErrorContract, SimulateMeasurementsWithNanZeroLength) {
  expect_refused("simulate-measurements " + example("hexapod.yaml") + " --out " + path("sim") +
                     " --zero-length nan",
                 "--zero-length");
}

TEST_F(ErrorContract, WorkspaceWithAWrenchOf1e308) {
  expect_refused("workspace " + example("hexapod.yaml") +
                     " --resolution 0.05 --wrench 1e308,0,0,0,0,0 --out " + path("ws"),
                 "--wrench");
}

// ---- Exit 1 for bad input ---------------------------------------------------------------------

TEST_F(ErrorContract, InvalidUtf8InAStudyString) {
  const std::string study = write("bad.yaml",
                                  "study: \"b\xff\"\nproblem: {benchmark: zdt1}\n"
                                  "optimizer: {algorithm: nsga2}\n");
  expect_refused("run " + study + " --out " + path("out"),
                 "bad.yaml:1:10: expected UTF-8 text, found the byte 0xff");
}

TEST_F(ErrorContract, WorkspaceResolutionOf1e308Or1e320) {
  for (const char* value : {"1e308", "1e-320", "1e-12"})
    expect_refused(
        "workspace " + example("hexapod.yaml") + " --resolution " + value + " --out " + path("ws"),
        "--resolution");
}

TEST_F(ErrorContract, MachineOfAMillionMetres) {
  const std::string machine = with_tool("tcp: [0, 0, 1.0e6]");
  expect_refused("describe " + write("big.yaml", machine), "tool.tcp");
}

TEST_F(ErrorContract, CalibrationNoiseOf5e324) {
  std::string calibration = read_text(library("calibration-demo/calibration.yaml"));
  const std::string from = "actuator: 0.001}";
  ASSERT_NE(calibration.find(from), std::string::npos);
  calibration.replace(calibration.find(from), from.size(), "actuator: 4.9e-324}");
  for (const char* name : {"nominal.yaml", "measurements.csv"})
    fs::copy_file(fs::path(library("calibration-demo")) / name, dir_ / name);
  const std::string file = write("calibration.yaml", calibration);
  expect_refused("calibrate " + file + " --out " + path("fit"), "noise.actuator");
  const CliRun r = run("calibrate " + file + " --out " + path("fit"));
  EXPECT_EQ(r.err.find("CalibrationOptions"), std::string::npos) << r.err;
}

TEST_F(ErrorContract, BenchmarkWithTwoBillionObjectivesOrVariables) {
  for (const char* key : {"objectives", "variables"}) {
    const std::string study = write(std::string(key) + ".yaml",
                                    std::string("study: b\nproblem: {benchmark: dtlz2, ") + key +
                                        ": 2147483648}\noptimizer: {algorithm: nsga2}\n");
    expect_refused("run " + study + " --out " + path("out"), std::string("problem.") + key);
  }
}

TEST_F(ErrorContract, NbiWithInt64MaxPoints) {
  const std::string study = write("nbi.yaml",
                                  "study: b\nproblem: {benchmark: zdt1}\n"
                                  "optimizer: {algorithm: nbi, points: 9223372036854775807}\n");
  expect_refused("run " + study + " --out " + path("out"), "optimizer.points");
  EXPECT_FALSE(fs::exists(dir_ / "out" / "journal.txt"));
}

TEST_F(ErrorContract, ParetoJsonWith1e999) {
  const fs::path source = fs::path(PKMOPT_SOURCE_DIR) / "tests/io/data/pareto_json/two";
  std::string json = read_text(source / "pareto.json");
  const std::size_t at = json.find("\"objectives\"");
  ASSERT_NE(at, std::string::npos);
  const std::size_t number = json.find_first_of("0123456789", json.find("\"designs\""));
  ASSERT_NE(number, std::string::npos);
  json.insert(number, "1e999");
  fs::create_directories(dir_ / "front");
  write("front/pareto.json", json);
  const CliRun r = run("export " + path("front") + " --out " + path("x.csv"));
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_FALSE(fs::exists(dir_ / "x.csv"));
}

TEST_F(ErrorContract, ParetoJsonWithAnObjectiveOf1e308) {  // plots got -nan coordinates
  const fs::path source = fs::path(PKMOPT_SOURCE_DIR) / "tests/io/data/pareto_json/two";
  std::string json = read_text(source / "pareto.json");
  const std::string from = "1.2345678901234567e7";  // designs[0].objectives.stiffness_min
  ASSERT_NE(json.find(from), std::string::npos);
  json.replace(json.find(from), from.size(), "-1.7976931348623157e308");
  fs::create_directories(dir_ / "front");
  write("front/pareto.json", json);
  const CliRun r = run("export " + path("front") + " --format html --out " + path("r.html"));
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_NE(r.err.find("stiffness_min: expected a finite number within +-1e15"), std::string::npos)
      << r.err;
  EXPECT_FALSE(fs::exists(dir_ / "r.html"));
}

TEST_F(ErrorContract, SimulateMeasurementsWithTenMillionPoses) {  // ran for minutes
  expect_refused("simulate-measurements " + example("hexapod.yaml") + " --out " + path("sim") +
                     " --poses 10000000",
                 "1 <= poses <= 100000");
}

TEST_F(ErrorContract, TripodWorkspaceWithoutResolution) {  // the refinement never ended
  const CliRun r = run("workspace " + example("tripod_3prs.yaml"));
  EXPECT_EQ(r.status, 3) << r.err;
  EXPECT_NE(r.err.find("pkmopt: warning: the volume's estimated error"), std::string::npos)
      << r.err;
}

// ---- Not one located line ---------------------------------------------------------------------

TEST_F(ErrorContract, TripodWhoseStrutsCannotReachThePlatform) {
  // Struts of 1 µm between slides 0.30 m and joints 0.15 m from the axis: no pose assembles,
  // the search box is empty. Once reported as a slice of "inf pixels of 0 m (the grid spacing)".
  std::string machine = read_text(example("tripod_3prs.yaml"));
  const std::string line = "strut: 0.55 ";
  machine.replace(machine.find(line), line.size(), "strut: 1e-6 ");
  const std::string file = write("short_struts.yaml", machine);
  expect_refused("workspace " + file + " --resolution 0.02 --out " + path("ws"),
                 file + ": expected legs that reach a common platform pose, found none");
  // The message speaks of the machine, never of an option that was not given.
  const CliRun r = run("workspace " + file + " --resolution 0.02");
  EXPECT_EQ(r.err.find("--slice-pixel"), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find("pixels"), std::string::npos) << r.err;
}

TEST_F(ErrorContract, CommandLineOptionErrorsAreOneLine) {
  const std::string study = tiny_study();
  expect_refused("run " + study + " --out " + path("o") + " --threads abc",
                 "run: --threads: expected an integer, found 'abc' (see 'pkmopt run --help')");
  expect_refused("run " + study + " --out " + path("o") + " --threads",
                 "--threads: expected an integer after it, found nothing");
  expect_refused("run " + study + " --ouy " + path("o"),
                 "run: expected the options and arguments listed by --help, found unknown '--ouy'");
  expect_refused("nosuch", "expected a command (analyze, fk, ");
  expect_refused("", "found none (see 'pkmopt --help')");
  expect_refused("workspace " + example("hexapod.yaml") + " --tolerance abc",
                 "--tolerance: expected a number, found 'abc'");
  expect_refused("describe \xff", "expected UTF-8 text");
}

TEST_F(ErrorContract, MisspeltCommandsAndOptionsGetADidYouMean) {
  const std::string study = tiny_study();
  expect_refused("rnu " + study, "found 'rnu'; did you mean 'run'?");
  expect_refused("run " + study + " --ouy " + path("o"), "did you mean '--out'?");
  expect_refused("analyze " + example("hexapod.yaml") + " --pose p.csv", "did you mean '--poses'?");
  // Nothing close: no guess.
  const CliRun r = run("run " + study + " --out " + path("o") + " --zzzzzz");
  EXPECT_EQ(r.err.find("did you mean"), std::string::npos) << r.err;
}

TEST_F(ErrorContract, RunIntoAFolderOfOtherFiles) {
  // --out naming a folder that holds files of something else (not a run) is refused, with
  // --force too: a run there would mix its files with the user's, --force would delete some.
  write("mine/notes.txt", "my notes\n");
  const std::string study = tiny_study();
  expect_refused("run " + study + " --out " + path("mine"),
                 "--out: expected a new or empty folder or a previous run, found the folder");
  expect_refused("run " + study + " --out " + path("mine") + " --force", "'notes.txt'");
  EXPECT_EQ(read_text(dir_ / "mine" / "notes.txt"), "my notes\n");
  // An empty folder is fine.
  fs::create_directories(dir_ / "empty");
  EXPECT_EQ(run("run " + study + " --out " + path("empty") + " --no-progress").status, 0);
}

TEST_F(ErrorContract, RunWithoutAFeasibleDesignSaysWhy) {
  std::string study = read_text(library("hexapod-quick.yaml"));
  study.replace(study.find("max: 10500"), 10, "max: 1");
  study.replace(study.find("population: 60, generations: 80"), 31, "population: 8, generations: 2");
  const CliRun r =
      run("run " + write("never.yaml", study) + " --out " + path("o") + " --no-progress");
  EXPECT_EQ(r.status, 3) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_NE(r.err.find("pkmopt: warning: run: no feasible design"), std::string::npos) << r.err;
  // Every design's leg force exceeds 1 N: the row is named with its count, of the 23 distinct
  // evaluations (8 x (2 + 1) = 24 requested, one a repeat served from the cache).
  EXPECT_NE(r.err.find("g_leg_force_max_max > 0 in 23"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("of 23 evaluations"), std::string::npos) << r.err;
  const std::string summary = read_text(dir_ / "o" / "summary.json");
  EXPECT_NE(summary.find("\"g_leg_force_max_max\": 23"), std::string::npos) << summary;
  EXPECT_NE(summary.find("\"hypervolume_missing\": \"no feasible design"), std::string::npos)
      << summary;
}

TEST_F(ErrorContract, PosesInMillimetresAreWarnedAbout) {
  const std::string hexapod = example("hexapod.yaml");
  CliRun r =
      run("analyze " + hexapod + " --poses " + write("mm.csv", "x,y,z\n0,0,900\n10,0,900\n"));
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.err.find("pkmopt: warning: analyze: none of the 2 poses"), std::string::npos)
      << r.err;
  EXPECT_NE(r.err.find("not millimetres"), std::string::npos) << r.err;
  r = run("analyze " + hexapod + " --poses " + write("m.csv", "x,y,z\n0,0,0.9\n"));
  EXPECT_EQ(r.err, "");
  // Leg lengths beyond the strokes (1.15 m at most) solve to a pose the machine cannot take.
  r = run("fk " + hexapod + " --q 1.5,1.5,1.5,1.5,1.5,1.5");
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.err.find("pkmopt: warning: fk: the pose solves --q but lies outside"),
            std::string::npos)
      << r.err;
  r = run("fk " + hexapod + " --q 0.9,0.9,0.9,0.9,0.9,0.9");
  EXPECT_EQ(r.err, "");
}

TEST_F(ErrorContract, TrajectoryWithADtOf1e15) {  // exited 1: "at least 2 times needed"
  expect_refused(
      "trajectory " + example("hexapod.yaml") + " --helix --helix-centre 0,0,0.9 --dt 1e15",
      "--dt: expected a time step of at most the path's duration (6.283185307179586 s");
}

TEST_F(ErrorContract, EmptyOptionValues) {  // were read as 0 or as the default, exit 0
  const std::string hexapod = example("hexapod.yaml");
  const std::string poses = write("p.csv", "x,y,z\n0,0,0.9\n");
  expect_refused("analyze " + hexapod + " --poses " + poses + " --wrench ''",
                 "--wrench: expected a value, found an empty string");
  expect_refused("simulate-measurements " + hexapod + " --out " + path("sim") + " --seed ''",
                 "--seed: expected a value, found an empty string");
  expect_refused("run " + tiny_study() + " --out " + path("o") + " --threads ''",
                 "--threads: expected a value, found an empty string");
  expect_refused("trajectory " + hexapod + " --helix --helix-radius ''",
                 "--helix-radius: expected a value, found an empty string");
  expect_refused("workspace " + hexapod + " --resolution ''",
                 "--resolution: expected a value, found an empty string");
  expect_refused(
      "simulate-measurements " + hexapod + " --out " + path("sim") + " --tracker-sigma ''",
      "--tracker-sigma: expected a value, found an empty string");
}

TEST_F(ErrorContract, TrajectoryWithStdoutFull) {  // printed its 11-line summary, then the error
  const CliRun r = run_redirected(
      "trajectory " + example("hexapod.yaml") + " --helix --helix-centre 0,0,0.9 --samples 11",
      ">/dev/full");
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_EQ(r.err.rfind("pkmopt: error: cannot write to standard output", 0), 0u) << r.err;
}

// Were accepted and gave inf in tau, q and more (or, for 1e-400, were read silently as 0).
TEST_F(ErrorContract, LengthsBeyondAKilometreAndNumbersThatUnderflow) {
  const std::string hexapod = example("hexapod.yaml");
  expect_refused("analyze " + hexapod + " --poses " + write("p.csv", "x,y,z\n1e15,0,0.9\n"),
                 "p.csv:2: column 1 'x': expected a length within +-1000 m, found '1e15'");
  expect_refused("analyze " + hexapod + " --poses " + write("p.csv", "x,y,z\n0,1001,0.9\n"),
                 "column 2 'y': expected a length within +-1000 m, found '1001'");
  std::string machine = read_text(hexapod);
  machine.replace(machine.find("radius: 0.60"), 12, "radius: 1e15");
  expect_refused(
      "analyze " + write("big.yaml", machine) + " --poses " + write("p.csv", "x,y,z\n0,0,0.9\n"),
      "base.radius: expected a length in (0, 1000] m, found '1e15'");
  expect_refused("trajectory " + hexapod + " --path " +
                     write("path.csv", "t,x,y,z\n0,0,0,0.9\n1,4294967296,0,0.9\n"),
                 "path.csv:3: column 2 'x': expected a length within +-1000 m");
  expect_refused("trajectory " + hexapod + " --helix --helix-radius 0,1e8",
                 "--helix-radius: expected 2 comma-separated finite numbers, found '0,1e8' (item 2 "
                 "is outside +-1000)");
  // Each option within bounds, the helix they make far beyond them.
  expect_refused("trajectory " + hexapod + " --helix --helix-radius 0,1000 --t-end 1e6",
                 "--helix-*: expected a helix within +-1000 m");
  expect_refused("workspace " + hexapod + " --resolution 2000",
                 "--resolution: expected a length within +-1000 m, found 2000");
  expect_refused("fk " + hexapod + " --q 1e4,1,1,1,1,1", "--q: expected 6 comma-separated");
  // A coordinate code's constant is a length too.
  const std::string hybrid = read_text(example("hybrid_long_axis_hexapod.yaml"));
  const std::size_t code = hybrid.find("code: ");
  ASSERT_NE(code, std::string::npos);
  const std::size_t end = hybrid.find('\n', code);
  fs::copy_file(hexapod, dir_ / "hexapod.yaml");
  const std::string far =
      write("far.yaml", hybrid.substr(0, code) + "code: \"3:1e15 1\"" + hybrid.substr(end));
  expect_refused("describe " + far, "constants that are a length within +-1000 m (motion 3: m)");
  // Underflow: 1e-400 (read as 0 by C) is refused as 1e-31 is, in a CSV, a YAML file, an option.
  for (const char* tiny : {"1e-400", "-1e-400", "1e-31"}) {
    expect_refused("analyze " + hexapod + " --poses " +
                       write("p.csv", std::string("x,y,z\n") + tiny + ",0,0.9\n"),
                   std::string("expected a finite number within +-1e15 (0 or at least 1e-30 in "
                               "magnitude), found '") +
                       tiny + "'");
    machine = read_text(hexapod);
    machine.replace(machine.find("E: 2.1e11"), 9, std::string("E: ") + tiny);
    expect_refused("describe " + write("tiny.yaml", machine),
                   "legs.E: expected a finite number within +-1e15 (0 or at least 1e-30");
    expect_refused("analyze " + hexapod + " --poses " + write("p.csv", "x,y,z\n0,0,0.9\n") +
                       " --wrench 0,0," + tiny + ",0,0,0",
                   "(item 3 is outside +-1e+09 or below 1e-30 in magnitude)");
  }
  // A written zero is 0.
  const CliRun zero =
      run("analyze " + hexapod + " --poses " + write("z.csv", "x,y,z\n0e-400,0.0,0.9\n"));
  EXPECT_EQ(zero.status, 0) << zero.err;
}

// The columns docs/conventions.md lists as possibly inf ("Singular poses"), as patterns: `tau_i`
// matches tau_1..tau_n, `J_r_c` J_1_1.., `C_ij` C_11..C_66.
std::vector<std::regex> documented_inf_columns() {
  const std::string docs = read_text(fs::path(PKMOPT_SOURCE_DIR) / "docs/conventions.md");
  const std::size_t begin = docs.find("<!-- inf-columns");
  const std::size_t end = docs.find("<!-- /inf-columns -->");
  EXPECT_NE(begin, std::string::npos);
  EXPECT_NE(end, std::string::npos);
  std::vector<std::regex> patterns;
  std::istringstream table(docs.substr(begin, end - begin));
  for (std::string line; std::getline(table, line);) {
    if (line.rfind("| `", 0) != 0) continue;
    std::string name = line.substr(3, line.find('`', 3) - 3);
    name = std::regex_replace(name, std::regex("_(i|r|c)(?=_|$)"), "_[0-9]+");
    name = std::regex_replace(name, std::regex("_ij$"), "_[1-6][1-6]");
    patterns.emplace_back(name);
  }
  return patterns;
}

// Every cell of a CSV output that is not a finite number must be an inf in a documented column;
// returns the inf columns found.
std::vector<std::string> check_inf_cells(const std::string& csv_text,
                                         const std::vector<std::regex>& allowed,
                                         const std::string& what) {
  std::istringstream in(csv_text);
  std::string line;
  std::getline(in, line);
  std::vector<std::string> header;
  for (std::istringstream h(line); std::getline(h, line, ',');) header.push_back(line);
  std::vector<std::string> found;
  while (std::getline(in, line)) {
    std::istringstream row(line);
    std::size_t col = 0;
    for (std::string cell; std::getline(row, cell, ','); ++col) {
      EXPECT_FALSE(cell.empty() || cell.find("nan") != std::string::npos)
          << what << ": " << header.at(col) << " = '" << cell << "'";
      if (cell.find("inf") == std::string::npos) continue;
      const bool documented = std::any_of(allowed.begin(), allowed.end(), [&](const std::regex& p) {
        return std::regex_match(header.at(col), p);
      });
      EXPECT_TRUE(documented) << what << ": " << header.at(col) << " is inf, not documented";
      if (std::find(found.begin(), found.end(), header.at(col)) == found.end())
        found.push_back(header.at(col));
    }
  }
  return found;
}

// analyze --compliance wrote inf in tcp_rotation_deflection_deg and all 36 C_ij, trajectory inf in
// tau_dyn_i, at the sample hexapod's singular pose: now every column that can be inf is listed in
// docs/conventions.md, and every command's every column is checked against that list there.
TEST_F(ErrorContract, InfOnlyInTheDocumentedColumnsAtASingularPose) {
  const std::vector<std::regex> allowed = documented_inf_columns();
  ASSERT_GE(allowed.size(), 8u);
  const std::string masses = example("hexapod_masses.yaml");
  const std::string wrench = " --wrench 100,-200,-1000,5,-5,10";
  const std::string poses = write("s.csv", "x,y,z,rx,ry,rz\n0,0,0.9,0,0,90\n0,0,0.9,0,0,0\n");
  for (const std::string& machine : {example("hexapod.yaml"), masses}) {
    const CliRun r = run("analyze " + machine + " --poses " + poses + " --compliance --out " +
                         path("a.csv") + wrench + (machine == masses ? " --mode-shapes" : ""));
    ASSERT_EQ(r.status, 0) << r.err;
    const std::vector<std::string> inf =
        check_inf_cells(read_text(dir_ / "a.csv"), allowed, "analyze " + machine);
    for (const char* expected : {"tau_1", "tcp_error_max", "tcp_deflection",
                                 "tcp_rotation_deflection_deg", "C_11", "C_66"})
      EXPECT_NE(std::find(inf.begin(), inf.end(), expected), inf.end()) << expected;
  }
  const std::string path_csv =
      write("p.csv", "t,x,y,z,rx,ry,rz\n0,0,0,0.9,0,0,89\n0.5,0,0,0.9,0,0,90\n1,0,0,0.9,0,0,91\n");
  const CliRun t = run("trajectory " + masses + " --path " + path_csv + " --jacobian --out " +
                       path("t.csv") + wrench);
  ASSERT_TRUE(t.status == 0 || t.status == 3) << t.err;
  const std::vector<std::string> inf =
      check_inf_cells(read_text(dir_ / "t.csv"), allowed, "trajectory");
  for (const char* expected : {"tau_1", "tau_dyn_1"})
    EXPECT_NE(std::find(inf.begin(), inf.end(), expected), inf.end()) << expected;
  const CliRun w = run("workspace " + masses + " --orientation 0,0,90 --resolution 0.02 --out " +
                       path("w") + wrench);
  ASSERT_TRUE(w.status == 0 || w.status == 3) << w.err;
  check_inf_cells(read_text(dir_ / "w" / "points.csv"), allowed, "workspace");
  EXPECT_EQ(read_text(dir_ / "w" / "summary.json").find("inf"), std::string::npos);
}

TEST_F(ErrorContract, DescribeReadsAHybridsNumbersAsAnalyzeDoes) {  // describe exited 0
  const std::string poses = write("p.csv", "x,y,z\n0,0,0.9\n");
  fs::copy_file(example("hexapod.yaml"), dir_ / "hexapod.yaml");
  const std::string hybrid = read_text(example("hybrid_long_axis_hexapod.yaml"));
  const std::string line = "stiffness: [1.5e8]";
  ASSERT_NE(hybrid.find(line), std::string::npos);
  int k = 0;
  for (const char* bad : {"stiffness: [abc]", "stiffness: [.NaN]", "stiffness: [+.inf]",
                          "stiffness: [-1e16]", "stiffness: [-5]"}) {
    std::string text = hybrid;
    text.replace(text.find(line), line.size(), bad);
    const std::string file = write("hybrid" + std::to_string(k++) + ".yaml", text);
    const CliRun analyze = run("analyze " + file + " --poses " + poses);
    const CliRun describe = run("describe " + file);
    EXPECT_EQ(analyze.status, 2) << bad << "\n" << analyze.err;
    EXPECT_EQ(describe.status, 2) << bad << "\n" << describe.err;
    EXPECT_EQ(describe.err, analyze.err) << bad;
  }
}

TEST_F(ErrorContract, CalibrationWithAReadingOf1000Metres) {
  // One leg reading of 1e6 mm in the demo: Ceres printed some 200 lines of its own warnings
  // ("levenberg_marquardt_strategy.cc ... Linear solver failure") before pkmopt's line, and
  // report.txt showed "O2 inf" where report.json has null.
  const fs::path demo = fs::path(PKMOPT_SOURCE_DIR) / "studies/library/calibration-demo";
  fs::copy(demo, dir_ / "demo", fs::copy_options::recursive);
  std::string csv = read_text(dir_ / "demo" / "measurements.csv");
  std::size_t at = 0;
  for (int line = 0; line < 5; ++line) at = csv.find('\n', at) + 1;    // the fifth data row
  for (int comma = 0; comma < 6; ++comma) at = csv.find(',', at) + 1;  // its q_1
  csv.replace(at, csv.find(',', at) - at, "1000000");
  write("demo/measurements.csv", csv);
  const CliRun r =
      run("calibrate " + (dir_ / "demo" / "calibration.yaml").string() + " --out " + path("fit"));
  EXPECT_EQ(r.status, 3) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_EQ(r.err.rfind("pkmopt: warning: ", 0), 0u) << r.err;
  const std::string report = read_text(dir_ / "fit" / "report.txt");
  EXPECT_EQ(report.find("inf"), std::string::npos) << report;
  EXPECT_NE(report.find("O2 (cond) n/a"), std::string::npos) << report;
}

TEST_F(ErrorContract, CsvHeaderWithAQuotedNewline) {
  const std::string poses = write("q.csv", "a,\"b\nc\"\n1,2\n");
  expect_refused("analyze " + example("hexapod.yaml") + " --poses " + poses, "b\\nc");
}

TEST_F(ErrorContract, SecondYamlDocument) {
  const std::string machine = read_text(example("hexapod.yaml")) + "---\nmodel: delta\n";
  expect_refused("describe " + write("two.yaml", machine),
                 "expected one YAML document, found a second one");
}

TEST_F(ErrorContract, YamlTheParserCannotAdvanceIn) {  // yaml-cpp's LoadAll never returned
  expect_refused("describe " + write("comma.yaml", ", Cal"), "comma.yaml:1:");
}

TEST_F(ErrorContract, HybridWhoseModuleIsItself) {  // recursed until the stack overflowed
  std::string hybrid = read_text(example("hybrid_gantry_3prs.yaml"));
  const std::string from = "file: tripod_3prs.yaml";
  ASSERT_NE(hybrid.find(from), std::string::npos);
  hybrid.replace(hybrid.find(from), from.size(), "file: self.yaml");
  const std::string file = write("self.yaml", hybrid);
  expect_refused("describe " + file, "parallel.file: expected a parallel machine file");
  const std::string poses = write("p.csv", "x,y,z\n0,0,1.0\n");
  expect_refused("analyze " + file + " --poses " + poses, "expected a parallel machine file");
}

TEST_F(ErrorContract, PathsTheFileSystemRefuses) {  // std::filesystem errors exited 1
  fs::create_symlink("loop.yaml", dir_ / "loop.yaml");
  expect_refused("describe " + path("loop.yaml"), "loop.yaml");
  std::string hybrid = read_text(example("hybrid_gantry_3prs.yaml"));
  const std::string from = "file: tripod_3prs.yaml";
  hybrid.replace(hybrid.find(from), from.size(), "file: loop.yaml");
  expect_refused("describe " + write("via-loop.yaml", hybrid), "loop.yaml");
  hybrid = read_text(example("hybrid_gantry_3prs.yaml"));
  hybrid.replace(hybrid.find(from), from.size(), "file: " + std::string(300, 'o') + ".yaml");
  expect_refused("describe " + write("long.yaml", hybrid), "expected an existing machine file");
  expect_refused("describe " + std::string(5000, 'o') + ".yaml", "File name too long");
}

// ---- Lost output ------------------------------------------------------------------------------

TEST_F(ErrorContract, OutputToAFullDisk) {
  const std::string poses = write("p.csv", "x,y,z\n0,0,0.9\n");
  for (const std::string& args :
       {"analyze " + example("hexapod.yaml") + " --poses " + poses,
        "fk " + example("hexapod.yaml") + " --q 0.9,0.9,0.9,0.9,0.9,0.9",
        "validate " + library("zdt1-nsga2.yaml"), "describe " + example("delta.yaml")}) {
    const CliRun r = run_redirected(args, ">/dev/full");
    EXPECT_EQ(r.status, 2) << args << "\n" << r.err;
    EXPECT_NE(r.err.find("cannot write to standard output"), std::string::npos) << r.err;
  }
}

// ---- Every command's exit statuses --------------------------------------------------------------

TEST_F(ErrorContract, EveryCommandExitsZeroTwoOrThreeAsDocumented) {
  const std::string hexapod = example("hexapod.yaml");
  const std::string poses = write("p.csv", "x,y,z\n0,0,0.9\n");
  // 0: a good run of every command.
  const std::vector<std::string> good = {
      "describe " + hexapod,
      "analyze " + hexapod + " --poses " + poses,
      "fk " + hexapod + " --q 0.9,0.9,0.9,0.9,0.9,0.9",
      "validate " + tiny_study(),
      "run " + tiny_study() + " --out " + path("zdt1") + " --no-progress",
      "run " + library("hexapod-quick.yaml") + " --out " + path("front") + " --no-progress",
      "run " + library("hexapod-quick.yaml") + " --out " + path("front2") + " --no-progress",
      "export " + path("front") + " --format csv --out " + path("front.csv"),
      "compare " + path("front") + " " + path("front2") + " --out " + path("compare.html"),
      "calibrate " + library("calibration-demo/calibration.yaml") + " --out " + path("fit"),
      "workspace " + hexapod + " --resolution 0.05",
      "trajectory " + hexapod + " --helix --samples 11",
      "calibration-poses " + hexapod + " --count 10 --grid --steps 2",
      "simulate-measurements " + hexapod + " --out " + path("sim"),
  };
  for (const std::string& args : good) {
    const CliRun r = run(args);
    EXPECT_EQ(r.status, 0) << args << "\n" << r.err;
  }
  // 2: a missing input file, for every command that reads one.
  for (const char* command :
       {"describe", "analyze", "fk", "validate", "run", "workspace", "trajectory",
        "calibration-poses", "simulate-measurements", "calibrate", "export", "compare"}) {
    const CliRun r = run(std::string(command) + " " + path("missing.yaml"));
    EXPECT_EQ(r.status, 2) << command << "\n" << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << command << "\n" << r.err;
  }
  // 3: a result written but probably wrong.
  const CliRun fk = run("fk " + hexapod + " --q 0.01,0.01,0.01,0.01,0.01,0.01");
  EXPECT_EQ(fk.status, 3) << fk.err;
  EXPECT_EQ(fk.err.rfind("pkmopt: warning: fk: ", 0), 0u) << fk.err;
  std::string tripod = read_text(example("tripod_3prs.yaml"));
  tripod.replace(tripod.find("strut: 0.55 "), 12, "strut: 0.15 ");
  // An empty workspace is a result (a design whose joints forbid the task), said loudly.
  const CliRun empty = run("workspace " + write("short.yaml", tripod));
  EXPECT_EQ(empty.status, 0) << empty.err;
  EXPECT_NE(empty.err.find("pkmopt: warning: the workspace is empty"), std::string::npos)
      << empty.err;
}

}  // namespace
