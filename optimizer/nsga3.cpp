#include "optimizer/nsga3.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <numeric>
#include <stdexcept>

#include "optimizer/aspiration_directions.hpp"
#include "optimizer/nsga2.hpp"
#include "optimizer/nsga3_selection.hpp"
#include "optimizer/population.hpp"
#include "optimizer/random.hpp"
#include "optimizer/reference_directions.hpp"
#include "optimizer/variation.hpp"

namespace pkmopt {
namespace {

// Binary tournament on constraint violation; of two feasible designs one at random.
std::size_t tournament(const std::vector<Individual>& pop, Random& rng) {
  const std::size_t a = rng.below(pop.size());
  const std::size_t b = rng.below(pop.size());
  if (pop[a].violation != pop[b].violation) return pop[a].violation < pop[b].violation ? a : b;
  return rng.bernoulli(0.5) ? a : b;
}

std::size_t aspiration_divisions(const Nsga3Options& options, std::size_t m) {
  return options.aspiration_divisions != 0 ? options.aspiration_divisions
                                           : default_aspiration_divisions(m);
}

// The `size` survivors of `merged` (see the header comment).
std::vector<Individual> survivors(std::vector<Individual>& merged, std::size_t size, std::size_t m,
                                  const std::vector<std::vector<double>>& fixed_directions,
                                  const Nsga3Options& options, NormalizationMemory& memory,
                                  Random& rng) {
  std::vector<std::size_t> kept;
  std::vector<std::size_t> last;
  for (const auto& front : sort_fronts(merged, m)) {
    if (kept.size() + front.size() <= size) {
      kept.insert(kept.end(), front.begin(), front.end());
      if (kept.size() == size) break;
      continue;
    }
    last = front;
    break;
  }
  const std::size_t left = size - kept.size();
  std::vector<std::size_t> chosen;
  if (left > 0 && merged[last.front()].violation > 0.0) {
    // Infeasible: the smallest violations.
    std::vector<std::size_t> order = last;
    std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
      return merged[a].violation < merged[b].violation;
    });
    chosen.assign(order.begin(), order.begin() + static_cast<std::ptrdiff_t>(left));
  } else if (left > 0) {
    // Normalise over the kept members and the last front, associate, fill the niches.
    std::vector<std::vector<double>> f;
    for (std::size_t k : kept)
      f.emplace_back(merged[k].fitness.begin(),
                     merged[k].fitness.begin() + static_cast<std::ptrdiff_t>(m));
    for (std::size_t k : last)
      f.emplace_back(merged[k].fitness.begin(),
                     merged[k].fitness.begin() + static_cast<std::ptrdiff_t>(m));
    const Normalization normalization = normalize_objectives(f, &memory);
    const std::vector<std::vector<double>> directions =
        options.aspiration_points.empty()
            ? fixed_directions
            : aspiration_directions(normalized(normalization, options.aspiration_points),
                                    aspiration_divisions(options, m), options.aspiration_spread);
    const std::vector<Association> a = associate(normalized(normalization, f), directions);
    std::vector<std::size_t> rho(directions.size(), 0);
    for (std::size_t i = 0; i < kept.size(); ++i) ++rho[a[i].direction];
    const std::vector<Association> last_a(a.begin() + static_cast<std::ptrdiff_t>(kept.size()),
                                          a.end());
    for (std::size_t i : niche_select(left, rho, last_a, rng)) chosen.push_back(last[i]);
  }
  std::vector<Individual> next;
  next.reserve(size);
  for (std::size_t k : kept) next.push_back(std::move(merged[k]));
  for (std::size_t k : chosen) next.push_back(std::move(merged[k]));
  return next;
}

}  // namespace

std::optional<std::string> Nsga3Options::validate() const {
  auto violated = [](const char* name, auto value, const char* rule) {
    return fmt::format("Nsga3Options::{} = {}. Violated constraint: {}", name, value, rule);
  };
  if (population != 0 && (population < 4 || population % 2 != 0))
    return violated("population", population, "population 0 (automatic) or even and >= 4");
  if (reference_directions.empty() && divisions < 1)
    return violated("divisions", divisions, "divisions >= 1");
  if (!(aspiration_spread > 0.0 && aspiration_spread <= 1.0))
    return violated("aspiration_spread", aspiration_spread, "0 < aspiration_spread <= 1");
  return check_evolution_options(
      "Nsga3Options", {crossover_probability, crossover_eta, mutation_probability, mutation_eta},
      equality_tolerance, threads);
}

std::vector<std::vector<double>> nsga3_directions(const Nsga3Options& options, std::size_t m) {
  if (!options.aspiration_points.empty()) {
    for (const std::vector<double>& z : options.aspiration_points)
      if (z.size() != m)
        throw std::invalid_argument(
            fmt::format("nsga3: expected aspiration points of {} objective values", m));
    return aspiration_directions(options.aspiration_points, aspiration_divisions(options, m),
                                 options.aspiration_spread);
  }
  if (options.reference_directions.empty())
    return two_layer_directions(m, options.divisions, options.inner_divisions);
  check_given_directions(options.reference_directions, m, "nsga3", "reference directions");
  return options.reference_directions;
}

FrontResult run_nsga3(const Problem& problem, const Nsga3Options& options) {
  if (auto error = options.validate()) throw std::invalid_argument(*error);
  if (auto reason = nsga2_explain_unsupported(problem)) throw std::invalid_argument(*reason);
  const auto start = std::chrono::steady_clock::now();
  CountingProblem counted(problem);
  const Bounds bounds = problem.bounds();
  const std::size_t n = bounds.lower.size();
  const std::size_t m = problem.num_objectives();
  const std::vector<std::vector<double>> directions = nsga3_directions(options, m);
  const std::size_t size =
      options.population != 0 ? options.population : (directions.size() + 3) / 4 * 4;
  const VariationSettings variation{options.crossover_probability, options.crossover_eta,
                                    resolved_mutation_probability(options.mutation_probability, n),
                                    options.mutation_eta};
  Random rng(options.seed);

  std::vector<Individual> population =
      initial_individuals(problem, size, options.initial_population, rng, "nsga3");
  evaluate_individuals(counted, population, 0, options.threads, options.equality_tolerance);
  NormalizationMemory memory;

  for (std::size_t generation = 0; generation < options.generations; ++generation) {
    std::vector<Individual> merged = population;
    merged.reserve(2 * size);
    append_offspring(
        population, size, bounds, variation, [&] { return tournament(population, rng); }, rng,
        merged);
    evaluate_individuals(counted, merged, size, options.threads, options.equality_tolerance);
    population = survivors(merged, size, m, directions, options, memory, rng);
  }

  return population_front(problem, population, options.equality_tolerance, "nsga3", counted, start);
}

}  // namespace pkmopt
