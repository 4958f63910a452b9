#include "optimizer/nlopt_solver.hpp"

#include <fmt/format.h>
#include <nlopt.h>

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cmath>
#include <memory>
#include <stdexcept>

namespace pkmopt {
namespace {

struct AlgorithmInfo {
  const char* name;
  const char* nlopt_name;
  nlopt_algorithm id;
  bool global;
  bool gradient;
  bool inequality;
  bool equality;
  bool needs_local;
};

constexpr AlgorithmInfo kAlgorithms[] = {
    {"DIRECT_L", "GN_DIRECT_L", NLOPT_GN_DIRECT_L, true, false, false, false, false},
    {"DIRECT", "GN_DIRECT", NLOPT_GN_DIRECT, true, false, false, false, false},
    {"CRS2", "GN_CRS2_LM", NLOPT_GN_CRS2_LM, true, false, false, false, false},
    {"ESCH", "GN_ESCH", NLOPT_GN_ESCH, true, false, false, false, false},
    {"ISRES", "GN_ISRES", NLOPT_GN_ISRES, true, false, true, true, false},
    {"MLSL", "G_MLSL_LDS", NLOPT_G_MLSL_LDS, true, false, false, false, true},
    {"SLSQP", "LD_SLSQP", NLOPT_LD_SLSQP, false, true, true, true, false},
    {"COBYLA", "LN_COBYLA", NLOPT_LN_COBYLA, false, false, true, true, false},
    {"BOBYQA", "LN_BOBYQA", NLOPT_LN_BOBYQA, false, false, false, false, false},
    {"MMA", "LD_MMA", NLOPT_LD_MMA, false, true, true, false, false},
    {"CCSAQ", "LD_CCSAQ", NLOPT_LD_CCSAQ, false, true, true, false, false},
    {"LBFGS", "LD_LBFGS", NLOPT_LD_LBFGS, false, true, false, false, false},
    {"NELDERMEAD", "LN_NELDERMEAD", NLOPT_LN_NELDERMEAD, false, false, false, false, false},
    {"SBPLX", "LN_SBPLX", NLOPT_LN_SBPLX, false, false, false, false, false},
    {"AUGLAG", "AUGLAG", NLOPT_AUGLAG, false, false, true, true, true},
};

std::string upper(std::string text) {
  for (char& c : text) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  return text;
}

const AlgorithmInfo* find_algorithm(const std::string& name) {
  const std::string key = upper(name);
  for (const AlgorithmInfo& info : kAlgorithms)
    if (key == info.name || key == info.nlopt_name) return &info;
  return nullptr;
}

std::string known_names() {
  std::string names;
  for (const AlgorithmInfo& info : kAlgorithms)
    names += (names.empty() ? "" : ", ") + std::string(info.name);
  return names;
}

// Evaluates fitness and (when asked) the dense Jacobian at the points NLopt asks for.
class Evaluator {
 public:
  Evaluator(const Problem& problem, double step) : problem_(problem), step_(step) {}

  const std::vector<double>& fitness(const double* x) {
    if (fitness_x_.empty() || !std::equal(fitness_x_.begin(), fitness_x_.end(), x)) {
      fitness_x_.assign(x, x + problem_.num_variables());
      ++fitness_evaluations_;
      fitness_ = checked_fitness(problem_, fitness_x_);
    }
    return fitness_;
  }

  const std::vector<double>& jacobian(const double* x) {
    if (jacobian_x_.empty() || !std::equal(jacobian_x_.begin(), jacobian_x_.end(), x)) {
      jacobian_x_.assign(x, x + problem_.num_variables());
      if (problem_.has_gradient()) {
        ++gradient_evaluations_;
        jacobian_ = dense_jacobian(problem_, jacobian_x_);
      } else {
        fitness_evaluations_ += 2 * static_cast<long long>(jacobian_x_.size());
        jacobian_ = finite_difference_jacobian(problem_, jacobian_x_, step_);
      }
    }
    return jacobian_;
  }

  const Problem& problem_;
  double step_;
  std::vector<double> fitness_x_, fitness_, jacobian_x_, jacobian_;
  long long fitness_evaluations_ = 0;
  long long gradient_evaluations_ = 0;
  std::string error_;
  nlopt_opt opt_ = nullptr;
};

double objective_callback(unsigned n, const double* x, double* grad, void* data) {
  auto& evaluator = *static_cast<Evaluator*>(data);
  try {
    const double f = evaluator.fitness(x)[0];
    if (grad != nullptr) {
      const std::vector<double>& jacobian = evaluator.jacobian(x);
      std::copy(jacobian.begin(), jacobian.begin() + n, grad);
    }
    return std::isnan(f) ? HUGE_VAL : f;
  } catch (const std::exception& e) {
    evaluator.error_ = e.what();
    nlopt_force_stop(evaluator.opt_);
    return HUGE_VAL;
  }
}

// Constraint block [first, first + count) of the fitness, as NLopt's vector constraint.
struct ConstraintBlock {
  Evaluator* evaluator;
  std::size_t first;
  std::size_t count;
};

void constraint_callback(unsigned m, double* result, unsigned n, const double* x, double* grad,
                         void* data) {
  auto& block = *static_cast<ConstraintBlock*>(data);
  try {
    const std::vector<double>& f = block.evaluator->fitness(x);
    for (unsigned i = 0; i < m; ++i) result[i] = f[block.first + i];
    if (grad != nullptr) {
      const std::vector<double>& jacobian = block.evaluator->jacobian(x);
      std::copy(jacobian.begin() + static_cast<std::ptrdiff_t>(block.first * n),
                jacobian.begin() + static_cast<std::ptrdiff_t>((block.first + m) * n), grad);
    }
  } catch (const std::exception& e) {
    block.evaluator->error_ = e.what();
    nlopt_force_stop(block.evaluator->opt_);
    for (unsigned i = 0; i < m; ++i) result[i] = HUGE_VAL;
  }
}

struct OptDeleter {
  void operator()(nlopt_opt opt) const { nlopt_destroy(opt); }
};

}  // namespace

std::optional<std::string> NloptOptions::validate() const {
  auto violated = [](const char* name, auto value, const char* rule) {
    return fmt::format("NloptOptions::{} = {}. Violated constraint: {}", name, value, rule);
  };
  if (find_algorithm(algorithm) == nullptr)
    return fmt::format("NloptOptions::algorithm = '{}'. Expected one of: {}", algorithm,
                       known_names());
  const AlgorithmInfo* local = find_algorithm(local_algorithm);
  if (local == nullptr || local->global || local->needs_local)
    return fmt::format("NloptOptions::local_algorithm = '{}'. Expected a local algorithm",
                       local_algorithm);
  if (max_evaluations < 1)
    return violated("max_evaluations", max_evaluations, "max_evaluations >= 1");
  if (!(max_seconds >= 0.0)) return violated("max_seconds", max_seconds, "max_seconds >= 0");
  if (!(relative_tolerance_f >= 0.0))
    return violated("relative_tolerance_f", relative_tolerance_f, "relative_tolerance_f >= 0");
  if (!(relative_tolerance_x >= 0.0))
    return violated("relative_tolerance_x", relative_tolerance_x, "relative_tolerance_x >= 0");
  if (!(constraint_tolerance > 0.0))
    return violated("constraint_tolerance", constraint_tolerance, "constraint_tolerance > 0");
  if (!(finite_difference_step > 0.0 && finite_difference_step < 0.1))
    return violated("finite_difference_step", finite_difference_step,
                    "0 < finite_difference_step < 0.1");
  return std::nullopt;
}

std::vector<std::string> nlopt_algorithm_names() {
  std::vector<std::string> names;
  for (const AlgorithmInfo& info : kAlgorithms) names.emplace_back(info.name);
  return names;
}

std::optional<std::string> nlopt_explain_unsupported(const Problem& problem,
                                                     const NloptOptions& options) {
  if (auto error = options.validate()) return error;
  try {
    check_bounds(problem);
  } catch (const std::invalid_argument& e) {
    return std::string(e.what());
  }
  const AlgorithmInfo& info = *find_algorithm(options.algorithm);
  if (problem.num_objectives() != 1)
    return fmt::format(
        "nlopt:{} solves single-objective problems, but the problem named '{}' has {} objectives",
        info.name, problem.name(), problem.num_objectives());
  if (problem.num_equality() > 0 && !info.equality)
    return fmt::format(
        "nlopt:{} does not support equality constraints, but the problem named '{}' has {} "
        "(algorithms that do: ISRES, SLSQP, COBYLA, AUGLAG)",
        info.name, problem.name(), problem.num_equality());
  if (problem.num_inequality() > 0 && !info.inequality)
    return fmt::format(
        "nlopt:{} does not support inequality constraints, but the problem named '{}' has {} "
        "(algorithms that do: ISRES, SLSQP, COBYLA, MMA, CCSAQ, AUGLAG)",
        info.name, problem.name(), problem.num_inequality());
  if (info.global) {
    const Bounds b = problem.bounds();
    for (std::size_t j = 0; j < b.lower.size(); ++j)
      if (!std::isfinite(b.lower[j]) || !std::isfinite(b.upper[j]))
        return fmt::format(
            "nlopt:{} is a global algorithm and needs finite bounds, but variable {} of '{}' is "
            "unbounded",
            info.name, j + 1, problem.name());
  }
  return std::nullopt;
}

SolveResult solve_with_nlopt(const Problem& problem, const std::vector<double>& x0,
                             const NloptOptions& options) {
  if (auto reason = nlopt_explain_unsupported(problem, options))
    throw std::invalid_argument(*reason);
  const AlgorithmInfo& info = *find_algorithm(options.algorithm);
  const std::size_t n = problem.num_variables();
  if (x0.size() != n)
    throw std::invalid_argument(
        fmt::format("nlopt: starting point has {} values, problem '{}' has {} variables", x0.size(),
                    problem.name(), n));
  const auto start = std::chrono::steady_clock::now();
  const Bounds bounds = problem.bounds();
  std::vector<double> x = x0;
  for (std::size_t j = 0; j < n; ++j) x[j] = std::clamp(x[j], bounds.lower[j], bounds.upper[j]);

  std::unique_ptr<nlopt_opt_s, OptDeleter> opt(nlopt_create(info.id, static_cast<unsigned>(n)));
  Evaluator evaluator(problem, options.finite_difference_step);
  evaluator.opt_ = opt.get();
  nlopt_set_lower_bounds(opt.get(), bounds.lower.data());
  nlopt_set_upper_bounds(opt.get(), bounds.upper.data());
  nlopt_set_min_objective(opt.get(), objective_callback, &evaluator);
  nlopt_set_maxeval(opt.get(),
                    static_cast<int>(std::min<long long>(options.max_evaluations, 2000000000)));
  if (options.max_seconds > 0.0) nlopt_set_maxtime(opt.get(), options.max_seconds);
  nlopt_set_ftol_rel(opt.get(), options.relative_tolerance_f);
  nlopt_set_xtol_rel(opt.get(), options.relative_tolerance_x);
  if (options.population > 0) nlopt_set_population(opt.get(), options.population);

  const std::size_t m = problem.num_objectives();
  ConstraintBlock equalities{&evaluator, m, problem.num_equality()};
  ConstraintBlock inequalities{&evaluator, m + problem.num_equality(), problem.num_inequality()};
  const std::vector<double> eq_tol(equalities.count, options.constraint_tolerance);
  const std::vector<double> ineq_tol(inequalities.count, options.constraint_tolerance);
  if (equalities.count > 0)
    nlopt_add_equality_mconstraint(opt.get(), static_cast<unsigned>(equalities.count),
                                   constraint_callback, &equalities, eq_tol.data());
  if (inequalities.count > 0)
    nlopt_add_inequality_mconstraint(opt.get(), static_cast<unsigned>(inequalities.count),
                                     constraint_callback, &inequalities, ineq_tol.data());
  std::unique_ptr<nlopt_opt_s, OptDeleter> local;
  if (info.needs_local) {
    local.reset(
        nlopt_create(find_algorithm(options.local_algorithm)->id, static_cast<unsigned>(n)));
    nlopt_set_ftol_rel(local.get(), options.relative_tolerance_f);
    nlopt_set_xtol_rel(local.get(), options.relative_tolerance_x);
    nlopt_set_local_optimizer(opt.get(), local.get());
  }
  nlopt_srand(options.seed);

  double best = HUGE_VAL;
  const nlopt_result code = nlopt_optimize(opt.get(), x.data(), &best);

  SolveResult result;
  result.solver = "nlopt:" + std::string(info.name);
  result.problem = problem.name();
  result.message = fmt::format("NLopt {}: {}", info.nlopt_name, nlopt_result_to_string(code));
  switch (code) {
    case NLOPT_SUCCESS:
    case NLOPT_STOPVAL_REACHED:
    case NLOPT_FTOL_REACHED:
    case NLOPT_XTOL_REACHED:
      result.status = SolveStatus::converged;
      break;
    case NLOPT_ROUNDOFF_LIMITED:
      result.status = SolveStatus::acceptable;
      break;
    case NLOPT_MAXEVAL_REACHED:
      // A global algorithm always ends on its budget: that is its normal end.
      result.status = info.global ? SolveStatus::acceptable : SolveStatus::max_iterations;
      break;
    case NLOPT_MAXTIME_REACHED:
      result.status = info.global ? SolveStatus::acceptable : SolveStatus::max_time;
      break;
    case NLOPT_FORCED_STOP:
      result.status = SolveStatus::evaluation_error;
      break;
    default:
      result.status = SolveStatus::failed;
      break;
  }
  if (!evaluator.error_.empty()) result.message += "; evaluation error: " + evaluator.error_;
  for (std::size_t j = 0; j < n; ++j) x[j] = std::clamp(x[j], bounds.lower[j], bounds.upper[j]);
  result.x = x;
  result.iterations = nlopt_get_numevals(opt.get());
  try {
    result.fitness = checked_fitness(problem, x);
    ++evaluator.fitness_evaluations_;
    result.objective = result.fitness[0];
    result.constraint_violation = constraint_violation(problem, result.fitness, 0.0, 0.0);
    // A NaN was a failed evaluation to NLopt (HUGE_VAL); a final point that is one is no answer.
    if (std::any_of(result.fitness.begin(), result.fitness.end(),
                    [](double v) { return std::isnan(v); })) {
      result.status = SolveStatus::evaluation_error;
      result.message += "; the problem's values at the final point are not numbers (NaN)";
    }
  } catch (const std::exception& e) {
    result.status = SolveStatus::evaluation_error;
    result.message += std::string("; evaluation at the final point failed: ") + e.what();
  }
  result.fitness_evaluations = evaluator.fitness_evaluations_;
  result.gradient_evaluations = evaluator.gradient_evaluations_;
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

}  // namespace pkmopt
