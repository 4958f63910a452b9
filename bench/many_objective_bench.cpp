// Many-objective fronts: NSGA-III, NSGA-II and MOEA/D of pkmopt and pagmo 2's MOEA/D on DTLZ1-4
// with 3, 5 and 8 objectives at equal evaluations (the settings of Deb & Jain, IEEE TEVC 18(4),
// 2014, Tables I-III: 91, 210 and 156 reference directions, population 92, 212 and 156, and their
// generation counts; pagmo's MOEA/D with its defaults, one member per weight: 91 and 210 on its
// grid, 156 low-discrepancy weights for 8 objectives). Objectives are normalised WFG-style by the
// true front's ideal (0) and nadir (0.5 for DTLZ1, 1 for DTLZ2-4); reported are the medians over
// kSeeds seeds of IGD+ against a dense sample of the analytic front (about 20,000 points) and,
// for 3 and 5 objectives, of the hypervolume up to (1.1, ..., 1.1).
//
//   build/bin/pkmopt_bench --benchmark_filter=ManyObjective
// Args: {DTLZ kind, objectives}.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <pagmo/algorithms/moead.hpp>
#include <pagmo/population.hpp>
#include <pagmo/problem.hpp>
#include <pagmo/problems/dtlz.hpp>
#include <string>
#include <vector>

#include "optimizer/indicators.hpp"
#include "optimizer/moead.hpp"
#include "optimizer/nsga2.hpp"
#include "optimizer/nsga3.hpp"
#include "problems/benchmarks/benchmarks.hpp"

namespace pkmopt {
namespace {

constexpr int kManySeeds = 5;

double median_of(std::vector<double> values) {
  std::sort(values.begin(), values.end());
  return values[values.size() / 2];
}

// Deb & Jain 2014's generations per problem (rows DTLZ1-4) and objective count (3, 5, 8).
std::size_t generations_for(int kind, std::size_t m) {
  const std::size_t table[4][3] = {
      {400, 600, 750}, {250, 350, 500}, {1000, 1000, 1000}, {600, 1000, 1250}};
  return table[kind - 1][m == 3 ? 0 : m == 5 ? 1 : 2];
}

struct Scores {
  std::vector<double> igd, hv;
};

void score(Scores& s, ObjectiveSet front, double nadir, const ObjectiveSet& reference,
           std::size_t m) {
  for (auto& f : front)
    for (double& v : f) v /= nadir;
  s.igd.push_back(igd_plus(front, reference));
  if (m <= 5) s.hv.push_back(hypervolume(front, std::vector<double>(m, 1.1)));
}

void BM_ManyObjective(benchmark::State& state) {
  const int kind = static_cast<int>(state.range(0));
  const std::size_t m = static_cast<std::size_t>(state.range(1));
  const auto problem = make_benchmark("dtlz" + std::to_string(kind), 0, m);
  const double nadir = kind == 1 ? 0.5 : 1.0;
  ObjectiveSet reference = problem->reference_front(20000);
  for (auto& f : reference)
    for (double& v : f) v /= nadir;
  const std::size_t generations = generations_for(kind, m);
  const std::size_t h1 = m == 3 ? 12 : m == 5 ? 6 : 3, h2 = m == 8 ? 2 : 0;
  Scores nsga3, nsga2, moead, pagmo_moead;
  std::size_t population = 0, weights = 0;
  for (auto _ : state) {
    for (int seed = 1; seed <= kManySeeds; ++seed) {
      Nsga3Options o3;
      o3.divisions = h1;
      o3.inner_divisions = h2;
      o3.generations = generations;
      o3.seed = static_cast<std::uint64_t>(seed);
      o3.threads = 1;
      const FrontResult f3 = run_nsga3(*problem, o3);
      population = f3.fitness_evaluations / (generations + 1);
      score(nsga3, f3.objectives(), nadir, reference, m);

      Nsga2Options o2;
      o2.population = population;
      o2.generations = generations;
      o2.seed = static_cast<std::uint64_t>(seed);
      o2.threads = 1;
      score(nsga2, run_nsga2(*problem, o2).objectives(), nadir, reference, m);

      MoeadOptions od;
      od.divisions = h1;
      od.inner_divisions = h2;
      od.generations = generations;
      od.seed = static_cast<std::uint64_t>(seed);
      od.threads = 1;
      const FrontResult fd = run_moead(*problem, od);
      weights = fd.fitness_evaluations / (generations + 1);
      score(moead, fd.objectives(), nadir, reference, m);

      pagmo::problem theirs{pagmo::dtlz(static_cast<unsigned>(kind),
                                        static_cast<unsigned>(problem->bounds().lower.size()),
                                        static_cast<unsigned>(m))};
      pagmo::population pop{theirs, weights, static_cast<unsigned>(seed)};
      pagmo::algorithm algorithm{pagmo::moead(static_cast<unsigned>(generations),
                                              m == 8 ? "low discrepancy" : "grid", "tchebycheff",
                                              20, 1.0, 0.5, 20., 0.9, 2, true,
                                              static_cast<unsigned>(seed))};
      pop = algorithm.evolve(pop);
      score(pagmo_moead, ObjectiveSet(pop.get_f().begin(), pop.get_f().end()), nadir, reference,
            m);
    }
  }
  state.counters["evaluations"] = static_cast<double>(population * (generations + 1));
  state.counters["nsga3_igd+"] = median_of(nsga3.igd);
  state.counters["nsga2_igd+"] = median_of(nsga2.igd);
  state.counters["moead_igd+"] = median_of(moead.igd);
  state.counters["pagmo_moead_igd+"] = median_of(pagmo_moead.igd);
  if (m <= 5) {
    state.counters["nsga3_hv"] = median_of(nsga3.hv);
    state.counters["nsga2_hv"] = median_of(nsga2.hv);
    state.counters["moead_hv"] = median_of(moead.hv);
    state.counters["pagmo_moead_hv"] = median_of(pagmo_moead.hv);
  }
}
BENCHMARK(BM_ManyObjective)
    ->ArgsProduct({{1, 2, 3, 4}, {3, 5, 8}})
    ->Iterations(1)
    ->Unit(benchmark::kSecond);

}  // namespace
}  // namespace pkmopt
