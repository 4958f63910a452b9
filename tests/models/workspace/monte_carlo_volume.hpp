// A Monte Carlo estimate of a workspace volume for the workspace tests: uniform samples of
// Machine::reachable in a box at one orientation, from a seeded splitmix64 stream.
//
// Example:
//   const test_volume::MonteCarlo mc = test_volume::monte_carlo_volume(hexapod, box, angles, 7);
//   EXPECT_LT(std::abs(volume - mc.volume), 4 * mc.standard_error);
#pragma once

#include <Eigen/Geometry>
#include <cmath>
#include <cstdint>

#include "models/core/machine.hpp"

namespace pkmopt::test_volume {

// splitmix64: a seeded, bit-reproducible stream of uniform doubles in [0, 1).
struct SplitMix64 {
  std::uint64_t state;
  double next() {
    std::uint64_t z = (state += 0x9e3779b97f4a7c15ULL);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    z ^= z >> 31;
    return static_cast<double>(z >> 11) * 0x1.0p-53;
  }
};

struct MonteCarlo {
  double volume = 0.0;          ///< hits / samples * box volume (m^3)
  double standard_error = 0.0;  ///< of the estimate (m^3)
};

/// `samples` uniform positions in `box` at the orientation `angles` (rad).
inline MonteCarlo monte_carlo_volume(const Machine& machine, const Eigen::AlignedBox3d& box,
                                     const Eigen::Vector3d& angles, std::uint64_t seed,
                                     int samples = 1'000'000) {
  SplitMix64 random{seed};
  const auto data = machine.make_data();
  int hits = 0;
  Pose pose{Eigen::Vector3d::Zero(), angles};
  for (int s = 0; s < samples; ++s) {
    for (int a = 0; a < 3; ++a)
      pose.position(a) = box.min()(a) + (box.max()(a) - box.min()(a)) * random.next();
    hits += machine.reachable(*data, pose) ? 1 : 0;
  }
  const double p = static_cast<double>(hits) / samples;
  return {p * box.volume(), std::sqrt(p * (1 - p) / samples) * box.volume()};
}

}  // namespace pkmopt::test_volume
