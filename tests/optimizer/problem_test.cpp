// Tests of optimizer/problem: batch evaluation, counting, finite differences, gradient checker.
#include "optimizer/problem.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

namespace pkmopt {
namespace {

// f = (x0^2 x1, sin x1), g = x0 + x1 - 1 <= 0; `wrong` corrupts d f0 / d x1.
class SmallProblem : public Problem {
 public:
  explicit SmallProblem(bool wrong = false) : wrong_(wrong) {}
  Bounds bounds() const override { return {{-2.0, -2.0}, {2.0, 2.0}}; }
  std::size_t num_objectives() const override { return 2; }
  std::size_t num_inequality() const override { return 1; }
  std::vector<double> fitness(const std::vector<double>& x) const override {
    return {x[0] * x[0] * x[1], std::sin(x[1]), x[0] + x[1] - 1.0};
  }
  bool has_gradient() const override { return true; }
  std::vector<double> gradient(const std::vector<double>& x) const override {
    return {2 * x[0] * x[1], x[0] * x[0] + (wrong_ ? 0.01 : 0.0), 0.0, std::cos(x[1]), 1.0, 1.0};
  }
  std::string name() const override { return "small"; }

 private:
  bool wrong_;
};

TEST(GradientCheck, AcceptsCorrectGradient) {
  const GradientCheck check = check_gradient(SmallProblem(), {0.3, -0.7});
  EXPECT_TRUE(check.ok) << check.report;
  EXPECT_LT(check.max_error, 1e-7);
}

TEST(GradientCheck, FindsTheWrongEntry) {
  const GradientCheck check = check_gradient(SmallProblem(true), {0.3, -0.7});
  EXPECT_FALSE(check.ok);
  EXPECT_EQ(check.worst_row, 0u);
  EXPECT_EQ(check.worst_column, 1u);
  EXPECT_NEAR(check.max_error, 0.01, 1e-6);
  EXPECT_NE(check.report.find("DISAGREES"), std::string::npos);
}

TEST(GradientCheck, RefusesProblemWithoutGradient) {
  class NoGradient : public SmallProblem {
    bool has_gradient() const override { return false; }
  };
  EXPECT_THROW(check_gradient(NoGradient(), {0.0, 0.0}), std::logic_error);
}

TEST(FiniteDifferences, OneSidedAtBound) {
  // At x0 = 2 (upper bound) the central step would leave the box; the slope must still match.
  const std::vector<double> jacobian = finite_difference_jacobian(SmallProblem(), {2.0, 0.5});
  EXPECT_NEAR(jacobian[0 * 2 + 0], 2 * 2.0 * 0.5, 1e-5);
  EXPECT_NEAR(jacobian[1 * 2 + 1], std::cos(0.5), 1e-6);
}

TEST(Problem, BatchFitnessIsTheSameForAnyThreadCount) {
  SmallProblem problem;
  std::vector<std::vector<double>> xs;
  for (int k = 0; k < 50; ++k) xs.push_back({0.01 * k, -0.02 * k});
  const auto serial = problem.batch_fitness(xs, 1);
  const auto parallel = problem.batch_fitness(xs, 2);
  ASSERT_EQ(serial.size(), xs.size());
  EXPECT_EQ(serial, parallel);
  EXPECT_EQ(serial[7], problem.fitness(xs[7]));
}

TEST(Problem, BatchFitnessRethrows) {
  class Throwing : public SmallProblem {
    std::vector<double> fitness(const std::vector<double>& x) const override {
      if (x[0] > 0.2) throw std::runtime_error("bad design");
      return SmallProblem::fitness(x);
    }
  };
  std::vector<std::vector<double>> xs{{0.0, 0.0}, {0.5, 0.0}, {0.1, 0.0}};
  EXPECT_THROW(Throwing().batch_fitness(xs, 2), std::runtime_error);
}

// A decorator built on ForwardingProblem changes only what it overrides: everything else is the
// inner problem's, including a sparsity pattern and thread safety that differ from the defaults.
class SparseSerialProblem : public SmallProblem {
 public:
  SparsityPattern gradient_sparsity() const override { return {{0, 0}, {0, 1}, {1, 1}, {2, 0}}; }
  ThreadSafety thread_safety() const override { return ThreadSafety::none; }
  std::size_t num_equality() const override { return 0; }
};

class NegatedFirstObjective : public ForwardingProblem {
 public:
  using ForwardingProblem::ForwardingProblem;
  std::vector<double> fitness(const std::vector<double>& x) const override {
    std::vector<double> f = inner().fitness(x);
    f[0] = -f[0];
    return f;
  }
};

TEST(Problem, ForwardingProblemForwardsEverythingItDoesNotOverride) {
  const SparseSerialProblem inner;
  const NegatedFirstObjective decorated(inner);
  EXPECT_EQ(decorated.bounds().lower, inner.bounds().lower);
  EXPECT_EQ(decorated.bounds().upper, inner.bounds().upper);
  EXPECT_EQ(decorated.num_objectives(), 2u);
  EXPECT_EQ(decorated.num_inequality(), 1u);
  EXPECT_EQ(decorated.num_equality(), 0u);
  EXPECT_TRUE(decorated.has_gradient());
  EXPECT_EQ(decorated.gradient({0.5, 0.25}), inner.gradient({0.5, 0.25}));
  EXPECT_EQ(decorated.gradient_sparsity(), inner.gradient_sparsity());
  EXPECT_EQ(decorated.thread_safety(), ThreadSafety::none);
  EXPECT_EQ(decorated.name(), "small");
  EXPECT_EQ(&decorated.inner(), &inner);
  const std::vector<double> x{0.5, 0.25};
  EXPECT_EQ(decorated.fitness(x)[0], -inner.fitness(x)[0]);
  EXPECT_EQ(decorated.fitness(x)[1], inner.fitness(x)[1]);
  // Batches evaluate the decorator's own fitness, not the inner problem's batch.
  const std::vector<std::vector<double>> xs{{0.5, 0.25}, {-1.0, 1.5}, {0.0, 0.0}};
  const auto batch = decorated.batch_fitness(xs, 2);
  ASSERT_EQ(batch.size(), xs.size());
  for (std::size_t k = 0; k < xs.size(); ++k) EXPECT_EQ(batch[k], decorated.fitness(xs[k]));
}

TEST(Problem, CountingProblemCounts) {
  SmallProblem problem;
  CountingProblem counted(problem);
  counted.fitness({0.0, 0.0});
  std::vector<std::vector<double>> xs(4, std::vector<double>{0.1, 0.1});
  counted.batch_fitness(xs, 2);
  counted.gradient({0.0, 0.0});
  EXPECT_EQ(counted.fitness_evaluations(), 5);
  EXPECT_EQ(counted.gradient_evaluations(), 1);
}

TEST(Problem, ConstraintViolationAndChecks) {
  SmallProblem problem;
  const std::vector<double> f{0.0, 0.0, 0.25};
  EXPECT_DOUBLE_EQ(constraint_violation(problem, f), 0.25);
  const std::vector<double> ok{0.0, 0.0, -3.0};
  EXPECT_DOUBLE_EQ(constraint_violation(problem, ok), 0.0);
  EXPECT_NO_THROW(check_bounds(problem));
  class BadBounds : public SmallProblem {
    Bounds bounds() const override { return {{1.0, 0.0}, {0.0, 1.0}}; }
  };
  EXPECT_THROW(check_bounds(BadBounds()), std::invalid_argument);
  class WrongSize : public SmallProblem {
    std::vector<double> fitness(const std::vector<double>&) const override { return {1.0}; }
  };
  EXPECT_THROW(checked_fitness(WrongSize(), {0.0, 0.0}), std::runtime_error);
}

}  // namespace
}  // namespace pkmopt
