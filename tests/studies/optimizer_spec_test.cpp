// Tests of studies/optimizer_spec: the `optimizer:` section of a study file read for each
// algorithm (nsga2, hybrid, epsilon_constraint, nbi, ipopt, nlopt:NAME), name(), nsga2() and
// expected_requests(), optimizer_section_yaml read back to the same spec, strict keys (an unknown
// algorithm, a key of another algorithm, an odd NSGA-II population), and run_optimizer on small
// benchmarks checked independently: every ZDT1 front point against ZDT1's formula written here,
// HS71 against its published optimum (Hock & Schittkowski 1981, problem 71: f* = 17.0140173 at
// x* = (1, 4.7429994, 3.8211503, 1.3794082)).
#include "studies/optimizer_spec.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <string>
#include <variant>
#include <vector>

#include "io/format/input_error.hpp"
#include "io/format/yaml_reader.hpp"
#include "problems/benchmarks/benchmarks.hpp"
#include "studies/benchmark_study.hpp"
#include "tests/scratch_dir.hpp"

namespace pkmopt {
namespace {

constexpr double kHs71Optimum = 17.0140173;
const std::vector<double> kHs71X{1.0, 4.7429994, 3.8211503, 1.3794082};

// The section `optimizer: <flow>` of a study file named study.yaml.
OptimizerSpec read(const std::string& flow, const Problem& problem) {
  const YamlValue root = YamlValue::load_string("optimizer: " + flow + "\n", "study.yaml");
  return read_optimizer_section(root.required("optimizer"), problem);
}

std::string error_of(const std::string& flow, const Problem& problem) {
  try {
    read(flow, problem);
  } catch (const InputError& e) {
    return e.what();
  }
  return "no error";
}

// The section written by optimizer_section_yaml, read again.
OptimizerSpec round_trip(const OptimizerSpec& spec, const Problem& problem) {
  return read(optimizer_section_yaml(spec), problem);
}

TEST(OptimizerSpec, Nsga2SectionAndItsDefaults) {
  const auto zdt1 = make_benchmark("zdt1", 5);
  const OptimizerSpec spec = read(
      "{algorithm: nsga2, population: 20, generations: 7, seed: 9, crossover_probability: 0.8, "
      "crossover_eta: 10, mutation_probability: 0.1, mutation_eta: 25}",
      *zdt1);
  EXPECT_EQ(spec.name(), "nsga2");
  EXPECT_EQ(spec.seed, 9u);
  ASSERT_TRUE(std::holds_alternative<Nsga2Spec>(spec.algorithm));
  const Nsga2Options* o = spec.nsga2();
  ASSERT_NE(o, nullptr);
  EXPECT_EQ(o->population, 20u);
  EXPECT_EQ(o->generations, 7u);
  EXPECT_EQ(o->seed, 9u);
  EXPECT_EQ(o->crossover_probability, 0.8);
  EXPECT_EQ(o->crossover_eta, 10.0);
  EXPECT_EQ(o->mutation_probability, 0.1);
  EXPECT_EQ(o->mutation_eta, 25.0);
  // The initial population and one offspring population per generation: 20 x (7 + 1).
  EXPECT_EQ(spec.expected_requests(), 160);

  // Keys left out take Nsga2Options' defaults (seed 1).
  const OptimizerSpec defaults = read("{algorithm: nsga2}", *zdt1);
  const Nsga2Options d;
  EXPECT_EQ(defaults.seed, 1u);
  EXPECT_EQ(defaults.nsga2()->population, d.population);
  EXPECT_EQ(defaults.nsga2()->generations, d.generations);
  EXPECT_EQ(defaults.nsga2()->crossover_probability, d.crossover_probability);
  EXPECT_EQ(defaults.nsga2()->crossover_eta, d.crossover_eta);
  EXPECT_EQ(defaults.nsga2()->mutation_probability, d.mutation_probability);
  EXPECT_EQ(defaults.nsga2()->mutation_eta, d.mutation_eta);
  EXPECT_EQ(defaults.expected_requests(),
            static_cast<long long>(d.population * (d.generations + 1)));
}

TEST(OptimizerSpec, HybridSection) {
  const auto zdt1 = make_benchmark("zdt1", 5);
  const OptimizerSpec spec = read(
      "{algorithm: hybrid, population: 12, generations: 3, polish_iterations: 50, seed: 4}", *zdt1);
  EXPECT_EQ(spec.name(), "hybrid");
  ASSERT_TRUE(std::holds_alternative<HybridSpec>(spec.algorithm));
  EXPECT_EQ(std::get<HybridSpec>(spec.algorithm).options.ipopt.max_iterations, 50);
  ASSERT_NE(spec.nsga2(), nullptr);  // the NSGA-II stage's options
  EXPECT_EQ(spec.nsga2()->population, 12u);
  EXPECT_EQ(spec.nsga2()->generations, 3u);
  EXPECT_EQ(spec.nsga2()->seed, 4u);
  EXPECT_EQ(spec.expected_requests(), 0);  // the polish makes an unknown number of requests
  // Hybrid builds fronts: a single-objective problem is refused.
  const auto hs71 = make_benchmark("hs71");
  EXPECT_NE(error_of("{algorithm: hybrid}", *hs71).find("one objective"), std::string::npos);
}

TEST(OptimizerSpec, FrontBuilderSections) {
  const auto zdt1 = make_benchmark("zdt1", 3);
  const OptimizerSpec eps = read(
      "{algorithm: epsilon_constraint, points: 7, primary_objective: 2, max_iterations: 150, "
      "tolerance: 1e-7, start: [0.5, 0.25, 0.75]}",
      *zdt1);
  EXPECT_EQ(eps.name(), "epsilon_constraint");
  ASSERT_TRUE(std::holds_alternative<EpsilonConstraintSpec>(eps.algorithm));
  const EpsilonConstraintOptions& e = std::get<EpsilonConstraintSpec>(eps.algorithm).options;
  EXPECT_EQ(e.points, 7u);
  EXPECT_EQ(e.primary_objective, 1u);  // 1-based in the file
  EXPECT_EQ(e.ipopt.max_iterations, 150);
  EXPECT_EQ(e.ipopt.tolerance, 1e-7);
  EXPECT_EQ(e.start, (std::vector<double>{0.5, 0.25, 0.75}));
  EXPECT_EQ(eps.nsga2(), nullptr);
  EXPECT_EQ(eps.expected_requests(), 0);
  EXPECT_NE(error_of("{algorithm: epsilon_constraint, primary_objective: 3}", *zdt1)
                .find("an objective number from 1 to 2"),
            std::string::npos);
  EXPECT_NE(error_of("{algorithm: epsilon_constraint, start: [0.5, 2, 0.5]}", *zdt1)
                .find("start values within the bounds"),
            std::string::npos);

  const OptimizerSpec nbi =
      read("{algorithm: nbi, points: 5, equality_form: true, max_iterations: 100, tolerance: 1e-6}",
           *zdt1);
  EXPECT_EQ(nbi.name(), "nbi");
  ASSERT_TRUE(std::holds_alternative<NbiSpec>(nbi.algorithm));
  const NbiOptions& b = std::get<NbiSpec>(nbi.algorithm).options;
  EXPECT_EQ(b.points, 5u);
  EXPECT_TRUE(b.equality_form);
  EXPECT_EQ(b.ipopt.max_iterations, 100);
  EXPECT_EQ(b.ipopt.tolerance, 1e-6);
  EXPECT_TRUE(b.start.empty());
  EXPECT_EQ(nbi.nsga2(), nullptr);
}

TEST(OptimizerSpec, SingleObjectiveSections) {
  const auto hs71 = make_benchmark("hs71");
  const OptimizerSpec ipopt =
      read("{algorithm: ipopt, max_iterations: 80, tolerance: 1e-9, start: [1, 5, 5, 1]}", *hs71);
  EXPECT_EQ(ipopt.name(), "ipopt");
  ASSERT_TRUE(std::holds_alternative<IpoptSpec>(ipopt.algorithm));
  EXPECT_EQ(std::get<IpoptSpec>(ipopt.algorithm).options.max_iterations, 80);
  EXPECT_EQ(std::get<IpoptSpec>(ipopt.algorithm).options.tolerance, 1e-9);
  EXPECT_EQ(std::get<IpoptSpec>(ipopt.algorithm).start, (std::vector<double>{1, 5, 5, 1}));
  EXPECT_EQ(ipopt.nsga2(), nullptr);
  EXPECT_EQ(ipopt.expected_requests(), 0);

  const OptimizerSpec slsqp =
      read("{algorithm: \"nlopt:SLSQP\", max_evaluations: 500, tolerance: 1e-6, seed: 3}", *hs71);
  EXPECT_EQ(slsqp.name(), "nlopt:SLSQP");
  ASSERT_TRUE(std::holds_alternative<NloptSpec>(slsqp.algorithm));
  const NloptSpec& s = std::get<NloptSpec>(slsqp.algorithm);
  EXPECT_EQ(s.options.algorithm, "SLSQP");
  EXPECT_EQ(s.options.max_evaluations, 500);
  EXPECT_EQ(s.options.relative_tolerance_x, 1e-6);
  EXPECT_EQ(s.options.seed, 3u);
  EXPECT_EQ(slsqp.expected_requests(), 0);

  // Only NSGA-II needs an even population: NLopt's population 5 is accepted.
  const auto rosenbrock = make_benchmark("rosenbrock", 2);
  const OptimizerSpec crs =
      read("{algorithm: \"nlopt:CRS2\", population: 5, max_evaluations: 2000}", *rosenbrock);
  EXPECT_EQ(std::get<NloptSpec>(crs.algorithm).options.population, 5u);
  const auto zdt1 = make_benchmark("zdt1", 5);
  const std::string odd = error_of("{algorithm: nsga2, population: 5}", *zdt1);
  EXPECT_NE(odd.find("optimizer.population: expected an even integer in [4, 1000000]"),
            std::string::npos)
      << odd;
  EXPECT_NE(odd.find("study.yaml:1:"), std::string::npos) << odd;
}

// optimizer_section_yaml gives a section that reads back to the same spec (so writing it again
// gives the same text).
TEST(OptimizerSpec, SectionYamlReadsBackToTheSameSpec) {
  const auto zdt1 = make_benchmark("zdt1", 3);
  const auto hs71 = make_benchmark("hs71");
  const auto rosenbrock = make_benchmark("rosenbrock", 2);
  struct Case {
    std::string flow;
    const Problem* problem;
  };
  const std::vector<Case> cases = {
      {"{algorithm: nsga2, population: 20, generations: 7, seed: 9, crossover_probability: 0.8, "
       "crossover_eta: 10, mutation_probability: 0.1, mutation_eta: 25}",
       zdt1.get()},
      {"{algorithm: hybrid, population: 12, generations: 3, polish_iterations: 50, seed: 4}",
       zdt1.get()},
      {"{algorithm: epsilon_constraint, points: 7, primary_objective: 2, max_iterations: 150, "
       "tolerance: 1e-7, start: [0.5, 0.25, 0.75]}",
       zdt1.get()},
      {"{algorithm: nbi, points: 5, equality_form: true, max_iterations: 100, tolerance: 1e-6}",
       zdt1.get()},
      {"{algorithm: ipopt, max_iterations: 80, tolerance: 1e-9, start: [1, 5, 5, 1]}", hs71.get()},
      {"{algorithm: \"nlopt:SLSQP\", max_evaluations: 500, tolerance: 1e-6, seed: 3}", hs71.get()},
      {"{algorithm: \"nlopt:CRS2\", population: 5, max_evaluations: 2000}", rosenbrock.get()},
  };
  for (const Case& c : cases) {
    const OptimizerSpec spec = read(c.flow, *c.problem);
    const std::string yaml = optimizer_section_yaml(spec);
    const OptimizerSpec again = round_trip(spec, *c.problem);
    EXPECT_EQ(again.name(), spec.name()) << yaml;
    EXPECT_EQ(again.seed, spec.seed) << yaml;
    EXPECT_EQ(again.algorithm.index(), spec.algorithm.index()) << yaml;
    EXPECT_EQ(again.expected_requests(), spec.expected_requests()) << yaml;
    EXPECT_EQ(optimizer_section_yaml(again), yaml);
    if (spec.nsga2()) {
      const Nsga2Options &a = *again.nsga2(), &b = *spec.nsga2();
      EXPECT_EQ(a.population, b.population);
      EXPECT_EQ(a.generations, b.generations);
      EXPECT_EQ(a.seed, b.seed);
      EXPECT_EQ(a.crossover_probability, b.crossover_probability);
      EXPECT_EQ(a.crossover_eta, b.crossover_eta);
      EXPECT_EQ(a.mutation_probability, b.mutation_probability);
      EXPECT_EQ(a.mutation_eta, b.mutation_eta);
    }
    if (const auto* e = std::get_if<EpsilonConstraintSpec>(&spec.algorithm)) {
      const auto& a = std::get<EpsilonConstraintSpec>(again.algorithm).options;
      EXPECT_EQ(a.points, e->options.points);
      EXPECT_EQ(a.primary_objective, e->options.primary_objective);
      EXPECT_EQ(a.ipopt.max_iterations, e->options.ipopt.max_iterations);
      EXPECT_EQ(a.ipopt.tolerance, e->options.ipopt.tolerance);
      EXPECT_EQ(a.start, e->options.start);
    }
    if (const auto* n = std::get_if<NbiSpec>(&spec.algorithm)) {
      const auto& a = std::get<NbiSpec>(again.algorithm).options;
      EXPECT_EQ(a.points, n->options.points);
      EXPECT_EQ(a.equality_form, n->options.equality_form);
      EXPECT_EQ(a.ipopt.tolerance, n->options.ipopt.tolerance);
    }
    if (const auto* i = std::get_if<IpoptSpec>(&spec.algorithm)) {
      const auto& a = std::get<IpoptSpec>(again.algorithm);
      EXPECT_EQ(a.options.max_iterations, i->options.max_iterations);
      EXPECT_EQ(a.options.tolerance, i->options.tolerance);
      EXPECT_EQ(a.start, i->start);
    }
    if (const auto* l = std::get_if<NloptSpec>(&spec.algorithm)) {
      const auto& a = std::get<NloptSpec>(again.algorithm);
      EXPECT_EQ(a.options.algorithm, l->options.algorithm);
      EXPECT_EQ(a.options.max_evaluations, l->options.max_evaluations);
      EXPECT_EQ(a.options.relative_tolerance_x, l->options.relative_tolerance_x);
      EXPECT_EQ(a.options.population, l->options.population);
      EXPECT_EQ(a.options.local_algorithm, l->options.local_algorithm);
      EXPECT_EQ(a.start, l->start);
    }
  }
}

TEST(OptimizerSpec, UnknownAlgorithmAndKeysOfAnotherAlgorithmNameTheKey) {
  const auto zdt1 = make_benchmark("zdt1", 5);
  const auto hs71 = make_benchmark("hs71");
  const std::string unknown = error_of("{algorithm: spea2}", *zdt1);
  EXPECT_NE(unknown.find("study.yaml:1:"), std::string::npos) << unknown;
  EXPECT_NE(unknown.find("optimizer.algorithm: expected one of nsga2"), std::string::npos)
      << unknown;
  EXPECT_NE(unknown.find("found 'spea2'"), std::string::npos) << unknown;
  // Each algorithm takes only its own keys.
  const struct {
    std::string flow, key;
    const Problem* problem;
  } foreign[] = {
      {"{algorithm: nsga2, points: 5}", "points", zdt1.get()},
      {"{algorithm: nbi, population: 20}", "population", zdt1.get()},
      {"{algorithm: epsilon_constraint, equality_form: true}", "equality_form", zdt1.get()},
      {"{algorithm: ipopt, generations: 3}", "generations", hs71.get()},
      {"{algorithm: \"nlopt:SLSQP\", max_iterations: 30}", "max_iterations", hs71.get()},
      {"{algorithm: hybrid, tolerance: 1e-6}", "tolerance", zdt1.get()},
  };
  for (const auto& f : foreign) {
    const std::string message = error_of(f.flow, *f.problem);
    EXPECT_NE(message.find("unknown key '" + f.key + "'"), std::string::npos)
        << f.flow << ": " << message;
    EXPECT_NE(message.find("optimizer." + f.key), std::string::npos) << f.flow << ": " << message;
  }
}

// Moved from tests/app/run_test.cpp (there through `pkmopt run`): the errors of a whole study file
// locate the key in the file.
TEST(OptimizerSpec, StudyFileErrorsGiveTheFileLineAndKey) {
  const scratch::ScratchDir dir;
  const std::string misspelt = dir.write("bad_key/study.yaml",
                                         "study: bad\n"
                                         "problem: {benchmark: zdt1}\n"
                                         "optimizer: {algorithm: nsga2, populaton: 20}\n");
  try {
    load_benchmark_study(misspelt);
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("study.yaml:3:"), std::string::npos) << message;
    EXPECT_NE(message.find("populaton"), std::string::npos) << message;
  }
  // An algorithm that cannot take the problem: BOBYQA and HS71's equality constraint.
  const std::string unsupported = dir.write("unsupported/study.yaml",
                                            "study: bad\n"
                                            "problem: {benchmark: hs71}\n"
                                            "optimizer: {algorithm: \"nlopt:BOBYQA\"}\n");
  try {
    load_benchmark_study(unsupported);
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("equality constraints"), std::string::npos) << message;
    EXPECT_NE(message.find("study.yaml:3:"), std::string::npos) << message;
  }
}

// ZDT1 (Zitzler, Deb & Thiele 2000), written out here: f1 = x1, g = 1 + 9 sum_{j>1} x_j / (n-1),
// f2 = g (1 - sqrt(f1 / g)).
std::vector<double> zdt1_by_hand(const std::vector<double>& x) {
  double sum = 0.0;
  for (std::size_t j = 1; j < x.size(); ++j) sum += x[j];
  const double g = 1.0 + 9.0 * sum / static_cast<double>(x.size() - 1);
  return {x[0], g * (1.0 - std::sqrt(x[0] / g))};
}

TEST(OptimizerSpec, RunOptimizerNsga2OnZdt1) {
  const auto zdt1 = make_benchmark("zdt1", 5);
  const OptimizerSpec spec =
      read("{algorithm: nsga2, population: 20, generations: 10, seed: 3}", *zdt1);
  const RunOutcome one = run_optimizer(*zdt1, spec, 1);
  EXPECT_EQ(one.status, "ok");
  EXPECT_FALSE(one.single.has_value());
  EXPECT_EQ(one.front.fitness_evaluations, spec.expected_requests());  // 20 x 11 = 220
  EXPECT_EQ(one.front.fitness_evaluations, 220);
  ASSERT_FALSE(one.front.x.empty());
  ASSERT_EQ(one.front.x.size(), one.front.fitness.size());
  for (std::size_t k = 0; k < one.front.x.size(); ++k) {
    const std::vector<double>& x = one.front.x[k];
    ASSERT_EQ(x.size(), 5u);
    for (double v : x) {
      EXPECT_GE(v, 0.0);
      EXPECT_LE(v, 1.0);
    }
    const std::vector<double> f = zdt1_by_hand(x);
    EXPECT_NEAR(one.front.fitness[k][0], f[0], 1e-15);
    EXPECT_NEAR(one.front.fitness[k][1], f[1], 1e-12);
    // No point of the front dominates another.
    for (std::size_t l = 0; l < one.front.x.size(); ++l) {
      if (l == k) continue;
      const auto& a = one.front.fitness[l];
      const auto& b = one.front.fitness[k];
      EXPECT_FALSE(a[0] <= b[0] && a[1] <= b[1] && (a[0] < b[0] || a[1] < b[1]))
          << "point " << l << " dominates point " << k;
    }
  }
  // The same seed gives the same front, whatever the thread count.
  const RunOutcome two = run_optimizer(*zdt1, spec, 2);
  EXPECT_EQ(two.front.x, one.front.x);
  EXPECT_EQ(two.front.fitness, one.front.fitness);
}

TEST(OptimizerSpec, RunOptimizerSingleObjectiveOnHs71) {
  const auto hs71 = make_benchmark("hs71");
  for (const std::string flow : {"{algorithm: ipopt, start: [1, 5, 5, 1]}",
                                 "{algorithm: \"nlopt:SLSQP\", start: [1, 5, 5, 1]}"}) {
    const OptimizerSpec spec = read(flow, *hs71);
    const RunOutcome outcome = run_optimizer(*hs71, spec, 1);
    ASSERT_TRUE(outcome.single.has_value()) << flow;
    const SolveResult& r = *outcome.single;
    EXPECT_TRUE(r.usable()) << flow << ": " << r.summary();
    EXPECT_EQ(outcome.status, std::string(to_string(r.status)));
    EXPECT_NEAR(r.objective, kHs71Optimum, 1e-6) << flow;
    ASSERT_EQ(r.x.size(), 4u);
    for (std::size_t j = 0; j < 4; ++j) EXPECT_NEAR(r.x[j], kHs71X[j], 1e-5) << flow << " x" << j;
    EXPECT_LT(r.constraint_violation, 1e-6) << flow;
    // The front of a single-objective run is its one point.
    ASSERT_EQ(outcome.front.x.size(), 1u);
    EXPECT_EQ(outcome.front.x[0], r.x);
    EXPECT_EQ(outcome.front.algorithm, spec.name());
  }
}

}  // namespace
}  // namespace pkmopt
