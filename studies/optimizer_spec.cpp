#include "studies/optimizer_spec.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <stdexcept>
#include <type_traits>

#include "io/csv.hpp"
#include "io/input_error.hpp"
#include "optimizer/anchors.hpp"

namespace pkmopt {
namespace {

template <class... Ts>
struct Overloaded : Ts... {
  using Ts::operator()...;
};
template <class... Ts>
Overloaded(Ts...) -> Overloaded<Ts...>;

std::size_t read_count(const YamlValue& value, long long minimum) {
  const long long n = value.as_int();
  if (n < minimum) value.fail(fmt::format("an integer >= {}", minimum), value.describe());
  return static_cast<std::size_t>(n);
}

double read_positive(const YamlValue& value) {
  const double v = value.as_double();
  if (!(v > 0.0)) value.fail("a number > 0", value.describe());
  return v;
}

double read_probability(const YamlValue& value) {
  const double v = value.as_double();
  if (!(v >= 0.0 && v <= 1.0)) value.fail("a probability in [0, 1]", value.describe());
  return v;
}

const std::vector<std::string> kNsga2Keys{"population",    "generations",
                                          "crossover_probability", "crossover_eta",
                                          "mutation_probability",  "mutation_eta"};

Nsga2Options read_nsga2_keys(const YamlValue& section, std::uint64_t seed) {
  Nsga2Options options;
  options.seed = seed;
  if (auto v = section.optional("population")) {
    options.population = read_count(*v, 4);
    if (options.population % 2 != 0) v->fail("an even integer >= 4", v->describe());
  }
  if (auto v = section.optional("generations")) options.generations = read_count(*v, 0);
  if (auto v = section.optional("crossover_probability"))
    options.crossover_probability = read_probability(*v);
  if (auto v = section.optional("crossover_eta")) options.crossover_eta = read_positive(*v);
  if (auto v = section.optional("mutation_probability"))
    options.mutation_probability = read_probability(*v);
  if (auto v = section.optional("mutation_eta")) options.mutation_eta = read_positive(*v);
  return options;
}

IpoptOptions read_ipopt_keys(const YamlValue& section) {
  IpoptOptions options;
  if (auto v = section.optional("max_iterations"))
    options.max_iterations = static_cast<int>(read_count(*v, 1));
  if (auto v = section.optional("tolerance")) {
    options.tolerance = read_positive(*v);
    options.acceptable_tolerance = std::max(options.acceptable_tolerance, options.tolerance);
  }
  return options;
}

std::vector<double> read_start(const YamlValue& section, const Problem& problem) {
  auto v = section.optional("start");
  if (!v) return {};
  std::vector<double> start = v->as_doubles(static_cast<int>(problem.num_variables()));
  const Bounds bounds = problem.bounds();
  for (std::size_t j = 0; j < start.size(); ++j)
    if (start[j] < bounds.lower[j] || start[j] > bounds.upper[j])
      v->fail(fmt::format("start values within the bounds (variable {} in [{}, {}])", j + 1,
                          bounds.lower[j], bounds.upper[j]),
              format_number(start[j]));
  return start;
}

// Each algorithm: its keys besides `algorithm` and `seed`, and its reader.
AlgorithmSpec read_nsga2(const YamlValue& s, const Problem& problem, std::uint64_t seed,
                         std::optional<std::string>& unsupported) {
  unsupported = nsga2_explain_unsupported(problem);
  return Nsga2Spec{read_nsga2_keys(s, seed)};
}

AlgorithmSpec read_hybrid(const YamlValue& s, const Problem& problem, std::uint64_t seed,
                          std::optional<std::string>& unsupported) {
  unsupported = nsga2_explain_unsupported(problem);
  if (!unsupported && problem.num_objectives() < 2)
    unsupported =
        fmt::format("hybrid builds fronts, but '{}' has one objective (use ipopt)", problem.name());
  HybridSpec spec;
  spec.options.nsga2 = read_nsga2_keys(s, seed);
  if (auto v = s.optional("polish_iterations"))
    spec.options.ipopt.max_iterations = static_cast<int>(read_count(*v, 1));
  return spec;
}

AlgorithmSpec read_epsilon_constraint(const YamlValue& s, const Problem& problem,
                                      std::optional<std::string>& unsupported) {
  EpsilonConstraintSpec spec;
  spec.options.ipopt = read_ipopt_keys(s);
  if (auto v = s.optional("points")) spec.options.points = read_count(*v, 2);
  if (auto v = s.optional("primary_objective")) {
    const std::size_t p = read_count(*v, 1);
    if (p > problem.num_objectives())
      v->fail(fmt::format("an objective number from 1 to {}", problem.num_objectives()),
              v->describe());
    spec.options.primary_objective = p - 1;
  }
  spec.options.start = read_start(s, problem);
  unsupported = epsilon_constraint_explain_unsupported(problem, spec.options);
  return spec;
}

AlgorithmSpec read_nbi(const YamlValue& s, const Problem& problem,
                       std::optional<std::string>& unsupported) {
  NbiSpec spec;
  spec.options.ipopt = read_ipopt_keys(s);
  if (auto v = s.optional("points")) spec.options.points = read_count(*v, 2);
  if (auto v = s.optional("equality_form")) spec.options.equality_form = v->as_bool();
  spec.options.start = read_start(s, problem);
  unsupported = nbi_explain_unsupported(problem, spec.options);
  return spec;
}

AlgorithmSpec read_ipopt(const YamlValue& s, const Problem& problem,
                         std::optional<std::string>& unsupported) {
  unsupported = ipopt_explain_unsupported(problem);
  IpoptSpec spec;
  spec.options = read_ipopt_keys(s);
  spec.start = read_start(s, problem);
  return spec;
}

AlgorithmSpec read_nlopt(const YamlValue& s, const Problem& problem, const std::string& name,
                         std::uint64_t seed, std::optional<std::string>& unsupported) {
  NloptSpec spec;
  spec.options.algorithm = name;
  spec.options.seed = seed;
  if (auto v = s.optional("max_evaluations"))
    spec.options.max_evaluations = static_cast<long long>(read_count(*v, 1));
  if (auto v = s.optional("tolerance")) spec.options.relative_tolerance_x = read_positive(*v);
  if (auto v = s.optional("population"))
    spec.options.population = static_cast<unsigned>(read_count(*v, 1));
  if (auto v = s.optional("local_algorithm")) spec.options.local_algorithm = v->as_string();
  spec.start = read_start(s, problem);
  unsupported = nlopt_explain_unsupported(problem, spec.options);
  return spec;
}

}  // namespace

std::string OptimizerSpec::name() const {
  return std::visit(Overloaded{[](const Nsga2Spec&) { return std::string("nsga2"); },
                               [](const HybridSpec&) { return std::string("hybrid"); },
                               [](const EpsilonConstraintSpec&) {
                                 return std::string("epsilon_constraint");
                               },
                               [](const NbiSpec&) { return std::string("nbi"); },
                               [](const IpoptSpec&) { return std::string("ipopt"); },
                               [](const NloptSpec& s) { return "nlopt:" + s.options.algorithm; }},
                    algorithm);
}

const Nsga2Options* OptimizerSpec::nsga2() const {
  if (const auto* s = std::get_if<Nsga2Spec>(&algorithm)) return &s->options;
  if (const auto* s = std::get_if<HybridSpec>(&algorithm)) return &s->options.nsga2;
  return nullptr;
}

long long OptimizerSpec::expected_requests() const {
  if (const auto* s = std::get_if<Nsga2Spec>(&algorithm))
    return static_cast<long long>(s->options.population * (s->options.generations + 1));
  return 0;
}

OptimizerSpec read_optimizer_section(const YamlValue& section, const Problem& problem) {
  section.expect_map();
  OptimizerSpec spec;
  const YamlValue algorithm = section.required("algorithm");
  const std::string name = algorithm.as_string();
  std::vector<std::string> allowed{"algorithm", "seed"};
  auto allow = [&](const std::vector<std::string>& keys) {
    allowed.insert(allowed.end(), keys.begin(), keys.end());
  };
  if (name == "nsga2") {
    allow(kNsga2Keys);
  } else if (name == "hybrid") {
    allow(kNsga2Keys);
    allow({"polish_iterations"});
  } else if (name == "epsilon_constraint") {
    allow({"points", "primary_objective", "max_iterations", "tolerance", "start"});
  } else if (name == "nbi") {
    allow({"points", "equality_form", "max_iterations", "tolerance", "start"});
  } else if (name == "ipopt") {
    allow({"max_iterations", "tolerance", "start"});
  } else if (name.starts_with("nlopt:")) {
    allow({"max_evaluations", "tolerance", "start", "population", "local_algorithm"});
  } else {
    algorithm.fail("one of nsga2, epsilon_constraint, nbi, hybrid, ipopt, nlopt:<ALGORITHM>",
                   quote_found(name));
  }
  section.check_keys(allowed);
  if (auto v = section.optional("seed")) spec.seed = static_cast<std::uint64_t>(read_count(*v, 0));

  std::optional<std::string> unsupported;
  if (name == "nsga2")
    spec.algorithm = read_nsga2(section, problem, spec.seed, unsupported);
  else if (name == "hybrid")
    spec.algorithm = read_hybrid(section, problem, spec.seed, unsupported);
  else if (name == "epsilon_constraint")
    spec.algorithm = read_epsilon_constraint(section, problem, unsupported);
  else if (name == "nbi")
    spec.algorithm = read_nbi(section, problem, unsupported);
  else if (name == "ipopt")
    spec.algorithm = read_ipopt(section, problem, unsupported);
  else
    spec.algorithm = read_nlopt(section, problem, name.substr(6), spec.seed, unsupported);
  if (unsupported) algorithm.fail(*unsupported);
  return spec;
}

std::string optimizer_section_yaml(const OptimizerSpec& spec) {
  const std::string name = spec.name();
  std::vector<std::string> items{
      "algorithm: " + (name.starts_with("nlopt:") ? "\"" + name + "\"" : name),
      fmt::format("seed: {}", spec.seed)};
  auto add = [&](std::string_view key, const std::string& value) {
    items.push_back(fmt::format("{}: {}", key, value));
  };
  auto add_start = [&](const std::vector<double>& start) {
    if (start.empty()) return;
    std::string list;
    for (double v : start) list += (list.empty() ? "" : ", ") + format_number(v);
    add("start", "[" + list + "]");
  };
  auto add_nsga2 = [&](const Nsga2Options& o) {
    add("population", std::to_string(o.population));
    add("generations", std::to_string(o.generations));
    add("crossover_probability", format_number(o.crossover_probability));
    add("crossover_eta", format_number(o.crossover_eta));
    add("mutation_probability", format_number(o.mutation_probability));
    add("mutation_eta", format_number(o.mutation_eta));
  };
  auto add_ipopt = [&](const IpoptOptions& o) {
    add("max_iterations", std::to_string(o.max_iterations));
    add("tolerance", format_number(o.tolerance));
  };
  std::visit(Overloaded{[&](const Nsga2Spec& s) { add_nsga2(s.options); },
                        [&](const HybridSpec& s) {
                          add_nsga2(s.options.nsga2);
                          add("polish_iterations", std::to_string(s.options.ipopt.max_iterations));
                        },
                        [&](const EpsilonConstraintSpec& s) {
                          add("points", std::to_string(s.options.points));
                          add("primary_objective", std::to_string(s.options.primary_objective + 1));
                          add_ipopt(s.options.ipopt);
                          add_start(s.options.start);
                        },
                        [&](const NbiSpec& s) {
                          add("points", std::to_string(s.options.points));
                          add("equality_form", s.options.equality_form ? "true" : "false");
                          add_ipopt(s.options.ipopt);
                          add_start(s.options.start);
                        },
                        [&](const IpoptSpec& s) {
                          add_ipopt(s.options);
                          add_start(s.start);
                        },
                        [&](const NloptSpec& s) {
                          add("max_evaluations", std::to_string(s.options.max_evaluations));
                          if (s.options.relative_tolerance_x > 0.0)
                            add("tolerance", format_number(s.options.relative_tolerance_x));
                          if (s.options.population > 0)
                            add("population", std::to_string(s.options.population));
                          add("local_algorithm", s.options.local_algorithm);
                          add_start(s.start);
                        }},
             spec.algorithm);
  std::string text;
  for (const std::string& item : items) text += (text.empty() ? "" : ", ") + item;
  return "{" + text + "}";
}

namespace {

RunOutcome single_objective_outcome(const Problem& problem, const std::string& name,
                                    SolveResult result) {
  RunOutcome outcome;
  outcome.front.algorithm = name;
  outcome.front.num_objectives = problem.num_objectives();
  if (!result.fitness.empty()) {
    outcome.front.x.push_back(result.x);
    outcome.front.fitness.push_back(result.fitness);
  }
  outcome.front.fitness_evaluations = result.fitness_evaluations;
  outcome.front.gradient_evaluations = result.gradient_evaluations;
  outcome.front.seconds = result.seconds;
  outcome.front.message = result.message;
  outcome.status = std::string(to_string(result.status));
  outcome.single = std::move(result);
  return outcome;
}

RunOutcome front_outcome(FrontResult front) {
  RunOutcome outcome;
  outcome.front = std::move(front);
  outcome.status = outcome.front.x.empty() ? "no_feasible_design" : "ok";
  return outcome;
}

}  // namespace

RunOutcome run_optimizer(const Problem& problem, const OptimizerSpec& spec, int threads) {
  auto start_of = [&](const std::vector<double>& start) {
    return start.empty() ? default_start(problem) : start;
  };
  return std::visit(
      Overloaded{[&](const Nsga2Spec& s) {
                   Nsga2Options options = s.options;
                   options.threads = threads;
                   return front_outcome(run_nsga2(problem, options));
                 },
                 [&](const HybridSpec& s) {
                   HybridOptions options = s.options;
                   options.nsga2.threads = threads;
                   return front_outcome(run_hybrid(problem, options));
                 },
                 [&](const EpsilonConstraintSpec& s) {
                   return front_outcome(run_epsilon_constraint(problem, s.options));
                 },
                 [&](const NbiSpec& s) { return front_outcome(run_nbi(problem, s.options)); },
                 [&](const IpoptSpec& s) {
                   return single_objective_outcome(
                       problem, spec.name(), solve_with_ipopt(problem, start_of(s.start), s.options));
                 },
                 [&](const NloptSpec& s) {
                   return single_objective_outcome(
                       problem, spec.name(), solve_with_nlopt(problem, start_of(s.start), s.options));
                 }},
      spec.algorithm);
}

}  // namespace pkmopt
