// Machine files of serial axes by coordinate code, `model: serial`
// (models/serial/serial_chain.hpp): read for `pkmopt describe` only (not computable by analyze or
// fk), and the serial axes of a hybrid machine (io/machine/machine_file_hybrid.hpp).
//
//   model: serial
//   name: "5-axis milling machine"   # optional
//   code: "641236"                   # motions 1..6 in chain order, workpiece to tool
//   axes: [C, A, X, Y, Z, S]         # optional, one name per variable motion
//   spindle: S                       # optional: the axis that is the cutting motion
#pragma once

#include "io/format/yaml_reader.hpp"
#include "io/machine/machine_description.hpp"
#include "models/serial/serial_chain.hpp"

namespace pkmopt {

/// The chain of a `code` value (SerialChain::from_code), its constants checked by the number
/// policy (io/format/number_policy.hpp): a translation within +-1000 m, a rotation (degrees) within
/// +-1e15 and not below 1e-30 in magnitude; throws InputError at `code`.
SerialChain chain_of_code(const YamlValue& code);

/// Reads the serial axes of `map` ({code, axes} and, with `allow_spindle`, spindle) into the
/// description: drives, degrees of freedom and the details lines. Returns the number of
/// variable axes. Throws InputError.
int describe_serial_axes(const YamlValue& map, bool allow_spindle, MachineDescription& description);

}  // namespace pkmopt
