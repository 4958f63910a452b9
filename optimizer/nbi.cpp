#include "optimizer/nbi.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <stdexcept>
#include <utility>
#include <vector>

#include "optimizer/anchors.hpp"
#include "optimizer/front_sweep.hpp"
#include "optimizer/scalarization.hpp"

namespace pkmopt {
namespace {

void lattice(std::size_t dimensions, std::size_t divisions, std::size_t index, std::size_t left,
             std::vector<double>& current, std::vector<std::vector<double>>& out) {
  if (index + 1 == dimensions) {
    current[index] = static_cast<double>(left) / static_cast<double>(divisions);
    out.push_back(current);
    return;
  }
  for (std::size_t k = left + 1; k-- > 0;) {
    current[index] = static_cast<double>(k) / static_cast<double>(divisions);
    lattice(dimensions, divisions, index + 1, left - k, current, out);
  }
}

// max t on the line c + t n through the CHIM point c of one lattice point: NbiProblem on the
// counted problem, variables (x, t).
class NbiSubproblem final : public FrontSubproblem {
 public:
  NbiSubproblem(const Problem& counted, const AnchorSet& anchors, std::vector<double> chim,
                const std::vector<double>& normal, const std::vector<double>& beta,
                bool equality_form)
      : counted_(counted),
        sub_(counted, anchors.ideal, anchors.range, std::move(chim), normal, equality_form) {
    // Restarts from the anchors, nearest (largest weight) first.
    restart_anchors_.resize(beta.size());
    for (std::size_t i = 0; i < beta.size(); ++i) restart_anchors_[i] = i;
    std::stable_sort(restart_anchors_.begin(), restart_anchors_.end(),
                     [&](std::size_t a, std::size_t b) { return beta[a] > beta[b]; });
  }
  const Problem& problem() const override { return sub_; }
  /// The design x with t set to its largest feasible value for this subproblem.
  std::vector<double> start(const std::vector<double>& x,
                            const std::vector<double>& fx) const override {
    const double t = sub_.feasible_t(fx.empty() ? checked_fitness(counted_, x) : fx);
    std::vector<double> xt = x;
    xt.push_back(t);
    return xt;
  }
  /// The largest t the point reaches on this subproblem's line.
  double score(const std::vector<double>& f) const override { return sub_.feasible_t(f); }
  std::vector<std::size_t> restart_anchors() const override { return restart_anchors_; }

 private:
  const Problem& counted_;
  NbiProblem sub_;
  std::vector<std::size_t> restart_anchors_;
};

// The lattice points of the simplex spanned by the anchors (vertices excluded: the anchors).
SweepPlan plan_nbi(const Problem& counted, const AnchorSet& anchors, const NbiOptions& options) {
  SweepPlan plan;
  if (anchors.failed != 0) {
    plan.failure =
        fmt::format("{} anchor(s) failed, so NBI could not build its simplex", anchors.failed);
    return plan;
  }
  const std::size_t m = counted.num_objectives();
  // Normalised pay-off matrix and quasi-normal.
  std::vector<std::vector<double>> phi(m, std::vector<double>(m));
  std::vector<double> normal(m, 0.0);
  for (std::size_t i = 0; i < m; ++i)
    for (std::size_t j = 0; j < m; ++j) {
      phi[i][j] = (anchors.points[i].fitness[j] - anchors.ideal[j]) / anchors.range[j];
      normal[j] -= phi[i][j];
    }
  double norm = 0.0;
  for (double v : normal) norm += v * v;
  norm = std::sqrt(norm);
  for (double& v : normal) v = norm > 0.0 ? v / norm : -1.0 / std::sqrt(static_cast<double>(m));

  std::size_t divisions = 1;
  if (m == 2) {
    divisions = options.points - 1;
  } else {
    while (simplex_lattice(m, divisions).size() < options.points) ++divisions;
  }
  for (const std::vector<double>& beta : simplex_lattice(m, divisions)) {
    if (std::count(beta.begin(), beta.end(), 1.0) == 1) continue;  // an anchor
    std::vector<double> chim(m, 0.0);
    for (std::size_t i = 0; i < m; ++i)
      for (std::size_t j = 0; j < m; ++j) chim[j] += beta[i] * phi[i][j];
    plan.subproblems.push_back(std::make_unique<NbiSubproblem>(
        counted, anchors, std::move(chim), normal, beta, options.equality_form));
  }
  plan.first_x = anchors.points[0].x;
  plan.first_f = anchors.points[0].fitness;
  // Jumped: farther than 3 lattice steps (1 / divisions) from the previous result.
  plan.jump_step = 3.0 / static_cast<double>(divisions);
  plan.jump_max_steps = 1.0;
  // Repair: a known point beats a result when it reaches a t larger by 1e-5 on its line. In the
  // relaxed form the known point is itself feasible, so if Ipopt does no better it is the
  // lattice point's answer (a repeat, dropped by the driver).
  plan.repair_margin = 1e-5;
  plan.keep_known_on_failed_repair = !options.equality_form;
  plan.nan_covers = true;
  return plan;
}

}  // namespace

std::vector<std::vector<double>> simplex_lattice(std::size_t dimensions, std::size_t divisions) {
  std::vector<std::vector<double>> out;
  if (dimensions == 0 || divisions == 0) return out;
  std::vector<double> current(dimensions, 0.0);
  lattice(dimensions, divisions, 0, divisions, current, out);
  return out;
}

std::optional<std::string> NbiOptions::validate() const {
  if (points < 2)
    return fmt::format("NbiOptions::points = {}. Violated constraint: points >= 2", points);
  for (double v : start)
    if (!std::isfinite(v)) return std::string("NbiOptions::start has a non-finite value");
  return ipopt.validate();
}

std::optional<std::string> nbi_explain_unsupported(const Problem& problem,
                                                   const NbiOptions& options) {
  if (auto reason = front_problem_explain_unsupported(problem, "nbi")) return reason;
  return front_start_explain_unsupported(problem, "nbi", options.start);
}

FrontResult run_nbi(const Problem& problem, const NbiOptions& options) {
  if (auto error = options.validate()) throw std::invalid_argument(*error);
  if (auto reason = nbi_explain_unsupported(problem, options)) throw std::invalid_argument(*reason);
  FrontSweepOptions sweep;
  sweep.algorithm = "nbi";
  sweep.ipopt = options.ipopt;
  sweep.start = options.start;
  sweep.global_starts = options.global_starts;
  sweep.seed = options.seed;
  return run_front_sweep(
      problem, sweep,
      [&](const Problem& counted, const AnchorSet& anchors, const std::vector<double>&) {
        return plan_nbi(counted, anchors, options);
      });
}

}  // namespace pkmopt
