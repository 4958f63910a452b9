#include "io/design/hybrid_study_machine.hpp"

#include <fmt/format.h>
#include <yaml-cpp/yaml.h>

#include <sstream>
#include <string>

#include "io/format/field_list.hpp"
#include "io/machine/machine_file_hybrid.hpp"
#include "io/machine/model_registry.hpp"
#include "problems/design/hybrid_design.hpp"

namespace pkmopt {
namespace {

// Lines of a text, each indented.
std::string indented(const std::string& text, const std::string& indent) {
  std::istringstream lines(text);
  std::string out;
  for (std::string line; std::getline(lines, line);) out += indent + line + "\n";
  return out;
}

}  // namespace

std::unique_ptr<StudyMachine> read_hybrid_study_machine(const YamlValue& machine) {
  machine.check_keys({"model", "name", "description", "serial", "parallel", "gravity"});
  const YamlValue parallel = machine.required("parallel");
  parallel.check_keys({"home", "machine"});
  const YamlValue module_section = parallel.required("machine");
  module_section.expect_map();
  const YamlValue module_model = module_section.required("model");
  const ModelEntry* entry = find_model(module_model.as_string());
  if (entry == nullptr || !entry->design_family || module_model.as_string() == "hybrid")
    module_model.fail(
        "a parallel model with a design family (linear_delta, hexaglide, "
        "tripod_3prs, ...)",
        module_model.describe());
  const std::unique_ptr<StudyMachine> module = read_family_study_machine(*entry, module_section);
  const DesignFamily& module_family = *module->design_family();

  // The carrier: the hybrid file of the section with the module's default machine inline, read
  // by the hybrid's own reader (its messages point into the study file).
  YAML::Node merged(YAML::NodeType::Map);
  for (const auto& item : machine.node()) merged[item.first] = item.second;
  YAML::Node merged_parallel(YAML::NodeType::Map);
  for (const auto& item : parallel.node())
    if (item.first.as<std::string>() != "machine") merged_parallel[item.first] = item.second;
  merged_parallel["machine"] =
      YAML::Load(module_family.machine_file(module_family.default_parameters()));
  merged["parallel"] = merged_parallel;
  YamlValue carrier_section(merged, std::make_shared<const std::string>(machine.file()),
                            machine.path());
  carrier_section.set_location(machine.line(), machine.column());
  const HybridDesign carrier = read_hybrid_design(carrier_section);

  DesignFamily family =
      hybrid_family(carrier, module_family, [](const HybridDesign& d, const std::string& inner) {
        return hybrid_design_to_yaml(d, "", inner);
      });
  // The resolved section: the carrier's keys, the module's resolved section inline.
  std::string yaml = "machine:\n";
  const std::string carrier_text = hybrid_design_to_yaml(carrier, "MODULE", "");
  std::istringstream lines(carrier_text);
  for (std::string line; std::getline(lines, line);) {
    if (line == "  file: MODULE") {
      const std::string inner = module->resolved_yaml;  // "machine:\n  model: ...\n"
      yaml += "    machine:\n" + indented(inner.substr(inner.find('\n') + 1), "    ");
      continue;
    }
    yaml += "  " + line + "\n";
  }
  return make_family_study_machine("hybrid", std::move(family), module->parameters,
                                   std::move(yaml));
}

std::string hybrid_study_machine_markdown() {
  return "| key | allowed | unit | default | meaning |\n"
         "| --- | --- | --- | --- | --- |\n"
         "| `model` | hybrid | – | required | the machine model |\n"
         "| `name`, `description` | a text | – | none | free text |\n"
         "| `serial` | a map | m | required | the serial axes, as in a hybrid machine file "
         "(code, axes, range, stiffness, error, mass); they stay as given |\n"
         "| `parallel.home` | [x, y, z] | m | required | the module's reference point of the "
         "follow rule |\n"
         "| `parallel.machine` | a map | – | required | the module's study section: a model with "
         "a design family and prismatic drives (linear_delta, hexaglide, tripod_3prs, "
         "tripod_3rps, lathe_16k20f3); its `parameters` are the study's |\n"
         "| `gravity` | [gx, gy, gz] | m/s² | [0, 0, -9.81] | as in a hybrid machine file |\n";
}

}  // namespace pkmopt
