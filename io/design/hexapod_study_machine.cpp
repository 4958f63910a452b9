#include "io/design/hexapod_study_machine.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <utility>

#include "io/design/actuator_catalog_file.hpp"
#include "io/format/csv.hpp"
#include "io/format/field_list.hpp"
#include "io/machine/body_fields.hpp"
#include "io/machine/hexapod_fields.hpp"
#include "io/machine/leg_shape_fields.hpp"
#include "io/machine/machine_file.hpp"
#include "io/machine/mass_fields.hpp"
#include "problems/design/hexapod_design.hpp"

namespace pkmopt {
namespace {

// The doc line of each hexapod design parameter (in the order of DesignParameterIndex).
constexpr const char* kHexapodParameterDocs[kNumDesignParameters] = {
    "radius r_b of the base joint circle",
    "radius r_p of the platform joint circle",
    "angle between the two joints of a base pair",
    "angle between the two joints of a platform pair",
    "shortest leg",
    "max_length = min_length + stroke",
    "the task region is lifted by this along base z"};

// The hexapod default design parameters (file units): the sample hexapod of docs/conventions.md.
constexpr double kHexapodParameterDefaults[kNumDesignParameters] = {0.60, 0.25, 20, 20,
                                                                    0.70, 0.45, 0.0};

FieldRule hexapod_parameter_rule(int i) {
  FieldRule rule{.unit = design_parameter_in_degrees(i) ? "deg" : "m",
                 .doc = kHexapodParameterDocs[i]};
  if (design_parameter_in_degrees(i)) {
    rule.min = 0;
    rule.max = 120;
    rule.max_exclusive = true;
  } else if (i != kHomeHeight) {
    rule.min = 0;
    rule.min_exclusive = true;
  }
  return rule;
}

// The hexapod's section: the design parameters' ranges (file units: m and degrees; min == max
// for a fixed parameter) and the template design's stiffness, joints, tool and actuator error.
struct HexapodStudySection {
  std::array<std::pair<double, double>, kNumDesignParameters> ranges{};
  HexapodDesign design;
};

class HexapodStudyMachine final : public StudyMachine {
 public:
  bool smooth_formulation() const override { return true; }
  std::string read_actuator_constraint(const YamlValue& c, const std::string& study_path,
                                       const DesignTask& task,
                                       std::vector<DesignConstraint>& constraints) override;
  const ActuatorCatalog* actuator_catalog() const override {
    return spec.actuator_catalog ? &*spec.actuator_catalog : nullptr;
  }
  bool prices_each_drive() const override { return spec.each_drive; }
  std::unique_ptr<DesignProblem> make_problem(DesignGoals goals) const override {
    HexapodDesignSpec s = spec;
    s.name = std::move(goals.name);
    s.task = std::move(goals.task);
    s.objectives = std::move(goals.objectives);
    s.constraints = std::move(goals.constraints);
    s.require_reachable = goals.require_reachable;
    s.formulation = goals.formulation;
    // The ranges in internal units, from the file-unit ones (capped by actuator constraints).
    for (int i = 0; i < kNumDesignParameters; ++i) {
      const double scale = design_parameter_in_degrees(i) ? kDegToRad : 1.0;
      const StudyParameter& p = parameters[static_cast<std::size_t>(i)];
      s.parameters[static_cast<std::size_t>(i)] = {p.min * scale, p.max * scale};
    }
    return std::make_unique<HexapodDesignProblem>(std::move(s));
  }
  std::string machine_file(const std::vector<double>& parameters) const override {
    std::array<double, kNumDesignParameters> p{};
    std::copy(parameters.begin(), parameters.end(), p.begin());
    return hexapod_design_to_yaml(hexapod_design_of(spec.machine_template, p));
  }

  HexapodDesignSpec spec;  // the template and the catalog (the ranges: `parameters`)
};

}  // namespace

template <class Fields>
void describe_fields(Fields& f, HexapodStudySection& m) {
  f.note("model", kHexapodModel, "", "required", "the machine model");
  f.section("parameters", {}, [&](auto& g) {
    for (int i = 0; i < kNumDesignParameters; ++i) {
      auto& [lo, hi] = m.ranges[static_cast<std::size_t>(i)];
      FieldBounds bounds{lo, hi};
      g.field(design_parameter_name(i), bounds, hexapod_parameter_rule(i));
    }
  });
  f.section("legs", {.required = true}, [&](auto& g) {
    describe_leg_stiffness(g, m.design.stiffness);
    describe_leg_shape(g, m.design.leg_shape);
  });
  describe_min_clearance(f, m.design.min_clearance);
  describe_machine_bodies(f, m.design.bodies);
  f.section("joints", {}, [&](auto& g) { describe_hexapod_joints(g, m.design.joints); });
  f.section("tool", {}, [&](auto& g) { describe_hexapod_tool(g, m.design.tcp); });
  describe_actuator_error(f, m.design.actuator_error);
  MassFields masses{m.design.masses, kTelescopicBodies};
  describe_mass_section(f, masses);
}

HexapodStudySection default_hexapod_study_machine() {
  HexapodStudySection m;
  for (int i = 0; i < kNumDesignParameters; ++i)
    m.ranges[static_cast<std::size_t>(i)] = {kHexapodParameterDefaults[i],
                                             kHexapodParameterDefaults[i]};
  m.design = HexapodDesignSpec{}.machine_template;
  m.design.stiffness = LegStiffness{};
  m.design.joints = HexapodJointLimits{};
  m.design.tcp.setZero();
  return m;
}

std::string hexapod_study_machine_markdown() {
  HexapodStudySection m = default_hexapod_study_machine();
  FieldDocs docs;
  describe_fields(docs, m);
  return docs.markdown();
}

std::unique_ptr<StudyMachine> read_hexapod_study_machine(const YamlValue& machine) {
  HexapodStudySection m = default_hexapod_study_machine();
  read_fields(machine, m);
  const YamlValue model = machine.required("model");
  if (model.as_string() != kHexapodModel)
    model.fail(fmt::format("'{}'", kHexapodModel), model.describe());
  check_leg_stiffness(machine.required("legs"), m.design.stiffness);
  normalize_joint_axes(machine, m.design.joints);
  check_mass_fields(machine, m.design.masses);
  try {
    check_leg_shape(m.design.leg_shape, m.design.min_clearance);
  } catch (const std::invalid_argument& e) {
    machine.required("legs").fail(e.what());
  }
  if (machine.has("bodies")) {
    try {
      check_hexapod_bodies(m.design.leg_shape, m.design.bodies);
    } catch (const std::invalid_argument& e) {
      machine.required("bodies").fail(e.what());
    }
  }
  auto study = std::make_unique<HexapodStudyMachine>();
  study->model = kHexapodModel;
  for (int i = 0; i < kNumDesignParameters; ++i) {
    const auto [lo, hi] = m.ranges[static_cast<std::size_t>(i)];
    study->parameters.push_back({std::string(design_parameter_name(i)),
                                 design_parameter_in_degrees(i) ? "deg" : "m", lo, hi});
  }
  study->spec.machine_template = m.design;
  FieldWriter writer;
  describe_fields(writer, m);
  study->resolved_yaml =
      "machine:\n  model: " + std::string(kHexapodModel) + "\n" + writer.block(2);
  return study;
}

// {actuator: NAME, catalog: FILE}: the legs are that catalog entry. Adds leg_force_max <= its
// force rating and caps the stroke parameter at its stroke.
// {actuator: cheapest, catalog: FILE}: the optimiser chooses, for every design, the cheapest
// entry that carries the legs (HexapodDesignSpec::actuator_catalog). Adds actuator_overload <= 0
// and caps the stroke parameter at the longest entry's stroke.
// Returns the resolved YAML line (catalog path made absolute so that study.resolved.yaml loads
// from anywhere).
std::string HexapodStudyMachine::read_actuator_constraint(
    const YamlValue& c, const std::string& study_path, const DesignTask& task,
    std::vector<DesignConstraint>& constraints) {
  const ActuatorConstraintFile file = read_actuator_constraint_file(c, study_path);
  if (!file.drives.empty())
    c.required("drives").fail("no 'drives' (a hexapod's six legs are alike: the entry is theirs)",
                              "a list of drives");
  const std::filesystem::path catalog_path = file.catalog_path;
  const ActuatorCatalog& catalog = file.catalog;
  const YamlValue name_value = c.required("actuator");
  const std::string name = file.keys.actuator;
  int stroke = -1;
  for (int i = 0; i < kNumDesignParameters; ++i) {
    if (design_parameter_name(i) == "stroke") stroke = i;
  }
  double& lo = parameters[static_cast<std::size_t>(stroke)].min;
  double& hi = parameters[static_cast<std::size_t>(stroke)].max;
  if (file.cheapest()) {
    if (spec.actuator_catalog)
      name_value.fail("one {actuator: cheapest, catalog: FILE} constraint per study",
                      "a second one");
    if (catalog.entries.empty())
      c.required("catalog").fail(
          "a catalog with linear entries for the hexapod's legs",
          fmt::format("catalog '{}' with rotary entries only", catalog.name));
    double longest = 0.0;
    for (const ActuatorEntry& e : catalog.entries) longest = std::max(longest, e.stroke);
    if (lo > longest)
      name_value.fail(fmt::format("a catalog with an entry of stroke at least "
                                  "machine.parameters.stroke ({} m)",
                                  format_number(lo)),
                      fmt::format("catalog '{}' whose longest stroke is {} m", catalog.name,
                                  format_number(longest)));
    hi = std::min(hi, longest);
    spec.actuator_catalog = catalog;
    spec.each_drive = file.keys.each_drive;
    const DesignMetric overload =
        spec.each_drive ? DesignMetric::drive_overload : DesignMetric::actuator_overload;
    constraints.push_back({overload, Relation::less_equal, 0.0});
    return fmt::format("  - {{actuator: {}, catalog: {}{}}}  # {} <= 0, stroke <= {} m\n",
                       kCheapestActuator, nlohmann::json(catalog_path.string()).dump(),
                       spec.each_drive ? ", each_drive: true" : "", design_metric_name(overload),
                       format_number(hi));
  }
  const ActuatorEntry* entry = &catalog.entries[static_cast<std::size_t>(file.entry)];
  constraints.push_back({DesignMetric::leg_force_max, Relation::less_equal, entry->max_force});
  const double peak = entry->peak_force.value_or(entry->max_force);
  const bool rapid = task.acceleration_max > 0.0;  // the rapid moves go against the peak
  if (rapid)
    constraints.push_back({DesignMetric::actuator_force_dynamic_max, Relation::less_equal, peak});
  if (lo > entry->stroke) {
    name_value.fail(fmt::format("an actuator with a stroke of at least machine.parameters.stroke "
                                "({} m)",
                                lo),
                    fmt::format("'{}' with {} m", name, entry->stroke));
  }
  hi = std::min(hi, entry->stroke);
  return fmt::format(
      "  - {{actuator: {}, catalog: {}}}  # leg_force_max <= {} N, {}stroke <= {} m\n",
      nlohmann::json(name).dump(), nlohmann::json(catalog_path.string()).dump(),
      format_number(entry->max_force),
      rapid ? "actuator_force_dynamic_max <= " + format_number(peak) + " N, " : "",
      format_number(entry->stroke));
}

}  // namespace pkmopt
