#include "io/machine/machine_description.hpp"

#include <fmt/format.h>

#include <filesystem>
#include <stdexcept>

#include "io/format/yaml_reader.hpp"
#include "io/machine/machine_file.hpp"
#include "io/machine/machine_file_hybrid.hpp"
#include "io/machine/model_registry.hpp"

namespace pkmopt {
MachineDescription describe_machine_file(const std::string& path) {
  return describe_machine(YamlValue::load_file(path));
}

MachineDescription describe_machine(const YamlValue& root) {
  root.expect_map();
  const YamlValue model_value = root.required("model");
  MachineDescription d;
  d.model = model_value.as_string();
  if (const auto name = root.optional("name")) d.name = name->as_string();
  const ModelEntry* entry = find_model(d.model);
  if (entry != nullptr && entry->describe) {
    entry->describe(root, d);
  } else {
    // A parallel machine: its platform's degrees of freedom and its actuators.
    const std::unique_ptr<Machine> machine = load_machine(root);
    const PlatformDofs dofs = entry->platform_dofs(root);  // load_machine found the entry
    d.translations = dofs.translations;
    d.rotations = dofs.rotations;
    d.parallel_drives = machine->num_actuators();
    d.details.push_back(fmt::format("actuators: {} {}", machine->num_actuators(),
                                    machine->revolute_actuators() ? "revolute" : "prismatic"));
  }
  d.structure = structure_class(d.serial_drives, d.parallel_drives);
  return d;
}

std::string format_description(const MachineDescription& d) {
  std::string out = fmt::format("model: {}\n", d.model);
  if (!d.name.empty()) out += fmt::format("name: {}\n", d.name);
  const int dof = d.translations + d.rotations;
  out += fmt::format("dof: {} ({} translations, {} rotations){}\n", dof, d.translations,
                     d.rotations, dof > 6 ? ", redundant" : "");
  out += fmt::format("drives: {} serial, {} parallel\n", d.serial_drives, d.parallel_drives);
  out += fmt::format("structure_class: {}\n", d.structure);
  for (const std::string& line : d.details) out += line + "\n";
  return out;
}

}  // namespace pkmopt
