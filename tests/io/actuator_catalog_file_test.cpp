// Tests of io/actuator_catalog_file: the shipped catalog loads, bad files give exact messages,
// every key of the field lists is read, and README.md carries the table generated from them.
#include "io/actuator_catalog_file.hpp"

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <string>

#include "io/input_error.hpp"

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
  const ActuatorChoice choice = choose_actuator(catalog, {6633.0, 0.15, 0.0});
  ASSERT_NE(choice.entry, nullptr);
  EXPECT_EQ(choice.entry->name, "CMS63S/200");
}

TEST(ActuatorCatalogFile, BadFilesGiveExactMessages) {
  const std::string entry =
      "  - {name: A, type: electric_cylinder, max_force: 100, stroke: 0.1, max_speed: 0.2}\n";
  EXPECT_EQ(error_of("catalog: c\nentries:\n" + entry), "no error");
  EXPECT_EQ(error_of("catalog: c\nentries:\n" + entry + "colour: red\n"),
            "cat.yaml:4:1: colour: unknown key 'colour'; allowed keys here: catalog, description, "
            "entries, drive_types");
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

}  // namespace
}  // namespace pkmopt
