// Tests of io/design/actuator_catalog_file: the shipped catalog loads, bad files give exact
// messages, every key of the field lists is read, README.md carries the table generated from them,
// and the writer's files read back to the same catalog.
#include "io/design/actuator_catalog_file.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "io/format/input_error.hpp"

namespace pkmopt {
namespace {

std::string error_of(const std::string& text) {
  try {
    read_actuator_catalog(YamlValue::load_string(text, "cat.yaml"));
  } catch (const InputError& e) {
    return e.what();
  }
  return "no error";
}

TEST(ActuatorCatalogFile, ShippedSewCatalogLoads) {
  const ActuatorCatalog catalog = load_actuator_catalog(std::string(PKMOPT_SOURCE_DIR) +
                                                        "/studies/library/catalogs/sew-cms.yaml");
  EXPECT_EQ(catalog.name, "sew-cms");
  ASSERT_EQ(catalog.entries.size(), 7u);
  EXPECT_EQ(check_actuator_catalog(catalog), "");
  const ActuatorEntry* cms63 = find_actuator(catalog, "CMS63S/200");
  ASSERT_NE(cms63, nullptr);
  EXPECT_EQ(cms63->max_force, 10500.0);
  EXPECT_EQ(cms63->stroke, 0.2);
  EXPECT_EQ(cms63->max_speed, 0.45);
  EXPECT_EQ(find_actuator(catalog, "CMS71L/350")->max_force, 17000.0);
  EXPECT_EQ(catalog.drive_types.size(), 4u);
  // The seeds' choice for the lathe legs: 6633 N carried by a CMS63S.
  const ActuatorChoice choice = choose_actuator(catalog, {6633.0, 0.15, 0.0, 0.0});
  ASSERT_NE(choice.entry, nullptr);
  EXPECT_EQ(choice.entry->name, "CMS63S/200");
}

TEST(ActuatorCatalogFile, BadFilesGiveExactMessages) {
  const std::string entry =
      "  - {name: A, type: electric_cylinder, max_force: 100, stroke: 0.1, max_speed: 0.2}\n";
  EXPECT_EQ(error_of("catalog: c\nentries:\n" + entry), "no error");
  EXPECT_EQ(error_of("catalog: c\nentries:\n" + entry + "colour: red\n"),
            "cat.yaml:4:1: colour: unknown key 'colour'; allowed keys here: catalog, description, "
            "entries, rotary_entries, drive_types");
  EXPECT_EQ(error_of("catalog: c\nentries: []\n"),
            "cat.yaml:2:10: entries: expected a list of at least one entry, found an empty list");
  EXPECT_EQ(error_of("catalog: c\nentries:\n  - {name: A, type: e, max_force: -5, stroke: 0.1, "
                     "max_speed: 0.2}\n"),
            "cat.yaml:3:35: entries[0].max_force: expected a number > 0, found '-5'");
  EXPECT_EQ(error_of("catalog: c\nentries:\n" + entry + entry),
            "cat.yaml:4:12: entries[1].name: expected a name not used by an earlier entry, found "
            "'A' again");
  EXPECT_EQ(error_of("catalog: c\nentries:\n" + entry +
                     "drive_types:\n  - {name: x, speed: [2, 1], accuracy: [1e-6, 1e-5]}\n"),
            "cat.yaml:5:22: drive_types[0].speed: expected [min, max] with 0 < min <= max, found "
            "a list of 2");
  EXPECT_EQ(error_of("catalog: c\nentries:\n  - {name: A, type: e, max_force: 100, peak_force: 80, "
                     "stroke: 0.1, max_speed: 0.2}\n"),
            "cat.yaml:3:52: entries[0].peak_force: expected a peak force (N) >= max_force = 100, "
            "found 80");
}

TEST(ActuatorCatalogFile, ReadsEveryKey) {
  const ActuatorCatalog catalog = read_actuator_catalog(YamlValue::load_string(
      "catalog: c\ndescription: \"test\"\nentries:\n"
      "  - {name: A, type: electric_cylinder, max_force: 100, stroke: 0.1, max_speed: 0.2,\n"
      "     accuracy: 1e-5, stiffness: 1.5e8, cost: 2}\n"
      "  - {name: B, type: linear_motor, max_force: 50, stroke: 0.3, max_speed: 3}\n"
      "drive_types:\n  - {name: x, speed: [1, 1], accuracy: [1e-6, 1e-5], note: \"a, b\"}\n"
      "  - {name: y, speed: [0.5, 2], accuracy: [2e-6, 2e-6]}\n",
      "cat.yaml"));
  EXPECT_EQ(catalog.name, "c");
  ASSERT_EQ(catalog.entries.size(), 2u);
  const ActuatorEntry& a = catalog.entries[0];
  EXPECT_EQ(a.name, "A");
  EXPECT_EQ(a.type, "electric_cylinder");
  EXPECT_EQ(a.max_force, 100.0);
  EXPECT_EQ(a.stroke, 0.1);
  EXPECT_EQ(a.max_speed, 0.2);
  EXPECT_EQ(a.accuracy, 1e-5);
  EXPECT_EQ(a.stiffness, 1.5e8);
  EXPECT_EQ(a.cost, 2.0);
  EXPECT_FALSE(catalog.entries[1].accuracy.has_value());
  EXPECT_FALSE(catalog.entries[1].stiffness.has_value());
  EXPECT_FALSE(catalog.entries[1].cost.has_value());
  ASSERT_EQ(catalog.drive_types.size(), 2u);
  EXPECT_EQ(catalog.drive_types[0].speed_min, 1.0);  // min == max allowed
  EXPECT_EQ(catalog.drive_types[0].speed_max, 1.0);
  EXPECT_EQ(catalog.drive_types[0].accuracy_min, 1e-6);
  EXPECT_EQ(catalog.drive_types[0].accuracy_max, 1e-5);
  EXPECT_EQ(catalog.drive_types[0].note, "a, b");
  EXPECT_EQ(catalog.drive_types[1].note, "");
  EXPECT_EQ(error_of("catalog: c\nentries:\n  - {name: '', type: e, max_force: 5, stroke: 0.1, "
                     "max_speed: 0.2}\n"),
            "cat.yaml:3:12: entries[0].name: expected a non-empty name, found ''");
  EXPECT_EQ(error_of("catalog: c\nentries:\n  - {name: A, type: e, max_force: 5, stroke: 0.1, "
                     "max_speed: 0.2, cost: 0}\n"),
            "cat.yaml:3:73: entries[0].cost: expected a number > 0, found '0'");
}

// Rotary drives: their own list, names unique across both lists, a catalog of rotary drives
// only, and the writer's text reads back to the same entries.
TEST(ActuatorCatalogFile, ReadsRotaryEntries) {
  const std::string rotary =
      "rotary_entries:\n"
      "  - {name: M40, type: gear_motor, max_torque: 40, peak_torque: 100, max_speed: 300, "
      "cost: 9}\n"
      "  - {name: T200, type: torque_motor, max_torque: 200, max_speed: 150}\n";
  const ActuatorCatalog catalog =
      read_actuator_catalog(YamlValue::load_string("catalog: c\n" + rotary, "cat.yaml"));
  EXPECT_TRUE(catalog.entries.empty());
  ASSERT_EQ(catalog.rotary_entries.size(), 2u);
  const RotaryEntry& m = catalog.rotary_entries[0];
  EXPECT_EQ(m.name, "M40");
  EXPECT_EQ(m.type, "gear_motor");
  EXPECT_EQ(m.max_torque, 40.0);
  EXPECT_EQ(m.peak_torque, 100.0);
  EXPECT_EQ(m.max_speed_rpm, 300.0);
  EXPECT_EQ(m.cost, 9.0);
  EXPECT_FALSE(catalog.rotary_entries[1].peak_torque.has_value());
  EXPECT_FALSE(catalog.rotary_entries[1].cost.has_value());
  const ActuatorCatalog back =
      read_actuator_catalog(YamlValue::load_string(actuator_catalog_to_yaml(catalog), "w.yaml"));
  ASSERT_EQ(back.rotary_entries.size(), 2u);
  EXPECT_EQ(back.rotary_entries[0].peak_torque, 100.0);
  EXPECT_EQ(back.rotary_entries[1].max_speed_rpm, 150.0);
  EXPECT_EQ(error_of("catalog: c\n"),
            "cat.yaml:1:1: expected entries (linear drives) or rotary_entries (rotary drives), "
            "found neither");
  EXPECT_EQ(error_of("catalog: c\nrotary_entries: []\n"),
            "cat.yaml:2:17: rotary_entries: expected a list of at least one entry, found an empty "
            "list");
  EXPECT_EQ(error_of("catalog: c\nentries:\n  - {name: M40, type: e, max_force: 5, stroke: 0.1, "
                     "max_speed: 0.2}\n" +
                     rotary),
            "cat.yaml:5:12: rotary_entries[0].name: expected a name not used by an earlier entry, "
            "found 'M40' again");
  EXPECT_EQ(error_of("catalog: c\nrotary_entries:\n  - {name: M, type: g, max_torque: 40, "
                     "peak_torque: 30, max_speed: 300}\n"),
            "cat.yaml:3:53: rotary_entries[0].peak_torque: expected a peak torque (N*m) >= "
            "max_torque = 40, found 30");
}

TEST(ActuatorCatalogFile, ReadmeTableMatchesTheFieldLists) {
  std::ifstream in(std::string(PKMOPT_SOURCE_DIR) + "/README.md");
  std::stringstream readme;
  readme << in.rdbuf();
  const std::string block = "<!-- fields: actuator_catalog -->\n" +
                            actuator_catalog_fields_markdown() + "<!-- /fields -->\n";
  EXPECT_NE(readme.str().find(block), std::string::npos)
      << "README.md lacks the generated catalog table:\n"
      << block;
}

// Every catalog file shipped in the repo (.yaml files with the lines `catalog:` and `entries:`).
std::vector<std::string> shipped_catalog_files() {
  std::vector<std::string> files;
  for (const char* dir : {"examples", "studies", "tests"}) {
    const std::filesystem::path root = std::filesystem::path(PKMOPT_SOURCE_DIR) / dir;
    for (const auto& entry : std::filesystem::recursive_directory_iterator(root)) {
      if (!entry.is_regular_file() || entry.path().extension() != ".yaml") continue;
      std::ifstream in(entry.path());
      std::stringstream text;
      text << in.rdbuf();
      const std::string t = "\n" + text.str();
      if (t.find("\ncatalog:") != std::string::npos && t.find("\nentries:") != std::string::npos)
        files.push_back(entry.path().string());
    }
  }
  return files;
}

// Every member equal (==).
void expect_same_catalog(const ActuatorCatalog& a, const ActuatorCatalog& b) {
  EXPECT_EQ(a.name, b.name);
  ASSERT_EQ(a.entries.size(), b.entries.size());
  for (std::size_t i = 0; i < a.entries.size(); ++i) {
    const ActuatorEntry& x = a.entries[i];
    const ActuatorEntry& y = b.entries[i];
    EXPECT_EQ(x.name, y.name) << "entry " << i;
    EXPECT_EQ(x.type, y.type) << "entry " << i;
    EXPECT_EQ(x.max_force, y.max_force) << "entry " << i;
    EXPECT_EQ(x.stroke, y.stroke) << "entry " << i;
    EXPECT_EQ(x.max_speed, y.max_speed) << "entry " << i;
    EXPECT_EQ(x.accuracy, y.accuracy) << "entry " << i;
    EXPECT_EQ(x.stiffness, y.stiffness) << "entry " << i;
    EXPECT_EQ(x.cost, y.cost) << "entry " << i;
  }
  ASSERT_EQ(a.drive_types.size(), b.drive_types.size());
  for (std::size_t i = 0; i < a.drive_types.size(); ++i) {
    const DriveType& x = a.drive_types[i];
    const DriveType& y = b.drive_types[i];
    EXPECT_EQ(x.name, y.name) << "drive type " << i;
    EXPECT_EQ(x.speed_min, y.speed_min) << "drive type " << i;
    EXPECT_EQ(x.speed_max, y.speed_max) << "drive type " << i;
    EXPECT_EQ(x.accuracy_min, y.accuracy_min) << "drive type " << i;
    EXPECT_EQ(x.accuracy_max, y.accuracy_max) << "drive type " << i;
    EXPECT_EQ(x.note, y.note) << "drive type " << i;
  }
}

// Written, then read by the strict reader; the catalog must be the same and writing it again the
// same text.
void expect_round_trip(const ActuatorCatalog& catalog) {
  const std::string text = actuator_catalog_to_yaml(catalog);
  SCOPED_TRACE(text);
  ActuatorCatalog again;
  ASSERT_NO_THROW(again = read_actuator_catalog(YamlValue::load_string(text, "written.yaml")));
  expect_same_catalog(catalog, again);
  EXPECT_EQ(actuator_catalog_to_yaml(again), text);
}

TEST(ActuatorCatalogFileWriter, ShippedCatalogsRoundTripExactly) {
  const std::vector<std::string> files = shipped_catalog_files();
  EXPECT_GE(files.size(), 1u);  // studies/library/catalogs/sew-cms.yaml
  for (const std::string& path : files) {
    SCOPED_TRACE(path);
    expect_round_trip(load_actuator_catalog(path));
  }
}

TEST(ActuatorCatalogFileWriter, WritesEveryKey) {
  ActuatorCatalog catalog;
  catalog.name = "test: catalog";  // texts YAML must quote
  catalog.entries = {{.name = "A, \"big\"",
                      .type = "null",
                      .max_force = 1.0 / 3.0,
                      .stroke = 0.1 + 0.2,
                      .max_speed = 0.45,
                      .accuracy = 1e-5 / 3.0,
                      .stiffness = 1.5e8,
                      .cost = 2.0,
                      .peak_force = 0.5},
                     {.name = "B/200",
                      .type = "linear_motor",
                      .max_force = 50,
                      .stroke = 0.3,
                      .max_speed = 3,
                      .accuracy = 2e-6,
                      .stiffness = 7.25e7,
                      .cost = 0.5,
                      .peak_force = std::nullopt}};
  catalog.drive_types = {{.name = "x",
                          .speed_min = 1,
                          .speed_max = 1,
                          .accuracy_min = 1e-6,
                          .accuracy_max = 1e-5,
                          .note = "a, b: \\ \"c\"\n# d"}};
  const std::string text = actuator_catalog_to_yaml(catalog);
  for (const char* key :
       {"catalog: ", "\nentries:\n", "{name: ", ", type: ", ", max_force: ", ", stroke: ",
        ", max_speed: ", ", accuracy: ", ", stiffness: ", ", cost: ", ", peak_force: ",
        "\ndrive_types:\n", ", speed: [1, 1]", ", note: "})
    EXPECT_NE(text.find(key), std::string::npos) << key << " missing in\n" << text;
  expect_round_trip(catalog);
}

TEST(ActuatorCatalogFileWriter, LeavesDefaultsOut) {
  // No accuracy, stiffness or cost, no drive types, a drive type without a note.
  ActuatorCatalog catalog;
  catalog.name = "c";
  ActuatorEntry entry;
  entry.name = "A";
  entry.type = "electric_cylinder";
  entry.max_force = 100;
  entry.stroke = 0.1;
  entry.max_speed = 0.2;
  catalog.entries = {entry};
  EXPECT_EQ(
      actuator_catalog_to_yaml(catalog),
      "catalog: c\nentries:\n"
      "  - {name: A, type: electric_cylinder, max_force: 100, stroke: 0.1, max_speed: 0.2}\n");
  expect_round_trip(catalog);
  DriveType type;
  type.name = "y";
  type.speed_min = 0.5;
  type.speed_max = 2;
  type.accuracy_min = 2e-6;
  type.accuracy_max = 2e-6;
  catalog.drive_types = {type};
  EXPECT_NE(actuator_catalog_to_yaml(catalog).find(
                "drive_types:\n  - {name: y, speed: [0.5, 2], accuracy: [2e-06, 2e-06]}\n"),
            std::string::npos);
  expect_round_trip(catalog);
}

}  // namespace
}  // namespace pkmopt
