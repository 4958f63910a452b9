#include "optimizer/ipopt_solver.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <coin/IpIpoptApplication.hpp>
#include <coin/IpSolveStatistics.hpp>
#include <coin/IpTNLP.hpp>
#include <sstream>
#include <stdexcept>

namespace pkmopt {
namespace {

using Ipopt::Index;
using Ipopt::Number;

constexpr double kIpoptInfinity = 1e19;

// The TNLP view of a Problem. Fitness and Jacobian are cached per point.
class ProblemTnlp : public Ipopt::TNLP {
 public:
  ProblemTnlp(const Problem& problem, std::vector<double> x0, const IpoptOptions& options)
      : problem_(problem),
        options_(options),
        bounds_(problem.bounds()),
        n_(problem.num_variables()),
        m_(problem.num_constraints()),
        x0_(std::move(x0)),
        use_gradient_(problem.has_gradient()) {
    if (use_gradient_) {
      const SparsityPattern pattern = problem.gradient_sparsity();
      for (std::size_t k = 0; k < pattern.size(); ++k) {
        sparsity_column_.push_back(pattern[k].second);
        if (pattern[k].first == 0) {
          objective_entries_.push_back(k);
        } else {
          constraint_entries_.push_back(k);
          constraint_pattern_.emplace_back(pattern[k].first - 1, pattern[k].second);
        }
      }
    } else {
      constraint_pattern_ = dense_sparsity(m_, n_);
    }
    best_x_ = x0_;
  }

  bool get_nlp_info(Index& n, Index& m, Index& nnz_jac_g, Index& nnz_h_lag,
                    IndexStyleEnum& index_style) override {
    n = static_cast<Index>(n_);
    m = static_cast<Index>(m_);
    nnz_jac_g = static_cast<Index>(constraint_pattern_.size());
    nnz_h_lag = 0;
    index_style = C_STYLE;
    return true;
  }

  bool get_bounds_info(Index, Number* x_l, Number* x_u, Index, Number* g_l, Number* g_u) override {
    for (std::size_t j = 0; j < n_; ++j) {
      x_l[j] = std::isfinite(bounds_.lower[j]) ? bounds_.lower[j] : -kIpoptInfinity;
      x_u[j] = std::isfinite(bounds_.upper[j]) ? bounds_.upper[j] : kIpoptInfinity;
    }
    const std::size_t p = problem_.num_equality();
    for (std::size_t i = 0; i < m_; ++i) {
      g_l[i] = i < p ? 0.0 : -kIpoptInfinity;
      g_u[i] = 0.0;
    }
    return true;
  }

  bool get_starting_point(Index, bool init_x, Number* x, bool, Number*, Number*, Index, bool,
                          Number*) override {
    if (init_x)
      for (std::size_t j = 0; j < n_; ++j) x[j] = x0_[j];
    return true;
  }

  bool eval_f(Index, const Number* x, bool, Number& obj_value) override {
    if (!update_fitness(x)) return false;
    obj_value = fitness_[0];
    return true;
  }

  bool eval_grad_f(Index, const Number* x, bool, Number* grad_f) override {
    if (!update_jacobian(x)) return false;
    if (use_gradient_) {
      std::fill(grad_f, grad_f + n_, 0.0);
      for (std::size_t k : objective_entries_) grad_f[pattern_column(k)] += gradient_[k];
    } else {
      for (std::size_t j = 0; j < n_; ++j) grad_f[j] = dense_[j];
    }
    return true;
  }

  bool eval_g(Index, const Number* x, bool, Index, Number* g) override {
    if (!update_fitness(x)) return false;
    const std::size_t objectives = problem_.num_objectives();
    for (std::size_t i = 0; i < m_; ++i) g[i] = fitness_[objectives + i];
    return true;
  }

  bool eval_jac_g(Index, const Number* x, bool, Index, Index, Index* iRow, Index* jCol,
                  Number* values) override {
    if (values == nullptr) {
      for (std::size_t k = 0; k < constraint_pattern_.size(); ++k) {
        iRow[k] = static_cast<Index>(constraint_pattern_[k].first);
        jCol[k] = static_cast<Index>(constraint_pattern_[k].second);
      }
      return true;
    }
    if (!update_jacobian(x)) return false;
    if (use_gradient_) {
      for (std::size_t k = 0; k < constraint_entries_.size(); ++k)
        values[k] = gradient_[constraint_entries_[k]];
    } else {
      for (std::size_t k = 0; k < constraint_pattern_.size(); ++k)
        values[k] = dense_[(constraint_pattern_[k].first + 1) * n_ + constraint_pattern_[k].second];
    }
    return true;
  }

  void finalize_solution(Ipopt::SolverReturn, Index, const Number* x, const Number*, const Number*,
                         Index, const Number*, const Number*, Number, const Ipopt::IpoptData*,
                         Ipopt::IpoptCalculatedQuantities*) override {
    best_x_.assign(x, x + n_);
    for (std::size_t j = 0; j < n_; ++j)
      best_x_[j] = std::clamp(best_x_[j], bounds_.lower[j], bounds_.upper[j]);
  }

  const std::vector<double>& final_x() const { return best_x_; }
  long long fitness_evaluations() const { return fitness_evaluations_; }
  long long gradient_evaluations() const { return gradient_evaluations_; }
  const std::string& error() const { return error_; }

 private:
  std::size_t pattern_column(std::size_t k) const { return sparsity_column_[k]; }

  bool same_point(const std::vector<double>& cached, const Number* x) const {
    return !cached.empty() && std::equal(cached.begin(), cached.end(), x);
  }

  bool update_fitness(const Number* x) {
    if (same_point(fitness_x_, x)) return fitness_ok_;
    fitness_x_.assign(x, x + n_);
    fitness_ok_ = false;
    try {
      ++fitness_evaluations_;
      fitness_ = checked_fitness(problem_, fitness_x_);
      fitness_ok_ =
          std::all_of(fitness_.begin(), fitness_.end(), [](double v) { return std::isfinite(v); });
    } catch (const std::exception& e) {
      error_ = e.what();
    }
    return fitness_ok_;
  }

  bool update_jacobian(const Number* x) {
    if (same_point(jacobian_x_, x)) return jacobian_ok_;
    jacobian_x_.assign(x, x + n_);
    jacobian_ok_ = false;
    try {
      if (use_gradient_) {
        ++gradient_evaluations_;
        gradient_ = problem_.gradient(jacobian_x_);
        if (gradient_.size() != sparsity_column_.size())
          throw std::runtime_error(
              fmt::format("problem '{}': gradient returned {} values, its sparsity pattern has {}",
                          problem_.name(), gradient_.size(), sparsity_column_.size()));
        jacobian_ok_ = std::all_of(gradient_.begin(), gradient_.end(),
                                   [](double v) { return std::isfinite(v); });
      } else {
        fitness_evaluations_ += 2 * static_cast<long long>(n_);
        dense_ = finite_difference_jacobian(problem_, jacobian_x_, options_.finite_difference_step);
        jacobian_ok_ =
            std::all_of(dense_.begin(), dense_.end(), [](double v) { return std::isfinite(v); });
      }
    } catch (const std::exception& e) {
      error_ = e.what();
    }
    return jacobian_ok_;
  }

  const Problem& problem_;
  const IpoptOptions& options_;
  Bounds bounds_;
  std::size_t n_;
  std::size_t m_;
  std::vector<double> x0_;
  bool use_gradient_;
  std::vector<std::size_t> objective_entries_;
  std::vector<std::size_t> constraint_entries_;
  SparsityPattern constraint_pattern_;
  std::vector<std::size_t> sparsity_column_;

  std::vector<double> fitness_x_, fitness_;
  bool fitness_ok_ = false;
  std::vector<double> jacobian_x_, gradient_, dense_;
  bool jacobian_ok_ = false;
  std::vector<double> best_x_;
  long long fitness_evaluations_ = 0;
  long long gradient_evaluations_ = 0;
  std::string error_;
};

SolveStatus status_from(Ipopt::ApplicationReturnStatus status) {
  switch (status) {
    case Ipopt::Solve_Succeeded:
      return SolveStatus::converged;
    case Ipopt::Solved_To_Acceptable_Level:
    case Ipopt::Feasible_Point_Found:
      return SolveStatus::acceptable;
    case Ipopt::Infeasible_Problem_Detected:
      return SolveStatus::infeasible;
    case Ipopt::Search_Direction_Becomes_Too_Small:
    case Ipopt::Diverging_Iterates:
      return SolveStatus::diverging;
    case Ipopt::Maximum_Iterations_Exceeded:
      return SolveStatus::max_iterations;
    case Ipopt::Maximum_CpuTime_Exceeded:
      return SolveStatus::max_time;
    case Ipopt::Invalid_Number_Detected:
      return SolveStatus::evaluation_error;
    default:
      return SolveStatus::failed;
  }
}

std::string ipopt_status_text(Ipopt::ApplicationReturnStatus status) {
  switch (status) {
    case Ipopt::Solve_Succeeded:
      return "Ipopt: optimal solution found";
    case Ipopt::Solved_To_Acceptable_Level:
      return "Ipopt: solved to acceptable level";
    case Ipopt::Infeasible_Problem_Detected:
      return "Ipopt: converged to a point of local infeasibility";
    case Ipopt::Search_Direction_Becomes_Too_Small:
      return "Ipopt: search direction becomes too small";
    case Ipopt::Diverging_Iterates:
      return "Ipopt: iterates diverging";
    case Ipopt::User_Requested_Stop:
      return "Ipopt: stopped by user";
    case Ipopt::Feasible_Point_Found:
      return "Ipopt: feasible point found";
    case Ipopt::Maximum_Iterations_Exceeded:
      return "Ipopt: maximum number of iterations exceeded";
    case Ipopt::Restoration_Failed:
      return "Ipopt: restoration phase failed";
    case Ipopt::Error_In_Step_Computation:
      return "Ipopt: error in step computation";
    case Ipopt::Maximum_CpuTime_Exceeded:
      return "Ipopt: maximum CPU time exceeded";
    case Ipopt::Not_Enough_Degrees_Of_Freedom:
      return "Ipopt: problem has too few degrees of freedom";
    case Ipopt::Invalid_Problem_Definition:
      return "Ipopt: invalid problem definition";
    case Ipopt::Invalid_Option:
      return "Ipopt: invalid option";
    case Ipopt::Invalid_Number_Detected:
      return "Ipopt: invalid number (NaN or inf) in the problem's values";
    default:
      return fmt::format("Ipopt: internal failure (status {})", static_cast<int>(status));
  }
}

bool set_option(Ipopt::IpoptApplication& app, const std::string& name, const std::string& value) {
  std::istringstream as_integer(value);
  long long integer = 0;
  // An integer text may name a real option ("0" for bound_relax_factor): try both.
  if (as_integer >> integer && as_integer.eof() &&
      app.Options()->SetIntegerValue(name, static_cast<Index>(integer)))
    return true;
  std::istringstream as_number(value);
  double number = 0.0;
  if (as_number >> number && as_number.eof()) return app.Options()->SetNumericValue(name, number);
  return app.Options()->SetStringValue(name, value);
}

}  // namespace

std::optional<std::string> IpoptOptions::validate() const {
  auto violated = [](const char* name, auto value, const char* rule) {
    return fmt::format("IpoptOptions::{} = {}. Violated constraint: {}", name, value, rule);
  };
  if (max_iterations < 0) return violated("max_iterations", max_iterations, "max_iterations >= 0");
  if (!(tolerance > 0.0)) return violated("tolerance", tolerance, "tolerance > 0");
  if (!(acceptable_tolerance >= tolerance))
    return violated("acceptable_tolerance", acceptable_tolerance,
                    "acceptable_tolerance >= tolerance");
  if (!(constraint_tolerance > 0.0))
    return violated("constraint_tolerance", constraint_tolerance, "constraint_tolerance > 0");
  if (!(max_seconds >= 0.0)) return violated("max_seconds", max_seconds, "max_seconds >= 0");
  if (limited_memory_history < 1)
    return violated("limited_memory_history", limited_memory_history,
                    "limited_memory_history >= 1");
  if (!(finite_difference_step > 0.0 && finite_difference_step < 0.1))
    return violated("finite_difference_step", finite_difference_step,
                    "0 < finite_difference_step < 0.1");
  if (print_level < 0 || print_level > 12)
    return violated("print_level", print_level, "0 <= print_level <= 12");
  return std::nullopt;
}

std::optional<std::string> ipopt_explain_unsupported(const Problem& problem) {
  try {
    check_bounds(problem);
  } catch (const std::invalid_argument& e) {
    return std::string(e.what());
  }
  if (problem.num_objectives() != 1)
    return fmt::format(
        "ipopt solves single-objective problems, but the problem named '{}' has {} objectives "
        "(use epsilon_constraint, nbi or hybrid to build a front)",
        problem.name(), problem.num_objectives());
  if (problem.has_gradient()) {
    const std::size_t rows = problem.fitness_size();
    const std::size_t n = problem.num_variables();
    for (const auto& [i, j] : problem.gradient_sparsity())
      if (i >= rows || j >= n)
        return fmt::format("the problem named '{}' has a sparsity entry ({}, {}) outside {}x{}",
                           problem.name(), i, j, rows, n);
  }
  return std::nullopt;
}

SolveResult solve_with_ipopt(const Problem& problem, const std::vector<double>& x0,
                             const IpoptOptions& options) {
  if (auto error = options.validate()) throw std::invalid_argument(*error);
  if (auto reason = ipopt_explain_unsupported(problem)) throw std::invalid_argument(*reason);
  const std::size_t n = problem.num_variables();
  if (x0.size() != n)
    throw std::invalid_argument(
        fmt::format("ipopt: starting point has {} values, problem '{}' has {} variables", x0.size(),
                    problem.name(), n));
  const auto start = std::chrono::steady_clock::now();
  const Bounds bounds = problem.bounds();
  std::vector<double> start_x = x0;
  for (std::size_t j = 0; j < n; ++j)
    start_x[j] = std::clamp(start_x[j], bounds.lower[j], bounds.upper[j]);

  SolveResult result;
  result.solver = "ipopt";
  result.problem = problem.name();

  Ipopt::SmartPtr<Ipopt::IpoptApplication> app = IpoptApplicationFactory();
  app->RethrowNonIpoptException(false);
  bool options_ok = true;
  options_ok &= app->Options()->SetStringValue("sb", "yes");
  options_ok &= app->Options()->SetIntegerValue("print_level", options.print_level);
  options_ok &= app->Options()->SetStringValue("hessian_approximation", "limited-memory");
  options_ok &=
      app->Options()->SetIntegerValue("limited_memory_max_history", options.limited_memory_history);
  options_ok &= app->Options()->SetIntegerValue("max_iter", options.max_iterations);
  options_ok &= app->Options()->SetNumericValue("tol", options.tolerance);
  options_ok &= app->Options()->SetNumericValue("acceptable_tol", options.acceptable_tolerance);
  options_ok &= app->Options()->SetNumericValue("constr_viol_tol", options.constraint_tolerance);
  // No relaxation of the bounds (Ipopt's default 1e-8 lets inequality rows end at about +1e-8:
  // results must satisfy g <= 0 as the problem states it).
  options_ok &= app->Options()->SetNumericValue("bound_relax_factor", 0.0);
  if (options.max_seconds > 0.0)
    options_ok &= app->Options()->SetNumericValue("max_cpu_time", options.max_seconds);
  std::string rejected;
  for (const auto& [name, value] : options.extra_options)
    if (!set_option(*app, name, value)) rejected += fmt::format(" '{}' = '{}'", name, value);
  std::istringstream no_option_file;
  const Ipopt::ApplicationReturnStatus init = app->Initialize(no_option_file);
  if (!options_ok || !rejected.empty() || init != Ipopt::Solve_Succeeded) {
    result.status = SolveStatus::failed;
    result.message = rejected.empty() ? "Ipopt rejected its options or failed to initialise"
                                      : "Ipopt rejected the options" + rejected;
    result.x = start_x;
    return result;
  }

  Ipopt::SmartPtr<ProblemTnlp> tnlp = new ProblemTnlp(problem, start_x, options);
  const Ipopt::ApplicationReturnStatus status = app->OptimizeTNLP(tnlp);
  result.status = status_from(status);
  result.message = ipopt_status_text(status);
  if (!tnlp->error().empty()) result.message += "; last evaluation error: " + tnlp->error();
  if (Ipopt::IsValid(app->Statistics())) result.iterations = app->Statistics()->IterationCount();
  result.x = tnlp->final_x();
  result.fitness_evaluations = tnlp->fitness_evaluations();
  result.gradient_evaluations = tnlp->gradient_evaluations();
  try {
    result.fitness = checked_fitness(problem, result.x);
    ++result.fitness_evaluations;
    result.objective = result.fitness[0];
    result.constraint_violation = constraint_violation(problem, result.fitness, 0.0, 0.0);
    if (!std::all_of(result.fitness.begin(), result.fitness.end(),
                     [](double v) { return std::isfinite(v); })) {
      result.status = SolveStatus::evaluation_error;
      result.message += "; non-finite fitness at the final point";
    }
  } catch (const std::exception& e) {
    result.fitness.clear();
    result.status = SolveStatus::evaluation_error;
    result.message += std::string("; evaluation at the final point failed: ") + e.what();
  }
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

}  // namespace pkmopt
