// Study files for `pkmopt run`: which problem, which optimizer, and the result files.
//
// A study file (YAML, strict: unknown keys are errors with file, line and column):
//   study: zdt1-nsga2                                  # name, required
//   description: "..."                                 # optional
//   problem: {benchmark: zdt1, variables: 30}          # required; see read_benchmark_problem
//   optimizer: {algorithm: nsga2, population: 100, generations: 250, seed: 1}   # required
//   indicators: {reference_point: [1.1, 1.1]}          # optional hypervolume reference point
//
// Design studies (studies/design_study.hpp) share the optimizer section and its runner
// (studies/optimizer_spec.hpp); write_run_outputs writes DIR/pareto.csv and DIR/summary.json.
//
// pareto.csv: one row per feasible non-dominated design, columns x_1..x_n, f_1..f_m (the
// problem's variables and objectives in its own units and sign). summary.json: study, problem,
// algorithm, status, message, evaluations, gradient_evaluations, points, hypervolume,
// reference_point, igd_plus (when an analytic front is known), time_seconds, seed, threads,
// subproblems, failed_subproblems, dominated_subproblems, knee_point (row index, 0-based) and
// pkmopt version. For single-objective algorithms (ipopt, nlopt:NAME) hypervolume,
// reference_point and igd_plus are null and `objective` and `constraint_violation` are given.
//
// Example:
//   BenchmarkStudy study = load_benchmark_study("studies/library/zdt1-nsga2.yaml");
//   RunOutcome outcome = run_optimizer(*study.problem, study.optimizer, /*threads=*/0);
//   write_run_outputs("out", study.name, *study.problem, study.optimizer, outcome, 0,
//                     study.reference_point, study.problem->reference_front(1000));
#pragma once

#include <cstdint>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "io/format/output_file.hpp"
#include "io/format/yaml_reader.hpp"
#include "problems/benchmarks/benchmarks.hpp"
#include "studies/optimizer_spec.hpp"

namespace pkmopt {

/// A study whose problem is a benchmark.
struct BenchmarkStudy {
  std::string name;
  std::unique_ptr<BenchmarkProblem> problem;
  OptimizerSpec optimizer;
  std::vector<double> reference_point;  ///< empty: chosen by write_run_outputs
  /// output.front_size: the front is thinned to this many points; 0: not thinned.
  std::size_t front_size = 0;
  /// The study with every optimizer default filled in (study.resolved.yaml; a valid study file).
  std::string resolved_yaml;
};

/// The `problem:` section of benchmark kind: keys benchmark (name), variables, objectives.
std::unique_ptr<BenchmarkProblem> read_benchmark_problem(const YamlValue& problem_section);

/// The docs table of the `problem:` section, from the field list its reader and the resolved
/// writer use.
std::string benchmark_problem_fields_markdown();

/// The optional `indicators:` section: reference_point with one value per objective.
std::vector<double> read_indicators_section(const YamlValue& indicators_section,
                                            std::size_t num_objectives);

/// Loads a whole benchmark study file (throws InputError for bad input).
BenchmarkStudy load_benchmark_study(const std::string& path);
/// The same from a parsed study.
BenchmarkStudy load_benchmark_study(const YamlValue& root);

/// A benchmark evaluation is feasible when its objectives are finite and every equality is
/// within this tolerance of 0 and every inequality at most this (the solvers' tolerance,
/// SolveResult::usable()): evaluations.csv's `feasible` column and the archive use this rule.
inline constexpr double kBenchmarkFeasibilityTolerance = 1e-6;
bool benchmark_feasible(const Problem& problem, const std::vector<double>& fitness);

/// The front of a run from every evaluation it made (xs[k] with fitness[k]): the non-dominated
/// set of the feasible ones, thinned to `front_size` when > 0 (optimizer/front_thinning.hpp), in
/// ascending order of objective vectors.
struct ArchivedFront {
  FrontResult front;                     ///< x and fitness of the chosen points
  std::size_t feasible_evaluations = 0;  ///< feasible evaluations among the inputs
  std::size_t archive_size = 0;          ///< of them non-dominated (before thinning)
};
ArchivedFront archive_front(const Problem& problem, const std::vector<std::vector<double>>& xs,
                            const std::vector<std::vector<double>>& fitness,
                            std::size_t front_size);

/// Writes DIR/pareto.csv and DIR/summary.json (creating DIR) and the files `also` names, all or
/// none (io/format/output_file.hpp); the keys of `extra_summary` are added to summary.json.
/// `reference_point` empty: nadir + 10% of the range of `reference_front` if given, else of
/// the front found. `reference_front` may be empty (no IGD+ then).
void write_run_outputs(const std::string& directory, const std::string& study_name,
                       const Problem& problem, const OptimizerSpec& spec, const RunOutcome& outcome,
                       int threads, const std::vector<double>& reference_point,
                       const ObjectiveSet& reference_front,
                       const nlohmann::json& extra_summary = nlohmann::json::object(),
                       const OutputFiles& also = {});

}  // namespace pkmopt
