// Tests of models/leg_chain/lathe_conversion: the 16K20F3 lathe conversion (2-PUS + 2-UPS
// Schoenflies mechanism about the spindle axis x), the seeds' strut-length formula, the task and
// the minimal strut length.
#include "models/leg_chain/lathe_conversion.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

#include "models/geometry/segment_distance.hpp"
#include "problems/design/cutting_load.hpp"

namespace pkmopt {
namespace {

// The poses of the test: the task's corners and centre (tool tip, approach angle a0) and a few
// with the turret turned about x (rx = phi).
std::vector<Pose> sample_poses() {
  std::vector<Pose> poses =
      lathe_task_poses(LatheTask{{-0.5, 0.0, 0.0}, {0.5, 0.4, 0.18}, {2, 2, 2}});
  poses.push_back(Pose{{0.1, 0.2, 0.09}, Eigen::Vector3d::Zero()});
  poses.push_back(Pose{{-0.3, 0.15, 0.05}, Eigen::Vector3d(deg_to_rad(5.0), 0.0, 0.0)});
  poses.push_back(Pose{{0.25, 0.3, 0.12}, Eigen::Vector3d(deg_to_rad(-8.0), 0.0, 0.0)});
  return poses;
}

// The seeds' turning case (problems/design/cutting_load.hpp): 6633 N at the optimal approach angle.
Wrench turning_wrench() {
  TurningConditions c;
  c.diameter_mm = 120;
  c.depth_mm = 3;
  c.feed_mm_per_rev = 0.84;
  c.tool_life_min = 60;
  c.C_v = 340;
  c.x_v = 0.15;
  c.y_v = 0.45;
  c.m = 0.2;
  c.K_v = 0.85;
  c.C_p = 200;
  c.x_p = 1;
  c.y_p = 0.75;
  c.n_p = 0;
  c.K_p = 1.0 * 0.98 * 1.15;
  const TurningLoad load = turning_load(c);
  Wrench w = Wrench::Zero();
  w.head<3>() = turning_machine_force(load, optimal_approach_angle(load));
  return w;
}

TEST(LatheConversion, DesignIsASchoenfliesMachineAboutTheSpindleAxis) {
  const LegChainDesign design = lathe_16k20f3_design(Lathe16k20f3Design{});
  EXPECT_EQ(design.model, "lathe_16k20f3");
  EXPECT_EQ(design.mobility, PlatformMobility::kSchoenflies);
  EXPECT_EQ(design.rotation_axis, Eigen::Vector3d::UnitX());
  ASSERT_EQ(design.legs.size(), 4u);
  EXPECT_EQ(design.legs[0].kind, LegKind::kPUS);
  EXPECT_EQ(design.legs[1].kind, LegKind::kPUS);
  EXPECT_EQ(design.legs[2].kind, LegKind::kUPS);
  EXPECT_EQ(design.legs[3].kind, LegKind::kUPS);
  EXPECT_EQ(design.legs[0].rods, 2);
  // The tool tip at tool_reach from the turret centre, pointing at the axis from angle a0.
  EXPECT_NEAR(design.tcp.norm(), 0.16, 1e-15);
  EXPECT_NEAR(std::atan2(-design.tcp.z(), -design.tcp.y()), std::atan(0.5), 1e-15);
}

TEST(LatheConversion, TwistJacobianMatchesFiniteDifferencesOfTheIk) {
  const Lathe16k20f3Design d;
  const LegChainMachine machine(lathe_16k20f3_design(d));
  const auto data = machine.make_data();
  const double h = 1e-6;
  for (const Pose& pose : sample_poses()) {
    Eigen::MatrixXd J;
    ASSERT_TRUE(machine.twist_jacobian(*data, pose, J));
    ASSERT_EQ(J.rows(), 4);
    ASSERT_EQ(J.cols(), 6);
    // DOF twists: v along x, y, z and omega about x (the platform's only rotation).
    for (int k = 0; k < 4; ++k) {
      Pose plus = pose, minus = pose;
      if (k < 3) {
        plus.position(k) += h;
        minus.position(k) -= h;
      } else {
        plus.angles(0) += h;
        minus.angles(0) -= h;
      }
      const auto q_plus = machine.inverse_kinematics(plus);
      const auto q_minus = machine.inverse_kinematics(minus);
      ASSERT_TRUE(q_plus && q_minus);
      const Eigen::VectorXd fd = (*q_plus - *q_minus) / (2 * h);
      const Eigen::VectorXd analytic = J.col(k);
      EXPECT_LT((fd - analytic).cwiseAbs().maxCoeff(), 1e-7) << "DOF " << k;
    }
  }
}

TEST(LatheConversion, ForwardKinematicsInvertsTheIk) {
  const LegChainMachine machine(lathe_16k20f3_design(Lathe16k20f3Design{}));
  for (const Pose& pose : sample_poses()) {
    const auto q = machine.inverse_kinematics(pose);
    ASSERT_TRUE(q);
    // Start 20 mm and 2 deg away.
    Pose guess = pose;
    guess.position += Eigen::Vector3d(0.02, -0.02, 0.02);
    guess.angles(0) += deg_to_rad(2.0);
    const FkResult fk = machine.forward_kinematics(*q, guess);
    ASSERT_TRUE(fk.converged) << fk.message;
    EXPECT_LT((fk.pose.position - pose.position).norm(), 1e-10);
    EXPECT_NEAR(fk.pose.angles(0), pose.angles(0), 1e-10);
    EXPECT_NEAR(fk.pose.angles(1), 0.0, 1e-12);
    EXPECT_NEAR(fk.pose.angles(2), 0.0, 1e-12);
  }
}

TEST(LatheConversion, SeedsFormulaIsTheDistanceToTheFarCorner) {
  // A Pythagorean quadruple: 2^2 + 3^2 + 6^2 = 7^2 (dm).
  SeedsStrutInputs in;
  in.X_K = 0.2;
  in.D_max = 0.32;
  in.Y_D = 0.05;
  in.Y_xx = 0.02;
  in.Y_I = -0.07;  // 0.05 + 0.16 + 0.02 + 0.07 = 0.30
  in.Z_D = 0.10;
  in.Z_xx = 0.03;
  in.Z_I = -0.31;  // 0.10 + 0.16 + 0.03 + 0.31 = 0.60
  EXPECT_NEAR(seeds_strut_length(in), 0.7, 1e-15);
}

// The formula's inputs as the conversion study defines them, read off the design by hand: the
// part axis from the hinge line (0.10, -0.175), the tool tip from the strut joint
// (0.16 (cos a0, sin a0) + (0.15, -0.10), a0 = arccot 2), the 70 deg hinge limit giving X_K.
TEST(LatheConversion, SeedsInputsAreReadOffTheDesignAsTheStudyDefinesThem) {
  const Lathe16k20f3Design d;
  const SeedsStrutInputs in = seeds_strut_inputs(d, 0.32, 0.02, 0.02);
  EXPECT_DOUBLE_EQ(in.Y_D, -0.10);
  EXPECT_DOUBLE_EQ(in.Z_D, 0.175);
  EXPECT_NEAR(in.Y_I, -(0.16 * 2.0 / std::sqrt(5.0) + 0.15), 1e-15);
  EXPECT_NEAR(in.Z_I, -(0.16 / std::sqrt(5.0) - 0.10), 1e-15);
  const double dy = -0.10 + 0.18 + 0.16 * 2.0 / std::sqrt(5.0) + 0.15;
  const double dz = 0.175 + 0.18 + 0.16 / std::sqrt(5.0) - 0.10;
  const double s70 = std::sin(70.0 * std::numbers::pi / 180.0);
  const SeedsStrutLength l = seeds_strut_length_at_inclination(in, d.strut_max_angle);
  EXPECT_NEAR(l.length, std::hypot(dy, dz) / s70, 1e-15);
  EXPECT_NEAR(l.X_K, l.length * std::cos(70.0 * std::numbers::pi / 180.0), 1e-15);
  // With that X_K the formula itself gives the same length (the strut at 70 deg to the guide).
  SeedsStrutInputs with_x = in;
  with_x.X_K = l.X_K;
  EXPECT_NEAR(seeds_strut_length(with_x), l.length, 1e-15);
  EXPECT_NEAR(l.length, 0.52765, 1e-5);  // the README's step 1, by hand: sqrt(0.24587) / sin 70
}

TEST(LatheConversion, MinimalStrutLengthReachesTheTaskAndOnePercentLessDoesNot) {
  const Lathe16k20f3Design d;
  const std::vector<Pose> task = lathe_task_poses(LatheTask{});
  const auto l_min = minimal_strut_length(d, task, 0.2, 0.8, 1e-6);
  ASSERT_TRUE(l_min);
  Lathe16k20f3Design at = d;
  at.strut_length = *l_min;
  EXPECT_TRUE(lathe_reaches(at, task));
  at.strut_length = 0.99 * *l_min;
  EXPECT_FALSE(lathe_reaches(at, task));
  // The study's region (tip up to D_max/2 + 20 mm in y and z) needs 0.5277 m (README, step 2),
  // what the study's formula gives with its own definitions.
  const auto l_seeds = minimal_strut_length(
      d, lathe_task_poses(LatheTask{{-0.5, 0.0, 0.0}, {0.5, 0.18, 0.18}, {5, 5, 5}}), 0.2, 0.8,
      1e-6);
  ASSERT_TRUE(l_seeds);
  // Regression pin (not an independent check): value from `minimal_strut_length(
  // Lathe16k20f3Design{}, lathe_task_poses(LatheTask{{-0.5, 0, 0}, {0.5, 0.18, 0.18}, {5, 5, 5}}),
  // 0.2, 0.8, 1e-6)`, the call above (README, step 2).
  EXPECT_NEAR(*l_seeds, 0.52765, 2e-5);
  EXPECT_NEAR(
      *l_seeds,
      seeds_strut_length_at_inclination(seeds_strut_inputs(d, 0.32, 0.02, 0.02), d.strut_max_angle)
          .length,
      2e-5);
  // The 400 mm cross travel: the formula with the travel in place of the largest part's radius
  // and clearance (Y_xx = 0.40 - 0.16) gives the task's minimal strut.
  EXPECT_NEAR(
      *l_min,
      seeds_strut_length_at_inclination(seeds_strut_inputs(d, 0.32, 0.24, 0.02), d.strut_max_angle)
          .length,
      2e-5);
  // Too short an upper end: nothing found.
  EXPECT_FALSE(minimal_strut_length(d, task, 0.1, 0.2, 1e-6));
}

// The axial cutting force along x (0.2 of P_z in the tool frame here, 0.2 of the machine-frame
// force in the conversion study; README, step 3) is carried by the two carriages alone, half
// each: the cylinders' forces do not change with it.
TEST(LatheConversion, TheAxialForceGoesToTheCarriagesOnly) {
  const auto machine = make_lathe_16k20f3(Lathe16k20f3Design{});
  auto data = machine->make_data();
  const double tool_frame = 1186.63, machine_frame = 0.2 * 6633.45;
  for (const Pose& pose : lathe_task_poses(LatheTask{})) {
    PoseMetrics a, b;
    machine->analyze(*data, pose, (Wrench() << tool_frame, 0, 6633.45, 0, 0, 0).finished(), a);
    machine->analyze(*data, pose, (Wrench() << machine_frame, 0, 6633.45, 0, 0, 0).finished(), b);
    ASSERT_TRUE(a.reachable);
    for (int i : {2, 3}) EXPECT_NEAR(b.tau(i), a.tau(i), 1e-9 * std::abs(a.tau(i)));
    for (int i : {0, 1})
      EXPECT_NEAR(std::abs(b.tau(i) - a.tau(i)), 0.5 * (machine_frame - tool_frame), 1e-6);
  }
}

TEST(LatheConversion, LegForcesBalanceTheTurningLoadByVirtualWork) {
  const Wrench w = turning_wrench();
  ASSERT_NEAR(w.head<3>().tail<2>().norm(), 6633.0, 1.0);  // the seeds' 6633 N (y, z plane)
  const LegChainMachine machine(lathe_16k20f3_design(Lathe16k20f3Design{}));
  const auto data = machine.make_data();
  const double h = 1e-6;
  for (const Pose& pose : sample_poses()) {
    PoseMetrics m;
    machine.analyze(*data, pose, w, m);
    ASSERT_TRUE(m.tau.allFinite());
    // For each DOF twist xi (finite differences of the IK give q_dot), the actuators' power
    // tau . q_dot equals the load's power w . (v, omega e).
    for (int k = 0; k < 4; ++k) {
      Pose plus = pose, minus = pose;
      Vector6d twist = Vector6d::Zero();
      if (k < 3) {
        plus.position(k) += h;
        minus.position(k) -= h;
        twist(k) = 1.0;
      } else {
        plus.angles(0) += h;
        minus.angles(0) -= h;
        twist(3) = 1.0;
      }
      const Eigen::VectorXd q_dot =
          (*machine.inverse_kinematics(plus) - *machine.inverse_kinematics(minus)) / (2 * h);
      EXPECT_NEAR(m.tau.dot(q_dot), w.dot(twist), 1e-4 * w.norm()) << "DOF " << k;
    }
  }
}

// The drive trains and joints are springs in series: a nut and a bearing in the carriage drive
// act as a softer carriage_stiffness, a cylinder's nut and joints as a softer
// leg_actuator_stiffness, and the struts' joints (per rod, constant strut length) as a thinner
// rod. The machines must agree on every metric of the compliance.
TEST(LatheConversion, DriveTrainsAndJointsAddInSeries) {
  Lathe16k20f3Design chain;
  chain.carriage_drive.nut_stiffness = 4.0e8;
  chain.carriage_drive.bearing_stiffness = 9.0e8;
  chain.strut_base_joint_stiffness = 3.0e8;
  chain.strut_platform_joint_stiffness = 5.0e8;
  chain.leg_drive.nut_stiffness = 2.5e8;
  chain.leg_base_joint_stiffness = 6.0e8;
  chain.leg_platform_joint_stiffness = 7.0e8;
  Lathe16k20f3Design lumped;
  lumped.carriage_stiffness = 1.0 / (1.0 / chain.carriage_stiffness + 1.0 / 4.0e8 + 1.0 / 9.0e8);
  lumped.leg_actuator_stiffness =
      1.0 / (1.0 / chain.leg_actuator_stiffness + 1.0 / 2.5e8 + 1.0 / 6.0e8 + 1.0 / 7.0e8);
  const double L = chain.strut_length, E = chain.strut_E;
  lumped.strut_area = L / (E * (L / (E * chain.strut_area) + 1.0 / 3.0e8 + 1.0 / 5.0e8));
  const auto a = make_lathe_16k20f3(chain), b = make_lathe_16k20f3(lumped);
  const auto plain = make_lathe_16k20f3(Lathe16k20f3Design{});
  const auto da = a->make_data(), db = b->make_data(), dp = plain->make_data();
  const Wrench w = turning_wrench();
  for (const Pose& pose : sample_poses()) {
    PoseMetrics ma, mb, mp;
    a->analyze(*da, pose, w, ma);
    b->analyze(*db, pose, w, mb);
    plain->analyze(*dp, pose, w, mp);
    ASSERT_GT(ma.stiffness_min, 0.0);
    EXPECT_NEAR(ma.stiffness_min, mb.stiffness_min, 1e-10 * mb.stiffness_min);
    EXPECT_NEAR(ma.tcp_deflection, mb.tcp_deflection, 1e-10 * mb.tcp_deflection);
    const Matrix6d& Ca = da->matrices.compliance;
    const Matrix6d& Cb = db->matrices.compliance;
    EXPECT_LE((Ca - Cb).norm(), 1e-10 * Cb.norm());
    // The added springs only soften the machine.
    EXPECT_LT(ma.stiffness_min, mp.stiffness_min);
    EXPECT_GT(ma.tcp_deflection, mp.tcp_deflection);
  }
  // A screw without its free length is refused, naming the drive.
  Lathe16k20f3Design bad;
  bad.leg_drive.E = 2.1e11;
  bad.leg_drive.root_diameter = 0.03;
  EXPECT_THROW(lathe_16k20f3_design(bad), std::invalid_argument);
}

// With masses the Schoenflies turret has four natural frequencies per pose, ascending and
// finite; the leg bodies lower each of them.
TEST(LatheConversion, MassesGiveFourNaturalFrequencies) {
  Lathe16k20f3Design d;
  d.masses.present = true;
  d.masses.platform.mass = 60.0;
  d.masses.platform.inertia = Eigen::Vector3d(1.5, 1.2, 1.1).asDiagonal();
  const auto bare = make_lathe_16k20f3(d);
  d.masses.legs.carriage = 12.0;
  d.masses.legs.link = {.mass = 5.0, .centre = 0.35, .inertia = 0.2};
  d.masses.legs.cylinder = {.mass = 9.0, .centre = 0.3, .inertia = 0.4};
  d.masses.legs.rod = {.mass = 4.0, .centre = 0.4, .inertia = 0.15};
  const auto heavy = make_lathe_16k20f3(d);
  ASSERT_TRUE(heavy->dynamics());
  ASSERT_EQ(heavy->dynamics()->natural_frequency_count(), 4);
  const auto db = bare->make_data(), dh = heavy->make_data();
  for (const Pose& pose : sample_poses()) {
    PoseMetrics mb, mh;
    bare->analyze(*db, pose, Wrench::Zero(), mb);
    heavy->analyze(*dh, pose, Wrench::Zero(), mh);
    ASSERT_EQ(mh.natural_frequencies.size(), 4);
    for (int j = 0; j < 4; ++j) {
      EXPECT_TRUE(std::isfinite(mh.natural_frequencies(j)));
      EXPECT_GT(mh.natural_frequencies(j), 1.0);
      if (j > 0) {
        EXPECT_GE(mh.natural_frequencies(j), mh.natural_frequencies(j - 1));
      }
      EXPECT_LT(mh.natural_frequencies(j), mb.natural_frequencies(j));
    }
  }
}

// Struts and legs with a diameter: the clearance is the smallest over the links placed here from
// the IK (struts from the carriages c = g + q u, legs from their base joints), a pose where
// they come closer than min_clearance is unreachable.
TEST(LatheConversion, StrutsAndLegsKeepTheirClearance) {
  Lathe16k20f3Design d;
  d.shapes.link_diameter = 0.05;
  const LegChainDesign design = lathe_16k20f3_design(d);
  const LegChainMachine machine(design);
  ASSERT_TRUE(machine.checks_leg_interference());
  int checked = 0;
  for (const Pose& pose : sample_poses()) {
    const auto q = machine.inverse_kinematics(pose);
    if (!q) continue;
    const Eigen::Matrix3d R = rotation_zyx<double>(pose.angles);
    std::vector<Eigen::Vector3d> a, b;
    for (std::size_t i = 0; i < design.legs.size(); ++i) {
      const LegChainLeg& leg = design.legs[i];
      const double qi = (*q)(static_cast<Eigen::Index>(i));
      Eigen::Vector3d start = leg.base_point;
      if (leg.kind == LegKind::kPUS) start += qi * leg.axis.normalized();
      a.push_back(start);
      b.push_back(pose.position + R * (leg.platform_point - design.tcp));
    }
    double expected = std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < a.size(); ++i)
      for (std::size_t j = i + 1; j < a.size(); ++j)
        expected = std::min(expected, segment_distance(a[i], b[i], a[j], b[j]) - 0.05);
    const Clearance c = machine.leg_clearance(pose);
    EXPECT_NEAR(c.value, expected, 1e-12);
    d.shapes.min_clearance = expected + 1e-3;
    const LegChainMachine tight(lathe_16k20f3_design(d));
    EXPECT_FALSE(tight.reachable(*tight.make_data(), pose));
    d.shapes.min_clearance = 0.0;
    ++checked;
  }
  EXPECT_GT(checked, 2);
}

TEST(LatheConversion, RejectsImpossibleDesigns) {
  Lathe16k20f3Design d;
  d.strut_length = 0.0;
  EXPECT_THROW(lathe_16k20f3_design(d), std::invalid_argument);
  d = Lathe16k20f3Design{};
  d.leg_max_length = d.leg_min_length;
  EXPECT_THROW(lathe_16k20f3_design(d), std::invalid_argument);
  EXPECT_THROW(lathe_task_poses(LatheTask{{0, 0, 0}, {-1, 0, 0}, {2, 2, 2}}),
               std::invalid_argument);
}

}  // namespace
}  // namespace pkmopt
