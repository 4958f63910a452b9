// The optimisation problem every pkmopt solver sees (shaped like pagmo's problem concept).
//
// A problem has n real design variables x with box bounds lower <= x <= upper, and a fitness
//
//   fitness(x) = [ f_1..f_m | h_1..h_p | g_1..g_q ]       (size m + p + q)
//
// with m objectives f (all minimised: "maximise" is a sign flip done by the caller), p equality
// constraints h(x) = 0 and q inequality constraints g(x) <= 0. Units are the problem's own.
//
// Optionally a problem gives the gradient of the whole fitness vector: `gradient(x)` returns the
// non-zero entries d fitness_i / d x_j in the order of `gradient_sparsity()`, a list of (i, j)
// pairs (i: fitness row, j: variable). The default sparsity is dense (row-major). Expensive
// problems (a machine measured over a task) declare whether `fitness` may be called from several
// threads at once (`thread_safety()`) and may override `batch_fitness` to evaluate many designs
// with their own per-thread scratch data (Model/Data split).
//
// Decorators (CountingProblem here, the study journal in studies/) derive from ForwardingProblem,
// which forwards every call to an inner problem, and override only what they change.
//
// The optimizer knows nothing of machines: problems live in problems/, solvers in optimizer/.
//
// Example:
//   class Parabola : public pkmopt::Problem {
//    public:
//     pkmopt::Bounds bounds() const override { return {{-1.0}, {1.0}}; }
//     std::vector<double> fitness(const std::vector<double>& x) const override {
//       return {x[0] * x[0]};
//     }
//     std::string name() const override { return "parabola"; }
//   };
//   pkmopt::GradientCheck check = pkmopt::check_gradient(my_problem_with_gradient, x);
//   if (!check.ok) std::puts(check.report.c_str());
#pragma once

#include <atomic>
#include <cstddef>
#include <span>
#include <string>
#include <utility>
#include <vector>

namespace pkmopt {

/// Box bounds on the design variables (same length; lower[i] <= upper[i]; may be +-infinity
/// for local gradient solvers, must be finite for evolutionary and global solvers).
struct Bounds {
  std::vector<double> lower;
  std::vector<double> upper;
};

/// Whether `fitness` may be called concurrently on the same object.
enum class ThreadSafety {
  none,   ///< one call at a time: batches are evaluated serially
  basic,  ///< `fitness` and `gradient` are const and re-entrant: batches run in parallel
};

/// (fitness row i, variable j) pairs of the non-zero gradient entries.
using SparsityPattern = std::vector<std::pair<std::size_t, std::size_t>>;

class Problem {
 public:
  virtual ~Problem() = default;

  /// Box bounds; their length is the number of variables n.
  virtual Bounds bounds() const = 0;
  virtual std::size_t num_objectives() const { return 1; }
  virtual std::size_t num_equality() const { return 0; }
  virtual std::size_t num_inequality() const { return 0; }

  /// [objectives | equalities | inequalities] at x (size fitness_size()).
  virtual std::vector<double> fitness(const std::vector<double>& x) const = 0;

  /// Fitness of many designs; result[k] = fitness(xs[k]). The default evaluates in parallel
  /// with OpenMP (`threads` > 1 and thread_safety() == basic) or serially; the result does not
  /// depend on the number of threads. Exceptions thrown by `fitness` are rethrown here.
  virtual std::vector<std::vector<double>> batch_fitness(std::span<const std::vector<double>> xs,
                                                         int threads) const;

  /// True when `gradient` is implemented.
  virtual bool has_gradient() const { return false; }
  /// Non-zero entries of d fitness / d x in the order of gradient_sparsity().
  /// The default throws std::logic_error naming the problem.
  virtual std::vector<double> gradient(const std::vector<double>& x) const;
  /// Default: dense, row-major over (fitness row, variable).
  virtual SparsityPattern gradient_sparsity() const;

  virtual std::string name() const = 0;
  virtual ThreadSafety thread_safety() const { return ThreadSafety::basic; }

  std::size_t num_variables() const { return bounds().lower.size(); }
  std::size_t num_constraints() const { return num_equality() + num_inequality(); }
  std::size_t fitness_size() const { return num_objectives() + num_constraints(); }
};

/// Dense row-major sparsity for `rows` fitness rows and `columns` variables.
SparsityPattern dense_sparsity(std::size_t rows, std::size_t columns);

/// Checks that bounds are consistent and of equal length; throws std::invalid_argument naming
/// the problem, the index and the values otherwise.
void check_bounds(const Problem& problem);

/// Calls problem.fitness(x) and checks its size (std::runtime_error naming the problem and
/// sizes when wrong). Non-finite values are returned as they are.
std::vector<double> checked_fitness(const Problem& problem, const std::vector<double>& x);

/// Sum of constraint violations of a fitness vector: sum |h_i| beyond `equality_tolerance` plus
/// sum max(g_i, 0) beyond `inequality_tolerance`; NaN constraints count as +infinity.
double constraint_violation(const Problem& problem, std::span<const double> fitness,
                            double equality_tolerance = 1e-6, double inequality_tolerance = 0.0);

/// Dense Jacobian (fitness_size x n, row-major) from finite differences: central differences
/// with step h_j = step * max(1, |x_j|), one-sided next to a bound. 2n fitness evaluations.
std::vector<double> finite_difference_jacobian(const Problem& problem, const std::vector<double>& x,
                                               double step = 1e-6);

/// Dense Jacobian (row-major) from the problem's own gradient and sparsity pattern.
std::vector<double> dense_jacobian(const Problem& problem, const std::vector<double>& x);

struct GradientCheckOptions {
  double step = 1e-6;                ///< relative finite-difference step
  double relative_tolerance = 1e-5;  ///< allowed |analytic - fd| / max(1, |fd|)
};

/// Outcome of comparing a problem's gradient with finite differences at one point.
struct GradientCheck {
  bool ok = false;
  double max_error = 0.0;  ///< largest |analytic - fd| / max(1, |fd|)
  std::size_t worst_row = 0;
  std::size_t worst_column = 0;
  double analytic_value = 0.0;  ///< at the worst entry
  double finite_difference_value = 0.0;
  std::string report;  ///< one readable line
};

/// Compares gradient(x) (scattered by gradient_sparsity(), so missing entries count as 0)
/// with central finite differences. Throws std::logic_error if the problem has no gradient.
GradientCheck check_gradient(const Problem& problem, const std::vector<double>& x,
                             const GradientCheckOptions& options = {});

/// The base of problem decorators: forwards every call (bounds, counts, fitness, gradient and
/// its sparsity, name, thread safety) to an inner problem, so a decorator overrides only what it
/// changes. The inner problem must outlive it. batch_fitness is not forwarded: by default it
/// evaluates this problem's own fitness (in parallel when thread_safety() allows), so a
/// decorator that changes fitness is right in batches too; a decorator that wants the inner
/// problem's own batch path (CountingProblem, the journal) overrides batch_fitness itself.
///
/// Example:
///   class Renamed : public pkmopt::ForwardingProblem {
///    public:
///     using ForwardingProblem::ForwardingProblem;
///     std::string name() const override { return inner().name() + " (renamed)"; }
///   };
class ForwardingProblem : public Problem {
 public:
  explicit ForwardingProblem(const Problem& inner) : inner_(inner) {}
  Bounds bounds() const override { return inner_.bounds(); }
  std::size_t num_objectives() const override { return inner_.num_objectives(); }
  std::size_t num_equality() const override { return inner_.num_equality(); }
  std::size_t num_inequality() const override { return inner_.num_inequality(); }
  std::vector<double> fitness(const std::vector<double>& x) const override {
    return inner_.fitness(x);
  }
  bool has_gradient() const override { return inner_.has_gradient(); }
  std::vector<double> gradient(const std::vector<double>& x) const override {
    return inner_.gradient(x);
  }
  SparsityPattern gradient_sparsity() const override { return inner_.gradient_sparsity(); }
  std::string name() const override { return inner_.name(); }
  ThreadSafety thread_safety() const override { return inner_.thread_safety(); }

  /// The decorated problem.
  const Problem& inner() const { return inner_; }

 private:
  const Problem& inner_;
};

/// A decorator that counts fitness and gradient evaluations of another problem (thread-safe
/// counters). The wrapped problem must outlive it.
class CountingProblem : public ForwardingProblem {
 public:
  using ForwardingProblem::ForwardingProblem;
  std::vector<double> fitness(const std::vector<double>& x) const override;
  std::vector<std::vector<double>> batch_fitness(std::span<const std::vector<double>> xs,
                                                 int threads) const override;
  std::vector<double> gradient(const std::vector<double>& x) const override;

  long long fitness_evaluations() const { return fitness_evaluations_.load(); }
  long long gradient_evaluations() const { return gradient_evaluations_.load(); }

 private:
  mutable std::atomic<long long> fitness_evaluations_{0};
  mutable std::atomic<long long> gradient_evaluations_{0};
};

/// Number of threads to use: `requested` if > 0, else omp_get_max_threads().
int resolve_thread_count(int requested);

}  // namespace pkmopt
