// Tests of problems/design/hexapod_design (aggregate formulation): a hand-computed design
// evaluation, sign conventions, failures without NaN, agreement with the model, the dynamic metrics
// (natural_frequency_min, moving_mass, actuator_force_dynamic_max), the legs' interference and the
// catalog choice. The
// smooth formulation is tested in hexapod_design_smooth_test.cpp.
#include "problems/design/hexapod_design.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <numbers>
#include <set>
#include <stdexcept>
#include <string>

#include "models/core/machine_sketch.hpp"
#include "models/dynamics/acceleration_capability.hpp"
#include "models/hexapod/swept_envelope.hpp"
#include "models/workspace/mode_certificate.hpp"
#include "tests/problems/design/hexapod_design_specs.hpp"
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
  spec.machine_template.masses = sample_machines::milling_hexapod_masses();
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

// actuator_force_dynamic_max: the worst force over the task when the TCP accelerates with
// |a| <= a_max (models/dynamics/acceleration_capability, checked against sampled directions in its
// own test) is the largest per-pose bound; it grows linearly with a_max from the weighted static
// force; it needs a_max and masses.
TEST(HexapodDesign, DynamicActuatorForceIsTheWorstAcceleratedForceOverTheTask) {
  HexapodDesignSpec spec = single_pose_spec(0.9, -2000.0);
  spec.task.poses.push_back(Pose{{0.1, -0.05, 0.85}, deg_to_rad(Eigen::Vector3d(5, -3, 10))});
  spec.objectives = {{DesignMetric::actuator_force_dynamic_max, Sense::minimize}};
  spec.machine_template.masses = sample_machines::milling_hexapod_masses();
  EXPECT_THROW(HexapodDesignProblem{spec}, std::invalid_argument);  // no a_max
  spec.task.acceleration_max = 9.81;
  auto force_at = [&](double a_max) {
    HexapodDesignSpec s = spec;
    s.task.acceleration_max = a_max;
    const DesignEvaluation ev = HexapodDesignProblem(s).evaluate({});
    EXPECT_TRUE(ev.ok()) << ev.failure;
    return ev.metrics[static_cast<int>(DesignMetric::actuator_force_dynamic_max)];
  };
  const double one_g = force_at(9.81);
  const HexapodDesignProblem problem(spec);
  const Hexapod hexapod(problem.design_of(problem.evaluate({}).parameters));
  HexapodData data(hexapod);
  double expected = 0.0;
  Eigen::VectorXd bound;
  for (const Pose& pose : spec.task.poses) {
    ASSERT_TRUE(acceleration_force_bound(hexapod, data, pose, spec.task.wrench, 9.81, bound));
    expected = std::max(expected, bound.maxCoeff());
  }
  EXPECT_DOUBLE_EQ(one_g, expected);
  // The cutting load alone carries less; 1 g adds much more than the weights.
  spec.objectives.push_back({DesignMetric::leg_force_max, Sense::minimize});
  const double static_force = HexapodDesignProblem(spec)
                                  .evaluate({})
                                  .metrics[static_cast<int>(DesignMetric::leg_force_max)];
  EXPECT_GT(one_g, static_force + 100.0);
  // Linear in a_max where the same leg and pose stay the worst.
  const double two_g = force_at(2 * 9.81), three_g = force_at(3 * 9.81);
  EXPECT_NEAR(three_g - two_g, two_g - one_g, 1e-9 * three_g);
  spec.machine_template.masses = MassModel{};
  EXPECT_THROW(HexapodDesignProblem{spec}, std::invalid_argument);  // a_max without masses
}

// With a_max the catalog sizes the legs for the accelerated task: a heavy platform at 3 g needs a
// stronger SEW cylinder than the static load does.
TEST(HexapodDesign, CatalogChoiceUsesTheAcceleratedForceWithAMax) {
  HexapodDesignSpec spec = single_pose_spec(0.9, -4000.0);
  spec.parameters[kStroke] = {0.3, 0.3};
  spec.objectives = {{DesignMetric::actuator_cost, Sense::minimize}};
  spec.actuator_catalog = sample_catalogs::sew_cms();
  spec.machine_template.masses = sample_machines::milling_hexapod_masses();
  spec.machine_template.masses.platform.mass = 150.0;
  const DesignEvaluation still = HexapodDesignProblem(spec).evaluate({});
  spec.task.acceleration_max = 3 * 9.81;
  const DesignEvaluation rapid = HexapodDesignProblem(spec).evaluate({});
  ASSERT_TRUE(still.ok() && rapid.ok()) << still.failure << rapid.failure;
  const double dynamic = rapid.metrics[static_cast<int>(DesignMetric::actuator_force_dynamic_max)];
  EXPECT_GT(dynamic, 5300.0);  // beyond the CMS50S
  EXPECT_LT(still.metrics[static_cast<int>(DesignMetric::leg_force_max)], 5300.0);
  EXPECT_EQ(spec.actuator_catalog->entries[static_cast<std::size_t>(still.actuator)].name,
            "CMS50S/300");
  EXPECT_EQ(spec.actuator_catalog->entries[static_cast<std::size_t>(rapid.actuator)].name,
            "CMS71L/350");
  // No peak ratings in this catalog: the accelerated force against the continuous rating.
  EXPECT_DOUBLE_EQ(rapid.metrics[static_cast<int>(DesignMetric::actuator_overload)],
                   dynamic - actuator_force_capacity(*spec.actuator_catalog, 0.3));
  // With peak ratings (2.5 x continuous) the cheap cylinder carries the rapids again.
  for (ActuatorEntry& e : spec.actuator_catalog->entries) e.peak_force = 2.5 * e.max_force;
  const DesignEvaluation peak = HexapodDesignProblem(spec).evaluate({});
  EXPECT_EQ(spec.actuator_catalog->entries[static_cast<std::size_t>(peak.actuator)].name,
            "CMS50S/300");
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

// With the legs' shape the reachability row includes the interference (the model's reachable
// with the same shape and min_clearance, at poses where legs do and do not collide), and
// leg_clearance_min is the smallest clearance over the task; the metric needs a shape, and the
// smooth formulation refuses a shape.
TEST(HexapodDesign, LegInterferenceCountsInReachabilityAndLegClearanceMin) {
  HexapodDesignSpec spec;
  spec.objectives = {{DesignMetric::leg_clearance_min, Sense::maximize}};
  spec.task.poses = {Pose{{0, 0, 0.9}, {0, 0, 0}}};
  EXPECT_THROW(HexapodDesignProblem{spec}, std::invalid_argument);  // no leg shape
  spec.machine_template.leg_shape.diameter = 0.08;
  spec.machine_template.min_clearance = 0.002;
  spec.machine_template.joints = HexapodJointLimits{};  // the legs, not the joints, limit the yaw
  spec.parameters[kStroke] = {0.7, 0.7};                // a yaw of 90 degrees needs 1.28 m legs
  const HexapodDesignProblem problem(spec);
  const Hexapod hexapod(problem.design_of(problem.evaluate({}).parameters));
  HexapodData data(hexapod);
  int reachable = 0, colliding = 0;
  // Legs cross beyond a yaw of about 90 degrees while their lengths stay within the stroke.
  for (int yaw = 60; yaw <= 110; yaw += 2) {
    for (const double x : {-0.01, 0.0, 0.01}) {
      const Pose pose{{x, 0.0, 0.9}, deg_to_rad(Eigen::Vector3d(0, 0, yaw))};
      spec.task.poses = {pose};
      const DesignEvaluation ev = HexapodDesignProblem(spec).evaluate({});
      EXPECT_EQ(ev.reachable, hexapod.reachable(data, pose)) << yaw << " " << x;
      const Clearance c = hexapod.leg_clearance(pose);
      EXPECT_NEAR(ev.metrics[static_cast<int>(DesignMetric::leg_clearance_min)], c.value, 1e-12);
      if (c.value < 0.002) {
        ++colliding;
        EXPECT_FALSE(ev.reachable);
        EXPECT_GE(ev.reach_violation, 0.002 - c.value - 1e-15);
      }
      reachable += ev.reachable ? 1 : 0;
    }
  }
  EXPECT_GT(reachable, 10);
  EXPECT_GT(colliding, 10);
  // Over a task: the minimum over its poses.
  spec.task.poses = {Pose{{0, 0, 0.9}, {0, 0, 0}},
                     Pose{{0.05, 0, 0.9}, deg_to_rad(Eigen::Vector3d(0, 0, 20))}};
  const DesignEvaluation both = HexapodDesignProblem(spec).evaluate({});
  EXPECT_NEAR(both.metrics[static_cast<int>(DesignMetric::leg_clearance_min)],
              std::min(hexapod.leg_clearance(spec.task.poses[0]).value,
                       hexapod.leg_clearance(spec.task.poses[1]).value),
              1e-12);
  HexapodDesignSpec smooth = test_specs::smooth_spec();
  smooth.machine_template.leg_shape.diameter = 0.08;
  EXPECT_THROW(HexapodDesignProblem{smooth}, std::invalid_argument);
}

// Over random designs of a milling-like study, the leg diameter removes designs: every design
// that reaches the task with 80 mm legs has them apart at every task pose (recomputed here from
// the design), it also reaches the task with line legs, and some designs that reach it with line
// legs (joints of a pair closer than 80 mm among them) are gone.
TEST(HexapodDesign, LegDiameterRemovesTheDesignsWhoseLegsCollide) {
  HexapodDesignSpec lines;
  lines.objectives = {{DesignMetric::machine_size, Sense::minimize}};
  lines.task.poses =
      box_task_poses({0, 0, 0.9}, {0.1, 0.1, 0.05}, {2, 2, 2}, deg_to_rad(15), 0.0, deg_to_rad(15));
  lines.parameters[kBaseRadius] = {0.35, 0.75};
  lines.parameters[kPlatformRadius] = {0.15, 0.30};
  lines.parameters[kBasePairSeparation] = {deg_to_rad(5), deg_to_rad(40)};
  lines.parameters[kPlatformPairSeparation] = {deg_to_rad(5), deg_to_rad(40)};
  lines.parameters[kMinLength] = {0.6, 1.0};
  lines.parameters[kHomeHeight] = {-0.2, 0.2};
  HexapodDesignSpec legs = lines;
  legs.machine_template.leg_shape.diameter = 0.08;
  const HexapodDesignProblem line_problem(lines), leg_problem(legs);
  const Bounds b = leg_problem.bounds();
  sample_machines::Uniform u(2026);
  int both = 0, removed = 0;
  for (int k = 0; k < 400; ++k) {
    std::vector<double> x(b.lower.size());
    for (std::size_t i = 0; i < x.size(); ++i) x[i] = u(b.lower[i], b.upper[i]);
    const DesignEvaluation with_legs = leg_problem.evaluate(x);
    const DesignEvaluation with_lines = line_problem.evaluate(x);
    if (with_legs.reachable) {
      EXPECT_TRUE(with_lines.reachable);
      const Hexapod hexapod(leg_problem.design_of(with_legs.parameters));
      for (Pose pose : legs.task.poses) {
        pose.position.z() += with_legs.parameters[kHomeHeight];
        EXPECT_GE(hexapod.leg_clearance(pose).value, 0.0);
      }
      ++both;
    } else if (with_lines.reachable) {
      ++removed;
    }
  }
  EXPECT_GT(both, 5);
  EXPECT_GT(removed, 5);
}

// Obstacles: a box around a base joint (the joints on a circle of 0.6 m at z = 0) takes the
// hexapod's drawing 20 mm deep (the box's half height); moved aside it changes nothing; the smooth
// formulation refuses obstacles.
TEST(HexapodDesign, ObstaclesCountInReachability) {
  HexapodDesignSpec spec;
  spec.objectives = {{DesignMetric::machine_size, Sense::minimize}};
  spec.task.poses = {Pose{{0, 0, 0.9}, {0, 0, 0}}};
  const double free = HexapodDesignProblem(spec).evaluate({}).reach_violation;
  const std::unique_ptr<Machine> hexapod = std::make_unique<Hexapod>(spec.machine_template);
  MachineSketch sketch;
  ASSERT_TRUE(hexapod->sketch(*hexapod->make_data(), spec.task.poses[0], sketch));
  const Eigen::Vector3d joint = sketch.base_joints.front();
  EXPECT_NEAR(joint.head<2>().norm(), 0.6, 1e-9);
  spec.task.obstacles = {
      {joint - Eigen::Vector3d(0.05, 0.05, 0.02), joint + Eigen::Vector3d(0.05, 0.05, 0.02)}};
  const DesignEvaluation blocked = HexapodDesignProblem(spec).evaluate({});
  EXPECT_FALSE(blocked.reachable);
  EXPECT_NEAR(blocked.reach_violation, 0.02, 1e-12);  // the joint at the box's centre
  spec.task.obstacles[0].min.z() += 1.5;
  spec.task.obstacles[0].max.z() += 1.5;
  EXPECT_EQ(HexapodDesignProblem(spec).evaluate({}).reach_violation, free);
  HexapodDesignSpec smooth = test_specs::smooth_spec();
  smooth.task.obstacles = spec.task.obstacles;
  EXPECT_THROW(HexapodDesignProblem{smooth}, std::invalid_argument);
}

// The installation space: the sample hexapod at home fits a box of its base (radius 0.6 m) and
// height; a box whose top is below the platform joints at a task pose makes the task
// unreachable by how far they stick out; a cylinder narrower than the base circle too; the
// leg diameter counts. Leg-chain problems refuse it.
TEST(HexapodDesign, InstallationSpaceCountsInReachability) {
  HexapodDesignSpec spec;
  spec.objectives = {{DesignMetric::machine_size, Sense::minimize}};
  spec.task.poses = {Pose{{0, 0, 0.9}, {0, 0, 0}}};
  const double fits = HexapodDesignProblem(spec).evaluate({}).reach_violation;
  spec.task.installation_space.kind = InstallationSpace::Kind::kBox;
  spec.task.installation_space.min = {-0.7, -0.7, -0.1};
  spec.task.installation_space.max = {0.7, 0.7, 1.2};
  const DesignEvaluation inside = HexapodDesignProblem(spec).evaluate({});
  EXPECT_TRUE(inside.reachable);
  EXPECT_EQ(inside.reach_violation, fits);  // the space is not the closest constraint here
  // The platform joints are at z = 0.9 + 0.1 (the TCP 0.1 m below the platform): a top at 0.95.
  spec.task.installation_space.max.z() = 0.95;
  const DesignEvaluation low = HexapodDesignProblem(spec).evaluate({});
  EXPECT_FALSE(low.reachable);
  EXPECT_NEAR(low.reach_violation, 0.05, 1e-12);
  // 80 mm legs stick out 0.04 m further.
  spec.machine_template.leg_shape.diameter = 0.08;
  EXPECT_NEAR(HexapodDesignProblem(spec).evaluate({}).reach_violation, 0.09, 1e-12);
  spec.machine_template.leg_shape = LegShape{};
  // A cylinder of radius 0.55 m about the axis: the base joints (radius 0.6 m) stick out 0.05 m.
  spec.task.installation_space = InstallationSpace{};
  spec.task.installation_space.kind = InstallationSpace::Kind::kCylinder;
  spec.task.installation_space.radius = 0.55;
  spec.task.installation_space.z_min = -0.1;
  spec.task.installation_space.z_max = 1.5;
  EXPECT_NEAR(HexapodDesignProblem(spec).evaluate({}).reach_violation, 0.05, 1e-12);
  // A base plate of radius 0.7 m enters by its circumscribed 32-gon (radius 0.7 / cos(pi/32)).
  spec.machine_template.leg_shape.cylinder_diameter = 0.01;  // a rod for the plate to see
  spec.machine_template.leg_shape.cylinder_length = 0.5;
  spec.machine_template.leg_shape.rod_diameter = 0.01;
  spec.machine_template.bodies.base.radius = 0.7;
  spec.machine_template.bodies.base.z_min = -0.05;
  EXPECT_NEAR(HexapodDesignProblem(spec).evaluate({}).reach_violation,
              0.7 / std::cos(std::numbers::pi / 32) - 0.55, 1e-12);
  spec.machine_template.bodies = MachineBodies{};
  spec.machine_template.leg_shape = LegShape{};
  HexapodDesignSpec smooth = test_specs::smooth_spec();
  smooth.task.installation_space = spec.task.installation_space;
  EXPECT_THROW(HexapodDesignProblem{smooth}, std::invalid_argument);
}

// swept_volume and footprint are the swept envelope of the design over its task poses (lifted by
// the home height); a longer task sweeps more. Leg-chain problems refuse both.
TEST(HexapodDesign, SweptVolumeAndFootprintAreTheEnvelopeOverTheTask) {
  HexapodDesignSpec spec;
  spec.objectives = {{DesignMetric::swept_volume, Sense::minimize},
                     {DesignMetric::footprint, Sense::minimize}};
  spec.task.poses = box_task_poses({0, 0, 0.9}, {0.1, 0.1, 0.05}, {2, 2, 2}, 0.0, 0.0);
  spec.parameters[kHomeHeight] = {0.05, 0.05};
  const HexapodDesignProblem problem(spec);
  const DesignEvaluation ev = problem.evaluate({});
  ASSERT_TRUE(ev.ok()) << ev.failure;
  const Hexapod hexapod(problem.design_of(ev.parameters));
  std::vector<Pose> lifted = spec.task.poses;
  for (Pose& pose : lifted) pose.position.z() += 0.05;
  const SweptEnvelope e = swept_envelope(hexapod, lifted);
  EXPECT_EQ(ev.metrics[static_cast<int>(DesignMetric::swept_volume)], e.volume);
  EXPECT_EQ(ev.metrics[static_cast<int>(DesignMetric::footprint)], e.footprint);
  EXPECT_GT(e.volume, 0.5);  // about the base circle (r 0.6 m) times the height (~1 m)
  spec.task.poses = box_task_poses({0, 0, 0.9}, {0.3, 0.3, 0.05}, {2, 2, 2}, 0.0, 0.0);
  EXPECT_GT(
      HexapodDesignProblem(spec).evaluate({}).metrics[static_cast<int>(DesignMetric::swept_volume)],
      e.volume);
}

// task_singularity_free is singularity_free_share of the task region lifted by the home height:
// 1 for a box about the home pose; below 1 when the yaw range reaches the turn of 90 degrees
// about z (Fichter's singularity); a task without a region is refused.
TEST(HexapodDesign, TaskSingularityFreeCertifiesTheTaskRegion) {
  HexapodDesignSpec spec;
  spec.objectives = {{DesignMetric::machine_size, Sense::minimize}};
  spec.constraints = {{DesignMetric::task_singularity_free, Relation::greater_equal, 1.0}};
  spec.task.poses = box_task_poses({0, 0, 0.85}, {0.05, 0.05, 0.05}, {2, 2, 2}, 0.0, 0.0);
  PoseBox region;
  region.position_lo = {-0.05, -0.05, 0.8};
  region.position_hi = {0.05, 0.05, 0.9};
  region.gamma = Interval(-10 * kDegToRad, 10 * kDegToRad);
  spec.task.region = region;
  spec.parameters[kHomeHeight] = {0.05, 0.05};
  const HexapodDesignProblem problem(spec);
  const DesignEvaluation ev = problem.evaluate({});
  ASSERT_TRUE(ev.ok()) << ev.failure;
  EXPECT_EQ(ev.metrics[static_cast<int>(DesignMetric::task_singularity_free)], 1.0);
  const Hexapod hexapod(problem.design_of(ev.parameters));
  PoseBox lifted = region;
  lifted.position_lo.z() += 0.05;
  lifted.position_hi.z() += 0.05;
  EXPECT_TRUE(certify_working_mode(hexapod, {lifted}, {}).certified());
  EXPECT_LE(problem.aggregate_fitness(ev)[1], 0.0);  // rows: objective, constraint, ...

  // Turned up to 100 degrees each way: the region holds Fichter's singular poses.
  spec.task.region->gamma = Interval(-100 * kDegToRad, 100 * kDegToRad);
  const DesignEvaluation turned = HexapodDesignProblem(spec).evaluate({});
  ASSERT_TRUE(turned.ok()) << turned.failure;
  const double share = turned.metrics[static_cast<int>(DesignMetric::task_singularity_free)];
  EXPECT_LT(share, 1.0);
  EXPECT_GT(share, 0.0);
  EXPECT_EQ(share, singularity_free_share(hexapod, [&] {
              PoseBox b = *spec.task.region;
              b.position_lo.z() += 0.05;
              b.position_hi.z() += 0.05;
              return b;
            }()));
  EXPECT_GT(HexapodDesignProblem(spec).aggregate_fitness(turned)[1], 0.0);  // violated

  spec.task.region.reset();
  EXPECT_THROW(HexapodDesignProblem{spec}, std::invalid_argument);
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

TEST(HexapodDesign, ChoosesTheCheapestCatalogActuatorThatCarriesTheLegs) {
  HexapodDesignSpec spec = test_specs::smooth_spec();
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
    const ActuatorChoice choice = choose_actuator(catalog, {force, stroke, 0.0, 0.0});
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

TEST(HexapodDesign, ActuatorChoiceErrors) {
  HexapodDesignSpec spec = test_specs::smooth_spec();
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
  spec = test_specs::smooth_spec();
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
