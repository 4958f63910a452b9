// Tests of io/results/pareto_json: reading pareto.json (format pkmopt-pareto-1) into a ParetoFront,
// writing it back (pareto_json) and the CSV of a front (pareto_csv). The expected values are
// those written in the fixture files tests/io/data/pareto_json/{two,three}/pareto.json (read
// independently with nlohmann::json where a test compares whole files).
#include "io/results/pareto_json.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "io/format/csv.hpp"
#include "io/format/input_error.hpp"
#include "tests/cli_runner.hpp"
#include "tests/scratch_dir.hpp"

namespace fs = std::filesystem;
using cli_runner::read_text;

namespace {

const fs::path kFixtures = fs::path(PKMOPT_SOURCE_DIR) / "tests/io/data/pareto_json";

nlohmann::json load_json(const fs::path& path) { return nlohmann::json::parse(read_text(path)); }

// The message of reading `text` as pareto.json, relative to the file's path.
std::string read_error(const std::string& text) {
  const scratch::ScratchDir dir;
  const std::string file = dir.write("pareto.json", text);
  try {
    pkmopt::read_pareto_json(file);
  } catch (const pkmopt::InputError& e) {
    const std::string what = e.what();
    return what.rfind(file, 0) == 0 ? what.substr(file.size()) : what;
  }
  return "no error";
}

TEST(ReadParetoJson, ReadsEveryField) {
  const auto front = pkmopt::read_pareto_json((kFixtures / "two/pareto.json").string());
  EXPECT_EQ(front.study, "fixture-two");
  ASSERT_EQ(front.parameters.size(), 2u);
  EXPECT_EQ(front.parameters[1].name, "platform_pair_separation_deg");
  EXPECT_EQ(front.parameters[1].unit, "deg");
  EXPECT_EQ(front.parameters[1].max, 40.0);
  ASSERT_EQ(front.fixed_parameters.size(), 2u);
  ASSERT_EQ(front.objectives.size(), 2u);
  EXPECT_EQ(front.objectives[0].sense, "maximize");
  ASSERT_EQ(front.constraints.size(), 2u);
  EXPECT_EQ(front.constraints[0].bound, 10500.0);
  EXPECT_EQ(front.constraints[1].kind, "reachable");
  EXPECT_EQ(front.task.centre.z(), 0.9);
  EXPECT_EQ(front.task.wrench[2], -3000.0);
  EXPECT_EQ(front.task.tilt_deg, 20.0);
  ASSERT_EQ(front.designs.size(), 4u);
  // Both numbers as written in two/pareto.json (17 significant digits; 0.30000000000000004 is
  // the double nearest 0.1 + 0.2): read to the same double.
  EXPECT_EQ(front.designs[0].parameters[1], 12.345678901234567);
  EXPECT_EQ(front.designs[0].objectives[1], 0.30000000000000004);
  EXPECT_FALSE(front.designs[3].feasible);
  EXPECT_EQ(front.designs[1].machine_file, std::optional<std::string>("designs/d0001.yaml"));
  EXPECT_FALSE(front.designs[2].machine_file.has_value());
  EXPECT_EQ(front.knee, std::optional<std::string>("d0001"));
  EXPECT_EQ(front.compromise, std::optional<std::string>("d0000"));
  EXPECT_EQ(front.high_trade_off, std::vector<std::string>{"d0001"});
  EXPECT_FALSE(front.home_height_is_parameter());
}

TEST(ReadParetoJson, NullIsNaNAndWritesBackAsNull) {
  const auto front = pkmopt::read_pareto_json((kFixtures / "three/pareto.json").string());
  EXPECT_TRUE(std::isnan(front.designs[1].constraints[0]));
  EXPECT_TRUE(front.home_height_is_parameter());
  const auto again = nlohmann::json::parse(pkmopt::pareto_json(front));
  EXPECT_TRUE(again["designs"][1]["constraints"]["g_singularity_margin_min"].is_null());
}

// A front whose study chose catalog actuators: the chosen entry is read, written back by
// pareto_json and pareto_csv, and a malformed one names its key.
TEST(ReadParetoJson, ChosenActuatorsRoundTrip) {
  nlohmann::json root = load_json(kFixtures / "two/pareto.json");
  root["actuator_catalog"] = {
      {"name", "sew-cms"}, {"entries", 7}, {"cost", "rank by force rating"}};
  root["designs"][0]["actuator"] = {{"name", "CMS63S/200"},    {"type", "electric_cylinder"},
                                    {"max_force", 10500.0},    {"stroke", 0.2},
                                    {"max_speed", 0.45},       {"cost", 5.0},
                                    {"leg_force_max", 7000.0}, {"force_reserve", 1.5}};
  for (std::size_t d = 1; d < root["designs"].size(); ++d) root["designs"][d]["actuator"] = nullptr;
  const scratch::ScratchDir dir;
  dir.write("pareto.json", root.dump(2));
  const auto front = pkmopt::read_pareto_json((dir / "pareto.json").string());
  ASSERT_EQ(front.actuator_catalog, std::optional<std::string>("sew-cms"));
  ASSERT_TRUE(front.designs[0].actuator.has_value());
  EXPECT_EQ(front.designs[0].actuator->name, "CMS63S/200");
  EXPECT_EQ(front.designs[0].actuator->max_force, 10500.0);
  EXPECT_EQ(front.designs[0].actuator->stroke, 0.2);
  EXPECT_EQ(front.designs[0].actuator->cost, 5.0);
  EXPECT_EQ(front.designs[0].actuator->force_reserve, 1.5);
  EXPECT_FALSE(front.designs[1].actuator.has_value());
  const nlohmann::json again = nlohmann::json::parse(pkmopt::pareto_json(front));
  EXPECT_EQ(again["actuator_catalog"]["name"], "sew-cms");
  EXPECT_EQ(again["designs"][0]["actuator"]["name"], "CMS63S/200");
  EXPECT_EQ(again["designs"][0]["actuator"]["force_reserve"], 1.5);
  EXPECT_TRUE(again["designs"][1]["actuator"].is_null());
  const std::string csv = pkmopt::pareto_csv(front);
  const std::string header = csv.substr(0, csv.find('\n'));
  EXPECT_NE(header.find(",actuator,feasible,knee"), std::string::npos) << header;
  EXPECT_NE(csv.find(",CMS63S/200,"), std::string::npos) << csv;
  // A chosen actuator without its name.
  root["designs"][0]["actuator"].erase("name");
  dir.write("pareto.json", root.dump(2));
  try {
    pkmopt::read_pareto_json((dir / "pareto.json").string());
    ADD_FAILURE() << "no error";
  } catch (const pkmopt::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("designs[0].actuator.name: expected a string"),
              std::string::npos)
        << e.what();
  }
}

TEST(ReadParetoJson, TaskExtentSelectionAndConvergenceAreOptionalAndRoundTrip) {
  nlohmann::json root = load_json(kFixtures / "two/pareto.json");
  const auto plain = pkmopt::read_pareto_json((kFixtures / "two/pareto.json").string());
  EXPECT_FALSE(plain.task.positions.has_value());
  EXPECT_FALSE(plain.selection.has_value());
  EXPECT_FALSE(plain.convergence.has_value());
  root["task"]["positions_min"] = {-0.15, -0.1, 0.8};
  root["task"]["positions_max"] = {0.15, 0.1, 1.0};
  root["front_selection"] = {{"rule", "the non-dominated set"},
                             {"evaluations", 120},
                             {"feasible_evaluations", 80},
                             {"archive_size", 4}};
  root["convergence"] = {{"evaluations", {40, 80, 120}}, {"hypervolume", {0.1, 0.25, 0.3}}};
  const scratch::ScratchDir dir;
  const auto front = pkmopt::read_pareto_json(dir.write("pareto.json", root.dump(2)));
  ASSERT_TRUE(front.task.positions.has_value());
  EXPECT_EQ(front.task.positions->first, Eigen::Vector3d(-0.15, -0.1, 0.8));
  EXPECT_EQ(front.task.positions->second, Eigen::Vector3d(0.15, 0.1, 1.0));
  ASSERT_TRUE(front.selection.has_value());
  EXPECT_EQ(front.selection->rule, "the non-dominated set");
  EXPECT_EQ(front.selection->evaluations, 120.0);
  EXPECT_EQ(front.selection->feasible_evaluations, 80.0);
  EXPECT_EQ(front.selection->archive_size, 4.0);
  ASSERT_TRUE(front.convergence.has_value());
  EXPECT_EQ(front.convergence->evaluations, (std::vector<double>{40, 80, 120}));
  EXPECT_EQ(front.convergence->hypervolume, (std::vector<double>{0.1, 0.25, 0.3}));
  const nlohmann::json again = nlohmann::json::parse(pkmopt::pareto_json(front));
  EXPECT_EQ(again["task"]["positions_max"], root["task"]["positions_max"]);
  EXPECT_EQ(again["front_selection"], root["front_selection"]);
  EXPECT_EQ(again["convergence"], root["convergence"]);
  // Checked like the rest.
  root["convergence"]["hypervolume"] = {0.1, 0.2};
  EXPECT_NE(read_error(root.dump())
                .find("convergence.hypervolume: expected 3 numbers (one per "
                      "evaluations entry), found 2"),
            std::string::npos);
  root["convergence"]["hypervolume"] = {0.1, 0.2, 0.3};
  root["task"]["positions_min"] = {0.2, -0.1, 0.8};
  EXPECT_NE(read_error(root.dump())
                .find("task.positions_max: expected a corner above "
                      "task.positions_min"),
            std::string::npos);
  root["task"]["positions_min"] = {-0.15, -0.1};
  EXPECT_NE(read_error(root.dump()).find("task.positions_min: expected 3 numbers"),
            std::string::npos);
}

// Files written before the compromise and the high-trade-off designs were named read without them.
TEST(ReadParetoJson, CompromiseAndHighTradeOffAreOptional) {
  nlohmann::json root = load_json(kFixtures / "two/pareto.json");
  root.erase("compromise");
  root.erase("high_trade_off");
  const scratch::ScratchDir dir;
  const auto front = pkmopt::read_pareto_json(dir.write("pareto.json", root.dump(2)));
  EXPECT_FALSE(front.compromise.has_value());
  EXPECT_TRUE(front.high_trade_off.empty());
  EXPECT_EQ(front.knee, std::optional<std::string>("d0001"));
}

// Writing a front read from a file gives the file's JSON again: every key, every number bit for
// bit (null for the missing constraint value of "three").
TEST(ParetoJson, WritesBackEveryValueOfTheFile) {
  for (const std::string name : {"two", "three"}) {
    const fs::path file = kFixtures / name / "pareto.json";
    const std::string text = pkmopt::pareto_json(pkmopt::read_pareto_json(file.string()));
    EXPECT_EQ(nlohmann::json::parse(text), load_json(file)) << name;
    // The written text reads back to the same text (a fixed point).
    const scratch::ScratchDir dir;
    EXPECT_EQ(pkmopt::pareto_json(pkmopt::read_pareto_json(dir.write("pareto.json", text))), text)
        << name;
  }
}

// The CSV columns: id, free parameters, home_height (unless a free parameter), objectives,
// constraint values, feasible, knee; one row per design with the file's numbers, empty cells for
// null.
TEST(ParetoCsv, ColumnsAndValuesOfTheFixtures) {
  struct Case {
    std::string name, header;
  };
  for (const Case& c :
       {Case{"two",
             "id,base_radius,platform_pair_separation_deg,home_height,stiffness_min,machine_size,"
             "g_leg_force_max_max,g_task_reachable,feasible,knee"},
        Case{"three",
             "id,min_length,home_height,stiffness_min,singularity_margin,leg_force_max,"
             "g_singularity_margin_min,feasible,knee"}}) {
    const fs::path file = kFixtures / c.name / "pareto.json";
    const std::string csv = pkmopt::pareto_csv(pkmopt::read_pareto_json(file.string()));
    EXPECT_EQ(csv.substr(0, csv.find('\n')), c.header) << c.name;
    const pkmopt::CsvTable table = pkmopt::parse_csv(csv, c.name + ".csv");
    const nlohmann::json source = load_json(file);
    ASSERT_EQ(table.rows.size(), source["designs"].size()) << c.name;
    for (std::size_t d = 0; d < table.rows.size(); ++d) {
      const nlohmann::json& design = source["designs"][d];
      const pkmopt::CsvRow& row = table.rows[d];
      EXPECT_EQ(row.cells[0], design["id"].get<std::string>());
      for (const char* group : {"parameters", "objectives", "constraints"}) {
        for (const auto& [key, value] : design[group].items()) {
          const int column = table.require_column(key);
          if (value.is_null()) {
            EXPECT_EQ(row.cells[static_cast<std::size_t>(column)], "") << c.name << " " << key;
          } else {
            EXPECT_EQ(table.number(row, column), value.get<double>()) << c.name << " " << key;
          }
        }
      }
      EXPECT_EQ(table.number(row, table.require_column("feasible")),
                design["feasible"].get<bool>() ? 1.0 : 0.0);
      EXPECT_EQ(table.number(row, table.require_column("knee")),
                design["id"] == source["knee"] ? 1.0 : 0.0);
    }
  }
}

// Bad files: the message names the key, what was expected and what was found; syntax errors
// give the line and column.
// The number policy's underflow rule: 1e-400, which the JSON parser reads as 0, is refused as it is
// in the other inputs (it was read silently as 0); a written zero in any form is 0; strings are
// not numbers.
TEST(ReadParetoJson, ANumberThatUnderflowsIsRefused) {
  EXPECT_EQ(read_error("{\n  \"study\": \"1e-400\",\n  \"x\": [0, 1e-400]\n}\n"),
            ":3:12: expected a finite number within +-1e15 (0 or at least 1e-30 in magnitude), "
            "found '1e-400'");
  EXPECT_EQ(read_error("{\"x\": -2.5e-330}").rfind(":1:7: expected a finite number", 0), 0u);
  const std::string zeros = read_error("{\"study\": \"a 1e-400 b\", \"x\": [0e-400, 0.0, -0]}");
  EXPECT_EQ(zeros.find("1e-400"), std::string::npos) << zeros;
}

TEST(ReadParetoJson, ErrorsNameTheKey) {
  const std::string two = read_text(kFixtures / "two/pareto.json");
  nlohmann::json root = nlohmann::json::parse(two);
  root["designs"][2].erase("feasible");
  EXPECT_EQ(read_error(root.dump(2)),
            ": designs[2].feasible: expected true or false, found no such key");
  root = nlohmann::json::parse(two);
  root["knee"] = "d0042";
  EXPECT_EQ(read_error(root.dump(2)),
            ": knee: expected the id of a design in `designs`, found 'd0042'");
  root = nlohmann::json::parse(two);
  root["compromise"] = 3;
  EXPECT_EQ(read_error(root.dump(2)),
            ": compromise: expected a design id or null, found the number 3");
  root = nlohmann::json::parse(two);
  root["high_trade_off"] = {"d0000", nullptr};
  EXPECT_EQ(read_error(root.dump(2)), ": high_trade_off[1]: expected a design id, found null");
  root["high_trade_off"] = {"x"};
  EXPECT_EQ(read_error(root.dump(2)),
            ": high_trade_off[0]: expected the id of a design in `designs`, found 'x'");
  root = nlohmann::json::parse(two);
  root["format"] = "pkmopt-pareto-9";
  EXPECT_EQ(read_error(root.dump(2)),
            ": format: expected 'pkmopt-pareto-1', found 'pkmopt-pareto-9'");
  // "study": at line 3, the value missing at column 12.
  const std::string syntax =
      read_error("{\n  \"format\": \"pkmopt-pareto-1\",\n  \"study\": ,\n}\n");
  EXPECT_EQ(syntax.rfind(":3:12: expected JSON, found a syntax error (", 0), 0u) << syntax;
  const scratch::ScratchDir dir;
  try {
    pkmopt::read_pareto_json((dir / "none.json").string());
    ADD_FAILURE() << "no error";
  } catch (const pkmopt::InputError& e) {
    EXPECT_EQ(std::string(e.what()), (dir / "none.json").string() +
                                         ": cannot open the file (does it exist and is it "
                                         "readable?)");
  }
}

}  // namespace
