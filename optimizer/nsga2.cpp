#include "optimizer/nsga2.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <numeric>
#include <stdexcept>

#include "optimizer/population.hpp"
#include "optimizer/random.hpp"
#include "optimizer/variation.hpp"

namespace pkmopt {
namespace {

void assign_crowding(std::vector<Individual>& pop, const std::vector<std::size_t>& front,
                     std::size_t m) {
  for (std::size_t k : front) pop[k].crowding = 0.0;
  if (front.size() <= 2) {
    for (std::size_t k : front) pop[k].crowding = INFINITY;
    return;
  }
  std::vector<std::size_t> order = front;
  for (std::size_t i = 0; i < m; ++i) {
    std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
      return pop[a].fitness[i] < pop[b].fitness[i];
    });
    const double low = pop[order.front()].fitness[i];
    const double high = pop[order.back()].fitness[i];
    pop[order.front()].crowding = INFINITY;
    pop[order.back()].crowding = INFINITY;
    const double range = high - low;
    if (!(range > 0.0) || !std::isfinite(range)) continue;
    for (std::size_t k = 1; k + 1 < order.size(); ++k)
      pop[order[k]].crowding +=
          (pop[order[k + 1]].fitness[i] - pop[order[k - 1]].fitness[i]) / range;
  }
}

// Crowded-comparison binary tournament.
std::size_t tournament(const std::vector<Individual>& pop, Random& rng) {
  const std::size_t a = rng.below(pop.size());
  const std::size_t b = rng.below(pop.size());
  if (pop[a].rank != pop[b].rank) return pop[a].rank < pop[b].rank ? a : b;
  if (pop[a].crowding != pop[b].crowding) return pop[a].crowding > pop[b].crowding ? a : b;
  return rng.bernoulli(0.5) ? a : b;
}

}  // namespace

std::optional<std::string> Nsga2Options::validate() const {
  auto violated = [](const char* name, auto value, const char* rule) {
    return fmt::format("Nsga2Options::{} = {}. Violated constraint: {}", name, value, rule);
  };
  if (population < 4 || population % 2 != 0)
    return violated("population", population, "population even and >= 4");
  return check_evolution_options(
      "Nsga2Options", {crossover_probability, crossover_eta, mutation_probability, mutation_eta},
      equality_tolerance, threads);
}

std::optional<std::string> nsga2_explain_unsupported(const Problem& problem) {
  try {
    check_bounds(problem);
  } catch (const std::invalid_argument& e) {
    return std::string(e.what());
  }
  const Bounds b = problem.bounds();
  for (std::size_t j = 0; j < b.lower.size(); ++j)
    if (!std::isfinite(b.lower[j]) || !std::isfinite(b.upper[j]))
      return fmt::format("nsga2 samples within the bounds, but variable {} of '{}' is unbounded",
                         j + 1, problem.name());
  return std::nullopt;
}

struct Nsga2Search::State {
  State(const Problem& p, const Nsga2Options& o)
      : problem(p),
        options(o),
        start(std::chrono::steady_clock::now()),
        counted(p),
        bounds(p.bounds()),
        m(p.num_objectives()),
        rng(o.seed) {}
  const Problem& problem;
  Nsga2Options options;
  std::chrono::steady_clock::time_point start;
  CountingProblem counted;
  Bounds bounds;
  std::size_t m;
  Random rng;
  VariationSettings variation;
  std::vector<Individual> population;
  std::size_t generations = 0;

  void generation();
};

// One generation: offspring by tournament, SBX and mutation; parents and children merged and
// truncated by front and crowding distance.
void Nsga2Search::State::generation() {
  const std::size_t size = options.population;
  std::vector<Individual> merged = population;
  merged.reserve(2 * size);
  append_offspring(
      population, size, bounds, variation, [&] { return tournament(population, rng); }, rng,
      merged);
  evaluate_individuals(counted, merged, size, options.threads, options.equality_tolerance);

  std::vector<Individual> next;
  next.reserve(size);
  for (const auto& front : sort_fronts(merged, m)) {
    assign_crowding(merged, front, m);
    if (next.size() + front.size() <= size) {
      for (std::size_t k : front) next.push_back(std::move(merged[k]));
      if (next.size() == size) break;
      continue;
    }
    std::vector<std::size_t> order = front;
    std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
      return merged[a].crowding > merged[b].crowding;
    });
    for (std::size_t k = 0; next.size() < size; ++k) next.push_back(std::move(merged[order[k]]));
    break;
  }
  population = std::move(next);
  // Ranks and crowding of the survivors, for the next tournaments.
  for (const auto& front : sort_fronts(population, m)) assign_crowding(population, front, m);
  ++generations;
}

Nsga2Search::Nsga2Search(const Problem& problem, const Nsga2Options& options) {
  if (auto error = options.validate()) throw std::invalid_argument(*error);
  if (auto reason = nsga2_explain_unsupported(problem)) throw std::invalid_argument(*reason);
  state_ = std::make_unique<State>(problem, options);
  State& s = *state_;
  const std::size_t n = s.bounds.lower.size();
  s.variation = {options.crossover_probability, options.crossover_eta,
                 resolved_mutation_probability(options.mutation_probability, n),
                 options.mutation_eta};
  s.population =
      initial_individuals(problem, options.population, options.initial_population, s.rng, "nsga2");
  evaluate_individuals(s.counted, s.population, 0, options.threads, options.equality_tolerance);
  for (const auto& front : sort_fronts(s.population, s.m))
    assign_crowding(s.population, front, s.m);
}

Nsga2Search::~Nsga2Search() = default;
Nsga2Search::Nsga2Search(Nsga2Search&&) noexcept = default;
Nsga2Search& Nsga2Search::operator=(Nsga2Search&&) noexcept = default;

void Nsga2Search::advance(std::size_t generations) {
  for (std::size_t g = 0; g < generations; ++g) state_->generation();
}

std::size_t Nsga2Search::generations() const { return state_->generations; }

long long Nsga2Search::fitness_evaluations() const {
  return state_->counted.fitness_evaluations();
}

FrontResult Nsga2Search::front() const {
  const State& s = *state_;
  return population_front(s.problem, s.population, s.options.equality_tolerance, "nsga2",
                          s.counted, s.start);
}

FrontResult run_nsga2(const Problem& problem, const Nsga2Options& options) {
  Nsga2Search search(problem, options);
  search.advance(options.generations);
  return search.front();
}

}  // namespace pkmopt
