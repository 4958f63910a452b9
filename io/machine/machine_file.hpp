// Machine files (YAML): reading with strict validation, and writing.
//
// The hexapod form is fixed by docs/conventions.md:
//   model: hexapod
//   base: {radius: 0.60, pair_separation_deg: 20}        # or base_joints: [[x,y,z] x 6]
//   platform: {radius: 0.25, pair_separation_deg: 20}    # or platform_joints: [[x,y,z] x 6]
//   legs: {min_length: 0.70, max_length: 1.15, E: 2.1e11, area: 3.0e-4,
//          actuator_stiffness: 2.0e8}                   # or axial_stiffness: N/m
//   joints: {base_max_angle_deg: 45, platform_max_angle_deg: 45,
//            base_axis: [0,0,1], platform_axis: [0,0,-1]}   # optional
//   tool: {tcp: [0, 0, -0.10]}                            # optional
//   characteristic_length: 0.25                           # optional
//   actuator_error: 1.0e-5                                # optional
// Unknown keys, missing required keys, wrong counts, non-finite numbers and impossible values
// throw InputError naming file, line, column and key.
#pragma once

#include <memory>
#include <string>

#include "io/format/yaml_reader.hpp"
#include "models/core/machine.hpp"
#include "models/hexapod/hexapod.hpp"

namespace pkmopt {

/// Any machine file: dispatches on `model:`. Throws InputError.
std::unique_ptr<Machine> load_machine_file(const std::string& path);
/// A machine from a parsed YAML map (e.g. a `machine:` section of a larger file).
std::unique_ptr<Machine> load_machine(const YamlValue& root);

/// A hexapod design from a parsed YAML map with `model: hexapod`. Throws InputError.
HexapodDesign read_hexapod_design(const YamlValue& root);

/// The machine file text of a hexapod design (explicit joint coordinates, every value
/// written so that it round-trips).
std::string hexapod_design_to_yaml(const HexapodDesign& design);

/// The docs table of the hexapod machine file's keys, from the field list its reader and writer
/// use.
std::string hexapod_machine_fields_markdown();

}  // namespace pkmopt
