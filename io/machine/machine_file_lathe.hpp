// Machine files (YAML) of the 16K20F3 lathe conversion, `model: lathe_16k20f3`
// (models/leg_chain/lathe_conversion.hpp has the mechanism, frame and formulas).
//
// Every key is a top-level scalar (or pair) named like the Lathe16k20f3Design field it sets;
// every key but `model` is optional and defaults to the study's design. Angles in degrees, lengths
// in m, stiffness in N/m, E in Pa, areas in m^2. Strict like the other readers: unknown keys,
// non-finite or impossible values (empty ranges, zero lengths) throw InputError naming file, line,
// column and key. The keys are described once (`describe_fields` below, io/format/field_list.hpp):
// the reader, the writer lathe_16k20f3_machine_file and the
// docs table of docs/machines.md come from that list.
//
//   model: lathe_16k20f3
//   centre_height: 0.215          # spindle axis above the guideways
//   tool_reach: 0.16              # turret centre to the working tool's tip
//   approach_angle_deg: 26.565    # a0: the tool's approach angle at phi = 0
//   strut_length: 0.73            # constant-length strut pairs (PUS)
//   guide_y: 0.10                 # carriages' hinge line (y, z)
//   guide_z: -0.175
//   strut_joint_spread: 0.10      # platform strut joints at (-/+ spread, strut_joint_y, _z)
//   strut_joint_y: 0.15
//   strut_joint_z: -0.10
//   carriage_travel: [-1.4, 1.4]  # carriage position range along x
//   strut_max_angle_deg: 70       # hinge limit: angle between strut and guide
//   strut_E: 2.1e11               # per rod, 2 rods per pair
//   strut_area: 4.0e-4
//   carriage_stiffness: 1.5e8     # carriage drive
//   leg_base_x: 0.0               # overhead base joints (x, y -/+ spacing/2, z)
//   leg_base_y: 0.10
//   leg_base_z: 1.60
//   leg_base_spacing: 0.40
//   leg_joint_spacing: 0.40       # platform leg joints at (0, -/+ spacing/2, leg_joint_z)
//   leg_joint_z: 0.10
//   leg_length: [1.235, 1.585]      # electro-cylinder length range
//   leg_max_angle_deg: 40         # U joint at the beam, from -z
//   leg_E: 2.1e11
//   leg_area: 1.5e-3
//   leg_actuator_stiffness: 1.0e8
//   actuator_error: 1.0e-5
//
// Example:
//   YamlValue root = YamlValue::load_file("studies/library/lathe-16k20f3/lathe.yaml");
//   Lathe16k20f3Design d = read_lathe_16k20f3_design(root);
#pragma once

#include <memory>
#include <string>

#include "io/format/yaml_reader.hpp"
#include "models/leg_chain/lathe_conversion.hpp"

namespace pkmopt {

/// The design of a `model: lathe_16k20f3` file. Throws InputError.
Lathe16k20f3Design read_lathe_16k20f3_design(const YamlValue& root);

/// The docs table of the lathe machine file's keys, from the field list its reader and writer use.
std::string lathe_machine_fields_markdown();

/// The field list of the lathe machine file (io/format/field_list.hpp): instantiated in
/// io/machine/machine_file_lathe.cpp for its reader and docs, and for FieldWriter.
template <class Fields>
void describe_fields(Fields& f, Lathe16k20f3Design& design);

/// The `model: lathe_16k20f3` machine file of a design, every key written (model_file_text,
/// io/format/field_list.hpp): reading a written file gives the same machine.
std::string lathe_16k20f3_machine_file(const Lathe16k20f3Design& design);

}  // namespace pkmopt
