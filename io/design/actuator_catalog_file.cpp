#include "io/design/actuator_catalog_file.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <optional>
#include <set>
#include <string>
#include <type_traits>
#include <vector>

#include "io/format/field_list.hpp"

namespace pkmopt {
namespace {

// [min, max] with 0 < min <= max.
FieldRule range_rule(std::string_view unit, std::string_view doc) {
  return {.min = 0,
          .min_exclusive = true,
          .required = true,
          .unit = unit,
          .expected = "[min, max] with 0 < min <= max",
          .doc = doc};
}

FieldRule positive(std::string_view unit, std::string_view doc, bool required) {
  return {.min = 0, .min_exclusive = true, .required = required, .unit = unit, .doc = doc};
}

}  // namespace

template <class Fields>
void describe_fields(Fields& f, ActuatorEntry& e) {
  f.field("name", e.name, {.required = true, .doc = "the entry's name, unique in the catalog"});
  f.field("type", e.type,
          {.required = true, .doc = "drive type, e.g. electric_cylinder, linear_motor"});
  f.field("max_force", e.max_force, positive("N", "rated (continuous) axial force", true));
  f.field(
      "peak_force", e.peak_force,
      positive("N", "short-time peak axial force (>= max_force; max_force when not given)", false));
  f.field("stroke", e.stroke, positive("m", "stroke", true));
  f.field("max_speed", e.max_speed, positive("m/s", "maximum speed", true));
  f.field("accuracy", e.accuracy, positive("m", "positioning accuracy (repeatability)", false));
  f.field("stiffness", e.stiffness, positive("N/m", "axial stiffness", false));
  f.field("cost", e.cost,
          positive("", "relative cost (the cheapest entry that carries wins)", false));
}

template <class Fields>
void describe_fields(Fields& f, RotaryEntry& e) {
  f.field("name", e.name, {.required = true, .doc = "the entry's name, unique in the catalog"});
  f.field("type", e.type,
          {.required = true, .doc = "drive type, e.g. servo_motor, gear_motor, torque_motor"});
  f.field("max_torque", e.max_torque,
          positive("N*m", "rated (continuous) torque at the output shaft", true));
  f.field(
      "peak_torque", e.peak_torque,
      positive("N*m", "short-time peak torque (>= max_torque; max_torque when not given)", false));
  f.field("max_speed", e.max_speed_rpm, positive("1/min", "maximum output speed", true));
  f.field("cost", e.cost,
          positive("", "relative cost, in the unit of the linear entries' costs", false));
}

template <class Fields>
void describe_fields(Fields& f, DriveType& t) {
  f.field("name", t.name, {.required = true, .doc = "the drive type"});
  FieldRange speed{.low = t.speed_min, .high = t.speed_max, .closed = true};
  f.field("speed", speed, range_rule("m/s", "typical speed range"));
  FieldRange accuracy{.low = t.accuracy_min, .high = t.accuracy_max, .closed = true};
  f.field("accuracy", accuracy, range_rule("m", "typical positioning accuracy (best .. worst)"));
  f.field("note", t.note, {.zero_is_unset = true, .doc = "free text"});
}

template <class Fields>
void describe_fields(Fields& f, ActuatorCatalog& c) {
  f.field("catalog", c.name, {.required = true, .doc = "the catalog's name"});
  f.note("description", "a text", "", "none", "free text");
  f.note("entries", "a list of entries (entries[] below)", "", "none",
         "the linear drives, one entry per orderable variant (the catalog needs at least one "
         "entry, linear or rotary)");
  f.note("rotary_entries", "a list of rotary entries (rotary_entries[] below)", "", "none",
         "the rotary drives (revolute actuators), priced by {actuator: cheapest, catalog: FILE, "
         "each_drive: true}");
  f.note("drive_types", "a list of drive types (drive_types[] below)", "", "none",
         "a comparison table of drive principles (not used for sizing)");
}

namespace {

// The entries of one list: each read by its field list, named, its peak rating at least its
// rating, its name not used before (in either list).
template <class Entry>
void read_entries(const std::vector<YamlValue>& items, const char* peak_key,
                  std::string_view peak_expected, std::optional<double> Entry::*peak,
                  double Entry::*rating, std::set<std::string>& names, std::vector<Entry>& out) {
  for (const YamlValue& item : items) {
    Entry entry;
    read_fields(item, entry);
    if (entry.name.empty()) item.required("name").fail("a non-empty name", "''");
    if ((entry.*peak) && *(entry.*peak) < entry.*rating)
      item.required(peak_key).fail(fmt::format("{} = {}", peak_expected, entry.*rating),
                                   fmt::format("{}", *(entry.*peak)));
    if (!names.insert(entry.name).second)
      item.required("name").fail("a name not used by an earlier entry",
                                 "'" + entry.name + "' again");
    out.push_back(std::move(entry));
  }
}

}  // namespace

ActuatorCatalog read_actuator_catalog(const YamlValue& root) {
  ActuatorCatalog catalog;
  read_fields(root, catalog);
  if (const auto d = root.optional("description")) (void)d->as_string();
  const std::optional<YamlValue> entries = root.optional("entries");
  const std::optional<YamlValue> rotary = root.optional("rotary_entries");
  const std::vector<YamlValue> items = entries ? entries->elements() : std::vector<YamlValue>{};
  const std::vector<YamlValue> rotary_items =
      rotary ? rotary->elements() : std::vector<YamlValue>{};
  if (items.empty() && rotary_items.empty()) {
    if (entries) entries->fail("a list of at least one entry", "an empty list");
    if (rotary) rotary->fail("a list of at least one entry", "an empty list");
    root.fail("entries (linear drives) or rotary_entries (rotary drives)", "neither");
  }
  std::set<std::string> names;  // unique across the linear and rotary entries
  read_entries(items, "peak_force", "a peak force (N) >= max_force", &ActuatorEntry::peak_force,
               &ActuatorEntry::max_force, names, catalog.entries);
  read_entries(rotary_items, "peak_torque", "a peak torque (N*m) >= max_torque",
               &RotaryEntry::peak_torque, &RotaryEntry::max_torque, names, catalog.rotary_entries);
  if (const auto types = root.optional("drive_types")) {
    for (const YamlValue& item : types->elements()) {
      DriveType type;
      read_fields(item, type);
      catalog.drive_types.push_back(std::move(type));
    }
  }
  return catalog;
}

ActuatorCatalog load_actuator_catalog(const std::string& path) {
  return read_actuator_catalog(YamlValue::load_file(path));
}

std::string actuator_catalog_to_yaml(const ActuatorCatalog& catalog) {
  auto flow_map = [](auto item) {  // "{key: value, ...}" of an entry or a drive type
    FieldWriter w;
    describe_fields(w, item);
    return w.flow_map();
  };
  ActuatorCatalog copy = catalog;
  FieldWriter top;  // catalog
  describe_fields(top, copy);
  std::string out = top.flow_lines();
  // The lists by hand, as the reader takes them (no description: the catalog holds none).
  out += catalog.entries.empty() ? "entries: []\n" : "entries:\n";
  for (const ActuatorEntry& entry : catalog.entries) out += "  - " + flow_map(entry) + "\n";
  if (!catalog.rotary_entries.empty()) out += "rotary_entries:\n";
  for (const RotaryEntry& entry : catalog.rotary_entries) out += "  - " + flow_map(entry) + "\n";
  if (!catalog.drive_types.empty()) out += "drive_types:\n";
  for (const DriveType& type : catalog.drive_types) out += "  - " + flow_map(type) + "\n";
  return out;
}

std::string actuator_catalog_fields_markdown() {
  FieldDocs docs;
  ActuatorCatalog catalog;
  describe_fields(docs, catalog);
  ActuatorEntry entry;
  docs.set_prefix("entries[].");
  describe_fields(docs, entry);
  RotaryEntry rotary;
  docs.set_prefix("rotary_entries[].");
  describe_fields(docs, rotary);
  DriveType type;
  docs.set_prefix("drive_types[].");
  describe_fields(docs, type);
  return docs.markdown();
}

ActuatorConstraintFile read_actuator_constraint_file(const YamlValue& constraint,
                                                     const std::string& study_path) {
  ActuatorConstraintFile out;
  read_fields(constraint, out.keys);
  const YamlValue catalog_value = constraint.required("catalog");
  std::filesystem::path path = out.keys.catalog;
  if (path.is_relative()) path = std::filesystem::path(study_path).parent_path() / path;
  if (!std::filesystem::exists(path))
    catalog_value.fail("an actuator catalog file", "'" + path.string() + "' (no such file)");
  path = std::filesystem::absolute(path).lexically_normal();
  out.catalog_path = path.string();
  out.catalog = load_actuator_catalog(out.catalog_path);
  const YamlValue name_value = constraint.required("actuator");
  const std::string& name = out.keys.actuator;
  const ActuatorEntry* entry = find_actuator(out.catalog, name);
  if (out.keys.each_drive) {
    if (name != kCheapestActuator)
      name_value.fail(fmt::format("{} (each_drive: true chooses per design)", kCheapestActuator),
                      "'" + name + "'");
    if (constraint.optional("drives"))
      constraint.required("drives").fail(
          "no drives list with each_drive: true (every drive is "
          "priced)",
          "a list");
    if (const std::string problem = check_drive_pricing(out.catalog); !problem.empty())
      catalog_value.fail(fmt::format("a catalog that prices every drive (each_drive: true) in '{}'",
                                     out.catalog_path),
                         problem);
    return out;
  }
  if (out.catalog.entries.empty())
    catalog_value.fail(
        "a catalog with linear entries (rotary_entries are priced with each_drive: "
        "true)",
        fmt::format("catalog '{}' with rotary entries only", out.catalog.name));
  if (name == kCheapestActuator) {
    if (entry != nullptr)
      name_value.fail(fmt::format("a catalog without an entry named '{}' (the word asks for the "
                                  "cheapest entry)",
                                  kCheapestActuator),
                      fmt::format("catalog '{}' with such an entry", out.catalog.name));
    try {
      actuator_costs(out.catalog);
    } catch (const std::invalid_argument& error) {
      catalog_value.fail("a catalog whose entries all have a cost or all have none", error.what());
    }
  } else if (entry == nullptr) {
    std::string names;
    for (const ActuatorEntry& e : out.catalog.entries)
      names += (names.empty() ? "" : ", ") + e.name;
    name_value.fail(fmt::format("an entry of catalog '{}' ({})", out.catalog.name, names),
                    "'" + name + "'");
  } else {
    out.entry = static_cast<int>(entry - out.catalog.entries.data());
  }
  if (const auto drives = constraint.optional("drives")) {
    const std::vector<YamlValue> numbers = drives->elements();
    if (numbers.empty()) drives->fail("a list of actuator numbers (1-based)", "an empty list");
    for (const YamlValue& number : numbers) {
      const long long n = number.as_int();
      if (n < 1 || n > 1000) number.fail("an actuator number >= 1", std::to_string(n));
      if (std::find(out.drives.begin(), out.drives.end(), static_cast<int>(n - 1)) !=
          out.drives.end())
        number.fail("distinct actuator numbers", std::to_string(n) + " twice");
      out.drives.push_back(static_cast<int>(n - 1));
    }
  }
  return out;
}

}  // namespace pkmopt
