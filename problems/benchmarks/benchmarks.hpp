// Standard test problems for the optimizer, with their analytic Pareto fronts.
//
// Multi-objective (all minimised, dimensionless):
// - ZDT1, ZDT2, ZDT3, ZDT4, ZDT6 (Zitzler, Deb & Thiele 2000): f_1 = f_1(x_1), f_2 = g(x_2..n)
// h(f_1, g).
//   Fronts (g = 1): ZDT1/ZDT4 f_2 = 1 - sqrt(f_1); ZDT2 f_2 = 1 - f_1^2; ZDT3 the non-dominated
//   parts of f_2 = 1 - sqrt(f_1) - f_1 sin(10 pi f_1) (disconnected); ZDT6 f_2 = 1 - f_1^2 with
//   f_1 in [0.2807753191, 1]. Default n: 30 (ZDT1-3), 10 (ZDT4, ZDT6). Exact gradients.
// - DTLZ1, DTLZ2, DTLZ3, DTLZ4, DTLZ7 (Deb, Thiele, Laumanns & Zitzler 2005) for any number of
//   objectives m >= 2, n = m + k - 1 variables (default k = 5 for DTLZ1, 10 for DTLZ2-4, 20 for
//   DTLZ7). Fronts: DTLZ1 the simplex sum f_i = 0.5; DTLZ2-4 the unit sphere sum f_i^2 = 1 in the
//   positive orthant; DTLZ7 disconnected, f_m = 2 (m - sum_{i<m} f_i/2 (1 + sin(3 pi f_i))).
// - Constrained, two objectives: BNH (Binh & Korn 1997), SRN (Srinivas & Deb 1994), TNK
//   (Tanaka 1995), OSY (Osyczka & Kundu 1995), as stated in Deb, "Multi-objective optimization
//   using evolutionary algorithms" (2001), with exact gradients.
// Single objective (for the gradient solvers): HS71 (Hock & Schittkowski 1981, problem 71:
// min x1 x4 (x1 + x2 + x3) + x3, x1 x2 x3 x4 >= 25, sum x_i^2 = 40, 1 <= x <= 5; optimum
// f* = 17.0140173 at (1, 4.7429994, 3.8211503, 1.3794082)) and Rosenbrock (n variables in
// [-5, 10], f = sum 100 (x_{i+1} - x_i^2)^2 + (1 - x_i)^2, optimum 0 at x = 1).
//
// Example:
//   auto zdt1 = pkmopt::make_benchmark("zdt1", 30);       // 30 variables
//   auto front = zdt1->reference_front(200);              // 200 points on the true front
//   auto dtlz2 = pkmopt::make_benchmark("dtlz2", 0, 4);   // default variables, 4 objectives
#pragma once

#include <cstddef>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "optimizer/indicators.hpp"
#include "optimizer/problem.hpp"

namespace pkmopt {

/// A benchmark problem that may know its Pareto front.
class BenchmarkProblem : public Problem {
 public:
  /// About `n_points` objective vectors on the exact Pareto front (non-dominated, sorted);
  /// empty if no analytic front is known (single-objective problems).
  virtual ObjectiveSet reference_front(std::size_t n_points) const = 0;
  /// The known optimum of a single-objective problem (x*, f*), empty otherwise.
  virtual std::vector<double> known_optimum_x() const { return {}; }
};

/// ZDT1..ZDT6 (kind 1, 2, 3, 4 or 6), `variables` >= 2.
class Zdt : public BenchmarkProblem {
 public:
  Zdt(int kind, std::size_t variables);
  Bounds bounds() const override;
  std::size_t num_objectives() const override { return 2; }
  std::vector<double> fitness(const std::vector<double>& x) const override;
  bool has_gradient() const override { return true; }
  std::vector<double> gradient(const std::vector<double>& x) const override;
  SparsityPattern gradient_sparsity() const override;
  std::string name() const override { return "zdt" + std::to_string(kind_); }
  ObjectiveSet reference_front(std::size_t n_points) const override;

 private:
  int kind_;
  std::size_t variables_;
};

/// DTLZ1..DTLZ4, DTLZ7 (kind 1, 2, 3, 4 or 7), `objectives` >= 2, `variables` >= objectives.
class Dtlz : public BenchmarkProblem {
 public:
  Dtlz(int kind, std::size_t objectives, std::size_t variables);
  Bounds bounds() const override;
  std::size_t num_objectives() const override { return objectives_; }
  std::vector<double> fitness(const std::vector<double>& x) const override;
  std::string name() const override { return "dtlz" + std::to_string(kind_); }
  ObjectiveSet reference_front(std::size_t n_points) const override;

 private:
  int kind_;
  std::size_t objectives_;
  std::size_t variables_;
};

/// BNH: x1 in [0, 5], x2 in [0, 3]; f = (4x1^2 + 4x2^2, (x1-5)^2 + (x2-5)^2);
/// g1 = (x1-5)^2 + x2^2 - 25 <= 0, g2 = 7.7 - (x1-8)^2 - (x2+3)^2 <= 0.
class Bnh : public BenchmarkProblem {
 public:
  Bounds bounds() const override { return {{0.0, 0.0}, {5.0, 3.0}}; }
  std::size_t num_objectives() const override { return 2; }
  std::size_t num_inequality() const override { return 2; }
  std::vector<double> fitness(const std::vector<double>& x) const override;
  bool has_gradient() const override { return true; }
  std::vector<double> gradient(const std::vector<double>& x) const override;
  std::string name() const override { return "bnh"; }
  ObjectiveSet reference_front(std::size_t n_points) const override;
};

/// SRN: x in [-20, 20]^2; f = (2 + (x1-2)^2 + (x2-1)^2, 9x1 - (x2-1)^2);
/// g1 = x1^2 + x2^2 - 225 <= 0, g2 = x1 - 3x2 + 10 <= 0.
class Srn : public BenchmarkProblem {
 public:
  Bounds bounds() const override { return {{-20.0, -20.0}, {20.0, 20.0}}; }
  std::size_t num_objectives() const override { return 2; }
  std::size_t num_inequality() const override { return 2; }
  std::vector<double> fitness(const std::vector<double>& x) const override;
  bool has_gradient() const override { return true; }
  std::vector<double> gradient(const std::vector<double>& x) const override;
  std::string name() const override { return "srn"; }
  ObjectiveSet reference_front(std::size_t n_points) const override;
};

/// TNK: x1 in [0, pi], x2 in [1e-12, pi]; f = (x1, x2);
/// g1 = 1 + 0.1 cos(16 atan(x1/x2)) - x1^2 - x2^2 <= 0, g2 = (x1-0.5)^2 + (x2-0.5)^2 - 0.5 <= 0.
class Tnk : public BenchmarkProblem {
 public:
  Bounds bounds() const override;
  std::size_t num_objectives() const override { return 2; }
  std::size_t num_inequality() const override { return 2; }
  std::vector<double> fitness(const std::vector<double>& x) const override;
  bool has_gradient() const override { return true; }
  std::vector<double> gradient(const std::vector<double>& x) const override;
  std::string name() const override { return "tnk"; }
  ObjectiveSet reference_front(std::size_t n_points) const override;
};

/// OSY: six variables, x1,x2,x6 in [0,10], x3,x5 in [1,5], x4 in [0,6];
/// f1 = -(25(x1-2)^2 + (x2-2)^2 + (x3-1)^2 + (x4-4)^2 + (x5-1)^2), f2 = sum x_i^2;
/// six linear/quadratic inequality constraints (Deb 2001, eq. 14.9).
class Osy : public BenchmarkProblem {
 public:
  Bounds bounds() const override;
  std::size_t num_objectives() const override { return 2; }
  std::size_t num_inequality() const override { return 6; }
  std::vector<double> fitness(const std::vector<double>& x) const override;
  bool has_gradient() const override { return true; }
  std::vector<double> gradient(const std::vector<double>& x) const override;
  std::string name() const override { return "osy"; }
  ObjectiveSet reference_front(std::size_t n_points) const override;
};

/// Hock–Schittkowski 71; fitness = [f, sum x^2 - 40, 25 - x1 x2 x3 x4].
class Hs71 : public BenchmarkProblem {
 public:
  Bounds bounds() const override { return {{1, 1, 1, 1}, {5, 5, 5, 5}}; }
  std::size_t num_equality() const override { return 1; }
  std::size_t num_inequality() const override { return 1; }
  std::vector<double> fitness(const std::vector<double>& x) const override;
  bool has_gradient() const override { return true; }
  std::vector<double> gradient(const std::vector<double>& x) const override;
  std::string name() const override { return "hs71"; }
  ObjectiveSet reference_front(std::size_t) const override { return {{17.0140173}}; }
  std::vector<double> known_optimum_x() const override {
    return {1.0, 4.7429994, 3.8211503, 1.3794082};
  }
};

/// Rosenbrock in n >= 2 variables.
class Rosenbrock : public BenchmarkProblem {
 public:
  explicit Rosenbrock(std::size_t variables);
  Bounds bounds() const override;
  std::vector<double> fitness(const std::vector<double>& x) const override;
  bool has_gradient() const override { return true; }
  std::vector<double> gradient(const std::vector<double>& x) const override;
  std::string name() const override { return "rosenbrock"; }
  ObjectiveSet reference_front(std::size_t) const override { return {{0.0}}; }
  std::vector<double> known_optimum_x() const override {
    return std::vector<double>(variables_, 1.0);
  }

 private:
  std::size_t variables_;
};

/// The benchmark names make_benchmark accepts.
std::vector<std::string> benchmark_names();

/// The largest benchmark make_benchmark builds (study files, the command line and Python alike):
/// more would only exhaust memory or time.
inline constexpr std::size_t kMaxBenchmarkVariables = 10000;
inline constexpr std::size_t kMaxBenchmarkObjectives = 50;

/// Builds a benchmark by name (lower case, see benchmark_names()). `variables` = 0 and
/// `objectives` = 0 take the defaults; `objectives` only applies to DTLZ. Throws
/// std::invalid_argument with the reason for an unknown name or impossible sizes (more than
/// kMaxBenchmarkVariables variables or kMaxBenchmarkObjectives objectives included).
std::unique_ptr<BenchmarkProblem> make_benchmark(std::string_view name, std::size_t variables = 0,
                                                 std::size_t objectives = 0);

}  // namespace pkmopt
