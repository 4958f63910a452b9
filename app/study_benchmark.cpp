#include "app/study_benchmark.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <sstream>
#include <stdexcept>

#include "app/csv.hpp"
#include "app/input_error.hpp"
#include "app/output_file.hpp"
#include "optimizer/anchors.hpp"
#include "optimizer/indicators.hpp"
#include "pkmopt/version.hpp"

namespace pkmopt {
namespace {

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

void read_nsga2_keys(const YamlValue& section, Nsga2Options& options) {
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
}

void read_ipopt_keys(const YamlValue& section, IpoptOptions& options, const char* iterations_key) {
  if (auto v = section.optional(iterations_key))
    options.max_iterations = static_cast<int>(read_count(*v, 1));
  if (auto v = section.optional("tolerance")) {
    options.tolerance = read_positive(*v);
    options.acceptable_tolerance = std::max(options.acceptable_tolerance, options.tolerance);
  }
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

}  // namespace

std::unique_ptr<BenchmarkProblem> read_benchmark_problem(const YamlValue& section) {
  section.check_keys({"benchmark", "variables", "objectives"});
  const YamlValue name = section.required("benchmark");
  std::size_t variables = 0, objectives = 0;
  if (auto v = section.optional("variables")) variables = read_count(*v, 1);
  if (auto v = section.optional("objectives")) objectives = read_count(*v, 2);
  const std::string key = name.as_string();
  const std::vector<std::string> known = benchmark_names();
  if (std::find(known.begin(), known.end(), key) == known.end()) {
    std::string list;
    for (const std::string& n : known) list += (list.empty() ? "" : ", ") + n;
    name.fail("one of " + list, quote_found(key));
  }
  try {
    return make_benchmark(key, variables, objectives);
  } catch (const std::invalid_argument& e) {
    section.fail(e.what());
  }
}

OptimizerSpec read_optimizer_section(const YamlValue& section, const Problem& problem) {
  section.expect_map();
  OptimizerSpec spec;
  const YamlValue algorithm = section.required("algorithm");
  spec.algorithm = algorithm.as_string();
  const std::vector<std::string> nsga2_keys{
      "population",    "generations",          "crossover_probability",
      "crossover_eta", "mutation_probability", "mutation_eta"};
  std::vector<std::string> allowed{"algorithm", "seed"};
  auto allow = [&](const std::vector<std::string>& keys) {
    allowed.insert(allowed.end(), keys.begin(), keys.end());
  };
  std::optional<std::string> unsupported;
  if (spec.algorithm == "nsga2") {
    allow(nsga2_keys);
    unsupported = nsga2_explain_unsupported(problem);
  } else if (spec.algorithm == "hybrid") {
    allow(nsga2_keys);
    allow({"polish_iterations"});
    unsupported = nsga2_explain_unsupported(problem);
    if (!unsupported && problem.num_objectives() < 2)
      unsupported = fmt::format("hybrid builds fronts, but '{}' has one objective (use ipopt)",
                                problem.name());
  } else if (spec.algorithm == "epsilon_constraint") {
    allow({"points", "primary_objective", "max_iterations", "tolerance", "start"});
  } else if (spec.algorithm == "nbi") {
    allow({"points", "equality_form", "max_iterations", "tolerance", "start"});
  } else if (spec.algorithm == "ipopt") {
    allow({"max_iterations", "tolerance", "start"});
    unsupported = ipopt_explain_unsupported(problem);
  } else if (spec.algorithm.starts_with("nlopt:")) {
    allow({"max_evaluations", "tolerance", "start", "population", "local_algorithm"});
    spec.nlopt.algorithm = spec.algorithm.substr(6);
  } else {
    algorithm.fail("one of nsga2, epsilon_constraint, nbi, hybrid, ipopt, nlopt:<ALGORITHM>",
                   quote_found(spec.algorithm));
  }
  section.check_keys(allowed);

  if (auto v = section.optional("seed")) spec.seed = static_cast<std::uint64_t>(read_count(*v, 0));
  spec.nsga2.seed = spec.seed;
  spec.nlopt.seed = spec.seed;
  read_nsga2_keys(section, spec.nsga2);
  spec.hybrid.nsga2 = spec.nsga2;
  if (auto v = section.optional("polish_iterations"))
    spec.hybrid.ipopt.max_iterations = static_cast<int>(read_count(*v, 1));
  read_ipopt_keys(section, spec.ipopt, "max_iterations");
  spec.epsilon_constraint.ipopt = spec.ipopt;
  spec.nbi.ipopt = spec.ipopt;
  if (auto v = section.optional("points")) {
    spec.epsilon_constraint.points = read_count(*v, 2);
    spec.nbi.points = spec.epsilon_constraint.points;
  }
  if (auto v = section.optional("primary_objective")) {
    const std::size_t p = read_count(*v, 1);
    if (p > problem.num_objectives())
      v->fail(fmt::format("an objective number from 1 to {}", problem.num_objectives()),
              v->describe());
    spec.epsilon_constraint.primary_objective = p - 1;
  }
  if (auto v = section.optional("equality_form")) spec.nbi.equality_form = v->as_bool();
  spec.start = read_start(section, problem);
  spec.epsilon_constraint.start = spec.start;
  spec.nbi.start = spec.start;
  if (auto v = section.optional("max_evaluations"))
    spec.nlopt.max_evaluations = static_cast<long long>(read_count(*v, 1));
  if (auto v = section.optional("tolerance"); v && spec.algorithm.starts_with("nlopt:"))
    spec.nlopt.relative_tolerance_x = read_positive(*v);
  if (auto v = section.optional("population"); v && spec.algorithm.starts_with("nlopt:"))
    spec.nlopt.population = static_cast<unsigned>(read_count(*v, 1));
  if (auto v = section.optional("local_algorithm")) spec.nlopt.local_algorithm = v->as_string();

  if (spec.algorithm.starts_with("nlopt:"))
    unsupported = nlopt_explain_unsupported(problem, spec.nlopt);
  if (spec.algorithm == "epsilon_constraint")
    unsupported = epsilon_constraint_explain_unsupported(problem, spec.epsilon_constraint);
  if (spec.algorithm == "nbi") unsupported = nbi_explain_unsupported(problem, spec.nbi);
  if (unsupported) algorithm.fail(*unsupported);
  return spec;
}

std::string optimizer_section_yaml(const OptimizerSpec& spec) {
  std::vector<std::string> items{
      "algorithm: " +
          (spec.algorithm.starts_with("nlopt:") ? "\"" + spec.algorithm + "\"" : spec.algorithm),
      fmt::format("seed: {}", spec.seed)};
  auto add = [&](std::string_view key, const std::string& value) {
    items.push_back(fmt::format("{}: {}", key, value));
  };
  auto add_start = [&] {
    if (spec.start.empty()) return;
    std::string list;
    for (double v : spec.start) list += (list.empty() ? "" : ", ") + format_number(v);
    add("start", "[" + list + "]");
  };
  if (spec.algorithm == "nsga2" || spec.algorithm == "hybrid") {
    const Nsga2Options& o = spec.nsga2;
    add("population", std::to_string(o.population));
    add("generations", std::to_string(o.generations));
    add("crossover_probability", format_number(o.crossover_probability));
    add("crossover_eta", format_number(o.crossover_eta));
    add("mutation_probability", format_number(o.mutation_probability));
    add("mutation_eta", format_number(o.mutation_eta));
    if (spec.algorithm == "hybrid")
      add("polish_iterations", std::to_string(spec.hybrid.ipopt.max_iterations));
  } else if (spec.algorithm == "epsilon_constraint" || spec.algorithm == "nbi") {
    const bool epsilon = spec.algorithm == "epsilon_constraint";
    add("points", std::to_string(epsilon ? spec.epsilon_constraint.points : spec.nbi.points));
    if (epsilon)
      add("primary_objective", std::to_string(spec.epsilon_constraint.primary_objective + 1));
    else
      add("equality_form", spec.nbi.equality_form ? "true" : "false");
    add("max_iterations", std::to_string(spec.ipopt.max_iterations));
    add("tolerance", format_number(spec.ipopt.tolerance));
    add_start();
  } else if (spec.algorithm == "ipopt") {
    add("max_iterations", std::to_string(spec.ipopt.max_iterations));
    add("tolerance", format_number(spec.ipopt.tolerance));
    add_start();
  } else if (spec.algorithm.starts_with("nlopt:")) {
    add("max_evaluations", std::to_string(spec.nlopt.max_evaluations));
    if (spec.nlopt.relative_tolerance_x > 0.0)
      add("tolerance", format_number(spec.nlopt.relative_tolerance_x));
    if (spec.nlopt.population > 0) add("population", std::to_string(spec.nlopt.population));
    add("local_algorithm", spec.nlopt.local_algorithm);
    add_start();
  }
  std::string text;
  for (const std::string& item : items) text += (text.empty() ? "" : ", ") + item;
  return "{" + text + "}";
}

std::vector<double> read_indicators_section(const YamlValue& section, std::size_t num_objectives) {
  section.check_keys({"reference_point"});
  if (auto v = section.optional("reference_point"))
    return v->as_doubles(static_cast<int>(num_objectives));
  return {};
}

BenchmarkStudy load_benchmark_study(const std::string& path) {
  const YamlValue root = YamlValue::load_file(path);
  root.check_keys({"study", "description", "problem", "optimizer", "indicators"});
  BenchmarkStudy study;
  study.name = root.required("study").as_string();
  if (auto v = root.optional("description")) v->as_string();
  study.problem = read_benchmark_problem(root.required("problem"));
  study.optimizer = read_optimizer_section(root.required("optimizer"), *study.problem);
  if (auto v = root.optional("indicators"))
    study.reference_point = read_indicators_section(*v, study.problem->num_objectives());
  // study.resolved.yaml: the problem section as written, the optimizer with every default.
  std::string resolved = fmt::format("study: {}\n", nlohmann::json(study.name).dump());
  if (auto v = root.optional("description"))
    resolved += fmt::format("description: {}\n", nlohmann::json(v->as_string()).dump());
  const YamlValue problem = root.required("problem");
  resolved += fmt::format("problem: {{benchmark: {}", problem.required("benchmark").as_string());
  if (auto v = problem.optional("variables"))
    resolved += fmt::format(", variables: {}", v->as_int());
  if (auto v = problem.optional("objectives"))
    resolved += fmt::format(", objectives: {}", v->as_int());
  resolved += "}\noptimizer: " + optimizer_section_yaml(study.optimizer) + "\n";
  if (!study.reference_point.empty()) {
    std::string list;
    for (double r : study.reference_point) list += (list.empty() ? "" : ", ") + format_number(r);
    resolved += "indicators: {reference_point: [" + list + "]}\n";
  }
  study.resolved_yaml = resolved;
  return study;
}

RunOutcome run_optimizer(const Problem& problem, const OptimizerSpec& spec, int threads) {
  RunOutcome outcome;
  if (spec.algorithm == "ipopt" || spec.algorithm.starts_with("nlopt:")) {
    CountingProblem counted(problem);
    const std::vector<double> start = spec.start.empty() ? default_start(problem) : spec.start;
    SolveResult result = spec.algorithm == "ipopt" ? solve_with_ipopt(problem, start, spec.ipopt)
                                                   : solve_with_nlopt(problem, start, spec.nlopt);
    outcome.front.algorithm = spec.algorithm;
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
  if (spec.algorithm == "nsga2") {
    Nsga2Options options = spec.nsga2;
    options.threads = threads;
    outcome.front = run_nsga2(problem, options);
  } else if (spec.algorithm == "hybrid") {
    HybridOptions options = spec.hybrid;
    options.nsga2.threads = threads;
    outcome.front = run_hybrid(problem, options);
  } else if (spec.algorithm == "epsilon_constraint") {
    outcome.front = run_epsilon_constraint(problem, spec.epsilon_constraint);
  } else if (spec.algorithm == "nbi") {
    outcome.front = run_nbi(problem, spec.nbi);
  } else {
    throw std::invalid_argument("unknown algorithm '" + spec.algorithm + "'");
  }
  outcome.status = outcome.front.x.empty() ? "no_feasible_design" : "ok";
  return outcome;
}

namespace {

nlohmann::json finite_or_null(double value) {
  return std::isfinite(value) ? nlohmann::json(value) : nlohmann::json(nullptr);
}

}  // namespace

void write_run_outputs(const std::string& directory, const std::string& study_name,
                       const Problem& problem, const OptimizerSpec& spec, const RunOutcome& outcome,
                       int threads, const std::vector<double>& reference_point,
                       const ObjectiveSet& reference_front, const nlohmann::json& extra_summary) {
  std::error_code error;
  std::filesystem::create_directories(directory, error);
  if (error || !std::filesystem::is_directory(directory))
    throw InputError(fmt::format("--out: cannot create the folder '{}': {}", directory,
                                 error ? error.message() : "not a folder"));
  const std::size_t n = problem.num_variables();
  const std::size_t m = problem.num_objectives();
  const FrontResult& front = outcome.front;

  std::ostringstream csv;
  for (std::size_t j = 0; j < n; ++j) csv << (j ? "," : "") << "x_" << j + 1;
  for (std::size_t i = 0; i < m; ++i) csv << ",f_" << i + 1;
  csv << '\n';
  for (std::size_t k = 0; k < front.x.size(); ++k) {
    for (std::size_t j = 0; j < n; ++j) csv << (j ? "," : "") << format_number(front.x[k][j]);
    for (std::size_t i = 0; i < m; ++i) csv << ',' << format_number(front.fitness[k][i]);
    csv << '\n';
  }

  nlohmann::json summary;
  summary["study"] = study_name;
  summary["problem"] = problem.name();
  summary["variables"] = n;
  summary["objectives"] = m;
  summary["algorithm"] = spec.algorithm;
  summary["status"] = outcome.status;
  summary["message"] = front.message;
  summary["evaluations"] = front.fitness_evaluations;
  summary["gradient_evaluations"] = front.gradient_evaluations;
  summary["points"] = front.x.size();
  summary["time_seconds"] = front.seconds;
  summary["seed"] = spec.seed;
  summary["threads"] = resolve_thread_count(threads);
  summary["subproblems"] = front.subproblems;
  summary["failed_subproblems"] = front.failed_subproblems;
  summary["dominated_subproblems"] = front.dominated_subproblems;
  summary["version"] = kVersion;
  const ObjectiveSet objectives = front.objectives();
  if (m >= 2) {
    std::vector<double> reference = reference_point;
    if (reference.empty() && !reference_front.empty())
      reference = reference_point_from(reference_front);
    if (reference.empty() && !objectives.empty()) reference = reference_point_from(objectives);
    if (reference.empty()) reference.assign(m, 0.0);
    summary["reference_point"] = reference;
    summary["hypervolume"] = finite_or_null(hypervolume(objectives, reference));
    summary["igd_plus"] = !reference_front.empty() && !objectives.empty()
                              ? finite_or_null(igd_plus(objectives, reference_front))
                              : nlohmann::json(nullptr);
    summary["knee_point"] =
        objectives.empty() ? nlohmann::json(nullptr) : nlohmann::json(knee_point(objectives));
  } else {
    summary["reference_point"] = nullptr;
    summary["hypervolume"] = nullptr;
    summary["igd_plus"] = nullptr;
    summary["knee_point"] = nullptr;
    if (outcome.single) {
      summary["objective"] = finite_or_null(outcome.single->objective);
      summary["constraint_violation"] = finite_or_null(outcome.single->constraint_violation);
      summary["iterations"] = outcome.single->iterations;
    }
  }
  for (const auto& [key, value] : extra_summary.items()) summary[key] = value;
  const std::filesystem::path dir(directory);
  write_file_atomically((dir / "pareto.csv").string(), csv.str());
  write_file_atomically((dir / "summary.json").string(), summary.dump(2) + "\n");
}

}  // namespace pkmopt
