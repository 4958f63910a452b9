// Machine files (YAML) of hybrid machines, `model: hybrid`: serial translation axes carrying a
// parallel module (models/hybrid/hybrid_machine.hpp has the model, the follow rule and the
// metrics).
//
//   model: hybrid
//   name: "long axis carrying a hexapod"                 # optional
//   serial:
//     code: "1"              # coordinate code; variable elements must be translations 1, 2, 3;
//                            # constants "k:v" (m for 1..3, DEGREES for rotations 4..6)
//     axes: [X]              # optional names, one per variable element
//     range: [[-1.0, 1.0]]   # [min, max] per axis (m), required
//     stiffness: [2.0e8]     # optional, N/m per axis (0 = rigid; absent: all rigid)
//     error: [5.0e-6]        # optional, m per axis (absent: 0)
//   parallel:
//     file: hexapod.yaml     # the module's machine file, relative to this file
//     home: [0, 0, 0.9]      # module-local reference point h of the follow rule (m), required
//
// Strict like the other readers: unknown keys, counts that differ from the number of axes,
// min > max, variable rotary axes, linearly dependent axes, a module file that is missing, is
// itself serial or hybrid, or has revolute drives (a delta) all throw InputError naming file, line,
// column and key (exit 2). The keys are described once in a field list (io/format/field_list.hpp):
// the reader, the writer (hybrid_design_to_yaml) and the docs table of docs/hybrid-machines.md come
// from it; the code, the axis names and the module file are read and written by hand next to it.
// The design holds the module as a machine, not as a file: the writer is given the module file to
// name, and writes no name or description (the design has none). Numbers are written in their
// shortest round-trip form and constant rotations in degrees that convert back to the same
// radians, so reading a written file gives the same design.
//
// Example:
//   YamlValue root = YamlValue::load_file("examples/hybrid_long_axis_hexapod.yaml");
//   std::unique_ptr<Machine> machine = load_hybrid_machine(root);
//   std::string yaml = hybrid_design_to_yaml(read_hybrid_design(root), "hexapod.yaml");
#pragma once

#include <memory>
#include <string>

#include "io/format/yaml_reader.hpp"
#include "models/hybrid/hybrid_machine.hpp"

namespace pkmopt {

/// The design of a `model: hybrid` map; module file paths are relative to root.file().
HybridDesign read_hybrid_design(const YamlValue& root);
/// The machine file of a design, `module_file` as its parallel.file (relative to the written file),
/// or, when `module_yaml` is given, the module's machine file inline (parallel.machine).
std::string hybrid_design_to_yaml(const HybridDesign& design, const std::string& module_file,
                                  const std::string& module_yaml = "");
/// The machine of a `model: hybrid` map.
std::unique_ptr<Machine> load_hybrid_machine(const YamlValue& root);

/// The numbers of a hybrid file — serial range, stiffness, error and mass (one per variable axis
/// of a chain with `num_variables`), parallel home, gravity — read by the rules of
/// read_hybrid_design (the same messages). For `pkmopt describe`, which accepts chains
/// read_hybrid_design refuses (variable rotary axes) but no number it would refuse.
void check_hybrid_numbers(const YamlValue& root, int num_variables);
/// The module file a hybrid's `parallel.file` names (relative to `hybrid_file`), parsed; throws
/// InputError at `file` when it is missing, not a regular file, or a hybrid or serial machine.
YamlValue read_hybrid_module_file(const YamlValue& file, const std::string& hybrid_file);
/// The module of a hybrid's `parallel` section: its `file` (as read_hybrid_module_file) or its
/// inline `machine` map (exactly one of them).
YamlValue read_hybrid_module(const YamlValue& parallel, const std::string& hybrid_file);

/// The docs table of the hybrid machine file's keys, from the field list its reader uses.
std::string hybrid_machine_fields_markdown();

}  // namespace pkmopt
