// Tests of models/motion/trajectory_modes: the distance to the nearest other assembly mode along a
// path, against the mirror mode of the sample hexapod found by hand as the platform turns toward
// Fichter's singularity (rz = 90 deg), and against an independent reading of the 40-path solver's
// output on a helix; the same result for any thread count.
#include "models/motion/trajectory_modes.hpp"

#include <gtest/gtest.h>
#include <omp.h>

#include <Eigen/Geometry>
#include <cmath>
#include <numbers>
#include <vector>

#include "models/hexapod/assembly_modes.hpp"
#include "models/hexapod/hexapod.hpp"
#include "models/sample_machines.hpp"

namespace {

using namespace pkmopt;

constexpr double kPi = std::numbers::pi;

// The mean distance of the platform joints from the TCP (rho of the pose distance).
double rho_of(const Hexapod& h) { return h.platform_rel_tcp().colwise().norm().mean(); }

// The poses (0, 0, 0.9, 0, 0, rz) for rz = 60 .. 90 deg in steps of 1 deg, t = rz - 60.
TrajectoryResult fichter_turn(const Hexapod& hexapod) {
  std::vector<double> times;
  std::vector<Pose> poses;
  for (int k = 0; k <= 30; ++k) {
    times.push_back(k);
    poses.push_back(Pose{{0.0, 0.0, 0.9}, {0.0, 0.0, (60.0 + k) * kPi / 180.0}});
  }
  return evaluate_trajectory(hexapod, SampledPath(times, poses), times);
}

// The height z' at which the platform turned by 180 deg - rz has the same first leg length as at
// (0, 0, 0.9, 0, 0, rz), by bisection below 0.9 (the length grows with the height there).
double mirror_height(const Hexapod& hexapod, double rz) {
  const double target = hexapod.inverse_kinematics(Pose{{0.0, 0.0, 0.9}, {0.0, 0.0, rz}})(0);
  double lo = 0.3, hi = 0.9;
  for (int it = 0; it < 200; ++it) {
    const double mid = 0.5 * (lo + hi);
    const double l = hexapod.inverse_kinematics(Pose{{0.0, 0.0, mid}, {0.0, 0.0, kPi - rz}})(0);
    (l < target ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

TEST(TrajectoryModes, TheMirrorModeComesNearAsThePlatformTurnsTowardFichtersSingularity) {
  // The sample hexapod is symmetric: the platform turned by 180 deg - rz about z, at another
  // height, has the same six leg lengths as at rz (the legs swap in pairs). That mirror mode
  // meets the machine's own at rz = 90 deg, Fichter's singularity.
  const Hexapod hexapod(sample_machines::conventions_hexapod_design());
  const TrajectoryResult run = fichter_turn(hexapod);
  const auto solver = hexapod.all_forward_kinematics_solver();
  ASSERT_TRUE(solver);
  const TrajectoryModes modes = trajectory_assembly_modes(*solver.get(), run);
  ASSERT_EQ(modes.samples.size(), run.samples.size());
  EXPECT_NEAR(modes.distance_length, rho_of(hexapod), 1e-15);
  for (std::size_t k = 0; k + 1 < run.samples.size(); ++k) {
    const double rz = run.samples[k].pose.angles(2);
    const double z = mirror_height(hexapod, rz);
    const Pose mirror{{0.0, 0.0, z}, {0.0, 0.0, kPi - rz}};
    // The mirror pose has all six lengths of the sample (the symmetry, checked).
    EXPECT_LT((hexapod.inverse_kinematics(mirror) - run.samples[k].metrics.q).cwiseAbs().maxCoeff(),
              1e-12);
    const double expected = std::hypot(0.9 - z, rho_of(hexapod) * (kPi - 2.0 * rz));
    const AssemblyModeSample& m = modes.samples[k];
    EXPECT_TRUE(m.tracked_found) << k;
    EXPECT_EQ(m.failed_paths, 0u) << k;
    EXPECT_GE(m.real_modes, 2u) << k;
    EXPECT_EQ(m.real_modes % 2, 0u) << k;
    EXPECT_NEAR(m.nearest_other, expected, 1e-9) << "rz = " << rz * 180.0 / kPi;
  }
  // At rz = 90 deg the two modes are one: the sample is singular, the distance 0.
  EXPECT_TRUE(run.samples.back().metrics.singular);
  EXPECT_EQ(modes.samples.back().nearest_other, 0.0);
}

// The pose distance of the header, written out again.
double pose_distance(const Eigen::Vector3d& p, const Eigen::Matrix3d& R, const Pose& pose,
                     double rho) {
  const Eigen::Matrix3d Q = rotation_zyx(pose.angles);
  const double theta = Eigen::AngleAxisd(R.transpose() * Q).angle();
  return std::hypot((p - pose.position).norm(), rho * theta);
}

TEST(TrajectoryModes, OnAHelixTheDistanceIsTheNearestOfTheFortyPathSolutions) {
  const Hexapod hexapod(sample_machines::conventions_hexapod_design());
  HelixParameters h;
  h.centre = {0.0, 0.0, 0.9};
  h.radius_start = 0.05;
  h.angle_amplitudes = Eigen::Vector3d(0.1, 0.1, 0.3);
  const std::vector<double> times = uniform_times(0.0, 2.0 * kPi, 9);
  const TrajectoryResult run = evaluate_trajectory(hexapod, HelixPath(h), times);
  const TrajectoryModes modes =
      trajectory_assembly_modes(*hexapod.all_forward_kinematics_solver().get(), run);
  const double rho = rho_of(hexapod);
  for (std::size_t k = 0; k < run.samples.size(); ++k) {
    const Pose& pose = run.samples[k].pose;
    const Eigen::Matrix<double, 6, 1> lengths = run.samples[k].metrics.q;
    // The 40 paths from the universal start, with the nearest other mode read here.
    const AssemblyModes all =
        all_assembly_modes(hexapod.design().base_joints, hexapod.platform_rel_tcp(), lengths);
    double own = INFINITY, other = INFINITY;
    for (const AssemblyMode& m : all.real) {
      const double d = pose_distance(m.position, m.rotation, pose, rho);
      if (d < 1e-6)
        own = d;
      else
        other = std::min(other, d);
    }
    EXPECT_LT(own, 1e-9) << k;
    EXPECT_EQ(modes.samples[k].real_modes, all.real.size()) << k;
    EXPECT_NEAR(modes.samples[k].nearest_other, other, 1e-9) << k;
  }
}

TEST(TrajectoryModes, TheSameForAnyThreadCount) {
  const Hexapod hexapod(sample_machines::conventions_hexapod_design());
  const TrajectoryResult run = fichter_turn(hexapod);
  const AllForwardKinematics& solver = *hexapod.all_forward_kinematics_solver().get();
  const int before = omp_get_max_threads();
  omp_set_num_threads(1);
  const TrajectoryModes one = trajectory_assembly_modes(solver, run);
  omp_set_num_threads(2);
  const TrajectoryModes two = trajectory_assembly_modes(solver, run);
  omp_set_num_threads(before);
  for (std::size_t k = 0; k < one.samples.size(); ++k) {
    EXPECT_EQ(one.samples[k].nearest_other, two.samples[k].nearest_other);
    EXPECT_EQ(one.samples[k].real_modes, two.samples[k].real_modes);
  }
}

}  // namespace
