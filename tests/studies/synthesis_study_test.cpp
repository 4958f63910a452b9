// Synthesis study files: candidates from the registry, the mobility filter (rules, then the rank
// of the inverse Jacobian on the task's motions), seeds, the resolved file and bad input.
#include "studies/synthesis_study.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "io/format/csv.hpp"
#include "io/format/input_error.hpp"

namespace pkmopt {
namespace {

// A synthesis study around a task section, with a small optimizer.
std::string study_text(const std::string& candidates, const std::string& task,
                       const std::string& extra = "") {
  return "study: t\n"
         "candidates: " +
         candidates +
         "\n"
         "task:\n" +
         task +
         "objectives:\n"
         "  - maximize: stiffness_min\n"
         "  - minimize: machine_size\n"
         "constraints:\n"
         "  - task_reachable\n"
         "optimizer: {algorithm: nsga2, population: 8, generations: 8, seed: 3}\n" +
         extra;
}

const std::string kBoxTask =
    "  region: {shape: box, centre: [0, 0, 0], size: [0.3, 0.3, 0.2], points: [2, 2, 2]}\n";

SynthesisStudy load(const std::string& text) {
  return load_synthesis_study(YamlValue::load_string(text, "synthesis.yaml"));
}

std::set<std::string> searched_names(const SynthesisStudy& s) {
  std::set<std::string> names;
  for (std::size_t k : s.searched()) names.insert(s.candidates[k].name);
  return names;
}

const SynthesisCandidate& candidate(const SynthesisStudy& s, const std::string& name) {
  for (const SynthesisCandidate& c : s.candidates)
    if (c.name == name) return c;
  throw std::runtime_error("no candidate " + name);
}

std::string load_error(const std::string& text) {
  try {
    load(text);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(SynthesisStudy, ThreeAxisTaskKeepsTheTranslationalStructures) {
  const SynthesisStudy s = load(study_text("auto", kBoxTask));
  EXPECT_EQ(s.motion.type(), "3T0R");
  EXPECT_EQ(s.motion.words(), "x, y, z");
  EXPECT_EQ(searched_names(s),
            (std::set<std::string>{"hexapod", "delta", "linear_delta", "hexaglide",
                                   "x_linear_delta", "x_hexaglide", "xy_tripod_3prs",
                                   "xy_tripod_3rps", "serial_table_ca", "serial_head_ca"}));
  const SynthesisCandidate& tripod = candidate(s, "tripod_3prs");
  EXPECT_FALSE(tripod.searched);
  EXPECT_NE(tripod.dropped.find("no x, y:"), std::string::npos) << tripod.dropped;
  EXPECT_NE(tripod.dropped.find("(1T2R)"), std::string::npos) << tripod.dropped;
  // Every searched structure passed the numeric check with full rank at the checked poses
  // where its middle design closes (the 5-axis machines have their tool along the C axis at
  // every pose of this task: no Jacobian, not checked).
  for (std::size_t k : s.searched())
    if (s.candidates[k].model != "serial") {
      EXPECT_TRUE(s.candidates[k].mobility.starts_with("J S of rank 3 of 3 at "))
          << s.candidates[k].name << ": " << s.candidates[k].mobility;
    }
  EXPECT_EQ(candidate(s, "hexapod").mobility, "J S of rank 3 of 3 at 8 of 8 checked task poses");
  // The task sits where each model works: the region's centre (the offset) plus its place.
  const SynthesisCandidate& hexapod = candidate(s, "hexapod");
  EXPECT_NEAR(hexapod.study->task_centre[2], 0.9, 1e-12);
  EXPECT_NEAR(candidate(s, "linear_delta").study->task_centre[2], -0.4, 1e-12);
}

// The installation space and the obstacles are written where the region is: each structure gets
// them moved to its task centre, with the region; the resolved file holds them moved.
TEST(SynthesisStudy, SpaceAndObstaclesMoveWithTheTask) {
  const SynthesisStudy s = load(study_text(
      "[hexapod, linear_delta]",
      kBoxTask + "  installation_space: {box: {min: [-1, -1, -1.5], max: [1, 1, 1]}}\n"
                 "  obstacles: [{box: {min: [0.5, 0.5, -0.2], max: [0.7, 0.7, 0.3]}}]\n"));
  for (const char* name : {"hexapod", "linear_delta"}) {
    const SynthesisCandidate& c = candidate(s, name);
    const double z = c.study->task_centre[2];
    const DesignTask& task = c.study->problem->task();
    EXPECT_NEAR(task.installation_space.min.z(), -1.5 + z, 1e-12) << name;
    EXPECT_NEAR(task.installation_space.max.z(), 1.0 + z, 1e-12) << name;
    ASSERT_EQ(task.obstacles.size(), 1u);
    EXPECT_NEAR(task.obstacles[0].min.z(), -0.2 + z, 1e-12) << name;
    EXPECT_NEAR(task.obstacles[0].max.x(), 0.7, 1e-12) << name;
    EXPECT_NE(c.study->resolved_yaml.find("  obstacles: [{box: {min: [0.5, 0.5, " +
                                          format_number(-0.2 + z) + "], max: [0.7, 0.7, " +
                                          format_number(0.3 + z) + "]}}]\n"),
              std::string::npos)
        << c.study->resolved_yaml;
  }
  EXPECT_NE(load_error(study_text("[hexapod]",
                                  kBoxTask + "  obstacles: [{box: {min: [0, 0, 0], max: [1, 0, "
                                             "1]}}]\n")),
            "");
  EXPECT_NE(load_error(study_text("[hexapod]", kBoxTask + "  obstacles: []\n"))
                .find("task.obstacles: expected a list of at least one obstacle"),
            std::string::npos);
}

TEST(SynthesisStudy, SixDofTaskKeepsOnlySixDofStructures) {
  // Tilt and yaw: only a platform with six degrees of freedom can make the task; every other
  // structure carries the motions it lacks.
  const SynthesisStudy s = load(
      study_text("auto", kBoxTask + "  orientations: {tilt_deg: 15, yaw_deg: 10, step_deg: 15}\n"));
  EXPECT_EQ(s.motion.type(), "3T3R");
  EXPECT_EQ(searched_names(s), (std::set<std::string>{"hexapod", "hexaglide", "x_hexaglide"}));
  // The 5-axis machines leave the turn about the tool axis to the spindle; the gantry's head
  // cannot turn its tool either.
  for (const char* name : {"serial_table_ca", "serial_head_ca", "xy_tripod_3prs", "xy_tripod_3rps"})
    EXPECT_NE(candidate(s, name).dropped.find("no yaw about z:"), std::string::npos)
        << candidate(s, name).dropped;
  for (const char* name : {"delta", "linear_delta"}) {
    const SynthesisCandidate& c = candidate(s, name);
    EXPECT_FALSE(c.searched);
    EXPECT_TRUE(c.dropped.starts_with("no tilt about x, tilt about y, yaw about z:")) << c.dropped;
    EXPECT_NE(c.dropped.find("(3T0R) only"), std::string::npos) << c.dropped;
  }
  EXPECT_TRUE(candidate(s, "tripod_3prs").dropped.starts_with("no x, y, yaw about z:"))
      << candidate(s, "tripod_3prs").dropped;
  for (std::size_t k : s.searched())
    EXPECT_NE(s.candidates[k].mobility.find("rank 6 of 6"), std::string::npos)
        << s.candidates[k].mobility;
}

TEST(SynthesisStudy, TiltingColumnTaskKeepsTheTripod) {
  // A column of z with a tilt cone (1T2R): the 3-PRS head makes it, and so do the six-DOF
  // machines; the translational ones cannot tilt.
  const SynthesisStudy s = load(
      study_text("auto",
                 "  region: {shape: box, centre: [0, 0, 0], size: [0, 0, 0.2], points: [1, 1, 3]}\n"
                 "  orientations: {tilt_deg: 20, yaw_deg: 0, step_deg: 20}\n"));
  EXPECT_EQ(s.motion.type(), "1T2R");
  EXPECT_EQ(searched_names(s),
            (std::set<std::string>{"hexapod", "hexaglide", "x_hexaglide", "tripod_3prs",
                                   "tripod_3rps", "xy_tripod_3prs", "xy_tripod_3rps",
                                   "serial_table_ca", "serial_head_ca"}));
  EXPECT_TRUE(candidate(s, "delta").dropped.starts_with("no tilt about x, tilt about y:"));
}

TEST(SynthesisStudy, ArchitectureSingularHexapodIsDroppedByItsRank) {
  // Semi-regular layouts with base and platform separations adding to 120 deg put the platform
  // joints at the base joints' azimuths: similar hexagons, a Gough–Stewart platform singular at
  // every pose (Ma & Angeles 1991, "Architecture singularities of platform manipulators"). The
  // rules pass it (six degrees of freedom), the rank check drops it; 20 + 20 deg is an ordinary
  // hexapod.
  const std::string legs = "legs: {E: 2.1e11, area: 3.0e-4, actuator_stiffness: 2.0e8}";
  auto entry = [&](const std::string& name, int platform_separation) {
    return "{name: " + name +
           ", task_centre: [0, 0, 0.9], machine: {model: hexapod, parameters: {base_radius: 0.6, "
           "platform_radius: 0.3, base_pair_separation_deg: 20, platform_pair_separation_deg: " +
           std::to_string(platform_separation) +
           ", min_length: {min: 0.5, max: 0.9}, stroke: 0.6, home_height: 0}, " + legs + "}}";
  };
  const SynthesisStudy s =
      load(study_text("\n  - " + entry("similar", 100) + "\n  - " + entry("ordinary", 20),
                      kBoxTask + "  orientations: {tilt_deg: 10, yaw_deg: 10, step_deg: 10}\n"));
  const SynthesisCandidate& similar = candidate(s, "similar");
  EXPECT_FALSE(similar.searched);
  EXPECT_NE(similar.dropped.find("has rank 5 of 6 at every checked task pose"), std::string::npos)
      << similar.dropped;
  EXPECT_EQ(similar.origin, "the study file");
  EXPECT_TRUE(candidate(s, "ordinary").searched) << candidate(s, "ordinary").dropped;
}

TEST(SynthesisStudy, StructuresThatCannotMeasureTheGoalsAreDropped) {
  // task_singularity_free is proved for hexapods only: every other structure says why it is not
  // searched, and the study goes on with the hexapod.
  std::string text = study_text("auto", kBoxTask);
  const std::string reachable = "  - task_reachable\n";
  text.replace(text.find(reachable), reachable.size(), reachable + "  - task_singularity_free\n");
  const SynthesisStudy s = load(text);
  EXPECT_EQ(searched_names(s), (std::set<std::string>{"hexapod"}));
  const SynthesisCandidate& glide = candidate(s, "hexaglide");
  EXPECT_TRUE(glide.dropped.starts_with("cannot be measured: ")) << glide.dropped;
  EXPECT_NE(glide.dropped.find("task_singularity_free is computed only in hexapod design problems"),
            std::string::npos)
      << glide.dropped;
  // A mistake in the shared sections stops the study with its own message, not as drops.
  std::string typo = study_text("auto", kBoxTask);
  typo.replace(typo.find("minimize: machine_size"), 22, "minimize: machine_sise");
  EXPECT_NE(load_error(typo).find("objectives[1].minimize: expected one of stiffness_min"),
            std::string::npos)
      << load_error(typo);
  // A structure the study file writes is the user's: its mistakes stop the study.
  const std::string own = study_text(
      "[hexapod, {name: mine, task_centre: [0, 0, -0.4], machine: {model: linear_delta, "
      "parameters: {rod: {min: 0.4, max: 1.1}}, rods: {E: -1, area: 1.5e-4}}}]",
      kBoxTask);
  EXPECT_NE(load_error(own).find("candidates[1].machine.rods.E"), std::string::npos)
      << load_error(own);
}

// A study on the first natural frequency: the structures scaled from the task come with a mass
// model where their model takes one (the same 40 kg spindle platform, steel links); a serial
// machine and a gantry on a 3-PRS head have none and say why. Without a mass metric the templates
// carry no masses.
TEST(SynthesisStudy, MassMetricsGiveTheTemplatesMassesOrDropThem) {
  std::string text = study_text("auto", kBoxTask);
  text.replace(text.find("minimize: machine_size"), 22, "maximize: natural_frequency_min");
  const SynthesisStudy s = load(text);
  EXPECT_EQ(searched_names(s),
            (std::set<std::string>{"hexapod", "delta", "linear_delta", "hexaglide"}));
  for (const char* name : {"hexapod", "delta", "linear_delta", "hexaglide"}) {
    ASSERT_TRUE(candidate(s, name).study) << name;
    const std::string& resolved = candidate(s, name).study->resolved_yaml;
    EXPECT_NE(resolved.find("masses:"), std::string::npos) << resolved;
  }
  const std::string& serial = candidate(s, "serial_table_ca").dropped;
  EXPECT_NE(serial.find("natural_frequency_min needs a mass model: serial machines have no mass "
                        "model"),
            std::string::npos)
      << serial;
  const std::string& gantry = candidate(s, "xy_tripod_3prs").dropped;
  EXPECT_NE(gantry.find("its parallel module has parasitic motion (planar legs)"),
            std::string::npos)
      << gantry;
  const SynthesisStudy plain = load(study_text("auto", kBoxTask));
  ASSERT_TRUE(candidate(plain, "hexapod").study);
  EXPECT_EQ(candidate(plain, "hexapod").study->resolved_yaml.find("masses:"), std::string::npos);
}

TEST(SynthesisStudy, ListNamesModelsOrStructures) {
  // A model's name takes every structure it offers; a structure's name that one.
  const SynthesisStudy s = load(study_text("[serial, xy_tripod_3prs]", kBoxTask));
  std::set<std::string> names;
  for (const SynthesisCandidate& c : s.candidates) names.insert(c.name);
  EXPECT_EQ(names, (std::set<std::string>{"serial_table_ca", "serial_head_ca", "xy_tripod_3prs"}));
  EXPECT_EQ(candidate(s, "xy_tripod_3prs").model, "hybrid");
}

TEST(SynthesisStudy, SeedsDependOnTheStudySeedAndTheNameOnly) {
  const SynthesisStudy a = load(study_text("[hexapod, linear_delta]", kBoxTask));
  const SynthesisStudy b = load(study_text("[linear_delta, delta, hexapod]", kBoxTask));
  EXPECT_EQ(candidate(a, "hexapod").seed, candidate(b, "hexapod").seed);
  EXPECT_EQ(candidate(a, "linear_delta").seed, candidate(b, "linear_delta").seed);
  EXPECT_NE(candidate(a, "hexapod").seed, candidate(a, "linear_delta").seed);
  EXPECT_EQ(candidate(a, "hexapod").seed, candidate_seed(3, "hexapod"));
  EXPECT_NE(candidate_seed(3, "hexapod"), candidate_seed(4, "hexapod"));
  // The structure's own study carries its seed: run alone it makes the same search.
  const DesignStudy& own = *candidate(a, "hexapod").study;
  EXPECT_EQ(own.optimizer.seed, candidate_seed(3, "hexapod"));
  ASSERT_NE(own.optimizer.nsga2(), nullptr);
  EXPECT_EQ(own.optimizer.nsga2()->seed, candidate_seed(3, "hexapod"));
  EXPECT_EQ(a.nsga2.seed, 3u);
}

TEST(SynthesisStudy, ResolvedFileLoadsToTheSameStudy) {
  const SynthesisStudy s = load(
      study_text("auto", kBoxTask + "  wrench: [300, 300, -1000, 0, 0, 0]\n",
                 "allocation: {floor_generations: 3}\noutput: {designs: false, front_size: 20}\n"));
  const SynthesisStudy again = load(s.resolved_yaml);
  EXPECT_EQ(again.resolved_yaml, s.resolved_yaml);
  ASSERT_EQ(again.candidates.size(), s.candidates.size());
  for (std::size_t k = 0; k < s.candidates.size(); ++k) {
    EXPECT_EQ(again.candidates[k].name, s.candidates[k].name);
    EXPECT_EQ(again.candidates[k].searched, s.candidates[k].searched);
    EXPECT_EQ(again.candidates[k].seed, s.candidates[k].seed);
    if (s.candidates[k].searched) {
      EXPECT_EQ(again.candidates[k].study->resolved_yaml, s.candidates[k].study->resolved_yaml);
    }
  }
  EXPECT_EQ(again.allocation.floor_generations, 3u);
  EXPECT_EQ(again.front_size, 20u);
  EXPECT_FALSE(again.write_designs);
  // The default floor is a quarter of the generations, rounded up.
  EXPECT_EQ(load(study_text("[hexapod]", kBoxTask)).allocation.floor_generations, 2u);
}

TEST(SynthesisStudy, DocsCarryTheAllocationTable) {
  std::ifstream in(std::string(PKMOPT_SOURCE_DIR) + "/docs/design-studies.md");
  std::stringstream docs;
  docs << in.rdbuf();
  const std::string block = "<!-- fields: allocation -->\n" +
                            synthesis_fields_markdown("allocation") + "<!-- /fields -->\n";
  EXPECT_NE(docs.str().find(block), std::string::npos)
      << "docs/design-studies.md lacks the generated allocation table:\n"
      << block;
}

TEST(SynthesisStudy, BadInputSaysWhereAndWhat) {
  struct Case {
    std::string text;
    std::string expected;
  };
  const std::vector<Case> cases = {
      {study_text("all", kBoxTask), "synthesis.yaml:2:13: candidates: expected auto or a list"},
      {study_text("[]", kBoxTask), "expected auto or a list of at least one candidate"},
      {study_text("[hexapod, cube]", kBoxTask),
       "candidates[1]: expected a model that offers structures to a synthesis (hexapod, delta, "
       "linear_delta, hexaglide, tripod_3prs, tripod_3rps, hybrid, serial), one of its "
       "structures (hexapod, delta, linear_delta, hexaglide, tripod_3prs, tripod_3rps, "
       "x_linear_delta, x_hexaglide, xy_tripod_3prs, xy_tripod_3rps, serial_table_ca, "
       "serial_head_ca)"},
      {study_text("[hexapod, hexapod]", kBoxTask), "expected a candidate name not used before"},
      {study_text("[{name: a/b, machine: {model: hexapod}}]", kBoxTask),
       "expected a name of letters, digits, '-' and '_'"},
      {study_text("[{machine: {model: lathe_16k20f3}}]", kBoxTask),
       "expected task_centre (the model lathe_16k20f3 has no place for a synthesis task)"},
      {study_text("[{machine: {model: hexapod}, speed: 3}]", kBoxTask), "speed"},
      {study_text("[hexapod]", kBoxTask, "allocation: {floor_generations: 9}\n"),
       "allocation.floor_generations: expected at most the optimizer's generations (8)"},
      {study_text("[hexapod]", kBoxTask, "allocation: {rule: greedy}\n"), "allocation.rule"},
      {study_text("[delta, linear_delta]", kBoxTask + "  orientations: {tilt_deg: 20}\n"),
       "expected at least one structure that makes the task's motions (3T2R"},
  };
  for (const Case& c : cases) {
    const std::string error = load_error(c.text);
    EXPECT_NE(error.find(c.expected), std::string::npos)
        << "expected '" << c.expected << "' in '" << error << "'";
  }
  std::string text = study_text("[hexapod]", kBoxTask);
  text.replace(text.find("algorithm: nsga2"), 16, "algorithm: nsga3");
  EXPECT_NE(load_error(text).find("expected nsga2 (a synthesis runs NSGA-II on every structure)"),
            std::string::npos)
      << load_error(text);
}

}  // namespace
}  // namespace pkmopt
