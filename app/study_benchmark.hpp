// Study files for `pkmopt run`: which problem, which optimizer, and the result files.
//
// A study file (YAML, strict: unknown keys are errors with file, line and column):
//   study: zdt1-nsga2                                  # name, required
//   description: "..."                                 # optional
//   problem: {benchmark: zdt1, variables: 30}          # required; see read_benchmark_problem
//   optimizer: {algorithm: nsga2, population: 100, generations: 250, seed: 1}   # required
//   indicators: {reference_point: [1.1, 1.1]}          # optional hypervolume reference point
//
// The pieces are separate so that other problem kinds (a machine and a task) reuse the
// optimizer section and the output writing: read_optimizer_section takes any Problem,
// run_optimizer runs it, write_run_outputs writes DIR/pareto.csv and DIR/summary.json.
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
//   BenchmarkStudy study = load_benchmark_study("studies/zdt1-nsga2.yaml");
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

#include "app/yaml_reader.hpp"
#include "optimizer/epsilon_constraint.hpp"
#include "optimizer/front_result.hpp"
#include "optimizer/hybrid.hpp"
#include "optimizer/ipopt_solver.hpp"
#include "optimizer/nbi.hpp"
#include "optimizer/nlopt_solver.hpp"
#include "optimizer/nsga2.hpp"
#include "optimizer/solve_result.hpp"
#include "problems/benchmarks.hpp"

namespace pkmopt {

/// The `optimizer:` section, resolved: the algorithm and the options of that algorithm.
struct OptimizerSpec {
  std::string algorithm;  ///< nsga2, epsilon_constraint, nbi, hybrid, ipopt or nlopt:<NAME>
  std::uint64_t seed = 1;
  Nsga2Options nsga2;
  EpsilonConstraintOptions epsilon_constraint;
  NbiOptions nbi;
  HybridOptions hybrid;
  IpoptOptions ipopt;
  NloptOptions nlopt;
  std::vector<double> start;  ///< start point for ipopt / nlopt (empty: bounds centre)
};

/// What a run produced: a front, and for single-objective algorithms the solver's result.
struct RunOutcome {
  FrontResult front;
  std::optional<SolveResult> single;
  std::string status;  ///< "ok", "no_feasible_design", or the single solver's status
};

/// A study whose problem is a benchmark.
struct BenchmarkStudy {
  std::string name;
  std::unique_ptr<BenchmarkProblem> problem;
  OptimizerSpec optimizer;
  std::vector<double> reference_point;  ///< empty: chosen by write_run_outputs
  /// The study with every optimizer default filled in (study.resolved.yaml; a valid study file).
  std::string resolved_yaml;
};

/// The `problem:` section of benchmark kind: keys benchmark (name), variables, objectives.
std::unique_ptr<BenchmarkProblem> read_benchmark_problem(const YamlValue& problem_section);

/// The `optimizer:` section for a given problem (checks that the algorithm can take it).
OptimizerSpec read_optimizer_section(const YamlValue& optimizer_section, const Problem& problem);

/// The resolved `optimizer:` section as a YAML flow map (every option of the algorithm with its
/// value; reading it back gives the same OptimizerSpec).
std::string optimizer_section_yaml(const OptimizerSpec& spec);

/// The optional `indicators:` section: reference_point with one value per objective.
std::vector<double> read_indicators_section(const YamlValue& indicators_section,
                                            std::size_t num_objectives);

/// Loads a whole benchmark study file (throws InputError for bad input).
BenchmarkStudy load_benchmark_study(const std::string& path);

/// Runs the optimizer of `spec` on `problem` (`threads` = 0: OpenMP's default).
RunOutcome run_optimizer(const Problem& problem, const OptimizerSpec& spec, int threads);

/// Writes DIR/pareto.csv and DIR/summary.json (creating DIR), each atomically; the keys of
/// `extra_summary` are added to summary.json.
/// `reference_point` empty: nadir + 10% of the range of `reference_front` if given, else of
/// the front found. `reference_front` may be empty (no IGD+ then).
void write_run_outputs(const std::string& directory, const std::string& study_name,
                       const Problem& problem, const OptimizerSpec& spec, const RunOutcome& outcome,
                       int threads, const std::vector<double>& reference_point,
                       const ObjectiveSet& reference_front,
                       const nlohmann::json& extra_summary = nlohmann::json::object());

}  // namespace pkmopt
