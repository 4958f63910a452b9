#include "io/actuator_catalog_file.hpp"

#include <set>
#include <tuple>
#include <utility>
#include <vector>

namespace pkmopt {
namespace {

// [min, max] with 0 < min <= max.
std::pair<double, double> read_range(const YamlValue& value) {
  const std::vector<double> range = value.as_doubles(2);
  if (!(range[0] > 0.0 && range[0] <= range[1])) {
    value.fail("[min, max] with 0 < min <= max", value.describe());
  }
  return {range[0], range[1]};
}

ActuatorEntry read_entry(const YamlValue& value) {
  value.check_keys(
      {"name", "type", "max_force", "stroke", "max_speed", "accuracy", "stiffness", "cost"});
  ActuatorEntry entry;
  const YamlValue name = value.required("name");
  entry.name = name.as_string();
  if (entry.name.empty()) name.fail("a non-empty name", "''");
  entry.type = value.required("type").as_string();
  entry.max_force = value.required("max_force").as_positive();
  entry.stroke = value.required("stroke").as_positive();
  entry.max_speed = value.required("max_speed").as_positive();
  if (const auto v = value.optional("accuracy")) entry.accuracy = v->as_positive();
  if (const auto v = value.optional("stiffness")) entry.stiffness = v->as_positive();
  if (const auto v = value.optional("cost")) entry.cost = v->as_positive();
  return entry;
}

DriveType read_drive_type(const YamlValue& value) {
  value.check_keys({"name", "speed", "accuracy", "note"});
  DriveType type;
  type.name = value.required("name").as_string();
  std::tie(type.speed_min, type.speed_max) = read_range(value.required("speed"));
  std::tie(type.accuracy_min, type.accuracy_max) = read_range(value.required("accuracy"));
  if (const auto note = value.optional("note")) type.note = note->as_string();
  return type;
}

}  // namespace

ActuatorCatalog read_actuator_catalog(const YamlValue& root) {
  root.check_keys({"catalog", "description", "entries", "drive_types"});
  ActuatorCatalog catalog;
  catalog.name = root.required("catalog").as_string();
  if (const auto d = root.optional("description")) (void)d->as_string();
  const YamlValue entries = root.required("entries");
  const std::vector<YamlValue> items = entries.elements();
  if (items.empty()) entries.fail("a list of at least one entry", "an empty list");
  std::set<std::string> names;
  for (const YamlValue& item : items) {
    catalog.entries.push_back(read_entry(item));
    if (!names.insert(catalog.entries.back().name).second) {
      item.required("name").fail("a name not used by an earlier entry",
                                 "'" + catalog.entries.back().name + "' again");
    }
  }
  if (const auto types = root.optional("drive_types")) {
    for (const YamlValue& item : types->elements()) {
      catalog.drive_types.push_back(read_drive_type(item));
    }
  }
  return catalog;
}

ActuatorCatalog load_actuator_catalog(const std::string& path) {
  return read_actuator_catalog(YamlValue::load_file(path));
}

}  // namespace pkmopt
