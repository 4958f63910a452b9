// Tests of studies/design_study: strict design study files and a small study end to end.
#include "studies/design_study.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <string>

#include "io/format/csv.hpp"
#include "io/format/input_error.hpp"
#include "io/machine/machine_file.hpp"
#include "tests/cli_runner.hpp"
#include "tests/scratch_dir.hpp"

namespace pkmopt {
namespace {

namespace fs = std::filesystem;

// The range of a free parameter as the optimizer sees it: its bounds (internal units), checked
// against the study's file-unit range.
std::pair<double, double> free_range(const pkmopt::DesignStudy& study, const std::string& name) {
  const std::vector<int>& free = study.problem->free_parameters();
  for (std::size_t k = 0; k < free.size(); ++k) {
    const pkmopt::StudyParameter& p = study.parameters[static_cast<std::size_t>(free[k])];
    if (p.name != name) continue;
    const double lower = study.problem->bounds().lower[k];
    const double upper = study.problem->bounds().upper[k];
    EXPECT_EQ(p.unit, "m");
    EXPECT_EQ(p.min, lower);
    EXPECT_EQ(p.max, upper);
    return {lower, upper};
  }
  ADD_FAILURE() << name << " is not a free parameter";
  return {0.0, 0.0};
}

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

// Every test has its own scratch folder; write_study(name, text) writes <dir_>/<name>/study.yaml.
class DesignStudyTest : public scratch::ScratchDirTest {
 protected:
  fs::path write_study(const std::string& name, const std::string& text) const {
    write(fs::path(name) / "study.yaml", text);
    return dir_ / name;
  }

  std::string load_error(const std::string& name, const std::string& text) const {
    const fs::path dir = write_study(name, text);
    try {
      load_design_study((dir / "study.yaml").string());
    } catch (const InputError& error) {
      return error.what();
    }
    return "no error";
  }
};
// The suites keep their names; the study type is therefore pkmopt::DesignStudy in this file.
class DesignStudy : public DesignStudyTest {};
class LegChainDesignStudy : public DesignStudyTest {};

using cli_runner::read_text;

std::string replaced(std::string text, const std::string& from, const std::string& to) {
  const std::size_t at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  return text.replace(at, from.size(), to);
}

TEST_F(DesignStudy, LoadsTheProblemItDescribes) {
  const fs::path dir = write_study("load", kStudy);
  const pkmopt::DesignStudy study = load_design_study((dir / "study.yaml").string());
  EXPECT_EQ(study.name, "tiny");
  EXPECT_TRUE(is_design_study_file((dir / "study.yaml").string()));
  const DesignProblem& problem = *study.problem;
  ASSERT_EQ(problem.free_parameters().size(), 2u);
  EXPECT_EQ(problem.bounds().lower[1], deg_to_rad(10));  // degrees in the file, rad inside
  EXPECT_EQ(problem.num_objectives(), 2u);
  EXPECT_EQ(problem.num_inequality(), 2u);
  // 4 points x (1 + 7) orientations: the rim of a 10 deg cone sampled every 10 deg holds
  // max(4, ceil(2 pi sin(10 deg) / 10 deg)) = 7 azimuths.
  EXPECT_EQ(problem.task().poses.size(), 4u * 8u);
  EXPECT_TRUE(problem.aggregate());
  EXPECT_EQ(study.optimizer.seed, 5u);
}

// `- task_singularity_free` under constraints: the task region (the box times the 10 deg cone)
// is certified for every design; it resolves to {metric: task_singularity_free, min: 1}.
TEST_F(DesignStudy, TaskSingularityFreeConstraintCertifiesTheTaskBox) {
  const fs::path dir = write_study(
      "certify",
      replaced(kStudy, "  - task_reachable\n", "  - task_reachable\n  - task_singularity_free\n"));
  const pkmopt::DesignStudy study = load_design_study((dir / "study.yaml").string());
  EXPECT_EQ(study.problem->num_inequality(), 3u);
  const auto& region = study.problem->task().region;
  ASSERT_TRUE(region.has_value());
  EXPECT_TRUE(region->position_lo.isApprox(Eigen::Vector3d(-0.1, -0.1, 0.85)));
  EXPECT_TRUE(region->position_hi.isApprox(Eigen::Vector3d(0.1, 0.1, 0.95)));
  EXPECT_EQ(region->theta.hi, deg_to_rad(10));
  EXPECT_NE(study.resolved_yaml.find("  - {metric: task_singularity_free, min: 1}\n"),
            std::string::npos)
      << study.resolved_yaml;
  const fs::path again = write_study("certify_resolved", study.resolved_yaml);
  EXPECT_EQ(load_design_study((again / "study.yaml").string()).resolved_yaml, study.resolved_yaml);
  EXPECT_NE(load_error("certify_bad",
                       replaced(kStudy, "  - task_reachable\n", "  - task_singularity_freee\n"))
                .find("task_reachable, task_singularity_free, {metric: NAME"),
            std::string::npos);
}

TEST_F(DesignStudy, ActuatorFromACatalogBoundsForceAndStroke) {
  const std::string catalog =
      std::string(PKMOPT_SOURCE_DIR) + "/studies/library/catalogs/sew-cms.yaml";
  std::string text = replaced(kStudy, "  - {metric: leg_force_max, max: 10500}\n",
                              "  - {actuator: CMS71L/350, catalog: " + catalog + "}\n");
  text = replaced(text, "    base_radius: {min: 0.5, max: 0.7}\n",
                  "    base_radius: {min: 0.5, max: 0.7}\n    stroke: {min: 0.30, max: 0.45}\n");
  const fs::path dir = write_study("actuator", text);
  const pkmopt::DesignStudy study = load_design_study((dir / "study.yaml").string());
  ASSERT_EQ(study.constraints().size(), 1u);
  EXPECT_EQ(study.constraints()[0].metric, DesignMetric::leg_force_max);
  EXPECT_EQ(study.constraints()[0].bound, 17000.0);  // CMS71L/350: 17 kN
  const auto [stroke_lower, stroke_upper] = free_range(study, "stroke");
  EXPECT_EQ(stroke_lower, 0.30);
  EXPECT_EQ(stroke_upper, 0.35);  // capped
  // The resolved study (absolute catalog path) loads to the same problem.
  const fs::path again = write_study("actuator_resolved", study.resolved_yaml);
  const pkmopt::DesignStudy reloaded = load_design_study((again / "study.yaml").string());
  EXPECT_EQ(reloaded.resolved_yaml, study.resolved_yaml);
  EXPECT_EQ(reloaded.constraints()[0].bound, 17000.0);

  // A catalog relative to the study file, an unknown entry, a too-short actuator.
  const std::string relative = replaced(text, catalog, "cat.yaml");
  EXPECT_NE(load_error("actuator_rel", relative).find("(no such file)"), std::string::npos);
  const fs::path rel_dir = write_study("actuator_rel2", relative);
  fs::copy_file(catalog, rel_dir / "cat.yaml", fs::copy_options::overwrite_existing);
  EXPECT_NO_THROW(load_design_study((rel_dir / "study.yaml").string()));
  const std::string unknown = load_error("actuator_unknown", replaced(text, "CMS71L/350", "CMS99"));
  EXPECT_NE(unknown.find("constraints[1].actuator: expected an entry of catalog 'sew-cms' "
                         "(CMS50S/70, CMS50S/150"),
            std::string::npos)
      << unknown;
  EXPECT_NE(unknown.find("found 'CMS99'"), std::string::npos) << unknown;
  const std::string short_stroke =
      load_error("actuator_short", replaced(text, "CMS71L/350", "CMS63S/200"));
  EXPECT_NE(short_stroke.find("constraints[1].actuator: expected an actuator with a stroke of at "
                              "least machine.parameters.stroke (0.3 m), found 'CMS63S/200' with "
                              "0.2 m"),
            std::string::npos)
      << short_stroke;
}

// {actuator: cheapest, catalog: FILE}: every design gets the cheapest entry that carries its
// legs; actuator_cost can be minimised; pareto.csv/json and the report name the entry.
TEST_F(DesignStudy, CheapestCatalogActuatorIsChosenForEveryDesign) {
  const std::string catalog_path =
      std::string(PKMOPT_SOURCE_DIR) + "/studies/library/catalogs/sew-cms.yaml";
  std::string text = replaced(kStudy, "  - {metric: leg_force_max, max: 10500}\n",
                              "  - {actuator: cheapest, catalog: " + catalog_path + "}\n");
  text = replaced(text, "    base_radius: {min: 0.5, max: 0.7}\n",
                  "    base_radius: {min: 0.5, max: 0.7}\n    stroke: {min: 0.10, max: 0.45}\n"
                  "    home_height: {min: -0.35, max: 0}\n    min_length: {min: 0.55, max: 0.8}\n");
  text = replaced(text, "size: [0.2, 0.2, 0.1]", "size: [0.1, 0.1, 0.05]");
  text = replaced(text, "population: 12, generations: 4", "population: 24, generations: 8");
  text = replaced(text, "  - minimize: machine_size\n", "  - minimize: actuator_cost\n");
  text = replaced(text, "wrench: [0, 0, -3000, 0, 0, 0]", "wrench: [2000, 0, -20000, 0, 0, 0]");
  const fs::path dir = write_study("cheapest", text);
  const pkmopt::DesignStudy study = load_design_study((dir / "study.yaml").string());
  ASSERT_NE(study.problem->actuator_catalog(), nullptr);
  EXPECT_EQ(study.problem->actuator_catalog()->entries.size(), 7u);
  ASSERT_EQ(study.constraints().size(), 1u);
  EXPECT_EQ(study.constraints()[0].metric, DesignMetric::actuator_overload);
  EXPECT_EQ(study.constraints()[0].bound, 0.0);
  EXPECT_EQ(free_range(study, "stroke").second, 0.35);  // capped at the longest entry
  const fs::path again = write_study("cheapest_resolved", study.resolved_yaml);
  EXPECT_EQ(load_design_study((again / "study.yaml").string()).resolved_yaml, study.resolved_yaml);

  const cli_runner::CliRun validate = run_cli("validate " + (dir / "study.yaml").string());
  ASSERT_EQ(validate.status, 0) << validate.err;
  const std::string validate_text = validate.out + validate.err;
  EXPECT_NE(validate_text.find("actuators: each design's cheapest entry of catalog 'sew-cms' (7 "
                               "entries, by force rating) that carries its legs"),
            std::string::npos)
      << validate_text;
  const cli_runner::CliRun run = run_cli("run " + (dir / "study.yaml").string() + " --out " +
                                         (dir / "out").string() + " --threads 2");
  ASSERT_EQ(run.status, 0) << run.out << run.err;
  std::ifstream csv(dir / "out" / "pareto.csv");
  std::string header;
  std::getline(csv, header);
  EXPECT_EQ(
      header,
      "id,base_radius,platform_pair_separation_deg,min_length,stroke,home_height,stiffness_min,"
      "actuator_cost,g_actuator_overload_max,g_task_reachable,actuator,feasible,failure");
  const nlohmann::json pareto = nlohmann::json::parse(read_text(dir / "out" / "pareto.json"));
  EXPECT_EQ(pareto["actuator_catalog"]["name"], "sew-cms");
  const ActuatorCatalog& catalog = *study.problem->actuator_catalog();
  const std::vector<double> ranks = actuator_costs(catalog);
  ASSERT_GT(pareto["designs"].size(), 0u);
  std::set<std::string> names;
  std::string row;
  for (const nlohmann::json& d : pareto["designs"]) {
    ASSERT_TRUE(std::getline(csv, row));
    if (!d["feasible"].get<bool>()) continue;
    const nlohmann::json& a = d["actuator"];
    ASSERT_TRUE(a.is_object()) << d.dump();
    const double force = a["leg_force_max"].get<double>();
    const double stroke = d["parameters"]["stroke"].get<double>();
    const ActuatorChoice choice = choose_actuator(catalog, {force, stroke, 0.0, 0.0});
    ASSERT_NE(choice.entry, nullptr);
    EXPECT_EQ(a["name"], choice.entry->name);
    EXPECT_EQ(a["max_force"], choice.entry->max_force);
    EXPECT_DOUBLE_EQ(a["force_reserve"].get<double>(), choice.entry->max_force / force);
    const double rank = ranks[static_cast<std::size_t>(choice.entry - catalog.entries.data())];
    EXPECT_EQ(d["objectives"]["actuator_cost"], rank);
    EXPECT_EQ(a["cost"], rank);
    EXPECT_NE(row.find("," + csv_field(choice.entry->name) + ",1,"), std::string::npos) << row;
    names.insert(choice.entry->name);
  }
  EXPECT_FALSE(names.empty());
  // The report carries the chosen entries (its table and comparison show them) and the catalog.
  ASSERT_EQ(run_cli("export " + (dir / "out").string() + " --format html").status, 0);
  const std::string report = read_text(dir / "out" / "report.html");
  for (const std::string& name : names)
    EXPECT_NE(report.find("\"actuator\":{\"force_reserve\":"), std::string::npos) << name;
  EXPECT_NE(report.find("\"name\":\"" + *names.begin() + "\""), std::string::npos);
  EXPECT_NE(report.find("each design's cheapest entry of catalog"), std::string::npos);

  // Errors: an actuator metric without the choice; a catalog with some prices; the word
  // 'cheapest' as an entry name.
  const std::string no_choice =
      load_error("cheapest_none",
                 replaced(text, "  - {actuator: cheapest, catalog: " + catalog_path + "}\n", ""));
  EXPECT_NE(no_choice.find("objectives[1].minimize: expected a metric of this hexapod study "
                           "(actuator_cost and actuator_overload need a constraint "
                           "{actuator: cheapest, catalog: FILE}"),
            std::string::npos)
      << no_choice;
  const fs::path priced_dir =
      write_study("cheapest_priced", replaced(text, catalog_path, "cat.yaml"));
  std::string priced = read_text(catalog_path);
  priced = replaced(priced, "max_speed: 0.375}", "max_speed: 0.375, cost: 3}");
  write("cheapest_priced/cat.yaml", priced);
  try {
    load_design_study((priced_dir / "study.yaml").string());
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("constraints[1].catalog: expected a catalog whose "
                                         "entries all have a cost or all have none"),
              std::string::npos)
        << e.what();
  }
  std::string named = read_text(catalog_path);
  named = replaced(named, "name: CMS50S/70,", "name: cheapest,");
  write("cheapest_priced/cat.yaml", named);
  try {
    load_design_study((priced_dir / "study.yaml").string());
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("constraints[1].actuator: expected a catalog without an "
                                         "entry named 'cheapest'"),
              std::string::npos)
        << e.what();
  }
}

// {actuator: cheapest, catalog: FILE, each_drive: true}: the six legs priced as one group of
// alike drives, drive_cost = 6 x the entry's cost; the metrics of the other mode are refused.
TEST_F(DesignStudy, EveryDrivePricedHexapodStudy) {
  const std::string catalog_path =
      std::string(PKMOPT_SOURCE_DIR) + "/studies/library/catalogs/milling-drives.yaml";
  std::string text =
      replaced(kStudy, "  - {metric: leg_force_max, max: 10500}\n",
               "  - {actuator: cheapest, catalog: " + catalog_path + ", each_drive: true}\n");
  text = replaced(text, "  - minimize: machine_size\n", "  - minimize: drive_cost\n");
  const fs::path dir = write_study("each_drive", text);
  const pkmopt::DesignStudy study = load_design_study((dir / "study.yaml").string());
  EXPECT_TRUE(study.problem->prices_each_drive());
  ASSERT_EQ(study.constraints().size(), 1u);
  EXPECT_EQ(study.constraints()[0].metric, DesignMetric::drive_overload);
  const fs::path again = write_study("each_drive_resolved", study.resolved_yaml);
  EXPECT_EQ(load_design_study((again / "study.yaml").string()).resolved_yaml, study.resolved_yaml);
  const cli_runner::CliRun validate = run_cli("validate " + (dir / "study.yaml").string());
  ASSERT_EQ(validate.status, 0) << validate.err;
  EXPECT_NE(validate.out.find("drives: every drive priced from catalog 'milling-drives' (11 "
                              "linear, 5 rotary entries, by cost)"),
            std::string::npos)
      << validate.out;
  const cli_runner::CliRun run = run_cli("run " + (dir / "study.yaml").string() + " --out " +
                                         (dir / "out").string() + " --threads 2");
  ASSERT_EQ(run.status, 0) << run.out << run.err;
  const nlohmann::json pareto = nlohmann::json::parse(read_text(dir / "out" / "pareto.json"));
  EXPECT_EQ(pareto["drive_catalog"]["name"], "milling-drives");
  EXPECT_EQ(pareto["drive_catalog"]["rotary_entries"], 5);
  EXPECT_FALSE(pareto.contains("actuator_catalog"));
  const ActuatorCatalog& catalog = *study.problem->actuator_catalog();
  int checked = 0;
  for (const nlohmann::json& d : pareto["designs"]) {
    if (!d["feasible"].get<bool>()) continue;
    EXPECT_FALSE(d.contains("actuator"));
    // The cost is six of some entry's, and that entry carries the design's stroke.
    const double cost = d["objectives"]["drive_cost"].get<double>();
    double stroke = 0.0;  // fixed in this study
    for (const pkmopt::StudyParameter& p : study.parameters)
      if (p.name == "stroke") stroke = p.min;
    ASSERT_GT(stroke, 0.0);
    bool some = false;
    for (const ActuatorEntry& e : catalog.entries)
      some = some || (std::abs(cost - 6.0 * *e.cost) < 1e-12 && e.stroke >= stroke);
    EXPECT_TRUE(some) << cost;
    // The drives named: six of the entry whose cost it is.
    const std::string drives = d["drives"].get<std::string>();
    ASSERT_EQ(drives.rfind("q1-q6 6 x ", 0), 0u) << drives;
    const ActuatorEntry* entry = find_actuator(catalog, drives.substr(10));
    ASSERT_NE(entry, nullptr) << drives;
    EXPECT_NEAR(cost, 6.0 * *entry->cost, 1e-12);
    ++checked;
  }
  EXPECT_GT(checked, 0);
  // The one-entry metric with each_drive; drive_cost without it; a named entry with it.
  EXPECT_NE(load_error("each_drive_mixed", replaced(text, "  - minimize: drive_cost\n",
                                                    "  - minimize: actuator_cost\n"))
                .find("objectives[1].minimize: expected a metric of this study (with each_drive: "
                      "true the catalog prices every drive: drive_cost, drive_overload), found "
                      "'actuator_cost'"),
            std::string::npos);
  EXPECT_NE(load_error("each_drive_off", replaced(text, ", each_drive: true", ""))
                .find("objectives[1].minimize: expected a metric of this study (drive_cost and "
                      "drive_overload need each_drive: true"),
            std::string::npos);
  EXPECT_NE(load_error("each_drive_named", replaced(text, "cheapest", "CMS63S/200"))
                .find("constraints[1].actuator: expected cheapest (each_drive: true chooses per "
                      "design), found 'CMS63S/200'"),
            std::string::npos);
}

// The shipped actuator-choice study, reduced (population 12, 3 generations), through the CLI:
// it resolves to itself and every feasible front design names the catalog entry it chose.
TEST_F(DesignStudy, ShippedActuatorChoiceStudyRunsReduced) {
  const std::string source =
      std::string(PKMOPT_SOURCE_DIR) + "/studies/library/hexapod-actuator-choice.yaml";
  const pkmopt::DesignStudy study = load_design_study(source);
  // Resolved again it is the same but for the comment on where the milling wrench came from.
  auto without_comments = [](const std::string& yaml) {
    std::istringstream in(yaml);
    std::string line, kept;
    while (std::getline(in, line))
      if (!line.starts_with("  #")) kept += line + "\n";
    return kept;
  };
  const fs::path resolved = write_study("actuator_choice_resolved", study.resolved_yaml);
  EXPECT_EQ(load_design_study((resolved / "study.yaml").string()).resolved_yaml,
            without_comments(study.resolved_yaml));
  const std::string text =
      replaced(replaced(read_text(source), "population: 80, generations: 50",
                        "population: 12, generations: 3"),
               "catalogs/sew-cms.yaml",
               std::string(PKMOPT_SOURCE_DIR) + "/studies/library/catalogs/sew-cms.yaml");
  const fs::path dir = write_study("actuator_choice", text);
  const cli_runner::CliRun run =
      run_cli("run " + (dir / "study.yaml").string() + " --out " + (dir / "out").string());
  ASSERT_EQ(run.status, 0) << run.out << run.err;
  const nlohmann::json pareto = nlohmann::json::parse(read_text(dir / "out" / "pareto.json"));
  EXPECT_EQ(pareto["actuator_catalog"]["name"], "sew-cms");
  for (const nlohmann::json& d : pareto["designs"]) {
    if (d["feasible"].get<bool>()) {
      EXPECT_TRUE(d["actuator"].is_object()) << d.dump();
    }
  }
}

TEST_F(DesignStudy, WrenchFromTheMillingModel) {
  const std::string text =
      replaced(kStudy, "  wrench: [0, 0, -3000, 0, 0, 0]\n",
               "  wrench:\n"
               "    milling: {cutter_diameter_mm: 63, teeth: 5, cutting_speed: 200,\n"
               "              feed_per_tooth_mm: 0.15, width_mm: 63, depth_mm: 3, k_c1: 1700}\n"
               "    factor: 2\n");
  const fs::path dir = write_study("milling", text);
  const pkmopt::DesignStudy study = load_design_study((dir / "study.yaml").string());
  // Full slot: F_t = a_p a_e f_z z k_c / (pi D), k_c = 1700 (2 f_z / pi)^-0.25; times 2.
  const double k_c = 1700.0 * std::pow(2.0 * 0.15 / M_PI, -0.25);
  const double F_t = 3.0 * 63.0 * 0.15 * 5 * k_c / (M_PI * 63.0);
  const Wrench& w = study.task().wrench;
  EXPECT_NEAR(w(0), -2.0 * F_t, 1e-9 * F_t);
  EXPECT_NEAR(w(1), 2.0 * 0.3 * F_t, 1e-9 * F_t);
  EXPECT_NEAR(w(5), -2.0 * F_t * 0.0315, 1e-9 * F_t);
  EXPECT_NE(study.resolved_yaml.find("# wrench from the cutting model: milling:"),
            std::string::npos);
  const fs::path again = write_study("milling_resolved", study.resolved_yaml);
  EXPECT_EQ(load_design_study((again / "study.yaml").string()).task().wrench, w);
}

TEST_F(DesignStudy, SchemaErrorsNameFileLineKeyExpectedAndFound) {
  const std::string file = (dir_ / "e1" / "study.yaml").string();
  EXPECT_EQ(load_error("e1", replaced(kStudy, "    base_radius:", "    base_radiu:")),
            file +
                ":5:5: machine.parameters.base_radiu: unknown key 'base_radiu'; allowed keys here: "
                "base_radius, platform_radius, base_pair_separation_deg, "
                "platform_pair_separation_deg, min_length, stroke, home_height");
  const std::string file2 = (dir_ / "e2" / "study.yaml").string();
  EXPECT_EQ(
      load_error("e2", replaced(kStudy, "maximize: stiffness_min", "maximize: stifness")),
      file2 +
          ":15:15: objectives[0].maximize: expected one of stiffness_min, "
          "singularity_margin, leg_force_max, tcp_error_max, workspace_volume, "
          "conditioning_index, machine_size, actuator_cost, actuator_overload, tcp_deflection_max, "
          "stiffness_min_loaded, natural_frequency_min, moving_mass, actuator_force_dynamic_max, "
          "leg_clearance_min, swept_volume, footprint, task_singularity_free, task_margin, "
          "drive_cost, drive_overload, found 'stifness'");
  const std::string file3 = (dir_ / "e3" / "study.yaml").string();
  EXPECT_EQ(load_error("e3", replaced(kStudy, "{min: 0.5, max: 0.7}", "{min: 0.7, max: 0.5}")),
            file3 + ":5:34: machine.parameters.base_radius.max: expected max > min, found '0.5'");
  const std::string file4 = (dir_ / "e4" / "study.yaml").string();
  EXPECT_EQ(
      load_error("e4", replaced(kStudy, "task:\n", "tasks:\n")),
      file4 +
          ":10:1: tasks: unknown key 'tasks'; allowed keys here: study, description, machine, "
          "task, objectives, constraints, optimizer, output");
}

TEST_F(DesignStudy, SmallStudyEndToEnd) {
  const fs::path dir = write_study("run", kStudy);
  const cli_runner::CliRun run = run_cli("run " + (dir / "study.yaml").string() + " --out " +
                                         (dir / "out").string() + " --threads 1");
  ASSERT_EQ(run.status, 0) << run.out << run.err;
  std::ifstream csv(dir / "out" / "pareto.csv");
  std::string header, row;
  std::getline(csv, header);
  EXPECT_EQ(header,
            "id,base_radius,platform_pair_separation_deg,home_height,stiffness_min,machine_size,"
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

  // pareto.json: the pkmopt-pareto-1 format, one design per pareto.csv row.
  const nlohmann::json pareto = nlohmann::json::parse(read_text(dir / "out" / "pareto.json"));
  EXPECT_EQ(pareto["format"], "pkmopt-pareto-1");
  EXPECT_EQ(pareto["study"], "tiny");
  ASSERT_EQ(pareto["designs"].size(), static_cast<std::size_t>(rows));
  EXPECT_EQ(pareto["parameters"][0]["name"], "base_radius");
  EXPECT_EQ(pareto["parameters"][0]["min"], 0.5);
  EXPECT_EQ(pareto["fixed_parameters"]["home_height"], 0.0);
  EXPECT_EQ(pareto["constraints"][0]["name"], "g_leg_force_max_max");
  EXPECT_EQ(pareto["constraints"][0]["bound"], 10500.0);
  EXPECT_EQ(pareto["constraints"][1]["kind"], "reachable");
  EXPECT_EQ(pareto["objectives"][0]["unit"], "N/m");
  const nlohmann::json& first = pareto["designs"][0];
  EXPECT_EQ(first["id"], "d0000");
  EXPECT_EQ(first["home_height"], 0.0);
  EXPECT_EQ(first["machine_file"], "designs/d0000.yaml");
  EXPECT_TRUE(first["feasible"].get<bool>());
  EXPECT_GT(first["objectives"]["stiffness_min"].get<double>(), 0.0);
  EXPECT_TRUE(pareto["knee"].is_string());

  // summary.json: user-sign hypervolume with its reference point; counts of evaluations.
  const nlohmann::json summary = nlohmann::json::parse(read_text(dir / "out" / "summary.json"));
  EXPECT_EQ(summary["evaluations"], 12 * 5);  // population 12 x (4 generations + 1)
  EXPECT_EQ(summary["evaluations_from_cache"].get<long long>() +
                summary["evaluations_distinct"].get<long long>(),
            12 * 5);
  EXPECT_EQ(summary["seed"], 5);
  ASSERT_EQ(summary["reference_point"].size(), 2u);
  // maximize stiffness: the reference lies below the front's smallest stiffness.
  double smallest_stiffness = 1e300;
  for (const auto& d : pareto["designs"])
    smallest_stiffness =
        std::min(smallest_stiffness, d["objectives"]["stiffness_min"].get<double>());
  EXPECT_LT(summary["reference_point"][0].get<double>(), smallest_stiffness);
  EXPECT_TRUE(summary["hypervolume"].is_number());

  // evaluations.csv: one row per distinct evaluation.
  std::ifstream evaluations(dir / "out" / "evaluations.csv");
  std::getline(evaluations, header);
  EXPECT_EQ(header,
            "index,generation,base_radius,platform_pair_separation_deg,stiffness_min,"
            "machine_size,g_leg_force_max_max,g_task_reachable,feasible,failure");
  long long evaluation_rows = 0, last_generation = 0;
  while (std::getline(evaluations, row)) {
    ++evaluation_rows;
    // NSGA-II's generations, in order: 0 the initial population, then one per generation.
    const long long generation = std::stoll(row.substr(row.find(',') + 1));
    EXPECT_GE(generation, last_generation) << row;
    last_generation = generation;
  }
  EXPECT_EQ(evaluation_rows, summary["evaluations_distinct"].get<long long>());

  // A second run into the same folder is refused without --resume or --force.
  const cli_runner::CliRun again =
      run_cli("run " + (dir / "study.yaml").string() + " --out " + (dir / "out").string());
  EXPECT_EQ(again.status, 2);
}

TEST_F(DesignStudy, ResolvedStudyLoadsToTheSameProblem) {
  const fs::path dir = write_study("resolved", kStudy);
  const pkmopt::DesignStudy study = load_design_study((dir / "study.yaml").string());
  write("resolved/resolved.yaml", study.resolved_yaml);
  const pkmopt::DesignStudy again = load_design_study((dir / "resolved.yaml").string());
  EXPECT_EQ(again.resolved_yaml, study.resolved_yaml);  // a fixed point: nothing left to fill in
  const DesignProblem& a = *study.problem;
  const DesignProblem& b = *again.problem;
  EXPECT_EQ(a.bounds().lower, b.bounds().lower);
  EXPECT_EQ(a.bounds().upper, b.bounds().upper);
  EXPECT_EQ(a.free_parameters(), b.free_parameters());
  ASSERT_EQ(a.task().poses.size(), b.task().poses.size());
  for (std::size_t k = 0; k < a.task().poses.size(); ++k) {
    EXPECT_EQ(a.task().poses[k].position, b.task().poses[k].position);
    EXPECT_EQ(a.task().poses[k].angles, b.task().poses[k].angles);
  }
  EXPECT_EQ(a.task().wrench, b.task().wrench);
  EXPECT_EQ(again.optimizer.nsga2()->population, 12u);
  EXPECT_EQ(again.optimizer.nsga2()->crossover_eta, study.optimizer.nsga2()->crossover_eta);
  const std::vector<double> x = {0.6, deg_to_rad(25)};
  EXPECT_EQ(a.fitness(x), b.fitness(x));
}

TEST_F(DesignStudy, EvaluationRowsRecordFailuresWithoutNumbers) {
  const fs::path dir = write_study("rows", kStudy);
  const pkmopt::DesignStudy study = load_design_study((dir / "study.yaml").string());
  const JournalOptions options = design_journal_options(study);
  EXPECT_EQ(options.csv_header,
            "index,generation,base_radius,platform_pair_separation_deg,stiffness_min,"
            "machine_size,g_leg_force_max_max,g_task_reachable,feasible,failure");
  // A successful design: objectives in user sign (stiffness positive), the g values as rows.
  JournalEntry good = options.evaluate({0.6, deg_to_rad(25)});
  good.x = {0.6, deg_to_rad(25)};  // the journal sets x after the evaluation
  EXPECT_TRUE(good.note.empty());
  const DesignRecord ev = study.problem->measure({0.6, deg_to_rad(25)});
  good.generation = 7;  // the request that asked for it
  const std::string row = options.csv_row(3, good);
  EXPECT_EQ(row.substr(0, row.find(',', row.find(',', row.find(',', 2) + 1) + 1)),
            "3,7,0.6," + format_number(rad_to_deg(deg_to_rad(25))));
  EXPECT_NE(row.find("," + format_number(ev.metrics[0]) + ","), std::string::npos) << row;
  // A failed design: empty objective and constraint cells, feasible 0, the quoted reason.
  JournalEntry failed = good;
  for (double& f : failed.fitness) f = kFailurePenalty;
  failed.note = "singular at task pose 2 (x 0.1, y 0, z 0.9 m)";
  failed.generation = -1;  // read from a journal, not asked for again yet: an empty cell
  EXPECT_EQ(options.csv_row(4, failed),
            "4,,0.6," + format_number(rad_to_deg(deg_to_rad(25))) +
                ",,,,,0,\"singular at task pose 2 (x 0.1, y 0, z 0.9 m)\"");
}

TEST_F(DesignStudy, ShippedQuickStudyResolvesToItself) {
  const pkmopt::DesignStudy study =
      load_design_study(std::string(PKMOPT_SOURCE_DIR) + "/studies/library/hexapod-quick.yaml");
  const fs::path dir = write_study("quick_resolved", study.resolved_yaml);
  EXPECT_EQ(load_design_study((dir / "study.yaml").string()).resolved_yaml, study.resolved_yaml);
}

// ---------------------------------------------------------------------------------------------
// Leg-chain design studies (MachineDesignProblem).

const char* const kLinearDeltaStudy =
    "study: tiny-linear-delta\n"
    "machine:\n"
    "  model: linear_delta\n"
    "  parameters:\n"
    "    rod: {min: 0.5, max: 0.9}\n"
    "    stroke: {min: 0.4, max: 0.8}\n"
    "    inclination_deg: 10\n"
    "    home_height: {min: -0.1, max: 0.1}\n"
    "  rods: {E: 2.1e11, area: 1.5e-4}\n"
    "  carriage_stiffness: 2.0e8\n"
    "  tool: {tcp: [0, 0, -0.05]}\n"
    "task:\n"
    "  region: {shape: box, centre: [0, 0, -0.35], size: [0.2, 0.2, 0.1], points: [2, 2, 2]}\n"
    "  wrench: [300, 300, -1000, 0, 0, 0]\n"
    "objectives:\n"
    "  - maximize: stiffness_min\n"
    "  - minimize: machine_size\n"
    "constraints:\n"
    "  - task_reachable\n"
    "  - {metric: singularity_margin, min: 0.02}\n"
    "optimizer: {algorithm: nsga2, population: 12, generations: 4, seed: 3}\n";

TEST_F(LegChainDesignStudy, LoadsTheFamilyWithTheTemplateFromTheMachineSection) {
  const fs::path dir = write_study("lc_load", kLinearDeltaStudy);
  const pkmopt::DesignStudy study = load_design_study((dir / "study.yaml").string());
  EXPECT_EQ(study.model, "linear_delta");
  ASSERT_NE(study.problem, nullptr);
  const DesignProblem& problem = *study.problem;
  EXPECT_EQ(problem.free_parameters(), (std::vector<int>{2, 3, 5}));  // rod, stroke, home_height
  EXPECT_EQ(problem.task().poses.size(), 8u);
  EXPECT_EQ(study.parameters[4].name, "inclination_deg");
  EXPECT_EQ(study.parameters[4].unit, "deg");
  EXPECT_EQ(study.parameters[4].min, 10.0);
  // The template keys reach the machine: the written design file carries them.
  const std::string file = study.machine->machine_file(problem.design_parameters({0.7, 0.6, 0.0}));
  EXPECT_NE(file.find("rods: {E: 210000000000, area: 0.00015}"), std::string::npos) << file;
  EXPECT_NE(file.find("carriage_stiffness: 200000000"), std::string::npos) << file;
  EXPECT_NE(file.find("tcp: [0, 0, -0.05]"), std::string::npos) << file;
  EXPECT_NE(file.find("inclination_deg: 10"), std::string::npos) << file;
  // study.resolved.yaml loads to the same problem.
  const fs::path again = write_study("lc_load_resolved", study.resolved_yaml);
  const pkmopt::DesignStudy reloaded = load_design_study((again / "study.yaml").string());
  EXPECT_EQ(reloaded.resolved_yaml, study.resolved_yaml);
  EXPECT_EQ(reloaded.problem->fitness({0.7, 0.6, 0.05}), problem.fitness({0.7, 0.6, 0.05}));
}

TEST_F(LegChainDesignStudy, SchemaErrors) {
  const std::string file = (dir_ / "lc_e1" / "study.yaml").string();
  EXPECT_EQ(
      load_error("lc_e1", replaced(kLinearDeltaStudy, "model: linear_delta", "model: tripod")),
      file +
          ":3:10: machine.model: expected one of hexapod, delta, linear_delta, hexaglide, "
          "tripod_3prs, tripod_3rps, lathe_16k20f3, hybrid, serial (the models with a design "
          "family), found 'tripod'");
  const std::string file2 = (dir_ / "lc_e2" / "study.yaml").string();
  EXPECT_EQ(load_error("lc_e2", replaced(kLinearDeltaStudy, "    rod:", "    rods:")),
            file2 +
                ":5:5: machine.parameters.rods: unknown key 'rods'; allowed keys here: "
                "guide_radius, platform_radius, rod, stroke, inclination_deg, home_height");
  // A key the parameters set may not appear in the machine section.
  EXPECT_NE(load_error("lc_e3", replaced(kLinearDeltaStudy, "  carriage_stiffness:",
                                         "  rod: 0.6\n  carriage_stiffness:"))
                .find(":10:8: machine.rod: no 'rod' in the machine section"),
            std::string::npos);
  // Template errors come from the machine-file reader, located in the study file.
  const std::string e4 =
      load_error("lc_e4", replaced(kLinearDeltaStudy, "area: 1.5e-4", "area: -1.5e-4"));
  EXPECT_NE(e4.find(":9:27: machine.rods.area: expected a number > 0"), std::string::npos) << e4;
  // Gradient algorithms are refused with a pointer to nsga2.
  const std::string e5 = load_error("lc_e5", replaced(kLinearDeltaStudy,
                                                      "algorithm: nsga2, population: 12, "
                                                      "generations: 4, seed: 3",
                                                      "algorithm: ipopt"));
  EXPECT_NE(e5.find("optimizer.algorithm: expected nsga2"), std::string::npos) << e5;
  EXPECT_NE(e5.find("found 'ipopt'"), std::string::npos) << e5;
  // A model with linear drives takes a catalog constraint; its drives are numbered 1..3.
  const std::string catalog =
      std::string(PKMOPT_SOURCE_DIR) + "/studies/library/catalogs/sew-cms.yaml";
  const std::string e8 = load_error(
      "lc_e8",
      replaced(kLinearDeltaStudy, "  - task_reachable\n",
               "  - task_reachable\n  - {actuator: cheapest, catalog: " + catalog + "}\n"));
  EXPECT_EQ(e8, "no error") << e8;
  const std::string e9 = load_error(
      "lc_e9", replaced(kLinearDeltaStudy, "  - task_reachable\n",
                        "  - task_reachable\n  - {actuator: cheapest, catalog: " + catalog +
                            ", drives: [2, 4]}\n"));
  EXPECT_NE(e9.find("constraints[1].drives: expected actuator numbers 1..3 (linear_delta "
                    "drives), found 4"),
            std::string::npos)
      << e9;
  // A translational platform cannot tilt.
  const std::string e6 = load_error(
      "lc_e6",
      replaced(kLinearDeltaStudy, "  wrench:", "  orientations: {tilt_deg: 10}\n  wrench:"));
  EXPECT_NE(e6.find("task.orientations: expected tilt_deg: 0 and yaw_deg: 0"), std::string::npos)
      << e6;
  // Angles out of their range.
  const std::string e7 = load_error(
      "lc_e7", replaced(kLinearDeltaStudy, "inclination_deg: 10", "inclination_deg: 95"));
  EXPECT_NE(e7.find("machine.parameters.inclination_deg: expected values within [-89, 89] deg"),
            std::string::npos)
      << e7;
  // Through the CLI: exit status 2, nothing written.
  const fs::path dir = write_study("lc_e8", replaced(kLinearDeltaStudy,
                                                     "algorithm: nsga2, "
                                                     "population: 12, "
                                                     "generations: 4, seed: 3",
                                                     "algorithm: nlopt:SLSQP"));
  const cli_runner::CliRun run =
      run_cli("run " + (dir / "study.yaml").string() + " --out " + (dir / "out").string());
  EXPECT_EQ(run.status, 2) << run.err;
  EXPECT_NE(run.err.find("expected nsga2"), std::string::npos) << run.err;
  EXPECT_FALSE(fs::exists(dir / "out" / "pareto.csv"));
}

TEST_F(LegChainDesignStudy, SmallStudyEndToEndThroughTheCli) {
  const fs::path dir = write_study("lc_run", kLinearDeltaStudy);
  const std::string study = (dir / "study.yaml").string();
  const std::string out = (dir / "out").string();
  const cli_runner::CliRun validate = run_cli("validate " + study);
  ASSERT_EQ(validate.status, 0) << validate.err;
  EXPECT_NE(validate.out.find("(model linear_delta) is valid"), std::string::npos) << validate.out;
  EXPECT_NE(validate.out.find("design space: 3 free of 6 parameters\n    rod "), std::string::npos)
      << validate.out;
  EXPECT_NE(validate.out.find("0.5 .. 0.9        m\n"), std::string::npos) << validate.out;

  const cli_runner::CliRun run =
      run_cli("run " + study + " --out " + out + " --threads 2 --no-progress");
  ASSERT_EQ(run.status, 0) << run.err;
  std::ifstream csv(dir / "out" / "pareto.csv");
  std::string header, row;
  std::getline(csv, header);
  EXPECT_EQ(header,
            "id,rod,stroke,home_height,stiffness_min,machine_size,g_singularity_margin_min,"
            "g_task_reachable,feasible,failure");
  int rows = 0;
  while (std::getline(csv, row)) {
    ++rows;
    EXPECT_EQ(row.find("nan"), std::string::npos) << row;
    EXPECT_NE(row.find(",1,\"\""), std::string::npos) << row;  // feasible, no failure
  }
  ASSERT_GT(rows, 0);

  const nlohmann::json pareto = nlohmann::json::parse(read_text(dir / "out" / "pareto.json"));
  EXPECT_EQ(pareto["format"], "pkmopt-pareto-1");
  EXPECT_EQ(pareto["model"], "linear_delta");
  ASSERT_EQ(pareto["designs"].size(), static_cast<std::size_t>(rows));
  EXPECT_EQ(pareto["parameters"][0]["name"], "rod");
  EXPECT_EQ(pareto["parameters"][0]["unit"], "m");
  EXPECT_EQ(pareto["fixed_parameters"]["inclination_deg"], 10.0);
  EXPECT_EQ(pareto["constraints"][1]["name"], "g_task_reachable");
  const nlohmann::json summary = nlohmann::json::parse(read_text(dir / "out" / "summary.json"));
  EXPECT_EQ(summary["model"], "linear_delta");
  EXPECT_EQ(summary["evaluations"], 12 * 5);  // population 12 x (4 generations + 1)

  // Every design file is a machine file `pkmopt analyze` loads, and it is the design evaluated.
  const pkmopt::DesignStudy loaded = load_design_study(study);
  for (const auto& d : pareto["designs"]) {
    const fs::path machine_file = dir / "out" / d["machine_file"].get<std::string>();
    const auto machine = load_machine_file(machine_file.string());
    EXPECT_EQ(machine->model(), "linear_delta");
    const std::vector<double> x = {d["parameters"]["rod"].get<double>(),
                                   d["parameters"]["stroke"].get<double>(),
                                   d["home_height"].get<double>()};
    const DesignRecord ev = loaded.problem->measure(x);
    EXPECT_EQ(ev.metrics[static_cast<int>(DesignMetric::stiffness_min)],
              d["objectives"]["stiffness_min"].get<double>());
    EXPECT_NEAR(*machine->envelope_volume(), d["objectives"]["machine_size"].get<double>(), 1e-12);
  }
  const std::string first = (dir / "out" / "designs" / "d0000.yaml").string();
  write("lc_run/poses.csv", "x,y,z\n0,0,-0.3\n");
  const cli_runner::CliRun analyze =
      run_cli("analyze " + first + " --poses " + (dir / "poses.csv").string() + " --out " +
              (dir / "analysis.csv").string());
  EXPECT_EQ(analyze.status, 0) << analyze.err;

  // --resume of a finished run gives the same front; the html report reads it.
  const std::string before = read_text(dir / "out" / "pareto.csv");
  const cli_runner::CliRun resumed =
      run_cli("run " + study + " --out " + out + " --threads 1 --resume --no-progress");
  ASSERT_EQ(resumed.status, 0) << resumed.err;
  EXPECT_EQ(read_text(dir / "out" / "pareto.csv"), before);
  const cli_runner::CliRun html =
      run_cli("export " + out + " --format html --out " + (dir / "report.html").string());
  EXPECT_EQ(html.status, 0) << html.err;
  EXPECT_NE(read_text(dir / "report.html").find("linear_delta"), std::string::npos);
}

TEST_F(LegChainDesignStudy, ShippedComparisonStudiesResolveToThemselves) {
  for (const char* name : {"hexapod", "hexaglide", "linear-delta"}) {
    const pkmopt::DesignStudy study = load_design_study(
        std::string(PKMOPT_SOURCE_DIR) + "/studies/library/compare-300/" + name + ".yaml");
    const fs::path dir = write_study(std::string("compare_") + name, study.resolved_yaml);
    EXPECT_EQ(load_design_study((dir / "study.yaml").string()).resolved_yaml, study.resolved_yaml)
        << name;
  }
}

TEST_F(LegChainDesignStudy, TripodStudyRunsReducedThroughTheCli) {
  std::string text =
      read_text(fs::path(PKMOPT_SOURCE_DIR) / "studies" / "library" / "tripod-z3.yaml");
  const std::string full = "population: 40, generations: 40";
  ASSERT_NE(text.find(full), std::string::npos);
  text.replace(text.find(full), full.size(), "population: 12, generations: 6");
  const fs::path dir = write_study("tripod_run", text);
  const cli_runner::CliRun run = run_cli("run " + (dir / "study.yaml").string() + " --out " +
                                         (dir / "out").string() + " --no-progress");
  ASSERT_EQ(run.status, 0) << run.err;
  const nlohmann::json pareto = nlohmann::json::parse(read_text(dir / "out" / "pareto.json"));
  EXPECT_EQ(pareto["model"], "tripod_3prs");
  ASSERT_GT(pareto["designs"].size(), 0u);
  const pkmopt::DesignStudy loaded = load_design_study((dir / "study.yaml").string());
  for (const auto& d : pareto["designs"]) {
    EXPECT_TRUE(d["feasible"].get<bool>());
    const auto machine =
        load_machine_file((dir / "out" / d["machine_file"].get<std::string>()).string());
    EXPECT_EQ(machine->model(), "tripod_3prs");
    // The written head reaches every task pose (4 heights x the 40 deg cone) at the design's
    // home height, and its stiffness is the front's value.
    const double lift = d["home_height"].get<double>();
    auto data = machine->make_data();
    PoseMetrics m;
    double worst = std::numeric_limits<double>::infinity();
    for (const Pose& task_pose : loaded.task().poses) {
      Pose pose = task_pose;
      pose.position.z() += lift;
      machine->analyze(*data, pose, loaded.task().wrench, m);
      EXPECT_TRUE(m.reachable);
      worst = std::min(worst, m.stiffness_min);
    }
    EXPECT_NEAR(worst / d["objectives"]["stiffness_min"].get<double>(), 1.0, 1e-12);
  }
}

}  // namespace
}  // namespace pkmopt

namespace pkmopt {
namespace {

// docs/design-studies.md carries the tables of the sections described by field lists exactly as
// generated; the failure message shows the block to paste.
TEST(DesignStudyFields, DocsTablesMatchTheFieldLists) {
  std::ifstream in(std::string(PKMOPT_SOURCE_DIR) + "/docs/design-studies.md");
  std::stringstream docs;
  docs << in.rdbuf();
  for (const char* section :
       {"machine hexapod", "machine.parameters delta", "machine.parameters linear_delta",
        "machine.parameters hexaglide", "machine.parameters tripod_3prs",
        "machine.parameters tripod_3rps", "machine.parameters lathe_16k20f3", "machine hybrid",
        "machine.parameters serial", "task.region box", "task.region cylinder", "task.orientations",
        "task.workspace", "objectives[]", "constraints[]", "constraints[] actuator", "output"}) {
    const std::string block = std::string("<!-- fields: ") + section + " -->\n" +
                              design_study_fields_markdown(section) + "<!-- /fields -->\n";
    EXPECT_NE(docs.str().find(block), std::string::npos)
        << "docs/design-studies.md lacks the generated table of '" << section << "':\n"
        << block;
  }
}

}  // namespace
}  // namespace pkmopt
