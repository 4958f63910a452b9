// Tests of the leg-chain machine files (app/machine_file_leg_chain) and of `pkmopt analyze`,
// `fk` and `workspace` on a delta and a hexaglide: results agree with the library, revolute
// coordinates are in degrees, bad input exits with status 2 and one message.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "app/input_error.hpp"
#include "app/machine_file.hpp"
#include "app/machine_file_leg_chain.hpp"
#include "models/leg_chain.hpp"
#include "tests/cli_runner.hpp"

namespace pkmopt {
namespace {

namespace fs = std::filesystem;
using cli_runner::CliRun;

std::string example(const char* name) {
  return (fs::path(PKMOPT_SOURCE_DIR) / "examples" / name).string();
}

std::vector<std::string> split(const std::string& line, char sep = ',') {
  std::vector<std::string> out;
  std::stringstream s(line);
  std::string cell;
  while (std::getline(s, cell, sep)) out.push_back(cell);
  return out;
}

std::vector<std::string> lines(const std::string& text) {
  std::vector<std::string> out;
  std::stringstream s(text);
  std::string line;
  while (std::getline(s, line)) out.push_back(line);
  return out;
}

class LegChainCli : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("pkmopt_leg_chain_cli_test_" + std::to_string(::getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  std::string write(const std::string& name, const std::string& text) {
    const fs::path p = dir_ / name;
    std::ofstream(p) << text;
    return p.string();
  }
  CliRun run(const std::string& args) { return cli_runner::run_cli(dir_, args); }
  void expect_input_error(const CliRun& r, const std::string& fragment) {
    EXPECT_EQ(r.status, 2) << r.err;
    EXPECT_NE(r.err.find(fragment), std::string::npos) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  }

  fs::path dir_;
};

TEST_F(LegChainCli, ExampleFilesLoad) {
  for (const char* name : {"delta.yaml", "linear_delta.yaml", "hexaglide.yaml"}) {
    const auto machine = load_machine_file(example(name));
    ASSERT_NE(machine, nullptr);
    EXPECT_EQ(std::string(machine->model()) + ".yaml", name);
  }
  const auto delta = load_machine_file(example("delta.yaml"));
  EXPECT_EQ(delta->num_actuators(), 3);
  EXPECT_TRUE(delta->revolute_actuators());
  const auto glide = load_machine_file(example("hexaglide.yaml"));
  EXPECT_EQ(glide->num_actuators(), 6);
  EXPECT_FALSE(glide->revolute_actuators());
}

// The delta file maps onto DeltaDesign key by key (degrees converted).
TEST_F(LegChainCli, DeltaFileValues) {
  const DeltaDesign d = read_delta_design(YamlValue::load_file(example("delta.yaml")));
  EXPECT_EQ(d.base_radius, 0.164);
  EXPECT_EQ(d.platform_radius, 0.044);
  EXPECT_EQ(d.upper_arm, 0.524);
  EXPECT_EQ(d.rod, 1.244);
  EXPECT_DOUBLE_EQ(d.theta_min, deg_to_rad(-60));
  EXPECT_DOUBLE_EQ(d.theta_max, deg_to_rad(100));
  EXPECT_EQ(d.branch, 1);
  EXPECT_EQ(d.stiffness.E, 7.0e10);
  EXPECT_EQ(d.stiffness.area, 5.0e-5);
  EXPECT_EQ(d.stiffness.actuator_stiffness, 5.0e4);
  EXPECT_DOUBLE_EQ(d.elbow_max_angle, deg_to_rad(60));
  EXPECT_DOUBLE_EQ(d.actuator_error, deg_to_rad(0.001));
}

// analyze on the delta: q in degrees and the published IK of Williams (2015) for the IRB 360
// (P = (0.3, 0.5, -1.1) m -> theta = (47.5, -11.6, 21.4) deg, rounded to 0.1 deg); tau in N*m
// equal to the library's; fk returns the pose.
TEST_F(LegChainCli, AnalyzeAndFkOnTheDelta) {
  const std::string poses = write("poses.csv", "x,y,z,label\n0.3,0.5,-1.1,a\n0,0,-0.9,b\n");
  const CliRun r =
      run("analyze " + example("delta.yaml") + " --poses " + poses + " --wrench 0,0,-50,0,0,0");
  ASSERT_EQ(r.status, 0) << r.err;
  const auto rows = lines(r.out);
  ASSERT_EQ(rows.size(), 3u);
  EXPECT_EQ(rows[0],
            "x,y,z,rx,ry,rz,reachable,q_1,q_2,q_3,tau_1,tau_2,tau_3,stiffness_min,"
            "singularity_margin,det_j,tcp_error_max,label");
  const auto a = split(rows[1]);
  ASSERT_EQ(a.size(), 18u);
  EXPECT_EQ(a[6], "1");
  EXPECT_NEAR(std::stod(a[7]), 47.5, 0.05);
  EXPECT_NEAR(std::stod(a[8]), -11.6, 0.05);
  EXPECT_NEAR(std::stod(a[9]), 21.4, 0.05);
  EXPECT_EQ(a[17], "a");
  // The same numbers as the library.
  const auto machine = load_machine_file(example("delta.yaml"));
  auto data = machine->make_data();
  PoseMetrics m;
  Wrench w = Wrench::Zero();
  w(2) = -50;
  machine->analyze(*data, Pose{{0.3, 0.5, -1.1}, Eigen::Vector3d::Zero()}, w, m);
  for (int i = 0; i < 3; ++i) {
    EXPECT_EQ(std::stod(a[7 + i]), rad_to_deg(m.q(i)));
    EXPECT_EQ(std::stod(a[10 + i]), m.tau(i));
  }
  EXPECT_EQ(std::stod(a[13]), m.stiffness_min);
  EXPECT_EQ(std::stod(a[14]), m.singularity_margin);
  // At the centre pose a downward load of 50 N loads the three drives equally, in the direction
  // that lowers the elbows (positive, like theta); by virtual work 3 tau dtheta = -50 dz, with
  // dz/dtheta from the forward kinematics.
  const auto b = split(rows[2]);
  const double tau_centre = std::stod(b[10]);
  EXPECT_GT(tau_centre, 0.0);
  EXPECT_NEAR(std::stod(b[11]), tau_centre, 1e-9 * tau_centre);
  EXPECT_NEAR(std::stod(b[12]), tau_centre, 1e-9 * tau_centre);
  const double theta = deg_to_rad(std::stod(b[7])), h = 1e-6;
  const double z_plus =
      machine->forward_kinematics(Eigen::VectorXd::Constant(3, theta + h), std::nullopt)
          .pose.position.z();
  const double z_minus =
      machine->forward_kinematics(Eigen::VectorXd::Constant(3, theta - h), std::nullopt)
          .pose.position.z();
  EXPECT_NEAR(tau_centre, -50.0 / 3.0 * (z_plus - z_minus) / (2 * h), 1e-6 * tau_centre);

  const CliRun fk = run("fk " + example("delta.yaml") + " --q " + a[7] + "," + a[8] + "," + a[9]);
  ASSERT_EQ(fk.status, 0) << fk.err;
  const auto fk_rows = lines(fk.out);
  ASSERT_EQ(fk_rows.size(), 2u);
  const auto f = split(fk_rows[1]);
  EXPECT_NEAR(std::stod(f[0]), 0.3, 1e-9);
  EXPECT_NEAR(std::stod(f[1]), 0.5, 1e-9);
  EXPECT_NEAR(std::stod(f[2]), -1.1, 1e-9);
  EXPECT_EQ(f[6], "1");
}

TEST_F(LegChainCli, AnalyzeAndFkOnTheHexaglide) {
  const std::string poses = write("poses.csv", "x,y,z,rx,ry,rz\n0.02,-0.03,0.62,2,-3,4\n");
  const CliRun r = run("analyze " + example("hexaglide.yaml") + " --poses " + poses);
  ASSERT_EQ(r.status, 0) << r.err;
  const auto rows = lines(r.out);
  ASSERT_EQ(rows.size(), 2u);
  const auto a = split(rows[1]);
  ASSERT_EQ(a.size(), 23u);
  EXPECT_EQ(a[6], "1");
  std::string q;
  for (int i = 0; i < 6; ++i) q += (i ? "," : "") + a[static_cast<std::size_t>(7 + i)];
  const CliRun fk = run("fk " + example("hexaglide.yaml") + " --q " + q);
  ASSERT_EQ(fk.status, 0) << fk.err;
  const auto f = split(lines(fk.out)[1]);
  const double expected[6] = {0.02, -0.03, 0.62, 2, -3, 4};
  for (int k = 0; k < 6; ++k)
    EXPECT_NEAR(std::stod(f[static_cast<std::size_t>(k)]), expected[k], 1e-8);
}

TEST_F(LegChainCli, WorkspaceOfTheDelta) {
  const fs::path out = dir_ / "ws";
  const CliRun r =
      run("workspace " + example("delta.yaml") + " --resolution 0.08 --out " + out.string());
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(r.out.rfind("workspace (constant_orientation): volume ", 0), 0u) << r.out;
  EXPECT_TRUE(fs::exists(out / "summary.json"));
  const std::string summary = cli_runner::read_text(out / "summary.json");
  EXPECT_NE(summary.find("\"model\": \"delta\""), std::string::npos);
}

TEST_F(LegChainCli, BadFilesExitWithStatusTwo) {
  const std::string base =
      "model: delta\nbase_radius: 0.164\nplatform_radius: 0.044\nupper_arm: 0.524\nrod: 1.244\n"
      "drive_range_deg: [-60, 100]\nrods: {E: 7.0e10, area: 5.0e-5}\n";
  const std::string poses = write("poses.csv", "x,y,z\n0,0,-0.9\n");
  const struct {
    std::string text;
    std::string fragment;
  } cases[] = {
      {base + "colour: red\n", "colour"},
      {"model: delta\nbase_radius: 0.164\n", "platform_radius"},
      {base + "tool: {tcp: [0, 0]}\n", "tcp"},
      {"model: delta\nbase_radius: .nan\nplatform_radius: 0.044\nupper_arm: 0.524\nrod: 1.244\n"
       "drive_range_deg: [-60, 100]\nrods: {E: 7.0e10, area: 5.0e-5}\n",
       "base_radius"},
      {"model: delta\nbase_radius: 0.164\nplatform_radius: 0.044\nupper_arm: 0.524\nrod: 1.244\n"
       "drive_range_deg: [100, -60]\nrods: {E: 7.0e10, area: 5.0e-5}\n",
       "drive_range_deg"},
      {"model: delta\nbase_radius: 0.164\nplatform_radius: 0.044\nupper_arm: -0.5\nrod: 1.244\n"
       "drive_range_deg: [-60, 100]\nrods: {E: 7.0e10, area: 5.0e-5}\n",
       "upper_arm"},
      {base + "branch: sideways\n", "branch"},
      {"model: delta\nbase_radius: 0.164\nplatform_radius: 0.044\nupper_arm: 0.524\nrod: 1.244\n"
       "drive_range_deg: [-60, 100]\nrods: {E: 7.0e10, axial_stiffness: 1e6}\n",
       "axial_stiffness"},
      {"model: hexaglide\nguides: {y: [0, 1, 2]}\nstrut: 0.8\n"
       "platform: {radius: 0.25, pair_separation_deg: 20}\nstroke: [-1, 1]\n"
       "struts: {E: 2.1e11, area: 3.0e-4}\n",
       "guides.y"},
      {"model: linear_delta\nguide_radius: 0.25\nplatform_radius: 0.04\nrod: 0.35\n"
       "stroke: [0, 0.6]\nrods: {E: 7e10, area: 3e-5}\ninclination_deg: 95\n",
       "inclination_deg"},
      {"model: tetrapod\n", "a known model"},
  };
  int k = 0;
  for (const auto& c : cases) {
    const std::string machine = write("bad" + std::to_string(k++) + ".yaml", c.text);
    const fs::path out = dir_ / "out.csv";
    const CliRun r = run("analyze " + machine + " --poses " + poses + " --out " + out.string());
    expect_input_error(r, c.fragment);
    EXPECT_FALSE(fs::exists(out));
  }
  // fk: wrong count of drive angles.
  expect_input_error(run("fk " + example("delta.yaml") + " --q 10,20"), "--q");
}

}  // namespace
}  // namespace pkmopt
