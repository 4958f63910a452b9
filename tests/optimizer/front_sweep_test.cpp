// Tests of optimizer/front_sweep: the driver with toy scalarisations on a problem with a known
// front.
#include "optimizer/front_sweep.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "optimizer/scalarization.hpp"

namespace pkmopt {
namespace {

// f_1 = x_1^2 + x_2^2, f_2 = (x_1 - 2)^2 + x_2^2 on [-1, 3]^2. Pareto set x_2 = 0,
// 0 <= x_1 <= 2; front f_2 = (sqrt(f_1) - 2)^2; the weighted sum w f_1 + (1 - w) f_2 is
// minimised at x_1 = 2 (1 - w).
class TwoCircles : public Problem {
 public:
  Bounds bounds() const override { return {{-1.0, -1.0}, {3.0, 3.0}}; }
  std::size_t num_objectives() const override { return 2; }
  std::vector<double> fitness(const std::vector<double>& x) const override {
    return {x[0] * x[0] + x[1] * x[1], (x[0] - 2.0) * (x[0] - 2.0) + x[1] * x[1]};
  }
  bool has_gradient() const override { return true; }
  std::vector<double> gradient(const std::vector<double>& x) const override {
    return {2.0 * x[0], 2.0 * x[1], 2.0 * (x[0] - 2.0), 2.0 * x[1]};
  }
  std::string name() const override { return "two circles"; }
};

// min w f_1 + (1 - w) f_2 (and any epsilon bounds): a toy scalarisation on ScalarizedProblem.
class WeightedSum final : public FrontSubproblem {
 public:
  WeightedSum(const Problem& counted, double w, std::vector<ObjectiveBound> bounds = {},
              bool admits_all = true)
      : w_(w), admits_all_(admits_all), sub_(counted, {w, 1.0 - w}, std::move(bounds)) {}
  const Problem& problem() const override { return sub_; }
  std::vector<double> start(const std::vector<double>& x,
                            const std::vector<double>&) const override {
    return x;
  }
  double score(const std::vector<double>& f) const override {
    return -(w_ * f[0] + (1.0 - w_) * f[1]);
  }
  bool admits(const std::vector<double>&) const override { return admits_all_; }
  std::vector<std::size_t> restart_anchors() const override { return {0, 1}; }

 private:
  double w_;
  bool admits_all_;
  ScalarizedProblem sub_;
};

FrontSweepOptions sweep_options() {
  FrontSweepOptions options;
  options.algorithm = "weighted_sum";
  return options;
}

TEST(FrontSweep, ToyScalarisationFindsTheKnownFront) {
  TwoCircles problem;
  const std::vector<double> weights{0.8, 0.6, 0.4, 0.2};
  std::size_t anchor_solves = 0;
  const FrontResult front = run_front_sweep(
      problem, sweep_options(),
      [&](const Problem& counted, const AnchorSet& anchors, const std::vector<double>&) {
        anchor_solves = anchors.solves;
        SweepPlan plan;
        for (double w : weights)
          plan.subproblems.push_back(std::make_unique<WeightedSum>(counted, w));
        plan.first_x = anchors.points[0].x;
        plan.first_f = anchors.points[0].fitness;
        return plan;
      });
  EXPECT_EQ(front.algorithm, "weighted_sum");
  EXPECT_EQ(front.message, "");  // continuation never needed a restart
  EXPECT_EQ(front.failed_subproblems, 0u);
  EXPECT_EQ(front.dominated_subproblems, 0u);
  EXPECT_EQ(front.subproblems, anchor_solves + weights.size());
  EXPECT_GT(front.fitness_evaluations, 0);
  EXPECT_GT(front.gradient_evaluations, 0);
  ASSERT_EQ(front.x.size(), 2 + weights.size());
  for (const auto& f : front.objectives())
    EXPECT_NEAR(f[1], (std::sqrt(f[0]) - 2.0) * (std::sqrt(f[0]) - 2.0), 1e-6);
  // Each weight's point: x_1 = 2 (1 - w), whatever order make_front keeps them in.
  for (double w : weights) {
    const double x1 = 2.0 * (1.0 - w);
    bool found = false;
    for (const auto& x : front.x) found = found || std::abs(x[0] - x1) < 1e-5;
    EXPECT_TRUE(found) << "no point at x_1 = " << x1;
  }
}

TEST(FrontSweep, PlannerFailureIsTheMessage) {
  TwoCircles problem;
  const FrontResult front = run_front_sweep(
      problem, sweep_options(), [](const Problem&, const AnchorSet&, const std::vector<double>&) {
        SweepPlan plan;
        plan.failure = "no simplex today";
        return plan;
      });
  EXPECT_EQ(front.message, "no simplex today");
  EXPECT_EQ(front.x.size(), 2u);  // the anchors
  EXPECT_EQ(front.failed_subproblems, 0u);
}

// f_1 <= -1 cannot hold: every start fails. Depending on the plan, repair either leaves the
// subproblem failed or makes the best known point its answer (a repeat of an anchor).
FrontResult run_infeasible(bool admits, bool keep_known) {
  TwoCircles problem;
  FrontSweepOptions options = sweep_options();
  options.ipopt.max_iterations = 100;  // Ipopt only has to give up
  return run_front_sweep(
      problem, options,
      [&](const Problem& counted, const AnchorSet& anchors, const std::vector<double>&) {
        SweepPlan plan;
        plan.subproblems.push_back(std::make_unique<WeightedSum>(
            counted, 0.5, std::vector<ObjectiveBound>{{0, -1.0, 1.0}}, admits));
        plan.first_x = anchors.points[0].x;
        plan.first_f = anchors.points[0].fitness;
        plan.keep_known_on_failed_repair = keep_known;
        return plan;
      });
}

TEST(FrontSweep, InfeasibleSubproblemIsFailed) {
  const FrontResult front = run_infeasible(false, true);
  EXPECT_EQ(front.failed_subproblems, 1u);
  EXPECT_EQ(front.dominated_subproblems, 0u);
  EXPECT_EQ(front.x.size(), 2u);
  EXPECT_EQ(front.message,
            "1 of 1 subproblems failed; 1 subproblem(s) restarted, 0 repaired from a neighbour");
}

TEST(FrontSweep, RepairKeepsTheKnownPointOrLeavesTheFailure) {
  const FrontResult kept = run_infeasible(true, true);
  EXPECT_EQ(kept.failed_subproblems, 0u);
  EXPECT_EQ(kept.dominated_subproblems, 1u);  // the known point repeats an anchor
  EXPECT_EQ(kept.x.size(), 2u);
  EXPECT_EQ(kept.message, "1 subproblem(s) restarted, 1 repaired from a neighbour");

  const FrontResult left = run_infeasible(true, false);
  EXPECT_EQ(left.failed_subproblems, 1u);
  EXPECT_EQ(left.dominated_subproblems, 0u);
  EXPECT_EQ(left.message,
            "1 of 1 subproblems failed; 1 subproblem(s) restarted, 1 repaired from a neighbour");
}

TEST(FrontSweep, ExplainUnsupported) {
  TwoCircles problem;
  EXPECT_FALSE(front_problem_explain_unsupported(problem, "toy"));
  EXPECT_FALSE(front_start_explain_unsupported(problem, "toy", {}));
  EXPECT_EQ(front_start_explain_unsupported(problem, "toy", {1.0}).value_or(""),
            "toy: start has 1 values, the problem has 2 variables");
  class OneObjective : public TwoCircles {
    std::size_t num_objectives() const override { return 1; }
    std::vector<double> fitness(const std::vector<double>& x) const override {
      return {TwoCircles::fitness(x)[0]};
    }
  };
  EXPECT_EQ(front_problem_explain_unsupported(OneObjective(), "toy").value_or(""),
            "toy builds fronts, but the problem named 'two circles' has one objective (use ipopt)");
}

}  // namespace
}  // namespace pkmopt
