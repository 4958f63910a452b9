#include "problems/calibration/calibration_candidates.hpp"

#include <memory>

#include "models/core/require.hpp"

namespace pkmopt {

CalibrationCandidates reachable_candidates(const Machine& machine, const std::vector<Pose>& poses,
                                           const std::vector<int>& labels) {
  require(poses.size() == labels.size(), "reachable_candidates: one label per pose needed");
  const std::unique_ptr<MachineData> data = machine.make_data();
  CalibrationCandidates candidates;
  for (std::size_t i = 0; i < poses.size(); ++i) {
    if (!machine.reachable(*data, poses[i])) {
      ++candidates.unreachable;
      continue;
    }
    candidates.poses.push_back(poses[i]);
    candidates.labels.push_back(labels[i]);
  }
  return candidates;
}

CalibrationCandidates grid_candidates(const Machine& machine, const CandidateGrid& grid) {
  require(grid.steps >= 2, "grid_candidates: steps must be >= 2");
  const int n = grid.steps;
  auto level = [&](double lo, double hi, int i) { return lo + (hi - lo) * i / (n - 1); };
  const double r = grid.xy_range;
  const double a = grid.angle_range;
  const std::unique_ptr<MachineData> data = machine.make_data();
  CalibrationCandidates candidates;
  for (int ix = 0; ix < n; ++ix)
    for (int iy = 0; iy < n; ++iy)
      for (int iz = 0; iz < n; ++iz)
        for (int ia = 0; ia < n; ++ia)
          for (int ib = 0; ib < n; ++ib)
            for (int ic = 0; ic < n; ++ic) {
              Pose pose;
              pose.position = {level(-r, r, ix), level(-r, r, iy),
                               level(grid.z_min, grid.z_max, iz)};
              pose.angles = {level(-a, a, ia), level(-a, a, ib), level(-a, a, ic)};
              if (!machine.reachable(*data, pose)) {
                ++candidates.unreachable;
                continue;
              }
              candidates.poses.push_back(pose);
              candidates.labels.push_back(static_cast<int>(candidates.poses.size()));
            }
  return candidates;
}

}  // namespace pkmopt
