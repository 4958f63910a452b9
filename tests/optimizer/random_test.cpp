// Tests of optimizer/random: reproducible streams and the hand-written distributions.
#include "optimizer/random.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "bench/uniform_stream.hpp"

namespace pkmopt {
namespace {

TEST(Random, SameSeedSameStream) {
  Random a(7), b(7), c(8);
  for (int k = 0; k < 100; ++k) {
    const auto word = a.next();
    EXPECT_EQ(word, b.next());
    (void)c;
  }
  EXPECT_NE(Random(7).next(), Random(8).next());
}

TEST(Random, SplitmixReferenceValue) {
  // splitmix64 from state 0: first output 0xE220A8397B1DCDAF (Vigna's reference code).
  std::uint64_t state = 0;
  EXPECT_EQ(splitmix64(state), 0xE220A8397B1DCDAFULL);
}

// The sample stream of the tests and benchmarks (bench/uniform_stream.hpp) draws
// lo + (hi - lo) * (w >> 11) 2^-53 from the splitmix64 words w of its seed: here with splitmix64
// written out again (Steele, Lea & Flood 2014), so the benchmarks' poses stay the same numbers.
TEST(Random, SampleUniformStreamIsSplitmix64) {
  for (const std::uint64_t seed : {0ULL, 7ULL, 42ULL, 12345ULL}) {
    sample_machines::Uniform uniform(seed);
    std::uint64_t state = seed;
    for (int k = 0; k < 1000; ++k) {
      std::uint64_t z = (state += 0x9e3779b97f4a7c15ULL);
      z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
      z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
      z ^= z >> 31;
      const double lo = -0.5 * k, hi = 1.0 + k;
      EXPECT_EQ(uniform(lo, hi), lo + (hi - lo) * static_cast<double>(z >> 11) * 0x1.0p-53)
          << "seed " << seed << " draw " << k;
    }
  }
}

TEST(Random, UniformMomentsAndRange) {
  Random rng(1);
  const int n = 200000;
  double sum = 0.0, sum_squares = 0.0;
  for (int k = 0; k < n; ++k) {
    const double u = rng.uniform01();
    ASSERT_GE(u, 0.0);
    ASSERT_LT(u, 1.0);
    sum += u;
    sum_squares += u * u;
  }
  // Mean 1/2 and variance 1/12 within 5 standard errors.
  EXPECT_NEAR(sum / n, 0.5, 5 * std::sqrt(1.0 / 12.0 / n));
  EXPECT_NEAR(sum_squares / n - (sum / n) * (sum / n), 1.0 / 12.0, 0.002);
}

TEST(Random, BelowIsUniform) {
  Random rng(3);
  std::vector<int> counts(7, 0);
  const int n = 70000;
  for (int k = 0; k < n; ++k) ++counts[rng.below(7)];
  for (int c : counts) EXPECT_NEAR(c, n / 7.0, 5 * std::sqrt(n / 7.0));
}

TEST(Random, NormalMoments) {
  Random rng(5);
  const int n = 200000;
  double sum = 0.0, sum_squares = 0.0;
  for (int k = 0; k < n; ++k) {
    const double z = rng.normal();
    sum += z;
    sum_squares += z * z;
  }
  EXPECT_NEAR(sum / n, 0.0, 5.0 / std::sqrt(n));
  EXPECT_NEAR(sum_squares / n, 1.0, 0.02);
}

TEST(Random, SplitStreamsDifferAndRepeat) {
  Random parent(11);
  Random a = parent.split(0), b = parent.split(1), a2 = parent.split(0);
  const auto first = a.next();
  EXPECT_EQ(first, a2.next());
  EXPECT_NE(first, b.next());
}

TEST(Random, ShuffleIsAPermutation) {
  Random rng(2);
  std::vector<int> values{0, 1, 2, 3, 4, 5, 6, 7, 8, 9};
  rng.shuffle(values);
  std::vector<int> sorted = values;
  std::sort(sorted.begin(), sorted.end());
  for (int k = 0; k < 10; ++k) EXPECT_EQ(sorted[k], k);
}

}  // namespace
}  // namespace pkmopt
