#include "io/machine_description.hpp"

#include <fmt/format.h>

#include <filesystem>
#include <set>
#include <stdexcept>

#include "io/machine_file.hpp"
#include "io/machine_file_hybrid.hpp"
#include "io/model_registry.hpp"
#include "io/yaml_reader.hpp"
#include "models/serial_chain.hpp"

namespace pkmopt {
namespace {

struct SerialPart {
  SerialChain chain;
  std::vector<std::string> axes;
  int spindle = -1;  // index of the spindle axis among the variables, -1 if none
};

SerialPart read_serial(const YamlValue& map, bool allow_spindle) {
  SerialPart part;
  part.chain = chain_of_code(map.required("code"));
  const int n = part.chain.num_variables();
  if (const auto axes = map.optional("axes")) {
    for (const YamlValue& a : axes->elements(n)) part.axes.push_back(a.as_string());
    std::set<std::string> unique(part.axes.begin(), part.axes.end());
    if (static_cast<int>(unique.size()) != n) axes->fail("distinct axis names", axes->describe());
  } else {
    for (int i = 0; i < n; ++i) part.axes.push_back(fmt::format("q{}", i + 1));
  }
  if (allow_spindle) {
    if (const auto spindle = map.optional("spindle")) {
      const std::string name = spindle->as_string();
      for (int i = 0; i < n; ++i) {
        if (part.axes[static_cast<std::size_t>(i)] == name) part.spindle = i;
      }
      if (part.spindle < 0) spindle->fail("one of the names in 'axes'", "'" + name + "'");
      int motion = 0, k = 0;
      for (const ChainElement& e : part.chain.elements()) {
        if (e.variable && k++ == part.spindle) motion = e.motion;
      }
      if (motion < 4) spindle->fail("a rotary axis (motion 4, 5 or 6)", "'" + name + "'");
    }
  }
  return part;
}

void add_serial(MachineDescription& d, const SerialPart& part) {
  int k = 0;
  std::string axes;
  for (const ChainElement& e : part.chain.elements()) {
    if (!e.variable) {
      axes += fmt::format(" ({}:{:g})", e.motion, e.value);
      continue;
    }
    const bool spindle = k == part.spindle;
    axes += fmt::format(" {}({}{})", part.axes[static_cast<std::size_t>(k)], e.motion,
                        spindle ? ", spindle" : "");
    if (!spindle) {
      ++d.serial_drives;
      (e.motion <= 3 ? d.translations : d.rotations) += 1;
    }
    ++k;
  }
  d.details.push_back("code: " + part.chain.code());
  d.details.push_back("axes:" + axes);
}

}  // namespace

int describe_serial_axes(const YamlValue& map, bool allow_spindle, MachineDescription& d) {
  const SerialPart part = read_serial(map, allow_spindle);
  add_serial(d, part);
  return part.chain.num_variables();
}

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

ModelEntry serial_model_entry() {
  ModelEntry entry;
  entry.name = "serial";
  entry.describe = [](const YamlValue& root, MachineDescription& d) {
    root.check_keys({"model", "name", "description", "code", "axes", "spindle"});
    describe_serial_axes(root, true, d);
  };
  return entry;
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
