#include "app/study_design.hpp"

#include <fmt/format.h>

#include <cmath>
#include <filesystem>
#include <limits>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>
#include <stdexcept>

#include "app/actuator_catalog_file.hpp"
#include "app/csv.hpp"
#include "app/input_error.hpp"
#include "app/machine_file.hpp"
#include "app/output_file.hpp"
#include "app/task_wrench_file.hpp"
#include "optimizer/indicators.hpp"
#include "pkmopt/version.hpp"

namespace pkmopt {
namespace {

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

std::string num(double v) { return format_number(v); }

std::string triple(const double* v, int n = 3) {
  std::string text;
  for (int i = 0; i < n; ++i) text += (i ? ", " : "") + num(v[i]);
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
                        lo == hi ? num(lo) : fmt::format("{{min: {}, max: {}}}", num(lo), num(hi)));
  }
  if (d.stiffness.axial_stiffness > 0.0)
    yaml += fmt::format("  legs: {{axial_stiffness: {}", num(d.stiffness.axial_stiffness));
  else
    yaml += fmt::format("  legs: {{E: {}, area: {}", num(d.stiffness.E), num(d.stiffness.area));
  if (d.stiffness.actuator_stiffness > 0.0)
    yaml += fmt::format(", actuator_stiffness: {}", num(d.stiffness.actuator_stiffness));
  yaml += "}\n";
  std::string joints;
  if (std::isfinite(d.joints.base_max_angle))
    joints += fmt::format("base_max_angle_deg: {}", num(base_deg));
  if (std::isfinite(d.joints.platform_max_angle))
    joints +=
        fmt::format("{}platform_max_angle_deg: {}", joints.empty() ? "" : ", ", num(platform_deg));
  const bool unlimited =
      !std::isfinite(d.joints.base_max_angle) || !std::isfinite(d.joints.platform_max_angle);
  yaml += "  joints: {" + joints + "}" + (unlimited ? "  # a missing limit: unlimited" : "") + "\n";
  const double tcp[3] = {d.tcp.x(), d.tcp.y(), d.tcp.z()};
  yaml += "  tool: {tcp: " + triple(tcp) + "}\n";
  yaml += "  actuator_error: " + num(d.actuator_error) + "\n";
}

void read_task(const YamlValue& task, HexapodDesignSpec& spec, DesignStudy& study,
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
    spec.task.poses = box_task_poses(centre, 0.5 * Eigen::Vector3d(size[0], size[1], size[2]),
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
    spec.task.poses =
        cylinder_task_poses(centre, radius, height, rings, per_ring, layers, tilt, yaw, step);
    study.task_positions = static_cast<std::size_t>((1 + rings * per_ring) * layers);
    yaml += fmt::format(
        "  region: {{shape: cylinder, centre: {}, radius: {}, height: {}, rings: {}, per_ring: "
        "{}, layers: {}}}\n",
        triple(c.data()), num(radius), num(height), rings, per_ring, layers);
  } else {
    shape.fail("'box' or 'cylinder'", shape.describe());
  }
  if (spec.task.poses.size() > 100000)
    region.fail(fmt::format("at most 100000 task poses, found {}", spec.task.poses.size()));
  yaml += fmt::format("  orientations: {{tilt_deg: {}, yaw_deg: {}, step_deg: {}}}\n",
                      num(tilt_deg), num(yaw_deg), num(step_deg));
  spec.task.wrench.setZero();
  std::string wrench_origin;
  if (auto v = task.optional("wrench")) {
    const TaskWrench task_wrench = read_task_wrench(*v);  // a list, or a turning/milling model
    spec.task.wrench = task_wrench.wrench;
    wrench_origin = task_wrench.origin;
  }
  const double wrench[6] = {spec.task.wrench(0), spec.task.wrench(1), spec.task.wrench(2),
                            spec.task.wrench(3), spec.task.wrench(4), spec.task.wrench(5)};
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
  spec.task.workspace.resolution = resolution;
  spec.task.workspace.orientations.tilt = deg_to_rad(ws_tilt);
  spec.task.workspace.orientations.yaw_range = deg_to_rad(ws_yaw);
  spec.task.workspace.orientations.orientation_step = deg_to_rad(ws_step);
  yaml += fmt::format("  workspace: {{resolution: {}, tilt_deg: {}, yaw_deg: {}, step_deg: {}}}\n",
                      num(resolution), num(ws_tilt), num(ws_yaw), num(ws_step));
}

DesignMetric read_metric(const YamlValue& v) {
  const std::optional<DesignMetric> metric = design_metric_from_name(v.as_string());
  if (!metric)
    v.fail(
        "one of stiffness_min, singularity_margin, leg_force_max, tcp_error_max, "
        "workspace_volume, conditioning_index, machine_size",
        v.describe());
  return *metric;
}

// {actuator: NAME, catalog: FILE}: the legs are that catalog entry. Adds leg_force_max <= its
// force rating and caps the stroke parameter at its stroke. Returns the resolved YAML line
// (catalog path made absolute so that study.resolved.yaml loads from anywhere).
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
  const ActuatorEntry* entry = find_actuator(catalog, name);
  if (entry == nullptr) {
    std::string names;
    for (const ActuatorEntry& e : catalog.entries) names += (names.empty() ? "" : ", ") + e.name;
    name_value.fail(fmt::format("an entry of catalog '{}' ({})", catalog.name, names),
                    "'" + name + "'");
  }
  spec.constraints.push_back({DesignMetric::leg_force_max, Relation::less_equal, entry->max_force});
  int stroke = -1;
  for (int i = 0; i < kNumDesignParameters; ++i) {
    if (design_parameter_name(i) == "stroke") stroke = i;
  }
  auto& [lo, hi] = study.parameter_ranges[static_cast<std::size_t>(stroke)];
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
                     num(entry->max_force), num(entry->stroke));
}

}  // namespace

bool is_design_study_file(const std::string& path) {
  const YamlValue root = YamlValue::load_file(path);
  return root.is_map() && root.has("machine");
}

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
  HexapodDesignSpec spec;
  spec.name = study.name;
  read_machine(root.required("machine"), spec, study, yaml);
  read_task(root.required("task"), spec, study, yaml);

  const YamlValue objectives = root.required("objectives");
  const std::vector<YamlValue> objective_list = objectives.elements();
  if (objective_list.empty()) objectives.fail("a list of at least one objective", "an empty list");
  yaml += "objectives:\n";
  for (const YamlValue& o : objective_list) {
    o.check_keys({"minimize", "maximize"});
    if (o.keys().size() != 1) o.fail("one of minimize: METRIC or maximize: METRIC", o.describe());
    const bool maximize = o.has("maximize");
    spec.objectives.push_back({read_metric(o.required(maximize ? "maximize" : "minimize")),
                               maximize ? Sense::maximize : Sense::minimize});
    yaml += fmt::format("  - {}: {}\n", maximize ? "maximize" : "minimize",
                        design_metric_name(spec.objectives.back().metric));
  }
  spec.require_reachable = false;
  std::string constraint_yaml;
  if (auto constraints = root.optional("constraints")) {
    for (const YamlValue& c : constraints->elements()) {
      if (c.is_scalar()) {
        if (c.as_string() != "task_reachable")
          c.fail(
              "task_reachable, {metric: NAME, max|min: VALUE} or {actuator: NAME, catalog: FILE}",
              c.describe());
        spec.require_reachable = true;
        continue;
      }
      if (c.has("actuator")) {
        constraint_yaml += read_actuator_constraint(c, path, spec, study);
        continue;
      }
      c.check_keys({"metric", "max", "min"});
      const DesignMetric metric = read_metric(c.required("metric"));
      if (c.has("max") == c.has("min")) c.fail("exactly one of max and min", c.describe());
      const bool upper = c.has("max");
      spec.constraints.push_back({metric, upper ? Relation::less_equal : Relation::greater_equal,
                                  c.required(upper ? "max" : "min").as_double()});
      constraint_yaml += fmt::format("  - {{metric: {}, {}: {}}}\n", design_metric_name(metric),
                                     upper ? "max" : "min", num(spec.constraints.back().bound));
    }
  }
  if (spec.require_reachable) constraint_yaml = "  - task_reachable\n" + constraint_yaml;
  yaml += constraint_yaml.empty() ? "constraints: []\n" : "constraints:\n" + constraint_yaml;
  const YamlValue optimizer = root.required("optimizer");
  optimizer.expect_map();
  const std::string algorithm = optimizer.required("algorithm").as_string();
  spec.formulation =
      algorithm == "nsga2" ? DesignFormulation::aggregate : DesignFormulation::smooth;
  try {
    study.problem = std::make_unique<HexapodDesignProblem>(std::move(spec));
  } catch (const std::invalid_argument& error) {
    root.fail(error.what());
  }
  study.optimizer = read_optimizer_section(optimizer, *study.problem);
  if (auto output = root.optional("output")) {
    output->check_keys({"designs"});
    if (auto v = output->optional("designs")) study.write_designs = v->as_bool();
  }
  yaml += "optimizer: " + optimizer_section_yaml(study.optimizer) + "\n";
  yaml += fmt::format("output: {{designs: {}}}\n", study.write_designs ? "true" : "false");
  study.resolved_yaml = yaml;
  return study;
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
    case DesignMetric::singularity_margin:
    case DesignMetric::conditioning_index:
      return "";
  }
  return "";
}

namespace {

double parameter_in_file_units(int i, double value) {
  return design_parameter_in_degrees(i) ? rad_to_deg(value) : value;
}

double sense_sign(Sense sense) { return sense == Sense::maximize ? -1.0 : 1.0; }

std::vector<std::string> constraint_names(const HexapodDesignSpec& spec) {
  std::vector<std::string> names;
  for (const DesignConstraint& c : spec.constraints)
    names.push_back(fmt::format("g_{}_{}", design_metric_name(c.metric),
                                c.relation == Relation::less_equal ? "max" : "min"));
  if (spec.require_reachable) names.emplace_back("g_task_reachable");
  return names;
}

}  // namespace

JournalOptions design_journal_options(const DesignStudy& study) {
  const HexapodDesignProblem& problem = *study.problem;
  const HexapodDesignSpec& spec = problem.spec();
  const bool aggregate = spec.formulation == DesignFormulation::aggregate;
  JournalOptions options;
  std::string header = "index";
  for (int i : problem.free_parameters()) header += fmt::format(",{}", design_parameter_name(i));
  for (const DesignObjective& o : spec.objectives)
    header += fmt::format(",{}", design_metric_name(o.metric));
  if (aggregate)
    for (const std::string& name : constraint_names(spec)) header += "," + name;
  else
    header += ",g_max";
  header += ",feasible,failure";
  options.csv_header = header;
  const HexapodDesignProblem* p = &problem;
  if (aggregate)
    options.evaluate = [p](const std::vector<double>& x) {
      const DesignEvaluation ev = p->evaluate(x);
      JournalEntry entry;
      entry.fitness = p->aggregate_fitness(ev);
      entry.note = ev.failure;
      return entry;
    };
  options.csv_row = [p, aggregate](std::size_t index, const JournalEntry& e) {
    const HexapodDesignSpec& s = p->spec();
    std::string row = std::to_string(index);
    const std::array<double, kNumDesignParameters> parameters = p->parameters_of(e.x);
    for (int i : p->free_parameters())
      row += "," + format_number(parameter_in_file_units(i, parameters[i]));
    const bool failed = !e.note.empty();
    bool feasible = !failed;
    for (std::size_t k = 0; k < s.objectives.size(); ++k) {
      const double f = e.fitness[k];
      feasible = feasible && std::isfinite(f);
      row += failed || !std::isfinite(f)
                 ? ","
                 : "," + format_number(sense_sign(s.objectives[k].sense) * f);
    }
    double g_max = -std::numeric_limits<double>::infinity();
    for (std::size_t r = s.objectives.size(); r < e.fitness.size(); ++r) {
      const double g = e.fitness[r];
      feasible = feasible && g <= 0.0;
      g_max = std::max(g_max, g);
      if (aggregate) row += failed || !std::isfinite(g) ? "," : "," + format_number(g);
    }
    if (!aggregate)
      row += e.fitness.size() == s.objectives.size() || !std::isfinite(g_max)
                 ? ","
                 : "," + format_number(g_max);
    row += feasible ? ",1," : ",0,";
    row += csv_field(e.note);
    return row;
  };
  return options;
}

namespace {

struct FrontDesign {
  std::vector<double> x;
  DesignEvaluation evaluation;
  std::vector<double> aggregate;  // [objectives internal | constraint rows]
};

nlohmann::json json_number(double value) {
  return std::isfinite(value) ? nlohmann::json(value) : nlohmann::json(nullptr);
}

}  // namespace

void write_design_outputs(const std::string& directory, const DesignStudy& study,
                          const RunOutcome& outcome, const DesignRunFacts& facts) {
  namespace fs = std::filesystem;
  const HexapodDesignProblem& problem = *study.problem;
  const HexapodDesignSpec& spec = problem.spec();
  const std::size_t n_free = problem.free_parameters().size();
  const std::size_t m = spec.objectives.size();
  const bool home_free = !spec.parameters[kHomeHeight].fixed();

  // Re-measure the front designs (aggregate metrics in user units for every formulation); a
  // failed design never enters the front.
  std::vector<FrontDesign> front(outcome.front.x.size());
  const long long count = static_cast<long long>(front.size());
#pragma omp parallel for num_threads(resolve_thread_count(facts.threads)) schedule(dynamic)
  for (long long k = 0; k < count; ++k) {
    FrontDesign& d = front[static_cast<std::size_t>(k)];
    const std::vector<double>& x = outcome.front.x[static_cast<std::size_t>(k)];
    d.x = x;
    d.evaluation = problem.evaluate(x);
    d.aggregate = problem.aggregate_fitness(d.evaluation);
  }
  std::erase_if(front, [](const FrontDesign& d) { return !d.evaluation.ok(); });
  ObjectiveSet objectives;  // internal (minimised) sign
  for (const FrontDesign& d : front)
    objectives.emplace_back(d.aggregate.begin(),
                            d.aggregate.begin() + static_cast<std::ptrdiff_t>(m));
  const std::vector<std::string> g_names = constraint_names(spec);
  auto id_of = [](std::size_t k) { return fmt::format("d{:04}", k); };

  // pareto.csv
  std::ostringstream csv;
  csv << "id";
  for (int i : problem.free_parameters()) csv << ',' << design_parameter_name(i);
  if (!home_free) csv << ",home_height";
  for (const DesignObjective& o : spec.objectives) csv << ',' << design_metric_name(o.metric);
  for (const std::string& g : g_names) csv << ',' << g;
  csv << ",feasible,failure\n";
  if (study.write_designs) fs::create_directories(fs::path(directory) / "designs");
  nlohmann::json designs = nlohmann::json::array();
  for (std::size_t k = 0; k < front.size(); ++k) {
    const FrontDesign& d = front[k];
    const DesignEvaluation& ev = d.evaluation;
    const std::string id = id_of(k);
    nlohmann::json design;
    design["id"] = id;
    csv << id;
    nlohmann::json parameters = nlohmann::json::object();
    for (int i : problem.free_parameters()) {
      const double value = parameter_in_file_units(i, ev.parameters[i]);
      csv << ',' << format_number(value);
      parameters[std::string(design_parameter_name(i))] = json_number(value);
    }
    if (!home_free) csv << ',' << format_number(ev.parameters[kHomeHeight]);
    design["parameters"] = parameters;
    design["home_height"] = json_number(ev.parameters[kHomeHeight]);
    nlohmann::json objective_values = nlohmann::json::object();
    for (const DesignObjective& o : spec.objectives) {
      const double value = ev.metrics[static_cast<int>(o.metric)];
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
    design["feasible"] = feasible;
    csv << ',' << (feasible ? 1 : 0) << ",\"\"\n";
    if (study.write_designs) {
      write_file_atomically(directory + "/designs/" + id + ".yaml",
                            hexapod_design_to_yaml(problem.design_of(ev.parameters)));
      design["machine_file"] = "designs/" + id + ".yaml";
    }
    designs.push_back(design);
  }
  (void)n_free;

  // pareto.json (pkmopt-pareto-1, /work/helper/PARETO_JSON.md)
  nlohmann::json pareto;
  pareto["format"] = "pkmopt-pareto-1";
  pareto["pkmopt_version"] = kVersion;
  pareto["study"] = study.name;
  pareto["description"] = study.description;
  pareto["model"] = "hexapod";
  nlohmann::json parameter_list = nlohmann::json::array();
  nlohmann::json fixed = nlohmann::json::object();
  for (int i = 0; i < kNumDesignParameters; ++i) {
    const auto [lo, hi] = study.parameter_ranges[i];
    const std::string name(design_parameter_name(i));
    if (spec.parameters[i].fixed())
      fixed[name] = lo;
    else
      parameter_list.push_back({{"name", name},
                                {"unit", design_parameter_in_degrees(i) ? "deg" : "m"},
                                {"min", lo},
                                {"max", hi}});
  }
  pareto["parameters"] = parameter_list;
  pareto["fixed_parameters"] = fixed;
  nlohmann::json objective_list = nlohmann::json::array();
  for (const DesignObjective& o : spec.objectives)
    objective_list.push_back({{"name", design_metric_name(o.metric)},
                              {"sense", o.sense == Sense::maximize ? "maximize" : "minimize"},
                              {"unit", design_metric_unit(o.metric)}});
  pareto["objectives"] = objective_list;
  nlohmann::json constraint_list = nlohmann::json::array();
  for (std::size_t r = 0; r < spec.constraints.size(); ++r) {
    const DesignConstraint& c = spec.constraints[r];
    constraint_list.push_back({{"name", g_names[r]},
                               {"metric", design_metric_name(c.metric)},
                               {"kind", c.relation == Relation::less_equal ? "max" : "min"},
                               {"bound", c.bound},
                               {"unit", design_metric_unit(c.metric)}});
  }
  if (spec.require_reachable)
    constraint_list.push_back({{"name", "g_task_reachable"},
                               {"metric", "task_reachable"},
                               {"kind", "reachable"},
                               {"bound", 0},
                               {"unit", ""}});
  pareto["constraints"] = constraint_list;
  pareto["task"] = {
      {"centre", study.task_centre},
      {"wrench", std::vector<double>(spec.task.wrench.data(), spec.task.wrench.data() + 6)},
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
  summary["model"] = "hexapod";
  summary["version"] = kVersion;
  summary["algorithm"] = study.optimizer.algorithm;
  summary["formulation"] =
      spec.formulation == DesignFormulation::aggregate ? "aggregate" : "smooth";
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
      user_reference[i] = sense_sign(spec.objectives[i].sense) * reference[i];
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
