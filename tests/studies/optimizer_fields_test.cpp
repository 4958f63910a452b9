// Tests of studies/optimizer_fields.hpp: the optimizer keys' one description gives the reader,
// the resolved writer and the tables of docs/optimizer.md.
#include "studies/optimizer_fields.hpp"

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "io/format/input_error.hpp"
#include "problems/benchmarks/benchmarks.hpp"
#include "studies/benchmark_study.hpp"

namespace pkmopt {
namespace {

std::string read_docs(const std::string& name) {
  std::ifstream in(std::string(PKMOPT_SOURCE_DIR) + "/docs/" + name);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// docs/optimizer.md carries each algorithm's table between <!-- fields: NAME --> and
// <!-- /fields -->, exactly as generated; the failure message shows the block to paste.
TEST(OptimizerFields, DocsTablesMatchTheFieldLists) {
  const std::string docs = read_docs("optimizer.md");
  for (const char* algorithm :
       {"nsga2", "nsga3", "moead", "hybrid", "epsilon_constraint", "nbi", "ipopt", "nlopt"}) {
    const std::string block = std::string("<!-- fields: ") + algorithm + " -->\n" +
                              optimizer_fields_markdown(algorithm) + "<!-- /fields -->\n";
    EXPECT_NE(docs.find(block), std::string::npos)
        << "docs/optimizer.md lacks the generated table of '" << algorithm << "':\n"
        << block;
  }
}

// nsga3 without a population takes the directions' count rounded up to a multiple of 4 and
// writes it back resolved (ZDT1, two objectives, H = 5: 6 directions, population 8).
TEST(OptimizerFields, Nsga3PopulationFollowsTheDirections) {
  const auto problem = make_benchmark("zdt1", 4, 0);
  const OptimizerSpec spec = read_optimizer_section(
      YamlValue::load_string("{algorithm: nsga3, divisions: 5, generations: 2}", "o.yaml"),
      *problem);
  ASSERT_NE(spec.nsga3(), nullptr);
  EXPECT_EQ(spec.nsga3()->population, 8u);
  EXPECT_EQ(spec.expected_requests(), 8 * 3);
  EXPECT_NE(optimizer_section_yaml(spec).find("population: 8,"), std::string::npos);
}

// nsga3's aspiration points: by objective name or in objective order, in the objectives' own
// sense (a maximised one is negated for the optimizer), written back as lists; the population
// follows the directions about them (ZDT1: H = 29 by default, 30 + 2 directions, population 32).
TEST(OptimizerFields, Nsga3AspirationPointsByNameAndSense) {
  const auto problem = make_benchmark("zdt1", 4, 0);
  const ObjectiveNaming naming{{"f1", "f2"}, {false, true}};
  const OptimizerSpec spec = read_optimizer_section(
      YamlValue::load_string("{algorithm: nsga3, generations: 2, aspiration: [{f2: 0.5, f1: 0.2}, "
                             "[0.7, 0.1]], aspiration_spread: 0.25}",
                             "o.yaml"),
      *problem, naming);
  ASSERT_NE(spec.nsga3(), nullptr);
  const std::vector<std::vector<double>> minimised{{0.2, -0.5}, {0.7, -0.1}};
  EXPECT_EQ(spec.nsga3()->aspiration_points, minimised);
  EXPECT_EQ(spec.nsga3()->population, 64u);  // 2 x 30 + 2 = 62 directions
  const std::string yaml = optimizer_section_yaml(spec);
  EXPECT_NE(yaml.find("aspiration_spread: 0.25"), std::string::npos) << yaml;
  EXPECT_NE(yaml.find("aspiration: [[0.2, 0.5], [0.7, 0.1]]"), std::string::npos) << yaml;
  const OptimizerSpec again =
      read_optimizer_section(YamlValue::load_string(yaml, "o.yaml"), *problem, naming);
  EXPECT_EQ(again.nsga3()->aspiration_points, minimised);
  EXPECT_EQ(optimizer_section_yaml(again), yaml);
  // Without names only lists; a map, a wrong length or a lone spread are refused.
  EXPECT_THROW(read_optimizer_section(
                   YamlValue::load_string("{algorithm: nsga3, aspiration: [{f1: 1, f2: 2}]}", "o"),
                   *problem),
               InputError);
  EXPECT_THROW(read_optimizer_section(
                   YamlValue::load_string("{algorithm: nsga3, aspiration: [[1]]}", "o"), *problem),
               InputError);
  EXPECT_THROW(
      read_optimizer_section(
          YamlValue::load_string("{algorithm: nsga3, aspiration_divisions: 3}", "o"), *problem),
      InputError);
  // Without aspiration points the keys are not written.
  EXPECT_EQ(optimizer_section_yaml(
                read_optimizer_section(YamlValue::load_string("{algorithm: nsga3}", "o"), *problem))
                .find("aspiration"),
            std::string::npos);
}

TEST(OptimizerFields, EveryAlgorithmKeyIsReadAndWrittenBack) {
  const auto problem = make_benchmark("zdt1", 4, 0);
  const char* sections[] = {
      "{algorithm: nsga2, seed: 3, population: 8, generations: 2, crossover_probability: 0.8, "
      "crossover_eta: 10, mutation_probability: 0.25, mutation_eta: 30}",
      "{algorithm: nsga3, seed: 4, population: 12, generations: 3, divisions: 5, "
      "inner_divisions: 1, crossover_probability: 0.9, crossover_eta: 30, mutation_probability: "
      "0, mutation_eta: 20}",
      "{algorithm: hybrid, seed: 1, population: 8, generations: 2, crossover_probability: 1, "
      "crossover_eta: 20, mutation_probability: 0, mutation_eta: 20, polish_iterations: 7}",
      "{algorithm: epsilon_constraint, seed: 1, points: 5, primary_objective: 2, "
      "max_iterations: 40, tolerance: 1e-07, start: [0.5, 0.5, 0.5, 0.5]}",
      "{algorithm: nbi, seed: 1, points: 6, equality_form: true, max_iterations: 30, "
      "tolerance: 1e-06}",
  };
  for (const char* text : sections) {
    const OptimizerSpec spec =
        read_optimizer_section(YamlValue::load_string(text, "o.yaml"), *problem);
    EXPECT_EQ(optimizer_section_yaml(spec), text);
  }
  const auto hs71 = make_benchmark("hs71", 0, 0);
  for (const char* text :
       {"{algorithm: ipopt, seed: 1, max_iterations: 50, tolerance: 1e-09, start: [1, 5, 5, 1]}",
        "{algorithm: \"nlopt:LN_COBYLA\", seed: 2, max_evaluations: 500, tolerance: 1e-06, "
        "population: 5, local_algorithm: SLSQP}"}) {
    const OptimizerSpec spec =
        read_optimizer_section(YamlValue::load_string(text, "o.yaml"), *hs71);
    EXPECT_EQ(optimizer_section_yaml(spec), text);
  }
}

TEST(OptimizerFields, ToleranceKeepsIpoptsAcceptableToleranceAboveIt) {
  const auto hs71 = make_benchmark("hs71", 0, 0);
  const OptimizerSpec spec = read_optimizer_section(
      YamlValue::load_string("{algorithm: ipopt, tolerance: 1e-3}", "o.yaml"), *hs71);
  const auto& ipopt = std::get<IpoptSpec>(spec.algorithm).options;
  EXPECT_EQ(ipopt.tolerance, 1e-3);
  EXPECT_EQ(ipopt.acceptable_tolerance, 1e-3);  // default 1e-6 raised to the tolerance
}

}  // namespace
}  // namespace pkmopt

namespace pkmopt {
namespace {

// The benchmark `problem:` section's table in docs/optimizer.md, generated from its field list.
TEST(OptimizerFields, DocsProblemTableMatchesTheFieldList) {
  const std::string docs = read_docs("optimizer.md");
  const std::string block =
      "<!-- fields: problem -->\n" + benchmark_problem_fields_markdown() + "<!-- /fields -->\n";
  EXPECT_NE(docs.find(block), std::string::npos)
      << "docs/optimizer.md lacks the generated problem table:\n"
      << block;
}

}  // namespace
}  // namespace pkmopt
