// `pkmopt describe`: the degrees of freedom and the structure class of a machine file.
//
// Machine files with a parallel model (hexapod, delta, ...; io/machine/machine_file.hpp), serial
// axes by coordinate code (io/machine/machine_file_serial.hpp; not computable by analyze/fk), and
// hybrid machines (serial axes carrying a parallel module; computable,
// io/machine/machine_file_hybrid.hpp). Each model describes itself through its registry entry
// (io/machine/model_registry.hpp); a parallel model by its platform's degrees of freedom.
//
// Drives: every variable serial axis except the spindle is a serial (open-chain) feed drive;
// every actuator of the parallel module a parallel (closed-chain) drive. The structure class is
// "P<serial>З<parallel>" (by drive coupling, models/serial/serial_chain.hpp). The degrees of
// freedom of the tool relative to the workpiece are counted per kind (translations, rotations);
// a hybrid's are the sum (more than 6 means redundancy).
#pragma once

#include <string>
#include <vector>

#include "io/format/yaml_reader.hpp"

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

/// The text `pkmopt describe` prints.
std::string format_description(const MachineDescription& description);

}  // namespace pkmopt
