// The hexapod benchmarks' poses: deterministic (splitmix64, seed 12345), spread over the
// working region of the docs/conventions.md hexapod: x, y in [-0.15, 0.15] m, z in
// [0.75, 0.95] m, rx, ry in [-15, 15] deg, rz in [-20, 20] deg.
#pragma once

#include <Eigen/Core>
#include <cstddef>
#include <vector>

#include "bench/uniform_stream.hpp"
#include "models/core/pose.hpp"

namespace pkmopt::sample_machines {

inline std::vector<Pose> hexapod_bench_poses(std::size_t n) {
  Uniform uniform(12345);
  std::vector<Pose> poses(n);
  for (auto& p : poses) {
    p.position = {uniform(-0.15, 0.15), uniform(-0.15, 0.15), uniform(0.75, 0.95)};
    p.angles = deg_to_rad(Eigen::Vector3d(uniform(-15, 15), uniform(-15, 15), uniform(-20, 20)));
  }
  return poses;
}

}  // namespace pkmopt::sample_machines
