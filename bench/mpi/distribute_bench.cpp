// The MPI evaluator of `pkmopt run` (studies/distribute.hpp): its overhead per design and its
// parallel efficiency. Run under mpirun; rank 0 runs the benchmarks, the other ranks evaluate:
//
//   mpirun --oversubscribe -np 2 build/bin/pkmopt_bench_mpi     # 1 worker
//   mpirun --oversubscribe -np 3 build/bin/pkmopt_bench_mpi     # 2 workers
//   mpirun --oversubscribe -np 5 build/bin/pkmopt_bench_mpi     # 4 workers
//
// A design's evaluation burns x[0] microseconds of CPU time (a busy loop on the thread's CPU
// clock, so its cost is fixed whatever else runs on the core).
//   BM_MpiRoundTrip: batches of 100 designs that cost nothing: us_per_design is the evaluator's
//     overhead (messages, packing, scheduling) per design.
//   BM_MpiFixedCost/C: batches of 16 designs per worker of C microseconds each: efficiency is
//     (designs x C) / (wall time x workers), 1 for perfect scaling. With more processes than
//     cores (oversubscribed) the workers share cores and the efficiency says so.
#include <benchmark/benchmark.h>
#include <time.h>

#include <algorithm>
#include <cstdio>
#include <memory>
#include <vector>

#include "studies/distribute.hpp"

namespace {

using namespace pkmopt;

double thread_cpu_us() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) * 1e6 + static_cast<double>(t.tv_nsec) * 1e-3;
}

StudyEvaluator busy_evaluator() {
  StudyEvaluator ev;
  ev.study_hash = 0x6265'6e63'6820'6d70ULL;
  ev.num_variables = 1;
  ev.fitness_size = 1;
  ev.evaluate = [](const std::vector<double>& x) {
    const double start = thread_cpu_us();
    volatile double sink = 0.0;
    while (thread_cpu_us() - start < x[0]) sink = sink + 1.0;
    JournalEntry e;
    e.fitness = {x[0]};
    return e;
  };
  return ev;
}

MpiDispatcher* g_dispatcher = nullptr;

void BM_MpiRoundTrip(benchmark::State& state) {
  const std::vector<std::vector<double>> xs(100, std::vector<double>{0.0});
  for (auto _ : state) benchmark::DoNotOptimize(g_dispatcher->evaluate(xs));
  state.counters["workers"] = g_dispatcher->workers();
  state.counters["us_per_design"] = benchmark::Counter(
      100e-6, benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}
BENCHMARK(BM_MpiRoundTrip)->Unit(benchmark::kMicrosecond)->UseRealTime();

void BM_MpiFixedCost(benchmark::State& state) {
  const double cost = static_cast<double>(state.range(0));
  const std::size_t designs = 16 * static_cast<std::size_t>(std::max(1, g_dispatcher->workers()));
  const std::vector<std::vector<double>> xs(designs, std::vector<double>{cost});
  for (auto _ : state) benchmark::DoNotOptimize(g_dispatcher->evaluate(xs));
  state.counters["workers"] = g_dispatcher->workers();
  // Work per iteration over (wall per iteration x workers).
  state.counters["efficiency"] = benchmark::Counter(
      static_cast<double>(designs) * cost * 1e-6 / std::max(1, g_dispatcher->workers()),
      benchmark::Counter::kIsIterationInvariantRate);
}
BENCHMARK(BM_MpiFixedCost)->Arg(1000)->Arg(10000)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace

int main(int argc, char** argv) {
  const MpiSession session(/*with_workers=*/true);
  if (session.size() < 2) {
    std::fprintf(stderr, "pkmopt_bench_mpi: run it under mpirun with 2 or more ranks\n");
    return 2;
  }
  if (session.rank() > 0) {
    serve_as_worker(busy_evaluator, 1);
    return 0;
  }
  auto dispatcher = std::make_unique<MpiDispatcher>(busy_evaluator(), 600.0);
  g_dispatcher = dispatcher.get();
  benchmark::Initialize(&argc, argv);
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  dispatcher.reset();
  return 0;
}
