// `pkmopt describe`: the degrees of freedom and the structure class of a machine file.
//
// Machine files with a parallel model (hexapod, delta, ...; io/machine_file.hpp), serial axes by
// coordinate code (described here; not computable by analyze/fk), and hybrid machines (serial
// axes carrying a parallel module; computable, io/machine_file_hybrid.hpp):
//
//   model: serial                    # serial axes by coordinate code (models/serial_chain.hpp)
//   name: "5-axis milling machine"   # optional
//   code: "641236"                   # motions 1..6 in chain order, workpiece to tool
//   axes: [C, A, X, Y, Z, S]         # optional, one name per variable motion
//   spindle: S                       # optional: the axis that is the cutting motion
//
//   model: hybrid                    # serial axes carrying a parallel module
//   name: "gantry with a tripod head"
//   serial: {code: "12", axes: [X, Y]}
//   parallel: {file: delta.yaml}     # a machine file, relative to this file
//
// Drives: every variable serial axis except the spindle is a serial (open-chain) feed drive;
// every actuator of the parallel module a parallel (closed-chain) drive. The structure class is
// "P<serial>З<parallel>" (by drive coupling, models/serial_chain.hpp). The degrees of
// freedom of the tool relative to the workpiece are counted per kind (translations, rotations);
// a hybrid's are the sum (more than 6 means redundancy).
#pragma once

#include <string>
#include <vector>

#include "io/yaml_reader.hpp"

namespace pkmopt {

struct MachineDescription {
  std::string model;
  std::string name;
  int translations = 0;  ///< translational degrees of freedom (feed motions)
  int rotations = 0;     ///< rotational degrees of freedom (feed motions)
  int serial_drives = 0;
  int parallel_drives = 0;
  std::string structure;             ///< "P5З0"
  std::vector<std::string> details;  ///< further "key: value" lines
};

/// Reads and describes a machine file. Throws InputError for bad files.
MachineDescription describe_machine_file(const std::string& path);
/// The same for a parsed machine file (a hybrid's module file is taken relative to the folder of
/// root.file()).
MachineDescription describe_machine(const YamlValue& root);

/// Reads the serial axes of `map` ({code, axes} and, with `allow_spindle`, spindle) into the
/// description: drives, degrees of freedom and the details lines. Returns the number of
/// variable axes. Throws InputError.
int describe_serial_axes(const YamlValue& map, bool allow_spindle, MachineDescription& description);

/// The text `pkmopt describe` prints.
std::string format_description(const MachineDescription& description);

}  // namespace pkmopt
