#include "studies/design_study.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>
#include <stdexcept>

#include "io/design/actuator_catalog_file.hpp"
#include "io/design/hexapod_study_machine.hpp"
#include "io/design/task_wrench_file.hpp"
#include "io/format/csv.hpp"
#include "io/format/input_error.hpp"
#include "io/format/output_file.hpp"
#include "optimizer/indicators.hpp"
#include "pkmopt/version.hpp"
#include "studies/design_study_sections.hpp"

namespace pkmopt {

using namespace design_study_detail;

bool is_design_study_file(const std::string& path) {
  const YamlValue root = YamlValue::load_file(path);
  return root.is_map() && root.has("machine");
}

namespace {

// nlopt algorithms that need no gradient (optimizer/nlopt_solver.hpp), by either name.
bool derivative_free_nlopt(std::string algorithm) {
  if (!algorithm.starts_with("nlopt:")) return false;
  algorithm = algorithm.substr(6);
  std::transform(algorithm.begin(), algorithm.end(), algorithm.begin(),
                 [](unsigned char c) { return static_cast<char>(std::toupper(c)); });
  if (algorithm.starts_with("GN_") || algorithm.starts_with("LN_")) return true;
  for (const char* name :
       {"DIRECT_L", "DIRECT", "CRS2", "ESCH", "ISRES", "COBYLA", "BOBYQA", "NELDERMEAD", "SBPLX"})
    if (algorithm == name) return true;
  return false;
}

}  // namespace

DesignStudy load_design_study(const std::string& path) {
  return load_design_study(YamlValue::load_file(path));
}

namespace {

// Where the actuator metrics (actuator_cost, actuator_overload, drive_cost, drive_overload) are
// used: they need the constraint {actuator: cheapest, catalog: FILE} (the drive_ ones with
// each_drive: true, the others without).
struct ActuatorMetricValue {
  YamlValue value;  // the metric's name in the file
  DesignMetric metric;
};
using ActuatorMetricUse = std::vector<ActuatorMetricValue>;

// `objectives:` into goals.objectives; appends its resolved YAML.
void read_objectives(const YamlValue& root, DesignGoals& goals,
                     ActuatorMetricUse& actuator_metric_use, std::string& yaml) {
  std::vector<DesignObjective>& objectives_list = goals.objectives;
  const YamlValue objectives = root.required("objectives");
  const std::vector<YamlValue> objective_list = objectives.elements();
  if (objective_list.empty()) objectives.fail("a list of at least one objective", "an empty list");
  yaml += "objectives:\n";
  for (const YamlValue& o : objective_list) {
    o.expect_map();
    ObjectiveEntry entry;
    read_fields(o, entry);
    if (o.keys().size() != 1) o.fail("one of minimize: METRIC or maximize: METRIC", o.describe());
    const bool maximize = entry.maximize >= 0;
    const YamlValue metric_value = o.required(maximize ? "maximize" : "minimize");
    objectives_list.push_back(
        {static_cast<DesignMetric>(maximize ? entry.maximize : entry.minimize),
         maximize ? Sense::maximize : Sense::minimize});
    if (is_actuator_metric(objectives_list.back().metric))
      actuator_metric_use.push_back({metric_value, objectives_list.back().metric});
    yaml += "  - " + fields_flow_map(entry) + "\n";
  }
}

// `constraints:` into goals (the model reads actuator constraints); appends its resolved YAML.
void read_constraints(const YamlValue& root, const std::string& path, StudyMachine& machine,
                      DesignGoals& goals, ActuatorMetricUse& actuator_metric_use,
                      std::string& yaml) {
  std::vector<DesignConstraint>& limits = goals.constraints;
  const DesignTask& task = goals.task;
  bool require_reachable = false;
  std::string constraint_yaml;
  if (auto constraints = root.optional("constraints")) {
    for (const YamlValue& c : constraints->elements()) {
      if (c.is_scalar()) {
        if (c.as_string() == "task_singularity_free") {
          // The task region proved free of parallel singularities: the share must be 1.
          limits.push_back({DesignMetric::task_singularity_free, Relation::greater_equal, 1.0});
          constraint_yaml += "  - {metric: task_singularity_free, min: 1}\n";
          continue;
        }
        if (c.as_string() != "task_reachable")
          c.fail(
              "task_reachable, task_singularity_free, {metric: NAME, max|min: VALUE} or "
              "{actuator: NAME, catalog: FILE}",
              c.describe());
        require_reachable = true;
        continue;
      }
      if (c.has("actuator")) {
        constraint_yaml += machine.read_actuator_constraint(c, path, task, limits);
        continue;
      }
      ConstraintEntry entry;
      read_fields(c, entry);
      const auto metric = static_cast<DesignMetric>(entry.metric);
      if (is_actuator_metric(metric)) actuator_metric_use.push_back({c.required("metric"), metric});
      if (entry.max.has_value() == entry.min.has_value())
        c.fail("exactly one of max and min", c.describe());
      const bool upper = entry.max.has_value();
      limits.push_back({metric, upper ? Relation::less_equal : Relation::greater_equal,
                        upper ? *entry.max : *entry.min});
      constraint_yaml += "  - " + fields_flow_map(entry) + "\n";
    }
  }
  if (!actuator_metric_use.empty() && machine.actuator_catalog() == nullptr)
    actuator_metric_use.front().value.fail(
        fmt::format("a metric of this {} study (actuator_cost and actuator_overload need a "
                    "constraint {{actuator: cheapest, catalog: FILE}}, drive_cost and "
                    "drive_overload one with each_drive: true)",
                    machine.model),
        actuator_metric_use.front().value.describe());
  for (const auto& [use, metric] : actuator_metric_use) {
    const bool drive = is_drive_metric(metric);
    if (drive && !machine.prices_each_drive())
      use.fail(
          "a metric of this study (drive_cost and drive_overload need each_drive: true in "
          "the {actuator: cheapest, catalog: FILE} constraint)",
          use.describe());
    if (!drive && machine.prices_each_drive())
      use.fail(
          "a metric of this study (with each_drive: true the catalog prices every drive: "
          "drive_cost, drive_overload)",
          use.describe());
  }
  goals.require_reachable = require_reachable;
  if (require_reachable) constraint_yaml = "  - task_reachable\n" + constraint_yaml;
  yaml += constraint_yaml.empty() ? "constraints: []\n" : "constraints:\n" + constraint_yaml;
}

// The formulation the algorithm asks for, refused when the model has no smooth one.
void read_formulation(const YamlValue& optimizer, const StudyMachine& machine, DesignGoals& goals) {
  optimizer.expect_map();
  const YamlValue algorithm_value = optimizer.required("algorithm");
  const std::string algorithm = algorithm_value.as_string();
  const bool evolutionary = algorithm == "nsga2" || algorithm == "nsga3" || algorithm == "moead";
  goals.formulation = evolutionary ? DesignFormulation::aggregate : DesignFormulation::smooth;
  if (!machine.smooth_formulation()) {
    if (!evolutionary && !derivative_free_nlopt(algorithm))
      algorithm_value.fail(
          fmt::format("nsga2, nsga3 or moead (or a derivative-free nlopt:COBYLA, nlopt:ISRES, "
                      "nlopt:BOBYQA, ... "
                      "for one objective): a {} design study measures worst cases over the task "
                      "and has no gradients",
                      machine.model),
          "'" + algorithm + "'");
    goals.formulation = DesignFormulation::aggregate;
  }
}

}  // namespace

DesignStudy load_design_study(const YamlValue& root) {
  root.check_keys({"study", "description", "machine", "task", "objectives", "constraints",
                   "optimizer", "output"});
  return load_design_study_part(root, root.required("study").as_string(), root.required("machine"),
                                {});
}

DesignStudy load_design_study_part(const YamlValue& root, const std::string& name,
                                   const YamlValue& machine_section,
                                   const std::array<double, 3>& placement) {
  const std::string& path = root.file();
  DesignStudy study;
  study.name = name;
  if (auto v = root.optional("description")) study.description = v->as_string();
  std::string yaml = fmt::format("# {} resolved: every default filled in (pkmopt {})\n",
                                 nlohmann::json(study.name).dump(), kVersion);
  yaml += "study: " + nlohmann::json(study.name).dump() + "\n";
  yaml += "description: " + nlohmann::json(study.description).dump() + "\n";
  std::unique_ptr<StudyMachine> machine = read_study_machine(machine_section);
  study.model = machine->model;
  yaml += machine->resolved_yaml;
  DesignGoals goals;
  goals.name = study.name;
  DesignTask& task = goals.task;
  const YamlValue task_section = root.required("task");
  read_task(task_section, task, study, yaml, placement);
  if (machine->translational && (study.task_tilt_deg > 0.0 || study.task_yaw_deg > 0.0))
    task_section.required("orientations")
        .fail(fmt::format("tilt_deg: 0 and yaw_deg: 0 (the {} platform keeps its orientation)",
                          study.model),
              fmt::format("tilt_deg {}, yaw_deg {}", format_number(study.task_tilt_deg),
                          format_number(study.task_yaw_deg)));

  ActuatorMetricUse actuator_metric_use;
  read_objectives(root, goals, actuator_metric_use, yaml);
  read_constraints(root, path, *machine, goals, actuator_metric_use, yaml);
  const YamlValue optimizer = root.required("optimizer");
  read_formulation(optimizer, *machine, goals);
  try {
    study.problem = machine->make_problem(std::move(goals));
  } catch (const std::invalid_argument& error) {
    root.fail(error.what());
  }
  study.parameters = machine->parameters;
  study.machine = std::move(machine);
  ObjectiveNaming naming;
  for (const DesignObjective& o : study.objectives()) {
    naming.names.emplace_back(design_metric_name(o.metric));
    naming.maximize.push_back(o.sense == Sense::maximize);
  }
  study.optimizer = read_optimizer_section(optimizer, study.optimization_problem(), naming);
  OutputSection output;
  if (auto section = root.optional("output")) read_fields(*section, output);
  study.write_designs = output.designs;
  study.front_size = static_cast<std::size_t>(output.front_size);
  yaml += "optimizer: " + optimizer_section_yaml(study.optimizer) + "\n";
  yaml += "output: " + fields_flow_map(output) + "\n";
  study.resolved_yaml = yaml;
  return study;
}

std::string design_study_fields_markdown(std::string_view section) {
  if (section == "task.orientations") return fields_markdown(TaskOrientationsSection{});
  if (section == "task.workspace") return fields_markdown(TaskWorkspaceSection{});
  if (section == "output") return fields_markdown(OutputSection{});
  if (section == "task.region box") return fields_markdown(BoxRegionSection{});
  if (section == "task.region cylinder") return fields_markdown(CylinderRegionSection{});
  if (section == "objectives[]") return fields_markdown(ObjectiveEntry{});
  if (section == "constraints[]") return fields_markdown(ConstraintEntry{});
  if (section == "constraints[] actuator") return fields_markdown(ActuatorConstraintEntry{});
  if (section.starts_with("machine.parameters "))
    return study_machine_fields_markdown(section.substr(19));
  if (section.starts_with("machine ")) return study_machine_fields_markdown(section.substr(8));
  throw std::invalid_argument("design_study_fields_markdown: unknown section '" +
                              std::string(section) + "'");
}

}  // namespace pkmopt
