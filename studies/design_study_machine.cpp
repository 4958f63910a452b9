#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>
#include <stdexcept>

#include "io/actuator_catalog_file.hpp"
#include "io/body_fields.hpp"
#include "io/csv.hpp"
#include "io/field_list.hpp"
#include "io/hexapod_fields.hpp"
#include "io/input_error.hpp"
#include "io/leg_shape_fields.hpp"
#include "io/machine_file.hpp"
#include "io/machine_file_lathe.hpp"
#include "io/machine_file_leg_chain.hpp"
#include "io/machine_file_writer.hpp"
#include "io/mass_fields.hpp"
#include "io/output_file.hpp"
#include "io/task_wrench_file.hpp"
#include "optimizer/indicators.hpp"
#include "pkmopt/version.hpp"
#include "problems/lathe_design.hpp"
#include "studies/design_study_sections.hpp"

namespace pkmopt::design_study_detail {

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

}  // namespace

template <class Fields>
void describe_fields(Fields& f, HexapodStudyMachine& m) {
  f.note("model", "hexapod", "", "required", "the machine model");
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

HexapodStudyMachine default_hexapod_study_machine() {
  HexapodStudyMachine m;
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
  HexapodStudyMachine m = default_hexapod_study_machine();
  FieldDocs docs;
  describe_fields(docs, m);
  return docs.markdown();
}

void read_machine(const YamlValue& machine, HexapodDesignSpec& spec, DesignStudy& study,
                  std::string& yaml) {
  HexapodStudyMachine m = default_hexapod_study_machine();
  read_fields(machine, m);
  const YamlValue model = machine.required("model");
  if (model.as_string() != "hexapod") model.fail("'hexapod'", model.describe());
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
  study.parameter_ranges = m.ranges;
  for (int i = 0; i < kNumDesignParameters; ++i) {
    const double scale = design_parameter_in_degrees(i) ? kDegToRad : 1.0;
    const auto [lo, hi] = m.ranges[static_cast<std::size_t>(i)];
    spec.parameters[static_cast<std::size_t>(i)] = {lo * scale, hi * scale};
  }
  spec.machine_template = m.design;
  FieldWriter writer;
  describe_fields(writer, m);
  yaml += "machine:\n  model: hexapod\n" + writer.block(2);
}

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
void describe_family_parameters(Fields& g, const DesignFamily& family, DesignStudy& study) {
  for (std::size_t i = 0; i < family.parameters.size(); ++i) {
    std::string expected;
    FieldBounds bounds{study.parameters[i].min, study.parameters[i].max};
    g.field(family.parameters[i].name, bounds,
            family_parameter_rule(family.parameters[i], expected));
  }
}

std::string family_parameters_markdown(const std::string& model) {
  const DesignFamily family = *leg_chain_family(model, nullptr);
  DesignStudy study;
  for (const FamilyParameter& p : family.parameters)
    study.parameters.push_back({p.name, p.unit, p.default_value, p.default_value});
  FieldDocs docs;
  describe_family_parameters(docs, family, study);
  return docs.markdown();
}

// The design family of a leg-chain model built around a template design (nullopt: not one).
std::optional<DesignFamily> leg_chain_family(const std::string& model, const YamlValue* machine) {
  if (model == "delta") return delta_family(machine ? read_delta_design(*machine) : DeltaDesign{});
  if (model == "linear_delta")
    return linear_delta_family(machine ? read_linear_delta_design(*machine) : LinearDeltaDesign{});
  if (model == "hexaglide")
    return hexaglide_family(machine ? read_hexaglide_design(*machine) : HexaglideDesign{});
  if (model == "tripod_3prs")
    return tripod_3prs_family(machine ? read_tripod_3prs_design(*machine) : Tripod3PrsDesign{});
  if (model == "lathe_16k20f3")
    return lathe_16k20f3_family(machine ? read_lathe_16k20f3_design(*machine)
                                        : Lathe16k20f3Design{});
  return std::nullopt;
}

// The machine section of a leg-chain study: `parameters:` (the family's), and every other key
// of the model's machine file except those the parameters set. The template design is read by
// the machine-file reader from the section with the parameter keys filled in from the defaults
// (so its messages point into the study file).
void read_leg_chain_machine(const YamlValue& machine, const std::string& model,
                            MachineDesignSpec& spec, DesignStudy& study, std::string& yaml) {
  const DesignFamily defaults = *leg_chain_family(model, nullptr);
  for (const std::string& key : defaults.parameter_keys)
    if (machine.has(key))
      machine.required(key).fail(fmt::format(
          "no '{}' in the machine section of a {} design study: its parameters set it (give "
          "them under machine.parameters)",
          key, model));
  const YAML::Node default_file =
      YAML::Load(family_machine_file(defaults.design(defaults.default_parameters())));
  YAML::Node merged(YAML::NodeType::Map);
  for (const auto& entry : machine.node())
    if (entry.first.as<std::string>() != "parameters") merged[entry.first] = entry.second;
  for (const std::string& key : defaults.parameter_keys)
    if (default_file[key]) merged[key] = default_file[key];
  YamlValue template_section(merged, std::make_shared<const std::string>(machine.file()),
                             machine.path());
  template_section.set_location(machine.line(), machine.column());
  spec.family = *leg_chain_family(model, &template_section);
  const DesignFamily& family = spec.family;
  spec.parameters = default_ranges(family);
  for (const FamilyParameter& p : family.parameters)
    study.parameters.push_back({p.name, p.unit, p.default_value, p.default_value});
  if (auto section = machine.optional("parameters")) {
    FieldReader::read_section(*section,
                              [&](auto& g) { describe_family_parameters(g, family, study); });
    for (std::size_t i = 0; i < family.parameters.size(); ++i)
      if (section->has(family.parameters[i].name))
        spec.parameters[i] = {family.parameters[i].to_internal(study.parameters[i].min),
                              family.parameters[i].to_internal(study.parameters[i].max)};
  }
  FieldWriter writer;
  writer.section("parameters", {}, [&](auto& g) { describe_family_parameters(g, family, study); });
  yaml += "machine:\n  model: " + model + "\n" + writer.block(2);
  // The template's own keys: the machine file of the defaults without the parameter keys.
  std::istringstream lines(family_machine_file(family.design(family.default_parameters())));
  for (std::string line; std::getline(lines, line);) {
    const std::string key = line.substr(0, line.find(':'));
    if (key == "model" || std::find(family.parameter_keys.begin(), family.parameter_keys.end(),
                                    key) != family.parameter_keys.end())
      continue;
    yaml += "  " + line + "\n";
  }
}

}  // namespace pkmopt::design_study_detail
