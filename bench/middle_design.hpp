// One design evaluation per iteration, of the middle of a problem's design box (a mid-range
// machine): the design and synthesis benchmarks' common loop.
#pragma once

#include <benchmark/benchmark.h>

#include <cstddef>
#include <vector>

#include "optimizer/problem.hpp"

namespace pkmopt_bench {

inline void evaluate_middle_design(benchmark::State& state, const pkmopt::Problem& problem) {
  const pkmopt::Bounds bounds = problem.bounds();
  std::vector<double> x(bounds.lower.size());
  for (std::size_t i = 0; i < x.size(); ++i) x[i] = 0.5 * (bounds.lower[i] + bounds.upper[i]);
  for (auto _ : state) {
    std::vector<double> f = problem.fitness(x);
    benchmark::DoNotOptimize(f.data());
  }
}

}  // namespace pkmopt_bench
