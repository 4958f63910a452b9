// Tests of the leg-chain machine files (io/machine/machine_file_leg_chain) and of `pkmopt analyze`,
// `fk`, `workspace` and `describe` on a delta, a hexaglide, a Schoenflies machine in the generic
// `leg_chain` form and the tripod_3prs head: results agree with the library, revolute
// coordinates are in degrees, bad input exits with status 2 and one message.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "io/format/csv.hpp"
#include "io/format/input_error.hpp"
#include "io/machine/machine_file.hpp"
#include "io/machine/machine_file_leg_chain.hpp"
#include "models/leg_chain/leg_chain.hpp"
#include "tests/cli_runner.hpp"
#include "tests/scratch_dir.hpp"

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

class LegChainCli : public scratch::ScratchDirTest {
 protected:
  CliRun run(const std::string& args) { return run_cli(args); }
  void expect_input_error(const CliRun& r, const std::string& fragment) {
    EXPECT_EQ(r.status, 2) << r.err;
    EXPECT_NE(r.err.find(fragment), std::string::npos) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  }
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
            "singularity_margin,det_j,tcp_error_max,tcp_deflection,tcp_rotation_deflection_deg,"
            "stiffness_min_loaded,stiffness_dir_x,stiffness_dir_y,stiffness_dir_z,label");
  const auto a = split(rows[1]);
  ASSERT_EQ(a.size(), 24u);
  EXPECT_EQ(a[6], "1");
  EXPECT_NEAR(std::stod(a[7]), 47.5, 0.05);
  EXPECT_NEAR(std::stod(a[8]), -11.6, 0.05);
  EXPECT_NEAR(std::stod(a[9]), 21.4, 0.05);
  EXPECT_EQ(a[23], "a");
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
  EXPECT_EQ(std::stod(a[17]), m.tcp_deflection);
  EXPECT_EQ(std::stod(a[19]), m.stiffness_min_loaded);
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
  ASSERT_EQ(a.size(), 29u);
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

TEST_F(LegChainCli, SchoenfliesAndTripodExamplesLoad) {
  const auto schoenflies = load_machine_file(example("schoenflies_4pus.yaml"));
  EXPECT_EQ(schoenflies->model(), "leg_chain");
  EXPECT_EQ(schoenflies->num_actuators(), 4);
  const auto& lc = dynamic_cast<const LegChainMachine&>(*schoenflies);
  EXPECT_EQ(lc.design().mobility, PlatformMobility::kSchoenflies);
  EXPECT_EQ(lc.design().rotation_axis, Eigen::Vector3d::UnitZ());
  EXPECT_EQ(lc.design().legs[1].base_point, Eigen::Vector3d(0.0, 0.4, 0.0));
  EXPECT_EQ(lc.design().legs[1].rods, 2);
  EXPECT_EQ(lc.design().legs[1].branch, -1);
  EXPECT_DOUBLE_EQ(lc.design().legs[1].base_max_angle, deg_to_rad(80));
  const auto tripod = load_machine_file(example("tripod_3prs.yaml"));
  EXPECT_EQ(tripod->model(), "tripod_3prs");
  EXPECT_EQ(tripod->num_actuators(), 3);
  const Tripod3PrsDesign d =
      read_tripod_3prs_design(YamlValue::load_file(example("tripod_3prs.yaml")));
  const Tripod3PrsDesign defaults;
  EXPECT_EQ(d.base_radius, defaults.base_radius);
  EXPECT_EQ(d.platform_radius, defaults.platform_radius);
  EXPECT_EQ(d.strut, defaults.strut);
  EXPECT_EQ(d.q_min, defaults.q_min);
  EXPECT_EQ(d.q_max, defaults.q_max);
  EXPECT_EQ(d.tool_length, defaults.tool_length);
  EXPECT_DOUBLE_EQ(d.revolute_max_angle, defaults.revolute_max_angle);
  EXPECT_DOUBLE_EQ(d.platform_max_angle, defaults.platform_max_angle);
}

// analyze and fk on the Schoenflies example: a pose turned about e = z round-trips; a tilted pose
// is not reachable.
TEST_F(LegChainCli, AnalyzeAndFkOnTheSchoenfliesExample) {
  const std::string poses =
      write("poses.csv", "x,y,z,rx,ry,rz\n0.03,-0.02,0.05,0,0,15\n0.03,-0.02,0.05,2,0,15\n");
  const CliRun r = run("analyze " + example("schoenflies_4pus.yaml") + " --poses " + poses +
                       " --wrench 10,-20,-100,1,2,3");
  ASSERT_EQ(r.status, 0) << r.err;
  const auto rows = lines(r.out);
  ASSERT_EQ(rows.size(), 3u);
  const auto a = split(rows[1]);
  ASSERT_EQ(a.size(), 25u);
  EXPECT_EQ(a[6], "1");
  EXPECT_EQ(split(rows[2])[6], "0");
  std::string q;
  for (int i = 0; i < 4; ++i) q += (i ? "," : "") + a[static_cast<std::size_t>(7 + i)];
  for (int i = 0; i < 4; ++i)
    EXPECT_TRUE(std::isfinite(std::stod(a[static_cast<std::size_t>(11 + i)])));
  const CliRun fk = run("fk " + example("schoenflies_4pus.yaml") + " --q " + q);
  ASSERT_EQ(fk.status, 0) << fk.err;
  const auto f = split(lines(fk.out)[1]);
  const double expected[6] = {0.03, -0.02, 0.05, 0, 0, 15};
  for (int k = 0; k < 6; ++k)
    EXPECT_NEAR(std::stod(f[static_cast<std::size_t>(k)]), expected[k], 1e-8);
  const CliRun describe = run("describe " + example("schoenflies_4pus.yaml"));
  ASSERT_EQ(describe.status, 0) << describe.err;
  EXPECT_NE(describe.out.find("dof: 4 (3 translations, 1 rotations)"), std::string::npos)
      << describe.out;
}

// analyze on the tripod: the given x, y, rz are ignored (parasitic); fk of the computed slide
// positions returns z, rx, ry and the parasitic x, y, rz; workspace and describe run.
TEST_F(LegChainCli, AnalyzeFkWorkspaceDescribeOnTheTripod) {
  const std::string poses =
      write("poses.csv", "x,y,z,rx,ry,rz\n0,0,1.2,30,-20,0\n0.5,-0.5,1.2,30,-20,7\n");
  const CliRun r = run("analyze " + example("tripod_3prs.yaml") + " --poses " + poses);
  ASSERT_EQ(r.status, 0) << r.err;
  const auto rows = lines(r.out);
  ASSERT_EQ(rows.size(), 3u);
  const auto a = split(rows[1]);
  const auto b = split(rows[2]);
  ASSERT_EQ(a.size(), 23u);
  EXPECT_EQ(a[6], "1");
  for (std::size_t k = 6; k < a.size(); ++k) EXPECT_EQ(a[k], b[k]) << k;  // same machine pose
  const CliRun fk =
      run("fk " + example("tripod_3prs.yaml") + " --q " + a[7] + "," + a[8] + "," + a[9]);
  ASSERT_EQ(fk.status, 0) << fk.err;
  const auto f = split(lines(fk.out)[1]);
  EXPECT_NEAR(std::stod(f[2]), 1.2, 1e-9);
  EXPECT_NEAR(std::stod(f[3]), 30, 1e-8);
  EXPECT_NEAR(std::stod(f[4]), -20, 1e-8);
  const auto machine = load_machine_file(example("tripod_3prs.yaml"));
  const auto actual = dynamic_cast<const LegChainMachine&>(*machine).actual_pose(
      Pose{{0, 0, 1.2}, deg_to_rad(Eigen::Vector3d(30, -20, 0))});
  ASSERT_TRUE(actual.has_value());
  EXPECT_NEAR(std::stod(f[0]), actual->position.x(), 1e-9);
  EXPECT_NEAR(std::stod(f[1]), actual->position.y(), 1e-9);
  EXPECT_NEAR(std::stod(f[5]), rad_to_deg(actual->angles(2)), 1e-8);
  EXPECT_GT(actual->position.head<2>().norm(), 1e-3);  // parasitic x, y of several mm

  // Workspace of the level head: its bounding box spans the z travel of the level platform,
  // from the strut drop sqrt(0.55^2 - 0.15^2) plus the tool (0.2 m) to that plus the stroke.
  const fs::path out = dir_ / "ws";
  const CliRun ws = run("workspace " + example("tripod_3prs.yaml") + " --resolution 0.05 --out " +
                        out.string() + " --slice-pixel 0.01");
  ASSERT_EQ(ws.status, 0) << ws.err;
  const std::string summary = cli_runner::read_text(out / "summary.json");
  const auto bbox = summary.find("\"bounding_box\"");
  ASSERT_NE(bbox, std::string::npos) << summary;
  // "min": [x, y, z] then "max": [x, y, z]: the third numbers.
  auto third_number_after = [&](const std::string& key, std::size_t from) {
    std::size_t at = summary.find(key, from);
    at = summary.find('[', at);
    std::string inner = summary.substr(at + 1, summary.find(']', at) - at - 1);
    const auto parts = split(inner);
    return std::stod(parts.at(2));
  };
  const double drop = std::sqrt(0.55 * 0.55 - 0.15 * 0.15) + 0.2;
  EXPECT_NEAR(third_number_after("\"min\"", bbox), drop, 1e-3);
  EXPECT_NEAR(third_number_after("\"max\"", bbox), drop + 0.95, 1e-3);
  const CliRun describe = run("describe " + example("tripod_3prs.yaml"));
  ASSERT_EQ(describe.status, 0) << describe.err;
  EXPECT_NE(describe.out.find("dof: 3 (1 translations, 2 rotations)"), std::string::npos)
      << describe.out;
}

// The generic form written from the tripod_3prs design (mobility planar_legs) is the same
// machine: same actuator coordinates, metrics and parasitic pose.
TEST_F(LegChainCli, GenericFileReproducesTheTripod) {
  const LegChainDesign d = tripod_3prs_design(Tripod3PrsDesign{});
  auto vec = [](const Eigen::Vector3d& v) {
    return "[" + format_number(v.x()) + ", " + format_number(v.y()) + ", " + format_number(v.z()) +
           "]";
  };
  std::string text = "model: leg_chain\nmobility: planar_legs\ntool: {tcp: " + vec(d.tcp) +
                     "}\nhome: {position: " + vec(d.home.position) + "}\nlegs:\n";
  for (const LegChainLeg& leg : d.legs) {
    text += "  - kind: PUS\n    base_point: " + vec(leg.base_point) +
            "\n    axis: " + vec(leg.axis) +
            "\n    link_length: " + format_number(leg.link_length) +
            "\n    platform_point: " + vec(leg.platform_point) + "\n    range: [" +
            format_number(leg.q_min) + ", " + format_number(leg.q_max) +
            "]\n    link: {E: " + format_number(leg.E) + ", area: " + format_number(leg.area) +
            "}\n    actuator_stiffness: " + format_number(leg.actuator_stiffness) +
            "\n    joints: {base_max_angle_deg: " + format_number(rad_to_deg(leg.base_max_angle)) +
            ", platform_max_angle_deg: " + format_number(rad_to_deg(leg.platform_max_angle)) +
            ", base_axis: " + vec(leg.base_axis) + ", platform_axis: " + vec(leg.platform_axis) +
            "}\n    plane_normal: " + vec(leg.plane_normal) + "\n";
  }
  const auto generic = load_machine_file(write("generic.yaml", text));
  const auto named = make_tripod_3prs(Tripod3PrsDesign{});
  auto dg = generic->make_data();
  auto dn = named->make_data();
  const Pose pose{{0, 0, 1.1}, deg_to_rad(Eigen::Vector3d(25, -15, 0))};
  Wrench w;
  w << 100, -50, -300, 5, 10, -2;
  PoseMetrics mg, mn;
  generic->analyze(*dg, pose, w, mg);
  named->analyze(*dn, pose, w, mn);
  EXPECT_TRUE(mn.reachable);
  EXPECT_EQ(mg.reachable, mn.reachable);
  EXPECT_NEAR((mg.q - mn.q).norm(), 0.0, 1e-14);
  EXPECT_NEAR((mg.tau - mn.tau).norm(), 0.0, 1e-9 * mn.tau.norm());
  EXPECT_NEAR(mg.stiffness_min, mn.stiffness_min, 1e-9 * mn.stiffness_min);
  EXPECT_NEAR(mg.singularity_margin, mn.singularity_margin, 1e-12);
  const CliRun describe = run("describe " + write("generic2.yaml", text));
  ASSERT_EQ(describe.status, 0) << describe.err;
  EXPECT_NE(describe.out.find("dof: 3 (1 translations, 2 rotations)"), std::string::npos);
}

TEST_F(LegChainCli, BadLegChainAndTripodFilesExitWithStatusTwo) {
  const std::string leg =
      "  - kind: PUS\n    base_point: [0.4, 0, 0]\n    axis: [0, 0, 1]\n    link_length: 0.5\n"
      "    platform_point: [0.06, 0.1, 0]\n    range: [-0.5, 1.0]\n    branch: -1\n"
      "    link: {E: 7.0e10, area: 3.0e-5, rods: 2}\n";
  std::string four;
  for (int k = 0; k < 4; ++k) four += leg;
  const std::string head = "model: leg_chain\nmobility: schoenflies\nlegs:\n";
  const std::string tripod =
      "model: tripod_3prs\nbase_radius: 0.3\nplatform_radius: 0.15\nstruts: {E: 2.1e11, "
      "area: 6e-4}\n";
  const std::string poses = write("poses.csv", "x,y,z\n0,0,0\n");
  const struct {
    std::string text;
    std::string fragment;
  } cases[] = {
      {"model: leg_chain\nmobility: wobbly\nlegs:\n" + four, "mobility"},
      {head + leg + leg + leg, "legs"},           // 3 legs, 4 expected
      {head + four + "  - kind: XYZ\n", "legs"},  // 5 legs
      {"model: leg_chain\nmobility: schoenflies\nrotation_axis: [0, 0, 0]\nlegs:\n" + four,
       "rotation_axis"},
      {"model: leg_chain\nmobility: translational\nrotation_axis: [0, 0, 1]\nlegs:\n" + leg + leg +
           leg,
       "rotation_axis"},
      {head + leg + leg + leg + "  - kind: RUS\n    base_point: [0, 0, 0]\n", "legs[3]"},
      {head + leg + leg + leg + leg + "    colour: red\n", "colour"},
      {head + leg + leg + leg +
           "  - kind: PUS\n    base_point: [0.4, 0, 0]\n    axis: [0, 0, "
           "1]\n    link_length: 0.5\n    platform_point: [0.06, 0.1, 0]\n    range: [1.0, -0.5]\n"
           "    link: {E: 7.0e10, area: 3.0e-5}\n",
       "range"},
      {head + leg + leg + leg +
           "  - kind: PUS\n    base_point: [0.4, 0, 0]\n    axis: [0, 0, "
           "1]\n    link_length: 0.5\n    platform_point: [0.06, 0.1, 0]\n    range: [-0.5, 1.0]\n"
           "    branch: 2\n    link: {E: 7.0e10, area: 3.0e-5}\n",
       "branch"},
      {head + leg + leg + leg +
           "  - kind: UPS\n    base_point: [0.4, 0, 0]\n"
           "    platform_point: [0.06, 0.1, 0]\n    range: [0.5, 1.0]\n"
           "    link: {E: 7.0e10, area: 3.0e-5}\n    link_length: 0.5\n",
       "link_length"},
      {tripod + "strut: -0.55\nstroke: [0, 0.95]\n", "strut"},
      {tripod + "strut: 0.55\nstroke: [0.95, 0]\n", "stroke"},
      {tripod + "strut: 0.55\n", "stroke"},
      {tripod + "strut: 0.55\nstroke: [0, 0.95]\njoints: {revolute_max_angle_deg: 200}\n",
       "revolute_max_angle_deg"},
  };
  int k = 0;
  for (const auto& c : cases) {
    const std::string machine = write("bad" + std::to_string(k++) + ".yaml", c.text);
    const fs::path out = dir_ / "out.csv";
    const CliRun r = run("analyze " + machine + " --poses " + poses + " --out " + out.string());
    expect_input_error(r, c.fragment);
    EXPECT_FALSE(fs::exists(out)) << c.text;
  }
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
