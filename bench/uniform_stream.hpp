// The seeded uniform stream the benchmarks and the tests draw their sample poses and random
// geometries from: splitmix64 (optimizer/random.hpp), 53 bits per draw, the same numbers on every
// platform. Benchmarks include it from here (bench/ uses the library layers only); the tests get
// it through tests/sample_machines.hpp.
//
//   pkmopt::sample_machines::Uniform uniform(12345);
//   const double x = uniform(-0.15, 0.15);  // in [-0.15, 0.15)
#pragma once

#include <cstdint>

#include "optimizer/random.hpp"

namespace pkmopt::sample_machines {

/// Draw k is lo + (hi - lo) * (splitmix64 word k >> 11) * 2^-53 of the stream seeded `seed`.
class Uniform {
 public:
  explicit Uniform(std::uint64_t seed) : state_(seed) {}
  double operator()(double lo, double hi) {
    return lo + (hi - lo) * static_cast<double>(splitmix64(state_) >> 11) * 0x1.0p-53;
  }

 private:
  std::uint64_t state_;
};

}  // namespace pkmopt::sample_machines
