// Tests of the smooth formulation of problems/design/hexapod_design (the epigraph rows Ipopt and
// NLopt solve): gradients against finite differences, agreement of the rows with the aggregate
// metrics, the principal-minor stiffness rows and a 1-parameter Ipopt optimum equal to the
// aggregate stiffness, the actuator-overload rows, and the metrics it refuses.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "optimizer/ipopt_solver.hpp"
#include "problems/design/hexapod_design.hpp"
#include "tests/problems/design/hexapod_design_specs.hpp"
#include "tests/sample_catalogs.hpp"
#include "tests/sample_machines.hpp"

namespace pkmopt {
namespace {
TEST(HexapodDesign, SmoothFormulationGradientsMatchFiniteDifferences) {
  const HexapodDesignProblem problem(test_specs::smooth_spec());
  ASSERT_TRUE(problem.has_gradient());
  ASSERT_EQ(problem.num_variables(), 8u);  // 7 parameters + 1 epigraph variable
  const std::size_t poses = problem.spec().task.poses.size();
  EXPECT_EQ(problem.num_inequality(), 12 * poses + 12 * poses + 1 + 24 * poses);
  const std::vector<std::vector<double>> points = {
      {0.6, 0.25, deg_to_rad(20), deg_to_rad(20), 0.7, 0.45, 0.0, 2.0},  // t in kN
      {0.55, 0.28, deg_to_rad(32), deg_to_rad(14), 0.75, 0.35, 0.06, 3.5}};
  for (const std::vector<double>& x : points) {
    const GradientCheck check = check_gradient(problem, x);
    EXPECT_TRUE(check.ok) << check.report;
    for (double v : problem.fitness(x)) EXPECT_TRUE(std::isfinite(v));
  }
}

TEST(HexapodDesign, SmoothRowsAgreeWithTheAggregateMetrics) {
  HexapodDesignSpec spec = test_specs::smooth_spec();
  const HexapodDesignProblem smooth(spec);
  spec.formulation = DesignFormulation::aggregate;
  const HexapodDesignProblem aggregate(spec);
  const std::vector<double> design{0.6, 0.25, deg_to_rad(20), deg_to_rad(20), 0.7, 0.45, 0.0};
  const DesignEvaluation ev = aggregate.evaluate(design);
  ASSERT_TRUE(ev.ok()) << ev.failure;
  const double force = ev.metrics[static_cast<int>(DesignMetric::leg_force_max)];
  // With t = the worst leg force (kN) the largest epigraph row is exactly 0.
  std::vector<double> x = design;
  x.push_back(force / kEpigraphForceUnit);
  const std::vector<double> f = smooth.fitness(x);
  const std::size_t rows = 12 * spec.task.poses.size();
  const double worst = *std::max_element(f.begin() + 2, f.begin() + 2 + rows);
  EXPECT_NEAR(worst, kSmoothRowMargin, 1e-12 * force);
  EXPECT_NEAR(f[0], force, 1e-12 * force);
  EXPECT_DOUBLE_EQ(f[1], -ev.metrics[static_cast<int>(DesignMetric::machine_size)]);
  // The reachability rows' maximum is the aggregate g_reach.
  EXPECT_NEAR(*std::max_element(f.end() - 24 * spec.task.poses.size(), f.end()),
              ev.reach_violation + kSmoothRowMargin, 1e-15);
}

// Smooth stiffness_min: a maximised objective (epigraph variable s in N/um) and a >= constraint.
HexapodDesignSpec smooth_stiffness_spec() {
  HexapodDesignSpec spec = test_specs::smooth_spec();
  spec.objectives = {{DesignMetric::stiffness_min, Sense::maximize},
                     {DesignMetric::leg_force_max, Sense::minimize}};
  spec.constraints = {{DesignMetric::stiffness_min, Relation::greater_equal, 4.0e6},
                      {DesignMetric::machine_size, Relation::less_equal, 2.0}};
  return spec;
}

double aggregate_stiffness(const HexapodDesignProblem& aggregate, const std::vector<double>& x) {
  const DesignEvaluation ev = aggregate.evaluate(x);
  return ev.ok() ? ev.metrics[static_cast<int>(DesignMetric::stiffness_min)] : -1.0;
}

// Random designs inside the bounds that the aggregate metrics accept (not singular).
std::vector<std::vector<double>> random_designs(const HexapodDesignProblem& aggregate, int count,
                                                std::uint64_t seed) {
  sample_machines::Uniform u(seed);
  const Bounds b = aggregate.bounds();
  std::vector<std::vector<double>> designs;
  while (static_cast<int>(designs.size()) < count) {
    std::vector<double> x;
    for (std::size_t j = 0; j < b.lower.size(); ++j) x.push_back(u(b.lower[j], b.upper[j]));
    if (aggregate_stiffness(aggregate, x) > 0.0) designs.push_back(x);
  }
  return designs;
}

TEST(HexapodDesign, SmoothStiffnessRowsHaveFiniteDifferenceGradients) {
  HexapodDesignSpec spec = smooth_stiffness_spec();
  const HexapodDesignProblem smooth(spec);
  spec.formulation = DesignFormulation::aggregate;
  const HexapodDesignProblem aggregate(spec);
  const std::size_t poses = spec.task.poses.size();
  ASSERT_EQ(smooth.num_variables(), 9u);  // 7 parameters, s (N/um), t (kN)
  EXPECT_EQ(smooth.num_inequality(), 7 * poses + 12 * poses + 7 * poses + 1 + 24 * poses);
  EXPECT_EQ(smooth.bounds().lower[7], 0.0);
  // The upper bound of s is above any stiffness: 6 k(q) at the shortest leg, in N/um.
  EXPECT_GT(smooth.bounds().upper[7],
            1e-6 * aggregate_stiffness(aggregate, {0.6, 0.25, 0.35, 0.35, 0.7, 0.45, 0}));
  for (const std::vector<double>& design : random_designs(aggregate, 4, 17)) {
    const double stiffness = aggregate_stiffness(aggregate, design);
    std::vector<double> x = design;
    x.push_back(0.9 * stiffness / kEpigraphStiffnessUnit);  // feasible epigraph values
    x.push_back(3.0);
    const GradientCheck check = check_gradient(smooth, x);
    EXPECT_TRUE(check.ok) << check.report;
    for (double v : smooth.fitness(x)) EXPECT_TRUE(std::isfinite(v));
  }
}

// stiffness_min >= b  <=>  every minor row of I - b C_tt is <= 0, on random designs and bounds;
// at b = stiffness_min the largest row is 0 (the constraint is active).
TEST(HexapodDesign, SmoothStiffnessRowsAgreeWithTheAggregateMetric) {
  HexapodDesignSpec spec = smooth_stiffness_spec();
  spec.objectives = {{DesignMetric::machine_size, Sense::minimize}};
  spec.require_reachable = false;
  HexapodDesignSpec aggregate_spec = spec;
  aggregate_spec.formulation = DesignFormulation::aggregate;
  const HexapodDesignProblem aggregate(aggregate_spec);
  sample_machines::Uniform u(5);
  int feasible = 0, infeasible = 0;
  for (const std::vector<double>& x : random_designs(aggregate, 12, 23)) {
    const double stiffness = aggregate_stiffness(aggregate, x);
    for (const double factor : {0.5, 0.97, 0.999, 1.001, 1.03, 2.0, u(0.6, 1.4)}) {
      spec.constraints = {
          {DesignMetric::stiffness_min, Relation::greater_equal, factor * stiffness}};
      const std::vector<double> f = HexapodDesignProblem(spec).fitness(x);
      const double worst = *std::max_element(f.begin() + 1, f.end());
      EXPECT_EQ(worst - kSmoothRowMargin <= 0.0, factor <= 1.0) << "factor " << factor;
      EXPECT_EQ(worst <= 0.0, factor <= 1.0) << "factor " << factor;  // margin << 0.1 %
      (worst <= 0.0 ? feasible : infeasible)++;
    }
    spec.constraints = {{DesignMetric::stiffness_min, Relation::greater_equal, stiffness}};
    const std::vector<double> f = HexapodDesignProblem(spec).fitness(x);
    EXPECT_NEAR(*std::max_element(f.begin() + 1, f.end()), kSmoothRowMargin, 1e-9);
  }
  EXPECT_GT(feasible, 30);
  EXPECT_GT(infeasible, 30);
}

// One free parameter, maximise stiffness_min by Ipopt: at the optimum the epigraph variable
// equals the aggregate stiffness_min (its constraint rows are active), and no design on a fine
// grid of the parameter is stiffer.
// One free parameter (home_height), maximise stiffness_min by Ipopt with the task reachable:
// the machine gets stiffer the lower the task sits, until the legs reach min_length. At the
// optimum the epigraph variable equals the aggregate stiffness_min (its rows are active), and no
// reachable design on a fine grid of the parameter is stiffer.
TEST(HexapodDesign, SmoothStiffnessOptimumIsTheAggregateStiffness) {
  HexapodDesignSpec spec;
  spec.formulation = DesignFormulation::smooth;
  spec.task.poses =
      box_task_poses({0, 0, 0.9}, {0.05, 0.05, 0.05}, {2, 1, 2}, deg_to_rad(10), 0, deg_to_rad(10));
  spec.parameters[kHomeHeight] = {-0.4, 0.1};
  spec.objectives = {{DesignMetric::stiffness_min, Sense::maximize}};
  const HexapodDesignProblem smooth(spec);
  spec.formulation = DesignFormulation::aggregate;
  const HexapodDesignProblem aggregate(spec);
  const SolveResult result = solve_with_ipopt(smooth, {-0.1, 1.0});
  ASSERT_TRUE(result.usable()) << result.summary();
  const double stiffness = aggregate_stiffness(aggregate, {result.x[0]});
  EXPECT_NEAR(result.x[1] * kEpigraphStiffnessUnit, stiffness, 1e-5 * stiffness);
  EXPECT_LT(result.x[1] * kEpigraphStiffnessUnit, stiffness);  // the margin keeps it below
  EXPECT_NEAR(-result.objective, result.x[1] * kEpigraphStiffnessUnit, 1e-9 * stiffness);
  const std::size_t stiffness_rows = kStiffnessRowsPerPose * spec.task.poses.size();
  const std::vector<double> f = smooth.fitness(result.x);
  EXPECT_NEAR(*std::max_element(f.begin() + 1, f.begin() + 1 + stiffness_rows), 0.0, 1e-7);
  EXPECT_TRUE(aggregate.evaluate({result.x[0]}).reachable);  // feasible in the strict check
  EXPECT_GT(result.x[0], -0.4 + 1e-3);  // an interior optimum: reachability limits it
  int reachable = 0;
  for (int k = 0; k <= 50; ++k) {
    const double h = -0.4 + 0.5 * k / 50.0;
    if (!aggregate.evaluate({h}).reachable) continue;
    ++reachable;
    EXPECT_LE(aggregate_stiffness(aggregate, {h}), stiffness * (1.0 + 1e-6)) << "h " << h;
  }
  EXPECT_GT(reachable, 5);
}

TEST(HexapodDesign, SmoothFormulationRefusesNonSmoothMetricsAndAggregateHasNoGradient) {
  HexapodDesignSpec spec = test_specs::smooth_spec();
  spec.objectives[1] = {DesignMetric::stiffness_min, Sense::minimize};
  EXPECT_THROW(HexapodDesignProblem{spec}, std::invalid_argument);
  spec.objectives[1] = {DesignMetric::singularity_margin, Sense::maximize};
  EXPECT_THROW(HexapodDesignProblem{spec}, std::invalid_argument);
  spec.objectives = {{DesignMetric::stiffness_min, Sense::maximize},
                     {DesignMetric::stiffness_min, Sense::maximize}};
  EXPECT_THROW(HexapodDesignProblem{spec}, std::invalid_argument);  // one epigraph per metric
  spec = test_specs::smooth_spec();
  spec.constraints.push_back({DesignMetric::singularity_margin, Relation::greater_equal, 0.1});
  EXPECT_THROW(HexapodDesignProblem{spec}, std::invalid_argument);
  spec = test_specs::smooth_spec();
  spec.formulation = DesignFormulation::aggregate;
  const HexapodDesignProblem aggregate(spec);
  EXPECT_FALSE(aggregate.has_gradient());
  EXPECT_THROW(aggregate.gradient(std::vector<double>(7, 0.5)), std::logic_error);
  spec.parameters[kStroke] = {0.6, 0.3};
  EXPECT_THROW(HexapodDesignProblem{spec}, std::invalid_argument);
  spec = test_specs::smooth_spec();
  spec.objectives.clear();
  EXPECT_THROW(HexapodDesignProblem{spec}, std::invalid_argument);
  // a_max: the inertia forces have no smooth rows.
  spec = test_specs::smooth_spec();
  sample_machines::Uniform u(5);
  spec.machine_template.masses = sample_machines::random_hexapod_masses(u);
  spec.task.acceleration_max = 9.81;
  try {
    HexapodDesignProblem{spec};
    ADD_FAILURE() << "a_max accepted by the smooth formulation";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("task a_max has no smooth formulation"), std::string::npos)
        << e.what();
  }
}

// The optimiser chooses the cheapest catalog entry: actuator_cost, actuator_overload and the
// chosen entry follow from leg_force_max and the stroke exactly as the catalog functions say.
// With a fixed stroke the catalog's capacity F is a constant, and the smooth formulation's
// actuator_overload <= b rows are the leg_force_max <= b + F rows.
TEST(HexapodDesign, SmoothActuatorOverloadRowsAreForceRowsAtTheCapacity) {
  HexapodDesignSpec spec = test_specs::smooth_spec();
  spec.parameters[kStroke] = {0.2, 0.2};
  spec.actuator_catalog = sample_catalogs::sew_cms();
  spec.constraints = {{DesignMetric::actuator_overload, Relation::less_equal, -500.0}};
  const HexapodDesignProblem overload(spec);
  spec.constraints = {{DesignMetric::leg_force_max, Relation::less_equal, 20000.0 - 500.0}};
  spec.actuator_catalog.reset();
  const HexapodDesignProblem force(spec);
  ASSERT_EQ(overload.num_inequality(), force.num_inequality());
  const std::vector<double> x{0.6, 0.25, deg_to_rad(20), deg_to_rad(20), 0.7, 0.0, 2.0};
  EXPECT_EQ(overload.fitness(x), force.fitness(x));
  EXPECT_EQ(overload.gradient(x), force.gradient(x));
  const GradientCheck check = check_gradient(overload, x);
  EXPECT_TRUE(check.ok) << check.report;
}

}  // namespace
}  // namespace pkmopt
