#include "app/study_design.hpp"

#include <fmt/format.h>

#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <sstream>
#include <stdexcept>

#include "app/csv.hpp"
#include "app/input_error.hpp"
#include "app/machine_file.hpp"
#include "app/output_file.hpp"

namespace pkmopt {
namespace {

double positive(const YamlValue& v) {
  const double value = v.as_double();
  if (!(value > 0.0)) v.fail("a number > 0", v.describe());
  return value;
}

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

void read_parameters(const YamlValue& section, HexapodDesignSpec& spec) {
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
      range.lower = v->required("min").as_double() * scale;
      range.upper = v->required("max").as_double() * scale;
      if (!(range.lower < range.upper))
        v->required("max").fail("max > min", v->required("max").describe());
    } else {
      range.lower = range.upper = v->as_double() * scale;
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

void read_machine(const YamlValue& machine, HexapodDesignSpec& spec) {
  machine.check_keys({"model", "parameters", "legs", "joints", "tool", "actuator_error"});
  const YamlValue model = machine.required("model");
  if (model.as_string() != "hexapod") model.fail("'hexapod'", model.describe());
  if (auto v = machine.optional("parameters")) read_parameters(*v, spec);
  HexapodDesign& d = spec.machine_template;
  const YamlValue legs = machine.required("legs");
  legs.check_keys({"axial_stiffness", "E", "area", "actuator_stiffness"});
  d.stiffness = LegStiffness{};
  if (auto v = legs.optional("axial_stiffness")) {
    if (legs.has("E") || legs.has("area"))
      v->fail("either axial_stiffness or E and area, not both");
    d.stiffness.axial_stiffness = positive(*v);
  } else {
    d.stiffness.E = positive(legs.required("E"));
    d.stiffness.area = positive(legs.required("area"));
  }
  if (auto v = legs.optional("actuator_stiffness")) d.stiffness.actuator_stiffness = positive(*v);
  d.joints = HexapodJointLimits{};
  if (auto joints = machine.optional("joints")) {
    joints->check_keys({"base_max_angle_deg", "platform_max_angle_deg"});
    if (auto v = joints->optional("base_max_angle_deg"))
      d.joints.base_max_angle = angle_deg(*v, 1, 179);
    if (auto v = joints->optional("platform_max_angle_deg"))
      d.joints.platform_max_angle = angle_deg(*v, 1, 179);
  }
  d.tcp.setZero();
  if (auto tool = machine.optional("tool")) {
    tool->check_keys({"tcp"});
    const std::vector<double> tcp = tool->required("tcp").as_doubles(3);
    d.tcp = Eigen::Vector3d(tcp[0], tcp[1], tcp[2]);
  }
  if (auto v = machine.optional("actuator_error")) d.actuator_error = positive(*v);
}

void read_task(const YamlValue& task, HexapodDesignSpec& spec) {
  task.check_keys({"region", "orientations", "wrench", "workspace"});
  double tilt = 0.0, yaw = 0.0, step = deg_to_rad(10);
  if (auto o = task.optional("orientations")) {
    o->check_keys({"tilt_deg", "yaw_deg", "step_deg"});
    if (auto v = o->optional("tilt_deg")) tilt = angle_deg(*v, 0, 89);
    if (auto v = o->optional("yaw_deg")) yaw = angle_deg(*v, 0, 179);
    if (auto v = o->optional("step_deg")) step = angle_deg(*v, 0.5, 90);
  }
  const YamlValue region = task.required("region");
  region.expect_map();
  const YamlValue shape = region.required("shape");
  const std::vector<double> c = region.required("centre").as_doubles(3);
  const Eigen::Vector3d centre(c[0], c[1], c[2]);
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
  } else {
    shape.fail("'box' or 'cylinder'", shape.describe());
  }
  if (spec.task.poses.size() > 100000)
    region.fail(fmt::format("at most 100000 task poses, found {}", spec.task.poses.size()));
  spec.task.wrench.setZero();
  if (auto v = task.optional("wrench")) {
    const std::vector<double> w = v->as_doubles(6);
    for (int i = 0; i < 6; ++i) spec.task.wrench(i) = w[i];
  }
  if (auto w = task.optional("workspace")) {
    w->check_keys({"resolution", "tilt_deg", "yaw_deg", "step_deg"});
    if (auto v = w->optional("resolution")) spec.task.workspace.resolution = positive(*v);
    if (auto v = w->optional("tilt_deg"))
      spec.task.workspace.orientations.tilt = angle_deg(*v, 0, 89);
    if (auto v = w->optional("yaw_deg"))
      spec.task.workspace.orientations.yaw_range = angle_deg(*v, 0, 179);
    if (auto v = w->optional("step_deg"))
      spec.task.workspace.orientations.orientation_step = angle_deg(*v, 0.5, 90);
  }
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
  if (auto v = root.optional("description")) v->as_string();
  HexapodDesignSpec spec;
  spec.name = study.name;
  read_machine(root.required("machine"), spec);
  read_task(root.required("task"), spec);

  const YamlValue objectives = root.required("objectives");
  const std::vector<YamlValue> objective_list = objectives.elements();
  if (objective_list.empty()) objectives.fail("a list of at least one objective", "an empty list");
  for (const YamlValue& o : objective_list) {
    o.check_keys({"minimize", "maximize"});
    if (o.keys().size() != 1) o.fail("one of minimize: METRIC or maximize: METRIC", o.describe());
    const bool maximize = o.has("maximize");
    spec.objectives.push_back({read_metric(o.required(maximize ? "maximize" : "minimize")),
                               maximize ? Sense::maximize : Sense::minimize});
  }
  spec.require_reachable = false;
  if (auto constraints = root.optional("constraints")) {
    for (const YamlValue& c : constraints->elements()) {
      if (c.is_scalar()) {
        if (c.as_string() != "task_reachable")
          c.fail("task_reachable or {metric: NAME, max|min: VALUE}", c.describe());
        spec.require_reachable = true;
        continue;
      }
      c.check_keys({"metric", "max", "min"});
      const DesignMetric metric = read_metric(c.required("metric"));
      if (c.has("max") == c.has("min")) c.fail("exactly one of max and min", c.describe());
      const bool upper = c.has("max");
      spec.constraints.push_back({metric, upper ? Relation::less_equal : Relation::greater_equal,
                                  c.required(upper ? "max" : "min").as_double()});
    }
  }
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
  return study;
}

void write_design_outputs(const std::string& directory, const DesignStudy& study,
                          const RunOutcome& outcome, int threads) {
  const HexapodDesignProblem& problem = *study.problem;
  const HexapodDesignSpec& spec = problem.spec();
  // summary.json (and a generic pareto.csv, replaced below) from the benchmark writer.
  write_run_outputs(directory, study.name, problem, study.optimizer, outcome, threads, {}, {});

  std::ostringstream csv;
  csv << "id";
  for (int i : problem.free_parameters()) csv << ',' << design_parameter_name(i);
  for (const DesignObjective& o : spec.objectives) csv << ',' << design_metric_name(o.metric);
  for (const DesignConstraint& c : spec.constraints)
    csv << ",g_" << design_metric_name(c.metric)
        << (c.relation == Relation::less_equal ? "_max" : "_min");
  if (spec.require_reachable) csv << ",g_task_reachable";
  csv << ",feasible,failure\n";
  if (study.write_designs) std::filesystem::create_directories(directory + "/designs");
  for (std::size_t k = 0; k < outcome.front.x.size(); ++k) {
    const std::vector<double>& x = outcome.front.x[k];
    const DesignEvaluation ev = problem.evaluate(std::vector<double>(
        x.begin(), x.begin() + static_cast<std::ptrdiff_t>(problem.free_parameters().size())));
    const std::vector<double> f = problem.aggregate_fitness(ev);
    const std::string id = fmt::format("d{:04}", k);
    csv << id;
    for (int i : problem.free_parameters())
      csv << ','
          << format_number(design_parameter_in_degrees(i) ? rad_to_deg(ev.parameters[i])
                                                          : ev.parameters[i]);
    for (const DesignObjective& o : spec.objectives)
      csv << ',' << format_number(ev.metrics[static_cast<int>(o.metric)]);
    bool feasible = ev.ok();
    for (std::size_t r = spec.objectives.size(); r < f.size(); ++r) {
      csv << ',' << format_number(f[r]);
      feasible = feasible && f[r] <= 0.0;
    }
    csv << ',' << (feasible ? 1 : 0) << ",\"" << ev.failure << "\"\n";
    if (study.write_designs)
      write_file_atomically(directory + "/designs/" + id + ".yaml",
                            hexapod_design_to_yaml(problem.design_of(ev.parameters)));
  }
  write_file_atomically(directory + "/pareto.csv", csv.str());
}

}  // namespace pkmopt
