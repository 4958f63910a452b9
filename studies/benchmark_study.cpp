#include "studies/benchmark_study.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <sstream>
#include <stdexcept>

#include "io/format/csv.hpp"
#include "io/format/field_list.hpp"
#include "io/format/input_error.hpp"
#include "io/format/output_file.hpp"
#include "optimizer/decision.hpp"
#include "optimizer/front_thinning.hpp"
#include "optimizer/indicators.hpp"
#include "pkmopt/version.hpp"
#include "studies/optimizer_fields.hpp"

namespace pkmopt {

/// The `problem:` section of a benchmark study, in file form.
struct BenchmarkProblemSection {
  std::string benchmark;
  std::size_t variables = 0;   ///< 0: the problem's default
  std::size_t objectives = 0;  ///< 0: the problem's default
};

template <class Fields>
void describe_fields(Fields& f, BenchmarkProblemSection& p) {
  f.field("benchmark", p.benchmark,
          {.required = true,
           .expected = "zdt1, zdt2, zdt3, zdt4, zdt6, dtlz1, dtlz2, dtlz3, dtlz4, dtlz7, bnh, srn, "
                       "tnk, osy, hs71 or rosenbrock",
           .doc = "the benchmark problem (formulas in problems/benchmarks/benchmarks.hpp)"});
  f.field("variables", p.variables,
          {.min = 1,
           .max = static_cast<double>(kMaxBenchmarkVariables),
           .zero_is_unset = true,
           .default_text = "ZDT1–3: 30, ZDT4/6: 10, DTLZ: m + k − 1 (k = 5 DTLZ1, 10 DTLZ2–4, 20 "
                           "DTLZ7), Rosenbrock: 10",
           .doc = "number of variables (fixed-size problems accept only their own)"});
  f.field("objectives", p.objectives,
          {.min = 2,
           .max = static_cast<double>(kMaxBenchmarkObjectives),
           .zero_is_unset = true,
           .default_text = "3",
           .doc = "number of objectives (DTLZ only)"});
}

std::string benchmark_problem_fields_markdown() {
  return fields_markdown(BenchmarkProblemSection{});
}

namespace {

BenchmarkProblemSection read_problem_section(const YamlValue& section) {
  BenchmarkProblemSection p;
  read_fields(section, p);
  return p;
}

// The `output:` section of a benchmark study.
struct BenchmarkOutputSection {
  int front_size = 0;  ///< 0: every non-dominated design
};

template <class Fields>
void describe_fields(Fields& f, BenchmarkOutputSection& o) {
  front_size_field(f, o.front_size);
}

}  // namespace

std::unique_ptr<BenchmarkProblem> read_benchmark_problem(const YamlValue& section) {
  const BenchmarkProblemSection p = read_problem_section(section);
  const YamlValue name = section.required("benchmark");
  const std::size_t variables = p.variables, objectives = p.objectives;
  const std::string key = p.benchmark;
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
  return load_benchmark_study(YamlValue::load_file(path));
}

BenchmarkStudy load_benchmark_study(const YamlValue& root) {
  root.check_keys({"study", "description", "problem", "optimizer", "indicators", "output"});
  BenchmarkStudy study;
  study.name = root.required("study").as_string();
  if (auto v = root.optional("description")) v->as_string();
  study.problem = read_benchmark_problem(root.required("problem"));
  study.optimizer = read_optimizer_section(root.required("optimizer"), *study.problem);
  if (auto v = root.optional("indicators"))
    study.reference_point = read_indicators_section(*v, study.problem->num_objectives());
  BenchmarkOutputSection output;
  if (auto v = root.optional("output")) read_fields(*v, output);
  study.front_size = static_cast<std::size_t>(output.front_size);
  // study.resolved.yaml: the problem section as written, the optimizer with every default.
  std::string resolved = fmt::format("study: {}\n", nlohmann::json(study.name).dump());
  if (auto v = root.optional("description"))
    resolved += fmt::format("description: {}\n", nlohmann::json(v->as_string()).dump());
  resolved += "problem: " + fields_flow_map(read_problem_section(root.required("problem"))) +
              "\noptimizer: " + optimizer_section_yaml(study.optimizer) + "\n";
  if (!study.reference_point.empty()) {
    std::string list;
    for (double r : study.reference_point) list += (list.empty() ? "" : ", ") + format_number(r);
    resolved += "indicators: {reference_point: [" + list + "]}\n";
  }
  if (output.front_size > 0) resolved += "output: " + fields_flow_map(output) + "\n";
  study.resolved_yaml = resolved;
  return study;
}

namespace {

nlohmann::json finite_or_null(double value) {
  return std::isfinite(value) ? nlohmann::json(value) : nlohmann::json(nullptr);
}

}  // namespace

bool benchmark_feasible(const Problem& problem, const std::vector<double>& fitness) {
  for (std::size_t i = 0; i < problem.num_objectives(); ++i)
    if (!std::isfinite(fitness[i])) return false;
  return constraint_violation(problem, fitness, kBenchmarkFeasibilityTolerance,
                              kBenchmarkFeasibilityTolerance) == 0.0;
}

ArchivedFront archive_front(const Problem& problem, const std::vector<std::vector<double>>& xs,
                            const std::vector<std::vector<double>>& fitness,
                            std::size_t front_size) {
  const std::size_t m = problem.num_objectives();
  std::vector<std::size_t> candidates;
  ObjectiveSet objectives;
  for (std::size_t k = 0; k < xs.size(); ++k)
    if (fitness[k].size() == problem.fitness_size() && benchmark_feasible(problem, fitness[k])) {
      candidates.push_back(k);
      objectives.emplace_back(fitness[k].begin(),
                              fitness[k].begin() + static_cast<std::ptrdiff_t>(m));
    }
  ArchivedFront result;
  result.feasible_evaluations = candidates.size();
  result.front.num_objectives = m;
  for (std::size_t k : select_front(objectives, front_size, &result.archive_size)) {
    result.front.x.push_back(xs[candidates[k]]);
    result.front.fitness.push_back(fitness[candidates[k]]);
  }
  return result;
}

void write_run_outputs(const std::string& directory, const std::string& study_name,
                       const Problem& problem, const OptimizerSpec& spec, const RunOutcome& outcome,
                       int threads, const std::vector<double>& reference_point,
                       const ObjectiveSet& reference_front, const nlohmann::json& extra_summary,
                       const OutputFiles& also) {
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
    summary["hypervolume_missing"] = "a single objective has no hypervolume";
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
  OutputFiles files = also;
  files.emplace_back((dir / "pareto.csv").string(), csv.str());
  files.emplace_back((dir / "summary.json").string(), summary.dump(2) + "\n");
  write_files_together(files);
}

}  // namespace pkmopt
