#include "io/machine_description.hpp"

#include <fmt/format.h>

#include <filesystem>
#include <map>
#include <set>
#include <stdexcept>
#include <utility>

#include "io/machine_file.hpp"
#include "io/machine_file_hybrid.hpp"
#include "io/yaml_reader.hpp"
#include "models/serial_chain.hpp"

namespace pkmopt {
namespace {

// Platform mobility of the parallel models: {translations, rotations}.
std::pair<int, int> parallel_mobility(const YamlValue& model_value, const std::string& model) {
  static const std::map<std::string, std::pair<int, int>> kMobility = {
      {"hexapod", {3, 3}},      {"hexaglide", {3, 3}},   {"delta", {3, 0}},
      {"linear_delta", {3, 0}}, {"tripod_3prs", {1, 2}}, {"lathe_16k20f3", {3, 1}}};
  const auto it = kMobility.find(model);
  if (it == kMobility.end()) model_value.fail("a known model", "'" + model + "'");
  return it->second;
}

// Platform mobility of `model: leg_chain` files from their `mobility:` key (already validated).
std::pair<int, int> leg_chain_mobility(const YamlValue& root) {
  const std::string mobility = root.required("mobility").as_string();
  if (mobility == "translational") return {3, 0};
  if (mobility == "schoenflies") return {3, 1};
  if (mobility == "planar_legs") return {1, 2};
  return {3, 3};
}

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

MachineDescription describe_machine_file(const std::string& path) {
  return describe_machine(YamlValue::load_file(path));
}

MachineDescription describe_machine(const YamlValue& root) {
  const std::string& path = root.file();
  root.expect_map();
  const YamlValue model_value = root.required("model");
  MachineDescription d;
  d.model = model_value.as_string();
  if (const auto name = root.optional("name")) d.name = name->as_string();
  if (d.model == "serial") {
    root.check_keys({"model", "name", "description", "code", "axes", "spindle"});
    add_serial(d, read_serial(root, true));
  } else if (d.model == "hybrid") {
    root.check_keys({"model", "name", "description", "serial", "parallel", "gravity"});
    const YamlValue serial = root.required("serial");
    serial.check_keys({"code", "axes", "range", "stiffness", "error", "mass"});
    const SerialPart part = read_serial(serial, false);
    // The numbers by the rules `analyze` reads them with: one reader, one verdict.
    check_hybrid_numbers(root, part.chain.num_variables());
    add_serial(d, part);
    const YamlValue parallel = root.required("parallel");
    parallel.check_keys({"file", "home"});
    const YamlValue file = parallel.required("file");
    const YamlValue module_root = read_hybrid_module_file(file, path);
    const MachineDescription inner = describe_machine(module_root);
    d.translations += inner.translations;
    d.rotations += inner.rotations;
    d.parallel_drives = inner.parallel_drives;
    d.details.push_back(fmt::format("parallel: {} ({})", inner.model, module_root.file()));
  } else {
    const std::unique_ptr<Machine> machine = load_machine(root);
    const auto [translations, rotations] =
        d.model == "leg_chain" ? leg_chain_mobility(root) : parallel_mobility(model_value, d.model);
    d.translations = translations;
    d.rotations = rotations;
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
