#include "models/motion/trajectory_modes.hpp"

namespace pkmopt {
namespace {

constexpr double kSamePose = 1e-6;  // m: a solution this near the sample's pose is the pose

}  // namespace

TrajectoryModes trajectory_assembly_modes(const AllForwardKinematics& solver,
                                          const TrajectoryResult& run) {
  TrajectoryModes out;
  out.samples.resize(run.samples.size());
  const long n = static_cast<long>(run.samples.size());
#pragma omp parallel for schedule(dynamic, 4)
  for (long k = 0; k < n; ++k) {
    const TrajectorySample& sample = run.samples[static_cast<std::size_t>(k)];
    const ForwardSolutions all = solver.all_forward_kinematics(sample.metrics.q, sample.pose);
    AssemblyModeSample& m = out.samples[static_cast<std::size_t>(k)];
    m.real_modes = all.real.size();
    m.failed_paths = all.failed;
    if (k == 0) out.distance_length = all.distance_length;  // rho: the machine's, every sample
    // The solutions come by increasing distance to the sample's pose: the first is the tracked
    // one when it lies within the solutions' accuracy of that pose.
    m.tracked_found = !all.real.empty() && all.real.front().to_reference <= kSamePose;
    m.nearest_other =
        m.tracked_found && !sample.metrics.singular ? all.real.front().nearest_other : 0.0;
  }
  return out;
}

}  // namespace pkmopt
