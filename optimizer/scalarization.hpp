// Single-objective problems built from a multi-objective one, solved by Ipopt to build fronts.
//
// ScalarizedProblem (epsilon-constraint, lexicographic anchor refinement, hybrid polish):
//   min  sum_i w_i f_i(x)
//   s.t. h(x) = 0, g(x) <= 0 (the base problem's constraints)
//        (f_j(x) - epsilon_j) / scale_j <= 0   for each bound (j, epsilon_j, scale_j)
//
// NbiProblem (Normal Boundary Intersection, Das & Dennis 1998), variables (x, t):
//   normalised objectives  F^_i(x) = (f_i(x) - ideal_i) / range_i
//   max t  s.t.  F^(x) - c - t n = 0   (equality form, Das & Dennis)
//          or    F^(x) - c - t n <= 0  (relaxed form, default: never stops at a point that a
//                                       move along -n would improve; gaps give weakly
//                                       dominated points, which the builder discards)
//   with c = Phi^T beta a point of the convex hull of individual minima (CHIM), Phi the
//   normalised pay-off matrix (row i = F^(anchor_i)), beta on the unit simplex and
//   n = -Phi^T 1 / |Phi^T 1| the quasi-normal pointing towards the ideal point.
//
// Both forward the base problem's gradient (chain rule, dense pattern) when it has one, so
// Ipopt uses exact derivatives; otherwise Ipopt differentiates them numerically.
//
// Example:
//   // min f_1 s.t. f_2 <= 0.5 on ZDT1 (scale 1)
//   pkmopt::ScalarizedProblem sub(zdt1, {1.0, 0.0}, {{1, 0.5, 1.0}});
//   pkmopt::SolveResult r = pkmopt::solve_with_ipopt(sub, x0);
#pragma once

#include <cstddef>
#include <vector>

#include "optimizer/problem.hpp"

namespace pkmopt {

struct ObjectiveBound {
  std::size_t objective;  ///< j, 0-based
  double epsilon;         ///< f_j <= epsilon
  double scale;           ///< > 0, divides the constraint for conditioning
};

class ScalarizedProblem : public Problem {
 public:
  /// `weights` has one entry per objective of `base`; `base` must outlive this problem.
  ScalarizedProblem(const Problem& base, std::vector<double> weights,
                    std::vector<ObjectiveBound> objective_bounds);
  Bounds bounds() const override { return base_.bounds(); }
  std::size_t num_objectives() const override { return 1; }
  std::size_t num_equality() const override { return base_.num_equality(); }
  std::size_t num_inequality() const override {
    return base_.num_inequality() + objective_bounds_.size();
  }
  std::vector<double> fitness(const std::vector<double>& x) const override;
  bool has_gradient() const override { return base_.has_gradient(); }
  std::vector<double> gradient(const std::vector<double>& x) const override;
  std::string name() const override { return base_.name() + " (scalarised)"; }
  ThreadSafety thread_safety() const override { return base_.thread_safety(); }

 private:
  std::vector<double> scalarise(const std::vector<double>& base_rows, std::size_t columns) const;
  const Problem& base_;
  std::vector<double> weights_;
  std::vector<ObjectiveBound> objective_bounds_;
};

class NbiProblem : public Problem {
 public:
  /// `ideal` and `range` normalise the objectives; `chim_point` = c, `normal` = n (size m).
  NbiProblem(const Problem& base, std::vector<double> ideal, std::vector<double> range,
             std::vector<double> chim_point, std::vector<double> normal, bool equality_form);
  Bounds bounds() const override;  ///< the base bounds, then t unbounded
  std::size_t num_objectives() const override { return 1; }
  std::size_t num_equality() const override;
  std::size_t num_inequality() const override;
  /// [-t | base eq | (NBI rows if equality form) | base ineq | (NBI rows if relaxed)]
  std::vector<double> fitness(const std::vector<double>& xt) const override;
  bool has_gradient() const override { return base_.has_gradient(); }
  std::vector<double> gradient(const std::vector<double>& xt) const override;
  std::string name() const override { return base_.name() + " (NBI)"; }
  ThreadSafety thread_safety() const override { return base_.thread_safety(); }

  /// The largest t for which x satisfies the relaxed constraints (a feasible start for t).
  double feasible_t(const std::vector<double>& base_fitness) const;

 private:
  const Problem& base_;
  std::vector<double> ideal_, range_, chim_point_, normal_;
  bool equality_form_;
};

}  // namespace pkmopt
