#include "optimizer/problem.hpp"

#include <fmt/format.h>
#include <omp.h>

#include <algorithm>
#include <cmath>
#include <exception>
#include <stdexcept>

namespace pkmopt {

std::vector<std::vector<double>> Problem::batch_fitness(std::span<const std::vector<double>> xs,
                                                        int threads) const {
  std::vector<std::vector<double>> result(xs.size());
  const int thread_count = resolve_thread_count(threads);
  if (thread_count <= 1 || thread_safety() == ThreadSafety::none || xs.size() < 2) {
    for (std::size_t k = 0; k < xs.size(); ++k) result[k] = fitness(xs[k]);
    return result;
  }
  std::exception_ptr first_error;
  const long long count = static_cast<long long>(xs.size());
#pragma omp parallel for num_threads(thread_count) schedule(dynamic)
  for (long long k = 0; k < count; ++k) {
    try {
      result[static_cast<std::size_t>(k)] = fitness(xs[static_cast<std::size_t>(k)]);
    } catch (...) {
#pragma omp critical(pkmopt_batch_fitness_error)
      if (!first_error) first_error = std::current_exception();
    }
  }
  if (first_error) std::rethrow_exception(first_error);
  return result;
}

std::vector<double> Problem::gradient(const std::vector<double>&) const {
  throw std::logic_error(fmt::format("the problem named '{}' does not provide a gradient", name()));
}

SparsityPattern Problem::gradient_sparsity() const {
  return dense_sparsity(fitness_size(), num_variables());
}

SparsityPattern dense_sparsity(std::size_t rows, std::size_t columns) {
  SparsityPattern pattern;
  pattern.reserve(rows * columns);
  for (std::size_t i = 0; i < rows; ++i)
    for (std::size_t j = 0; j < columns; ++j) pattern.emplace_back(i, j);
  return pattern;
}

void check_bounds(const Problem& problem) {
  const Bounds b = problem.bounds();
  if (b.lower.size() != b.upper.size())
    throw std::invalid_argument(fmt::format("problem '{}': {} lower bounds but {} upper bounds",
                                            problem.name(), b.lower.size(), b.upper.size()));
  if (b.lower.empty())
    throw std::invalid_argument(fmt::format("problem '{}' has no variables", problem.name()));
  for (std::size_t i = 0; i < b.lower.size(); ++i) {
    if (std::isnan(b.lower[i]) || std::isnan(b.upper[i]) || b.lower[i] > b.upper[i])
      throw std::invalid_argument(
          fmt::format("problem '{}': bounds of variable {} are [{}, {}]; expected lower <= upper",
                      problem.name(), i + 1, b.lower[i], b.upper[i]));
  }
  if (problem.num_objectives() == 0)
    throw std::invalid_argument(fmt::format("problem '{}' has no objectives", problem.name()));
}

std::vector<double> checked_fitness(const Problem& problem, const std::vector<double>& x) {
  std::vector<double> f = problem.fitness(x);
  if (f.size() != problem.fitness_size())
    throw std::runtime_error(
        fmt::format("problem '{}': fitness returned {} values, expected {} "
                    "({} objectives + {} equalities + {} inequalities)",
                    problem.name(), f.size(), problem.fitness_size(), problem.num_objectives(),
                    problem.num_equality(), problem.num_inequality()));
  return f;
}

double constraint_violation(const Problem& problem, std::span<const double> fitness,
                            double equality_tolerance, double inequality_tolerance) {
  const std::size_t m = problem.num_objectives();
  const std::size_t p = problem.num_equality();
  const std::size_t q = problem.num_inequality();
  double violation = 0.0;
  for (std::size_t i = m; i < m + p; ++i) {
    const double h = fitness[i];
    if (std::isnan(h)) return INFINITY;
    violation += std::max(std::abs(h) - equality_tolerance, 0.0);
  }
  for (std::size_t i = m + p; i < m + p + q; ++i) {
    const double g = fitness[i];
    if (std::isnan(g)) return INFINITY;
    violation += std::max(g - inequality_tolerance, 0.0);
  }
  return violation;
}

std::vector<double> finite_difference_jacobian(const Problem& problem, const std::vector<double>& x,
                                               double step) {
  const Bounds b = problem.bounds();
  const std::size_t n = x.size();
  const std::size_t rows = problem.fitness_size();
  std::vector<double> jacobian(rows * n, 0.0);
  std::vector<double> probe = x;
  for (std::size_t j = 0; j < n; ++j) {
    const double h = step * std::max(1.0, std::abs(x[j]));
    double forward = x[j] + h;
    double backward = x[j] - h;
    if (forward > b.upper[j]) forward = x[j];
    if (backward < b.lower[j]) backward = x[j];
    if (forward == backward) continue;  // a variable fixed by its bounds
    probe[j] = forward;
    const std::vector<double> f_forward = checked_fitness(problem, probe);
    probe[j] = backward;
    const std::vector<double> f_backward = checked_fitness(problem, probe);
    probe[j] = x[j];
    const double width = forward - backward;
    for (std::size_t i = 0; i < rows; ++i)
      jacobian[i * n + j] = (f_forward[i] - f_backward[i]) / width;
  }
  return jacobian;
}

std::vector<double> dense_jacobian(const Problem& problem, const std::vector<double>& x) {
  const std::size_t n = x.size();
  const std::vector<double> values = problem.gradient(x);
  const SparsityPattern pattern = problem.gradient_sparsity();
  if (values.size() != pattern.size())
    throw std::runtime_error(fmt::format(
        "problem '{}': gradient returned {} values but its sparsity pattern has {} entries",
        problem.name(), values.size(), pattern.size()));
  std::vector<double> jacobian(problem.fitness_size() * n, 0.0);
  for (std::size_t k = 0; k < pattern.size(); ++k) {
    const auto [i, j] = pattern[k];
    if (i >= problem.fitness_size() || j >= n)
      throw std::runtime_error(
          fmt::format("problem '{}': sparsity entry {} is ({}, {}), outside the {}x{} Jacobian",
                      problem.name(), k, i, j, problem.fitness_size(), n));
    jacobian[i * n + j] = values[k];
  }
  return jacobian;
}

GradientCheck check_gradient(const Problem& problem, const std::vector<double>& x,
                             const GradientCheckOptions& options) {
  if (!problem.has_gradient())
    throw std::logic_error(fmt::format(
        "check_gradient: the problem named '{}' does not provide a gradient", problem.name()));
  const std::size_t n = x.size();
  const std::vector<double> analytic = dense_jacobian(problem, x);
  const std::vector<double> numeric = finite_difference_jacobian(problem, x, options.step);
  GradientCheck check;
  check.max_error = 0.0;
  for (std::size_t k = 0; k < analytic.size(); ++k) {
    const double error = std::abs(analytic[k] - numeric[k]) / std::max(1.0, std::abs(numeric[k]));
    if (!(error <= check.max_error)) {  // also catches NaN
      check.max_error = std::isnan(error) ? INFINITY : error;
      check.worst_row = k / n;
      check.worst_column = k % n;
      check.analytic_value = analytic[k];
      check.finite_difference_value = numeric[k];
    }
  }
  check.ok = check.max_error <= options.relative_tolerance;
  check.report = fmt::format(
      "problem '{}': gradient {} (largest relative error {:.3g} at d fitness[{}] / d x[{}]: "
      "analytic {:.10g}, finite differences {:.10g}; tolerance {:.3g})",
      problem.name(),
      check.ok ? "agrees with finite differences" : "DISAGREES with finite differences",
      check.max_error, check.worst_row, check.worst_column, check.analytic_value,
      check.finite_difference_value, options.relative_tolerance);
  return check;
}

std::vector<double> CountingProblem::fitness(const std::vector<double>& x) const {
  ++fitness_evaluations_;
  return inner().fitness(x);
}

std::vector<std::vector<double>> CountingProblem::batch_fitness(
    std::span<const std::vector<double>> xs, int threads) const {
  fitness_evaluations_ += static_cast<long long>(xs.size());
  return inner().batch_fitness(xs, threads);
}

std::vector<double> CountingProblem::gradient(const std::vector<double>& x) const {
  ++gradient_evaluations_;
  return inner().gradient(x);
}

int resolve_thread_count(int requested) {
  return requested > 0 ? requested : std::max(1, omp_get_max_threads());
}

}  // namespace pkmopt
