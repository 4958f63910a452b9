// The `optimizer:` section of a study file: which algorithm, its options, and running it.
//
// A study names one algorithm and only that algorithm's options (strict: any other key is an
// error with file, line and column). The resolved spec is a closed set: OptimizerSpec holds the
// seed and exactly one of the algorithm specs below.
//
//   optimizer: {algorithm: nsga2, population: 100, generations: 250, seed: 1,
//               crossover_probability: 0.9, crossover_eta: 15, mutation_probability: 0 (= 1/n),
//               mutation_eta: 20}
//   optimizer: {algorithm: hybrid, <nsga2 keys>, polish_iterations: 200}
//   optimizer: {algorithm: nsga3, divisions: 12, generations: 250}   # population: automatic
//   optimizer: {algorithm: epsilon_constraint, points: 21, primary_objective: 1,
//               max_iterations: 200, tolerance: 1e-8, start: [...]}
//   optimizer: {algorithm: nbi, points: 21, equality_form: false, max_iterations, tolerance, start}
//   optimizer: {algorithm: ipopt, max_iterations, tolerance, start}
//   optimizer: {algorithm: "nlopt:SLSQP", max_evaluations, tolerance, population,
//               local_algorithm, start}
// docs/optimizer.md lists every key with its default and meaning.
//
// Example:
//   const OptimizerSpec spec = read_optimizer_section(root.required("optimizer"), problem);
//   const RunOutcome outcome = run_optimizer(problem, spec, /*threads=*/0);
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "io/format/yaml_reader.hpp"
#include "optimizer/epsilon_constraint.hpp"
#include "optimizer/front_result.hpp"
#include "optimizer/hybrid.hpp"
#include "optimizer/ipopt_solver.hpp"
#include "optimizer/moead.hpp"
#include "optimizer/nbi.hpp"
#include "optimizer/nlopt_solver.hpp"
#include "optimizer/nsga2.hpp"
#include "optimizer/nsga3.hpp"
#include "optimizer/problem.hpp"
#include "optimizer/solve_result.hpp"

namespace pkmopt {

/// NSGA-II (optimizer/nsga2.hpp); options.seed is the spec's seed.
struct Nsga2Spec {
  Nsga2Options options;
};
/// NSGA-III (optimizer/nsga3.hpp); options.seed is the spec's seed, options.population the
/// resolved one (never 0 once read).
struct Nsga3Spec {
  Nsga3Options options;
  /// The `aspiration` points as the study file gives them (objective order, the objectives' own
  /// sense and units); options.aspiration_points holds them minimised.
  std::vector<std::vector<double>> aspiration;
};
/// MOEA/D-DE (optimizer/moead.hpp); options.seed is the spec's seed.
struct MoeadSpec {
  MoeadOptions options;
  std::size_t population = 0;  ///< the number of weight vectors, resolved when read
};
/// NSGA-II, then every front point polished by Ipopt (optimizer/hybrid.hpp).
struct HybridSpec {
  HybridOptions options;
};
/// The epsilon-constraint front builder (optimizer/epsilon_constraint.hpp).
struct EpsilonConstraintSpec {
  EpsilonConstraintOptions options;
};
/// Normal Boundary Intersection (optimizer/nbi.hpp).
struct NbiSpec {
  NbiOptions options;
};
/// One Ipopt solve of a single-objective problem from `start` (empty: the bounds' centre).
struct IpoptSpec {
  IpoptOptions options;
  std::vector<double> start;
};
/// One NLopt solve; options.algorithm is the NAME of `nlopt:NAME`.
struct NloptSpec {
  NloptOptions options;
  std::vector<double> start;
};

using AlgorithmSpec = std::variant<Nsga2Spec, Nsga3Spec, MoeadSpec, HybridSpec,
                                   EpsilonConstraintSpec, NbiSpec, IpoptSpec, NloptSpec>;

/// The `optimizer:` section, resolved.
struct OptimizerSpec {
  std::uint64_t seed = 1;
  AlgorithmSpec algorithm = Nsga2Spec{};

  /// The algorithm's name as written in study files: nsga2, nsga3, hybrid, epsilon_constraint, nbi,
  /// ipopt or nlopt:NAME.
  std::string name() const;
  /// The NSGA-II options of nsga2 and hybrid; null for the other algorithms.
  const Nsga2Options* nsga2() const;
  /// The NSGA-III options of nsga3; null for the other algorithms.
  const Nsga3Options* nsga3() const;
  /// The MOEA/D options of moead; null for the other algorithms.
  const MoeadOptions* moead() const;
  /// The number of fitness requests an nsga2 run makes (population x (generations + 1)); 0 when
  /// it is not known in advance.
  long long expected_requests() const;
};

/// What a run produced: a front, and for single-objective algorithms the solver's result.
struct RunOutcome {
  FrontResult front;
  std::optional<SolveResult> single;
  std::string status;  ///< "ok", "no_feasible_design", or the single solver's status
};

/// The problem's objectives as a study file names them (for nsga3's `aspiration` points): names
/// (empty: the points are lists in objective order only) and which are maximised (the problem
/// minimises their negative).
struct ObjectiveNaming {
  std::vector<std::string> names;
  std::vector<bool> maximize;
};

/// The `optimizer:` section for a given problem (checks that the algorithm can take it; throws
/// InputError naming the key otherwise).
OptimizerSpec read_optimizer_section(const YamlValue& optimizer_section, const Problem& problem,
                                     const ObjectiveNaming& objectives = {});

/// The resolved `optimizer:` section as a YAML flow map (every option of the algorithm with its
/// value; reading it back gives the same OptimizerSpec).
std::string optimizer_section_yaml(const OptimizerSpec& spec);

/// The docs table of an algorithm's keys (nsga2, hybrid, epsilon_constraint, nbi, ipopt, nlopt),
/// from the same field list the reader and writer use (studies/optimizer_fields.hpp).
std::string optimizer_fields_markdown(std::string_view algorithm);

/// The largest `output: {front_size: N}` a study may ask for.
inline constexpr int kMaxFrontSize = 100000;

/// How the front of a run was chosen, in words for summary.json (`front_size` 0: not thinned).
std::string front_rule_text(std::size_t front_size, std::size_t num_objectives);

/// Runs the optimizer of `spec` on `problem` (`threads` = 0: OpenMP's default). A solver that
/// does not converge is a result (its status in RunOutcome::status), not an exception.
RunOutcome run_optimizer(const Problem& problem, const OptimizerSpec& spec, int threads);

}  // namespace pkmopt
