#include "optimizer/front_result.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "optimizer/archive.hpp"

namespace pkmopt {

ObjectiveSet FrontResult::objectives() const {
  ObjectiveSet result;
  result.reserve(fitness.size());
  for (const auto& f : fitness)
    result.emplace_back(f.begin(), f.begin() + static_cast<std::ptrdiff_t>(num_objectives));
  return result;
}

FrontResult make_front(const Problem& problem, const std::vector<std::vector<double>>& xs,
                       const std::vector<std::vector<double>>& fitness, double equality_tolerance,
                       double inequality_tolerance) {
  const std::size_t m = problem.num_objectives();
  std::vector<std::size_t> candidates;
  ObjectiveSet objectives;
  for (std::size_t k = 0; k < fitness.size(); ++k) {
    const auto& f = fitness[k];
    if (f.size() != problem.fitness_size()) continue;
    const bool finite = std::all_of(f.begin(), f.begin() + static_cast<std::ptrdiff_t>(m),
                                    [](double v) { return std::isfinite(v); });
    if (!finite || constraint_violation(problem, f, equality_tolerance, inequality_tolerance) > 0.0)
      continue;
    candidates.push_back(k);
    objectives.emplace_back(f.begin(), f.begin() + static_cast<std::ptrdiff_t>(m));
  }
  std::vector<std::size_t> keep = non_dominated_indices(objectives);
  std::sort(keep.begin(), keep.end(),
            [&](std::size_t a, std::size_t b) { return objectives[a] < objectives[b]; });
  FrontResult front;
  front.num_objectives = m;
  for (std::size_t index : keep) {
    front.x.push_back(xs[candidates[index]]);
    front.fitness.push_back(fitness[candidates[index]]);
  }
  return front;
}

}  // namespace pkmopt
