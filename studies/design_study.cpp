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

#include "io/actuator_catalog_file.hpp"
#include "io/csv.hpp"
#include "io/input_error.hpp"
#include "io/machine_file.hpp"
#include "io/machine_file_writer.hpp"
#include "io/machine_file_lathe.hpp"
#include "io/machine_file_leg_chain.hpp"
#include "io/output_file.hpp"
#include "io/task_wrench_file.hpp"
#include "optimizer/indicators.hpp"
#include "pkmopt/version.hpp"
#include "problems/lathe_design.hpp"

namespace pkmopt {
namespace {

// {actuator: cheapest, catalog: FILE}: the optimiser chooses the entry.
constexpr const char* kCheapestActuator = "cheapest";

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


std::string triple(const double* v, int n = 3) {
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
    yaml += fmt::format("    {}: {}\n", design_parameter_name(i),
                        lo == hi ? format_number(lo) : fmt::format("{{min: {}, max: {}}}", format_number(lo), format_number(hi)));
  }
  if (d.stiffness.axial_stiffness > 0.0)
    yaml += fmt::format("  legs: {{axial_stiffness: {}", format_number(d.stiffness.axial_stiffness));
  else
    yaml += fmt::format("  legs: {{E: {}, area: {}", format_number(d.stiffness.E), format_number(d.stiffness.area));
  if (d.stiffness.actuator_stiffness > 0.0)
    yaml += fmt::format(", actuator_stiffness: {}", format_number(d.stiffness.actuator_stiffness));
  yaml += "}\n";
  std::string joints;
  if (std::isfinite(d.joints.base_max_angle))
    joints += fmt::format("base_max_angle_deg: {}", format_number(base_deg));
  if (std::isfinite(d.joints.platform_max_angle))
    joints +=
        fmt::format("{}platform_max_angle_deg: {}", joints.empty() ? "" : ", ", format_number(platform_deg));
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
  const YAML::Node default_file = YAML::Load(family_machine_file(defaults.design(defaults.default_parameters())));
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
        v->fail(
            fmt::format("values within [-{0}, {0}] {1}", format_number(parameter.max_abs), parameter.unit),
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
        p.free() ? fmt::format("{{min: {}, max: {}}}", format_number(p.min), format_number(p.max)) : format_number(p.min));
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

void read_task(const YamlValue& task, DesignTask& task_spec, DesignStudy& study,
               std::string& yaml) {
  task.check_keys({"region", "orientations", "wrench", "workspace"});
  double tilt_deg = 0.0, yaw_deg = 0.0, step_deg = 10.0;
  if (auto o = task.optional("orientations")) {
    o->check_keys({"tilt_deg", "yaw_deg", "step_deg"});
    if (auto v = o->optional("tilt_deg")) angle_deg_kept(*v, 0, 89, tilt_deg);
    if (auto v = o->optional("yaw_deg")) angle_deg_kept(*v, 0, 179, yaw_deg);
    if (auto v = o->optional("step_deg")) angle_deg_kept(*v, 0.5, 90, step_deg);
  }
  const double tilt = deg_to_rad(tilt_deg), yaw = deg_to_rad(yaw_deg), step = deg_to_rad(step_deg);
  study.task_tilt_deg = tilt_deg;
  study.task_yaw_deg = yaw_deg;
  const YamlValue region = task.required("region");
  region.expect_map();
  const YamlValue shape = region.required("shape");
  const std::vector<double> c = region.required("centre").as_doubles(3);
  const Eigen::Vector3d centre(c[0], c[1], c[2]);
  study.task_centre = {c[0], c[1], c[2]};
  yaml += "task:\n";
  if (shape.as_string() == "box") {
    region.check_keys({"shape", "centre", "size", "points"});
    const YamlValue size_value = region.required("size");
    const std::vector<double> size = size_value.as_doubles(3);
    for (double s : size)
      if (s < 0.0) size_value.fail("sizes >= 0 (m)", size_value.describe());
    Eigen::Vector3i counts(1, 1, 1);
    if (auto v = region.optional("points")) {
      const std::vector<YamlValue> n = v->elements(3);
      for (int a = 0; a < 3; ++a) counts(a) = positive_int(n[a]);
    }
    task_spec.poses = box_task_poses(centre, 0.5 * Eigen::Vector3d(size[0], size[1], size[2]),
                                     counts, tilt, yaw, step);
    study.task_positions = static_cast<std::size_t>(counts.prod());
    yaml += fmt::format("  region: {{shape: box, centre: {}, size: {}, points: [{}, {}, {}]}}\n",
                        triple(c.data()), triple(size.data()), counts(0), counts(1), counts(2));
  } else if (shape.as_string() == "cylinder") {
    region.check_keys({"shape", "centre", "radius", "height", "rings", "per_ring", "layers"});
    const double radius = region.required("radius").as_double();
    const double height = region.required("height").as_double();
    if (radius < 0.0) region.required("radius").fail("a radius >= 0 (m)", "a negative number");
    if (height < 0.0) region.required("height").fail("a height >= 0 (m)", "a negative number");
    int rings = 1, per_ring = 6, layers = 1;
    if (auto v = region.optional("rings")) {
      rings = static_cast<int>(v->as_int());
      if (rings < 0 || rings > 100) v->fail("an integer in 0..100", v->describe());
    }
    if (auto v = region.optional("per_ring")) per_ring = positive_int(*v);
    if (auto v = region.optional("layers")) layers = positive_int(*v);
    task_spec.poses =
        cylinder_task_poses(centre, radius, height, rings, per_ring, layers, tilt, yaw, step);
    study.task_positions = static_cast<std::size_t>((1 + rings * per_ring) * layers);
    yaml += fmt::format(
        "  region: {{shape: cylinder, centre: {}, radius: {}, height: {}, rings: {}, per_ring: "
        "{}, layers: {}}}\n",
        triple(c.data()), format_number(radius), format_number(height), rings, per_ring, layers);
  } else {
    shape.fail("'box' or 'cylinder'", shape.describe());
  }
  if (task_spec.poses.size() > 100000)
    region.fail(fmt::format("at most 100000 task poses, found {}", task_spec.poses.size()));
  yaml += fmt::format("  orientations: {{tilt_deg: {}, yaw_deg: {}, step_deg: {}}}\n",
                      format_number(tilt_deg), format_number(yaw_deg), format_number(step_deg));
  task_spec.wrench.setZero();
  std::string wrench_origin;
  if (auto v = task.optional("wrench")) {
    const TaskWrench task_wrench = read_task_wrench(*v);  // a list, or a turning/milling model
    task_spec.wrench = task_wrench.wrench;
    wrench_origin = task_wrench.origin;
  }
  const double wrench[6] = {task_spec.wrench(0), task_spec.wrench(1), task_spec.wrench(2),
                            task_spec.wrench(3), task_spec.wrench(4), task_spec.wrench(5)};
  if (!wrench_origin.empty()) yaml += "  # wrench from the cutting model: " + wrench_origin + "\n";
  yaml += "  wrench: " + triple(wrench, 6) + "\n";
  double resolution = 0.05, ws_tilt = 0.0, ws_yaw = 0.0, ws_step = 5.0;
  if (auto w = task.optional("workspace")) {
    w->check_keys({"resolution", "tilt_deg", "yaw_deg", "step_deg"});
    if (auto v = w->optional("resolution")) resolution = v->as_positive();
    if (auto v = w->optional("tilt_deg")) angle_deg_kept(*v, 0, 89, ws_tilt);
    if (auto v = w->optional("yaw_deg")) angle_deg_kept(*v, 0, 179, ws_yaw);
    if (auto v = w->optional("step_deg")) angle_deg_kept(*v, 0.5, 90, ws_step);
  }
  task_spec.workspace.resolution = resolution;
  task_spec.workspace.orientations.tilt = deg_to_rad(ws_tilt);
  task_spec.workspace.orientations.yaw_range = deg_to_rad(ws_yaw);
  task_spec.workspace.orientations.orientation_step = deg_to_rad(ws_step);
  yaml += fmt::format("  workspace: {{resolution: {}, tilt_deg: {}, yaw_deg: {}, step_deg: {}}}\n",
                      format_number(resolution), format_number(ws_tilt), format_number(ws_yaw), format_number(ws_step));
}

DesignMetric read_metric(const YamlValue& v) {
  const std::optional<DesignMetric> metric = design_metric_from_name(v.as_string());
  if (!metric)
    v.fail(
        "one of stiffness_min, singularity_margin, leg_force_max, tcp_error_max, "
        "workspace_volume, conditioning_index, machine_size, actuator_cost, actuator_overload",
        v.describe());
  return *metric;
}

// {actuator: NAME, catalog: FILE}: the legs are that catalog entry. Adds leg_force_max <= its
// force rating and caps the stroke parameter at its stroke.
// {actuator: cheapest, catalog: FILE}: the optimiser chooses, for every design, the cheapest
// entry that carries the legs (HexapodDesignSpec::actuator_catalog). Adds actuator_overload <= 0
// and caps the stroke parameter at the longest entry's stroke.
// Returns the resolved YAML line (catalog path made absolute so that study.resolved.yaml loads
// from anywhere).
std::string read_actuator_constraint(const YamlValue& c, const std::string& study_path,
                                     HexapodDesignSpec& spec, DesignStudy& study) {
  c.check_keys({"actuator", "catalog"});
  const YamlValue catalog_value = c.required("catalog");
  std::filesystem::path catalog_path = catalog_value.as_string();
  if (catalog_path.is_relative())
    catalog_path = std::filesystem::path(study_path).parent_path() / catalog_path;
  if (!std::filesystem::exists(catalog_path))
    catalog_value.fail("an actuator catalog file",
                       "'" + catalog_path.string() + "' (no such file)");
  catalog_path = std::filesystem::absolute(catalog_path).lexically_normal();
  const ActuatorCatalog catalog = load_actuator_catalog(catalog_path.string());
  const YamlValue name_value = c.required("actuator");
  const std::string name = name_value.as_string();
  int stroke = -1;
  for (int i = 0; i < kNumDesignParameters; ++i) {
    if (design_parameter_name(i) == "stroke") stroke = i;
  }
  auto& [lo, hi] = study.parameter_ranges[static_cast<std::size_t>(stroke)];
  if (name == kCheapestActuator) {
    if (find_actuator(catalog, name) != nullptr)
      name_value.fail(fmt::format("a catalog without an entry named '{}' (the word asks for the "
                                  "cheapest entry)",
                                  kCheapestActuator),
                      fmt::format("catalog '{}' with such an entry", catalog.name));
    if (spec.actuator_catalog)
      name_value.fail("one {actuator: cheapest, catalog: FILE} constraint per study",
                      "a second one");
    try {
      actuator_costs(catalog);
    } catch (const std::invalid_argument& error) {
      catalog_value.fail("a catalog whose entries all have a cost or all have none", error.what());
    }
    double longest = 0.0;
    for (const ActuatorEntry& e : catalog.entries) longest = std::max(longest, e.stroke);
    if (lo > longest)
      name_value.fail(
          fmt::format("a catalog with an entry of stroke at least "
                      "machine.parameters.stroke ({} m)",
                      format_number(lo)),
          fmt::format("catalog '{}' whose longest stroke is {} m", catalog.name, format_number(longest)));
    hi = std::min(hi, longest);
    spec.parameters[static_cast<std::size_t>(stroke)].upper =
        std::min(spec.parameters[static_cast<std::size_t>(stroke)].upper, longest);
    spec.actuator_catalog = catalog;
    spec.constraints.push_back({DesignMetric::actuator_overload, Relation::less_equal, 0.0});
    return fmt::format(
        "  - {{actuator: {}, catalog: {}}}  # actuator_overload <= 0, stroke <= {} m\n",
        kCheapestActuator, nlohmann::json(catalog_path.string()).dump(), format_number(hi));
  }
  const ActuatorEntry* entry = find_actuator(catalog, name);
  if (entry == nullptr) {
    std::string names;
    for (const ActuatorEntry& e : catalog.entries) names += (names.empty() ? "" : ", ") + e.name;
    name_value.fail(fmt::format("an entry of catalog '{}' ({})", catalog.name, names),
                    "'" + name + "'");
  }
  spec.constraints.push_back({DesignMetric::leg_force_max, Relation::less_equal, entry->max_force});
  if (lo > entry->stroke) {
    name_value.fail(fmt::format("an actuator with a stroke of at least machine.parameters.stroke "
                                "({} m)",
                                lo),
                    fmt::format("'{}' with {} m", name, entry->stroke));
  }
  hi = std::min(hi, entry->stroke);
  spec.parameters[static_cast<std::size_t>(stroke)].upper =
      std::min(spec.parameters[static_cast<std::size_t>(stroke)].upper, entry->stroke);
  return fmt::format("  - {{actuator: {}, catalog: {}}}  # leg_force_max <= {} N, stroke <= {} m\n",
                     nlohmann::json(name).dump(), nlohmann::json(catalog_path.string()).dump(),
                     format_number(entry->max_force), format_number(entry->stroke));
}

}  // namespace

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
  const YamlValue root = YamlValue::load_file(path);
  root.check_keys({"study", "description", "machine", "task", "objectives", "constraints",
                   "optimizer", "output"});
  DesignStudy study;
  study.name = root.required("study").as_string();
  if (auto v = root.optional("description")) study.description = v->as_string();
  std::string yaml = fmt::format("# {} resolved: every default filled in (pkmopt {})\n",
                                 nlohmann::json(study.name).dump(), kVersion);
  yaml += "study: " + nlohmann::json(study.name).dump() + "\n";
  yaml += "description: " + nlohmann::json(study.description).dump() + "\n";
  const YamlValue machine = root.required("machine");
  machine.expect_map();
  const YamlValue model = machine.required("model");
  study.model = model.as_string();
  // The hexapod has its own problem (with a smooth formulation); the leg-chain models share the
  // generic one. Goals and task are read into whichever spec is used.
  HexapodDesignSpec spec;
  MachineDesignSpec machine_spec;
  const bool hexapod = study.model == "hexapod";
  if (hexapod) {
    spec.name = study.name;
    read_machine(machine, spec, study, yaml);
  } else if (leg_chain_family(study.model, nullptr)) {
    machine_spec.name = study.name;
    read_leg_chain_machine(machine, study.model, machine_spec, study, yaml);
  } else {
    // Models with a design family (the machine-file models may be more: leg_chain_model_names).
    model.fail(
        "one of hexapod, delta, linear_delta, hexaglide, tripod_3prs, lathe_16k20f3 (the models "
        "with a design family)",
        model.describe());
  }
  DesignTask& task = hexapod ? spec.task : machine_spec.task;
  std::vector<DesignObjective>& goals = hexapod ? spec.objectives : machine_spec.objectives;
  std::vector<DesignConstraint>& limits = hexapod ? spec.constraints : machine_spec.constraints;
  const YamlValue task_section = root.required("task");
  read_task(task_section, task, study, yaml);
  if (!hexapod && machine_spec.family.translational &&
      (study.task_tilt_deg > 0.0 || study.task_yaw_deg > 0.0))
    task_section.required("orientations")
        .fail(fmt::format("tilt_deg: 0 and yaw_deg: 0 (the {} platform keeps its orientation)",
                          study.model),
              fmt::format("tilt_deg {}, yaw_deg {}", format_number(study.task_tilt_deg),
                          format_number(study.task_yaw_deg)));

  // Where an actuator metric is first used (it needs {actuator: cheapest, catalog: FILE}).
  std::optional<YamlValue> actuator_metric_use;
  const YamlValue objectives = root.required("objectives");
  const std::vector<YamlValue> objective_list = objectives.elements();
  if (objective_list.empty()) objectives.fail("a list of at least one objective", "an empty list");
  yaml += "objectives:\n";
  for (const YamlValue& o : objective_list) {
    o.check_keys({"minimize", "maximize"});
    if (o.keys().size() != 1) o.fail("one of minimize: METRIC or maximize: METRIC", o.describe());
    const bool maximize = o.has("maximize");
    const YamlValue metric_value = o.required(maximize ? "maximize" : "minimize");
    goals.push_back({read_metric(metric_value), maximize ? Sense::maximize : Sense::minimize});
    if (is_actuator_metric(goals.back().metric) && !actuator_metric_use)
      actuator_metric_use = metric_value;
    yaml += fmt::format("  - {}: {}\n", maximize ? "maximize" : "minimize",
                        design_metric_name(goals.back().metric));
  }
  bool require_reachable = false;
  std::string constraint_yaml;
  if (auto constraints = root.optional("constraints")) {
    for (const YamlValue& c : constraints->elements()) {
      if (c.is_scalar()) {
        if (c.as_string() != "task_reachable")
          c.fail(
              "task_reachable, {metric: NAME, max|min: VALUE} or {actuator: NAME, catalog: FILE}",
              c.describe());
        require_reachable = true;
        continue;
      }
      if (c.has("actuator")) {
        if (!hexapod)
          c.required("actuator")
              .fail(fmt::format("{{metric: NAME, max|min: VALUE}} (actuator catalog constraints "
                                "size hexapod legs; a {} study bounds leg_force_max instead)",
                                study.model),
                    "an actuator constraint");
        constraint_yaml += read_actuator_constraint(c, path, spec, study);
        continue;
      }
      c.check_keys({"metric", "max", "min"});
      const DesignMetric metric = read_metric(c.required("metric"));
      if (is_actuator_metric(metric) && !actuator_metric_use)
        actuator_metric_use = c.required("metric");
      if (c.has("max") == c.has("min")) c.fail("exactly one of max and min", c.describe());
      const bool upper = c.has("max");
      limits.push_back({metric, upper ? Relation::less_equal : Relation::greater_equal,
                        c.required(upper ? "max" : "min").as_double()});
      constraint_yaml += fmt::format("  - {{metric: {}, {}: {}}}\n", design_metric_name(metric),
                                     upper ? "max" : "min", format_number(limits.back().bound));
    }
  }
  if (actuator_metric_use && !spec.actuator_catalog)
    actuator_metric_use->fail(
        fmt::format("a metric of this {} study (actuator_cost and actuator_overload need a "
                    "constraint {{actuator: cheapest, catalog: FILE}} on a hexapod study)",
                    study.model),
        actuator_metric_use->describe());
  spec.require_reachable = machine_spec.require_reachable = require_reachable;
  if (require_reachable) constraint_yaml = "  - task_reachable\n" + constraint_yaml;
  yaml += constraint_yaml.empty() ? "constraints: []\n" : "constraints:\n" + constraint_yaml;
  const YamlValue optimizer = root.required("optimizer");
  optimizer.expect_map();
  const YamlValue algorithm_value = optimizer.required("algorithm");
  const std::string algorithm = algorithm_value.as_string();
  spec.formulation =
      algorithm == "nsga2" ? DesignFormulation::aggregate : DesignFormulation::smooth;
  if (!hexapod && algorithm != "nsga2" && !derivative_free_nlopt(algorithm))
    algorithm_value.fail(
        fmt::format("nsga2 (or a derivative-free nlopt:COBYLA, nlopt:ISRES, nlopt:BOBYQA, ... for "
                    "one objective): a {} design study measures worst cases over the task and "
                    "has no gradients",
                    study.model),
        "'" + algorithm + "'");
  try {
    if (hexapod)
      study.problem = std::make_unique<HexapodDesignProblem>(std::move(spec));
    else
      study.machine_problem = std::make_unique<MachineDesignProblem>(std::move(machine_spec));
  } catch (const std::invalid_argument& error) {
    root.fail(error.what());
  }
  if (hexapod) {
    for (int i = 0; i < kNumDesignParameters; ++i) {
      const auto [lo, hi] = study.parameter_ranges[static_cast<std::size_t>(i)];
      study.parameters.push_back({std::string(design_parameter_name(i)),
                                  design_parameter_in_degrees(i) ? "deg" : "m", lo, hi});
    }
  }
  study.optimizer = read_optimizer_section(optimizer, study.optimization_problem());
  if (auto output = root.optional("output")) {
    output->check_keys({"designs"});
    if (auto v = output->optional("designs")) study.write_designs = v->as_bool();
  }
  yaml += "optimizer: " + optimizer_section_yaml(study.optimizer) + "\n";
  yaml += fmt::format("output: {{designs: {}}}\n", study.write_designs ? "true" : "false");
  study.resolved_yaml = yaml;
  return study;
}

const Problem& DesignStudy::optimization_problem() const {
  if (problem) return *problem;
  return *machine_problem;
}
const std::vector<DesignObjective>& DesignStudy::objectives() const {
  return problem ? problem->spec().objectives : machine_problem->spec().objectives;
}
const std::vector<DesignConstraint>& DesignStudy::constraints() const {
  return problem ? problem->spec().constraints : machine_problem->spec().constraints;
}
bool DesignStudy::require_reachable() const {
  return problem ? problem->spec().require_reachable : machine_problem->spec().require_reachable;
}
const DesignTask& DesignStudy::task() const {
  return problem ? problem->spec().task : machine_problem->spec().task;
}
bool DesignStudy::aggregate() const {
  return !problem || problem->spec().formulation == DesignFormulation::aggregate;
}

std::string_view design_metric_unit(DesignMetric metric) {
  switch (metric) {
    case DesignMetric::stiffness_min:
      return "N/m";
    case DesignMetric::leg_force_max:
      return "N";
    case DesignMetric::tcp_error_max:
      return "m";
    case DesignMetric::workspace_volume:
    case DesignMetric::machine_size:
      return "m^3";
    case DesignMetric::actuator_overload:
      return "N";
    case DesignMetric::singularity_margin:
    case DesignMetric::conditioning_index:
    case DesignMetric::actuator_cost:
      return "";
  }
  return "";
}

namespace {

double sense_sign(Sense sense) { return sense == Sense::maximize ? -1.0 : 1.0; }

std::vector<std::string> constraint_names(const DesignStudy& study) {
  std::vector<std::string> names;
  for (const DesignConstraint& c : study.constraints())
    names.push_back(fmt::format("g_{}_{}", design_metric_name(c.metric),
                                c.relation == Relation::less_equal ? "max" : "min"));
  if (study.require_reachable()) names.emplace_back("g_task_reachable");
  return names;
}

// Indices (into study.parameters) of the variables, in variable order.
std::vector<int> free_parameter_indices(const DesignStudy& study) {
  return study.problem ? study.problem->free_parameters()
                       : study.machine_problem->free_parameters();
}

// Every parameter of a variable vector in file units (study.parameters order).
std::vector<double> file_parameters(const DesignStudy& study, const std::vector<double>& x) {
  std::vector<double> values;
  if (study.problem) {
    const std::array<double, kNumDesignParameters> p = study.problem->parameters_of(x);
    for (int i = 0; i < kNumDesignParameters; ++i)
      values.push_back(design_parameter_in_degrees(i) ? rad_to_deg(p[i]) : p[i]);
  } else {
    const std::vector<double> p = study.machine_problem->parameters_of(x);
    const DesignFamily& family = study.machine_problem->family();
    for (std::size_t i = 0; i < p.size(); ++i) values.push_back(family.parameters[i].to_file(p[i]));
  }
  return values;
}

// A design measured for the outputs, whichever problem the study has.
struct MeasuredDesign {
  std::vector<double> x;
  std::vector<double> parameters;  // every parameter, file units (study.parameters order)
  double home_height = 0.0;        // m
  DesignMetrics metrics{};
  std::vector<double> aggregate;  // [objectives internal | constraint rows]
  std::string failure;
  std::string machine_file;  // YAML of the machine (when asked for)
  int actuator = -1;         // chosen catalog entry (hexapod studies choosing the cheapest)
  bool ok() const { return failure.empty(); }
};

MeasuredDesign measure_design(const DesignStudy& study, const std::vector<double>& x,
                              bool machine_file) {
  MeasuredDesign d;
  d.x = x;
  d.parameters = file_parameters(study, x);
  if (study.problem) {
    const DesignEvaluation ev = study.problem->evaluate(x);
    d.home_height = ev.parameters[kHomeHeight];
    d.metrics = ev.metrics;
    d.aggregate = study.problem->aggregate_fitness(ev);
    d.failure = ev.failure;
    d.actuator = ev.actuator;
    if (machine_file && ev.ok())
      d.machine_file = hexapod_design_to_yaml(study.problem->design_of(ev.parameters));
  } else {
    const MachineDesignProblem& problem = *study.machine_problem;
    const MachineDesignEvaluation ev = problem.evaluate(x);
    d.home_height = problem.home_height_of(ev.parameters);
    d.metrics = ev.metrics;
    d.aggregate = problem.aggregate_fitness(ev);
    d.failure = ev.failure;
    if (machine_file && ev.ok()) d.machine_file = family_machine_file(problem.family().design(ev.parameters));
  }
  return d;
}

}  // namespace

JournalOptions design_journal_options(const DesignStudy& study) {
  const bool aggregate = study.aggregate();
  JournalOptions options;
  std::string header = "index";
  const std::vector<int> free = free_parameter_indices(study);
  for (int i : free) header += "," + study.parameters[static_cast<std::size_t>(i)].name;
  for (const DesignObjective& o : study.objectives())
    header += fmt::format(",{}", design_metric_name(o.metric));
  if (aggregate)
    for (const std::string& name : constraint_names(study)) header += "," + name;
  else
    header += ",g_max";
  header += ",feasible,failure";
  options.csv_header = header;
  const DesignStudy* s = &study;
  if (aggregate)
    options.evaluate = [s](const std::vector<double>& x) {
      const MeasuredDesign d = measure_design(*s, x, false);
      JournalEntry entry;
      entry.fitness = d.aggregate;
      entry.note = d.failure;
      return entry;
    };
  options.csv_row = [s, free, aggregate](std::size_t index, const JournalEntry& e) {
    const std::vector<DesignObjective>& objectives = s->objectives();
    std::string row = std::to_string(index);
    const std::vector<double> parameters = file_parameters(*s, e.x);
    for (int i : free) row += "," + format_number(parameters[static_cast<std::size_t>(i)]);
    const bool failed = !e.note.empty();
    bool feasible = !failed;
    for (std::size_t k = 0; k < objectives.size(); ++k) {
      const double f = e.fitness[k];
      feasible = feasible && std::isfinite(f);
      row += failed || !std::isfinite(f) ? ","
                                         : "," + format_number(sense_sign(objectives[k].sense) * f);
    }
    double g_max = -std::numeric_limits<double>::infinity();
    for (std::size_t r = objectives.size(); r < e.fitness.size(); ++r) {
      const double g = e.fitness[r];
      feasible = feasible && g <= 0.0;
      g_max = std::max(g_max, g);
      if (aggregate) row += failed || !std::isfinite(g) ? "," : "," + format_number(g);
    }
    if (!aggregate)
      row += e.fitness.size() == objectives.size() || !std::isfinite(g_max)
                 ? ","
                 : "," + format_number(g_max);
    row += feasible ? ",1," : ",0,";
    row += csv_field(e.note);
    return row;
  };
  return options;
}

namespace {

nlohmann::json json_number(double value) {
  return std::isfinite(value) ? nlohmann::json(value) : nlohmann::json(nullptr);
}

}  // namespace

void write_design_outputs(const std::string& directory, const DesignStudy& study,
                          const RunOutcome& outcome, const DesignRunFacts& facts) {
  namespace fs = std::filesystem;
  const std::vector<DesignObjective>& objectives_spec = study.objectives();
  const std::vector<DesignConstraint>& constraints_spec = study.constraints();
  const std::size_t m = objectives_spec.size();
  const std::vector<int> free = free_parameter_indices(study);
  const int home_index = [&] {
    for (std::size_t i = 0; i < study.parameters.size(); ++i)
      if (study.parameters[i].name == "home_height") return static_cast<int>(i);
    return -1;
  }();
  const bool home_free =
      home_index >= 0 && study.parameters[static_cast<std::size_t>(home_index)].free();

  // Re-measure the front designs (aggregate metrics in user units for every formulation); a
  // failed design never enters the front.
  std::vector<MeasuredDesign> front(outcome.front.x.size());
  const long long count = static_cast<long long>(front.size());
#pragma omp parallel for num_threads(resolve_thread_count(facts.threads)) schedule(dynamic)
  for (long long k = 0; k < count; ++k)
    front[static_cast<std::size_t>(k)] =
        measure_design(study, outcome.front.x[static_cast<std::size_t>(k)], study.write_designs);
  std::erase_if(front, [](const MeasuredDesign& d) { return !d.ok(); });
  ObjectiveSet objectives;  // internal (minimised) sign
  for (const MeasuredDesign& d : front)
    objectives.emplace_back(d.aggregate.begin(),
                            d.aggregate.begin() + static_cast<std::ptrdiff_t>(m));
  const std::vector<std::string> g_names = constraint_names(study);
  auto id_of = [](std::size_t k) { return fmt::format("d{:04}", k); };
  // The catalog the optimiser chose actuators from ({actuator: cheapest, catalog: FILE}).
  const ActuatorCatalog* catalog = study.problem && study.problem->spec().actuator_catalog
                                       ? &*study.problem->spec().actuator_catalog
                                       : nullptr;

  // pareto.csv
  std::ostringstream csv;
  csv << "id";
  for (int i : free) csv << ',' << study.parameters[static_cast<std::size_t>(i)].name;
  if (!home_free) csv << ",home_height";
  for (const DesignObjective& o : objectives_spec) csv << ',' << design_metric_name(o.metric);
  for (const std::string& g : g_names) csv << ',' << g;
  if (catalog) csv << ",actuator";
  csv << ",feasible,failure\n";
  if (study.write_designs) fs::create_directories(fs::path(directory) / "designs");
  nlohmann::json designs = nlohmann::json::array();
  for (std::size_t k = 0; k < front.size(); ++k) {
    const MeasuredDesign& d = front[k];
    const std::string id = id_of(k);
    nlohmann::json design;
    design["id"] = id;
    csv << id;
    nlohmann::json parameters = nlohmann::json::object();
    for (int i : free) {
      const double value = d.parameters[static_cast<std::size_t>(i)];
      csv << ',' << format_number(value);
      parameters[study.parameters[static_cast<std::size_t>(i)].name] = json_number(value);
    }
    if (!home_free) csv << ',' << format_number(d.home_height);
    design["parameters"] = parameters;
    design["home_height"] = json_number(d.home_height);
    nlohmann::json objective_values = nlohmann::json::object();
    for (const DesignObjective& o : objectives_spec) {
      const double value = d.metrics[static_cast<int>(o.metric)];
      csv << ',' << format_number(value);
      objective_values[std::string(design_metric_name(o.metric))] = json_number(value);
    }
    design["objectives"] = objective_values;
    nlohmann::json constraint_values = nlohmann::json::object();
    bool feasible = true;
    for (std::size_t r = 0; r < g_names.size(); ++r) {
      const double g = d.aggregate[m + r];
      csv << ',' << format_number(g);
      constraint_values[g_names[r]] = json_number(g);
      feasible = feasible && g <= 0.0;
    }
    design["constraints"] = constraint_values;
    if (catalog) {
      if (d.actuator >= 0) {
        const ActuatorEntry& e = catalog->entries[static_cast<std::size_t>(d.actuator)];
        const double force = d.metrics[static_cast<int>(DesignMetric::leg_force_max)];
        csv << ',' << csv_field(e.name);
        design["actuator"] = {{"name", e.name},
                              {"type", e.type},
                              {"max_force", e.max_force},
                              {"stroke", e.stroke},
                              {"max_speed", e.max_speed},
                              {"cost", d.metrics[static_cast<int>(DesignMetric::actuator_cost)]},
                              {"leg_force_max", json_number(force)},
                              {"force_reserve", json_number(e.max_force / force)}};
      } else {
        csv << ",";
        design["actuator"] = nullptr;
      }
    }
    design["feasible"] = feasible;
    csv << ',' << (feasible ? 1 : 0) << ",\"\"\n";
    if (study.write_designs) {
      write_file_atomically(directory + "/designs/" + id + ".yaml", d.machine_file);
      design["machine_file"] = "designs/" + id + ".yaml";
    }
    designs.push_back(design);
  }

  // pareto.json (pkmopt-pareto-1, docs/design-studies.md)
  nlohmann::json pareto;
  pareto["format"] = "pkmopt-pareto-1";
  pareto["pkmopt_version"] = kVersion;
  pareto["study"] = study.name;
  pareto["description"] = study.description;
  pareto["model"] = study.model;
  nlohmann::json parameter_list = nlohmann::json::array();
  nlohmann::json fixed = nlohmann::json::object();
  for (const StudyParameter& p : study.parameters) {
    if (!p.free())
      fixed[p.name] = p.min;
    else
      parameter_list.push_back(
          {{"name", p.name}, {"unit", p.unit}, {"min", p.min}, {"max", p.max}});
  }
  pareto["parameters"] = parameter_list;
  pareto["fixed_parameters"] = fixed;
  nlohmann::json objective_list = nlohmann::json::array();
  for (const DesignObjective& o : objectives_spec)
    objective_list.push_back({{"name", design_metric_name(o.metric)},
                              {"sense", o.sense == Sense::maximize ? "maximize" : "minimize"},
                              {"unit", design_metric_unit(o.metric)}});
  pareto["objectives"] = objective_list;
  nlohmann::json constraint_list = nlohmann::json::array();
  for (std::size_t r = 0; r < constraints_spec.size(); ++r) {
    const DesignConstraint& c = constraints_spec[r];
    constraint_list.push_back({{"name", g_names[r]},
                               {"metric", design_metric_name(c.metric)},
                               {"kind", c.relation == Relation::less_equal ? "max" : "min"},
                               {"bound", c.bound},
                               {"unit", design_metric_unit(c.metric)}});
  }
  if (study.require_reachable())
    constraint_list.push_back({{"name", "g_task_reachable"},
                               {"metric", "task_reachable"},
                               {"kind", "reachable"},
                               {"bound", 0},
                               {"unit", ""}});
  pareto["constraints"] = constraint_list;
  if (catalog) {
    pareto["actuator_catalog"] = {
        {"name", catalog->name},
        {"entries", catalog->entries.size()},
        {"cost", catalog->entries.front().cost ? "catalog cost" : "rank by force rating"}};
  }
  const Wrench& wrench = study.task().wrench;
  pareto["task"] = {{"centre", study.task_centre},
                    {"wrench", std::vector<double>(wrench.data(), wrench.data() + 6)},
                    {"tilt_deg", study.task_tilt_deg},
                    {"yaw_deg", study.task_yaw_deg}};
  pareto["designs"] = designs;
  nlohmann::json knee = nullptr;
  if (!objectives.empty()) knee = id_of(knee_point(objectives));
  pareto["knee"] = knee;

  // summary.json: hypervolume in user sign and units.
  nlohmann::json summary;
  summary["study"] = study.name;
  summary["description"] = study.description;
  summary["model"] = study.model;
  summary["version"] = kVersion;
  summary["algorithm"] = study.optimizer.name();
  summary["formulation"] = study.aggregate() ? "aggregate" : "smooth";
  summary["status"] = front.empty() ? std::string("no_feasible_design") : outcome.status;
  summary["message"] = outcome.front.message;
  summary["seed"] = study.optimizer.seed;
  summary["threads"] = resolve_thread_count(facts.threads);
  summary["resumed"] = facts.resumed;
  summary["evaluations"] = outcome.front.fitness_evaluations;
  summary["gradient_evaluations"] = outcome.front.gradient_evaluations;
  if (facts.journal) {
    const JournaledProblem& j = *facts.journal;
    summary["evaluations_from_cache"] = j.cache_hits();
    summary["evaluations_distinct"] = j.entries().size();
    summary["evaluations_loaded_from_journal"] = j.loaded_entries();
    summary["evaluations_new"] = j.entries().size() - j.loaded_entries();
    summary["evaluations_failed"] = j.failed();
  }
  summary["subproblems"] = outcome.front.subproblems;
  summary["failed_subproblems"] = outcome.front.failed_subproblems;
  summary["dominated_subproblems"] = outcome.front.dominated_subproblems;
  if (outcome.single) {
    summary["solver_status"] = outcome.status;
    summary["iterations"] = outcome.single->iterations;
  }
  summary["points"] = front.size();
  summary["objectives"] = objective_list;
  if (!objectives.empty() && m >= 2) {
    const std::vector<double> reference = reference_point_from(objectives);
    std::vector<double> user_reference(m);
    for (std::size_t i = 0; i < m; ++i)
      user_reference[i] = sense_sign(objectives_spec[i].sense) * reference[i];
    summary["reference_point"] = user_reference;
    summary["reference_point_rule"] =
        "front's worst value of each objective moved 10% of the front's range (1 when the "
        "range is 0) further away from the front";
    summary["hypervolume"] = json_number(hypervolume(objectives, reference));
  } else {
    summary["reference_point"] = nullptr;
    summary["hypervolume"] = nullptr;
  }
  summary["knee"] = knee;
  summary["time_seconds"] = outcome.front.seconds;
  summary["wall_seconds"] = facts.wall_seconds;

  write_file_atomically(directory + "/pareto.csv", csv.str());
  write_file_atomically(directory + "/pareto.json", pareto.dump(2) + "\n");
  write_file_atomically(directory + "/summary.json", summary.dump(2) + "\n");
}

}  // namespace pkmopt
