#include "optimizer/aspiration_directions.hpp"

#include <cmath>
#include <stdexcept>

#include "optimizer/reference_directions.hpp"

namespace pkmopt {

std::size_t default_aspiration_divisions(std::size_t objectives) {
  if (objectives < 2) return 1;
  std::size_t divisions = 1;
  while (das_dennis_count(objectives, divisions + 1) <= 30) ++divisions;
  return divisions;
}

std::vector<std::vector<double>> aspiration_directions(
    const std::vector<std::vector<double>>& normalised_points, std::size_t divisions,
    double spread) {
  if (normalised_points.empty())
    throw std::invalid_argument("aspiration_directions: no aspiration point");
  if (!(spread > 0.0 && spread <= 1.0))
    throw std::invalid_argument("aspiration_directions: spread must be in (0, 1]");
  const std::size_t m = normalised_points.front().size();
  const std::vector<std::vector<double>> local = das_dennis_directions(m, divisions);
  const double md = static_cast<double>(m);
  std::vector<std::vector<double>> directions;
  directions.reserve(normalised_points.size() * local.size() + m);
  for (const std::vector<double>& z : normalised_points) {
    if (z.size() != m) throw std::invalid_argument("aspiration_directions: points differ in size");
    double sum = 0.0;
    for (double v : z) {
      if (!std::isfinite(v))
        throw std::invalid_argument("aspiration_directions: a component is not finite");
      sum += v;
    }
    std::vector<double> p(m);
    for (std::size_t i = 0; i < m; ++i) p[i] = z[i] + (1.0 - sum) / md;
    for (const std::vector<double>& w0 : local) {
      std::vector<double> w(m);
      double total = 0.0;
      bool clipped = false;
      for (std::size_t i = 0; i < m; ++i) {
        w[i] = spread * w0[i] + p[i] - spread / md;
        if (w[i] < 0.0) {
          w[i] = 0.0;
          clipped = true;
        }
        total += w[i];
      }
      if (clipped)
        for (double& v : w) v /= total;
      directions.push_back(std::move(w));
    }
  }
  for (std::size_t j = 0; j < m; ++j) {
    std::vector<double> e(m, 0.0);
    e[j] = 1.0;
    directions.push_back(std::move(e));
  }
  return directions;
}

}  // namespace pkmopt
