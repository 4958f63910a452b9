// Tests of io/actuator_catalog_file: the shipped catalog loads, and bad files give exact
// messages.
#include "io/actuator_catalog_file.hpp"

#include <gtest/gtest.h>

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
  const ActuatorCatalog catalog =
      load_actuator_catalog(std::string(PKMOPT_SOURCE_DIR) + "/studies/library/catalogs/sew-cms.yaml");
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

}  // namespace
}  // namespace pkmopt
