// Reading actuator catalog files (YAML) into problems/design/actuator_catalog.
//
//   catalog: sew-cms                     # name, required
//   description: "..."                   # optional
//   entries:                             # at least one
//     - {name: CMS63S/200, type: electric_cylinder, max_force: 10500, stroke: 0.200,
//        max_speed: 0.45, accuracy: 1.0e-5, stiffness: 1.5e8, cost: 2.0}   # last 3 optional
//   drive_types:                         # optional comparison table
//     - {name: linear_motor, speed: [2, 5], accuracy: [1.0e-6, 5.0e-6], note: "..."}
//
// SI units: N, m, m/s, N/m. Strict: unknown keys, missing keys, non-finite or non-positive
// numbers, repeated names -> InputError "file:line:col: key: expected ..., found ...". The keys
// of the catalog, its entries and its drive types are described once in field lists
// (io/format/field_list.hpp): the reader, the writer (actuator_catalog_to_yaml: numbers in their
// shortest round-trip form, texts quoted where YAML needs it; the catalog holds no description, so
// none is written) and the docs table in README.md come from them.
#pragma once

#include <string>
#include <vector>

#include "io/format/field_list.hpp"
#include "io/format/yaml_reader.hpp"
#include "problems/design/actuator_catalog.hpp"

namespace pkmopt {

ActuatorCatalog read_actuator_catalog(const YamlValue& root);
ActuatorCatalog load_actuator_catalog(const std::string& path);
/// The catalog file text of a catalog (read back by read_actuator_catalog to the same catalog).
std::string actuator_catalog_to_yaml(const ActuatorCatalog& catalog);

/// One `{actuator, catalog}` entry of a study's `constraints:`.
struct ActuatorConstraintEntry {
  std::string actuator;
  std::string catalog;
  bool each_drive = false;
};

template <class Fields>
void describe_fields(Fields& f, ActuatorConstraintEntry& a) {
  f.field(
      "actuator", a.actuator,
      {.required = true,
       .expected = "an entry name of the catalog, or cheapest",
       .doc = "the legs are this catalog entry, or cheapest: the optimiser chooses per design"});
  f.field("catalog", a.catalog,
          {.required = true,
           .expected = "a path",
           .doc = "actuator catalog file, relative to the study file"});
  f.note("drives", "a list of actuator numbers (1-based, as q_1..q_n)", "", "every drive",
         "the drives the entry is chosen for (a machine with two kinds of drive, e.g. the "
         "16K20F3 lathe's cylinders 3 and 4 beside its carriages 1 and 2); not for hexapods, "
         "whose six legs are alike");
  f.field("each_drive", a.each_drive,
          {.doc = "true: every drive is priced, linear ones from entries[], revolute ones from "
                  "rotary_entries[]; alike drives (a parallel machine's legs) share the entry "
                  "that carries the worst of them, each serial axis gets its own; the metrics "
                  "drive_cost (the sum) and drive_overload, and drive_overload <= 0; needs "
                  "actuator: cheapest and a cost on every entry"});
}

/// `{actuator: cheapest, catalog: FILE}`: the optimiser chooses the entry.
inline constexpr const char* kCheapestActuator = "cheapest";

/// A study's `{actuator, catalog}` constraint read: its keys, the catalog file's absolute path
/// (resolved against the study file's folder) and the catalog.
struct ActuatorConstraintFile {
  ActuatorConstraintEntry keys;
  std::vector<int> drives;  ///< 0-based actuator indices from `drives`; empty: every drive
  /// The named entry's index in `catalog`; -1 for `cheapest`.
  int entry = -1;
  bool cheapest() const { return entry < 0; }
  std::string catalog_path;
  ActuatorCatalog catalog;
};
/// Reads `constraint` of the study at `study_path`. Throws InputError at `catalog` when the file
/// does not exist or is not a catalog, or (for `cheapest`) when only some entries have a cost; at
/// `actuator` when the name is no entry of the catalog, or is `cheapest` and the catalog has an
/// entry of that name.
ActuatorConstraintFile read_actuator_constraint_file(const YamlValue& constraint,
                                                     const std::string& study_path);

/// The docs table of the catalog file's keys (entries' keys as `entries[].KEY`, drive types' as
/// `drive_types[].KEY`), from the field lists the reader uses.
std::string actuator_catalog_fields_markdown();

}  // namespace pkmopt
