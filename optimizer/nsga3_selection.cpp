#include "optimizer/nsga3_selection.hpp"

#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace pkmopt {
namespace {

constexpr double kAxisWeight = 1e-6;  // the other components of an axis's ASF weight

}  // namespace

Normalization normalize_objectives(const std::vector<std::vector<double>>& f,
                                   NormalizationMemory* memory) {
  if (f.empty() || f.front().empty())
    throw std::invalid_argument("normalize_objectives: expected objective vectors, found none");
  const std::size_t m = f.front().size();
  Normalization n;
  n.ideal.assign(m, std::numeric_limits<double>::infinity());
  for (const std::vector<double>& v : f) {
    if (v.size() != m)
      throw std::invalid_argument("normalize_objectives: objective vectors of different sizes");
    for (std::size_t j = 0; j < m; ++j) n.ideal[j] = std::min(n.ideal[j], v[j]);
  }
  // The candidates for the extreme points: the set, then the remembered ones.
  std::vector<const std::vector<double>*> candidates;
  for (const std::vector<double>& v : f) candidates.push_back(&v);
  if (memory != nullptr && memory->ideal.size() == m) {
    for (std::size_t j = 0; j < m; ++j) n.ideal[j] = std::min(n.ideal[j], memory->ideal[j]);
    for (const std::vector<double>& e : memory->extremes)
      if (e.size() == m) candidates.push_back(&e);
  }
  // Extreme points by the achievement scalarising function of each axis.
  Eigen::MatrixXd E(m, m);
  std::vector<double> worst(m, 0.0);
  std::vector<std::vector<double>> extreme_points;
  for (std::size_t axis = 0; axis < m; ++axis) {
    double best = std::numeric_limits<double>::infinity();
    std::size_t chosen = 0;
    for (std::size_t s = 0; s < candidates.size(); ++s) {
      double asf = 0.0;
      for (std::size_t i = 0; i < m; ++i) {
        const double shifted = (*candidates[s])[i] - n.ideal[i];
        if (s < f.size()) worst[i] = std::max(worst[i], shifted);
        asf = std::max(asf, shifted / (i == axis ? 1.0 : kAxisWeight));
      }
      if (asf < best) {
        best = asf;
        chosen = s;
      }
    }
    for (std::size_t i = 0; i < m; ++i)
      E(static_cast<Eigen::Index>(axis), static_cast<Eigen::Index>(i)) =
          (*candidates[chosen])[i] - n.ideal[i];
    extreme_points.push_back(*candidates[chosen]);
  }
  if (memory != nullptr) {
    memory->ideal = n.ideal;
    memory->extremes = extreme_points;
  }
  // The hyperplane through them: E b = 1, a = 1 / b.
  n.intercepts.assign(m, 0.0);
  const Eigen::FullPivLU<Eigen::MatrixXd> lu(E);
  bool ok = lu.rank() == static_cast<Eigen::Index>(m);
  if (ok) {
    const Eigen::VectorXd b = lu.solve(Eigen::VectorXd::Ones(static_cast<Eigen::Index>(m)));
    for (std::size_t j = 0; j < m && ok; ++j) {
      const double a = 1.0 / b(static_cast<Eigen::Index>(j));
      ok = std::isfinite(a) && a > 1e-10;
      n.intercepts[j] = a;
    }
  }
  n.from_hyperplane = ok;
  if (!ok)
    for (std::size_t j = 0; j < m; ++j) n.intercepts[j] = worst[j] > 0.0 ? worst[j] : 1.0;
  return n;
}

std::vector<std::vector<double>> normalized(const Normalization& n,
                                            const std::vector<std::vector<double>>& f) {
  std::vector<std::vector<double>> out = f;
  for (std::vector<double>& v : out)
    for (std::size_t j = 0; j < v.size(); ++j) v[j] = (v[j] - n.ideal[j]) / n.intercepts[j];
  return out;
}

std::vector<Association> associate(const std::vector<std::vector<double>>& points,
                                   const std::vector<std::vector<double>>& directions) {
  if (directions.empty())
    throw std::invalid_argument("associate: expected reference directions, found none");
  std::vector<Association> out(points.size());
  for (std::size_t p = 0; p < points.size(); ++p) {
    const std::vector<double>& f = points[p];
    double best = std::numeric_limits<double>::infinity();
    for (std::size_t d = 0; d < directions.size(); ++d) {
      const std::vector<double>& w = directions[d];
      double wf = 0.0, ww = 0.0;
      for (std::size_t j = 0; j < f.size(); ++j) {
        wf += w[j] * f[j];
        ww += w[j] * w[j];
      }
      // |f - (w.f / |w|^2) w|, from its components (no cancellation).
      double squared = 0.0;
      for (std::size_t j = 0; j < f.size(); ++j) {
        const double r = f[j] - wf / ww * w[j];
        squared += r * r;
      }
      const double distance = std::sqrt(squared);
      if (distance < best) {
        best = distance;
        out[p] = {d, distance};
      }
    }
  }
  return out;
}

std::vector<std::size_t> niche_select(std::size_t count, std::vector<std::size_t>& rho,
                                      const std::vector<Association>& last_front, Random& rng) {
  std::vector<std::size_t> chosen;
  std::vector<bool> taken(last_front.size(), false);
  std::vector<bool> excluded(rho.size(), false);
  for (const Association& a : last_front)
    if (a.direction >= rho.size())
      throw std::invalid_argument("niche_select: an association names no direction");
  while (chosen.size() < count && chosen.size() < last_front.size()) {
    std::size_t least = std::numeric_limits<std::size_t>::max();
    for (std::size_t d = 0; d < rho.size(); ++d)
      if (!excluded[d]) least = std::min(least, rho[d]);
    std::vector<std::size_t> candidates;
    for (std::size_t d = 0; d < rho.size(); ++d)
      if (!excluded[d] && rho[d] == least) candidates.push_back(d);
    const std::size_t d = candidates[rng.below(candidates.size())];
    std::vector<std::size_t> members;
    for (std::size_t k = 0; k < last_front.size(); ++k)
      if (!taken[k] && last_front[k].direction == d) members.push_back(k);
    if (members.empty()) {
      excluded[d] = true;
      continue;
    }
    std::size_t pick = members.front();
    if (rho[d] == 0) {
      for (std::size_t k : members)
        if (last_front[k].distance < last_front[pick].distance) pick = k;
    } else {
      pick = members[rng.below(members.size())];
    }
    taken[pick] = true;
    chosen.push_back(pick);
    ++rho[d];
  }
  return chosen;
}

}  // namespace pkmopt
