#include "models/pose_analysis.hpp"

#include <algorithm>
#include <memory>

#include "models/hexapod.hpp"
#include "models/hexapod_batch.hpp"

namespace pkmopt {

std::vector<PoseMetrics> analyze_poses(const Machine& machine, std::span<const Pose> poses,
                                       const Wrench& wrench,
                                       std::vector<PoseCompliance>* matrices) {
  const std::size_t n = poses.size();
  std::vector<PoseMetrics> metrics(n);
  if (matrices) matrices->assign(n, PoseCompliance{});
  PoseCompliance* matrices_out = matrices ? matrices->data() : nullptr;
  if (const auto* hexapod = dynamic_cast<const Hexapod*>(&machine)) {
    constexpr std::size_t kSlice = 1024;
#pragma omp parallel for schedule(static)
    for (std::size_t start = 0; start < n; start += kSlice) {
      analyze_hexapod_batch(*hexapod, poses.data() + start, std::min(kSlice, n - start), wrench,
                            metrics.data() + start, HexapodBatchKernel::automatic,
                            matrices_out ? matrices_out + start : nullptr);
    }
  } else {
#pragma omp parallel
    {
      const std::unique_ptr<MachineData> data = machine.make_data();
#pragma omp for schedule(static)
      for (std::size_t i = 0; i < n; ++i) {
        machine.analyze(*data, poses[i], wrench, metrics[i]);
        if (matrices_out) matrices_out[i] = data->matrices;
      }
    }
  }
  return metrics;
}

std::vector<PoseModes> mode_shapes_of_poses(const Machine& machine, std::span<const Pose> poses) {
  const std::size_t n = poses.size();
  std::vector<PoseModes> modes(n);
#pragma omp parallel
  {
    const std::unique_ptr<MachineData> data = machine.make_data();
#pragma omp for schedule(static)
    for (std::size_t i = 0; i < n; ++i) {
      if (!machine.mode_shapes(*data, poses[i], modes[i])) modes[i] = PoseModes{};
    }
  }
  return modes;
}

}  // namespace pkmopt
