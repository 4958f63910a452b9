#include "problems/benchmarks/benchmarks.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <numeric>
#include <stdexcept>

#include "optimizer/archive.hpp"

namespace pkmopt {
namespace {

constexpr double kPi = std::numbers::pi;
// Keeps sqrt(f_1) derivatives finite at f_1 = 0 (ZDT1/3/4 at x_1 = 0).
constexpr double kTiny = 1e-300;

// Keeps the non-dominated points of a dense sample and thins them to about n_points.
ObjectiveSet thin_front(const ObjectiveSet& dense, std::size_t n_points) {
  ObjectiveSet front;
  for (std::size_t k : non_dominated_indices(dense)) front.push_back(dense[k]);
  std::sort(front.begin(), front.end());
  if (n_points == 0 || front.size() <= n_points) return front;
  ObjectiveSet thinned;
  thinned.reserve(n_points);
  for (std::size_t k = 0; k < n_points; ++k)
    thinned.push_back(front[k * (front.size() - 1) / (n_points - 1 == 0 ? 1 : n_points - 1)]);
  return thinned;
}

// Das–Dennis lattice: all w >= 0 with sum w = 1 and w_i multiples of 1/divisions.
void simplex_lattice(std::size_t m, std::size_t divisions, std::size_t index, std::size_t left,
                     std::vector<double>& current, ObjectiveSet& out) {
  if (index + 1 == m) {
    current[index] = static_cast<double>(left) / static_cast<double>(divisions);
    out.push_back(current);
    return;
  }
  for (std::size_t k = 0; k <= left; ++k) {
    current[index] = static_cast<double>(k) / static_cast<double>(divisions);
    simplex_lattice(m, divisions, index + 1, left - k, current, out);
  }
}

ObjectiveSet simplex_points(std::size_t m, std::size_t n_points) {
  std::size_t divisions = 1;
  auto count = [m](std::size_t h) {
    double c = 1.0;  // binomial(h + m - 1, m - 1)
    for (std::size_t i = 1; i < m; ++i) c = c * static_cast<double>(h + i) / static_cast<double>(i);
    return c;
  };
  while (count(divisions) < static_cast<double>(n_points)) ++divisions;
  ObjectiveSet out;
  std::vector<double> current(m);
  simplex_lattice(m, divisions, 0, divisions, current, out);
  return out;
}

void require_size(const std::vector<double>& x, std::size_t n, const std::string& name) {
  if (x.size() != n)
    throw std::invalid_argument(
        fmt::format("problem '{}': expected {} variables, got {}", name, n, x.size()));
}

}  // namespace

// ---- ZDT ---------------------------------------------------------------------------------------

Zdt::Zdt(int kind, std::size_t variables) : kind_(kind), variables_(variables) {
  if (kind != 1 && kind != 2 && kind != 3 && kind != 4 && kind != 6)
    throw std::invalid_argument(fmt::format("zdt{} does not exist (1, 2, 3, 4 or 6)", kind));
  if (variables < 2)
    throw std::invalid_argument(
        fmt::format("zdt{} needs at least 2 variables, got {}", kind, variables));
}

Bounds Zdt::bounds() const {
  Bounds b{std::vector<double>(variables_, 0.0), std::vector<double>(variables_, 1.0)};
  if (kind_ == 4)
    for (std::size_t i = 1; i < variables_; ++i) {
      b.lower[i] = -5.0;
      b.upper[i] = 5.0;
    }
  return b;
}

namespace {

struct ZdtParts {
  double f1, df1_dx1, g;
  std::vector<double> dg_dx;  // d g / d x_i for i >= 1 (index 0 unused)
};

ZdtParts zdt_parts(int kind, const std::vector<double>& x, bool with_derivatives) {
  const std::size_t n = x.size();
  ZdtParts parts{};
  if (kind == 6) {
    const double e = std::exp(-4.0 * x[0]);
    const double s = std::sin(6.0 * kPi * x[0]);
    parts.f1 = 1.0 - e * std::pow(s, 6);
    parts.df1_dx1 = 4.0 * e * std::pow(s, 6) -
                    e * 6.0 * std::pow(s, 5) * std::cos(6.0 * kPi * x[0]) * 6.0 * kPi;
  } else {
    parts.f1 = x[0];
    parts.df1_dx1 = 1.0;
  }
  if (with_derivatives) parts.dg_dx.assign(n, 0.0);
  const double scale = 1.0 / static_cast<double>(n - 1);
  if (kind == 4) {
    double sum = 0.0;
    for (std::size_t i = 1; i < n; ++i) {
      sum += x[i] * x[i] - 10.0 * std::cos(4.0 * kPi * x[i]);
      if (with_derivatives) parts.dg_dx[i] = 2.0 * x[i] + 40.0 * kPi * std::sin(4.0 * kPi * x[i]);
    }
    parts.g = 1.0 + 10.0 * static_cast<double>(n - 1) + sum;
  } else if (kind == 6) {
    const double mean = std::accumulate(x.begin() + 1, x.end(), 0.0) * scale;
    parts.g = 1.0 + 9.0 * std::pow(mean, 0.25);
    if (with_derivatives)
      for (std::size_t i = 1; i < n; ++i)
        parts.dg_dx[i] = 9.0 * 0.25 * std::pow(std::max(mean, kTiny), -0.75) * scale;
  } else {
    const double sum = std::accumulate(x.begin() + 1, x.end(), 0.0);
    parts.g = 1.0 + 9.0 * sum * scale;
    if (with_derivatives)
      for (std::size_t i = 1; i < n; ++i) parts.dg_dx[i] = 9.0 * scale;
  }
  return parts;
}

// f_2 = g h(f_1, g) and its partial derivatives in f_1 and g.
void zdt_second(int kind, double f1, double g, double& f2, double& df2_df1, double& df2_dg) {
  switch (kind) {
    case 2:
    case 6:
      f2 = g - f1 * f1 / g;
      df2_df1 = -2.0 * f1 / g;
      df2_dg = 1.0 + f1 * f1 / (g * g);
      return;
    case 3: {
      const double root = std::sqrt(std::max(f1, 0.0) * g);
      f2 = g - root - f1 * std::sin(10.0 * kPi * f1);
      df2_df1 = -0.5 * std::sqrt(g / std::max(f1, kTiny)) - std::sin(10.0 * kPi * f1) -
                10.0 * kPi * f1 * std::cos(10.0 * kPi * f1);
      df2_dg = 1.0 - 0.5 * std::sqrt(std::max(f1, 0.0) / g);
      return;
    }
    default: {  // 1 and 4
      const double root = std::sqrt(std::max(f1, 0.0) * g);
      f2 = g - root;
      df2_df1 = -0.5 * std::sqrt(g / std::max(f1, kTiny));
      df2_dg = 1.0 - 0.5 * std::sqrt(std::max(f1, 0.0) / g);
      return;
    }
  }
}

}  // namespace

std::vector<double> Zdt::fitness(const std::vector<double>& x) const {
  require_size(x, variables_, name());
  const ZdtParts parts = zdt_parts(kind_, x, false);
  double f2, df2_df1, df2_dg;
  zdt_second(kind_, parts.f1, parts.g, f2, df2_df1, df2_dg);
  return {parts.f1, f2};
}

SparsityPattern Zdt::gradient_sparsity() const {
  SparsityPattern pattern{{0, 0}};
  for (std::size_t j = 0; j < variables_; ++j) pattern.emplace_back(1, j);
  return pattern;
}

std::vector<double> Zdt::gradient(const std::vector<double>& x) const {
  require_size(x, variables_, name());
  const ZdtParts parts = zdt_parts(kind_, x, true);
  double f2, df2_df1, df2_dg;
  zdt_second(kind_, parts.f1, parts.g, f2, df2_df1, df2_dg);
  std::vector<double> values{parts.df1_dx1, df2_df1 * parts.df1_dx1};
  for (std::size_t j = 1; j < variables_; ++j) values.push_back(df2_dg * parts.dg_dx[j]);
  return values;
}

ObjectiveSet Zdt::reference_front(std::size_t n_points) const {
  const std::size_t n = std::max<std::size_t>(n_points, 2);
  auto second = [this](double f1) {
    double f2, a, b;
    zdt_second(kind_, f1, 1.0, f2, a, b);
    return f2;
  };
  if (kind_ == 3) {
    ObjectiveSet dense;
    const std::size_t samples = 200 * n;
    for (std::size_t k = 0; k < samples; ++k) {
      const double f1 = static_cast<double>(k) / static_cast<double>(samples - 1);
      dense.push_back({f1, second(f1)});
    }
    return thin_front(dense, n);
  }
  const double f1_min = kind_ == 6 ? 0.2807753191 : 0.0;
  ObjectiveSet front;
  for (std::size_t k = 0; k < n; ++k) {
    const double f1 = f1_min + (1.0 - f1_min) * static_cast<double>(k) / static_cast<double>(n - 1);
    front.push_back({f1, second(f1)});
  }
  return front;
}

// ---- DTLZ --------------------------------------------------------------------------------------

Dtlz::Dtlz(int kind, std::size_t objectives, std::size_t variables)
    : kind_(kind), objectives_(objectives), variables_(variables) {
  if (kind != 1 && kind != 2 && kind != 3 && kind != 4 && kind != 7)
    throw std::invalid_argument(fmt::format("dtlz{} is not provided (1, 2, 3, 4 or 7)", kind));
  if (objectives < 2)
    throw std::invalid_argument(
        fmt::format("dtlz{} needs at least 2 objectives, got {}", kind, objectives));
  if (variables < objectives)
    throw std::invalid_argument(
        fmt::format("dtlz{} with {} objectives needs at least {} variables, got {}", kind,
                    objectives, objectives, variables));
}

Bounds Dtlz::bounds() const {
  return {std::vector<double>(variables_, 0.0), std::vector<double>(variables_, 1.0)};
}

std::vector<double> Dtlz::fitness(const std::vector<double>& x) const {
  require_size(x, variables_, name());
  const std::size_t m = objectives_;
  const std::size_t k = variables_ - m + 1;
  std::vector<double> f(m, 0.0);
  if (kind_ == 7) {
    double sum = 0.0;
    for (std::size_t i = m - 1; i < variables_; ++i) sum += x[i];
    const double g = 1.0 + 9.0 * sum / static_cast<double>(k);
    double h = static_cast<double>(m);
    for (std::size_t i = 0; i + 1 < m; ++i) {
      f[i] = x[i];
      h -= f[i] / (1.0 + g) * (1.0 + std::sin(3.0 * kPi * f[i]));
    }
    f[m - 1] = (1.0 + g) * h;
    return f;
  }
  double g = 0.0;
  if (kind_ == 1 || kind_ == 3) {
    double sum = 0.0;
    for (std::size_t i = m - 1; i < variables_; ++i)
      sum += (x[i] - 0.5) * (x[i] - 0.5) - std::cos(20.0 * kPi * (x[i] - 0.5));
    g = 100.0 * (static_cast<double>(k) + sum);
  } else {
    for (std::size_t i = m - 1; i < variables_; ++i) g += (x[i] - 0.5) * (x[i] - 0.5);
  }
  for (std::size_t i = 0; i < m; ++i) {
    if (kind_ == 1) {
      double value = 0.5 * (1.0 + g);
      for (std::size_t j = 0; j + 1 + i < m; ++j) value *= x[j];
      if (i > 0) value *= 1.0 - x[m - 1 - i];
      f[i] = value;
    } else {
      const double alpha = kind_ == 4 ? 100.0 : 1.0;
      auto angle = [&](std::size_t j) { return std::pow(x[j], alpha) * kPi / 2.0; };
      double value = 1.0 + g;
      for (std::size_t j = 0; j + 1 + i < m; ++j) value *= std::cos(angle(j));
      if (i > 0) value *= std::sin(angle(m - 1 - i));
      f[i] = value;
    }
  }
  return f;
}

ObjectiveSet Dtlz::reference_front(std::size_t n_points) const {
  const std::size_t m = objectives_;
  if (kind_ == 7) {
    // Grid over f_1..f_{m-1} in [0, 1], f_m at g = 1, then the non-dominated part.
    const std::size_t per_axis = std::max<std::size_t>(
        8, static_cast<std::size_t>(std::ceil(
               std::pow(20.0 * static_cast<double>(n_points), 1.0 / static_cast<double>(m - 1)))));
    ObjectiveSet dense;
    std::vector<std::size_t> index(m - 1, 0);
    while (true) {
      std::vector<double> f(m);
      double h = static_cast<double>(m);
      for (std::size_t i = 0; i + 1 < m; ++i) {
        f[i] = static_cast<double>(index[i]) / static_cast<double>(per_axis - 1);
        h -= f[i] / 2.0 * (1.0 + std::sin(3.0 * kPi * f[i]));
      }
      f[m - 1] = 2.0 * h;
      dense.push_back(std::move(f));
      std::size_t axis = 0;
      while (axis + 1 < m && ++index[axis] == per_axis) index[axis++] = 0;
      if (axis + 1 == m) break;
    }
    ObjectiveSet front;
    for (std::size_t k : non_dominated_indices(dense)) front.push_back(dense[k]);
    if (front.size() <= n_points || m > 2) return front;
    return thin_front(front, n_points);
  }
  ObjectiveSet front = simplex_points(m, std::max<std::size_t>(n_points, m));
  for (auto& f : front) {
    if (kind_ == 1) {
      for (double& v : f) v *= 0.5;
    } else {
      const double norm = std::sqrt(std::inner_product(f.begin(), f.end(), f.begin(), 0.0));
      for (double& v : f) v /= norm;
    }
  }
  return front;
}

// ---- BNH ---------------------------------------------------------------------------------------

std::vector<double> Bnh::fitness(const std::vector<double>& x) const {
  require_size(x, 2, name());
  return {4.0 * x[0] * x[0] + 4.0 * x[1] * x[1],
          (x[0] - 5.0) * (x[0] - 5.0) + (x[1] - 5.0) * (x[1] - 5.0),
          (x[0] - 5.0) * (x[0] - 5.0) + x[1] * x[1] - 25.0,
          7.7 - (x[0] - 8.0) * (x[0] - 8.0) - (x[1] + 3.0) * (x[1] + 3.0)};
}

std::vector<double> Bnh::gradient(const std::vector<double>& x) const {
  require_size(x, 2, name());
  return {8.0 * x[0],         8.0 * x[1], 2.0 * (x[0] - 5.0),  2.0 * (x[1] - 5.0),
          2.0 * (x[0] - 5.0), 2.0 * x[1], -2.0 * (x[0] - 8.0), -2.0 * (x[1] + 3.0)};
}

ObjectiveSet Bnh::reference_front(std::size_t n_points) const {
  // Pareto set: x1 = x2 in [0, 3], then x2 = 3 with x1 in [3, 5] (Deb 2001).
  ObjectiveSet dense;
  const std::size_t samples = 50 * std::max<std::size_t>(n_points, 2);
  for (std::size_t k = 0; k < samples; ++k) {
    const double t = 5.0 * static_cast<double>(k) / static_cast<double>(samples - 1);
    const std::vector<double> x{t, std::min(t, 3.0)};
    const std::vector<double> f = fitness(x);
    dense.push_back({f[0], f[1]});
  }
  return thin_front(dense, n_points);
}

// ---- SRN ---------------------------------------------------------------------------------------

std::vector<double> Srn::fitness(const std::vector<double>& x) const {
  require_size(x, 2, name());
  return {2.0 + (x[0] - 2.0) * (x[0] - 2.0) + (x[1] - 1.0) * (x[1] - 1.0),
          9.0 * x[0] - (x[1] - 1.0) * (x[1] - 1.0), x[0] * x[0] + x[1] * x[1] - 225.0,
          x[0] - 3.0 * x[1] + 10.0};
}

std::vector<double> Srn::gradient(const std::vector<double>& x) const {
  require_size(x, 2, name());
  return {2.0 * (x[0] - 2.0), 2.0 * (x[1] - 1.0), 9.0, -2.0 * (x[1] - 1.0),
          2.0 * x[0],         2.0 * x[1],         1.0, -3.0};
}

ObjectiveSet Srn::reference_front(std::size_t n_points) const {
  // Pareto set: x1 = -2.5, 2.5 <= x2 <= sqrt(225 - 6.25) (Deb 2001).
  ObjectiveSet dense;
  const std::size_t samples = 50 * std::max<std::size_t>(n_points, 2);
  const double top = std::sqrt(225.0 - 6.25);
  for (std::size_t k = 0; k < samples; ++k) {
    const double x2 = 2.5 + (top - 2.5) * static_cast<double>(k) / static_cast<double>(samples - 1);
    const std::vector<double> f = fitness({-2.5, x2});
    dense.push_back({f[0], f[1]});
  }
  return thin_front(dense, n_points);
}

// ---- TNK ---------------------------------------------------------------------------------------

Bounds Tnk::bounds() const { return {{0.0, 1e-12}, {kPi, kPi}}; }

std::vector<double> Tnk::fitness(const std::vector<double>& x) const {
  require_size(x, 2, name());
  return {x[0], x[1],
          1.0 + 0.1 * std::cos(16.0 * std::atan(x[0] / x[1])) - x[0] * x[0] - x[1] * x[1],
          (x[0] - 0.5) * (x[0] - 0.5) + (x[1] - 0.5) * (x[1] - 0.5) - 0.5};
}

std::vector<double> Tnk::gradient(const std::vector<double>& x) const {
  require_size(x, 2, name());
  const double r2 = x[0] * x[0] + x[1] * x[1];
  const double s = std::sin(16.0 * std::atan(x[0] / x[1]));
  return {1.0,
          0.0,
          0.0,
          1.0,
          -1.6 * s * x[1] / r2 - 2.0 * x[0],
          1.6 * s * x[0] / r2 - 2.0 * x[1],
          2.0 * (x[0] - 0.5),
          2.0 * (x[1] - 0.5)};
}

ObjectiveSet Tnk::reference_front(std::size_t n_points) const {
  // The front lies on g1 = 0: along a ray at angle theta = atan(x1/x2) from the x2 axis the
  // boundary radius is sqrt(1 + 0.1 cos(16 theta)); keep the part with g2 <= 0.
  ObjectiveSet dense;
  const std::size_t samples = 400 * std::max<std::size_t>(n_points, 2);
  for (std::size_t k = 0; k < samples; ++k) {
    const double theta = kPi / 2.0 * static_cast<double>(k) / static_cast<double>(samples - 1);
    const double r = std::sqrt(1.0 + 0.1 * std::cos(16.0 * theta));
    const double x1 = r * std::sin(theta);
    const double x2 = r * std::cos(theta);
    if ((x1 - 0.5) * (x1 - 0.5) + (x2 - 0.5) * (x2 - 0.5) - 0.5 <= 0.0) dense.push_back({x1, x2});
  }
  return thin_front(dense, n_points);
}

// ---- OSY ---------------------------------------------------------------------------------------

Bounds Osy::bounds() const { return {{0, 0, 1, 0, 1, 0}, {10, 10, 5, 6, 5, 10}}; }

std::vector<double> Osy::fitness(const std::vector<double>& x) const {
  require_size(x, 6, name());
  const double f1 = -(25.0 * (x[0] - 2) * (x[0] - 2) + (x[1] - 2) * (x[1] - 2) +
                      (x[2] - 1) * (x[2] - 1) + (x[3] - 4) * (x[3] - 4) + (x[4] - 1) * (x[4] - 1));
  double f2 = 0.0;
  for (double v : x) f2 += v * v;
  return {f1,
          f2,
          2.0 - x[0] - x[1],
          x[0] + x[1] - 6.0,
          x[1] - x[0] - 2.0,
          x[0] - 3.0 * x[1] - 2.0,
          (x[2] - 3) * (x[2] - 3) + x[3] - 4.0,
          4.0 - (x[4] - 3) * (x[4] - 3) - x[5]};
}

std::vector<double> Osy::gradient(const std::vector<double>& x) const {
  require_size(x, 6, name());
  std::vector<double> jacobian(8 * 6, 0.0);
  auto at = [&](std::size_t row, std::size_t column) -> double& {
    return jacobian[row * 6 + column];
  };
  at(0, 0) = -50.0 * (x[0] - 2);
  at(0, 1) = -2.0 * (x[1] - 2);
  at(0, 2) = -2.0 * (x[2] - 1);
  at(0, 3) = -2.0 * (x[3] - 4);
  at(0, 4) = -2.0 * (x[4] - 1);
  for (std::size_t j = 0; j < 6; ++j) at(1, j) = 2.0 * x[j];
  at(2, 0) = -1;
  at(2, 1) = -1;
  at(3, 0) = 1;
  at(3, 1) = 1;
  at(4, 0) = -1;
  at(4, 1) = 1;
  at(5, 0) = 1;
  at(5, 1) = -3;
  at(6, 2) = 2.0 * (x[2] - 3);
  at(6, 3) = 1;
  at(7, 4) = -2.0 * (x[4] - 3);
  at(7, 5) = -1;
  return jacobian;
}

ObjectiveSet Osy::reference_front(std::size_t n_points) const {
  // Pareto set (Deb 2001, table for OSY; x4 = x6 = 0), five pieces; sampled and filtered.
  ObjectiveSet dense;
  const std::size_t samples = 100 * std::max<std::size_t>(n_points, 2);
  auto add = [&](const std::vector<double>& x) {
    const std::vector<double> f = fitness(x);
    dense.push_back({f[0], f[1]});
  };
  for (std::size_t k = 0; k < samples; ++k) {
    const double t = static_cast<double>(k) / static_cast<double>(samples - 1);
    add({5, 1, 1 + 4 * t, 0, 5, 0});
    add({5, 1, 1 + 4 * t, 0, 1, 0});
    const double x1 = 4.056 + (5 - 4.056) * t;
    add({x1, (x1 - 2) / 3, 1, 0, 1, 0});
    add({0, 2, 1 + 2.732 * t, 0, 1, 0});
    add({t, 2 - t, 1, 0, 1, 0});
  }
  return thin_front(dense, n_points);
}

// ---- HS71 and Rosenbrock -----------------------------------------------------------------------

std::vector<double> Hs71::fitness(const std::vector<double>& x) const {
  require_size(x, 4, name());
  return {x[0] * x[3] * (x[0] + x[1] + x[2]) + x[2],
          x[0] * x[0] + x[1] * x[1] + x[2] * x[2] + x[3] * x[3] - 40.0,
          25.0 - x[0] * x[1] * x[2] * x[3]};
}

std::vector<double> Hs71::gradient(const std::vector<double>& x) const {
  require_size(x, 4, name());
  const double s = x[0] + x[1] + x[2];
  return {x[3] * s + x[0] * x[3],
          x[0] * x[3],
          x[0] * x[3] + 1.0,
          x[0] * s,
          2 * x[0],
          2 * x[1],
          2 * x[2],
          2 * x[3],
          -x[1] * x[2] * x[3],
          -x[0] * x[2] * x[3],
          -x[0] * x[1] * x[3],
          -x[0] * x[1] * x[2]};
}

Rosenbrock::Rosenbrock(std::size_t variables) : variables_(variables) {
  if (variables < 2)
    throw std::invalid_argument(
        fmt::format("rosenbrock needs at least 2 variables, got {}", variables));
}

Bounds Rosenbrock::bounds() const {
  return {std::vector<double>(variables_, -5.0), std::vector<double>(variables_, 10.0)};
}

std::vector<double> Rosenbrock::fitness(const std::vector<double>& x) const {
  require_size(x, variables_, name());
  double f = 0.0;
  for (std::size_t i = 0; i + 1 < variables_; ++i)
    f += 100.0 * (x[i + 1] - x[i] * x[i]) * (x[i + 1] - x[i] * x[i]) + (1.0 - x[i]) * (1.0 - x[i]);
  return {f};
}

std::vector<double> Rosenbrock::gradient(const std::vector<double>& x) const {
  require_size(x, variables_, name());
  std::vector<double> g(variables_, 0.0);
  for (std::size_t i = 0; i + 1 < variables_; ++i) {
    const double r = x[i + 1] - x[i] * x[i];
    g[i] += -400.0 * r * x[i] - 2.0 * (1.0 - x[i]);
    g[i + 1] += 200.0 * r;
  }
  return g;
}

// ---- Factory -----------------------------------------------------------------------------------

std::vector<std::string> benchmark_names() {
  return {"zdt1",  "zdt2",  "zdt3", "zdt4", "zdt6", "dtlz1", "dtlz2", "dtlz3",
          "dtlz4", "dtlz7", "bnh",  "srn",  "tnk",  "osy",   "hs71",  "rosenbrock"};
}

std::unique_ptr<BenchmarkProblem> make_benchmark(std::string_view name, std::size_t variables,
                                                 std::size_t objectives) {
  const std::string key(name);
  if (variables > kMaxBenchmarkVariables)
    throw std::invalid_argument(
        fmt::format("expected at most {} variables, found {}", kMaxBenchmarkVariables, variables));
  if (objectives > kMaxBenchmarkObjectives)
    throw std::invalid_argument(fmt::format("expected at most {} objectives, found {}",
                                            kMaxBenchmarkObjectives, objectives));
  if (objectives != 0 && !key.starts_with("dtlz"))
    throw std::invalid_argument(fmt::format(
        "'{}' has a fixed number of objectives; 'objectives' applies to DTLZ only", key));
  auto fixed = [&](std::unique_ptr<BenchmarkProblem> problem) {
    if (variables != 0 && variables != problem->num_variables())
      throw std::invalid_argument(fmt::format("'{}' has exactly {} variables, not {}", key,
                                              problem->num_variables(), variables));
    return problem;
  };
  if (key.size() == 4 && key.starts_with("zdt")) {
    const int kind = key[3] - '0';
    const std::size_t n = variables != 0 ? variables : (kind == 4 || kind == 6 ? 10 : 30);
    return std::make_unique<Zdt>(kind, n);
  }
  if (key.size() == 5 && key.starts_with("dtlz")) {
    const int kind = key[4] - '0';
    const std::size_t m = objectives != 0 ? objectives : 3;
    const std::size_t k = kind == 1 ? 5 : (kind == 7 ? 20 : 10);
    return std::make_unique<Dtlz>(kind, m, variables != 0 ? variables : m + k - 1);
  }
  if (key == "bnh") return fixed(std::make_unique<Bnh>());
  if (key == "srn") return fixed(std::make_unique<Srn>());
  if (key == "tnk") return fixed(std::make_unique<Tnk>());
  if (key == "osy") return fixed(std::make_unique<Osy>());
  if (key == "hs71") return fixed(std::make_unique<Hs71>());
  if (key == "rosenbrock") return std::make_unique<Rosenbrock>(variables != 0 ? variables : 10);
  std::string known;
  for (const std::string& n : benchmark_names()) known += (known.empty() ? "" : ", ") + n;
  throw std::invalid_argument(fmt::format("unknown benchmark '{}' (known: {})", key, known));
}

}  // namespace pkmopt
