// The compiled part of the Python package `pkmopt` (python/pkmopt/__init__.py).
#include <pybind11/pybind11.h>

#include "io/format/input_error.hpp"
#include "pkmopt/version.hpp"
#include "python/src/bindings.hpp"

PYBIND11_MODULE(_core, m) {
  namespace py = pybind11;
  m.doc() = "pkmopt: multi-objective design optimisation of parallel kinematic machine tools";
  py::register_exception<pkmopt::InputError>(m, "InputError", PyExc_ValueError);
  m.attr("__version__") = pkmopt::kVersion;
  pkmopt::python::bind_machine(m);
  pkmopt::python::bind_studies(m);
  pkmopt::python::bind_problems(m);
}
