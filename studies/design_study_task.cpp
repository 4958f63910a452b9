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
#include "io/design/task_wrench_file.hpp"
#include "io/format/csv.hpp"
#include "io/format/input_error.hpp"
#include "io/format/output_file.hpp"
#include "io/machine/machine_file.hpp"
#include "models/workspace/mode_certificate.hpp"
#include "optimizer/indicators.hpp"
#include "pkmopt/version.hpp"
#include "studies/design_study_sections.hpp"

namespace pkmopt::design_study_detail {
namespace {

// installation_space: {box: {min: [x, y, z], max: [x, y, z]}} or
// {cylinder: {radius: R, z_min: a, z_max: b, centre: [x, y]}} (m, base frame).
void read_installation_space(const YamlValue& value, InstallationSpace& space) {
  value.check_keys({"box", "cylinder"});
  if (value.has("box") == value.has("cylinder"))
    value.fail("exactly one of 'box' and 'cylinder'", value.describe());
  if (auto box = value.optional("box")) {
    box->check_keys({"min", "max"});
    const auto lo = box->required("min").as_lengths(3), hi = box->required("max").as_lengths(3);
    space.kind = InstallationSpace::Kind::kBox;
    space.min = {lo[0], lo[1], lo[2]};
    space.max = {hi[0], hi[1], hi[2]};
    for (int a = 0; a < 3; ++a) {
      if (!(space.max(a) > space.min(a)))
        box->required("max").fail("max > min on every axis (m)", box->required("max").describe());
    }
  } else {
    const YamlValue c = value.required("cylinder");
    c.check_keys({"radius", "z_min", "z_max", "centre"});
    space.kind = InstallationSpace::Kind::kCylinder;
    space.radius = c.required("radius").as_positive_length();
    space.z_min = c.required("z_min").as_length();
    space.z_max = c.required("z_max").as_length();
    if (!(space.z_max > space.z_min))
      c.required("z_max").fail("a number > z_min (m)", c.required("z_max").describe());
    if (auto centre = c.optional("centre")) {
      const auto xy = centre->as_lengths(2);
      space.centre = {xy[0], xy[1]};
    }
  }
}

// The space moved by a synthesis structure's placement (its task centre), as the region is.
void place_installation_space(InstallationSpace& space, const std::array<double, 3>& placement) {
  const Eigen::Vector3d shift(placement[0], placement[1], placement[2]);
  space.min += shift;
  space.max += shift;
  space.centre += shift.head<2>();
  space.z_min += shift.z();
  space.z_max += shift.z();
}

// obstacles: a list of {box: {min: [x, y, z], max: [x, y, z]}} (m, base frame), each moved by
// the placement.
void read_obstacles(const YamlValue& value, std::vector<ObstacleBox>& obstacles,
                    const std::array<double, 3>& placement) {
  const std::vector<YamlValue> items = value.elements();
  if (items.empty())
    value.fail("a list of at least one obstacle {box: {min, max}}", "an empty list");
  for (const YamlValue& item : items) {
    item.check_keys({"box"});
    const YamlValue box = item.required("box");
    box.check_keys({"min", "max"});
    const auto lo = box.required("min").as_lengths(3), hi = box.required("max").as_lengths(3);
    ObstacleBox o;
    for (int a = 0; a < 3; ++a) {
      o.min(a) = lo[static_cast<std::size_t>(a)] + placement[static_cast<std::size_t>(a)];
      o.max(a) = hi[static_cast<std::size_t>(a)] + placement[static_cast<std::size_t>(a)];
      if (!(hi[static_cast<std::size_t>(a)] > lo[static_cast<std::size_t>(a)]))
        box.required("max").fail("max > min on every axis (m)", box.required("max").describe());
    }
    obstacles.push_back(o);
  }
}

std::string obstacles_yaml(const std::vector<ObstacleBox>& obstacles) {
  std::string t = "[";
  for (const ObstacleBox& o : obstacles)
    t +=
        fmt::format("{}{{box: {{min: [{}, {}, {}], max: [{}, {}, {}]}}}}", t.size() > 1 ? ", " : "",
                    format_number(o.min.x()), format_number(o.min.y()), format_number(o.min.z()),
                    format_number(o.max.x()), format_number(o.max.y()), format_number(o.max.z()));
  return t + "]";
}

std::string installation_space_yaml(const InstallationSpace& s) {
  auto list = [](std::initializer_list<double> v) {
    std::string t = "[";
    for (double x : v) t += (t.size() > 1 ? ", " : "") + format_number(x);
    return t + "]";
  };
  if (s.kind == InstallationSpace::Kind::kBox)
    return "{box: {min: " + list({s.min.x(), s.min.y(), s.min.z()}) +
           ", max: " + list({s.max.x(), s.max.y(), s.max.z()}) + "}}";
  return "{cylinder: {radius: " + format_number(s.radius) + ", z_min: " + format_number(s.z_min) +
         ", z_max: " + format_number(s.z_max) + ", centre: " + list({s.centre.x(), s.centre.y()}) +
         "}}";
}

// The task as a region of poses: positions lo..hi times the orientation set (the region
// task_singularity_free certifies).
PoseBox task_region(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi,
                    const OrientationSet& set) {
  PoseBox box = orientation_box(set);
  box.position_lo = lo;
  box.position_hi = hi;
  return box;
}

}  // namespace

void read_task(const YamlValue& task, DesignTask& task_spec, DesignStudy& study, std::string& yaml,
               const std::array<double, 3>& placement) {
  task.check_keys({"region", "orientations", "wrench", "a_max", "workspace", "installation_space",
                   "obstacles"});
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
  yaml += "task:\n";
  // The count is checked before the poses are made (1000^3 points or a 0.01 deg step over a
  // wide cone would exhaust memory).
  OrientationSet orientation_set;
  orientation_set.tilt = tilt;
  orientation_set.yaw_range = yaw;
  orientation_set.orientation_step = step;
  const double orientations_per_position = static_cast<double>(orientation_count(orientation_set));
  if (shape.as_string() == "box") {
    BoxRegionSection box;
    read_fields(region, box);
    for (int a = 0; a < 3; ++a) box.centre[a] += placement[a];
    const Eigen::Vector3d centre(box.centre[0], box.centre[1], box.centre[2]);
    const Eigen::Vector3i counts(box.points[0], box.points[1], box.points[2]);
    const double total = static_cast<double>(box.points[0]) * box.points[1] * box.points[2] *
                         orientations_per_position;
    if (total > 100000)
      region.fail(
          fmt::format("at most 100000 task poses (points × orientations), found {:.0f}", total));
    task_spec.poses =
        box_task_poses(centre, 0.5 * Eigen::Vector3d(box.size[0], box.size[1], box.size[2]), counts,
                       tilt, yaw, step);
    study.task_centre = box.centre;
    study.task_positions = static_cast<std::size_t>(counts.prod());
    const Eigen::Vector3d half = 0.5 * Eigen::Vector3d(box.size[0], box.size[1], box.size[2]);
    task_spec.region = task_region(centre - half, centre + half, orientation_set);
    yaml += "  region: {shape: box, " + fields_flow_map(box).substr(1) + "\n";
  } else if (shape.as_string() == "cylinder") {
    CylinderRegionSection cylinder;
    read_fields(region, cylinder);
    for (int a = 0; a < 3; ++a) cylinder.centre[a] += placement[a];
    const Eigen::Vector3d centre(cylinder.centre[0], cylinder.centre[1], cylinder.centre[2]);
    const double total = (1.0 + static_cast<double>(cylinder.rings) * cylinder.per_ring) *
                         cylinder.layers * orientations_per_position;
    if (total > 100000)
      region.fail(
          fmt::format("at most 100000 task poses (points × orientations), found {:.0f}", total));
    task_spec.poses = cylinder_task_poses(centre, cylinder.radius, cylinder.height, cylinder.rings,
                                          cylinder.per_ring, cylinder.layers, tilt, yaw, step);
    study.task_centre = cylinder.centre;
    study.task_region = "cylinder";
    // The cylinder's bounding box: a region a little larger than the task.
    const Eigen::Vector3d half(cylinder.radius, cylinder.radius, 0.5 * cylinder.height);
    task_spec.region = task_region(centre - half, centre + half, orientation_set);
    study.task_positions =
        static_cast<std::size_t>((1 + cylinder.rings * cylinder.per_ring) * cylinder.layers);
    yaml += "  region: {shape: cylinder, " + fields_flow_map(cylinder).substr(1) + "\n";
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
    study.task_wrench_origin = wrench_origin.empty() ? "as typed" : wrench_origin;
  }
  const std::vector<double> wrench(task_spec.wrench.data(), task_spec.wrench.data() + 6);
  if (!wrench_origin.empty()) yaml += "  # wrench from the cutting model: " + wrench_origin + "\n";
  yaml += "  wrench: " + field_detail::value_text(wrench) + "\n";
  if (auto a = task.optional("a_max")) {
    // The TCP acceleration the drives are sized for (m/s^2): actuator_force_dynamic_max.
    task_spec.acceleration_max = a->as_positive();
    yaml += "  a_max: " + format_number(task_spec.acceleration_max) + "\n";
  }
  if (auto space = task.optional("installation_space")) {
    read_installation_space(*space, task_spec.installation_space);
    place_installation_space(task_spec.installation_space, placement);
    yaml += "  installation_space: " + installation_space_yaml(task_spec.installation_space) + "\n";
  }
  if (auto obstacles = task.optional("obstacles")) {
    read_obstacles(*obstacles, task_spec.obstacles, placement);
    yaml += "  obstacles: " + obstacles_yaml(task_spec.obstacles) + "\n";
  }
  TaskWorkspaceSection workspace;
  if (auto w = task.optional("workspace")) read_fields(*w, workspace);
  task_spec.workspace.resolution = workspace.resolution;
  task_spec.workspace.orientations.tilt = deg_to_rad(workspace.tilt_deg);
  task_spec.workspace.orientations.yaw_range = deg_to_rad(workspace.yaw_deg);
  task_spec.workspace.orientations.orientation_step = deg_to_rad(workspace.step_deg);
  yaml += "  workspace: " + fields_flow_map(workspace) + "\n";
}

const std::string& metric_names_text() {
  static const std::string text = [] {
    std::string names;
    for (int m = 0; m < kNumDesignMetrics; ++m)
      names += (m == 0 ? "one of " : ", ") +
               std::string(design_metric_name(static_cast<DesignMetric>(m)));
    return names;
  }();
  return text;
}

FieldChoice<int> metric_choice(int& member) {
  FieldChoice<int> choice{member, {}};
  for (int m = 0; m < kNumDesignMetrics; ++m)
    choice.options.emplace_back(design_metric_name(static_cast<DesignMetric>(m)), m);
  return choice;
}

}  // namespace pkmopt::design_study_detail
