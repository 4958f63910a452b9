// Python values -> the engine's numbers, paths and thread counts, with the messages of the
// command line's options.
#include <fmt/format.h>

#include <cmath>
#include <string>

#include "io/format/input_error.hpp"
#include "io/format/number_policy.hpp"
#include "python/src/bindings.hpp"
#include "studies/run_study.hpp"

namespace pkmopt::python {

std::string path_from_python(py::handle path) {
  const py::object text = py::module_::import("os").attr("fspath")(path);
  if (!py::isinstance<py::str>(text))
    throw InputError(fmt::format("expected a path as text, found {}", python_repr(text)));
  try {
    return text.cast<std::string>();
  } catch (const py::error_already_set&) {  // not encodable as UTF-8 (a lone surrogate)
    throw InputError(fmt::format("expected a path as UTF-8 text, found {}", python_repr(text)));
  } catch (const py::cast_error&) {
    throw InputError(fmt::format("expected a path as UTF-8 text, found {}", python_repr(text)));
  }
}

std::string text_from_python(py::handle value, const std::string& what) {
  try {
    return value.cast<std::string>();
  } catch (const py::error_already_set&) {  // not encodable as UTF-8 (a lone surrogate)
    throw InputError(fmt::format("{}: expected UTF-8 text, found {}", what, python_repr(value)));
  } catch (const py::cast_error&) {
    throw InputError(fmt::format("{}: expected UTF-8 text, found {}", what, python_repr(value)));
  }
}

std::string python_repr(py::handle value) {
  std::string text;
  try {
    text = py::repr(value).cast<std::string>();
  } catch (const py::error_already_set&) {
    text = "<an object without a printable repr>";
  }
  std::string line;
  for (const char c : text) {
    const bool space = c == ' ' || c == '\n' || c == '\r' || c == '\t';
    if (space && (line.empty() || line.back() == ' ')) continue;
    line += space ? ' ' : c;
  }
  constexpr std::size_t kMax = 120;
  if (line.size() > kMax) {
    std::size_t cut = kMax;
    while (cut > 0 && (static_cast<unsigned char>(line[cut]) & 0xC0) == 0x80) --cut;  // UTF-8
    line = line.substr(0, cut) + "...";
  }
  return line;
}

double finite_number(py::handle value, const std::string& what) {
  double number = 0.0;
  try {
    number = py::float_(py::reinterpret_borrow<py::object>(value)).cast<double>();
  } catch (const py::error_already_set&) {
    throw InputError(
        fmt::format("{}: expected a finite number, found {}", what, python_repr(value)));
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
    throw InputError(
        fmt::format("{}: expected a finite number, found {}", what, python_repr(py::float_(x))));
  if (!sane_input_number(x))
    throw InputError(fmt::format("{}: expected {}, found {}", what, kSaneNumberText,
                                 python_repr(py::float_(x))));
  if (length && !sane_input_length(x))
    throw InputError(
        fmt::format("{}: expected {}, found {}", what, kLengthText, python_repr(py::float_(x))));
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
                                 kMaxThreads, python_repr(threads)));
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

py::object masked_where_missing(const py::array_t<double>& a) {
  const py::module_ np = py::module_::import("numpy");
  return np.attr("ma").attr("masked_array")(a, py::arg("mask") = np.attr("isnan")(a));
}

}  // namespace pkmopt::python
