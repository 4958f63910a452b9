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
#include "io/csv.hpp"
#include "io/input_error.hpp"
#include "io/machine_file.hpp"
#include "io/machine_file_lathe.hpp"
#include "io/machine_file_leg_chain.hpp"
#include "io/machine_file_writer.hpp"
#include "io/output_file.hpp"
#include "io/task_wrench_file.hpp"
#include "optimizer/indicators.hpp"
#include "pkmopt/version.hpp"
#include "problems/lathe_design.hpp"
#include "studies/design_study_sections.hpp"

namespace pkmopt::design_study_detail {

int positive_int(const YamlValue& v) {
  const long long value = v.as_int();
  if (value < 1 || value > 1000) v.fail("an integer in 1..1000", v.describe());
  return static_cast<int>(value);
}

double angle_deg(const YamlValue& v, double lo, double hi) {
  const double value = v.as_double();
  if (value < lo || value > hi)
    v.fail(fmt::format("an angle in [{}, {}] degrees", lo, hi), v.describe());
  return deg_to_rad(value);
}

void read_parameters(const YamlValue& section, HexapodDesignSpec& spec, DesignStudy& study) {
  std::vector<std::string> names;
  for (int i = 0; i < kNumDesignParameters; ++i) names.emplace_back(design_parameter_name(i));
  section.check_keys(names);
  for (int i = 0; i < kNumDesignParameters; ++i) {
    const auto v = section.optional(design_parameter_name(i));
    if (!v) continue;
    const double scale = design_parameter_in_degrees(i) ? kDegToRad : 1.0;
    ParameterRange range;
    if (v->is_map()) {
      v->check_keys({"min", "max"});
      study.parameter_ranges[i] = {v->required("min").as_double(), v->required("max").as_double()};
      range.lower = study.parameter_ranges[i].first * scale;
      range.upper = study.parameter_ranges[i].second * scale;
      if (!(range.lower < range.upper))
        v->required("max").fail("max > min", v->required("max").describe());
    } else {
      study.parameter_ranges[i] = {v->as_double(), v->as_double()};
      range.lower = range.upper = study.parameter_ranges[i].first * scale;
    }
    const bool may_be_negative = i == kHomeHeight;
    const bool may_be_zero = design_parameter_in_degrees(i);
    if (!may_be_negative && (range.lower < 0.0 || (!may_be_zero && range.lower == 0.0)))
      v->fail(may_be_zero ? "values >= 0" : "values > 0", v->describe());
    if (design_parameter_in_degrees(i) && range.upper >= deg_to_rad(120))
      v->fail("separations below 120 degrees", v->describe());
    spec.parameters[i] = range;
  }
}

std::string triple(const double* v, int n) {
  std::string text;
  for (int i = 0; i < n; ++i) text += (i ? ", " : "") + format_number(v[i]);
  return "[" + text + "]";
}

// Reads an angle in degrees (file value kept for the resolved study) and returns radians.
double angle_deg_kept(const YamlValue& v, double lo, double hi, double& file_value) {
  const double rad = angle_deg(v, lo, hi);
  file_value = v.as_double();
  return rad;
}

void read_machine(const YamlValue& machine, HexapodDesignSpec& spec, DesignStudy& study,
                  std::string& yaml) {
  machine.check_keys({"model", "parameters", "legs", "joints", "tool", "actuator_error"});
  const YamlValue model = machine.required("model");
  if (model.as_string() != "hexapod") model.fail("'hexapod'", model.describe());
  const std::array<double, kNumDesignParameters> defaults = {0.60, 0.25, 20, 20, 0.70, 0.45, 0.0};
  for (int i = 0; i < kNumDesignParameters; ++i) {
    study.parameter_ranges[i] = {defaults[i], defaults[i]};
    const double scale = design_parameter_in_degrees(i) ? kDegToRad : 1.0;
    spec.parameters[i] = {defaults[i] * scale, defaults[i] * scale};
  }
  if (auto v = machine.optional("parameters")) read_parameters(*v, spec, study);
  HexapodDesign& d = spec.machine_template;
  const YamlValue legs = machine.required("legs");
  legs.check_keys({"axial_stiffness", "E", "area", "actuator_stiffness"});
  d.stiffness = LegStiffness{};
  if (auto v = legs.optional("axial_stiffness")) {
    if (legs.has("E") || legs.has("area"))
      v->fail("either axial_stiffness or E and area, not both");
    d.stiffness.axial_stiffness = v->as_positive();
  } else {
    d.stiffness.E = legs.required("E").as_positive();
    d.stiffness.area = legs.required("area").as_positive();
  }
  if (auto v = legs.optional("actuator_stiffness"))
    d.stiffness.actuator_stiffness = v->as_positive();
  d.joints = HexapodJointLimits{};
  double base_deg = 0.0, platform_deg = 0.0;
  if (auto joints = machine.optional("joints")) {
    joints->check_keys({"base_max_angle_deg", "platform_max_angle_deg"});
    if (auto v = joints->optional("base_max_angle_deg"))
      d.joints.base_max_angle = angle_deg_kept(*v, 1, 179, base_deg);
    if (auto v = joints->optional("platform_max_angle_deg"))
      d.joints.platform_max_angle = angle_deg_kept(*v, 1, 179, platform_deg);
  }
  d.tcp.setZero();
  if (auto tool = machine.optional("tool")) {
    tool->check_keys({"tcp"});
    const std::vector<double> tcp = tool->required("tcp").as_doubles(3);
    d.tcp = Eigen::Vector3d(tcp[0], tcp[1], tcp[2]);
  }
  if (auto v = machine.optional("actuator_error")) d.actuator_error = v->as_positive();

  yaml += "machine:\n  model: hexapod\n  parameters:\n";
  for (int i = 0; i < kNumDesignParameters; ++i) {
    const auto [lo, hi] = study.parameter_ranges[i];
    yaml += fmt::format(
        "    {}: {}\n", design_parameter_name(i),
        lo == hi ? format_number(lo)
                 : fmt::format("{{min: {}, max: {}}}", format_number(lo), format_number(hi)));
  }
  if (d.stiffness.axial_stiffness > 0.0)
    yaml +=
        fmt::format("  legs: {{axial_stiffness: {}", format_number(d.stiffness.axial_stiffness));
  else
    yaml += fmt::format("  legs: {{E: {}, area: {}", format_number(d.stiffness.E),
                        format_number(d.stiffness.area));
  if (d.stiffness.actuator_stiffness > 0.0)
    yaml += fmt::format(", actuator_stiffness: {}", format_number(d.stiffness.actuator_stiffness));
  yaml += "}\n";
  std::string joints;
  if (std::isfinite(d.joints.base_max_angle))
    joints += fmt::format("base_max_angle_deg: {}", format_number(base_deg));
  if (std::isfinite(d.joints.platform_max_angle))
    joints += fmt::format("{}platform_max_angle_deg: {}", joints.empty() ? "" : ", ",
                          format_number(platform_deg));
  const bool unlimited =
      !std::isfinite(d.joints.base_max_angle) || !std::isfinite(d.joints.platform_max_angle);
  yaml += "  joints: {" + joints + "}" + (unlimited ? "  # a missing limit: unlimited" : "") + "\n";
  const double tcp[3] = {d.tcp.x(), d.tcp.y(), d.tcp.z()};
  yaml += "  tool: {tcp: " + triple(tcp) + "}\n";
  yaml += "  actuator_error: " + format_number(d.actuator_error) + "\n";
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
    std::vector<std::string> names;
    for (const FamilyParameter& p : family.parameters) names.push_back(p.name);
    section->check_keys(names);
    for (std::size_t i = 0; i < family.parameters.size(); ++i) {
      const FamilyParameter& parameter = family.parameters[i];
      const auto v = section->optional(parameter.name);
      if (!v) continue;
      double lo = 0.0, hi = 0.0;
      if (v->is_map()) {
        v->check_keys({"min", "max"});
        lo = v->required("min").as_double();
        hi = v->required("max").as_double();
        if (!(lo < hi)) v->required("max").fail("max > min", v->required("max").describe());
      } else {
        lo = hi = v->as_double();
      }
      if (!parameter.may_be_negative && (lo < 0.0 || (!parameter.may_be_zero && lo == 0.0)))
        v->fail(parameter.may_be_zero ? "values >= 0" : "values > 0", v->describe());
      if (std::abs(lo) > parameter.max_abs || std::abs(hi) > parameter.max_abs)
        v->fail(fmt::format("values within [-{0}, {0}] {1}", format_number(parameter.max_abs),
                            parameter.unit),
                v->describe());
      study.parameters[i].min = lo;
      study.parameters[i].max = hi;
      spec.parameters[i] = {parameter.to_internal(lo), parameter.to_internal(hi)};
    }
  }
  yaml += "machine:\n  model: " + model + "\n  parameters:\n";
  for (const StudyParameter& p : study.parameters)
    yaml += fmt::format(
        "    {}: {}\n", p.name,
        p.free() ? fmt::format("{{min: {}, max: {}}}", format_number(p.min), format_number(p.max))
                 : format_number(p.min));
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
