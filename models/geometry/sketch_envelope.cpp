#include "models/geometry/sketch_envelope.hpp"

#include "models/core/machine_sketch.hpp"
#include "models/workspace/workspace.hpp"

namespace pkmopt {

SketchEnvelope sketch_envelope(const Machine& machine, const std::vector<Pose>& poses) {
  SketchEnvelope out;
  const std::unique_ptr<MachineData> data = machine.make_data();
  std::vector<Eigen::Vector3d> points;
  MachineSketch sketch;
  for (const Pose& pose : poses) {
    sketch = MachineSketch{};
    if (!machine.sketch(*data, pose, sketch)) continue;
    ++out.drawn;
    for (const MachineSketch::Line& line : sketch.lines) {
      points.push_back(line.from);
      points.push_back(line.to);
    }
    points.insert(points.end(), sketch.base_joints.begin(), sketch.base_joints.end());
    points.insert(points.end(), sketch.platform_joints.begin(), sketch.platform_joints.end());
    points.push_back(sketch.tcp);
  }
  out.volume = convex_hull_volume(points);
  out.footprint = footprint_area(points);
  return out;
}

}  // namespace pkmopt
