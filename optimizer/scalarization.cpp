#include "optimizer/scalarization.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace pkmopt {

ScalarizedProblem::ScalarizedProblem(const Problem& base, std::vector<double> weights,
                                     std::vector<ObjectiveBound> objective_bounds)
    : base_(base), weights_(std::move(weights)), objective_bounds_(std::move(objective_bounds)) {
  if (weights_.size() != base.num_objectives())
    throw std::invalid_argument("ScalarizedProblem: one weight per objective expected");
  for (const ObjectiveBound& b : objective_bounds_)
    if (b.objective >= base.num_objectives() || !(b.scale > 0.0))
      throw std::invalid_argument("ScalarizedProblem: bad objective bound");
}

// Works on rows of the base fitness (columns = 1) or of its Jacobian (columns = n).
std::vector<double> ScalarizedProblem::scalarise(const std::vector<double>& base_rows,
                                                 std::size_t columns) const {
  const std::size_t m = base_.num_objectives();
  const std::size_t constraints = base_.num_constraints();
  std::vector<double> out((1 + constraints + objective_bounds_.size()) * columns, 0.0);
  for (std::size_t i = 0; i < m; ++i)
    if (weights_[i] != 0.0)
      for (std::size_t c = 0; c < columns; ++c) out[c] += weights_[i] * base_rows[i * columns + c];
  std::copy(base_rows.begin() + static_cast<std::ptrdiff_t>(m * columns), base_rows.end(),
            out.begin() + static_cast<std::ptrdiff_t>(columns));
  for (std::size_t k = 0; k < objective_bounds_.size(); ++k) {
    const ObjectiveBound& b = objective_bounds_[k];
    for (std::size_t c = 0; c < columns; ++c)
      out[(1 + constraints + k) * columns + c] = base_rows[b.objective * columns + c] / b.scale;
  }
  return out;
}

std::vector<double> ScalarizedProblem::fitness(const std::vector<double>& x) const {
  std::vector<double> out = scalarise(checked_fitness(base_, x), 1);
  const std::size_t first = 1 + base_.num_constraints();
  for (std::size_t k = 0; k < objective_bounds_.size(); ++k)
    out[first + k] -= objective_bounds_[k].epsilon / objective_bounds_[k].scale;
  return out;
}

std::vector<double> ScalarizedProblem::gradient(const std::vector<double>& x) const {
  return scalarise(dense_jacobian(base_, x), x.size());
}

NbiProblem::NbiProblem(const Problem& base, std::vector<double> ideal, std::vector<double> range,
                       std::vector<double> chim_point, std::vector<double> normal,
                       bool equality_form)
    : base_(base),
      ideal_(std::move(ideal)),
      range_(std::move(range)),
      chim_point_(std::move(chim_point)),
      normal_(std::move(normal)),
      equality_form_(equality_form) {}

Bounds NbiProblem::bounds() const {
  Bounds b = base_.bounds();
  b.lower.push_back(-INFINITY);
  b.upper.push_back(INFINITY);
  return b;
}

std::size_t NbiProblem::num_equality() const {
  return base_.num_equality() + (equality_form_ ? base_.num_objectives() : 0);
}

std::size_t NbiProblem::num_inequality() const {
  return base_.num_inequality() + (equality_form_ ? 0 : base_.num_objectives());
}

std::vector<double> NbiProblem::fitness(const std::vector<double>& xt) const {
  const std::size_t n = xt.size() - 1;
  const std::size_t m = base_.num_objectives();
  const std::size_t p = base_.num_equality();
  const double t = xt[n];
  const std::vector<double> f =
      checked_fitness(base_, std::vector<double>(xt.begin(), xt.end() - 1));
  std::vector<double> nbi_rows(m);
  for (std::size_t i = 0; i < m; ++i)
    nbi_rows[i] = (f[i] - ideal_[i]) / range_[i] - chim_point_[i] - t * normal_[i];
  std::vector<double> out{-t};
  out.insert(out.end(), f.begin() + static_cast<std::ptrdiff_t>(m),
             f.begin() + static_cast<std::ptrdiff_t>(m + p));
  if (equality_form_) out.insert(out.end(), nbi_rows.begin(), nbi_rows.end());
  out.insert(out.end(), f.begin() + static_cast<std::ptrdiff_t>(m + p), f.end());
  if (!equality_form_) out.insert(out.end(), nbi_rows.begin(), nbi_rows.end());
  return out;
}

std::vector<double> NbiProblem::gradient(const std::vector<double>& xt) const {
  const std::size_t n = xt.size() - 1;
  const std::size_t m = base_.num_objectives();
  const std::size_t p = base_.num_equality();
  const std::size_t q = base_.num_inequality();
  const std::vector<double> jac =
      dense_jacobian(base_, std::vector<double>(xt.begin(), xt.end() - 1));
  const std::size_t columns = n + 1;
  std::vector<double> out((1 + p + q + m) * columns, 0.0);
  out[n] = -1.0;  // d(-t)/dt
  std::size_t row = 1;
  auto copy_base_row = [&](std::size_t base_row) {
    std::copy(jac.begin() + static_cast<std::ptrdiff_t>(base_row * n),
              jac.begin() + static_cast<std::ptrdiff_t>((base_row + 1) * n),
              out.begin() + static_cast<std::ptrdiff_t>(row * columns));
    ++row;
  };
  auto add_nbi_rows = [&] {
    for (std::size_t i = 0; i < m; ++i) {
      for (std::size_t j = 0; j < n; ++j) out[row * columns + j] = jac[i * n + j] / range_[i];
      out[row * columns + n] = -normal_[i];
      ++row;
    }
  };
  for (std::size_t k = 0; k < p; ++k) copy_base_row(m + k);
  if (equality_form_) add_nbi_rows();
  for (std::size_t k = 0; k < q; ++k) copy_base_row(m + p + k);
  if (!equality_form_) add_nbi_rows();
  return out;
}

double NbiProblem::feasible_t(const std::vector<double>& base_fitness) const {
  // F^_i - c_i - t n_i <= 0 with n_i < 0  <=>  t <= (c_i - F^_i) / |n_i|.
  double t = INFINITY;
  for (std::size_t i = 0; i < normal_.size(); ++i) {
    const double fhat = (base_fitness[i] - ideal_[i]) / range_[i];
    if (normal_[i] < 0.0) t = std::min(t, (chim_point_[i] - fhat) / -normal_[i]);
  }
  return std::isfinite(t) ? t : 0.0;
}

}  // namespace pkmopt
