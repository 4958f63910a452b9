#include "problems/design/design_metrics.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <utility>

namespace pkmopt {
namespace {

constexpr std::array<std::string_view, kNumDesignMetrics> kMetricNames = {
    "stiffness_min",
    "singularity_margin",
    "leg_force_max",
    "tcp_error_max",
    "workspace_volume",
    "conditioning_index",
    "machine_size",
    "actuator_cost",
    "actuator_overload",
    "tcp_deflection_max",
    "stiffness_min_loaded",
    "natural_frequency_min",
    "moving_mass",
    "actuator_force_dynamic_max",
    "leg_clearance_min",
    "swept_volume",
    "footprint",
    "task_singularity_free",
    "task_margin",
    "drive_cost",
    "drive_overload"};

double metric_sign(Sense sense) { return sense == Sense::maximize ? -1.0 : 1.0; }

std::vector<Eigen::Matrix3d> task_rotations(double tilt, double yaw, double orientation_step) {
  OrientationSet set;
  set.tilt = tilt;
  set.yaw_range = yaw;
  set.orientation_step = orientation_step;
  return sample_orientations(set);
}

}  // namespace

std::string_view design_metric_name(DesignMetric metric) {
  return kMetricNames.at(static_cast<int>(metric));
}

bool is_compliance_metric(DesignMetric metric) {
  return metric == DesignMetric::tcp_deflection_max ||
         metric == DesignMetric::stiffness_min_loaded ||
         metric == DesignMetric::natural_frequency_min;
}

bool is_actuator_metric(DesignMetric metric) {
  return metric == DesignMetric::actuator_cost || metric == DesignMetric::actuator_overload ||
         is_drive_metric(metric);
}

bool is_drive_metric(DesignMetric metric) {
  return metric == DesignMetric::drive_cost || metric == DesignMetric::drive_overload;
}

std::string actuator_metric_mismatch(const std::array<bool, kNumDesignMetrics>& needed,
                                     bool each_drive) {
  for (int m = 0; m < kNumDesignMetrics; ++m) {
    const auto metric = static_cast<DesignMetric>(m);
    if (!needed[m] || !is_actuator_metric(metric) || is_drive_metric(metric) == each_drive)
      continue;
    return each_drive ? fmt::format(
                            "{} prices one entry for the legs; with each_drive: true the "
                            "catalog prices every drive (drive_cost, drive_overload)",
                            kMetricNames[m])
                      : fmt::format(
                            "{} prices every drive: it needs each_drive: true in the {{actuator: "
                            "cheapest, catalog: FILE}} constraint",
                            kMetricNames[m]);
  }
  return {};
}

std::optional<DesignMetric> design_metric_from_name(std::string_view name) {
  for (int m = 0; m < kNumDesignMetrics; ++m)
    if (kMetricNames[m] == name) return static_cast<DesignMetric>(m);
  return std::nullopt;
}

std::vector<Pose> box_task_poses(const Eigen::Vector3d& centre, const Eigen::Vector3d& half_extents,
                                 const Eigen::Vector3i& counts, double tilt, double yaw,
                                 double orientation_step) {
  if ((counts.array() < 1).any()) throw std::invalid_argument("box task: counts must be >= 1");
  const std::vector<Eigen::Matrix3d> rotations = task_rotations(tilt, yaw, orientation_step);
  auto coordinate = [&](int axis, int j) {
    if (counts(axis) == 1) return centre(axis);
    return centre(axis) - half_extents(axis) + 2.0 * half_extents(axis) * j / (counts(axis) - 1);
  };
  std::vector<Pose> poses;
  for (int iz = 0; iz < counts.z(); ++iz)
    for (int iy = 0; iy < counts.y(); ++iy)
      for (int ix = 0; ix < counts.x(); ++ix)
        for (const Eigen::Matrix3d& R : rotations)
          poses.push_back(Pose{{coordinate(0, ix), coordinate(1, iy), coordinate(2, iz)},
                               angles_from_rotation(R)});
  return poses;
}

std::vector<Pose> cylinder_task_poses(const Eigen::Vector3d& centre, double radius, double height,
                                      int rings, int per_ring, int layers, double tilt, double yaw,
                                      double orientation_step) {
  if (rings < 0 || per_ring < 1 || layers < 1)
    throw std::invalid_argument("cylinder task: rings >= 0, per_ring >= 1, layers >= 1");
  const std::vector<Eigen::Matrix3d> rotations = task_rotations(tilt, yaw, orientation_step);
  std::vector<Pose> poses;
  for (int layer = 0; layer < layers; ++layer) {
    const double z =
        layers == 1 ? centre.z() : centre.z() - height / 2.0 + height * layer / (layers - 1);
    std::vector<Eigen::Vector3d> points{{centre.x(), centre.y(), z}};
    for (int ring = 1; ring <= rings; ++ring)
      for (int k = 0; k < per_ring; ++k) {
        const double phi = 2.0 * std::numbers::pi * k / per_ring;
        const double rr = radius * ring / rings;
        points.emplace_back(centre.x() + rr * std::cos(phi), centre.y() + rr * std::sin(phi), z);
      }
    for (const Eigen::Vector3d& p : points)
      for (const Eigen::Matrix3d& R : rotations) poses.push_back(Pose{p, angles_from_rotation(R)});
  }
  return poses;
}

NeededMetrics check_design_goals(const std::string& where,
                                 const std::vector<DesignObjective>& objectives,
                                 const std::vector<DesignConstraint>& constraints,
                                 DesignTask& task) {
  NeededMetrics needed{};
  if (objectives.empty())
    throw std::invalid_argument(where + ": expected at least one objective, found none");
  if (task.poses.empty())
    throw std::invalid_argument(where + ": expected at least one task pose, found none");
  try {
    check_installation_space(task.installation_space);
    for (const ObstacleBox& box : task.obstacles) check_obstacle(box);
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(where + ": task " + e.what());
  }
  for (const DesignObjective& o : objectives) needed[static_cast<int>(o.metric)] = true;
  for (const DesignConstraint& c : constraints) {
    if (!std::isfinite(c.bound))
      throw std::invalid_argument(fmt::format("{}: constraint on {}: expected a finite bound",
                                              where, design_metric_name(c.metric)));
    needed[static_cast<int>(c.metric)] = true;
  }
  if (!(std::isfinite(task.acceleration_max) && task.acceleration_max >= 0.0))
    throw std::invalid_argument(
        fmt::format("{}: task a_max: expected an acceleration in m/s^2 >= 0, found {}", where,
                    task.acceleration_max));
  if (needed[static_cast<int>(DesignMetric::actuator_force_dynamic_max)] &&
      !(task.acceleration_max > 0.0))
    throw std::invalid_argument(fmt::format(
        "{}: actuator_force_dynamic_max needs the task's a_max (m/s^2, e.g. a_max: 9.81 for 1 g), "
        "found none",
        where));
  if (needed[static_cast<int>(DesignMetric::task_singularity_free)] && !task.region)
    throw std::invalid_argument(fmt::format(
        "{}: task_singularity_free needs the task as a region (a box or cylinder task), found "
        "task poses only",
        where));
  if (needed[static_cast<int>(DesignMetric::workspace_volume)] ||
      needed[static_cast<int>(DesignMetric::conditioning_index)]) {
    WorkspaceOptions& w = task.workspace;
    // Maps (a metric evaluation at every inside node) only for the conditioning index.
    w.compliance_maps = false;  // the index needs the singularity margin only
    w.compute_maps = needed[static_cast<int>(DesignMetric::conditioning_index)];
    w.compute_hull = false;
    w.keep_points = false;
    const std::string message = validate(w);
    if (!message.empty()) throw std::invalid_argument(where + ": task workspace: " + message);
  }
  return needed;
}

void TaskWorstCase::add(const PoseMetrics& m) {
  stiffness_min = std::min(stiffness_min, m.stiffness_min);
  singularity_margin = std::min(singularity_margin, m.singularity_margin);
  leg_force_max = std::max(leg_force_max, m.tau.cwiseAbs().maxCoeff());
  tcp_error_max = std::max(tcp_error_max, m.tcp_error_max);
  tcp_deflection_max = std::max(tcp_deflection_max, m.tcp_deflection);
  stiffness_min_loaded = std::min(stiffness_min_loaded, m.stiffness_min_loaded);
  if (m.natural_frequencies.size() > 0)
    natural_frequency_min = std::min(natural_frequency_min, m.natural_frequencies(0));
  leg_clearance_min = std::min(leg_clearance_min, m.leg_clearance);
}

void TaskWorstCase::store(DesignMetrics& metrics) const {
  metrics[static_cast<int>(DesignMetric::stiffness_min)] = stiffness_min;
  metrics[static_cast<int>(DesignMetric::singularity_margin)] = singularity_margin;
  metrics[static_cast<int>(DesignMetric::leg_force_max)] = leg_force_max;
  metrics[static_cast<int>(DesignMetric::tcp_error_max)] = tcp_error_max;
  metrics[static_cast<int>(DesignMetric::tcp_deflection_max)] = tcp_deflection_max;
  metrics[static_cast<int>(DesignMetric::stiffness_min_loaded)] = stiffness_min_loaded;
  // 0 when no pose gave frequencies (the metric was not asked for).
  metrics[static_cast<int>(DesignMetric::natural_frequency_min)] =
      std::isfinite(natural_frequency_min) ? natural_frequency_min : 0.0;
  // 0 without a leg shape (the metric is then refused before any evaluation).
  metrics[static_cast<int>(DesignMetric::leg_clearance_min)] =
      std::isfinite(leg_clearance_min) ? leg_clearance_min : 0.0;
}

void measure_workspace_metrics(const Machine& machine, const WorkspaceOptions& options,
                               const NeededMetrics& needed, DesignMetrics& metrics,
                               std::string& failure) {
  auto need = [&](DesignMetric m) { return needed[static_cast<int>(m)]; };
  auto metric = [&](DesignMetric m) -> double& { return metrics[static_cast<int>(m)]; };
  if (need(DesignMetric::conditioning_index)) {
    // Global conditioning index: mean singularity margin over the inside workspace nodes.
    try {
      const WorkspaceResult workspace = compute_workspace(machine, options);
      metric(DesignMetric::conditioning_index) = workspace.maps.global_conditioning_index;
      if (need(DesignMetric::workspace_volume))
        metric(DesignMetric::workspace_volume) = workspace.volume;
      if (workspace.maps.points == 0 && failure.empty())
        failure = "conditioning index: the workspace has no inside grid node";
    } catch (const std::exception& error) {
      if (failure.empty()) failure = fmt::format("workspace: {}", error.what());
    }
  } else if (need(DesignMetric::workspace_volume)) {
    try {
      metric(DesignMetric::workspace_volume) = workspace_volume(machine, options);
    } catch (const std::exception& error) {
      if (failure.empty()) failure = fmt::format("workspace volume: {}", error.what());
    }
  }
}

void check_finite_metrics(const NeededMetrics& needed, DesignMetrics& metrics,
                          std::string& failure) {
  for (int m = 0; m < kNumDesignMetrics; ++m) {
    if (needed[m] && !std::isfinite(metrics[m])) {
      if (failure.empty()) failure = fmt::format("{} is not finite", kMetricNames[m]);
      metrics[m] = kFailurePenalty;
    }
  }
}

std::vector<double> aggregate_design_rows(const std::vector<DesignObjective>& objectives,
                                          const std::vector<DesignConstraint>& constraints,
                                          bool require_reachable, const DesignMetrics& metrics,
                                          double reach_violation, bool failed) {
  std::vector<double> f;
  f.reserve(objectives.size() + constraints.size() + 1);
  for (const DesignObjective& o : objectives)
    f.push_back(failed ? kFailurePenalty
                       : metric_sign(o.sense) * metrics[static_cast<int>(o.metric)]);
  for (const DesignConstraint& c : constraints) {
    const double value = metrics[static_cast<int>(c.metric)];
    f.push_back(failed ? kFailurePenalty
                       : (c.relation == Relation::less_equal ? value - c.bound : c.bound - value));
  }
  if (require_reachable) f.push_back(failed ? kFailurePenalty : reach_violation);
  return f;
}

namespace {

// The box of the poses' positions (poses not empty): {lo, hi}.
std::pair<Eigen::Vector3d, Eigen::Vector3d> position_box(const std::vector<Pose>& poses) {
  Eigen::Vector3d lo = poses.front().position, hi = lo;
  for (const Pose& pose : poses) {
    lo = lo.cwiseMin(pose.position);
    hi = hi.cwiseMax(pose.position);
  }
  return {lo, hi};
}

// The task's poses moved outwards by d (see task_margin).
bool grown_task_reachable(const Machine& machine, MachineData& data, const std::vector<Pose>& poses,
                          const Eigen::Vector3d& centre, const Eigen::Vector3d& tolerance,
                          double d) {
  for (Pose pose : poses) {
    for (int a = 0; a < 3; ++a) {
      const double off = pose.position(a) - centre(a);
      if (std::abs(off) > tolerance(a)) pose.position(a) += off > 0.0 ? d : -d;
    }
    if (!machine.reachable(data, pose)) return false;
  }
  return true;
}

}  // namespace

double task_margin(const Machine& machine, const std::vector<Pose>& poses, double d_max) {
  if (poses.empty()) return 0.0;
  const auto [lo, hi] = position_box(poses);
  const Eigen::Vector3d centre = 0.5 * (lo + hi);
  const Eigen::Vector3d tolerance = 1e-9 * (hi - lo).cwiseMax(Eigen::Vector3d::Constant(1.0));
  const std::unique_ptr<MachineData> data = machine.make_data();
  if (!grown_task_reachable(machine, *data, poses, centre, tolerance, 0.0)) return 0.0;
  if (grown_task_reachable(machine, *data, poses, centre, tolerance, d_max)) return d_max;
  double good = 0.0, bad = d_max;
  for (int k = 0; k < 16; ++k) {
    const double mid = 0.5 * (good + bad);
    (grown_task_reachable(machine, *data, poses, centre, tolerance, mid) ? good : bad) = mid;
  }
  return good;
}

double task_margin_limit(const std::vector<Pose>& poses) {
  if (poses.empty()) return 0.1;
  const auto [lo, hi] = position_box(poses);
  return std::max(0.1, (hi - lo).maxCoeff());
}

}  // namespace pkmopt
