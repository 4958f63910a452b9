// The space a machine sweeps over a set of poses: the volume of the convex hull of its parts and
// the area of its footprint (the convex hull of their projection on the base's x-y plane), for
// machine-size objectives that see the task.
//
// The parts are the base joints, the platform joints at every pose and, when the machine file
// gives them (models/geometry/solid_bodies.hpp), the base plate, the platform plate at every pose
// and the tool at every pose; discs and cylinders enter by the 32-gon circumscribed about them (so
// the hull holds them: at most 0.5 % larger in radius). Legs are the segments between the joints:
// the hull of the joints holds their axes (the legs' own radius is not added).
//
// Example:
//   pkmopt::SweptEnvelope e = pkmopt::swept_envelope(hexapod, task_poses);
//   // e.volume (m^3), e.footprint (m^2)
#pragma once

#include <vector>

#include "models/core/pose.hpp"
#include "models/hexapod/hexapod.hpp"
#include "models/workspace/workspace.hpp"  // convex_hull_volume, footprint_area

namespace pkmopt {

struct SweptEnvelope {
  double volume = 0.0;     ///< m^3, convex hull of the parts over the poses
  double footprint = 0.0;  ///< m^2, convex hull of their (x, y) in the base frame
};

/// Appends the outline points of the solids (a disc or cylinder by its circumscribed 32-gon, at
/// both ends) in the base frame, the platform frame at (R, origin).
void solid_outline_points(const MachineBodies& bodies, const Eigen::Matrix3d& R,
                          const Eigen::Vector3d& origin, std::vector<Eigen::Vector3d>& out);

/// The points the hull is built from (base frame), as the file comment says.
std::vector<Eigen::Vector3d> swept_points(const Hexapod& hexapod, const std::vector<Pose>& poses);

/// The hexapod's swept envelope over the poses (CGAL convex_hull_3 and convex_hull_2).
SweptEnvelope swept_envelope(const Hexapod& hexapod, const std::vector<Pose>& poses);

}  // namespace pkmopt
