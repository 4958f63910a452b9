// The study section of a design-family model (io/design/study_machine.hpp): `parameters:` takes the
// family's parameters, every other key of the model's machine file may follow except the keys
// the parameters set. The template design is read by the model's machine-file reader from the
// section with the parameter keys filled in from the defaults, so its messages point into the
// study file.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>
#include <stdexcept>

#include "io/design/actuator_catalog_file.hpp"
#include "io/design/study_machine.hpp"
#include "io/format/csv.hpp"
#include "io/format/field_list.hpp"
#include "io/machine/model_registry.hpp"

namespace pkmopt {
namespace {

// The rule of a family parameter; `expected` holds the message text the rule points to.
FieldRule family_parameter_rule(const FamilyParameter& p, std::string& expected) {
  FieldRule rule{.unit = p.unit, .doc = p.doc};
  if (!p.may_be_negative) {
    rule.min = 0;
    rule.min_exclusive = !p.may_be_zero;
  }
  if (std::isfinite(p.max_abs)) {
    if (p.may_be_negative) rule.min = -p.max_abs;
    rule.max = p.max_abs;
    expected = p.may_be_negative
                   ? fmt::format("values within [-{0}, {0}] {1}", format_number(p.max_abs), p.unit)
                   : fmt::format("values within [0, {}] {}", format_number(p.max_abs), p.unit);
    rule.expected = expected;
  }
  return rule;
}

template <class Fields>
void describe_family_parameters(Fields& g, const DesignFamily& family,
                                std::vector<StudyParameter>& parameters) {
  for (std::size_t i = 0; i < family.parameters.size(); ++i) {
    std::string expected;
    FieldBounds bounds{parameters[i].min, parameters[i].max};
    g.field(family.parameters[i].name, bounds,
            family_parameter_rule(family.parameters[i], expected));
  }
}

std::vector<StudyParameter> default_study_parameters(const DesignFamily& family) {
  std::vector<StudyParameter> parameters;
  for (const FamilyParameter& p : family.parameters)
    parameters.push_back({p.name, p.unit, p.default_value, p.default_value});
  return parameters;
}

class FamilyStudyMachine final : public StudyMachine {
 public:
  std::unique_ptr<DesignProblem> make_problem(DesignGoals goals) const override {
    MachineDesignSpec spec;
    spec.name = std::move(goals.name);
    spec.family = family;
    // The ranges in internal units, from the file-unit ones the section was read into.
    for (std::size_t i = 0; i < family.parameters.size(); ++i)
      spec.parameters.push_back({family.parameters[i].to_internal(parameters[i].min),
                                 family.parameters[i].to_internal(parameters[i].max)});
    spec.task = std::move(goals.task);
    spec.objectives = std::move(goals.objectives);
    spec.constraints = std::move(goals.constraints);
    spec.require_reachable = goals.require_reachable;
    spec.actuator_catalog = catalog;
    spec.actuator_drives = drives;
    spec.each_drive = each_drive;
    return std::make_unique<MachineDesignProblem>(std::move(spec));
  }
  const ActuatorCatalog* actuator_catalog() const override { return catalog ? &*catalog : nullptr; }
  bool prices_each_drive() const override { return each_drive; }

  // {actuator: cheapest, catalog: FILE}: every design's drives are the cheapest entry that
  // carries them; {actuator: NAME, catalog: FILE}: they are that entry. Either adds
  // actuator_overload <= 0 (the entry's force rating against leg_force_max, its stroke against
  // the design's longest actuator stroke).
  std::string read_actuator_constraint(const YamlValue& c, const std::string& study_path,
                                       const DesignTask& /*task*/,
                                       std::vector<DesignConstraint>& constraints) override {
    const ActuatorConstraintFile file = read_actuator_constraint_file(c, study_path);
    const YamlValue name_value = c.required("actuator");
    const std::string& name = file.keys.actuator;
    if (catalog) name_value.fail("one {actuator, catalog} constraint per study", "a second one");
    const std::unique_ptr<Machine> machine = family.build(family.default_parameters());
    for (const int i : file.drives)
      if (i >= machine->num_actuators())
        c.required("drives").fail(
            fmt::format("actuator numbers 1..{} ({} drives)", machine->num_actuators(), model),
            std::to_string(i + 1));
    drives = file.drives;
    if (file.keys.each_drive) {
      for (int i = 0; i < machine->num_actuators(); ++i) {
        const bool revolute = machine->revolute_actuator(i);
        if (revolute ? file.catalog.rotary_entries.empty() : file.catalog.entries.empty())
          c.required("catalog").fail(fmt::format("a catalog with {} entries ({} drive {} is {})",
                                                 revolute ? "rotary" : "linear", model, i + 1,
                                                 revolute ? "revolute" : "linear"),
                                     fmt::format("catalog '{}' without", file.catalog.name));
      }
      catalog = file.catalog;
      each_drive = true;
      constraints.push_back({DesignMetric::drive_overload, Relation::less_equal, 0.0});
      return fmt::format(
          "  - {{actuator: {}, catalog: {}, each_drive: true}}  # drive_overload <= 0\n",
          nlohmann::json(name).dump(), nlohmann::json(file.catalog_path).dump());
    }
    if (machine->any_revolute_actuator())
      name_value.fail(fmt::format("a model with linear drives (the catalog holds linear drives; "
                                  "bound leg_force_max instead)"),
                      fmt::format("{} with revolute drives", model));
    // A named entry is a one-entry catalog: the same choice, the same overload.
    catalog = file.cheapest()
                  ? file.catalog
                  : ActuatorCatalog{file.catalog.name,
                                    {file.catalog.entries[static_cast<std::size_t>(file.entry)]},
                                    {},
                                    {}};
    constraints.push_back({DesignMetric::actuator_overload, Relation::less_equal, 0.0});
    std::string listed;
    for (const int i : drives) listed += (listed.empty() ? "" : ", ") + std::to_string(i + 1);
    return fmt::format("  - {{actuator: {}, catalog: {}{}}}  # actuator_overload <= 0\n",
                       nlohmann::json(name).dump(), nlohmann::json(file.catalog_path).dump(),
                       drives.empty() ? "" : ", drives: [" + listed + "]");
  }
  std::string machine_file(const std::vector<double>& p) const override {
    return family.machine_file(p);
  }
  const DesignFamily* design_family() const override { return &family; }

  DesignFamily family;
  std::optional<ActuatorCatalog> catalog;  // from an {actuator, catalog} constraint
  std::vector<int> drives;                 // its drives (0-based), empty: every drive
  bool each_drive = false;                 // every drive priced (drive_cost, drive_overload)
};

}  // namespace

std::unique_ptr<StudyMachine> make_family_study_machine(std::string model, DesignFamily family,
                                                        std::vector<StudyParameter> parameters,
                                                        std::string resolved_yaml) {
  auto study = std::make_unique<FamilyStudyMachine>();
  study->model = std::move(model);
  study->translational = family.translational;
  study->family = std::move(family);
  study->parameters = std::move(parameters);
  study->resolved_yaml = std::move(resolved_yaml);
  return study;
}

std::string family_parameters_markdown(const DesignFamily& family) {
  std::vector<StudyParameter> parameters = default_study_parameters(family);
  FieldDocs docs;
  describe_family_parameters(docs, family, parameters);
  return docs.markdown();
}

std::unique_ptr<StudyMachine> read_family_study_machine(const ModelEntry& entry,
                                                        const YamlValue& machine) {
  const std::string& model = entry.name;
  const DesignFamily defaults = entry.design_family(nullptr);
  for (const std::string& key : defaults.parameter_keys)
    if (machine.has(key))
      machine.required(key).fail(fmt::format(
          "no '{}' in the machine section of a {} design study: its parameters set it (give "
          "them under machine.parameters)",
          key, model));
  const YAML::Node default_file = YAML::Load(defaults.machine_file(defaults.default_parameters()));
  YAML::Node merged(YAML::NodeType::Map);
  for (const auto& entry_node : machine.node())
    if (entry_node.first.as<std::string>() != "parameters")
      merged[entry_node.first] = entry_node.second;
  for (const std::string& key : defaults.parameter_keys)
    if (default_file[key]) merged[key] = default_file[key];
  YamlValue template_section(merged, std::make_shared<const std::string>(machine.file()),
                             machine.path());
  template_section.set_location(machine.line(), machine.column());

  auto study = std::make_unique<FamilyStudyMachine>();
  study->model = model;
  study->family = entry.design_family(&template_section);
  const DesignFamily& family = study->family;
  study->translational = family.translational;
  study->parameters = default_study_parameters(family);
  if (auto section = machine.optional("parameters")) {
    FieldReader::read_section(
        *section, [&](auto& g) { describe_family_parameters(g, family, study->parameters); });
  }
  FieldWriter writer;
  writer.section("parameters", {},
                 [&](auto& g) { describe_family_parameters(g, family, study->parameters); });
  std::string yaml = "machine:\n  model: " + model + "\n" + writer.block(2);
  // The template's own keys: the machine file of the defaults without the parameter keys.
  std::istringstream lines(family.machine_file(family.default_parameters()));
  for (std::string line; std::getline(lines, line);) {
    const std::string key = line.substr(0, line.find(':'));
    if (key == "model" || std::find(family.parameter_keys.begin(), family.parameter_keys.end(),
                                    key) != family.parameter_keys.end())
      continue;
    yaml += "  " + line + "\n";
  }
  study->resolved_yaml = std::move(yaml);
  return study;
}

}  // namespace pkmopt
