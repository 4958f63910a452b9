// The space a machine takes over a task, from its drawing (Machine::sketch): the volume of the
// convex hull of every drawn point (the ends of its lines: legs, guides, the serial axes' travel,
// the tool; its base and platform joints and the TCP) at every pose it can draw, and the area of
// that hull seen from above (its projection on the base's x-y plane). A pose counts when the
// model draws it, reachable or not (a design that misses poses is ranked by the reachability
// row; its drawing there is the model's own, e.g. with legs stretched). For any model with a
// sketch, so structures compare: the drawn machine, not its frame or covers (a lower bound of the
// space it needs).
//
// Example:
//   const SketchEnvelope e = sketch_envelope(machine, task_poses);
//   // e.volume (m^3), e.footprint (m^2), e.drawn poses
#pragma once

#include <cstddef>
#include <vector>

#include "models/core/machine.hpp"
#include "models/core/pose.hpp"

namespace pkmopt {

struct SketchEnvelope {
  double volume = 0.0;     ///< m^3
  double footprint = 0.0;  ///< m^2
  std::size_t drawn = 0;   ///< poses the machine could draw
};

/// The envelope over the poses (the machine draws with its own data).
SketchEnvelope sketch_envelope(const Machine& machine, const std::vector<Pose>& poses);

}  // namespace pkmopt
