// Tests of problems/hexapod_design: a hand-computed design evaluation, sign conventions,
// failures without NaN, agreement with the model, gradients against finite differences, and the
// smooth stiffness_min (principal-minor rows): gradients, agreement with the aggregate metric,
// and a 1-parameter Ipopt optimum equal to the aggregate stiffness.
#include "problems/hexapod_design.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <numbers>
#include <set>
#include <stdexcept>
#include <string>

#include "optimizer/ipopt_solver.hpp"
#include "tests/sample_catalogs.hpp"
#include "tests/sample_machines.hpp"

namespace pkmopt {
namespace {

// One pose above the base centre, no rotation, a pure vertical load.
HexapodDesignSpec single_pose_spec(double z, double fz) {
  HexapodDesignSpec spec;
  spec.task.poses = {Pose{{0, 0, z}, {0, 0, 0}}};
  spec.task.wrench << 0, 0, fz, 0, 0, 0;
  spec.objectives = {{DesignMetric::leg_force_max, Sense::minimize}};
  return spec;
}

TEST(HexapodDesign, BoxTaskPosesCoverTheGridTimesTheOrientations) {
  const std::vector<Pose> poses =
      box_task_poses({0, 0, 1}, {0.1, 0.2, 0.05}, {2, 3, 1}, deg_to_rad(20), 0, deg_to_rad(10));
  OrientationSet set;
  set.tilt = deg_to_rad(20);
  set.orientation_step = deg_to_rad(10);
  const std::size_t orientations = sample_orientations(set).size();
  ASSERT_EQ(poses.size(), 6 * orientations);
  double max_tilt = 0.0;
  for (const Pose& pose : poses) {
    EXPECT_NEAR(std::abs(pose.position.x()), 0.1, 1e-15);
    EXPECT_LE(std::abs(pose.position.y()), 0.2 + 1e-15);
    EXPECT_DOUBLE_EQ(pose.position.z(), 1.0);
    const Eigen::Vector3d axis = rotation_zyx<double>(pose.angles).col(2);
    max_tilt = std::max(max_tilt, std::acos(std::clamp(axis.z(), -1.0, 1.0)));
  }
  EXPECT_NEAR(max_tilt, deg_to_rad(20), 1e-9);
  const std::vector<Pose> cylinder = cylinder_task_poses({0, 0, 1}, 0.1, 0.2, 2, 4, 3, 0, 0);
  EXPECT_EQ(cylinder.size(), 3u * (1 + 2 * 4));
}

// Symmetric hexapod at its home pose under a vertical force F: by the three-fold and mirror
// symmetry all legs carry the same force and the moments cancel, so 6 tau cos(beta) = F with
// beta the angle of each leg from the vertical: tau = F / (6 cos beta).
TEST(HexapodDesign, LegForcesAtTheHomePoseOfASymmetricHexapod) {
  const double z_tcp = 0.9, force = -12000.0;
  HexapodDesignProblem problem(single_pose_spec(z_tcp, force));
  ASSERT_EQ(problem.num_variables(), 0u);
  const DesignEvaluation ev = problem.evaluate({});
  ASSERT_TRUE(ev.ok()) << ev.failure;

  // Leg 0: base joint at angle -10 deg, radius 0.6; platform joint at -60 + 10 deg, radius 0.25.
  const std::complex<double> a = std::polar(0.60, deg_to_rad(-10));
  const std::complex<double> b = std::polar(0.25, deg_to_rad(-50));
  const double height = z_tcp + 0.10;  // platform origin above the TCP (tcp = (0, 0, -0.1))
  const double length = std::hypot(std::abs(b - a), height);
  const double cos_beta = height / length;
  EXPECT_NEAR(ev.metrics[static_cast<int>(DesignMetric::leg_force_max)],
              std::abs(force) / (6.0 * cos_beta), 1e-9 * std::abs(force));
  EXPECT_TRUE(ev.reachable);
  EXPECT_LT(ev.reach_violation, 0.0);

  // machine_size = pi r_b^2 max_length, the envelope of the workspace module.
  const double size = ev.metrics[static_cast<int>(DesignMetric::machine_size)];
  EXPECT_NEAR(size, std::numbers::pi * 0.36 * 1.15, 1e-12);
  const Hexapod hexapod(problem.design_of(ev.parameters));
  EXPECT_NEAR(size, machine_envelope_volume(hexapod).value(), 1e-12);
  // The joints built by the problem are the library's semi-regular joints.
  const HexapodDesign reference = semi_regular_hexapod(0.60, deg_to_rad(20), 0.25, deg_to_rad(20));
  EXPECT_LT((hexapod.design().base_joints - reference.base_joints).cwiseAbs().maxCoeff(), 1e-15);
  EXPECT_LT((hexapod.design().platform_joints - reference.platform_joints).cwiseAbs().maxCoeff(),
            1e-15);
}

// natural_frequency_min: the lowest first natural frequency over the task poses, as analyze
// gives it for the design; without masses the problem is refused.
TEST(HexapodDesign, NaturalFrequencyMinIsTheLowestFirstFrequencyOverTheTask) {
  HexapodDesignSpec spec = single_pose_spec(0.9, 0.0);
  spec.task.poses.push_back(Pose{{0.1, -0.05, 0.85}, deg_to_rad(Eigen::Vector3d(5, -3, 10))});
  spec.task.poses.push_back(Pose{{-0.12, 0.08, 0.8}, deg_to_rad(Eigen::Vector3d(-8, 4, -15))});
  spec.objectives = {{DesignMetric::natural_frequency_min, Sense::maximize}};
  EXPECT_THROW(HexapodDesignProblem{spec}, std::invalid_argument);  // no masses
  MassModel& masses = spec.machine_template.masses;
  masses.present = true;
  masses.platform.mass = 45.0;
  masses.platform.centre_of_mass = {0, 0, -0.04};
  masses.platform.inertia = Eigen::Vector3d(1.3, 1.3, 2.0).asDiagonal();
  masses.legs.cylinder = {.mass = 6.0, .centre = 0.2, .inertia = 0.125};
  masses.legs.rod = {.mass = 3.0, .centre = 0.3, .inertia = 0.0625};
  const HexapodDesignProblem problem(spec);
  const DesignEvaluation ev = problem.evaluate({});
  ASSERT_TRUE(ev.ok()) << ev.failure;
  const Hexapod hexapod(problem.design_of(ev.parameters));
  HexapodData data(hexapod);
  double lowest = std::numeric_limits<double>::infinity();
  for (const Pose& pose : spec.task.poses) {
    PoseMetrics m;
    hexapod.analyze(data, pose, Wrench::Zero(), m);
    ASSERT_EQ(m.natural_frequencies.size(), 6);
    lowest = std::min(lowest, m.natural_frequencies(0));
  }
  EXPECT_GT(lowest, 10.0);
  EXPECT_DOUBLE_EQ(ev.metrics[static_cast<int>(DesignMetric::natural_frequency_min)], lowest);
  // moving_mass: the platform and six cylinders and rods.
  spec.objectives.push_back({DesignMetric::moving_mass, Sense::minimize});
  const DesignEvaluation with_mass = HexapodDesignProblem(spec).evaluate({});
  EXPECT_DOUBLE_EQ(with_mass.metrics[static_cast<int>(DesignMetric::moving_mass)],
                   45.0 + 6 * (6.0 + 3.0));
}

TEST(HexapodDesign, MaximizeFlipsTheSignAndConstraintsFollowTheirRelation) {
  HexapodDesignSpec spec = single_pose_spec(0.9, -5000.0);
  spec.parameters[kBaseRadius] = {0.5, 0.7};
  spec.objectives = {{DesignMetric::stiffness_min, Sense::minimize},
                     {DesignMetric::singularity_margin, Sense::minimize}};
  spec.constraints = {{DesignMetric::leg_force_max, Relation::less_equal, 900.0},
                      {DesignMetric::leg_force_max, Relation::greater_equal, 900.0}};
  const HexapodDesignProblem minimized(spec);
  spec.objectives[0].sense = Sense::maximize;
  spec.objectives[1].sense = Sense::maximize;
  const HexapodDesignProblem maximized(spec);
  const std::vector<double> x{0.62};
  const std::vector<double> fmin = minimized.fitness(x);
  const std::vector<double> fmax = maximized.fitness(x);
  ASSERT_EQ(fmin.size(), 5u);  // 2 objectives, 2 constraints, reachability
  EXPECT_GT(fmin[0], 0.0);
  EXPECT_EQ(fmax[0], -fmin[0]);
  EXPECT_EQ(fmax[1], -fmin[1]);
  const DesignEvaluation ev = minimized.evaluate(x);
  const double force = ev.metrics[static_cast<int>(DesignMetric::leg_force_max)];
  EXPECT_EQ(fmin[2], force - 900.0);
  EXPECT_EQ(fmin[3], 900.0 - force);
  EXPECT_EQ(fmin[4], ev.reach_violation);
  EXPECT_EQ(ev.metrics[static_cast<int>(DesignMetric::stiffness_min)], fmin[0]);
}

TEST(HexapodDesign, ReachabilityRowsAgreeWithTheModel) {
  HexapodDesignSpec spec;
  spec.objectives = {{DesignMetric::machine_size, Sense::minimize}};
  const Hexapod hexapod(spec.machine_template);
  HexapodData data(hexapod);
  int reachable = 0, unreachable = 0;
  // Poses spread from well inside to well outside the workspace.
  for (const Pose& pose : box_task_poses({0, 0, 0.95}, {0.5, 0.5, 0.45}, {5, 5, 7}, deg_to_rad(30),
                                         deg_to_rad(20), deg_to_rad(15))) {
    spec.task.poses = {pose};
    const DesignEvaluation ev = HexapodDesignProblem(spec).evaluate({});
    ASSERT_TRUE(std::isfinite(ev.reach_violation));
    EXPECT_EQ(ev.reachable, hexapod.reachable(data, pose));
    (ev.reachable ? reachable : unreachable)++;
  }
  EXPECT_GT(reachable, 20);
  EXPECT_GT(unreachable, 20);
}

TEST(HexapodDesign, FailingDesignsAreRecordedWithAReasonAndFiniteRows) {
  HexapodDesignSpec spec = single_pose_spec(0.9, -5000.0);
  spec.parameters[kPlatformRadius] = {0.0, 0.3};  // r_p = 0: all platform joints coincide
  spec.objectives = {{DesignMetric::leg_force_max, Sense::minimize},
                     {DesignMetric::stiffness_min, Sense::maximize},
                     {DesignMetric::tcp_error_max, Sense::minimize}};
  spec.constraints = {{DesignMetric::singularity_margin, Relation::greater_equal, 0.01}};
  const HexapodDesignProblem problem(spec);
  const DesignEvaluation failed = problem.evaluate({0.0});
  EXPECT_FALSE(failed.ok());
  EXPECT_NE(failed.failure.find("singular"), std::string::npos) << failed.failure;
  for (double v : failed.metrics) EXPECT_TRUE(std::isfinite(v));
  const std::vector<double> f = problem.fitness({0.0});
  ASSERT_EQ(f.size(), 5u);
  for (double v : f) EXPECT_EQ(v, kFailurePenalty);
  EXPECT_GT(constraint_violation(problem, f), 0.0);

  // A good design next to it succeeds; an unreachable task is a violated constraint, not NaN.
  EXPECT_TRUE(problem.evaluate({0.25}).ok());
  spec.task.poses = {Pose{{0, 0, 3.0}, {0, 0, 0}}};
  const HexapodDesignProblem far_task(spec);
  const std::vector<double> g = far_task.fitness({0.25});
  for (double v : g) EXPECT_TRUE(std::isfinite(v));
  EXPECT_GT(g.back(), 1.0);  // legs about 3.1 m long against max_length 1.15 m
}

TEST(HexapodDesign, WorkspaceVolumeIsTheWorkspaceModuleFastPath) {
  HexapodDesignSpec spec = single_pose_spec(0.9, 0.0);
  spec.objectives = {{DesignMetric::workspace_volume, Sense::maximize}};
  spec.task.workspace.resolution = 0.08;
  const HexapodDesignProblem problem(spec);
  const std::vector<double> f = problem.fitness({});
  WorkspaceOptions options = spec.task.workspace;
  options.compute_maps = false;
  options.compute_hull = false;
  const double volume = workspace_volume(Hexapod(spec.machine_template), options);
  EXPECT_GT(volume, 0.05);
  EXPECT_EQ(f[0], -volume);
}

TEST(HexapodDesign, ConditioningIndexIsTheMeanMarginOverTheWorkspace) {
  HexapodDesignSpec spec = single_pose_spec(0.9, 0.0);
  spec.objectives = {{DesignMetric::conditioning_index, Sense::maximize},
                     {DesignMetric::workspace_volume, Sense::maximize}};
  spec.task.workspace.resolution = 0.08;
  const HexapodDesignProblem problem(spec);
  const DesignEvaluation ev = problem.evaluate({});
  ASSERT_TRUE(ev.ok()) << ev.failure;
  WorkspaceOptions options = spec.task.workspace;
  options.compute_maps = true;
  options.compute_hull = false;
  const Hexapod hexapod(spec.machine_template);
  const WorkspaceResult workspace = compute_workspace(hexapod, options);
  ASSERT_GT(workspace.maps.points, 10);
  // Mean of the node margins, each in (0, 1].
  EXPECT_EQ(ev.metrics[static_cast<int>(DesignMetric::conditioning_index)],
            workspace.maps.global_conditioning_index);
  EXPECT_GT(workspace.maps.global_conditioning_index, 0.0);
  EXPECT_LE(workspace.maps.global_conditioning_index, 1.0);
  // Sharing the workspace computation gives the fast path's volume.
  options.compute_maps = false;
  EXPECT_EQ(ev.metrics[static_cast<int>(DesignMetric::workspace_volume)],
            workspace_volume(hexapod, options));
  const std::vector<double> f = problem.fitness({});
  EXPECT_EQ(f[0], -workspace.maps.global_conditioning_index);
}

TEST(HexapodDesign, BatchFitnessInParallelEqualsSerial) {
  HexapodDesignSpec spec;
  spec.task.poses = box_task_poses({0, 0, 0.9}, {0.1, 0.1, 0.05}, {2, 2, 2}, deg_to_rad(10), 0);
  spec.task.wrench << 100, 0, -3000, 0, 20, 0;
  spec.parameters[kBaseRadius] = {0.5, 0.7};
  spec.parameters[kStroke] = {0.3, 0.6};
  spec.objectives = {{DesignMetric::stiffness_min, Sense::maximize},
                     {DesignMetric::conditioning_index, Sense::maximize}};
  spec.task.workspace.resolution = 0.1;  // the conditioning index samples the workspace
  const HexapodDesignProblem problem(spec);
  EXPECT_EQ(problem.thread_safety(), ThreadSafety::basic);
  std::vector<std::vector<double>> xs;
  for (int k = 0; k < 8; ++k) xs.push_back({0.5 + 0.025 * k, 0.3 + 0.04 * k});
  const auto serial = problem.batch_fitness(xs, 1);
  const auto parallel = problem.batch_fitness(xs, 2);
  ASSERT_EQ(serial.size(), xs.size());
  for (std::size_t k = 0; k < xs.size(); ++k) {
    EXPECT_EQ(serial[k], parallel[k]);
    EXPECT_EQ(serial[k], problem.fitness(xs[k]));
  }
}

HexapodDesignSpec smooth_spec() {
  HexapodDesignSpec spec;
  spec.formulation = DesignFormulation::smooth;
  spec.task.poses = box_task_poses({0.02, -0.01, 0.9}, {0.1, 0.1, 0.05}, {2, 2, 2}, deg_to_rad(15),
                                   deg_to_rad(10), deg_to_rad(15));
  spec.task.wrench << 300, -200, -4000, 15, -25, 10;
  spec.parameters[kBaseRadius] = {0.5, 0.7};
  spec.parameters[kPlatformRadius] = {0.2, 0.3};
  spec.parameters[kBasePairSeparation] = {deg_to_rad(10), deg_to_rad(40)};
  spec.parameters[kPlatformPairSeparation] = {deg_to_rad(10), deg_to_rad(40)};
  spec.parameters[kMinLength] = {0.6, 0.8};
  spec.parameters[kStroke] = {0.3, 0.6};
  spec.parameters[kHomeHeight] = {-0.1, 0.1};
  spec.objectives = {{DesignMetric::leg_force_max, Sense::minimize},
                     {DesignMetric::machine_size, Sense::maximize}};
  spec.constraints = {{DesignMetric::leg_force_max, Relation::less_equal, 5000.0},
                      {DesignMetric::machine_size, Relation::greater_equal, 0.5}};
  return spec;
}

TEST(HexapodDesign, SmoothFormulationGradientsMatchFiniteDifferences) {
  const HexapodDesignProblem problem(smooth_spec());
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
  HexapodDesignSpec spec = smooth_spec();
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
  HexapodDesignSpec spec = smooth_spec();
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
  HexapodDesignSpec spec = smooth_spec();
  spec.objectives[1] = {DesignMetric::stiffness_min, Sense::minimize};
  EXPECT_THROW(HexapodDesignProblem{spec}, std::invalid_argument);
  spec.objectives[1] = {DesignMetric::singularity_margin, Sense::maximize};
  EXPECT_THROW(HexapodDesignProblem{spec}, std::invalid_argument);
  spec.objectives = {{DesignMetric::stiffness_min, Sense::maximize},
                     {DesignMetric::stiffness_min, Sense::maximize}};
  EXPECT_THROW(HexapodDesignProblem{spec}, std::invalid_argument);  // one epigraph per metric
  spec = smooth_spec();
  spec.constraints.push_back({DesignMetric::singularity_margin, Relation::greater_equal, 0.1});
  EXPECT_THROW(HexapodDesignProblem{spec}, std::invalid_argument);
  spec = smooth_spec();
  spec.formulation = DesignFormulation::aggregate;
  const HexapodDesignProblem aggregate(spec);
  EXPECT_FALSE(aggregate.has_gradient());
  EXPECT_THROW(aggregate.gradient(std::vector<double>(7, 0.5)), std::logic_error);
  spec.parameters[kStroke] = {0.6, 0.3};
  EXPECT_THROW(HexapodDesignProblem{spec}, std::invalid_argument);
  spec = smooth_spec();
  spec.objectives.clear();
  EXPECT_THROW(HexapodDesignProblem{spec}, std::invalid_argument);
}

// The optimiser chooses the cheapest catalog entry: actuator_cost, actuator_overload and the
// chosen entry follow from leg_force_max and the stroke exactly as the catalog functions say.
TEST(HexapodDesign, ChoosesTheCheapestCatalogActuatorThatCarriesTheLegs) {
  HexapodDesignSpec spec = smooth_spec();
  spec.formulation = DesignFormulation::aggregate;
  spec.parameters[kStroke] = {0.10, 0.35};
  spec.actuator_catalog = sample_catalogs::sew_cms();
  spec.objectives = {{DesignMetric::actuator_cost, Sense::minimize},
                     {DesignMetric::stiffness_min, Sense::maximize}};
  spec.constraints = {{DesignMetric::actuator_overload, Relation::less_equal, 0.0}};
  spec.require_reachable = false;
  const ActuatorCatalog& catalog = *spec.actuator_catalog;
  const std::vector<double> ranks = actuator_costs(catalog);
  sample_machines::Uniform u(17);
  std::set<std::string> chosen;
  int infeasible = 0;
  // Loads from 4 to 40 kN down: the weaker drives carry some designs, none carries others.
  const Wrench base_wrench = spec.task.wrench;
  for (int trial = 0; trial < 80; ++trial) {
    spec.task.wrench = base_wrench * (1.0 + trial % 8 * 1.3);
    const HexapodDesignProblem problem(spec);
    const Bounds b = problem.bounds();
    std::vector<double> x;
    for (std::size_t j = 0; j < b.lower.size(); ++j) x.push_back(u(b.lower[j], b.upper[j]));
    const DesignEvaluation ev = problem.evaluate(x);
    if (!ev.ok()) continue;
    const double force = ev.metrics[static_cast<int>(DesignMetric::leg_force_max)];
    const double stroke = ev.parameters[kStroke];
    EXPECT_EQ(ev.metrics[static_cast<int>(DesignMetric::actuator_overload)],
              force - actuator_force_capacity(catalog, stroke));
    const ActuatorChoice choice = choose_actuator(catalog, {force, stroke, 0.0});
    const std::vector<double> f = problem.fitness(x);
    ASSERT_EQ(f.size(), 3u);
    EXPECT_EQ(f[2], ev.metrics[static_cast<int>(DesignMetric::actuator_overload)]);
    if (choice.entry == nullptr) {
      ++infeasible;
      EXPECT_EQ(ev.actuator, -1);
      EXPECT_GT(f[2], 0.0);
      EXPECT_EQ(f[0], 8.0);  // no entry carries: rank catalog of 7 entries -> 8
    } else {
      const std::size_t index = static_cast<std::size_t>(choice.entry - catalog.entries.data());
      EXPECT_EQ(ev.actuator, static_cast<int>(index));
      EXPECT_LE(f[2], 0.0);
      EXPECT_EQ(f[0], ranks[index]);
      chosen.insert(choice.entry->name);
      // No cheaper entry carries the legs.
      for (std::size_t i = 0; i < catalog.entries.size(); ++i)
        if (ranks[i] < ranks[index]) {
          EXPECT_FALSE(carries(catalog.entries[i], {force, stroke, 0}));
        }
    }
  }
  // The random designs need different drives, and some need more than any entry has.
  EXPECT_GE(chosen.size(), 3u) << fmt::format("{}", fmt::join(chosen, ", "));
  EXPECT_GT(infeasible, 0);

  // With prices the cost is the price; a design no entry carries costs twice the dearest.
  for (std::size_t i = 0; i < spec.actuator_catalog->entries.size(); ++i)
    spec.actuator_catalog->entries[i].cost = 100.0 + 10.0 * static_cast<double>(i);
  spec.task.wrench = base_wrench * 30.0;  // 120 kN down: nothing carries it
  const HexapodDesignProblem priced(spec);
  const DesignEvaluation heavy =
      priced.evaluate({0.6, 0.25, deg_to_rad(20), deg_to_rad(20), 0.7, 0.3, 0.0});
  ASSERT_TRUE(heavy.ok()) << heavy.failure;
  EXPECT_EQ(heavy.actuator, -1);
  EXPECT_EQ(heavy.metrics[static_cast<int>(DesignMetric::actuator_cost)], 2.0 * 160.0);
  EXPECT_GT(heavy.metrics[static_cast<int>(DesignMetric::actuator_overload)], 0.0);
}

// With a fixed stroke the catalog's capacity F is a constant, and the smooth formulation's
// actuator_overload <= b rows are the leg_force_max <= b + F rows.
TEST(HexapodDesign, SmoothActuatorOverloadRowsAreForceRowsAtTheCapacity) {
  HexapodDesignSpec spec = smooth_spec();
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

TEST(HexapodDesign, ActuatorChoiceErrors) {
  HexapodDesignSpec spec = smooth_spec();
  spec.formulation = DesignFormulation::aggregate;
  spec.constraints = {{DesignMetric::actuator_overload, Relation::less_equal, 0.0}};
  EXPECT_THROW(HexapodDesignProblem{spec}, std::invalid_argument);  // no catalog
  spec.actuator_catalog = sample_catalogs::sew_cms();
  spec.parameters[kStroke] = {0.3, 0.6};  // longer than the longest entry (0.35 m)
  try {
    HexapodDesignProblem{spec};
    ADD_FAILURE() << "no error";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("parameter stroke: expected an upper bound <= 0.35 m"),
              std::string::npos)
        << e.what();
  }
  spec.parameters[kStroke] = {0.3, 0.35};
  EXPECT_NO_THROW(HexapodDesignProblem{spec});
  spec.actuator_catalog->entries[1].cost = 3.0;  // some prices, not all
  EXPECT_THROW(HexapodDesignProblem{spec}, std::invalid_argument);
  spec.actuator_catalog = sample_catalogs::sew_cms();
  spec.actuator_catalog->entries[1].max_force = -1.0;
  EXPECT_THROW(HexapodDesignProblem{spec}, std::invalid_argument);
  // Smooth: the overload needs a fixed stroke; the cost has no smooth formulation.
  spec = smooth_spec();
  spec.actuator_catalog = sample_catalogs::sew_cms();
  spec.parameters[kStroke] = {0.2, 0.3};
  spec.constraints = {{DesignMetric::actuator_overload, Relation::less_equal, 0.0}};
  EXPECT_THROW(HexapodDesignProblem{spec}, std::invalid_argument);
  spec.parameters[kStroke] = {0.3, 0.3};
  EXPECT_NO_THROW(HexapodDesignProblem{spec});
  spec.objectives[1] = {DesignMetric::actuator_cost, Sense::minimize};
  EXPECT_THROW(HexapodDesignProblem{spec}, std::invalid_argument);
}

}  // namespace
}  // namespace pkmopt
