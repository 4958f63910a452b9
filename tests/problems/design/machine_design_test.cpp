#include "problems/design/machine_design.hpp"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <random>

#include "models/core/capabilities.hpp"
#include "models/core/machine_sketch.hpp"
#include "models/hexapod/hexapod.hpp"
#include "models/serial/serial_machine.hpp"
#include "problems/design/leg_chain_design.hpp"
#include "problems/design/serial_design.hpp"
#include "tests/sample_machines.hpp"

namespace pkmopt {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// Steel rods, 2e8 N/m carriages, joints within 60 deg.
LinearDeltaDesign linear_delta_template() {
  LinearDeltaDesign t;
  t.stiffness = {0.0, 2.1e11, 1.5e-4, 2.0e8};
  t.carriage_max_angle = deg_to_rad(60);
  t.platform_max_angle = deg_to_rad(60);
  return t;
}

// A linear delta problem: rod, stroke and home_height free, a 3 x 3 x 2 box below the base.
MachineDesignSpec linear_delta_spec() {
  MachineDesignSpec spec;
  spec.name = "linear-delta-test";
  spec.family = linear_delta_family(linear_delta_template());
  spec.parameters = default_ranges(spec.family);
  spec.parameters[static_cast<std::size_t>(spec.family.index_of("rod"))] = {0.4, 0.9};
  spec.parameters[static_cast<std::size_t>(spec.family.index_of("stroke"))] = {0.3, 0.8};
  spec.parameters[static_cast<std::size_t>(spec.family.index_of("home_height"))] = {-0.2, 0.2};
  spec.task.poses = box_task_poses({0, 0, -0.35}, {0.1, 0.1, 0.05}, {3, 3, 2}, 0, 0);
  spec.task.wrench << 300, 300, -1000, 0, 0, 0;
  spec.objectives = {{DesignMetric::stiffness_min, Sense::maximize},
                     {DesignMetric::leg_force_max, Sense::minimize},
                     {DesignMetric::machine_size, Sense::minimize}};
  spec.constraints = {{DesignMetric::singularity_margin, Relation::greater_equal, 0.05},
                      {DesignMetric::tcp_error_max, Relation::less_equal, 1e-4}};
  return spec;
}

// A template design `t` (default: linear_delta_spec's) at x = {rod 0.7, stroke 0.6}.
LinearDeltaDesign design_at_x(LinearDeltaDesign t = linear_delta_template()) {
  t.rod = 0.7;
  t.q_min = 0.0;
  t.q_max = 0.6;
  return t;
}

// design_at_x()'s machine drawn at the spec's task poses lifted by x's home_height (0.1 m).
std::vector<MachineSketch> drawn_at_lifted_poses(const MachineDesignSpec& spec) {
  const std::unique_ptr<Machine> machine = make_linear_delta(design_at_x());
  const auto data = machine->make_data();
  std::vector<MachineSketch> sketches;
  for (Pose pose : spec.task.poses) {
    pose.position.z() += 0.1;
    MachineSketch sketch;
    EXPECT_TRUE(machine->sketch(*data, pose, sketch));
    sketches.push_back(sketch);
  }
  return sketches;
}

TEST(MachineDesign, MetricsAreTheWorstCasesOfMachineAnalyzeOverTheLiftedTask) {
  const MachineDesignProblem problem(linear_delta_spec());
  const std::vector<double> x = {0.7, 0.6, 0.1};  // rod, stroke, home_height
  const MachineDesignEvaluation ev = problem.evaluate(x);
  ASSERT_TRUE(ev.ok()) << ev.failure;
  EXPECT_EQ(ev.analysed_poses, problem.spec().task.poses.size());

  // The same design built directly from the model.
  const std::unique_ptr<Machine> machine = make_linear_delta(design_at_x());
  const auto data = machine->make_data();
  double stiffness = kInf, margin = kInf, force = 0.0, error = 0.0;
  int reachable = 0;
  double reach_sum = 0.0;
  for (Pose pose : problem.spec().task.poses) {
    pose.position.z() += 0.1;
    PoseMetrics m;
    machine->analyze(*data, pose, problem.spec().task.wrench, m);
    ASSERT_FALSE(m.singular);
    stiffness = std::min(stiffness, m.stiffness_min);
    margin = std::min(margin, m.singularity_margin);
    for (int i = 0; i < m.tau.size(); ++i) force = std::max(force, std::abs(m.tau(i)));
    error = std::max(error, m.tcp_error_max);
    reachable += m.reachable ? 1 : 0;
    if (!m.reachable) reach_sum += pose_reach_violation(*machine, pose);
  }
  auto metric = [&](DesignMetric m) { return ev.metrics[static_cast<int>(m)]; };
  EXPECT_EQ(metric(DesignMetric::stiffness_min), stiffness);
  EXPECT_EQ(metric(DesignMetric::singularity_margin), margin);
  EXPECT_EQ(metric(DesignMetric::leg_force_max), force);
  EXPECT_EQ(metric(DesignMetric::tcp_error_max), error);
  EXPECT_EQ(metric(DesignMetric::machine_size), *machine->envelope_volume());
  const double poses = static_cast<double>(problem.spec().task.poses.size());
  EXPECT_EQ(ev.reach_violation, reach_sum / poses);
  EXPECT_EQ(ev.reachable, reachable == static_cast<int>(poses));

  // Rows: maximised objectives flip sign, constraints follow their relation, then reachability.
  const std::vector<double> f = problem.fitness(x);
  ASSERT_EQ(f.size(), 3u + 2u + 1u);
  EXPECT_EQ(f[0], -stiffness);
  EXPECT_EQ(f[1], force);
  EXPECT_EQ(f[2], metric(DesignMetric::machine_size));
  EXPECT_EQ(f[3], 0.05 - margin);
  EXPECT_EQ(f[4], error - 1e-4);
  EXPECT_EQ(f[5], ev.reach_violation);
}

// A linear delta with masses: moving_mass is the platform and the three carriages and rod pairs
// (summed here from the mass model), natural_frequency_min the lowest first frequency over the
// lifted task, computed here from the machine's compliance and TCP mass matrix: the translational
// platform's K_tt = C_tt^-1 and M_tt, f = sqrt(eig(K_tt, M_tt)) / 2 pi.
TEST(MachineDesign, MassModelsGiveNaturalFrequencyAndMovingMass) {
  MachineDesignSpec spec = linear_delta_spec();
  LinearDeltaDesign t = linear_delta_template();
  t.masses.present = true;
  t.masses.platform.mass = 6.0;
  t.masses.platform.inertia = Eigen::Vector3d(0.05, 0.05, 0.08).asDiagonal();
  t.masses.legs.carriage = 2.5;
  t.masses.legs.link = {.mass = 0.8, .centre = 0.35, .inertia = 0.03};
  spec.family = linear_delta_family(t);
  spec.parameters = default_ranges(spec.family);
  spec.parameters[static_cast<std::size_t>(spec.family.index_of("rod"))] = {0.4, 0.9};
  spec.parameters[static_cast<std::size_t>(spec.family.index_of("stroke"))] = {0.3, 0.8};
  spec.parameters[static_cast<std::size_t>(spec.family.index_of("home_height"))] = {-0.2, 0.2};
  spec.objectives = {{DesignMetric::natural_frequency_min, Sense::maximize},
                     {DesignMetric::moving_mass, Sense::minimize}};
  const MachineDesignProblem problem(spec);
  const std::vector<double> x = {0.7, 0.6, 0.1};  // rod, stroke, home_height
  const MachineDesignEvaluation ev = problem.evaluate(x);
  ASSERT_TRUE(ev.ok()) << ev.failure;
  EXPECT_DOUBLE_EQ(ev.metrics[static_cast<int>(DesignMetric::moving_mass)], 6.0 + 3 * (2.5 + 0.8));

  const std::unique_ptr<Machine> machine = make_linear_delta(design_at_x(t));
  const Capability<Dynamics> dynamics = machine->dynamics();
  ASSERT_TRUE(dynamics);
  const auto data = machine->make_data();
  double lowest = kInf;
  for (Pose pose : spec.task.poses) {
    pose.position.z() += 0.1;
    PoseMetrics m;
    machine->analyze(*data, pose, spec.task.wrench, m);
    const Eigen::Matrix3d K = data->matrices.compliance.topLeftCorner<3, 3>().inverse();
    Matrix6d M;
    ASSERT_TRUE(dynamics->mass_matrix(*data, pose, M));
    const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::Matrix3d> eig(K, M.topLeftCorner<3, 3>());
    lowest = std::min(lowest, std::sqrt(eig.eigenvalues()(0)) / (2 * std::numbers::pi));
  }
  EXPECT_NEAR(ev.metrics[static_cast<int>(DesignMetric::natural_frequency_min)] / lowest, 1.0,
              1e-9);
  EXPECT_GT(lowest, 10.0);  // a stiff machine: tens of hertz at least

  // Without masses, and for a model with no mass model, the problem says why before any
  // evaluation.
  spec.family = linear_delta_family(LinearDeltaDesign{});
  spec.parameters = default_ranges(spec.family);
  for (const DesignMetric metric :
       {DesignMetric::natural_frequency_min, DesignMetric::moving_mass}) {
    spec.objectives = {{metric, Sense::maximize}};
    try {
      MachineDesignProblem refused(spec);
      ADD_FAILURE() << "no exception";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(std::string(design_metric_name(metric)) +
                                           " needs a mass model: the machine file has no 'masses'"),
                std::string::npos)
          << e.what();
    }
  }
}

// An installation space: at every lifted task pose the drawn machine (its lines' ends, joints,
// TCP) must lie inside; how far it sticks out (here from the sketch points and the box, by hand),
// at most 1 m per pose, joins the reach row. A box that holds everything changes nothing.
TEST(MachineDesign, InstallationSpaceHoldsTheDrawnMachine) {
  MachineDesignSpec spec = linear_delta_spec();
  const std::vector<double> x = {0.7, 0.6, 0.1};  // rod, stroke, home_height
  const MachineDesignEvaluation free = MachineDesignProblem(spec).evaluate(x);
  ASSERT_TRUE(free.ok()) << free.failure;

  std::vector<std::vector<Eigen::Vector3d>> drawn;
  double lowest = kInf;
  for (const MachineSketch& sketch : drawn_at_lifted_poses(spec)) {
    std::vector<Eigen::Vector3d> points = {sketch.tcp};
    for (const MachineSketch::Line& line : sketch.lines) {
      points.push_back(line.from);
      points.push_back(line.to);
    }
    for (const auto& p : sketch.base_joints) points.push_back(p);
    for (const auto& p : sketch.platform_joints) points.push_back(p);
    for (const auto& p : points) lowest = std::min(lowest, p.z());
    drawn.push_back(points);
  }
  // A floor 30 mm above the lowest drawn point (the tool tip at the lowest poses).
  spec.task.installation_space.kind = InstallationSpace::Kind::kBox;
  spec.task.installation_space.min = Eigen::Vector3d(-5, -5, lowest + 0.03);
  spec.task.installation_space.max = Eigen::Vector3d(5, 5, 5);
  double sticking_out = 0.0;
  for (const auto& points : drawn) {
    double worst = -kInf;
    for (const auto& p : points) worst = std::max(worst, lowest + 0.03 - p.z());
    sticking_out += std::min(1.0, std::max(0.0, worst));
  }
  ASSERT_GT(sticking_out, 0.0);
  const MachineDesignEvaluation boxed = MachineDesignProblem(spec).evaluate(x);
  EXPECT_NEAR(boxed.reach_violation,
              free.reach_violation + sticking_out / static_cast<double>(drawn.size()), 1e-12);
  EXPECT_FALSE(boxed.reachable);
  spec.task.installation_space.min.z() = -5;
  EXPECT_EQ(MachineDesignProblem(spec).evaluate(x).reach_violation, free.reach_violation);
}

// Linear motors for the carriages: the choice is the cheapest entry whose force rating and stroke
// carry the largest carriage force over the task and the carriage travel, checked here against
// the same design analysed by hand; the delta's cranks are refused.
TEST(MachineDesign, CarriagesGetTheCheapestCatalogEntryThatCarriesThem) {
  MachineDesignSpec spec = linear_delta_spec();
  ActuatorCatalog catalog;
  catalog.name = "motors";
  catalog.entries = {{"weak-long", "linear_motor", 100.0, 1.0, 3.0, {}, {}, 1.0, {}},
                     {"strong-short", "linear_motor", 5000.0, 0.4, 3.0, {}, {}, 2.0, {}},
                     {"strong-long", "linear_motor", 5000.0, 1.0, 3.0, {}, {}, 5.0, {}},
                     {"strongest-long", "linear_motor", 9000.0, 1.0, 3.0, {}, {}, 9.0, {}}};
  spec.actuator_catalog = catalog;
  spec.objectives.push_back({DesignMetric::actuator_cost, Sense::minimize});
  spec.constraints.push_back({DesignMetric::actuator_overload, Relation::less_equal, 0.0});
  const MachineDesignProblem problem(spec);
  auto metric = [](const MachineDesignEvaluation& ev, DesignMetric m) {
    return ev.metrics[static_cast<int>(m)];
  };
  // Stroke 0.6 m: the short entry is out; the force (about 1 kN) is beyond the weak one.
  const MachineDesignEvaluation ev = problem.evaluate({0.7, 0.6, 0.1});
  ASSERT_TRUE(ev.ok()) << ev.failure;
  const double force = metric(ev, DesignMetric::leg_force_max);
  ASSERT_GT(force, 100.0);
  ASSERT_LT(force, 5000.0);
  EXPECT_EQ(ev.actuator, 2);  // strong-long
  EXPECT_EQ(metric(ev, DesignMetric::actuator_cost), 5.0);
  EXPECT_EQ(metric(ev, DesignMetric::actuator_overload), force - 9000.0);  // the best long entry
  EXPECT_EQ(problem.measure({0.7, 0.6, 0.1}).actuator, 2);
  // Stroke 0.35 m: the short strong entry carries it and is cheaper.
  const MachineDesignEvaluation short_stroke = problem.evaluate({0.7, 0.35, 0.1});
  ASSERT_TRUE(short_stroke.ok()) << short_stroke.failure;
  EXPECT_EQ(short_stroke.actuator, 1);
  EXPECT_EQ(metric(short_stroke, DesignMetric::actuator_cost), 2.0);
  // Only the chosen drives count: none of a nonexistent drive.
  MachineDesignSpec wrong_drive = spec;
  wrong_drive.actuator_drives = {3};
  EXPECT_THROW(MachineDesignProblem{wrong_drive}, std::invalid_argument);
  // Without a catalog the actuator metrics are refused; a delta's cranks take no linear drive.
  MachineDesignSpec no_catalog = spec;
  no_catalog.actuator_catalog.reset();
  EXPECT_THROW(MachineDesignProblem{no_catalog}, std::invalid_argument);
  MachineDesignSpec delta;
  delta.family = delta_family(DeltaDesign{});
  delta.parameters = default_ranges(delta.family);
  delta.task.poses = box_task_poses({0, 0, -0.8}, {0.05, 0.05, 0.05}, {2, 2, 2}, 0, 0);
  delta.objectives = {{DesignMetric::actuator_cost, Sense::minimize}};
  delta.actuator_catalog = catalog;
  EXPECT_THROW(MachineDesignProblem{delta}, std::invalid_argument);
}

// Obstacles: at every lifted task pose the drawn machine (its lines but the tool's, its joints)
// must keep out; how deep it goes in (here from the drawing, by hand: a column around the first
// guide's middle, which every pose draws through it), at most 1 m per pose, joins the reach row.
TEST(MachineDesign, ObstaclesKeepTheDrawnMachineOut) {
  MachineDesignSpec spec = linear_delta_spec();
  const std::vector<double> x = {0.7, 0.6, 0.1};  // rod, stroke, home_height
  const MachineDesignEvaluation free = MachineDesignProblem(spec).evaluate(x);
  ASSERT_TRUE(free.ok()) << free.failure;
  const std::vector<MachineSketch> sketches = drawn_at_lifted_poses(spec);
  const MachineSketch::Line& guide = sketches.front().lines.front();
  ASSERT_EQ(guide.part, MachineSketch::Part::kGuide);
  const Eigen::Vector3d mid = 0.5 * (guide.from + guide.to);
  const ObstacleBox column{mid - Eigen::Vector3d(0.02, 0.02, 0.01),
                           mid + Eigen::Vector3d(0.02, 0.02, 0.01)};
  // The fixed guide goes 10 mm deep into the column at every pose (its z half-extent); nothing
  // else of the drawing comes closer.
  double intruding = 0.0;
  for (const MachineSketch& sketch : sketches) {
    double deepest = -kInf;
    for (const MachineSketch::Line& line : sketch.lines)
      if (line.part != MachineSketch::Part::kTool)
        deepest = std::max(deepest, intrusion(column, line.from, line.to));
    for (const auto& p : sketch.base_joints) deepest = std::max(deepest, depth(column, p));
    for (const auto& p : sketch.platform_joints) deepest = std::max(deepest, depth(column, p));
    EXPECT_NEAR(deepest, 0.01, 1e-12);
    intruding += std::min(1.0, std::max(0.0, deepest));
  }
  spec.task.obstacles = {column};
  const MachineDesignEvaluation blocked = MachineDesignProblem(spec).evaluate(x);
  EXPECT_NEAR(blocked.reach_violation,
              free.reach_violation + intruding / static_cast<double>(spec.task.poses.size()),
              1e-12);
  EXPECT_FALSE(blocked.reachable);
  // Moved 2 m aside, it is out of every drawing.
  spec.task.obstacles[0].min.x() += 2.0;
  spec.task.obstacles[0].max.x() += 2.0;
  EXPECT_EQ(MachineDesignProblem(spec).evaluate(x).reach_violation, free.reach_violation);
  // An empty box is refused.
  spec.task.obstacles[0].max.x() = spec.task.obstacles[0].min.x();
  EXPECT_THROW(MachineDesignProblem{spec}, std::invalid_argument);
}

// A catalog pricing every drive: ball-screw axes and cylinders, servo and torque motors.
ActuatorCatalog every_drive_catalog() {
  ActuatorCatalog c;
  c.name = "every-drive";
  c.entries = {{"axis-600", "ball_screw_axis", 3000.0, 0.6, 0.5, {}, {}, 3.0, {}},
               {"axis-1000", "ball_screw_axis", 3000.0, 1.0, 0.5, {}, {}, 4.0, {}},
               {"axis-1000-hd", "ball_screw_axis", 8000.0, 1.0, 0.5, {}, {}, 7.0, {}},
               {"cyl-300", "electric_cylinder", 10000.0, 0.3, 0.4, {}, {}, 2.5, {}}};
  c.rotary_entries = {{"servo-50", "gear_motor", 50.0, {}, 300.0, 2.0},
                      {"servo-200", "gear_motor", 200.0, {}, 200.0, 5.0},
                      {"torque-1000", "torque_motor", 1000.0, {}, 100.0, 12.0}};
  return c;
}

// Every drive priced: a C/A fork head's X, Y and Z get linear entries by their own force and
// travel, its C and A rotary ones by their torque, each axis alone; the sum is recomputed here
// from the drives' loads at the task poses.
TEST(MachineDesign, EveryDrivePricedFromItsLoadsAndTravel) {
  SerialDesign t;
  t.chain = SerialChain::from_code("123646");
  t.spindle = 5;
  t.axes = {{.min = -0.4, .max = 0.4, .stiffness = 1.5e8},
            {.min = -0.4, .max = 0.4, .stiffness = 1.5e8},
            {.min = -0.1, .max = 0.6, .stiffness = 1.2e8},
            {.min = -200 * M_PI / 180, .max = 200 * M_PI / 180, .stiffness = 1e6},
            {.min = -100 * M_PI / 180, .max = 100 * M_PI / 180, .stiffness = 1e6}};
  t.tool_point = {0, 0, -0.25};
  t.characteristic_length = 0.2;
  MachineDesignSpec spec;
  spec.name = "every-drive";
  spec.family = serial_family(t);
  spec.parameters = default_ranges(spec.family);
  spec.parameters[0] = {0.8, 1.2};  // x_travel
  const std::unique_ptr<Machine> machine = spec.family.build(spec.family.default_parameters());
  // The task: poses the template reaches, with tilted tools.
  sample_machines::Uniform u(4);
  for (int k = 0; k < 12; ++k) {
    Eigen::VectorXd q(5);
    q << u(-0.3, 0.3), u(-0.3, 0.3), u(0.0, 0.5), u(-1.0, 1.0), u(-0.3, 0.3);
    spec.task.poses.push_back(machine->forward_kinematics(q, std::nullopt).pose);
  }
  spec.task.wrench << -2455, 982, 1228, 0, 0, -77;
  spec.objectives = {{DesignMetric::drive_cost, Sense::minimize},
                     {DesignMetric::tcp_deflection_max, Sense::minimize}};
  spec.constraints = {{DesignMetric::drive_overload, Relation::less_equal, 0.0}};
  spec.actuator_catalog = every_drive_catalog();
  spec.each_drive = true;
  const MachineDesignProblem problem(spec);
  const MachineDesignEvaluation ev = problem.evaluate({0.8});
  ASSERT_TRUE(ev.ok()) << ev.failure;
  ASSERT_TRUE(ev.reachable);
  // The drives' largest loads over the task, and each axis's entry by brute force.
  const std::unique_ptr<MachineData> data = machine->make_data();
  Eigen::VectorXd load = Eigen::VectorXd::Zero(5);
  for (const Pose& pose : spec.task.poses) {
    PoseMetrics m;
    machine->analyze(*data, pose, spec.task.wrench, m);
    ASSERT_TRUE(m.reachable);
    load = load.cwiseMax(m.tau.cwiseAbs());
  }
  const ActuatorCatalog& c = *spec.actuator_catalog;
  double cost = 0.0, overload = -kInf;
  for (int i = 0; i < 5; ++i) {
    double best = kInf, least = kInf;
    if (i < 3) {
      const SerialAxis& a = t.axes[static_cast<std::size_t>(i)];
      const double travel = i == 0 ? 0.8 : a.max - a.min;
      for (const ActuatorEntry& e : c.entries) {
        const double r = std::max(load(i) / e.max_force, travel / e.stroke) - 1.0;
        least = std::min(least, r);
        if (r <= 0.0) best = std::min(best, *e.cost);
      }
    } else {
      for (const RotaryEntry& e : c.rotary_entries) {
        least = std::min(least, load(i) / e.max_torque - 1.0);
        if (load(i) <= e.max_torque) best = std::min(best, *e.cost);
      }
    }
    cost += std::isfinite(best) ? best : 24.0;  // none: twice the dearest (12)
    overload = std::max(overload, least);
  }
  const double drive_cost = ev.metrics[static_cast<int>(DesignMetric::drive_cost)];
  EXPECT_NEAR(drive_cost, cost, 1e-12);
  EXPECT_NEAR(ev.metrics[static_cast<int>(DesignMetric::drive_overload)], overload, 1e-12);
  // The loads are of the milling load's size: the axes carry kN, the C/A axes tens of N*m; X, Y
  // and Z are priced alone although two have equal travel.
  EXPECT_GT(load.head<3>().maxCoeff(), 1000.0);
  EXPECT_GT(load.tail<2>().maxCoeff(), 10.0);
  EXPECT_EQ(drive_group_needs(*machine, load).size(), 5u);
  // The one-entry metrics are refused with each_drive, the every-drive ones without it; a
  // revolute drive needs rotary entries.
  MachineDesignSpec one_entry = spec;
  one_entry.objectives.push_back({DesignMetric::actuator_cost, Sense::minimize});
  EXPECT_THROW(MachineDesignProblem{one_entry}, std::invalid_argument);
  MachineDesignSpec no_each = spec;
  no_each.each_drive = false;
  EXPECT_THROW(MachineDesignProblem{no_each}, std::invalid_argument);
  MachineDesignSpec no_rotary = spec;
  no_rotary.actuator_catalog->rotary_entries.clear();
  EXPECT_THROW(MachineDesignProblem{no_rotary}, std::invalid_argument);
}

// A parallel machine's alike legs are one group: the linear delta's three carriages cost three
// times the entry that carries the most loaded one.
TEST(MachineDesign, AlikeLegsArePricedAsOneEntry) {
  MachineDesignSpec spec = linear_delta_spec();
  spec.actuator_catalog = every_drive_catalog();
  spec.each_drive = true;
  spec.objectives.push_back({DesignMetric::drive_cost, Sense::minimize});
  const MachineDesignProblem problem(spec);
  const MachineDesignEvaluation ev = problem.evaluate({0.7, 0.6, 0.1});
  ASSERT_TRUE(ev.ok()) << ev.failure;
  const double force = ev.metrics[static_cast<int>(DesignMetric::leg_force_max)];
  ASSERT_LT(force, 3000.0);  // axis-600 (stroke 0.6 rules out the cylinder)
  EXPECT_EQ(ev.metrics[static_cast<int>(DesignMetric::drive_cost)], 3 * 3.0);
  const MachineDesignEvaluation longer = problem.evaluate({0.7, 0.65, 0.1});
  ASSERT_TRUE(longer.ok()) << longer.failure;
  ASSERT_LT(longer.metrics[static_cast<int>(DesignMetric::leg_force_max)], 3000.0);
  EXPECT_EQ(longer.metrics[static_cast<int>(DesignMetric::drive_cost)], 3 * 4.0);  // axis-1000
}

TEST(MachineDesign, FailuresGivePenaltyRowsAndAReason) {
  {  // an impossible machine: the drive range is empty
    MachineDesignSpec spec;
    spec.family = delta_family(DeltaDesign{});
    spec.parameters = default_ranges(spec.family);
    spec.parameters[4] = {deg_to_rad(-10), deg_to_rad(50)};  // drive_min_deg free
    spec.parameters[5] = {deg_to_rad(0), deg_to_rad(0)};     // drive_max_deg fixed at 0
    spec.task.poses = {Pose{{0, 0, -1.0}, {0, 0, 0}}};
    spec.objectives = {{DesignMetric::stiffness_min, Sense::maximize}};
    const MachineDesignProblem problem(spec);
    const MachineDesignEvaluation ev = problem.evaluate({deg_to_rad(20)});
    EXPECT_NE(ev.failure.find("invalid machine"), std::string::npos) << ev.failure;
    for (double v : problem.fitness({deg_to_rad(20)})) EXPECT_EQ(v, kFailurePenalty);
    EXPECT_TRUE(problem.evaluate({deg_to_rad(-10)}).ok());
  }
  {  // a task out of reach of every rod (5 m aside): nothing to analyse
    MachineDesignSpec spec = linear_delta_spec();
    spec.task.poses = box_task_poses({5.0, 0, -0.4}, {0.1, 0.1, 0.1}, {2, 2, 2}, 0, 0);
    const MachineDesignProblem problem(spec);
    const MachineDesignEvaluation ev = problem.evaluate({0.7, 0.6, 0.0});
    EXPECT_EQ(ev.analysed_poses, 0u);
    EXPECT_EQ(ev.reach_violation, 1.0);
    EXPECT_NE(ev.failure.find("no task pose"), std::string::npos) << ev.failure;
    for (double v : problem.fitness({0.7, 0.6, 0.0})) EXPECT_EQ(v, kFailurePenalty);
  }
  {  // part of the task beyond the stroke: infeasible but measured, g_reach = the fraction
    MachineDesignSpec spec = linear_delta_spec();
    const MachineDesignProblem problem(spec);
    const MachineDesignEvaluation ev = problem.evaluate({0.9, 0.3, -0.2});
    ASSERT_TRUE(ev.ok()) << ev.failure;
    EXPECT_GT(ev.reach_violation, 0.0);
    EXPECT_LT(ev.reach_violation, 1.0);
    EXPECT_FALSE(ev.reachable);
    EXPECT_EQ(problem.fitness({0.9, 0.3, -0.2}).back(), ev.reach_violation);
  }
}

TEST(MachineDesign, ReachViolationIsTheExcessOverTheStrokeOrJointLimit) {
  LinearDeltaDesign d;  // vertical guides, stroke [0, 0.6], joints unlimited
  const Pose pose{{0.05, -0.02, -0.1}, {0, 0, 0}};
  const auto reference = std::make_unique<LegChainMachine>(linear_delta_design(d));
  const std::optional<Eigen::VectorXd> q = reference->inverse_kinematics(pose);
  ASSERT_TRUE(q.has_value());
  ASSERT_TRUE(reference->reachable(*reference->make_data(), pose));
  d.q_max = q->maxCoeff() - 0.02;  // the highest carriage now misses by 20 mm
  EXPECT_NEAR(pose_reach_violation(*make_linear_delta(d), pose), 0.02, 1e-12);
  d.q_max = q->maxCoeff() - 2.0;  // capped at 1
  d.q_min = d.q_max - 0.5;
  EXPECT_EQ(pose_reach_violation(*make_linear_delta(d), pose), 1.0);
  d = LinearDeltaDesign{};
  Eigen::VectorXd base_angles, platform_angles;
  reference->joint_angles(pose, base_angles, platform_angles);
  d.carriage_max_angle = base_angles.maxCoeff() - 0.01;  // 0.01 rad over the carriage limit
  EXPECT_NEAR(pose_reach_violation(*make_linear_delta(d), pose), 0.01, 1e-12);
  // A pose no rod reaches.
  EXPECT_EQ(pose_reach_violation(*reference, Pose{{5, 0, -0.4}, {0, 0, 0}}), 1.0);
}

// A linear delta with rods of a diameter: leg_clearance_min is the smallest clearance of the
// built machine over the lifted task; a pose whose rods are closer than min_clearance misses by
// the gap. Without a link shape the metric is refused.
TEST(MachineDesign, LegChainLinksGiveLegClearanceMin) {
  MachineDesignSpec spec = linear_delta_spec();
  spec.objectives.push_back({DesignMetric::leg_clearance_min, Sense::maximize});
  EXPECT_THROW(MachineDesignProblem{spec}, std::invalid_argument);
  LinearDeltaDesign t;
  t.stiffness = {0.0, 2.1e11, 1.5e-4, 2.0e8};
  t.carriage_max_angle = t.platform_max_angle = deg_to_rad(60);
  t.shapes.link_diameter = 0.03;
  spec.family = linear_delta_family(t);
  const MachineDesignProblem problem(spec);
  const std::vector<double> x = {0.7, 0.6, 0.1};  // rod, stroke, home_height
  const MachineDesignEvaluation ev = problem.evaluate(x);
  ASSERT_TRUE(ev.ok()) << ev.failure;
  LinearDeltaDesign d = t;
  d.rod = 0.7;
  d.q_max = 0.6;
  const LegChainMachine machine(linear_delta_design(d));
  double clearance = kInf;
  for (Pose pose : problem.spec().task.poses) {
    pose.position.z() += 0.1;
    clearance = std::min(clearance, machine.leg_clearance(pose).value);
  }
  EXPECT_EQ(ev.metrics[static_cast<int>(DesignMetric::leg_clearance_min)], clearance);
  EXPECT_GT(clearance, 0.0);
  // A min_clearance beyond the clearance at a pose: that pose misses by the difference.
  const Pose pose{{0.05, -0.02, -0.1}, {0, 0, 0}};
  d.shapes.min_clearance = machine.leg_clearance(pose).value + 0.003;
  const LegChainMachine tight(linear_delta_design(d));
  EXPECT_FALSE(tight.reachable(*tight.make_data(), pose));
  EXPECT_NEAR(pose_reach_violation(tight, pose), 0.003, 1e-12);
}

TEST(MachineDesign, SpecErrorsNameTheField) {
  MachineDesignSpec spec = linear_delta_spec();
  spec.parameters.pop_back();
  EXPECT_THROW(MachineDesignProblem{spec}, std::invalid_argument);
  spec = linear_delta_spec();
  spec.objectives.clear();
  EXPECT_THROW(MachineDesignProblem{spec}, std::invalid_argument);
  spec = linear_delta_spec();
  spec.parameters[0] = {0.5, 0.4};
  try {
    MachineDesignProblem problem(spec);
    ADD_FAILURE() << "no exception";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("guide_radius"), std::string::npos) << e.what();
  }
  // The catalog actuator metrics belong to hexapod problems (they choose from a catalog).
  spec = linear_delta_spec();
  spec.objectives.push_back({DesignMetric::actuator_cost, Sense::minimize});
  try {
    MachineDesignProblem problem(spec);
    ADD_FAILURE() << "no exception";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("actuator_cost needs an actuator catalog"),
              std::string::npos)
        << e.what();
  }
}

TEST(MachineDesign, BatchesAreBitIdenticalOnOneAndTwoThreads) {
  MachineDesignSpec spec = linear_delta_spec();
  spec.objectives.push_back({DesignMetric::workspace_volume, Sense::maximize});
  spec.task.workspace.resolution = 0.1;
  const MachineDesignProblem problem(spec);
  std::mt19937_64 engine(7);
  const Bounds b = problem.bounds();
  std::vector<std::vector<double>> xs(6);
  for (auto& x : xs)
    for (std::size_t j = 0; j < b.lower.size(); ++j)
      x.push_back(b.lower[j] +
                  (b.upper[j] - b.lower[j]) * static_cast<double>(engine() >> 11) * 0x1.0p-53);
  const auto serial = problem.batch_fitness(xs, 1);
  const auto parallel = problem.batch_fitness(xs, 2);
  ASSERT_EQ(serial.size(), parallel.size());
  for (std::size_t k = 0; k < xs.size(); ++k) {
    EXPECT_EQ(serial[k], parallel[k]) << k;
    EXPECT_EQ(serial[k], problem.fitness(xs[k])) << k;
  }
}

}  // namespace
}  // namespace pkmopt
