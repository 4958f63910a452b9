// Benchmarks of the optimizer: NSGA-II overhead, hypervolume speed, and pkmopt against pagmo2
// at the same evaluation budget.
//
//   build*/bin/pkmopt_bench --benchmark_filter='Nsga2|Hypervolume|Pagmo|FrontEconomy'
//
// Counters: hypervolume (reference (1.1, 1.1)), evaluations, ns_per_evaluation (time of the run
// divided by evaluations: the framework overhead when the problem is cheap, as ZDT1 is).
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <pagmo/algorithms/nsga2.hpp>
#include <pagmo/population.hpp>
#include <pagmo/problem.hpp>
#include <pagmo/problems/zdt.hpp>
#include <pagmo/utils/hypervolume.hpp>
#include <vector>

#include "optimizer/epsilon_constraint.hpp"
#include "optimizer/front_thinning.hpp"
#include "optimizer/indicators.hpp"
#include "optimizer/nbi.hpp"
#include "optimizer/nsga2.hpp"
#include "optimizer/random.hpp"
#include "problems/benchmarks/benchmarks.hpp"

namespace {

using namespace pkmopt;

const std::vector<double> kReference{1.1, 1.1};
constexpr int kSeeds = 15;

std::size_t zdt_variables(int kind) { return kind == 4 || kind == 6 ? 10 : 30; }

double median(std::vector<double> values) {
  std::sort(values.begin(), values.end());
  return values[values.size() / 2];
}

// pkmopt NSGA-II on ZDT1, population 100, 250 generations (25,100 evaluations), one thread.
void BM_Nsga2OverheadZdt1(benchmark::State& state) {
  Zdt problem(1, 30);
  Nsga2Options options;
  options.population = 100;
  options.generations = 250;
  options.threads = 1;
  double hv = 0.0;
  long long evaluations = 0;
  for (auto _ : state) {
    const FrontResult front = run_nsga2(problem, options);
    hv = hypervolume(front.objectives(), kReference);
    evaluations = front.fitness_evaluations;
  }
  state.counters["hypervolume"] = hv;
  state.counters["evaluations"] = static_cast<double>(evaluations);
  state.counters["ns_per_evaluation"] = benchmark::Counter(
      static_cast<double>(evaluations) * 1e-9,
      benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}
BENCHMARK(BM_Nsga2OverheadZdt1)->Unit(benchmark::kMillisecond);

// The same budget with pagmo's NSGA-II (its defaults: cr 0.95, eta_c 10, m 1/n, eta_m 50).
void BM_PagmoNsga2OverheadZdt1(benchmark::State& state) {
  double hv = 0.0;
  for (auto _ : state) {
    pagmo::problem problem{pagmo::zdt(1, 30)};
    pagmo::population population{problem, 100, 1};
    pagmo::algorithm algorithm{pagmo::nsga2(250, 0.95, 10., 1. / 30., 50., 1)};
    population = algorithm.evolve(population);
    ObjectiveSet front(population.get_f().begin(), population.get_f().end());
    hv = hypervolume(front, kReference);
  }
  state.counters["hypervolume"] = hv;
  state.counters["evaluations"] = 25100;
  state.counters["ns_per_evaluation"] = benchmark::Counter(
      25100 * 1e-9, benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}
BENCHMARK(BM_PagmoNsga2OverheadZdt1)->Unit(benchmark::kMillisecond);

// Exact hypervolume of 1000 mutually non-dominated points in 3 objectives.
void BM_Hypervolume3d1000(benchmark::State& state) {
  Random rng(1);
  ObjectiveSet points(1000, std::vector<double>(3));
  for (auto& p : points) {
    double norm = 0.0;
    for (double& v : p) {
      v = rng.uniform01();
      norm += v * v;
    }
    for (double& v : p) v /= std::sqrt(norm);
  }
  const std::vector<double> reference{1.1, 1.1, 1.1};
  double hv = 0.0;
  for (auto _ : state) benchmark::DoNotOptimize(hv = hypervolume(points, reference));
  state.counters["hypervolume"] = hv;
}
BENCHMARK(BM_Hypervolume3d1000)->Unit(benchmark::kMillisecond);

// A run's front from its archive: the non-dominated set of N evaluations of 3 objectives (a
// sphere's octant, 10 % of them pushed off it and dominated), thinned to 100 points by SPEA2
// truncation (optimizer/front_thinning.hpp); N = 6800 gives about the 6115-point archive of
// dtlz2-nsga2's 23,092 evaluations.
void BM_SelectFrontThinned(benchmark::State& state) {
  Random rng(2);
  ObjectiveSet points(static_cast<std::size_t>(state.range(0)), std::vector<double>(3));
  for (std::size_t k = 0; k < points.size(); ++k) {
    double norm = 0.0;
    for (double& v : points[k]) {
      v = rng.uniform01();
      norm += v * v;
    }
    const double radius = k % 10 == 0 ? 1.2 : 1.0;
    for (double& v : points[k]) v *= radius / std::sqrt(norm);
  }
  std::size_t kept = 0;
  for (auto _ : state) benchmark::DoNotOptimize(kept = select_front(points, 100).size());
  state.counters["kept"] = static_cast<double>(kept);
}
BENCHMARK(BM_SelectFrontThinned)->Arg(1000)->Arg(6800)->Unit(benchmark::kMillisecond);

void BM_PagmoHypervolume3d1000(benchmark::State& state) {
  Random rng(1);
  std::vector<std::vector<double>> points(1000, std::vector<double>(3));
  for (auto& p : points) {
    double norm = 0.0;
    for (double& v : p) {
      v = rng.uniform01();
      norm += v * v;
    }
    for (double& v : p) v /= std::sqrt(norm);
  }
  double hv = 0.0;
  for (auto _ : state) {
    pagmo::hypervolume volume(points, false);
    benchmark::DoNotOptimize(hv = volume.compute({1.1, 1.1, 1.1}));
  }
  state.counters["hypervolume"] = hv;
}
BENCHMARK(BM_PagmoHypervolume3d1000)->Unit(benchmark::kMillisecond);

// pkmopt vs pagmo NSGA-II at 25,000 evaluations (population 100, 249 generations), median
// hypervolume over 15 seeds, on ZDT1-4 and ZDT6.
void BM_Nsga2VsPagmo(benchmark::State& state) {
  const int kind = static_cast<int>(state.range(0));
  const std::size_t n = zdt_variables(kind);
  std::vector<double> ours, theirs;
  for (auto _ : state) {
    ours.clear();
    theirs.clear();
    for (int seed = 1; seed <= kSeeds; ++seed) {
      Zdt problem(kind, n);
      Nsga2Options options;
      options.population = 100;
      options.generations = 249;
      options.seed = static_cast<std::uint64_t>(seed);
      options.threads = 1;
      ours.push_back(hypervolume(run_nsga2(problem, options).objectives(), kReference));

      pagmo::problem pagmo_problem{
          pagmo::zdt(static_cast<unsigned>(kind), static_cast<unsigned>(n))};
      pagmo::population population{pagmo_problem, 100, static_cast<unsigned>(seed)};
      pagmo::algorithm algorithm{pagmo::nsga2(249, 0.95, 10., 1. / static_cast<double>(n), 50.,
                                              static_cast<unsigned>(seed))};
      population = algorithm.evolve(population);
      theirs.push_back(hypervolume(
          ObjectiveSet(population.get_f().begin(), population.get_f().end()), kReference));
    }
  }
  state.counters["pkmopt_hypervolume"] = median(ours);
  state.counters["pagmo_hypervolume"] = median(theirs);
  state.counters["evaluations"] = 25000;
}
BENCHMARK(BM_Nsga2VsPagmo)
    ->Arg(1)
    ->Arg(2)
    ->Arg(3)
    ->Arg(4)
    ->Arg(6)
    ->Iterations(1)
    ->Unit(benchmark::kSecond);

// Evaluation economy on ZDT1 and ZDT2 (30 variables, exact gradients): epsilon-constraint
// and NBI with `points` points against NSGA-II (population 100) at several generation counts,
// reporting fitness and gradient evaluations, IGD+ against 1000 analytic points and
// hypervolume. Args: {ZDT kind, method (0 epsilon-constraint, 1 NBI, 2 NSGA-II), points or
// generations}.
void BM_FrontEconomy(benchmark::State& state) {
  const int kind = static_cast<int>(state.range(0));
  const int method = static_cast<int>(state.range(1));
  const std::size_t size = static_cast<std::size_t>(state.range(2));
  Zdt problem(kind, 30);
  FrontResult front;
  for (auto _ : state) {
    if (method == 0) {
      EpsilonConstraintOptions options;
      options.points = size;
      front = run_epsilon_constraint(problem, options);
    } else if (method == 1) {
      NbiOptions options;
      options.points = size;
      front = run_nbi(problem, options);
    } else {
      Nsga2Options options;
      options.population = 100;
      options.generations = size;
      options.threads = 1;
      front = run_nsga2(problem, options);
    }
  }
  state.SetLabel(method == 0 ? "epsilon_constraint" : (method == 1 ? "nbi" : "nsga2"));
  state.counters["hypervolume"] = hypervolume(front.objectives(), kReference);
  state.counters["igd_plus"] = igd_plus(front.objectives(), problem.reference_front(1000));
  state.counters["evaluations"] = static_cast<double>(front.fitness_evaluations);
  state.counters["gradient_evaluations"] = static_cast<double>(front.gradient_evaluations);
  state.counters["points"] = static_cast<double>(front.x.size());
  state.counters["subproblems"] = static_cast<double>(front.subproblems);
}
BENCHMARK(BM_FrontEconomy)
    ->Args({1, 0, 50})
    ->Args({1, 1, 50})
    ->Args({1, 0, 100})
    ->Args({1, 1, 100})
    ->Args({1, 2, 100})
    ->Args({1, 2, 250})
    ->Args({1, 2, 500})
    ->Args({2, 0, 50})
    ->Args({2, 1, 50})
    ->Args({2, 0, 100})
    ->Args({2, 1, 100})
    ->Args({2, 2, 100})
    ->Args({2, 2, 250})
    ->Args({2, 2, 500})
    ->Iterations(1)
    ->Unit(benchmark::kMillisecond);

}  // namespace
