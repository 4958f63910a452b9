#include "optimizer/moead.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <numeric>
#include <stdexcept>

#include "optimizer/nsga2.hpp"
#include "optimizer/population.hpp"
#include "optimizer/random.hpp"
#include "optimizer/reference_directions.hpp"
#include "optimizer/variation.hpp"

namespace pkmopt {
namespace {

constexpr double kSmallestWeight = 1e-6;

// Each weight's `t` nearest weights (itself first: distance 0), ties by index.
std::vector<std::vector<std::size_t>> neighbourhoods(const std::vector<std::vector<double>>& w,
                                                     std::size_t t) {
  std::vector<std::vector<std::size_t>> result(w.size());
  for (std::size_t i = 0; i < w.size(); ++i) {
    std::vector<std::pair<double, std::size_t>> by_distance;
    for (std::size_t j = 0; j < w.size(); ++j) {
      double d = 0.0;
      for (std::size_t k = 0; k < w[i].size(); ++k) d += (w[i][k] - w[j][k]) * (w[i][k] - w[j][k]);
      by_distance.emplace_back(d, j);
    }
    std::sort(by_distance.begin(), by_distance.end());
    for (std::size_t k = 0; k < t; ++k) result[i].push_back(by_distance[k].second);
  }
  return result;
}

// The ideal point and the nadir of the normalisation (feasible designs once there are any).
struct Frame {
  std::vector<double> ideal, ideal_feasible;
  bool any_feasible = false;

  void see(const Individual& x, std::size_t m) {
    if (ideal.empty()) ideal.assign(m, std::numeric_limits<double>::infinity());
    if (ideal_feasible.empty()) ideal_feasible.assign(m, std::numeric_limits<double>::infinity());
    for (std::size_t i = 0; i < m; ++i) {
      if (!std::isfinite(x.fitness[i])) continue;
      ideal[i] = std::min(ideal[i], x.fitness[i]);
      if (x.violation == 0.0) ideal_feasible[i] = std::min(ideal_feasible[i], x.fitness[i]);
    }
    any_feasible = any_feasible || x.violation == 0.0;
  }
  const std::vector<double>& best() const { return any_feasible ? ideal_feasible : ideal; }
};

std::vector<double> population_nadir(const std::vector<Individual>& pop, std::size_t m,
                                     bool feasible_only) {
  std::vector<double> nadir(m, -std::numeric_limits<double>::infinity());
  for (const Individual& x : pop) {
    if (feasible_only && x.violation > 0.0) continue;
    for (std::size_t i = 0; i < m; ++i)
      if (std::isfinite(x.fitness[i])) nadir[i] = std::max(nadir[i], x.fitness[i]);
  }
  return nadir;
}

// The Tchebycheff value of x for weight w in the frame (ideal z, scale s).
double tchebycheff(const Individual& x, const std::vector<double>& w, const std::vector<double>& z,
                   const std::vector<double>& s) {
  double worst = 0.0;
  for (std::size_t i = 0; i < w.size(); ++i) {
    if (!std::isfinite(x.fitness[i])) return std::numeric_limits<double>::infinity();
    worst = std::max(worst, std::max(w[i], kSmallestWeight) * std::abs(x.fitness[i] - z[i]) / s[i]);
  }
  return worst;
}

// DE/rand/1/bin about x_i with repair toward the parent, then polynomial mutation.
std::vector<double> de_child(const std::vector<double>& xi, const std::vector<double>& r1,
                             const std::vector<double>& r2, const Bounds& bounds,
                             const MoeadOptions& o, double mutation_probability, Random& rng) {
  const std::size_t n = xi.size();
  std::vector<double> y = xi;
  const std::size_t j_rand = rng.below(n);
  for (std::size_t j = 0; j < n; ++j) {
    if (j != j_rand && !rng.bernoulli(o.crossover_rate)) continue;
    double v = xi[j] + o.differential_weight * (r1[j] - r2[j]);
    if (v < bounds.lower[j]) v = bounds.lower[j] + rng.uniform01() * (xi[j] - bounds.lower[j]);
    if (v > bounds.upper[j]) v = bounds.upper[j] - rng.uniform01() * (bounds.upper[j] - xi[j]);
    y[j] = v;
  }
  polynomial_mutation(y, bounds, mutation_probability, o.mutation_eta, rng);
  return y;
}

}  // namespace

std::optional<std::string> MoeadOptions::validate() const {
  auto violated = [](const char* name, auto value, const char* rule) {
    return fmt::format("MoeadOptions::{} = {}. Violated constraint: {}", name, value, rule);
  };
  if (weights.empty() && divisions < 1) return violated("divisions", divisions, "divisions >= 1");
  if (neighbours < 2) return violated("neighbours", neighbours, "neighbours >= 2");
  if (!(neighbourhood_probability >= 0.0 && neighbourhood_probability <= 1.0))
    return violated("neighbourhood_probability", neighbourhood_probability, "in [0, 1]");
  if (max_replacements < 1)
    return violated("max_replacements", max_replacements, "max_replacements >= 1");
  if (!(differential_weight > 0.0 && differential_weight <= 2.0))
    return violated("differential_weight", differential_weight, "in (0, 2]");
  if (!(crossover_rate >= 0.0 && crossover_rate <= 1.0))
    return violated("crossover_rate", crossover_rate, "in [0, 1]");
  return check_evolution_options("MoeadOptions", {1.0, 20.0, mutation_probability, mutation_eta},
                                 equality_tolerance, threads);
}

std::vector<std::vector<double>> moead_weights(const MoeadOptions& options, std::size_t m) {
  if (options.weights.empty())
    return two_layer_directions(m, options.divisions, options.inner_divisions);
  for (const std::vector<double>& w : options.weights) {
    double sum = 0.0;
    bool ok = w.size() == m;
    for (double v : w) {
      ok = ok && std::isfinite(v) && v >= 0.0;
      sum += v;
    }
    if (!ok || !(sum > 0.0))
      throw std::invalid_argument(
          fmt::format("moead: expected weight vectors of {} finite components >= 0, not all 0", m));
  }
  return options.weights;
}

FrontResult run_moead(const Problem& problem, const MoeadOptions& options) {
  if (auto error = options.validate()) throw std::invalid_argument(*error);
  if (auto reason = nsga2_explain_unsupported(problem))
    throw std::invalid_argument(fmt::format("moead: {}", *reason));
  const auto start = std::chrono::steady_clock::now();
  CountingProblem counted(problem);
  const Bounds bounds = problem.bounds();
  const std::size_t n = bounds.lower.size();
  const std::size_t m = problem.num_objectives();
  const std::vector<std::vector<double>> weights = moead_weights(options, m);
  const std::size_t size = weights.size();
  if (size < 3)
    throw std::invalid_argument(fmt::format(
        "moead: expected at least 3 weight vectors (a population of 3), found {}", size));
  const std::vector<std::vector<std::size_t>> near =
      neighbourhoods(weights, std::min(options.neighbours, size));
  const double mutation_probability =
      resolved_mutation_probability(options.mutation_probability, n);
  Random rng(options.seed);

  std::vector<Individual> population =
      initial_individuals(problem, size, options.initial_population, rng, "moead");
  evaluate_individuals(counted, population, 0, options.threads, options.equality_tolerance);
  Frame frame;
  for (const Individual& x : population) frame.see(x, m);
  std::vector<std::size_t> all(size);
  std::iota(all.begin(), all.end(), 0);

  std::vector<double> nadir;  // of the population, kept until a member is replaced
  bool nadir_current = false, nadir_feasible = false;
  for (std::size_t generation = 0; generation < options.generations; ++generation) {
    std::vector<std::size_t> order = all;
    rng.shuffle(order);
    std::vector<Individual> children(size);
    std::vector<bool> local(size);
    for (std::size_t k = 0; k < size; ++k) {
      const std::size_t i = order[k];
      local[k] = rng.bernoulli(options.neighbourhood_probability);
      const std::vector<std::size_t>& pool = local[k] ? near[i] : all;
      const std::size_t a = pool[rng.below(pool.size())];
      std::size_t b = pool[rng.below(pool.size())];
      while (b == a) b = pool[rng.below(pool.size())];
      children[k].x = de_child(population[i].x, population[a].x, population[b].x, bounds, options,
                               mutation_probability, rng);
    }
    evaluate_individuals(counted, children, 0, options.threads, options.equality_tolerance);
    for (std::size_t k = 0; k < size; ++k) {
      const Individual& child = children[k];
      frame.see(child, m);
      const std::vector<double>& z = frame.best();
      std::vector<double> scale(m, 1.0);
      if (options.normalize) {
        // The nadir changes only when members are replaced or the first feasible design comes.
        if (!nadir_current || nadir_feasible != frame.any_feasible) {
          nadir = population_nadir(population, m, frame.any_feasible);
          nadir_feasible = frame.any_feasible;
          nadir_current = true;
        }
        for (std::size_t j = 0; j < m; ++j) {
          const double range = nadir[j] - z[j];
          scale[j] = std::isfinite(range) && range > 0.0 ? range : 1.0;
        }
      }
      std::vector<std::size_t> pool = local[k] ? near[order[k]] : all;
      rng.shuffle(pool);
      std::size_t replaced = 0;
      for (std::size_t j : pool) {
        if (replaced == options.max_replacements) break;
        const Individual& member = population[j];
        const bool better = child.violation != member.violation
                                ? child.violation < member.violation
                                : tchebycheff(child, weights[j], z, scale) <=
                                      tchebycheff(member, weights[j], z, scale);
        if (!better) continue;
        population[j] = child;
        nadir_current = false;
        ++replaced;
      }
    }
  }
  return population_front(problem, population, options.equality_tolerance, "moead", counted, start);
}

}  // namespace pkmopt
