// A seeded random stream whose every draw is the same on every platform and compiler.
//
// The engine is xoshiro256** (Blackman & Vigna 2018) seeded through splitmix64, so a seed gives
// one fixed sequence of 64-bit words. The distributions are written here (not <random>'s, whose
// algorithms are implementation-defined):
//   uniform01()        = (word >> 11) * 2^-53, in [0, 1)
//   uniform(a, b)      = a + (b - a) * uniform01()
//   below(n)           = an integer in [0, n), unbiased (modulo with rejection)
//   normal()           = Box–Muller, a standard normal deviate
// `split(k)` derives an independent stream for a sub-task k, so parallel work can own streams
// chosen by index (not by thread), which keeps results independent of the thread count.
//
// Example:
//   pkmopt::Random rng(42);
//   double u = rng.uniform(-1.0, 1.0);
//   std::size_t i = rng.below(10);
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <numbers>
#include <utility>

namespace pkmopt {

/// splitmix64: the next state and its output word (Steele, Lea & Flood 2014).
inline std::uint64_t splitmix64(std::uint64_t& state) {
  std::uint64_t z = (state += 0x9E3779B97F4A7C15ULL);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
  return z ^ (z >> 31);
}

class Random {
 public:
  explicit Random(std::uint64_t seed) {
    std::uint64_t state = seed;
    for (std::uint64_t& word : state_) word = splitmix64(state);
  }

  /// The next 64-bit word.
  std::uint64_t next() {
    const std::uint64_t result = rotl(state_[1] * 5, 7) * 9;
    const std::uint64_t t = state_[1] << 17;
    state_[2] ^= state_[0];
    state_[3] ^= state_[1];
    state_[1] ^= state_[2];
    state_[0] ^= state_[3];
    state_[2] ^= t;
    state_[3] = rotl(state_[3], 45);
    return result;
  }

  /// Uniform in [0, 1) with 53 random bits.
  double uniform01() { return static_cast<double>(next() >> 11) * 0x1.0p-53; }
  /// Uniform in [a, b).
  double uniform(double a, double b) { return a + (b - a) * uniform01(); }
  /// Uniform integer in [0, n); n > 0.
  std::size_t below(std::size_t n) {
    const std::uint64_t range = static_cast<std::uint64_t>(n);
    const std::uint64_t limit = UINT64_MAX - UINT64_MAX % range;  // a multiple of range
    std::uint64_t word = next();
    while (word >= limit) word = next();
    return static_cast<std::size_t>(word % range);
  }
  /// True with probability p.
  bool bernoulli(double p) { return uniform01() < p; }
  /// Standard normal deviate (Box–Muller, one of the pair used).
  double normal() {
    const double u1 = 1.0 - uniform01();  // in (0, 1]
    const double u2 = uniform01();
    return std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * std::numbers::pi * u2);
  }
  /// Fisher–Yates shuffle of a random-access range.
  template <typename Range>
  void shuffle(Range& range) {
    const std::size_t size = range.size();
    for (std::size_t i = size; i > 1; --i) {
      const std::size_t j = below(i);
      using std::swap;
      swap(range[i - 1], range[j]);
    }
  }
  /// An independent stream for sub-task `index` (deterministic in the parent's seed).
  Random split(std::uint64_t index) const {
    std::uint64_t state = state_[0] ^ (state_[3] + 0x632BE59BD9B4E019ULL * (index + 1));
    return Random(splitmix64(state));
  }

 private:
  static std::uint64_t rotl(std::uint64_t x, int k) { return (x << k) | (x >> (64 - k)); }
  std::uint64_t state_[4];
};

}  // namespace pkmopt
