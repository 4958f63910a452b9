// Tests of studies/run_study: run_study_file on a tiny benchmark study and a tiny design study
// into a scratch folder (the result files exist and agree with each other), the refusal to
// overwrite a run without resume or force (the message names --resume), resume giving the same
// pareto.csv, force starting over, and bad options or study files refused before anything is
// written.
#include "studies/run_study.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "io/format/csv.hpp"
#include "io/format/input_error.hpp"
#include "studies/run_lock.hpp"
#include "tests/cli_runner.hpp"
#include "tests/scratch_dir.hpp"

namespace pkmopt {
namespace {

namespace fs = std::filesystem;
using cli_runner::read_text;

const char* const kBenchmarkStudy =
    "study: tiny-zdt1\n"
    "problem: {benchmark: zdt1, variables: 4}\n"
    "optimizer: {algorithm: nsga2, population: 8, generations: 3, seed: 2}\n";

// A two-parameter hexapod study over 4 task poses (2 x 2 x 1 positions, level).
const char* const kDesignStudy =
    "study: tiny-hexapod\n"
    "machine:\n"
    "  model: hexapod\n"
    "  parameters:\n"
    "    base_radius: {min: 0.5, max: 0.7}\n"
    "    platform_pair_separation_deg: {min: 10, max: 40}\n"
    "  legs: {E: 2.1e11, area: 3.0e-4}\n"
    "  tool: {tcp: [0, 0, -0.10]}\n"
    "task:\n"
    "  region: {shape: box, centre: [0, 0, 0.9], size: [0.2, 0.2, 0.1], points: [2, 2, 1]}\n"
    "  wrench: [0, 0, -3000, 0, 0, 0]\n"
    "objectives:\n"
    "  - maximize: stiffness_min\n"
    "  - minimize: machine_size\n"
    "constraints:\n"
    "  - task_reachable\n"
    "optimizer: {algorithm: nsga2, population: 8, generations: 2, seed: 5}\n";

class RunStudy : public scratch::ScratchDirTest {
 protected:
  // Quiet options for a run into <dir_>/<out>; notes collected in messages_.
  StudyRunOptions options(const std::string& out) {
    StudyRunOptions o;
    o.out = path(out);
    o.threads = 1;
    o.show_progress = false;
    o.message = [this](const std::string& text) { messages_.push_back(text); };
    return o;
  }
  // The message of a run that must be refused.
  std::string refusal(const std::string& study, const StudyRunOptions& o) {
    try {
      run_study_file(study, o);
    } catch (const InputError& e) {
      return e.what();
    }
    return "no error";
  }
  static std::size_t lines(const fs::path& file) {
    const std::string text = read_text(file);
    return static_cast<std::size_t>(std::count(text.begin(), text.end(), '\n'));
  }

  std::vector<std::string> messages_;
};

TEST_F(RunStudy, BenchmarkStudyWritesItsResultFiles) {
  const std::string study = write("zdt1.yaml", kBenchmarkStudy);
  const StudyRunResult r = run_study_file(study, options("out"));
  EXPECT_FALSE(r.design_study);
  EXPECT_EQ(r.name, "tiny-zdt1");
  EXPECT_EQ(r.algorithm, "nsga2");
  EXPECT_EQ(r.problem, "zdt1");
  EXPECT_EQ(r.status, "ok");
  EXPECT_FALSE(r.resumed);
  EXPECT_EQ(r.evaluations, 8 * (3 + 1));  // the population and one offspring per generation
  const fs::path out = dir_ / "out";
  for (const char* file :
       {"pareto.csv", "summary.json", "journal.txt", "evaluations.csv", "study.resolved.yaml"})
    EXPECT_TRUE(fs::exists(out / file)) << file;
  // pareto.csv: x_1..x_4, f_1, f_2, one row per front point.
  const CsvTable front = read_csv_file((out / "pareto.csv").string());
  EXPECT_EQ(front.header, (std::vector<std::string>{"x_1", "x_2", "x_3", "x_4", "f_1", "f_2"}));
  EXPECT_EQ(front.rows.size(), r.designs);
  EXPECT_GT(r.designs, 0u);
  const nlohmann::json summary = nlohmann::json::parse(read_text(out / "summary.json"));
  EXPECT_EQ(summary["evaluations"], r.evaluations);
  EXPECT_EQ(summary["points"], r.designs);
  EXPECT_EQ(summary["seed"], 2);
  EXPECT_EQ(summary["resumed"], false);
  // evaluations.csv: the header and one row per distinct design.
  EXPECT_EQ(lines(out / "evaluations.csv"),
            1u + summary["evaluations_distinct"].get<std::size_t>());
}

// run_study on a study parsed in memory writes the files of run_study_file on the same text, and
// calls `progress` after every batch (the population, then each generation's offspring).
TEST_F(RunStudy, ParsedStudyRunsAsItsFileAndReportsProgress) {
  const std::string study = write("tiny.yaml", kDesignStudy);
  run_study_file(study, options("from-file"));
  StudyRunOptions o = options("parsed");
  std::vector<long long> requests;
  o.progress = [&](const JournalProgress& p) { requests.push_back(p.requests); };
  const StudyRunResult r = run_study(YamlValue::load_string(kDesignStudy, "<memory>"), o);
  EXPECT_TRUE(r.design_study);
  EXPECT_EQ(requests, (std::vector<long long>{8, 16, 24}));
  for (const char* file : {"pareto.csv", "pareto.json", "journal.txt", "evaluations.csv"})
    EXPECT_EQ(read_text(dir_ / "parsed" / file), read_text(dir_ / "from-file" / file)) << file;
}

TEST_F(RunStudy, DesignStudyWritesTheFrontAndItsMachineFiles) {
  const std::string study = write("hexapod.yaml", kDesignStudy);
  const StudyRunResult r = run_study_file(study, options("out"));
  EXPECT_TRUE(r.design_study);
  EXPECT_EQ(r.name, "tiny-hexapod");
  EXPECT_EQ(r.status, "ok");
  EXPECT_GT(r.designs, 0u);
  EXPECT_EQ(r.evaluations, 8 * (2 + 1));
  const fs::path out = dir_ / "out";
  for (const char* file : {"pareto.csv", "pareto.json", "summary.json", "journal.txt",
                           "evaluations.csv", "study.resolved.yaml"})
    EXPECT_TRUE(fs::exists(out / file)) << file;
  const nlohmann::json pareto = nlohmann::json::parse(read_text(out / "pareto.json"));
  EXPECT_EQ(pareto["study"], "tiny-hexapod");
  ASSERT_EQ(pareto["designs"].size(), r.designs);
  for (const nlohmann::json& d : pareto["designs"]) {
    if (d.contains("machine_file") && d["machine_file"].is_string()) {
      EXPECT_TRUE(fs::exists(out / d["machine_file"].get<std::string>())) << d.dump();
    }
  }
  EXPECT_EQ(read_csv_file((out / "pareto.csv").string()).rows.size(), r.designs);
}

TEST_F(RunStudy, SecondRunIsRefusedResumeGivesTheSameFrontForceStartsOver) {
  for (const char* text : {kBenchmarkStudy, kDesignStudy}) {
    const std::string name = text == kBenchmarkStudy ? "zdt1" : "hexapod";
    const std::string study = write(name + ".yaml", text);
    const std::string out = name + "-out";
    run_study_file(study, options(out));
    const std::string front = read_text(dir_ / out / "pareto.csv");
    const std::string journal = read_text(dir_ / out / "journal.txt");

    const std::string refused = refusal(study, options(out));
    EXPECT_NE(refused.find("--resume"), std::string::npos) << refused;
    EXPECT_NE(refused.find("--force"), std::string::npos) << refused;
    EXPECT_EQ(read_text(dir_ / out / "pareto.csv"), front);  // untouched

    StudyRunOptions resume = options(out);
    resume.resume = true;
    resume.threads = 2;
    const StudyRunResult resumed = run_study_file(study, resume);
    EXPECT_TRUE(resumed.resumed) << name;
    EXPECT_EQ(read_text(dir_ / out / "pareto.csv"), front) << name;
    EXPECT_EQ(read_text(dir_ / out / "journal.txt"), journal) << name;

    StudyRunOptions force = options(out);
    force.force = true;
    const StudyRunResult again = run_study_file(study, force);
    EXPECT_FALSE(again.resumed) << name;
    EXPECT_EQ(read_text(dir_ / out / "pareto.csv"), front) << name;  // same seed, same front
  }
  // --resume into a folder without a journal starts a new run and says so.
  StudyRunOptions fresh = options("fresh");
  fresh.resume = true;
  const StudyRunResult r = run_study_file(path("zdt1.yaml"), fresh);
  EXPECT_FALSE(r.resumed);
  ASSERT_FALSE(messages_.empty());
  EXPECT_NE(messages_.back().find("starting a new run"), std::string::npos) << messages_.back();
}

// A run that fails while writing its results leaves none of them, study.resolved.yaml included,
// and keeps the journal it resumes from (here summary.json cannot be written: a folder is there).
TEST_F(RunStudy, FailedRunLeavesNoResolvedStudyAndNoResults) {
  for (const char* text : {kBenchmarkStudy, kDesignStudy}) {
    const std::string name = text == kBenchmarkStudy ? "zdt1" : "hexapod";
    const std::string study = write(name + ".yaml", text);
    const fs::path out = dir_ / (name + "-failed");
    run_study_file(study, options(out.filename().string()));
    const std::string journal = read_text(out / "journal.txt");
    for (const char* file : {"pareto.csv", "pareto.json", "summary.json", "study.resolved.yaml"})
      fs::remove(out / file);
    fs::remove_all(out / "designs");
    fs::create_directory(out / "summary.json");
    StudyRunOptions resume = options(out.filename().string());
    resume.resume = true;
    const std::string refused = refusal(study, resume);
    EXPECT_NE(refused.find("summary.json"), std::string::npos) << refused;
    for (const char* file : {"pareto.csv", "pareto.json", "study.resolved.yaml"})
      EXPECT_FALSE(fs::exists(out / file)) << name << ": " << file;
    EXPECT_TRUE(!fs::exists(out / "designs") || fs::is_empty(out / "designs")) << name;
    EXPECT_EQ(read_text(out / "journal.txt"), journal) << name;
    fs::remove(out / "summary.json");
    EXPECT_TRUE(run_study_file(study, resume).resumed) << name;
    EXPECT_TRUE(fs::exists(out / "study.resolved.yaml")) << name;
  }
}

// Two runs into one folder: the second is refused (naming the first's PID) and changes nothing;
// temporaries left by a killed run are removed when the next run starts.
TEST_F(RunStudy, ConcurrentRunIsRefusedAndStaleTemporariesAreRemoved) {
  const std::string study = write("zdt1.yaml", kBenchmarkStudy);
  run_study_file(study, options("out"));
  const std::string front = read_text(dir_ / "out" / "pareto.csv");
  std::ofstream(dir_ / "out" / "pareto.csv.tmp.999999") << "half";
  {
    const RunLock holder((dir_ / "out").string());
    StudyRunOptions resume = options("out");
    resume.resume = true;
    const std::string refused = refusal(study, resume);
    EXPECT_NE(refused.find("another pkmopt run (PID " + std::to_string(::getpid()) + ")"),
              std::string::npos)
        << refused;
    StudyRunOptions force = options("out");
    force.force = true;
    EXPECT_NE(refusal(study, force).find("another pkmopt run"), std::string::npos);
    EXPECT_EQ(read_text(dir_ / "out" / "pareto.csv"), front);
  }
  StudyRunOptions resume = options("out");
  resume.resume = true;
  messages_.clear();
  run_study_file(study, resume);
  EXPECT_FALSE(fs::exists(dir_ / "out" / "pareto.csv.tmp.999999"));
  ASSERT_FALSE(messages_.empty());
  EXPECT_NE(messages_.front().find("removed 1 temporary file"), std::string::npos)
      << messages_.front();
}

TEST_F(RunStudy, BadOptionsAndStudiesAreRefusedBeforeAnythingIsWritten) {
  const std::string study = write("zdt1.yaml", kBenchmarkStudy);
  StudyRunOptions negative = options("out");
  negative.threads = -1;
  EXPECT_EQ(refusal(study, negative),
            "--threads: expected an integer in [0, 512] (0: all cores), found -1");
  StudyRunOptions both = options("out");
  both.resume = both.force = true;
  EXPECT_EQ(refusal(study, both), "--resume and --force: expected one of them, found both");
  EXPECT_FALSE(fs::exists(dir_ / "out"));

  // Moved from tests/app/run_test.cpp: a misspelt key, an algorithm that cannot take the
  // problem, an unknown benchmark: refused, no result file.
  const struct {
    std::string name, text, fragment;
  } bad[] = {
      {"bad_key",
       "study: bad\nproblem: {benchmark: zdt1}\noptimizer: {algorithm: nsga2, populaton: 20}\n",
       "populaton"},
      {"unsupported",
       "study: bad\nproblem: {benchmark: hs71}\noptimizer: {algorithm: \"nlopt:BOBYQA\"}\n",
       "equality constraints"},
      {"unknown", "study: bad\nproblem: {benchmark: zdt5}\noptimizer: {algorithm: nsga2}\n",
       "zdt5"},
  };
  for (const auto& b : bad) {
    const std::string file = write(b.name + "/study.yaml", b.text);
    const std::string message = refusal(file, options(b.name + "/out"));
    EXPECT_NE(message.find(b.fragment), std::string::npos) << b.name << ": " << message;
    EXPECT_FALSE(fs::exists(dir_ / b.name / "out" / "pareto.csv")) << b.name;
    EXPECT_FALSE(fs::exists(dir_ / b.name / "out" / "summary.json")) << b.name;
  }
}

}  // namespace
}  // namespace pkmopt
