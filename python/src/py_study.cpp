// pkmopt.run_study, read_front and calibrate: the study engine of `pkmopt run` and
// `pkmopt calibrate`.
#include <fmt/format.h>
#include <omp.h>
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <filesystem>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "io/calibration/calibration_files.hpp"
#include "io/calibration/calibration_output.hpp"
#include "io/format/csv.hpp"
#include "io/format/input_error.hpp"
#include "io/format/output_file.hpp"
#include "io/results/pareto_json.hpp"
#include "python/src/bindings.hpp"
#include "studies/run_study.hpp"

namespace pkmopt::python {
namespace {

namespace fs = std::filesystem;

py::object json_to_python(const std::string& text) {
  return py::module_::import("json").attr("loads")(text);
}

py::dict run_study_py(py::handle study, py::handle out, const py::object& threads, bool resume,
                      bool force, const py::object& progress, bool show_progress) {
  StudyRunOptions options;
  options.out = path_from_python(out);
  options.threads = threads_from_python(threads);
  options.resume = resume;
  options.force = force;
  options.show_progress = show_progress;
  // After every batch: let Python handle a pending Ctrl-C (KeyboardInterrupt stops the run with
  // its journal intact; `resume=True` continues it) and call the user's progress function.
  // The callback is held as a raw handle (`progress` outlives the run), so that the copies
  // run_study makes of this function touch no Python reference count without the GIL. A Python
  // exception is kept and raised after the run: some solvers turn an exception in a callback
  // into a status.
  PyObject* callback = progress.ptr();
  auto pending = std::make_shared<std::optional<py::error_already_set>>();
  options.progress = [callback, pending](const JournalProgress& p) {
    if (omp_in_parallel()) return;  // only from the thread that runs the optimizer
    py::gil_scoped_acquire acquire;
    try {
      if (PyErr_CheckSignals() != 0) throw py::error_already_set();
      const py::handle function(callback);
      if (function.is_none()) return;
      py::dict d;
      d["requests"] = p.requests;
      d["expected_requests"] = p.expected_requests;
      d["cache_hits"] = p.cache_hits;
      d["failed"] = p.failed;
      d["distinct"] = p.distinct;
      d["feasible_front"] = p.feasible_front;
      function(d);
    } catch (py::error_already_set& e) {
      if (!*pending) *pending = e;
      throw;
    }
  };
  const bool from_file = !py::isinstance<py::dict>(study);
  const YamlValue root =
      from_file ? YamlValue::load_file(path_from_python(study)) : yaml_from_python(study, "<dict>");
  StudyRunResult r;
  {
    py::gil_scoped_release release;
    r = run_study(root, options);
  }
  if (*pending) throw **pending;
  py::dict d;
  d["design_study"] = r.design_study;
  d["name"] = r.name;
  d["algorithm"] = r.algorithm;
  d["problem"] = r.problem;
  d["status"] = r.status;
  d["message"] = r.message;
  d["designs"] = r.designs;
  d["evaluations"] = r.evaluations;
  d["from_cache"] = r.from_cache;
  d["failed"] = r.failed;
  d["optimizer_seconds"] = r.optimizer_seconds;
  d["wall_seconds"] = r.wall_seconds;
  d["resumed"] = r.resumed;
  d["out"] = options.out;
  return d;
}

py::dict read_front(py::handle dir_in) {
  const fs::path dir(path_from_python(dir_in));
  if (!fs::is_directory(dir))
    throw InputError(fmt::format("{}: expected a results folder of `pkmopt run`, found {}",
                                 dir.string(), fs::exists(dir) ? "a file" : "nothing"));
  const fs::path csv_path = dir / "pareto.csv";
  if (!fs::exists(csv_path))
    throw InputError(
        fmt::format("{}: expected pareto.csv (a finished run), found none", dir.string()));
  py::dict out;
  // Every column of pareto.csv: numbers as masked float arrays (empty cells masked), text as
  // lists.
  const CsvTable table = read_csv_file(csv_path.string());
  py::dict columns;
  for (std::size_t c = 0; c < table.header.size(); ++c) {
    // A column is numeric when it holds a number and nothing but numbers and empty cells; a
    // column without any number (failure, always empty on a front) is text, not all NaN.
    bool numeric = false, text = false;
    for (const CsvRow& row : table.rows) {
      const std::string& cell = row.cells[c];
      if (cell.empty()) continue;
      char* end = nullptr;
      std::strtod(cell.c_str(), &end);
      (end == cell.c_str() + cell.size() ? numeric : text) = true;
    }
    numeric = numeric && !text;
    if (numeric) {
      py::array_t<double> a(static_cast<py::ssize_t>(table.rows.size()));
      for (std::size_t i = 0; i < table.rows.size(); ++i) {
        const std::string& cell = table.rows[i].cells[c];
        a.mutable_at(static_cast<py::ssize_t>(i)) = cell.empty()
                                                        ? std::numeric_limits<double>::quiet_NaN()
                                                        : std::strtod(cell.c_str(), nullptr);
      }
      columns[py::str(table.header[c])] = masked_where_missing(a);
    } else {
      py::list l;
      for (const CsvRow& row : table.rows) l.append(row.cells[c]);
      columns[py::str(table.header[c])] = l;
    }
  }
  out["columns"] = columns;
  if (fs::exists(dir / "summary.json"))
    out["summary"] = json_to_python(read_input_file((dir / "summary.json").string()));
  const fs::path json_path = dir / "pareto.json";
  if (!fs::exists(json_path)) return out;
  // A design study: the front with its names, units and senses (pkmopt-pareto-1).
  const ParetoFront front = read_pareto_json(json_path.string());
  out["study"] = front.study;
  out["description"] = front.description;
  out["model"] = front.model;
  py::list ids, machine_files;
  std::vector<std::vector<double>> parameters, objectives, constraints;
  py::array_t<bool> feasible(static_cast<py::ssize_t>(front.designs.size()));
  py::array_t<double> home(static_cast<py::ssize_t>(front.designs.size()));
  for (std::size_t i = 0; i < front.designs.size(); ++i) {
    const ParetoDesign& d = front.designs[i];
    ids.append(d.id);
    machine_files.append(d.machine_file ? py::cast((dir / *d.machine_file).string())
                                        : py::object(py::none()));
    parameters.push_back(d.parameters);
    objectives.push_back(d.objectives);
    constraints.push_back(d.constraints);
    feasible.mutable_at(static_cast<py::ssize_t>(i)) = d.feasible;
    home.mutable_at(static_cast<py::ssize_t>(i)) = d.home_height;
  }
  out["ids"] = ids;
  py::list parameter_info, objective_info, constraint_info;
  for (const ParetoParameter& p : front.parameters)
    parameter_info.append(py::dict(py::arg("name") = p.name, py::arg("unit") = p.unit,
                                   py::arg("min") = p.min, py::arg("max") = p.max));
  for (const ParetoObjective& o : front.objectives)
    objective_info.append(
        py::dict(py::arg("name") = o.name, py::arg("sense") = o.sense, py::arg("unit") = o.unit));
  for (const ParetoConstraint& c : front.constraints)
    constraint_info.append(py::dict(py::arg("name") = c.name, py::arg("metric") = c.metric,
                                    py::arg("kind") = c.kind, py::arg("bound") = c.bound,
                                    py::arg("unit") = c.unit));
  out["parameter_info"] = parameter_info;
  out["objective_info"] = objective_info;
  out["constraint_info"] = constraint_info;
  out["parameters"] = masked_where_missing(rows_to_array(parameters, front.parameters.size()));
  out["home_height"] = masked_where_missing(home);
  out["objectives"] = masked_where_missing(rows_to_array(objectives, front.objectives.size()));
  out["constraints"] = masked_where_missing(rows_to_array(constraints, front.constraints.size()));
  out["feasible"] = feasible;
  out["machine_files"] = machine_files;
  out["knee"] = front.knee ? py::cast(*front.knee) : py::object(py::none());
  return out;
}

py::dict calibrate_py(py::handle file_in, const py::object& out_in) {
  const std::string file = path_from_python(file_in);
  const CalibrationSetup setup = read_calibration_setup(file);
  CalibrationRun run;
  {
    py::gil_scoped_release release;
    run = run_calibration(setup);
  }
  if (!out_in.is_none()) {
    const fs::path dir(path_from_python(out_in));
    std::error_code error;
    fs::create_directories(dir, error);
    if (error || !fs::is_directory(dir))
      throw InputError(fmt::format("out {}: expected a writable directory, found: {}", dir.string(),
                                   error ? error.message() : "not a directory"));
    for (const auto& [name, bytes] : run.files())
      write_file_atomically((dir / name).string(), bytes);
  }
  py::dict d = json_to_python(run.report.dump());
  d["report_text"] = run.text;
  d["calibrated_machine_yaml"] = run.machine_yaml;
  return d;
}

}  // namespace

void bind_studies(py::module_& m) {
  m.def("_run_study", &run_study_py, py::arg("study"), py::arg("out"), py::arg("threads"),
        py::arg("resume"), py::arg("force"), py::arg("progress"), py::arg("show_progress"));
  m.def("read_front", &read_front, py::arg("directory"),
        R"(The result of a finished `pkmopt run` folder.

Returns 'columns' (every column of pareto.csv: numbers as float arrays in the study's units
and sense, text as lists) and 'summary' (summary.json). For a design study also, from
pareto.json: 'study', 'model', 'ids', 'parameters' (N, p) with 'parameter_info' (name, unit,
range), 'objectives' (N, m) in user units and sign with 'objective_info' (name, sense, unit),
'constraints' (N, c), the constrained metrics' values, with 'constraint_info', 'home_height'
(m), 'feasible', 'machine_files' (paths of designs/<id>.yaml, or None) and 'knee' (an id).)");
  m.def("calibrate", &calibrate_py, py::arg("path"), py::arg("out") = py::none(),
        "Calibrates a hexapod as `pkmopt calibrate` does (docs/calibration.md): returns the "
        "report (the fields of report.json) with 'report_text' and 'calibrated_machine_yaml'; "
        "with `out` also writes report.json, report.txt and calibrated.yaml there.");
}

}  // namespace pkmopt::python
