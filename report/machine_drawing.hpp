// A machine drawn in two orthographic views, as SVG: the front view (base x to the right, z up)
// and the top view (x to the right, y up), side by side at one scale. Drawn from the model's
// sketch at a pose (models/core/machine_sketch.hpp): the base (the outline of its joints, grey),
// the legs (actuated parts orange, passive links dark, guides dashed), the platform (the outline of
// its joints, blue), the tool and the TCP (red); a task box, when given, dashed green.
//
// Used by `pkmopt draw` and by the report, whose drawings of several designs share one scale
// (`bounds`) so that they can be compared side by side.
//
//   const auto machine = pkmopt::load_machine_file("examples/hexapod.yaml");
//   const pkmopt::Pose pose = *pkmopt::drawing_pose(*machine);
//   pkmopt::MachineSketch sketch;
//   machine->sketch(*machine->make_data(), pose, sketch);
//   const std::string svg = pkmopt::machine_svg(sketch, {.title = "hexapod"});
#pragma once

#include <Eigen/Geometry>
#include <optional>
#include <string>

#include "models/core/machine.hpp"

namespace pkmopt {

struct MachineDrawingOptions {
  std::string title = {};  ///< drawn above the views (may be empty)
  /// The region shown (base frame, m); empty: the sketch's own extent (with the task box).
  Eigen::AlignedBox3d bounds = {};
  /// A task box to draw (base frame, m), or empty.
  Eigen::AlignedBox3d task_box = {};
  int view_pixels = 220;   ///< the longer side of each view (px)
  bool standalone = true;  ///< an SVG file (xmlns, XML declaration) or inline in HTML
};

/// The two views of `sketch` (see the header comment).
std::string machine_svg(const MachineSketch& sketch, const MachineDrawingOptions& options);

/// The box holding every point of a sketch (joints, line ends, TCP).
Eigen::AlignedBox3d sketch_bounds(const MachineSketch& sketch);

/// A pose to draw a machine at when none is given: the platform level (R = I) on the vertical
/// through the centroid of the base joints (through the centre of the model's workspace search
/// box when nothing on that vertical is reachable), half way up the reachable part of the
/// vertical (sampled at 400 heights over the search box); nullopt when the model has no search
/// box or nothing on either vertical is reachable.
std::optional<Pose> drawing_pose(const Machine& machine);

}  // namespace pkmopt
