// pkmopt.optimize: pkmopt's optimizers (NSGA-II, hybrid, epsilon-constraint, NBI, Ipopt, NLopt)
// on a problem written in Python, or on a built-in benchmark problem.
#include <fmt/format.h>
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <cmath>
#include <exception>
#include <memory>
#include <string>
#include <vector>

#include "io/format/input_error.hpp"
#include "optimizer/problem.hpp"
#include "problems/benchmarks/benchmarks.hpp"
#include "python/src/bindings.hpp"
#include "studies/optimizer_spec.hpp"

namespace pkmopt::python {
namespace {

using DoubleArray = py::array_t<double, py::array::c_style | py::array::forcecast>;

// A count 0..1000000 from Python (InputError naming `what` otherwise).
std::size_t count_value(const py::object& value, const std::string& what) {
  int overflow = 0;
  const long long n = py::isinstance<py::int_>(value) && !py::isinstance<py::bool_>(value)
                          ? PyLong_AsLongLongAndOverflow(value.ptr(), &overflow)
                          : -1;
  if (overflow != 0 || n < 0 || n > 1'000'000)
    throw InputError(
        fmt::format("{}: expected an integer 0..1000000, found {}", what, python_repr(value)));
  return static_cast<std::size_t>(n);
}

std::size_t count_attribute(const py::object& obj, const char* name, std::size_t fallback) {
  if (!py::hasattr(obj, name)) return fallback;
  py::object value = obj.attr(name);
  if (PyCallable_Check(value.ptr())) value = value();
  return count_value(value, std::string("problem.") + name);
}

/// A Problem (optimizer/problem.hpp) whose fitness is a Python object's method. The GIL is taken
/// for every call; the optimizer evaluates serially (thread_safety none) unless the object gives
/// batch_fitness, which then gets whole batches.
class PythonProblem final : public Problem {
 public:
  explicit PythonProblem(py::object obj) : obj_(std::move(obj)) {
    if (!py::hasattr(obj_, "fitness"))
      throw InputError("problem: expected an object with bounds and fitness(x), found no fitness");
    if (!py::hasattr(obj_, "bounds"))
      throw InputError("problem: expected an object with bounds and fitness(x), found no bounds");
    py::object b = obj_.attr("bounds");
    if (PyCallable_Check(b.ptr())) b = b();
    const py::sequence pair = b.cast<py::sequence>();
    if (pair.size() != 2)
      throw InputError("problem.bounds: expected (lower, upper), two sequences of equal length");
    const DoubleArray lower = DoubleArray::ensure(pair[0]), upper = DoubleArray::ensure(pair[1]);
    if (!lower || !upper || lower.ndim() != 1 || upper.ndim() != 1 ||
        lower.shape(0) != upper.shape(0) || lower.shape(0) == 0)
      throw InputError("problem.bounds: expected (lower, upper), two sequences of equal length");
    for (py::ssize_t j = 0; j < lower.shape(0); ++j) {
      if (!(lower.at(j) <= upper.at(j)))
        throw InputError(fmt::format("problem.bounds[{}]: expected lower <= upper, found {} and {}",
                                     j, lower.at(j), upper.at(j)));
      bounds_.lower.push_back(lower.at(j));
      bounds_.upper.push_back(upper.at(j));
    }
    n_obj_ = count_attribute(obj_, "n_obj", 1);
    n_eq_ = count_attribute(obj_, "n_eq", 0);
    n_ineq_ = count_attribute(obj_, "n_ineq", 0);
    if (n_obj_ == 0) throw InputError("problem.n_obj: expected an integer >= 1, found 0");
    batch_ = py::hasattr(obj_, "batch_fitness");
    gradient_ = py::hasattr(obj_, "gradient");
    name_ = py::hasattr(obj_, "name")
                ? text_from_python(py::str(obj_.attr("name")), "problem.name")
                : py::str(py::type::of(obj_).attr("__name__")).cast<std::string>();
  }

  Bounds bounds() const override { return bounds_; }
  std::size_t num_objectives() const override { return n_obj_; }
  std::size_t num_equality() const override { return n_eq_; }
  std::size_t num_inequality() const override { return n_ineq_; }
  std::string name() const override { return name_; }
  ThreadSafety thread_safety() const override { return ThreadSafety::none; }

  std::vector<double> fitness(const std::vector<double>& x) const override {
    py::gil_scoped_acquire acquire;
    return guarded([&] { return row(obj_.attr("fitness")(vector_array(x)), "fitness"); });
  }

  /// The first exception out of the object's methods (a Python one, KeyboardInterrupt included,
  /// or a wrong result shape), kept because some solvers (Ipopt, NLopt) turn an exception in a
  /// callback into a status; optimize raises it once the solver has returned.
  std::exception_ptr pending_error() const { return pending_; }

  std::vector<std::vector<double>> batch_fitness(std::span<const std::vector<double>> xs,
                                                 int threads) const override {
    if (!batch_) return Problem::batch_fitness(xs, threads);
    py::gil_scoped_acquire acquire;
    return guarded([&] { return batch(xs); });
  }

  bool has_gradient() const override { return gradient_; }

  /// gradient(x): the dense Jacobian of the fitness, (fitness size, n), row-major here.
  std::vector<double> gradient(const std::vector<double>& x) const override {
    py::gil_scoped_acquire acquire;
    return guarded([&] { return jacobian(x); });
  }

 private:
  std::vector<std::vector<double>> batch(std::span<const std::vector<double>> xs) const {
    const std::size_t n = bounds_.lower.size();
    py::array_t<double> X({static_cast<py::ssize_t>(xs.size()), static_cast<py::ssize_t>(n)});
    auto w = X.mutable_unchecked<2>();
    for (std::size_t k = 0; k < xs.size(); ++k)
      for (std::size_t j = 0; j < n; ++j)
        w(static_cast<py::ssize_t>(k), static_cast<py::ssize_t>(j)) = xs[k][j];
    const DoubleArray F = DoubleArray::ensure(obj_.attr("batch_fitness")(X));
    const std::size_t m = fitness_size();
    if (!F || F.ndim() != 2 || static_cast<std::size_t>(F.shape(0)) != xs.size() ||
        static_cast<std::size_t>(F.shape(1)) != m)
      throw InputError(
          fmt::format("problem.batch_fitness: expected an array of shape ({}, {}) "
                      "(designs x [objectives | equalities | inequalities])",
                      xs.size(), m));
    std::vector<std::vector<double>> out(xs.size(), std::vector<double>(m));
    for (std::size_t k = 0; k < xs.size(); ++k)
      for (std::size_t i = 0; i < m; ++i)
        out[k][i] = F.at(static_cast<py::ssize_t>(k), static_cast<py::ssize_t>(i));
    return out;
  }

  std::vector<double> jacobian(const std::vector<double>& x) const {
    const DoubleArray G = DoubleArray::ensure(obj_.attr("gradient")(vector_array(x)));
    const std::size_t m = fitness_size(), n = bounds_.lower.size();
    const bool shaped =
        G && ((G.ndim() == 2 && G.shape(0) == static_cast<py::ssize_t>(m) &&
               G.shape(1) == static_cast<py::ssize_t>(n)) ||
              (G.ndim() == 1 && m == 1 && G.shape(0) == static_cast<py::ssize_t>(n)));
    if (!shaped)
      throw InputError(fmt::format(
          "problem.gradient: expected an array of shape ({}, {}) (d fitness_i / d x_j)", m, n));
    return std::vector<double>(G.data(), G.data() + m * n);
  }

  // Calls f (with the GIL held); its exception is kept (the first) and rethrown.
  template <class F>
  auto guarded(F&& f) const -> decltype(f()) {
    try {
      return f();
    } catch (...) {
      if (!pending_) pending_ = std::current_exception();
      throw;
    }
  }

  static py::array_t<double> vector_array(const std::vector<double>& x) {
    py::array_t<double> a(static_cast<py::ssize_t>(x.size()));
    std::copy(x.begin(), x.end(), a.mutable_data());
    return a;
  }

  std::vector<double> row(const py::object& value, const char* what) const {
    const DoubleArray a = DoubleArray::ensure(value);
    const std::size_t m = fitness_size();
    if (!a || a.size() != static_cast<py::ssize_t>(m))
      throw InputError(fmt::format(
          "problem.{}: expected {} numbers ([objectives | equalities | inequalities]), found {}",
          what, m, python_repr(value)));
    return std::vector<double>(a.data(), a.data() + m);
  }

  py::object obj_;
  Bounds bounds_;
  std::size_t n_obj_ = 1, n_eq_ = 0, n_ineq_ = 0;
  bool batch_ = false, gradient_ = false;
  std::string name_;
  mutable std::exception_ptr pending_;
};

py::dict optimize(const py::object& problem_in, const py::object& optimizer,
                  const py::object& threads_in) {
  std::unique_ptr<Problem> owned;
  const PythonProblem* python_problem = nullptr;
  if (py::isinstance<py::str>(problem_in)) {
    try {
      owned = make_benchmark(text_from_python(problem_in, "problem"));
    } catch (const std::invalid_argument& e) {
      throw InputError(fmt::format("problem: {}", e.what()));
    }
  } else if (py::isinstance<py::dict>(problem_in)) {
    const py::dict d = problem_in.cast<py::dict>();
    if (!d.contains("name"))
      throw InputError("problem: expected {name, variables, objectives} of a built-in problem");
    if (!py::isinstance<py::str>(d["name"]))
      throw InputError("problem.name: expected the name of a built-in problem (zdt1, dtlz2, ...)");
    const std::string name = text_from_python(d["name"], "problem.name");
    const std::size_t variables =
        d.contains("variables") ? count_value(d["variables"], "problem.variables") : 0;
    const std::size_t objectives =
        d.contains("objectives") ? count_value(d["objectives"], "problem.objectives") : 0;
    try {
      owned = make_benchmark(name, variables, objectives);
    } catch (const std::invalid_argument& e) {
      throw InputError(fmt::format("problem: {}", e.what()));
    }
  } else {
    owned = std::make_unique<PythonProblem>(problem_in);
    python_problem = static_cast<const PythonProblem*>(owned.get());
  }
  if (!owned) throw InputError("problem: expected a built-in problem name or a problem object");
  const Problem& problem = *owned;
  const int threads = threads_from_python(threads_in);
  const OptimizerSpec spec =
      read_optimizer_section(yaml_from_python(optimizer, "optimizer"), problem);
  RunOutcome outcome;
  {
    py::gil_scoped_release release;
    outcome = run_optimizer(problem, spec, threads);
  }
  if (python_problem && python_problem->pending_error())
    std::rethrow_exception(python_problem->pending_error());
  const FrontResult& front = outcome.front;
  py::dict d;
  d["algorithm"] = spec.name();
  d["problem"] = problem.name();
  d["status"] = outcome.status;
  d["message"] = front.message;
  // A point whose values are not numbers (a failed evaluation) is no answer: left out here, and
  // None in 'single' (nothing returned holds NaN).
  std::vector<std::vector<double>> xs, fitness, objectives;
  for (std::size_t k = 0; k < front.fitness.size(); ++k) {
    const auto& f = front.fitness[k];
    if (std::any_of(f.begin(), f.end(), [](double v) { return std::isnan(v); })) continue;
    xs.push_back(front.x[k]);
    fitness.push_back(f);
    objectives.emplace_back(f.begin(),
                            f.begin() + static_cast<std::ptrdiff_t>(problem.num_objectives()));
  }
  d["x"] = rows_to_array(xs, problem.num_variables());
  d["fitness"] = rows_to_array(fitness, problem.fitness_size());
  d["objectives"] = rows_to_array(objectives, problem.num_objectives());
  d["evaluations"] = front.fitness_evaluations;
  d["gradient_evaluations"] = front.gradient_evaluations;
  d["seconds"] = front.seconds;
  if (outcome.single) {
    const SolveResult& s = *outcome.single;
    py::dict single;
    auto number = [](double v) { return std::isnan(v) ? py::object(py::none()) : py::float_(v); };
    py::list single_fitness;
    for (double v : s.fitness) single_fitness.append(number(v));
    single["x"] = s.x;
    single["fitness"] = single_fitness;
    single["objective"] = number(s.objective);
    single["constraint_violation"] = number(s.constraint_violation);
    single["iterations"] = s.iterations;
    single["usable"] = s.usable();
    single["message"] = s.message;
    d["single"] = single;
  }
  return d;
}

}  // namespace

void bind_problems(py::module_& m) {
  m.def("optimize", &optimize, py::arg("problem"), py::arg("optimizer"),
        py::arg("threads") = py::none(),
        R"(Runs one of pkmopt's optimizers on a problem.

problem: a built-in benchmark ('zdt1', 'dtlz2', ..., or {'name': 'dtlz2', 'variables': 12,
  'objectives': 4}) or a Python object with
    bounds           (lower, upper): the box of the design variables
    n_obj, n_eq, n_ineq   counts (defaults 1, 0, 0)
    fitness(x)       -> [f_1..f_m, h_1..h_p, g_1..g_q], all objectives minimised,
                        equalities h = 0, inequalities g <= 0
  and optionally batch_fitness(X) -> (k, m + p + q) for a (k, n) array of designs, and
  gradient(x) -> the dense (m + p + q, n) Jacobian (needed by ipopt, nbi, epsilon_constraint
  and gradient-based nlopt algorithms).
optimizer: the `optimizer:` section of a study file as a dict, e.g. {'algorithm': 'nsga2',
  'population': 100, 'generations': 250, 'seed': 1} (docs/optimizer.md).
threads: OpenMP threads for built-in problems (Python problems are evaluated serially).

Returns {'x' (N, n), 'fitness' (N, m + p + q), 'objectives' (N, m): the feasible
non-dominated designs found, sorted (a point whose values are NaN, a failed evaluation, is
never among them; in 'single' such values are None); 'status', 'message', 'evaluations', ...};
the same seed gives the same front.)");
}

}  // namespace pkmopt::python
