#include "models/geometry/sketch_envelope.hpp"

#include <algorithm>
#include <limits>

#include "models/core/machine_sketch.hpp"
#include "models/workspace/workspace.hpp"

namespace pkmopt {

namespace {

// Appends every point of the drawing at `pose`; false when the model does not draw it.
bool add_sketch_points(const Machine& machine, MachineData& data, const Pose& pose,
                       std::vector<Eigen::Vector3d>& points) {
  MachineSketch sketch;
  if (!machine.sketch(data, pose, sketch)) return false;
  for (const MachineSketch::Line& line : sketch.lines) {
    points.push_back(line.from);
    points.push_back(line.to);
  }
  points.insert(points.end(), sketch.base_joints.begin(), sketch.base_joints.end());
  points.insert(points.end(), sketch.platform_joints.begin(), sketch.platform_joints.end());
  points.push_back(sketch.tcp);
  return true;
}

}  // namespace

SketchEnvelope sketch_envelope(const Machine& machine, const std::vector<Pose>& poses) {
  SketchEnvelope out;
  const std::unique_ptr<MachineData> data = machine.make_data();
  std::vector<Eigen::Vector3d> points;
  for (const Pose& pose : poses)
    if (add_sketch_points(machine, *data, pose, points)) ++out.drawn;
  out.volume = convex_hull_volume(points);
  out.footprint = footprint_area(points);
  return out;
}

double sketch_intrusion(const MachineSketch& sketch, const std::vector<ObstacleBox>& obstacles) {
  double deepest = -std::numeric_limits<double>::infinity();
  for (const ObstacleBox& box : obstacles) {
    for (const MachineSketch::Line& line : sketch.lines)
      if (line.part != MachineSketch::Part::kTool)
        deepest = std::max(deepest, intrusion(box, line.from, line.to));
    for (const Eigen::Vector3d& p : sketch.base_joints) deepest = std::max(deepest, depth(box, p));
    for (const Eigen::Vector3d& p : sketch.platform_joints)
      deepest = std::max(deepest, depth(box, p));
  }
  return deepest;
}

std::optional<double> sketch_intrusion(const Machine& machine, MachineData& data, const Pose& pose,
                                       const std::vector<ObstacleBox>& obstacles) {
  if (obstacles.empty()) return std::nullopt;
  MachineSketch sketch;
  if (!machine.sketch(data, pose, sketch)) return std::nullopt;
  return sketch_intrusion(sketch, obstacles);
}

double sketch_excess(const MachineSketch& sketch, const InstallationSpace& space) {
  double excess = space.excess(sketch.tcp, 0.0);
  for (const MachineSketch::Line& line : sketch.lines)
    excess = std::max({excess, space.excess(line.from, 0.0), space.excess(line.to, 0.0)});
  for (const Eigen::Vector3d& p : sketch.base_joints)
    excess = std::max(excess, space.excess(p, 0.0));
  for (const Eigen::Vector3d& p : sketch.platform_joints)
    excess = std::max(excess, space.excess(p, 0.0));
  return excess;
}

std::optional<double> sketch_excess(const Machine& machine, MachineData& data, const Pose& pose,
                                    const InstallationSpace& space) {
  MachineSketch sketch;
  if (!machine.sketch(data, pose, sketch)) return std::nullopt;
  return sketch_excess(sketch, space);
}

}  // namespace pkmopt
