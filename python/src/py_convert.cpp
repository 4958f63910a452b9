// Python values -> the engine's numbers, paths and thread counts, with the messages of the
// command line's options.
#include <fmt/format.h>

#include <cmath>
#include <string>

#include "io/input_error.hpp"
#include "io/number_policy.hpp"
#include "python/src/bindings.hpp"
#include "studies/run_study.hpp"

namespace pkmopt::python {

std::string path_from_python(py::handle path) {
  const py::object text = py::module_::import("os").attr("fspath")(path);
  if (!py::isinstance<py::str>(text))
    throw InputError(
        fmt::format("expected a path as text, found {}", py::repr(text).cast<std::string>()));
  try {
    return text.cast<std::string>();
  } catch (const py::error_already_set&) {  // not encodable as UTF-8 (a lone surrogate)
    throw InputError(
        fmt::format("expected a path as UTF-8 text, found {}", py::repr(text).cast<std::string>()));
  } catch (const py::cast_error&) {
    throw InputError(
        fmt::format("expected a path as UTF-8 text, found {}", py::repr(text).cast<std::string>()));
  }
}

double finite_number(py::handle value, const std::string& what) {
  double number = 0.0;
  try {
    number = py::float_(py::reinterpret_borrow<py::object>(value)).cast<double>();
  } catch (const py::error_already_set&) {
    throw InputError(fmt::format("{}: expected a finite number, found {}", what,
                                 py::repr(value).cast<std::string>()));
  }
  check_policy_number(number, false, what);
  return number;
}

double length_number(py::handle value, const std::string& what) {
  const double number = finite_number(value, what);
  check_policy_number(number, true, what);
  return number;
}

void check_policy_number(double x, bool length, const std::string& what) {
  if (!std::isfinite(x))
    throw InputError(fmt::format("{}: expected a finite number, found {}", what,
                                 py::repr(py::float_(x)).cast<std::string>()));
  if (!sane_input_number(x))
    throw InputError(fmt::format("{}: expected {}, found {}", what, kSaneNumberText,
                                 py::repr(py::float_(x)).cast<std::string>()));
  if (length && !sane_input_length(x))
    throw InputError(fmt::format("{}: expected {}, found {}", what, kLengthText,
                                 py::repr(py::float_(x)).cast<std::string>()));
}

int threads_from_python(const py::object& threads) {
  if (threads.is_none()) return 0;
  constexpr long long kMaxThreads = kMaxStudyThreads;  // as `pkmopt run --threads`
  const bool integer = py::isinstance<py::int_>(threads) && !py::isinstance<py::bool_>(threads);
  long long n = 0;
  bool overflow = false;
  if (integer) {
    int flag = 0;
    n = PyLong_AsLongLongAndOverflow(threads.ptr(), &flag);
    overflow = flag != 0;
  }
  if (!integer || overflow || n < 1 || n > kMaxThreads)
    throw InputError(fmt::format("threads: expected an integer 1..{} or None, found {}",
                                 kMaxThreads, py::repr(threads).cast<std::string>()));
  return static_cast<int>(n);
}

py::array_t<double> rows_to_array(const std::vector<std::vector<double>>& rows,
                                  std::size_t columns) {
  py::array_t<double> a({static_cast<py::ssize_t>(rows.size()), static_cast<py::ssize_t>(columns)});
  auto r = a.mutable_unchecked<2>();
  for (std::size_t i = 0; i < rows.size(); ++i)
    for (std::size_t j = 0; j < columns; ++j)
      r(static_cast<py::ssize_t>(i), static_cast<py::ssize_t>(j)) = rows[i][j];
  return a;
}

}  // namespace pkmopt::python
