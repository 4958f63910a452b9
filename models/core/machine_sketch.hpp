// A machine drawn as lines at a pose: the base joints, the legs with their actuated parts, the
// platform and the tool, in the base frame (m). What a designer recognises on paper, not a
// solid model: joints are points, legs and links are segments.
//
// Machine::sketch(data, pose, out) fills a MachineSketch (models/core/machine.hpp); it returns
// false when the model cannot draw itself or the pose is not one the legs can assemble in (the
// inverse kinematics has no solution). A pose outside the strokes or joint limits is still drawn
// (the sketch shows why it is out of reach); `reachable` says whether it is reachable.
//
//   pkmopt::MachineSketch sketch;
//   if (machine.sketch(*machine.make_data(), pose, sketch)) { /* sketch.lines, ... */ }
#pragma once

#include <Eigen/Core>
#include <vector>

namespace pkmopt {

struct MachineSketch {
  /// What a line is, for its drawing style.
  enum class Part {
    kGuide,     ///< a fixed guide or the travel of a serial axis (base side)
    kActuator,  ///< the actuated part: a leg's stroke, a crank
    kLink,      ///< a passive link of constant length (strut, rod)
    kTool,      ///< from the platform centre to the TCP
  };
  struct Line {
    Eigen::Vector3d from = Eigen::Vector3d::Zero();
    Eigen::Vector3d to = Eigen::Vector3d::Zero();
    Part part = Part::kLink;
    int leg = -1;  ///< 0-based leg (actuator) index; -1 for lines of no leg
  };
  std::vector<Line> lines;
  /// Base-side joints in leg order (an outline of the fixed frame), base frame (m).
  std::vector<Eigen::Vector3d> base_joints;
  /// Platform joints at the pose in leg order, base frame (m).
  std::vector<Eigen::Vector3d> platform_joints;
  Eigen::Vector3d tcp = Eigen::Vector3d::Zero();  ///< the TCP at the pose (m)
  bool reachable = false;                         ///< the pose within the strokes and joint limits
};

}  // namespace pkmopt
