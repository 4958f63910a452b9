// Tests of `pkmopt workspace`: the files it writes and bad options failing with exit status 2,
// one message, and nothing written.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

#include "io/machine/machine_file.hpp"
#include "models/workspace/mode_certificate.hpp"
#include "models/workspace/workspace.hpp"
#include "tests/cli_runner.hpp"
#include "tests/scratch_dir.hpp"

namespace {

namespace fs = std::filesystem;

using cli_runner::CliRun;
using cli_runner::read_text;

class WorkspaceCli : public scratch::ScratchDirTest {
 protected:
  void SetUp() override {
    machine_ = (fs::path(PKMOPT_SOURCE_DIR) / "examples/hexapod.yaml").string();
  }

  CliRun run(const std::string& args) { return run_cli("workspace " + args); }

  void expect_input_error(const std::string& args, const std::string& fragment) {
    const fs::path out_dir = dir_ / "result";
    const CliRun r = run(args + " --out " + out_dir.string());
    EXPECT_EQ(r.status, 2) << args << "\n" << r.err;
    EXPECT_NE(r.err.find(fragment), std::string::npos) << args << "\nstderr: " << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_FALSE(fs::exists(out_dir)) << args;
  }

  std::string machine_;
};

TEST_F(WorkspaceCli, WritesSummaryMeshPointsAndSlices) {
  const fs::path out_dir = dir_ / "ws";
  const CliRun r =
      run(machine_ + " --resolution 0.04 --wrench 0,0,-1000,0,0,0 --out " + out_dir.string());
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(std::count(r.out.begin(), r.out.end(), '\n'), 1) << r.out;
  EXPECT_EQ(r.out.rfind("workspace (constant_orientation): volume ", 0), 0u) << r.out;

  const nlohmann::json summary = nlohmann::json::parse(read_text(out_dir / "summary.json"));
  // The same numbers as the library at the same options.
  pkmopt::WorkspaceOptions options;
  options.resolution = 0.04;
  options.wrench << 0, 0, -1000, 0, 0, 0;
  const auto machine = pkmopt::load_machine_file(machine_);
  const pkmopt::WorkspaceResult ws = pkmopt::compute_workspace(*machine, options);
  EXPECT_DOUBLE_EQ(summary.at("volume").get<double>(), ws.volume);
  EXPECT_DOUBLE_EQ(summary.at("convex_hull_volume").get<double>(), ws.convex_hull_volume);
  EXPECT_DOUBLE_EQ(summary.at("surface_volume").get<double>(), ws.surface_volume);
  EXPECT_DOUBLE_EQ(summary.at("global_conditioning_index").get<double>(),
                   ws.maps.global_conditioning_index);
  EXPECT_DOUBLE_EQ(summary.at("max_leg_force").get<double>(), ws.maps.max_leg_force);
  EXPECT_DOUBLE_EQ(summary.at("envelope_ratio").get<double>(), *ws.envelope_ratio);
  EXPECT_EQ(summary.at("resolution").get<double>(), 0.04);
  EXPECT_EQ(summary.at("kind").get<std::string>(), "constant_orientation");
  EXPECT_GT(summary.at("seconds").get<double>(), 0.0);
  for (const char* key :
       {"stiffness_min_min", "stiffness_min_mean", "tcp_error_max", "tcp_deflection_max",
        "stiffness_min_loaded_min", "singularity_margin_min", "envelope_volume", "voxel_volume"}) {
    EXPECT_TRUE(summary.at(key).is_number()) << key;
  }
  EXPECT_GE(ws.convex_hull_volume, ws.volume);

  // PLY header counts match the binary STL triangle count.
  const std::string ply = read_text(out_dir / "boundary.ply");
  const std::string vertex_line =
      "element vertex " + std::to_string(ws.boundary.vertices.size()) + "\n";
  const std::string face_line =
      "element face " + std::to_string(ws.boundary.triangles.size()) + "\n";
  EXPECT_EQ(ply.rfind("ply\nformat ascii 1.0\n", 0), 0u);
  EXPECT_NE(ply.find(vertex_line), std::string::npos);
  EXPECT_NE(ply.find(face_line), std::string::npos);
  const std::string stl = read_text(out_dir / "boundary.stl");
  ASSERT_GE(stl.size(), 84u);
  EXPECT_EQ(stl.size(), 84u + 50u * ws.boundary.triangles.size());

  // Point cloud: header and one row per inside node.
  const std::string csv = read_text(out_dir / "points.csv");
  EXPECT_EQ(csv.rfind("x,y,z,singularity_margin,stiffness_min,max_leg_force,tcp_error_max,"
                      "tcp_deflection,stiffness_min_loaded\n",
                      0),
            0u);
  EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), ws.inside_nodes + 1);

  // Slice pictures.
  const std::string svg = read_text(out_dir / "slice_z.svg");
  EXPECT_EQ(svg.rfind("<svg", 0), 0u);
  EXPECT_NE(svg.find("x [mm]"), std::string::npos);
  EXPECT_NE(svg.find("y [mm]"), std::string::npos);
  EXPECT_NE(svg.find("</svg>"), std::string::npos);
  const std::string png = read_text(out_dir / "slice_z.png");
  ASSERT_GT(png.size(), 8u);
  EXPECT_EQ(png.substr(0, 8), std::string("\x89PNG\r\n\x1a\n", 8));
  // No temporaries left behind.
  for (const auto& entry : fs::directory_iterator(out_dir)) {
    EXPECT_EQ(entry.path().filename().string().find(".tmp."), std::string::npos);
  }
}

TEST_F(WorkspaceCli, OrientationWorkspaceAndNoOutFolder) {
  const CliRun some = run(machine_ +
                          " --resolution 0.08 --tilt 10 --orientation-step 10 "
                          "--mode some --slice-axis x --slice-metric stiffness_min "
                          "--slice-pixel 0.02");
  ASSERT_EQ(some.status, 0) << some.err;
  EXPECT_EQ(some.out.rfind("workspace (some_orientation): volume ", 0), 0u) << some.out;
  const CliRun all = run(machine_ +
                         " --resolution 0.08 --tilt 10 --yaw-range 5 "
                         "--orientation-step 10 --slice-pixel 0.02");
  ASSERT_EQ(all.status, 0) << all.err;
  EXPECT_EQ(all.out.rfind("workspace (all_orientations): volume ", 0), 0u) << all.out;
}

// A machine file with masses: points.csv gains natural_frequency_1, summary.json
// natural_frequency_min (their minimum, the library's), and the slice can show it.
TEST_F(WorkspaceCli, MassesAddTheFirstNaturalFrequencyToTheMaps) {
  const std::string file = (fs::path(PKMOPT_SOURCE_DIR) / "examples/hexapod_masses.yaml").string();
  const fs::path out_dir = dir_ / "wsm";
  const CliRun r =
      run(file + " --resolution 0.05 --slice-metric natural_frequency_1 --out " + out_dir.string());
  ASSERT_EQ(r.status, 0) << r.err;
  const std::string csv = read_text(out_dir / "points.csv");
  EXPECT_EQ(csv.rfind("x,y,z,singularity_margin,stiffness_min,max_leg_force,tcp_error_max,"
                      "tcp_deflection,stiffness_min_loaded,natural_frequency_1\n",
                      0),
            0u);
  pkmopt::WorkspaceOptions options;
  options.resolution = 0.05;
  options.keep_points = true;
  const auto machine = pkmopt::load_machine_file(file);
  const pkmopt::WorkspaceResult ws = pkmopt::compute_workspace(*machine, options);
  ASSERT_TRUE(ws.maps.natural_frequencies);
  double lowest = 1e300;
  for (const pkmopt::WorkspacePoint& p : ws.points) {
    EXPECT_GT(p.metrics.natural_frequency_1, 10.0);
    lowest = std::min(lowest, p.metrics.natural_frequency_1);
  }
  const nlohmann::json summary = nlohmann::json::parse(read_text(out_dir / "summary.json"));
  EXPECT_DOUBLE_EQ(summary.at("natural_frequency_min").get<double>(), lowest);
  EXPECT_DOUBLE_EQ(ws.maps.natural_frequency_min, lowest);
  EXPECT_NE(read_text(out_dir / "slice_z.svg").find("natural_frequency_1 [Hz]"), std::string::npos);
  // Without masses: no such column or key, and the slice metric is refused.
  EXPECT_FALSE(pkmopt::compute_workspace(*pkmopt::load_machine_file(machine_), options)
                   .maps.natural_frequencies);
  expect_input_error(machine_ + " --slice-metric natural_frequency_1", "has no masses");
}

TEST_F(WorkspaceCli, BadOptionsFailWithStatusTwoAndWriteNothing) {
  expect_input_error(machine_ + " --resolution 0", "--resolution");
  expect_input_error(machine_ + " --resolution -0.1", "--resolution");
  expect_input_error(machine_ + " --resolution 1e-5", "max_grid_nodes");
  expect_input_error(machine_ + " --tilt 200", "--tilt");
  expect_input_error(machine_ + " --yaw-range -5", "--yaw-range");
  expect_input_error(machine_ + " --orientation-step 0", "--orientation-step");
  expect_input_error(machine_ + " --tilt 179 --yaw-range 179 --orientation-step 0.01",
                     "--orientation-step: expected a step that samples at most 1000000");
  expect_input_error(machine_ + " --mode most", "--mode");
  expect_input_error(machine_ + " --orientation 1,2", "--orientation");
  expect_input_error(machine_ + " --wrench 1,2,3", "--wrench");
  expect_input_error(machine_ + " --min-margin 1.5", "--min-margin");
  expect_input_error(machine_ + " --min-stiffness -1", "--min-stiffness");
  expect_input_error(machine_ + " --slice-axis w", "--slice-axis");
  expect_input_error(machine_ + " --slice-metric volume", "--slice-metric");
  expect_input_error(machine_ + " --slice-pixel 0", "--slice-pixel");
  expect_input_error((dir_ / "missing.yaml").string(), "missing.yaml");
  const fs::path bad = dir_ / "bad.yaml";
  std::ofstream(bad) << read_text(machine_) << "colour: red\n";
  expect_input_error(bad.string(), "colour");
  // A value CLI11 cannot convert (its message has a second line pointing at --help).
  const CliRun not_a_number = run(machine_ + " --resolution abc --out " + (dir_ / "r").string());
  EXPECT_EQ(not_a_number.status, 2);
  EXPECT_NE(not_a_number.err.find("--resolution"), std::string::npos) << not_a_number.err;
  EXPECT_FALSE(fs::exists(dir_ / "r"));
  // --out naming an existing file.
  const fs::path file = dir_ / "a_file";
  std::ofstream(file) << "x";
  const CliRun r = run(machine_ + " --resolution 0.05 --out " + file.string());
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("--out"), std::string::npos) << r.err;
  EXPECT_EQ(read_text(file), "x");
}

// --certify on the sample hexapod: one working mode over its constant-orientation workspace,
// the same certificate as the library's over the same cells; on a long-legged variant turned
// near Fichter's singularity (90 degrees about z), not certified, every cell reported.
TEST_F(WorkspaceCli, CertifyProvesOneWorkingModeOrSaysWhereItCannot) {
  const fs::path out_dir = dir_ / "cert";
  CliRun r = run(machine_ + " --resolution 0.04 --certify --out " + out_dir.string());
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("certificate: one working mode (det J < 0) over the workspace's "),
            std::string::npos)
      << r.out;
  const nlohmann::json c = nlohmann::json::parse(read_text(out_dir / "certificate.json"));
  EXPECT_TRUE(c.at("certified").get<bool>());
  EXPECT_EQ(c.at("det_j_sign").get<int>(), -1);
  EXPECT_EQ(c.at("uncertified_first_boxes").get<int>(), 0);
  EXPECT_EQ(c.at("settings").at("min_size_m").get<double>(), 0.01);  // resolution / 4
  EXPECT_EQ(read_text(out_dir / "uncertified.csv"),
            "x_lo,x_hi,y_lo,y_hi,z_lo,z_hi,tilt_lo,tilt_hi,azimuth_lo,azimuth_hi,yaw_lo,yaw_hi,"
            "parts,uncertified_fraction,centre_margin,centre_det_sign,budget\n");
  // The library over the same cells gives the same boxes and margin.
  const auto machine = pkmopt::load_machine_file(machine_);
  pkmopt::WorkspaceOptions options;
  options.resolution = 0.04;
  options.keep_points = true;
  const pkmopt::WorkspaceResult ws = pkmopt::compute_workspace(*machine, options);
  pkmopt::CertifyOptions certify;
  certify.min_size = 0.01;
  const pkmopt::ModeCertificate library = pkmopt::certify_working_mode(
      *machine->jacobian_enclosure().get(),
      pkmopt::workspace_cells(ws.points, ws.resolution,
                              pkmopt::orientation_box(options.orientations)),
      certify);
  EXPECT_EQ(c.at("region").at("first_boxes").get<std::size_t>(), ws.points.size());
  EXPECT_EQ(c.at("certified_boxes").at("det_j_negative").get<std::int64_t>(),
            library.negative_boxes);
  EXPECT_EQ(c.at("certified_margin_min").get<double>(), library.min_margin);

  // Legs to 1.4 m, joints to 80 degrees; turned 85 +- 10 degrees about z.
  const fs::path long_legged = dir_ / "long.yaml";
  std::ofstream(long_legged) << "model: hexapod\n"
                                "base: {radius: 0.60, pair_separation_deg: 20}\n"
                                "platform: {radius: 0.25, pair_separation_deg: 20}\n"
                                "legs: {min_length: 0.70, max_length: 1.40, E: 2.1e11, area: "
                                "3.0e-4, actuator_stiffness: 2.0e8}\n"
                                "joints: {base_max_angle_deg: 80, platform_max_angle_deg: 80}\n"
                                "tool: {tcp: [0, 0, -0.10]}\n";
  const fs::path near = dir_ / "near";
  r = run(long_legged.string() +
          " --orientation 0,0,85 --yaw-range 10 --orientation-step 4 --resolution 0.1 --certify "
          "--certify-size 0.03 --out " +
          near.string());
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("certificate: NOT certified over the workspace's "), std::string::npos)
      << r.out;
  EXPECT_NE(r.err.find("pkmopt: warning: the workspace is not certified"), std::string::npos)
      << r.err;
  const nlohmann::json n = nlohmann::json::parse(read_text(near / "certificate.json"));
  EXPECT_FALSE(n.at("certified").get<bool>());
  const int cells = n.at("region").at("first_boxes").get<int>();
  EXPECT_EQ(n.at("uncertified_first_boxes").get<int>(), cells);
  const std::string csv = read_text(near / "uncertified.csv");
  EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), cells + 1);
  // Near the singularity: every reported cell's smallest centre margin is below 0.05.
  EXPECT_LT(n.at("uncertified_centre_margin_min").get<double>(), 0.05);
}

TEST_F(WorkspaceCli, CertifyOptionsAreChecked) {
  expect_input_error(machine_ + " --certify-size 0.01", "expected only together with --certify");
  expect_input_error(machine_ + " --certify --certify-size 0", "--certify-size");
  expect_input_error(machine_ + " --certify --certify-margin 1.5", "--certify-margin");
  expect_input_error((fs::path(PKMOPT_SOURCE_DIR) / "examples/delta.yaml").string() + " --certify",
                     "--certify: expected a machine whose Jacobian can be enclosed");
}

}  // namespace
