// The space a machine takes over a task, from its drawing (Machine::sketch): the volume of the
// convex hull of every drawn point (the ends of its lines: legs, guides, the serial axes' travel,
// the tool; its base and platform joints and the TCP) at every pose it can draw, and the area of
// that hull seen from above (its projection on the base's x-y plane). A pose counts when the
// model draws it, reachable or not (a design that misses poses is ranked by the reachability
// row; its drawing there is the model's own, e.g. with legs stretched). For any model with a
// sketch, so structures compare: the drawn machine, not its frame or covers (a lower bound of the
// space it needs).
//
// The same drawing against obstacles: how deep its lines (not the tool's) and joints go into
// them.
// The same drawing against an installation space (models/geometry/installation_space.hpp): how
// far the machine drawn at a pose sticks out of it, over the ends of its lines (segments: a
// convex region holds a segment when it holds both ends), its joints and the TCP.
//
// Example:
//   const SketchEnvelope e = sketch_envelope(machine, task_poses);
//   // e.volume (m^3), e.footprint (m^2), e.drawn poses
//   const std::optional<double> out = sketch_excess(machine, *data, pose, space);  // m, <= 0 in
#pragma once

#include <cstddef>
#include <optional>
#include <vector>

#include "models/core/machine.hpp"
#include "models/core/machine_sketch.hpp"
#include "models/core/pose.hpp"
#include "models/geometry/installation_space.hpp"
#include "models/geometry/obstacle.hpp"

namespace pkmopt {

struct SketchEnvelope {
  double volume = 0.0;     ///< m^3
  double footprint = 0.0;  ///< m^2
  std::size_t drawn = 0;   ///< poses the machine could draw
};

/// The envelope over the poses (the machine draws with its own data).
SketchEnvelope sketch_envelope(const Machine& machine, const std::vector<Pose>& poses);

/// How deep the machine drawn at `pose` goes into the obstacles (m; <= 0 when it keeps out): the
/// largest intrusion (models/geometry/obstacle.hpp) of its lines and joints, except the tool line
/// (from the platform to the TCP, which must reach the work); nullopt when the model does not draw
/// the pose or there are no obstacles.
std::optional<double> sketch_intrusion(const Machine& machine, MachineData& data, const Pose& pose,
                                       const std::vector<ObstacleBox>& obstacles);

/// How far the machine drawn at `pose` sticks out of `space` (m; <= 0 inside); nullopt when the
/// model does not draw the pose. `data` is the machine's (made by machine.make_data()).
/// The overloads on a drawing serve a caller that checks one drawing against both.
std::optional<double> sketch_excess(const Machine& machine, MachineData& data, const Pose& pose,
                                    const InstallationSpace& space);
double sketch_excess(const MachineSketch& sketch, const InstallationSpace& space);
double sketch_intrusion(const MachineSketch& sketch, const std::vector<ObstacleBox>& obstacles);

}  // namespace pkmopt
