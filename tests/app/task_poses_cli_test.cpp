// Tests of `pkmopt task-poses`: the task poses of a design, lifted by its home_height, are the
// poses the study measured it at. Checked against `pkmopt analyze` of the design's machine file
// at those poses: every pose reachable, and the study's worst-case metrics in pareto.csv equal
// the worst over analyze's rows (two separate code paths through the models).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include "tests/cli_runner.hpp"
#include "tests/scratch_dir.hpp"

namespace {

namespace fs = std::filesystem;
using cli_runner::CliRun;
using cli_runner::read_text;

// A field as a number; NaN for an empty or text field.
double number_or_nan(const std::string& field) {
  char* end = nullptr;
  const double v = std::strtod(field.c_str(), &end);
  return field.empty() || *end != '\0' ? NAN : v;
}

// A CSV text as columns by name (numbers; an empty or text field is NaN).
std::map<std::string, std::vector<double>> columns_of(const std::string& csv) {
  std::istringstream in(csv);
  std::string line;
  std::getline(in, line);
  std::vector<std::string> names;
  std::stringstream header(line);
  for (std::string name; std::getline(header, name, ',');) names.push_back(name);
  std::map<std::string, std::vector<double>> columns;
  while (std::getline(in, line)) {
    std::stringstream row(line);
    std::size_t k = 0;
    for (std::string field; std::getline(row, field, ',') && k < names.size(); ++k)
      columns[names[k]].push_back(number_or_nan(field));
  }
  return columns;
}

class TaskPoses : public scratch::ScratchDirTest {
 protected:
  // hexapod-quick with a short NSGA-II run into dir_/out.
  void run_quick_study() {
    std::string text =
        read_text(fs::path(PKMOPT_SOURCE_DIR) / "studies" / "library" / "hexapod-quick.yaml");
    const std::string from = "population: 60, generations: 80";
    text.replace(text.find(from), from.size(), "population: 20, generations: 20");
    write("quick.yaml", text);
    const CliRun r = run_cli("run " + path("quick.yaml") + " --out " + path("out") +
                             " --no-progress --threads 2");
    ASSERT_EQ(r.status, 0) << r.err;
  }
};

TEST_F(TaskPoses, ADesignsPosesReproduceItsStudyMetrics) {
  run_quick_study();
  const auto front = columns_of(read_text(dir_ / "out" / "pareto.csv"));
  ASSERT_GE(front.at("stiffness_min").size(), 1u);
  const std::size_t designs = front.at("stiffness_min").size();
  for (std::size_t k = 0; k < designs; k += std::max<std::size_t>(1, designs / 3)) {
    const std::string id = "d" + std::string(4 - std::to_string(k).size(), '0') + std::to_string(k);
    const std::string design = path(fs::path("out") / "designs" / (id + ".yaml"));
    CliRun r = run_cli("task-poses " + path("quick.yaml") + " --design " + design + " --out " +
                       path("poses.csv"));
    ASSERT_EQ(r.status, 0) << r.err;
    const auto poses = columns_of(read_text(dir_ / "poses.csv"));
    ASSERT_EQ(poses.at("x").size(), 64u);  // 2 x 2 x 2 positions x 8 orientations
    // The lift: the box's lowest z (0.90 - 0.10) plus the design's home_height.
    const double lowest = *std::min_element(poses.at("z").begin(), poses.at("z").end());
    EXPECT_NEAR(lowest, 0.80 + front.at("home_height")[k], 1e-12) << id;

    r = run_cli("analyze " + design + " --poses " + path("poses.csv") +
                " --wrench 300,300,-3000,0,0,0");
    ASSERT_EQ(r.status, 0) << r.err;
    const auto rows = columns_of(r.out);
    for (double reachable : rows.at("reachable")) EXPECT_EQ(reachable, 1.0) << id;
    const double stiffness =
        *std::min_element(rows.at("stiffness_min").begin(), rows.at("stiffness_min").end());
    EXPECT_NEAR(stiffness / front.at("stiffness_min")[k], 1.0, 1e-9) << id;
    double force = 0.0;
    for (int leg = 1; leg <= 6; ++leg)
      for (double tau : rows.at("tau_" + std::to_string(leg)))
        force = std::max(force, std::abs(tau));
    // g_leg_force_max_max = leg_force_max - 10500 N.
    EXPECT_NEAR(force - 10500.0, front.at("g_leg_force_max_max")[k], 1e-6 * force) << id;
  }
}

TEST_F(TaskPoses, HomeHeightOrNoLift) {
  const std::string study =
      (fs::path(PKMOPT_SOURCE_DIR) / "studies" / "library" / "hexapod-quick.yaml").string();
  CliRun raw = run_cli("task-poses " + study);
  ASSERT_EQ(raw.status, 0) << raw.err;
  CliRun lifted = run_cli("task-poses " + study + " --home-height 0.125");
  ASSERT_EQ(lifted.status, 0) << lifted.err;
  const auto a = columns_of(raw.out), b = columns_of(lifted.out);
  ASSERT_EQ(a.at("z").size(), 64u);
  for (std::size_t k = 0; k < 64; ++k) {
    EXPECT_EQ(b.at("x")[k], a.at("x")[k]);
    EXPECT_NEAR(b.at("z")[k], a.at("z")[k] + 0.125, 1e-15);
    EXPECT_EQ(b.at("ry")[k], a.at("ry")[k]);
  }
  // The tilt cone of 20 degrees: the tool axis R e_z of R = Rz Ry Rx has the z component
  // cos(rx) cos(ry); no pose is tilted further, and some reach the rim.
  double tilt_max = 0.0;
  for (std::size_t k = 0; k < 64; ++k) {
    const double deg = std::numbers::pi / 180.0;
    const double tilt = std::acos(std::cos(a.at("rx")[k] * deg) * std::cos(a.at("ry")[k] * deg));
    tilt_max = std::max(tilt_max, tilt / deg);
  }
  EXPECT_NEAR(tilt_max, 20.0, 1e-9);
  EXPECT_NE(lifted.err.find("64 poses of 'hexapod-quick', lifted by home_height 0.125 m"),
            std::string::npos)
      << lifted.err;
}

TEST_F(TaskPoses, RefusesWhatHasNoTaskOrNoLift) {
  const fs::path library = fs::path(PKMOPT_SOURCE_DIR) / "studies" / "library";
  CliRun r = run_cli("task-poses " + (library / "zdt1-nsga2.yaml").string());
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("expected a design study"), std::string::npos) << r.err;
  // A machine file outside a run folder has no pareto.json to take its home_height from.
  r = run_cli("task-poses " + (library / "hexapod-quick.yaml").string() + " --design " +
              (fs::path(PKMOPT_SOURCE_DIR) / "examples" / "hexapod.yaml").string());
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("give the lift with --home-height"), std::string::npos) << r.err;
  r = run_cli("task-poses " + (library / "hexapod-quick.yaml").string() +
              " --home-height 0.1 --design x.yaml");
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("expected one of them, found both"), std::string::npos) << r.err;
  r = run_cli("task-poses " + (library / "hexapod-quick.yaml").string() + " --home-height 2e3");
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("--home-height: expected a length within +-1000 m"), std::string::npos)
      << r.err;
}

}  // namespace
