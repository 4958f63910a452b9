#include "studies/benchmark_study.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <sstream>
#include <stdexcept>

#include "io/csv.hpp"
#include "io/input_error.hpp"
#include "io/output_file.hpp"
#include "optimizer/indicators.hpp"
#include "pkmopt/version.hpp"

namespace pkmopt {
namespace {

std::size_t read_count(const YamlValue& value, long long minimum) {
  const long long n = value.as_int();
  if (n < minimum) value.fail(fmt::format("an integer >= {}", minimum), value.describe());
  return static_cast<std::size_t>(n);
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
  summary["algorithm"] = spec.name();
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
