// Tests of studies/benchmark_study: the `problem:` and `indicators:` sections, whole benchmark
// study files (and their resolved form, a fixed point), the shipped benchmark studies, and
// write_run_outputs (pareto.csv and summary.json of a hand-made outcome whose hypervolume is
// computed by hand).
#include "studies/benchmark_study.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "io/format/input_error.hpp"
#include "io/format/yaml_reader.hpp"
#include "tests/cli_runner.hpp"
#include "tests/scratch_dir.hpp"

namespace pkmopt {
namespace {

namespace fs = std::filesystem;
using cli_runner::read_text;

YamlValue section(const std::string& key, const std::string& flow) {
  return YamlValue::load_string(key + ": " + flow + "\n", "study.yaml").required(key);
}

template <class Read>
std::string error_of(Read read) {
  try {
    read();
  } catch (const InputError& e) {
    return e.what();
  }
  return "no error";
}

TEST(BenchmarkStudy, ProblemSection) {
  const auto zdt1 = read_benchmark_problem(section("problem", "{benchmark: zdt1, variables: 7}"));
  EXPECT_EQ(zdt1->name(), "zdt1");
  EXPECT_EQ(zdt1->num_variables(), 7u);
  EXPECT_EQ(zdt1->num_objectives(), 2u);
  const auto dtlz2 =
      read_benchmark_problem(section("problem", "{benchmark: dtlz2, objectives: 4}"));
  EXPECT_EQ(dtlz2->num_objectives(), 4u);
  // Moved from tests/app/run_test.cpp (there through `pkmopt run`): an unknown benchmark.
  const std::string unknown =
      error_of([] { read_benchmark_problem(section("problem", "{benchmark: zdt5}")); });
  EXPECT_NE(unknown.find("study.yaml:1:"), std::string::npos) << unknown;
  EXPECT_NE(unknown.find("problem.benchmark: expected one of "), std::string::npos) << unknown;
  EXPECT_NE(unknown.find("found 'zdt5'"), std::string::npos) << unknown;
  EXPECT_NE(error_of([] {
              read_benchmark_problem(section("problem", "{benchmark: zdt1, variables: 0}"));
            }).find("problem.variables: expected an integer in [1, 10000]"),
            std::string::npos);
  EXPECT_NE(error_of([] {
              read_benchmark_problem(section("problem", "{benchmark: zdt1, size: 3}"));
            }).find("unknown key 'size'"),
            std::string::npos);
}

TEST(BenchmarkStudy, IndicatorsSection) {
  EXPECT_EQ(read_indicators_section(section("indicators", "{reference_point: [1.1, 2.5]}"), 2),
            (std::vector<double>{1.1, 2.5}));
  EXPECT_TRUE(read_indicators_section(section("indicators", "{}"), 2).empty());
  EXPECT_NE(error_of([] {
              read_indicators_section(section("indicators", "{reference_point: [1.1]}"), 2);
            }).find("indicators.reference_point: expected a list of 2"),
            std::string::npos);
}

TEST(BenchmarkStudy, StudyFileAndItsResolvedForm) {
  const scratch::ScratchDir dir;
  const std::string file = dir.write("study.yaml",
                                     "study: small\n"
                                     "description: \"a small run\"\n"
                                     "problem: {benchmark: zdt1, variables: 5}\n"
                                     "optimizer: {algorithm: nsga2, population: 8, seed: 4}\n"
                                     "indicators: {reference_point: [1.5, 1.5]}\n");
  const BenchmarkStudy study = load_benchmark_study(file);
  EXPECT_EQ(study.name, "small");
  EXPECT_EQ(study.problem->name(), "zdt1");
  EXPECT_EQ(study.problem->num_variables(), 5u);
  EXPECT_EQ(study.optimizer.name(), "nsga2");
  EXPECT_EQ(study.optimizer.seed, 4u);
  EXPECT_EQ(study.optimizer.nsga2()->population, 8u);
  EXPECT_EQ(study.reference_point, (std::vector<double>{1.5, 1.5}));
  // The resolved study holds every optimizer default and loads to itself.
  EXPECT_NE(study.resolved_yaml.find("generations: "), std::string::npos) << study.resolved_yaml;
  const BenchmarkStudy again =
      load_benchmark_study(dir.write("resolved.yaml", study.resolved_yaml));
  EXPECT_EQ(again.resolved_yaml, study.resolved_yaml);
  EXPECT_EQ(again.optimizer.nsga2()->generations, study.optimizer.nsga2()->generations);
  // Strict top-level keys.
  const std::string extra = error_of(
      [&] { load_benchmark_study(dir.write("extra.yaml", read_text(file) + "outputs: {}\n")); });
  EXPECT_NE(extra.find("extra.yaml:6:1: outputs: unknown key 'outputs'"), std::string::npos)
      << extra;
  // output.front_size: in the resolved study when set, checked like every other field.
  const BenchmarkStudy thinned =
      load_benchmark_study(dir.write("thin.yaml", read_text(file) + "output: {front_size: 7}\n"));
  EXPECT_EQ(thinned.front_size, 7u);
  EXPECT_NE(thinned.resolved_yaml.find("output: {front_size: 7}"), std::string::npos)
      << thinned.resolved_yaml;
  EXPECT_EQ(load_benchmark_study(dir.write("thin2.yaml", thinned.resolved_yaml)).front_size, 7u);
  const std::string zero = error_of([&] {
    load_benchmark_study(dir.write("zero.yaml", read_text(file) + "output: {front_size: -1}\n"));
  });
  EXPECT_NE(zero.find("front_size: expected an integer in [1, 100000], found '-1'"),
            std::string::npos)
      << zero;
  const std::string missing = error_of([&] {
    load_benchmark_study(dir.write("missing.yaml", "study: x\nproblem: {benchmark: zdt1}\n"));
  });
  EXPECT_NE(missing.find("missing required key 'optimizer'"), std::string::npos) << missing;
}

TEST(BenchmarkStudy, ShippedBenchmarkStudiesLoadAndResolveToThemselves) {
  const scratch::ScratchDir dir;
  for (const char* name : {"zdt1-nsga2", "zdt1-nbi", "zdt2-epsilon", "dtlz2-nsga2", "tnk-hybrid",
                           "hs71-ipopt", "rosenbrock-nlopt"}) {
    const BenchmarkStudy study =
        load_benchmark_study(std::string(PKMOPT_SOURCE_DIR) + "/studies/library/" + name + ".yaml");
    EXPECT_EQ(study.name, name);
    const BenchmarkStudy again =
        load_benchmark_study(dir.write(std::string(name) + ".yaml", study.resolved_yaml));
    EXPECT_EQ(again.resolved_yaml, study.resolved_yaml) << name;
  }
}

// Two front points (0.25, 0.75) and (0.75, 0.25) under the reference (1, 1): the union of the
// boxes they dominate is 0.75 * 0.25 + 0.25 * 0.75 - 0.25 * 0.25 = 0.3125.
TEST(BenchmarkStudy, RunOutputsOfAFront) {
  const auto zdt1 = make_benchmark("zdt1", 2);
  OptimizerSpec spec;
  spec.seed = 6;
  RunOutcome outcome;
  outcome.status = "ok";
  outcome.front.algorithm = "nsga2";
  outcome.front.num_objectives = 2;
  outcome.front.x = {{0.25, 0.5}, {0.75, 0.125}};
  outcome.front.fitness = {{0.25, 0.75}, {0.75, 0.25}};
  outcome.front.fitness_evaluations = 42;
  const scratch::ScratchDir dir;
  const fs::path out = dir / "out";  // created by write_run_outputs
  write_run_outputs(out.string(), "hand-made", *zdt1, spec, outcome, 2, {1.0, 1.0}, {},
                    nlohmann::json{{"note", "extra"}});
  EXPECT_EQ(read_text(out / "pareto.csv"),
            "x_1,x_2,f_1,f_2\n0.25,0.5,0.25,0.75\n0.75,0.125,0.75,0.25\n");
  const nlohmann::json s = nlohmann::json::parse(read_text(out / "summary.json"));
  EXPECT_EQ(s["study"], "hand-made");
  EXPECT_EQ(s["problem"], "zdt1");
  EXPECT_EQ(s["variables"], 2);
  EXPECT_EQ(s["objectives"], 2);
  EXPECT_EQ(s["algorithm"], "nsga2");
  EXPECT_EQ(s["status"], "ok");
  EXPECT_EQ(s["evaluations"], 42);
  EXPECT_EQ(s["points"], 2);
  EXPECT_EQ(s["seed"], 6);
  EXPECT_EQ(s["threads"], 2);
  EXPECT_EQ(s["reference_point"].get<std::vector<double>>(), (std::vector<double>{1.0, 1.0}));
  EXPECT_DOUBLE_EQ(s["hypervolume"].get<double>(), 0.3125);
  EXPECT_TRUE(s["igd_plus"].is_null());  // no reference front given
  EXPECT_TRUE(s["knee_point"].is_number_integer());
  EXPECT_EQ(s["note"], "extra");
  // Without a reference point: the front's nadir plus 10 % of its range, (0.8, 0.8), and the
  // hypervolume 0.55 * 0.05 + 0.05 * 0.55 - 0.05 * 0.05 = 0.0525.
  write_run_outputs((dir / "auto").string(), "hand-made", *zdt1, spec, outcome, 1, {}, {});
  const nlohmann::json a = nlohmann::json::parse(read_text(dir / "auto" / "summary.json"));
  ASSERT_EQ(a["reference_point"].size(), 2u);
  EXPECT_DOUBLE_EQ(a["reference_point"][0].get<double>(), 0.8);
  EXPECT_DOUBLE_EQ(a["reference_point"][1].get<double>(), 0.8);
  EXPECT_NEAR(a["hypervolume"].get<double>(), 0.0525, 1e-15);
}

TEST(BenchmarkStudy, RunOutputsOfASingleObjectiveSolve) {
  const auto hs71 = make_benchmark("hs71");
  OptimizerSpec spec;
  spec.algorithm = IpoptSpec{};
  RunOutcome outcome;
  outcome.status = "converged";
  SolveResult single;
  single.status = SolveStatus::converged;
  single.x = {1.0, 4.75, 3.75, 1.375};
  single.fitness = {17.5, 0.0, -0.5};
  single.objective = 17.5;
  single.constraint_violation = 0.0;
  single.iterations = 9;
  outcome.single = single;
  outcome.front.x = {single.x};
  outcome.front.fitness = {single.fitness};
  outcome.front.num_objectives = 1;
  const scratch::ScratchDir dir;
  write_run_outputs((dir / "out").string(), "hs71", *hs71, spec, outcome, 1, {}, {});
  EXPECT_EQ(read_text(dir / "out" / "pareto.csv"), "x_1,x_2,x_3,x_4,f_1\n1,4.75,3.75,1.375,17.5\n");
  const nlohmann::json s = nlohmann::json::parse(read_text(dir / "out" / "summary.json"));
  EXPECT_EQ(s["algorithm"], "ipopt");
  EXPECT_TRUE(s["hypervolume"].is_null());
  EXPECT_TRUE(s["reference_point"].is_null());
  EXPECT_TRUE(s["igd_plus"].is_null());
  EXPECT_TRUE(s["knee_point"].is_null());
  EXPECT_EQ(s["objective"], 17.5);
  EXPECT_EQ(s["constraint_violation"], 0.0);
  EXPECT_EQ(s["iterations"], 9);
}

}  // namespace
}  // namespace pkmopt
