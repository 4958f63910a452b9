#include "optimizer/epsilon_constraint.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <stdexcept>
#include <utility>
#include <vector>

#include "optimizer/anchors.hpp"
#include "optimizer/front_sweep.hpp"
#include "optimizer/scalarization.hpp"

namespace pkmopt {
namespace {

// min f_p / s_p subject to the epsilon bounds: ScalarizedProblem on the counted problem.
class EpsilonSubproblem final : public FrontSubproblem {
 public:
  EpsilonSubproblem(const Problem& counted, const std::vector<double>& weights,
                    std::vector<ObjectiveBound> bounds, std::size_t primary,
                    std::vector<std::size_t> restart_anchors)
      : sub_(counted, weights, bounds),
        bounds_(std::move(bounds)),
        primary_(primary),
        restart_anchors_(std::move(restart_anchors)) {}
  const Problem& problem() const override { return sub_; }
  std::vector<double> start(const std::vector<double>& x,
                            const std::vector<double>& /*fx*/) const override {
    return x;
  }
  /// -f_p: a lower primary objective is better.
  double score(const std::vector<double>& f) const override { return -f[primary_]; }
  /// A known point answers this subproblem when it satisfies the epsilon bounds.
  bool admits(const std::vector<double>& f) const override {
    bool satisfies = true;
    for (const ObjectiveBound& b : bounds_)
      satisfies = satisfies && f[b.objective] <= b.epsilon + 1e-8 * b.scale;
    return satisfies;
  }
  std::vector<std::size_t> restart_anchors() const override { return restart_anchors_; }

 private:
  ScalarizedProblem sub_;
  std::vector<ObjectiveBound> bounds_;
  std::size_t primary_;
  std::vector<std::size_t> restart_anchors_;
};

// The epsilon grid over the other objectives, walked in serpentine order.
SweepPlan plan_epsilon_constraint(const Problem& counted, const AnchorSet& anchors,
                                  const std::vector<double>& start,
                                  const EpsilonConstraintOptions& options) {
  SweepPlan plan;
  if (anchors.range.empty()) {
    plan.failure = "every anchor solve failed: " + anchors.points.front().summary;
    return plan;
  }
  const std::size_t m = counted.num_objectives();
  const std::size_t p = options.primary_objective;
  // The other objectives and their epsilon values.
  std::vector<std::size_t> others;
  for (std::size_t j = 0; j < m; ++j)
    if (j != p) others.push_back(j);
  std::vector<double> fractions;
  double grid_step;  // between neighbouring levels, as a fraction of the objective ranges
  if (m == 2) {
    const std::size_t per_axis = options.points - 2;
    for (std::size_t k = per_axis; k >= 1; --k)  // from the primary anchor's side
      fractions.push_back(static_cast<double>(k) / static_cast<double>(per_axis + 1));
    grid_step = 1.0 / static_cast<double>(per_axis + 1);
  } else {
    const std::size_t per_axis = std::max<std::size_t>(
        2, static_cast<std::size_t>(std::floor(
               std::pow(static_cast<double>(options.points), 1.0 / static_cast<double>(m - 1)) +
               1e-9)));
    for (std::size_t k = per_axis; k >= 1; --k)
      fractions.push_back(static_cast<double>(k) / static_cast<double>(per_axis));
    grid_step = 1.0 / static_cast<double>(per_axis);
  }
  // Fallback starts besides the driver's own: the primary anchor, then the anchors of the other
  // objectives (each satisfies its own epsilon bound whatever its value, so narrow feasible
  // sets stay reachable).
  std::vector<std::size_t> restart;
  if (anchors.points[p].ok) restart.push_back(p);
  for (std::size_t j = 0; j < m; ++j)
    if (j != p && anchors.points[j].ok) restart.push_back(j);
  std::vector<double> weights(m, 0.0);
  weights[p] = 1.0 / anchors.range[p];
  // Serpentine walk over the grid: axis 0 runs fastest and reverses direction each time a
  // slower axis moves, so consecutive subproblems are neighbours.
  const std::size_t total =
      fractions.empty()
          ? 0
          : static_cast<std::size_t>(std::llround(std::pow(static_cast<double>(fractions.size()),
                                                           static_cast<double>(others.size()))));
  for (std::size_t step = 0; step < total; ++step) {
    std::vector<ObjectiveBound> bounds;
    std::size_t stride = 1;
    for (std::size_t a = 0; a < others.size(); ++a) {
      const std::size_t level = (step / stride) % fractions.size();
      const bool reversed = ((step / (stride * fractions.size())) % 2) == 1;
      const std::size_t k = reversed ? fractions.size() - 1 - level : level;
      stride *= fractions.size();
      const std::size_t j = others[a];
      bounds.push_back({j, anchors.ideal[j] + fractions[k] * anchors.range[j], anchors.range[j]});
    }
    plan.subproblems.push_back(
        std::make_unique<EpsilonSubproblem>(counted, weights, std::move(bounds), p, restart));
  }
  plan.first_x = anchors.points[p].ok ? anchors.points[p].x : start;
  plan.first_f = anchors.points[p].ok ? anchors.points[p].fitness : std::vector<double>{};
  plan.jump_step = grid_step;  // jumped: farther than 3 grid steps
  plan.jump_max_steps = 3.0;
  // Repair: a known point beats a result when it satisfies the epsilon bounds with a primary
  // objective lower by more than 1e-5 of its range; a failed re-solve leaves the known point.
  plan.repair_margin = 1e-5 * anchors.range[p];
  plan.keep_known_on_failed_repair = true;
  return plan;
}

}  // namespace

std::optional<std::string> EpsilonConstraintOptions::validate() const {
  if (points < 2)
    return fmt::format("EpsilonConstraintOptions::points = {}. Violated constraint: points >= 2",
                       points);
  if (!start.empty())
    for (double v : start)
      if (!std::isfinite(v))
        return std::string("EpsilonConstraintOptions::start has a non-finite value");
  return ipopt.validate();
}

std::optional<std::string> epsilon_constraint_explain_unsupported(
    const Problem& problem, const EpsilonConstraintOptions& options) {
  if (auto reason = front_problem_explain_unsupported(problem, "epsilon_constraint")) return reason;
  if (options.primary_objective >= problem.num_objectives())
    return fmt::format("epsilon_constraint: primary objective {} out of range (the problem has {})",
                       options.primary_objective + 1, problem.num_objectives());
  return front_start_explain_unsupported(problem, "epsilon_constraint", options.start);
}

FrontResult run_epsilon_constraint(const Problem& problem,
                                   const EpsilonConstraintOptions& options) {
  if (auto error = options.validate()) throw std::invalid_argument(*error);
  if (auto reason = epsilon_constraint_explain_unsupported(problem, options))
    throw std::invalid_argument(*reason);
  FrontSweepOptions sweep;
  sweep.algorithm = "epsilon_constraint";
  sweep.ipopt = options.ipopt;
  sweep.start = options.start;
  sweep.global_starts = options.global_starts;
  sweep.seed = options.seed;
  return run_front_sweep(
      problem, sweep,
      [&](const Problem& counted, const AnchorSet& anchors, const std::vector<double>& start) {
        return plan_epsilon_constraint(counted, anchors, start, options);
      });
}

}  // namespace pkmopt
