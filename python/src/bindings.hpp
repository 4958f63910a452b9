// The pieces of the Python module `pkmopt._core` (python/pkmopt/__init__.py re-exports them).
//
// Every binding calls the library layers below it (models, optimizer, problems, io, report,
// studies): there is no second implementation of anything here, only the conversion between
// numpy arrays / Python objects and the engine's types.
#pragma once

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <string>
#include <vector>

#include "io/format/yaml_reader.hpp"

namespace pkmopt::python {

namespace py = pybind11;

void bind_machine(py::module_& m);
void bind_studies(py::module_& m);
void bind_problems(py::module_& m);

/// A parsed YAML document built from Python data (dict, list, tuple, str, int, float, bool,
/// None, numpy scalars and arrays), read with the same strict readers as a file; messages name
/// `name` where a file would name the file, and the key path ("legs.min_length").
YamlValue yaml_from_python(py::handle value, const std::string& name);

/// repr(value) for a message: on one line (whitespace runs become one space), at most 120
/// characters ("..." marks a cut).
std::string python_repr(py::handle value);

/// A str as UTF-8 text (InputError "what: expected UTF-8 text, found ..." for a str that is not
/// encodable, such as one holding a lone surrogate; pybind11 would raise RuntimeError).
std::string text_from_python(py::handle value, const std::string& what);

/// A file system path from a str or os.PathLike.
std::string path_from_python(py::handle path);

/// A number from Python within the input number policy (io/format/number_policy.hpp): finite,
/// within +-1e15, 0 or at least 1e-30 in magnitude (InputError "what: expected ..., found ...").
double finite_number(py::handle value, const std::string& what);

/// A length or position in metres from Python: finite_number and within +-1000 m.
double length_number(py::handle value, const std::string& what);

/// Throws InputError "what: expected ..., found ..." unless `x` obeys the number policy and, for
/// a length, is within +-1000 m.
void check_policy_number(double x, bool length, const std::string& what);

/// An (N, columns) float array of N rows (each at least `columns` long).
pybind11::array_t<double> rows_to_array(const std::vector<std::vector<double>>& rows,
                                        std::size_t columns);

/// `a` as a numpy masked array (numpy.ma) whose mask marks the NaN entries: a value a file holds
/// as missing (JSON null, an empty CSV cell) is masked, so nothing visible in it is NaN.
py::object masked_where_missing(const py::array_t<double>& a);

/// OpenMP threads from Python: None (0: all cores) or an integer 1..512 (InputError otherwise).
int threads_from_python(const py::object& threads);

}  // namespace pkmopt::python
