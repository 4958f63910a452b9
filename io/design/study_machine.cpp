#include "io/design/study_machine.hpp"

#include <fmt/format.h>

#include <stdexcept>

#include "io/machine/model_registry.hpp"

namespace pkmopt {
namespace {

bool has_design_family(const ModelEntry& entry) {
  return static_cast<bool>(entry.design_family) || static_cast<bool>(entry.study_machine);
}

}  // namespace

std::string StudyMachine::read_actuator_constraint(const YamlValue& constraint,
                                                   const std::string& /*study_path*/,
                                                   const DesignTask& /*task*/,
                                                   std::vector<DesignConstraint>& /*constraints*/) {
  constraint.required("actuator")
      .fail(fmt::format("{{metric: NAME, max|min: VALUE}} (a {} study chooses no actuators from "
                        "a catalog; it bounds leg_force_max instead)",
                        model),
            "an actuator constraint");
}

std::unique_ptr<StudyMachine> read_study_machine(const YamlValue& machine) {
  machine.expect_map();
  const YamlValue model = machine.required("model");
  const ModelEntry* entry = find_model(model.as_string());
  if (entry == nullptr || !has_design_family(*entry)) {
    std::string names;
    for (const ModelEntry* e : registered_models())
      if (has_design_family(*e)) names += (names.empty() ? "" : ", ") + e->name;
    model.fail(fmt::format("one of {} (the models with a design family)", names), model.describe());
  }
  if (entry->study_machine) return entry->study_machine(machine);
  return read_family_study_machine(*entry, machine);
}

std::string study_machine_fields_markdown(std::string_view model) {
  const ModelEntry* entry = find_model(model);
  if (entry != nullptr && entry->study_fields_markdown) return entry->study_fields_markdown();
  if (entry != nullptr && entry->design_family)
    return family_parameters_markdown(entry->design_family(nullptr));
  throw std::invalid_argument("study_machine_fields_markdown: no design family for model '" +
                              std::string(model) + "'");
}

}  // namespace pkmopt
