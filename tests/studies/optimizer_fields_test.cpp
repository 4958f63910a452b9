// Tests of studies/optimizer_fields.hpp: the optimizer keys' one description gives the reader,
// the resolved writer and the tables of docs/optimizer.md.
#include "studies/optimizer_fields.hpp"

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <string>

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
       {"nsga2", "nsga3", "hybrid", "epsilon_constraint", "nbi", "ipopt", "nlopt"}) {
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
