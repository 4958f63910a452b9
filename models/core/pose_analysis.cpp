#include "models/core/pose_analysis.hpp"

#include <omp.h>

#include <algorithm>
#include <exception>
#include <memory>

#include "models/core/capabilities.hpp"
#include "models/core/require.hpp"

namespace pkmopt {

std::vector<PoseMetrics> analyze_poses(const Machine& machine, std::span<const Pose> poses,
                                       const Wrench& wrench,
                                       std::vector<PoseCompliance>* matrices) {
  const std::size_t n = poses.size();
  std::vector<PoseMetrics> metrics(n);
  if (matrices) matrices->assign(n, PoseCompliance{});
  analyze_pose_slices(
      machine, n, wrench, matrices != nullptr, 0,
      [&](const PoseSlice& s) {
        std::copy_n(poses.begin() + static_cast<std::ptrdiff_t>(s.start), s.poses.size(),
                    s.poses.begin());
      },
      [&](const PoseSlice& s) {
        for (std::size_t k = 0; k < s.metrics.size(); ++k) {
          std::swap(metrics[s.start + k], s.metrics[k]);
          if (matrices) (*matrices)[s.start + k] = s.matrices[k];
        }
      });
  return metrics;
}

void analyze_pose_slices(const Machine& machine, std::size_t count, const Wrench& wrench,
                         bool matrices, int threads,
                         const std::function<void(const PoseSlice&)>& fill,
                         const std::function<void(const PoseSlice&)>& consume) {
  require(wrench_within_limits(wrench),
          "the wrench must be finite with every component within +-1e9 (N, N*m)");
  const BatchAnalysis* batch = machine.batch_analysis();
  const long long slices = static_cast<long long>((count + kPoseSlice - 1) / kPoseSlice);
  const int thread_count = threads > 0 ? threads : omp_get_max_threads();
  std::exception_ptr first_error;
#pragma omp parallel num_threads(thread_count)
  {
    std::vector<Pose> poses(kPoseSlice);
    std::vector<PoseMetrics> metrics(kPoseSlice);
    std::vector<PoseCompliance> compliance(matrices ? kPoseSlice : 0);
    std::unique_ptr<MachineData> data;
    try {
      if (!batch) data = machine.make_data();
    } catch (...) {
#pragma omp critical(pkmopt_pose_slices_error)
      if (!first_error) first_error = std::current_exception();
    }
#pragma omp for schedule(static)
    for (long long s = 0; s < slices; ++s) {
      if (!batch && !data) continue;  // its error is kept
      try {
        const std::size_t start = static_cast<std::size_t>(s) * kPoseSlice;
        const std::size_t size = std::min(kPoseSlice, count - start);
        const PoseSlice slice{.start = start,
                              .poses = std::span(poses).first(size),
                              .metrics = std::span(metrics).first(size),
                              .matrices = std::span(compliance).first(matrices ? size : 0)};
        fill(slice);
        if (batch) {
          batch->analyze_batch(poses.data(), size, wrench, metrics.data(),
                               matrices ? compliance.data() : nullptr);
        } else {
          for (std::size_t k = 0; k < size; ++k) {
            machine.analyze(*data, poses[k], wrench, metrics[k]);
            if (matrices) compliance[k] = data->matrices;
          }
        }
        consume(slice);
      } catch (...) {
#pragma omp critical(pkmopt_pose_slices_error)
        if (!first_error) first_error = std::current_exception();
      }
    }
  }
  if (first_error) std::rethrow_exception(first_error);
}

std::vector<PoseModes> mode_shapes_of_poses(const Machine& machine, std::span<const Pose> poses) {
  const std::size_t n = poses.size();
  std::vector<PoseModes> modes(n);
  const Capability<Dynamics> dynamics = machine.dynamics();
#pragma omp parallel
  {
    const std::unique_ptr<MachineData> data = machine.make_data();
#pragma omp for schedule(static)
    for (std::size_t i = 0; i < n; ++i) {
      if (!dynamics || !dynamics->mode_shapes(*data, poses[i], modes[i])) modes[i] = PoseModes{};
    }
  }
  return modes;
}

}  // namespace pkmopt
