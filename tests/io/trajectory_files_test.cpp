// The files of `pkmopt trajectory` (io/trajectory_files.hpp) for trajectory results built by
// hand on the docs/conventions.md hexapod (6 prismatic legs): the exact text of every table.
#include "io/trajectory_files.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <limits>
#include <numbers>
#include <string>
#include <vector>

#include "io/input_error.hpp"
#include "models/hexapod.hpp"
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
  return s;
}

TEST(TrajectoryCsv, HeaderAndRowWithoutJacobian) {
  TrajectoryResult r;
  r.samples.push_back(regular_sample());
  const std::string csv = pkmopt::trajectory_csv(hexapod(), r, false);
  EXPECT_EQ(csv,
            "t,x,y,z,rx,ry,rz,vx,vy,vz,wx,wy,wz,reachable,singular,q_1,q_2,q_3,q_4,q_5,q_6,"
            "q_dot_1,q_dot_2,q_dot_3,q_dot_4,q_dot_5,q_dot_6,q_dot_fd_1,q_dot_fd_2,q_dot_fd_3,"
            "q_dot_fd_4,q_dot_fd_5,q_dot_fd_6,singularity_margin,det_j\n"
            "0.5,0.1,-0.2,0.9,0,0,0,0.25,0,-0.5,0,0,0,1,0,0.8,0.81,0.82,0.83,0.84,0.85,"
            "0.5,0.5,0.5,0.5,0.5,0.5,0.25,0.25,0.25,0.25,0.25,0.25,0.125,-2.5\n");
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
  std::string expected =
      "trajectory: 3 samples, t 0 .. 6.25 s, 2 reachable, min singularity_margin 0.03125\n";
  for (int i = 1; i <= 5; ++i) {
    expected += "  q_" + std::to_string(i) + ": 0.75 .. 1 m, max |q_dot| 0.125 m/s\n";
  }
  expected += "  q_6: 0.7 .. 1 m, max |q_dot| 0.125 m/s\n";
  expected += "  max |q_dot - q_dot_fd| 2e-06 m/s (interior samples)\n";
  expected += "  singular poses: 1\n";
  expected +=
      "    t = 3.5 s (det_j changes sign): x,y,z = 0.1,0.2,0.9 m, rx,ry,rz = 0,0,0 deg, "
      "det_j 0.01 -> -0.02\n";
  EXPECT_EQ(pkmopt::trajectory_summary_text(hexapod(), r, s), expected);
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
