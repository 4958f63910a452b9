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

void read_task(const YamlValue& task, DesignTask& task_spec, DesignStudy& study,
               std::string& yaml) {
  task.check_keys({"region", "orientations", "wrench", "workspace"});
  TaskOrientationsSection orientations;
  if (auto o = task.optional("orientations")) read_fields(*o, orientations);
  const double tilt_deg = orientations.tilt_deg, yaw_deg = orientations.yaw_deg,
               step_deg = orientations.step_deg;
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
  yaml += "  orientations: " + fields_flow_map(orientations) + "\n";
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
  TaskWorkspaceSection workspace;
  if (auto w = task.optional("workspace")) read_fields(*w, workspace);
  task_spec.workspace.resolution = workspace.resolution;
  task_spec.workspace.orientations.tilt = deg_to_rad(workspace.tilt_deg);
  task_spec.workspace.orientations.yaw_range = deg_to_rad(workspace.yaw_deg);
  task_spec.workspace.orientations.orientation_step = deg_to_rad(workspace.step_deg);
  yaml += "  workspace: " + fields_flow_map(workspace) + "\n";
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
      name_value.fail(fmt::format("a catalog with an entry of stroke at least "
                                  "machine.parameters.stroke ({} m)",
                                  format_number(lo)),
                      fmt::format("catalog '{}' whose longest stroke is {} m", catalog.name,
                                  format_number(longest)));
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

}  // namespace pkmopt::design_study_detail
