// The files of `pkmopt trajectory` (io/results/trajectory_files.hpp) for trajectory results built
// by hand on the docs/conventions.md hexapod (6 prismatic legs): the exact text of every table.
#include "io/results/trajectory_files.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <limits>
#include <numbers>
#include <string>
#include <vector>

#include "io/format/input_error.hpp"
#include "models/hexapod/hexapod.hpp"
#include "models/sample_machines.hpp"
#include "tests/scratch_dir.hpp"

namespace {

namespace fs = std::filesystem;
using pkmopt::SingularPose;
using pkmopt::TrajectoryResult;
using pkmopt::TrajectorySample;

const pkmopt::Hexapod& hexapod() {
  static const pkmopt::Hexapod h(pkmopt::sample_machines::conventions_hexapod_design());
  return h;
}

// t = 0.5 s at (0.1, -0.2, 0.9) m, no rotation, moving at (0.25, 0, -0.5) m/s; legs 0.8..0.85 m.
TrajectorySample regular_sample() {
  TrajectorySample s;
  s.t = 0.5;
  s.pose.position = {0.1, -0.2, 0.9};
  s.twist << 0.25, 0, -0.5, 0, 0, 0;
  s.metrics.reachable = true;
  s.metrics.singular = false;
  s.metrics.q.resize(6);
  s.metrics.q << 0.8, 0.81, 0.82, 0.83, 0.84, 0.85;
  s.metrics.singularity_margin = 0.125;
  s.metrics.det_j = -2.5;
  s.jacobian_ok = true;
  s.J = Eigen::MatrixXd::Zero(6, 6);
  s.J(0, 0) = 1.5;
  s.J(5, 5) = -0.75;
  s.q_dot = Eigen::VectorXd::Constant(6, 0.5);
  s.q_dot_fd = Eigen::VectorXd::Constant(6, 0.25);
  s.twist_rate << 2, 0, -1, 0, 90 * pkmopt::kDegToRad, 0;  // m/s^2, 90 deg/s^2 about y
  s.metrics.tau = Eigen::VectorXd::Constant(6, 125.0);
  return s;
}

TEST(TrajectoryCsv, HeaderAndRowWithoutJacobian) {
  TrajectoryResult r;
  r.samples.push_back(regular_sample());
  const std::string csv = pkmopt::trajectory_csv(hexapod(), r, false);
  EXPECT_EQ(csv,
            "t,x,y,z,rx,ry,rz,vx,vy,vz,wx,wy,wz,ax,ay,az,alpha_x,alpha_y,alpha_z,reachable,"
            "singular,q_1,q_2,q_3,q_4,q_5,q_6,"
            "q_dot_1,q_dot_2,q_dot_3,q_dot_4,q_dot_5,q_dot_6,q_dot_fd_1,q_dot_fd_2,q_dot_fd_3,"
            "q_dot_fd_4,q_dot_fd_5,q_dot_fd_6,tau_1,tau_2,tau_3,tau_4,tau_5,tau_6,"
            "singularity_margin,det_j\n"
            "0.5,0.1,-0.2,0.9,0,0,0,0.25,0,-0.5,0,0,0,2,0,-1,0,90,0,1,0,0.8,0.81,0.82,0.83,0.84,"
            "0.85,0.5,0.5,0.5,0.5,0.5,0.5,0.25,0.25,0.25,0.25,0.25,0.25,125,125,125,125,125,125,"
            "0.125,-2.5\n");
}

// With masses every sample has tau_dyn: its columns follow tau's.
TEST(TrajectoryCsv, DynamicForceColumns) {
  TrajectoryResult r;
  r.samples.push_back(regular_sample());
  r.samples[0].tau_dyn = Eigen::VectorXd::LinSpaced(6, -250.0, 1000.0);
  const std::string csv = pkmopt::trajectory_csv(hexapod(), r, false);
  const std::string header = csv.substr(0, csv.find('\n'));
  EXPECT_NE(header.find(",tau_6,tau_dyn_1,tau_dyn_2,tau_dyn_3,tau_dyn_4,tau_dyn_5,tau_dyn_6,"
                        "singularity_margin,det_j"),
            std::string::npos)
      << header;
  EXPECT_NE(csv.find(",125,125,-250,0,250,500,750,1000,0.125,-2.5\n"), std::string::npos) << csv;
}

TEST(TrajectoryCsv, JacobianColumnsAndInfWhereItFailed) {
  TrajectoryResult r;
  r.samples.push_back(regular_sample());
  TrajectorySample failed = regular_sample();
  failed.jacobian_ok = false;
  failed.J.resize(0, 0);
  r.samples.push_back(failed);
  const std::string csv = pkmopt::trajectory_csv(hexapod(), r, true);
  const std::string header = csv.substr(0, csv.find('\n'));
  EXPECT_NE(header.find(",det_j,J_1_1,J_1_2,"), std::string::npos);
  EXPECT_EQ(header.substr(header.size() - 6), ",J_6_6");
  // First row ends with J_6_6 = -0.75, the second with 36 infinities.
  const std::size_t row1 = csv.find('\n') + 1, row2 = csv.find('\n', row1) + 1;
  const std::string first = csv.substr(row1, row2 - 1 - row1);
  EXPECT_EQ(first.substr(first.size() - 6), ",-0.75");
  EXPECT_NE(first.find(",-2.5,1.5,0,0,0,0,0,0,"), std::string::npos);
  std::string infinities;
  for (int k = 0; k < 36; ++k) infinities += ",inf";
  EXPECT_EQ(csv.substr(csv.size() - infinities.size() - 1), infinities + "\n");
}

// With assembly modes: three columns after det_j, and the summary lines with their warnings.
TEST(TrajectoryCsv, AssemblyModeColumnsAndSummary) {
  TrajectoryResult r;
  r.samples.push_back(regular_sample());
  r.samples.push_back(regular_sample());
  r.samples[1].t = 1.0;
  r.samples.push_back(regular_sample());
  r.samples[2].t = 1.5;
  pkmopt::TrajectoryModes modes;
  modes.distance_length = 0.25;
  modes.samples.resize(3);
  modes.samples[0] = {0.5, 4, 0, true};
  modes.samples[1] = {0.01, 4, 0, true};
  modes.samples[2] = {0.0, 2, 1, false};
  const std::string csv = pkmopt::trajectory_csv(hexapod(), r, false, &modes);
  EXPECT_NE(csv.find("singularity_margin,det_j,mode_distance,real_modes,failed_paths\n"),
            std::string::npos);
  EXPECT_NE(csv.find(",0.125,-2.5,0.5,4,0\n1,"), std::string::npos) << csv;
  EXPECT_NE(csv.find(",0.125,-2.5,0,2,1\n"), std::string::npos) << csv;
  const std::string text = pkmopt::assembly_modes_text(r, modes, 0.025);
  EXPECT_EQ(text,
            "  assembly modes: 2 .. 4 real; nearest other mode 0 m, at t = 1.5 s (pose distance "
            "sqrt(|dp|^2 + (rho theta)^2), rho = 0.25 m)\n"
            "  WARNING: another assembly mode comes within 0 m of the tracked pose (below 0.025 m) "
            "at 2 samples, first at t = 1 s: the path runs near a parallel singularity, where a "
            "disturbance could carry the machine into that mode\n"
            "  WARNING: the tracked pose was not among the forward-kinematics solutions at 1 "
            "samples, first at t = 1.5 s (mode_distance 0 there)\n"
            "  WARNING: forward-kinematics paths failed at 1 samples, first at t = 1.5 s: other "
            "modes may be missing there (failed_paths)\n");
}

TEST(SingularPosesCsv, BothKinds) {
  TrajectoryResult r;
  SingularPose a;
  a.kind = SingularPose::Kind::kSample;
  a.t = 1.0;
  a.pose.position = {0, 0, 0.9};
  a.det_j_before = 0.5;
  a.det_j_after = 0.25;
  SingularPose b;
  b.kind = SingularPose::Kind::kDetSignChange;
  b.t = 2.25;
  b.pose.position = {0.1, 0, 1};
  b.singularity_margin = 0.001;
  b.det_j_before = 1e-3;
  b.det_j_after = -2e-3;
  r.singular_poses = {a, b};
  EXPECT_EQ(pkmopt::singular_poses_csv(r),
            "t,x,y,z,rx,ry,rz,kind,singularity_margin,det_j_before,det_j_after\n"
            "1,0,0,0.9,0,0,0,sample,0,0.5,0.25\n"
            "2.25,0.1,0,1,0,0,0,det_j_sign_change,0.001,0.001,-0.002\n");
}

TEST(TrajectorySummaryText, LinesInMetres) {
  TrajectoryResult r;
  r.samples.resize(3);
  r.samples[0].t = 0.0;
  r.samples[2].t = 6.25;
  SingularPose p;
  p.kind = SingularPose::Kind::kDetSignChange;
  p.t = 3.5;
  p.pose.position = {0.1, 0.2, 0.9};
  p.det_j_before = 0.01;
  p.det_j_after = -0.02;
  r.singular_poses = {p};
  pkmopt::TrajectorySummary s;
  s.samples = 3;
  s.reachable = 2;
  s.singularity_margin_min = 0.03125;
  s.q_min = Eigen::VectorXd::Constant(6, 0.75);
  s.q_max = Eigen::VectorXd::Constant(6, 1.0);
  s.q_min(5) = 0.7;
  s.q_dot_max = Eigen::VectorXd::Constant(6, 0.125);
  s.q_dot_mismatch_max = 2e-6;
  s.speed_max = 0.5;
  s.acceleration_max = 2 * pkmopt::kStandardGravity;
  s.tau_max = Eigen::VectorXd::Constant(6, 250.0);
  std::string expected =
      "trajectory: 3 samples, t 0 .. 6.25 s, 2 reachable, min singularity_margin 0.03125\n";
  expected +=
      "  WARNING: 1 of 3 samples are not reachable (actuator ranges, joint limits or leg "
      "interference): the machine "
      "cannot follow this path\n";
  for (int i = 1; i <= 5; ++i) {
    expected += "  q_" + std::to_string(i) + ": 750 .. 1000 mm, max |q_dot| 125 mm/s\n";
  }
  expected += "  q_6: 700 .. 1000 mm, max |q_dot| 125 mm/s\n";
  expected += "  max |q_dot - q_dot_fd| 0.002 mm/s (interior samples)\n";
  expected += "  TCP: max speed 0.5 m/s, max acceleration 19.61 m/s^2 (2 g)\n";
  for (int i = 1; i <= 6; ++i) {
    expected += "  tau_" + std::to_string(i) + ": max |tau| 250 N under the wrench\n";
  }
  expected += "  no masses in the machine file: tau_dyn (gravity and inertia) not computed\n";
  expected += "  singular poses: 1\n";
  expected +=
      "    t = 3.5 s (det_j changes sign): x,y,z = 0.1,0.2,0.9 m, rx,ry,rz = 0,0,0 deg, "
      "det_j 0.01 -> -0.02\n";
  EXPECT_EQ(pkmopt::trajectory_summary_text(hexapod(), r, s), expected);
}

// A path whose margin falls below kNearSingularMargin: the warning names the sample, its pose and
// the fastest drive there, each axis in its unit.
TEST(TrajectorySummaryText, NearSingularSampleIsWarnedWithTheFastestDrive) {
  TrajectoryResult r;
  r.samples.resize(2);
  r.samples[1].t = 0.5;
  r.samples[1].pose.position = {0.1, 0.2, 0.9};
  r.samples[1].pose.angles = {0.0, pkmopt::deg_to_rad(10.0), 0.0};
  r.samples[1].metrics.singularity_margin = 0.004;
  r.samples[1].q_dot = Eigen::VectorXd::Constant(6, 0.01);
  r.samples[1].q_dot(3) = -0.25;
  pkmopt::TrajectorySummary s;
  s.samples = 2;
  s.reachable = 2;
  s.singularity_margin_min = 0.004;
  s.singularity_margin_min_sample = 1;
  s.q_min = s.q_max = s.q_dot_max = Eigen::VectorXd::Zero(6);
  s.tau_max = Eigen::VectorXd::Zero(6);
  const std::string text = pkmopt::trajectory_summary_text(hexapod(), r, s);
  EXPECT_NE(text.find("  WARNING: near a singular pose at t = 0.5 s (x,y,z = 0.1,0.2,0.9 m, "
                      "rx,ry,rz = 0,10,0 deg): singularity_margin 0.004 < 0.01; the drive rates "
                      "grow as 1/margin there (fastest: q_4 at 250 mm/s)\n"),
            std::string::npos)
      << text;
  s.singularity_margin_min = 0.02;  // not near: no warning
  EXPECT_EQ(pkmopt::trajectory_summary_text(hexapod(), r, s).find("near a singular"),
            std::string::npos);
}

// A summary with dynamics: the per-actuator lines and the drive check against an entry with and
// without a peak rating.
pkmopt::TrajectorySummary dynamic_summary() {
  pkmopt::TrajectorySummary s;
  s.samples = 2;
  s.q_min = Eigen::VectorXd::Constant(2, 0.8);
  s.q_max = Eigen::VectorXd::Constant(2, 1.0);
  s.q_dot_max = Eigen::Vector2d(0.25, 0.5);
  s.tau_max = Eigen::Vector2d(1000.0, 2000.0);
  s.dynamics = true;
  s.tau_dyn_max = Eigen::Vector2d(6000.0, 3000.0);
  s.tau_dyn_rms = Eigen::Vector2d(4000.0, 2500.0);
  s.power_max = Eigen::Vector2d(1500.0, 750.0);
  return s;
}

TEST(DriveCheckText, PeakRmsSpeedAndStrokeOfEveryActuator) {
  const pkmopt::TrajectorySummary s = dynamic_summary();
  pkmopt::ActuatorEntry entry{.name = "D",
                              .type = "electric_cylinder",
                              .max_force = 5000,
                              .stroke = 0.3,
                              .max_speed = 0.4,
                              .accuracy = {},
                              .stiffness = {},
                              .cost = {},
                              .peak_force = 8000};
  bool carries = true;
  std::string text = pkmopt::drive_check_text(entry, s, carries);
  EXPECT_FALSE(carries);  // actuator 2 runs at 0.5 m/s > 0.4
  EXPECT_NE(text.find("  actuator 1: peak 6000 N ok, RMS 4000 N ok, speed 0.25 m/s ok, stroke "
                      "0.2 m ok\n"),
            std::string::npos)
      << text;
  EXPECT_NE(text.find("  actuator 2: peak 3000 N ok, RMS 2500 N ok, speed 0.5 m/s EXCEEDED"),
            std::string::npos)
      << text;
  EXPECT_NE(text.find("WARNING: D does NOT carry this path"), std::string::npos) << text;
  // Without a peak rating the peak is checked against the continuous one.
  entry.peak_force.reset();
  entry.max_speed = 1.0;
  text = pkmopt::drive_check_text(entry, s, carries);
  EXPECT_FALSE(carries);
  EXPECT_NE(text.find("actuator 1: peak 6000 N EXCEEDED, RMS 4000 N ok"), std::string::npos)
      << text;
  entry.max_force = 6000;
  text = pkmopt::drive_check_text(entry, s, carries);
  EXPECT_TRUE(carries);
  EXPECT_NE(text.find("  D carries every actuator along this path\n"), std::string::npos) << text;
  // The RMS is the thermal check: a drive rated 3500 N carries actuator 2's peak (with a peak
  // rating) but not actuator 1's RMS.
  entry.max_force = 3500;
  entry.peak_force = 7000;
  text = pkmopt::drive_check_text(entry, s, carries);
  EXPECT_FALSE(carries);
  EXPECT_NE(text.find("actuator 1: peak 6000 N ok, RMS 4000 N EXCEEDED"), std::string::npos)
      << text;
}

class PathFile : public scratch::ScratchDirTest {
 protected:
  std::string write(const std::string& text) { return ScratchDirTest::write("path.csv", text); }
};

TEST_F(PathFile, InterpolatesBetweenSamples) {
  const pkmopt::SampledPath path =
      pkmopt::read_path_csv(write("t,x,y,z,rz\n0,0,0,1,0\n2,0.2,0,1,90\n"));
  EXPECT_EQ(path.times(), (std::vector<double>{0.0, 2.0}));
  const pkmopt::PathPoint mid = path.at(1.0);
  EXPECT_NEAR(mid.pose.position(0), 0.1, 1e-15);
  EXPECT_NEAR(mid.pose.angles(2), std::numbers::pi / 4, 1e-15);
  EXPECT_NEAR(mid.pose_rate(0), 0.1, 1e-15);  // 0.2 m in 2 s
}

TEST_F(PathFile, OneSampleIsAnInputError) {
  const std::string file = write("t,x,y,z\n0,0,0,1\n");
  try {
    pkmopt::read_path_csv(file);
    FAIL() << "expected InputError";
  } catch (const pkmopt::InputError& e) {
    EXPECT_EQ(std::string(e.what()), file + ": expected at least 2 path samples, found 1");
  }
}

}  // namespace
