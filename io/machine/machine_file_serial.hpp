// Machine files of serial machines by coordinate code, `model: serial`
// (models/serial/serial_chain.hpp; 5-axis machines are computable,
// models/serial/serial_machine.hpp), and the serial axes of a hybrid machine
// (io/machine/machine_file_hybrid.hpp).
//
//   model: serial
//   name: "5-axis milling machine"   # optional
//   code: "641236"                   # motions 1..6 in chain order, workpiece to tool
//   axes: [C, A, X, Y, Z, S]         # optional, one name per variable motion
//   spindle: S                       # optional: the axis that is the cutting motion
//   range: [[-360, 360], [-110, 0], [-0.5, 0.5], [-0.4, 0.4], [-0.3, 0.6]]
//                                    # per feed axis (the axes without the spindle), in chain
//                                    # order: m for a linear axis, degrees for a rotary one
//   stiffness: [2.0e5, 3.0e5, 1.5e8, 1.2e8, 1.0e8]   # optional, N/m or N*m/rad (absent: rigid)
//   error: [0.0005, 0.0005, 5e-6, 5e-6, 5e-6]        # optional, m or degrees (absent: 0)
//   tool: [0, 0, 0.15]               # optional, the tool point in the last frame (m)
//   tool_axis: [0, 0, 1]             # optional, the tool axis in the last frame
//   characteristic_length: 0.1       # optional, m: L of singularity_margin
//
// `pkmopt describe` takes any chain; a file with `range` is a machine for fk, analyze, trajectory
// and workspace, which need a 5-axis chain (two rotary and three linear feed axes). Strict like
// the other readers: every bad value throws InputError naming file, line, column and key.
#pragma once

#include <string>

#include "io/format/yaml_reader.hpp"
#include "io/machine/machine_description.hpp"
#include "models/serial/serial_chain.hpp"
#include "models/serial/serial_machine.hpp"

namespace pkmopt {

/// The design of a `model: serial` file (constant rotations and rotary values in radians).
SerialDesign read_serial_design(const YamlValue& root);

/// The chain of a `code` value (SerialChain::from_code), its constants checked by the number
/// policy (io/format/number_policy.hpp): a translation within +-1000 m, a rotation (degrees) within
/// +-1e15 and not below 1e-30 in magnitude; throws InputError at `code`.
SerialChain chain_of_code(const YamlValue& code);

/// The chain as a file's `code`: a digit per element, constants as "k:v" (m; degrees for
/// rotations, written so that the reader gets the same radians back).
std::string serial_code_text(const SerialChain& chain);
/// A rotation (rad) as the degrees the readers convert back to exactly that value when one
/// exists (12 significant digits, else the nearest shortest text).
std::string degrees_text(double rad);
/// The machine file of a serial design (every key; read_serial_design reads it back to the same
/// design).
std::string serial_design_to_yaml(const SerialDesign& design);

/// Reads the serial axes of `map` ({code, axes} and, with `allow_spindle`, spindle) into the
/// description: drives, degrees of freedom and the details lines. Returns the number of
/// variable axes. Throws InputError.
int describe_serial_axes(const YamlValue& map, bool allow_spindle, MachineDescription& description);

}  // namespace pkmopt
