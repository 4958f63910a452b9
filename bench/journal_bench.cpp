// The cost of the study journal (studies/journal.hpp) per evaluation: what `pkmopt run` adds to
// every design it evaluates (cache lookup, journal.txt and evaluations.csv lines, the feasible
// front for the progress display), on ZDT1 with 30 variables, whose evaluation costs well under
// a microsecond.
//
//   build/bin/pkmopt_bench --benchmark_filter=Journal
//
// Counters: us_per_evaluation (time of a batch of 100 new designs over 100), and for the
// reference BM_Zdt1Evaluation the evaluation alone.
#include <benchmark/benchmark.h>

#include <filesystem>
#include <random>
#include <string>
#include <vector>

#include "io/format/csv.hpp"
#include "problems/benchmarks/benchmarks.hpp"
#include "studies/journal.hpp"

namespace {

using namespace pkmopt;
namespace fs = std::filesystem;

constexpr std::size_t kBatch = 100;

std::vector<std::vector<double>> random_batch(std::mt19937_64& rng, std::size_t n) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<std::vector<double>> xs(kBatch, std::vector<double>(n));
  for (auto& x : xs)
    for (double& v : x) v = u(rng);
  return xs;
}

// Microseconds per design of a batch of kBatch designs, from the time per iteration.
benchmark::Counter us_per_evaluation() {
  return benchmark::Counter(
      static_cast<double>(kBatch) * 1e-6,
      benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}

// The evaluations.csv row of a benchmark study (as `pkmopt run` writes it).
std::string csv_row(std::size_t index, const JournalEntry& e) {
  std::string row = std::to_string(index) + ',' + std::to_string(e.generation);
  for (double v : e.x) row += "," + format_number(v);
  for (double v : e.fitness) row += "," + format_number(v);
  return row + ",1,";
}

void BM_JournalPerEvaluation(benchmark::State& state) {
  const Zdt problem(1, 30);
  const fs::path dir = fs::temp_directory_path() / "pkmopt-journal-bench";
  fs::remove_all(dir);
  fs::create_directories(dir);
  JournalOptions options;
  options.directory = dir.string();
  options.study_hash = study_hash("journal bench");
  options.csv_header = "index,generation,x...,f_1,f_2,feasible,failure";
  options.csv_row = csv_row;
  std::mt19937_64 rng(1);
  {
    JournaledProblem journaled(problem, options);
    for (auto _ : state) {
      state.PauseTiming();
      const auto xs = random_batch(rng, 30);
      state.ResumeTiming();
      benchmark::DoNotOptimize(journaled.batch_fitness(xs, 1));
    }
    state.counters["us_per_evaluation"] = us_per_evaluation();
    state.counters["journal_entries"] = static_cast<double>(journaled.entries().size());
  }
  fs::remove_all(dir);
}
BENCHMARK(BM_JournalPerEvaluation)->Unit(benchmark::kMicrosecond)->Iterations(250);

// The same designs evaluated without the journal: what the evaluation itself costs.
void BM_Zdt1Evaluation(benchmark::State& state) {
  const Zdt problem(1, 30);
  std::mt19937_64 rng(1);
  for (auto _ : state) {
    state.PauseTiming();
    const auto xs = random_batch(rng, 30);
    state.ResumeTiming();
    benchmark::DoNotOptimize(problem.batch_fitness(xs, 1));
  }
  state.counters["us_per_evaluation"] = us_per_evaluation();
}
BENCHMARK(BM_Zdt1Evaluation)->Unit(benchmark::kMicrosecond)->Iterations(250);

}  // namespace
