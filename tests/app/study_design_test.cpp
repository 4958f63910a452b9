// Tests of app/study_design: strict design study files and a small study end to end.
#include "app/study_design.hpp"

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "app/input_error.hpp"
#include "app/machine_file.hpp"

namespace pkmopt {
namespace {

namespace fs = std::filesystem;

const char* const kStudy =
    "study: tiny\n"
    "machine:\n"
    "  model: hexapod\n"
    "  parameters:\n"
    "    base_radius: {min: 0.5, max: 0.7}\n"
    "    platform_pair_separation_deg: {min: 10, max: 40}\n"
    "  legs: {E: 2.1e11, area: 3.0e-4}\n"
    "  joints: {base_max_angle_deg: 45, platform_max_angle_deg: 45}\n"
    "  tool: {tcp: [0, 0, -0.10]}\n"
    "task:\n"
    "  region: {shape: box, centre: [0, 0, 0.9], size: [0.2, 0.2, 0.1], points: [2, 2, 1]}\n"
    "  orientations: {tilt_deg: 10, step_deg: 10}\n"
    "  wrench: [0, 0, -3000, 0, 0, 0]\n"
    "objectives:\n"
    "  - maximize: stiffness_min\n"
    "  - minimize: machine_size\n"
    "constraints:\n"
    "  - task_reachable\n"
    "  - {metric: leg_force_max, max: 10500}\n"
    "optimizer: {algorithm: nsga2, population: 12, generations: 4, seed: 5}\n";

fs::path write_study(const std::string& name, const std::string& text) {
  const fs::path dir = fs::temp_directory_path() / ("pkmopt_study_design_test_" + name);
  fs::remove_all(dir);
  fs::create_directories(dir);
  std::ofstream(dir / "study.yaml") << text;
  return dir;
}

std::string load_error(const std::string& name, const std::string& text) {
  const fs::path dir = write_study(name, text);
  try {
    load_design_study((dir / "study.yaml").string());
  } catch (const InputError& error) {
    return error.what();
  }
  return "no error";
}

std::string replaced(std::string text, const std::string& from, const std::string& to) {
  const std::size_t at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  return text.replace(at, from.size(), to);
}

TEST(DesignStudy, LoadsTheProblemItDescribes) {
  const fs::path dir = write_study("load", kStudy);
  const DesignStudy study = load_design_study((dir / "study.yaml").string());
  EXPECT_EQ(study.name, "tiny");
  EXPECT_TRUE(is_design_study_file((dir / "study.yaml").string()));
  const HexapodDesignProblem& problem = *study.problem;
  ASSERT_EQ(problem.free_parameters().size(), 2u);
  EXPECT_EQ(problem.bounds().lower[1], deg_to_rad(10));  // degrees in the file, rad inside
  EXPECT_EQ(problem.num_objectives(), 2u);
  EXPECT_EQ(problem.num_inequality(), 2u);
  // 4 points x (1 + 7) orientations: the rim of a 10 deg cone sampled every 10 deg holds
  // max(4, ceil(2 pi sin(10 deg) / 10 deg)) = 7 azimuths.
  EXPECT_EQ(problem.spec().task.poses.size(), 4u * 8u);
  EXPECT_EQ(problem.spec().formulation, DesignFormulation::aggregate);
  EXPECT_EQ(study.optimizer.seed, 5u);
}

TEST(DesignStudy, SchemaErrorsNameFileLineKeyExpectedAndFound) {
  const std::string file =
      (fs::temp_directory_path() / "pkmopt_study_design_test_e1" / "study.yaml").string();
  EXPECT_EQ(load_error("e1", replaced(kStudy, "    base_radius:", "    base_radiu:")),
            file +
                ":5:5: machine.parameters.base_radiu: unknown key 'base_radiu'; allowed keys here: "
                "base_radius, platform_radius, base_pair_separation_deg, "
                "platform_pair_separation_deg, min_length, stroke, home_height");
  const std::string file2 =
      (fs::temp_directory_path() / "pkmopt_study_design_test_e2" / "study.yaml").string();
  EXPECT_EQ(load_error("e2", replaced(kStudy, "maximize: stiffness_min", "maximize: stifness")),
            file2 +
                ":15:15: objectives[0].maximize: expected one of stiffness_min, "
                "singularity_margin, leg_force_max, tcp_error_max, workspace_volume, "
                "conditioning_index, machine_size, found 'stifness'");
  const std::string file3 =
      (fs::temp_directory_path() / "pkmopt_study_design_test_e3" / "study.yaml").string();
  EXPECT_EQ(load_error("e3", replaced(kStudy, "{min: 0.5, max: 0.7}", "{min: 0.7, max: 0.5}")),
            file3 + ":5:34: machine.parameters.base_radius.max: expected max > min, found '0.5'");
  const std::string file4 =
      (fs::temp_directory_path() / "pkmopt_study_design_test_e4" / "study.yaml").string();
  EXPECT_EQ(
      load_error("e4", replaced(kStudy, "task:\n", "tasks:\n")),
      file4 +
          ":10:1: tasks: unknown key 'tasks'; allowed keys here: study, description, machine, "
          "task, objectives, constraints, optimizer, output");
}

TEST(DesignStudy, SmallStudyEndToEnd) {
  const fs::path dir = write_study("run", kStudy);
  const std::string command = std::string(PKMOPT_CLI) + " run " + (dir / "study.yaml").string() +
                              " --out " + (dir / "out").string() + " --threads 1 > " +
                              (dir / "log.txt").string() + " 2>&1";
  ASSERT_EQ(std::system(command.c_str()), 0);
  std::ifstream csv(dir / "out" / "pareto.csv");
  std::string header, row;
  std::getline(csv, header);
  EXPECT_EQ(header,
            "id,base_radius,platform_pair_separation_deg,stiffness_min,machine_size,"
            "g_leg_force_max_max,g_task_reachable,feasible,failure");
  int rows = 0;
  while (std::getline(csv, row)) {
    ++rows;
    EXPECT_EQ(row.find("nan"), std::string::npos) << row;
    EXPECT_NE(row.find(",1,\"\""), std::string::npos) << row;  // feasible, no failure
    const std::string id = row.substr(0, row.find(','));
    const auto machine = load_machine_file((dir / "out" / "designs" / (id + ".yaml")).string());
    EXPECT_EQ(machine->model(), "hexapod");
  }
  EXPECT_GT(rows, 0);
  EXPECT_TRUE(fs::exists(dir / "out" / "summary.json"));
}

}  // namespace
}  // namespace pkmopt
