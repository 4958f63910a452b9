// pkmopt.Machine: load_machine, machine_from_dict, describe, analyze, ik, fk, jacobian, workspace.
#include <fmt/format.h>
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <chrono>
#include <cmath>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

#include "io/format/input_error.hpp"
#include "io/format/number_policy.hpp"
#include "io/machine/machine_description.hpp"
#include "io/machine/machine_file.hpp"
#include "io/machine/model_registry.hpp"
#include "io/results/analyze_csv.hpp"
#include "models/core/capabilities.hpp"
#include "models/core/machine.hpp"
#include "models/core/pose_analysis.hpp"
#include "models/geometry/leg_interference.hpp"
#include "models/workspace/volume_accuracy.hpp"
#include "models/workspace/workspace.hpp"
#include "python/src/bindings.hpp"
#include "report/workspace_export.hpp"

namespace pkmopt::python {
namespace {

using DoubleArray = py::array_t<double, py::array::c_style | py::array::forcecast>;

/// A machine and the document it was read from (for describe()).
struct PyMachine {
  std::shared_ptr<const Machine> machine;
  YamlValue document;
  std::string source;  ///< the file, or "<dict>"
};

PyMachine load_machine_py(py::handle path) {
  const std::string file = path_from_python(path);
  YamlValue root = YamlValue::load_file(file);
  std::shared_ptr<const Machine> machine = load_machine(root);
  return {std::move(machine), std::move(root), file};
}

PyMachine machine_from_dict(py::handle d) {
  if (!py::isinstance<py::dict>(d))
    throw InputError(fmt::format("machine_from_dict: expected a dict, found a {}",
                                 py::str(py::type::of(d).attr("__name__")).cast<std::string>()));
  YamlValue root = yaml_from_python(d, "<dict>");
  std::shared_ptr<const Machine> machine = load_machine(root);
  return {std::move(machine), std::move(root), "<dict>"};
}

// A pose from a sequence of 3 (x, y, z in m) or 6 numbers (and rx, ry, rz in degrees).
Pose pose_from_python(py::handle value, const std::string& what) {
  const DoubleArray a = DoubleArray::ensure(value);
  if (!a || a.ndim() != 1 || (a.shape(0) != 3 && a.shape(0) != 6))
    throw InputError(fmt::format(
        "{}: expected 3 numbers x, y, z (m) or 6 numbers x, y, z (m), rx, ry, rz (deg), found {}",
        what, python_repr(value)));
  Eigen::Vector3d deg = Eigen::Vector3d::Zero();
  Pose pose;
  for (py::ssize_t k = 0; k < a.shape(0); ++k) {
    check_policy_number(a.at(k), k < 3, fmt::format("{}[{}]", what, k));
    if (k < 3)
      pose.position(k) = a.at(k);
    else
      deg(k - 3) = a.at(k);
  }
  pose.angles = deg_to_rad(deg);
  return pose;
}

py::array_t<double> pose_to_python(const Pose& pose) {
  py::array_t<double> out(6);
  auto r = out.mutable_unchecked<1>();
  for (int k = 0; k < 3; ++k) r(k) = pose.position(k);
  const Eigen::Vector3d deg = rad_to_deg(pose.angles);
  for (int k = 0; k < 3; ++k) r(3 + k) = deg(k);
  return out;
}

Wrench wrench_from_python(const py::object& value) {
  Wrench w = Wrench::Zero();
  if (value.is_none()) return w;
  if (!py::isinstance<py::sequence>(value) || py::isinstance<py::str>(value) || py::len(value) != 6)
    throw InputError(
        fmt::format("wrench: expected 6 numbers fx, fy, fz (N), mx, my, mz (N*m), "
                    "found {}",
                    python_repr(value)));
  const py::sequence s = value.cast<py::sequence>();
  for (int i = 0; i < 6; ++i) {
    w(i) = finite_number(s[i], fmt::format("wrench[{}]", i));
    if (!(std::abs(w(i)) <= kMaxInputForce))
      throw InputError(
          fmt::format("wrench[{}]: expected a force or moment within +-{:g} N or N*m, "
                      "found {}",
                      i, kMaxInputForce, format_number(w(i))));
  }
  return w;
}

// Where the value of one analyze column goes: `base[pose * stride + offset]`.
struct ColumnTarget {
  double* base = nullptr;
  std::size_t stride = 1;
  std::size_t offset = 0;
};

// An output array of analyze: a new one, or out[key] when the caller hands back the arrays of an
// earlier call (same shapes), so that repeated sweeps write into memory that is already mapped.
template <typename T>
py::array_t<T> output_array(const py::object& out, const char* key,
                            const std::vector<py::ssize_t>& shape) {
  if (out.is_none()) return py::array_t<T>(shape);
  const py::dict d = out.cast<py::dict>();
  std::string expected = "(";
  for (std::size_t k = 0; k < shape.size(); ++k)
    expected += (k ? ", " : "") + std::to_string(shape[k]) + (shape.size() == 1 ? "," : "");
  expected += ")";
  if (!d.contains(key))
    throw InputError(
        fmt::format("out['{}']: expected an array of shape {}, found no such key", key, expected));
  const py::object value = d[key];
  const bool ok = py::isinstance<py::array_t<T>>(value) && [&] {
    const py::array a = value.cast<py::array>();
    if (!a.dtype().is(py::dtype::of<T>()) || !a.writeable() || !(a.flags() & py::array::c_style) ||
        a.ndim() != static_cast<py::ssize_t>(shape.size()))
      return false;
    for (std::size_t k = 0; k < shape.size(); ++k)
      if (a.shape(static_cast<py::ssize_t>(k)) != shape[k]) return false;
    return true;
  }();
  if (!ok)
    throw InputError(fmt::format(
        "out['{}']: expected a writeable C-contiguous {} array of shape {} (the arrays of an "
        "earlier analyze with as many poses and the same options), found {}",
        key, std::is_same_v<T, bool> ? "bool" : "float64", expected,
        python_repr(py::getattr(value, "shape", py::none()))));
  return value.cast<py::array_t<T>>();
}

py::dict analyze(const PyMachine& self, py::handle poses_in, const py::object& wrench_in,
                 const py::object& threads_in, bool compliance, bool mode_shapes,
                 const py::object& out) {
  const Machine& machine = *self.machine;
  DoubleArray poses = DoubleArray::ensure(poses_in);
  if (!poses) throw InputError("poses: expected an array of numbers of shape (N, 3) or (N, 6)");
  if (poses.ndim() == 1) poses = poses.reshape({py::ssize_t{1}, poses.shape(0)});
  if (poses.ndim() != 2 || (poses.shape(1) != 3 && poses.shape(1) != 6))
    throw InputError(fmt::format(
        "poses: expected shape (N, 3) (x, y, z in m) or (N, 6) (and rx, ry, rz in deg), found "
        "shape {}",
        py::str(py::tuple(poses.attr("shape"))).cast<std::string>()));
  const Wrench wrench = wrench_from_python(wrench_in);
  const int threads = threads_from_python(threads_in);
  const Capability<Dynamics> dynamics = machine.dynamics();
  if (mode_shapes && !dynamics)
    throw InputError(fmt::format(
        "mode_shapes: needs a mass model: {} has no 'masses' (docs/dynamics.md)", self.source));
  const std::size_t n = static_cast<std::size_t>(poses.shape(0));
  const std::size_t width = static_cast<std::size_t>(poses.shape(1));
  const double* in = poses.data();
  for (std::size_t i = 0; i < n * width; ++i)
    if (!sane_input_number(in[i]) || (i % width < 3 && !sane_input_length(in[i])))
      check_policy_number(in[i], i % width < 3, fmt::format("poses[{}, {}]", i / width, i % width));

  // The outputs, named as the columns of `pkmopt analyze` (q_j and tau_j as (N, n) arrays,
  // C_ab as an (N, 6, 6) array, the mode shapes as (N, modes, axes + 6)).
  const std::vector<std::string> names = analyze_value_columns(machine, mode_shapes, compliance);
  const std::size_t na = static_cast<std::size_t>(machine.num_actuators());
  const std::size_t nf =
      static_cast<std::size_t>(dynamics ? dynamics->natural_frequency_count() : 0);
  const std::size_t rows = static_cast<std::size_t>(dynamics ? dynamics->mode_axis_count() : 0) + 6;
  if (!out.is_none() && !py::isinstance<py::dict>(out))
    throw InputError("out: expected the dict of an earlier analyze, or None");
  py::dict result;
  py::array_t<bool> reachable = output_array<bool>(out, "reachable", {static_cast<py::ssize_t>(n)});
  result["reachable"] = reachable;
  auto matrix = [&](const char* key, std::vector<py::ssize_t> shape) {
    py::array_t<double> a = output_array<double>(out, key, shape);
    result[key] = a;
    return a.mutable_data();
  };
  double* q = matrix("q", {static_cast<py::ssize_t>(n), static_cast<py::ssize_t>(na)});
  double* tau = matrix("tau", {static_cast<py::ssize_t>(n), static_cast<py::ssize_t>(na)});
  double* modes = nullptr;
  double* c = nullptr;
  std::vector<ColumnTarget> targets(names.size());
  std::size_t c_index = 0, mode_index = 0;
  for (std::size_t k = 1; k < names.size(); ++k) {
    const std::string& name = names[k];
    if (k <= na) {
      targets[k] = {q, na, k - 1};
    } else if (k <= 2 * na) {
      targets[k] = {tau, na, k - 1 - na};
    } else if (name.starts_with("C_")) {
      if (!c) c = matrix("compliance", {static_cast<py::ssize_t>(n), 6, 6});
      targets[k] = {c, 36, c_index++};
    } else if (name.starts_with("mode_")) {
      if (!modes)
        modes = matrix("mode_shapes", {static_cast<py::ssize_t>(n), static_cast<py::ssize_t>(nf),
                                       static_cast<py::ssize_t>(rows)});
      targets[k] = {modes, nf * rows, mode_index++};
    } else {
      targets[k] = {matrix(name.c_str(), {static_cast<py::ssize_t>(n)}), 1, 0};
    }
  }
  bool* reach = reachable.mutable_data();
  const bool interference = machine.checks_leg_interference();
  std::vector<std::string> pairs(interference ? n : 0);
  // Chunks of 64 slices (65,536 poses); between two the GIL is taken back for a moment so that
  // Ctrl-C (KeyboardInterrupt) stops a long call. A pose's numbers do not depend on its chunk.
  constexpr std::size_t kChunk = 64 * kPoseSlice;
  for (std::size_t first = 0; first < n; first += kChunk) {
    {
      py::gil_scoped_release release;
      analyze_pose_slices(
          machine, std::min(kChunk, n - first), wrench, compliance, threads,
          [&](const PoseSlice& s) {
            for (std::size_t k = 0; k < s.poses.size(); ++k) {
              const double* row = in + (first + s.start + k) * width;
              Pose& pose = s.poses[k];
              pose.position = {row[0], row[1], row[2]};
              const Eigen::Vector3d deg =
                  width == 6 ? Eigen::Vector3d(row[3], row[4], row[5]) : Eigen::Vector3d::Zero();
              pose.angles = deg_to_rad(deg);
            }
          },
          [&](const PoseSlice& s) {
            const std::size_t columns = names.size();
            std::vector<double> values(columns);
            std::vector<double*> at(columns, nullptr);  // column c of pose s.start + k
            for (std::size_t col = 1; col < columns; ++col)
              at[col] =
                  targets[col].base + (first + s.start) * targets[col].stride + targets[col].offset;
            std::unique_ptr<MachineData> data = mode_shapes ? machine.make_data() : nullptr;
            PoseModes pose_modes;
            for (std::size_t k = 0; k < s.metrics.size(); ++k) {
              const std::size_t i = first + s.start + k;
              if (mode_shapes && !dynamics->mode_shapes(*data, s.poses[k], pose_modes))
                pose_modes = PoseModes{};
              analyze_values(machine, s.metrics[k], mode_shapes ? &pose_modes : nullptr,
                             compliance ? &s.matrices[k] : nullptr, values.data());
              reach[i] = s.metrics[k].reachable;
              for (std::size_t col = 1; col < columns; ++col) {
                *at[col] = values[col];
                at[col] += targets[col].stride;
              }
              if (interference)
                pairs[i] = clearance_pair_text(s.metrics[k].clearance_first,
                                               s.metrics[k].clearance_second);
            }
          });
    }
    if (PyErr_CheckSignals() != 0) throw py::error_already_set();
  }
  if (interference) result["clearance_pair"] = py::cast(pairs);
  return result;
}

py::dict ik(const PyMachine& self, py::handle pose_in) {
  const Machine& machine = *self.machine;
  const Pose pose = pose_from_python(pose_in, "pose");
  const std::unique_ptr<MachineData> data = machine.make_data();
  data->compliance_metrics = false;
  PoseMetrics metrics;
  machine.analyze(*data, pose, Wrench::Zero(), metrics);
  py::dict out;
  bool closes = metrics.q.size() == machine.num_actuators() && metrics.q.allFinite();
  if (closes) {
    py::array_t<double> q(metrics.q.size());
    for (Eigen::Index j = 0; j < metrics.q.size(); ++j)
      q.mutable_at(j) =
          metrics.q(j) * (machine.revolute_actuator(static_cast<int>(j)) ? kRadToDeg : 1.0);
    out["q"] = q;
  } else {
    out["q"] = py::none();
  }
  out["reachable"] = metrics.reachable;
  return out;
}

py::dict fk(const PyMachine& self, py::handle q_in, const py::object& guess_in,
            int max_iterations) {
  const Machine& machine = *self.machine;
  const int na = machine.num_actuators();
  const DoubleArray qa = DoubleArray::ensure(q_in);
  if (!qa || qa.ndim() != 1 || qa.shape(0) != na)
    throw InputError(fmt::format("q: expected {} actuator coordinates ({}), found {}", na,
                                 machine.revolute_actuators()      ? "deg"
                                 : machine.any_revolute_actuator() ? "m or deg per axis"
                                                                   : "m",
                                 python_repr(q_in)));
  Eigen::VectorXd q(na);
  for (int i = 0; i < na; ++i)
    q(i) = machine.revolute_actuator(i)
               ? finite_number(py::float_(qa.at(i)), fmt::format("q[{}]", i)) * kDegToRad
               : length_number(py::float_(qa.at(i)), fmt::format("q[{}]", i));
  if (const std::string expected = machine.actuator_coordinates_requirement(q); !expected.empty())
    throw InputError(fmt::format("q: expected {}, found {}", expected, python_repr(q_in)));
  std::optional<Pose> guess;
  if (!guess_in.is_none()) guess = pose_from_python(guess_in, "guess");
  if (max_iterations < 1)
    throw InputError(
        fmt::format("max_iterations: expected an integer >= 1, found {}", max_iterations));
  FkOptions options;
  options.max_iterations = max_iterations;
  FkResult r;
  {
    py::gil_scoped_release release;
    r = machine.forward_kinematics(q, guess, options);
  }
  py::dict out;
  out["pose"] = pose_to_python(r.pose);
  out["converged"] = r.converged;
  out["iterations"] = r.iterations;
  out["residual"] = r.residual;
  out["message"] = r.message;
  return out;
}

py::object jacobian(const PyMachine& self, py::handle pose_in) {
  const Machine& machine = *self.machine;
  const Pose pose = pose_from_python(pose_in, "pose");
  const std::unique_ptr<MachineData> data = machine.make_data();
  Eigen::MatrixXd J;
  if (!machine.twist_jacobian(*data, pose, J)) return py::none();
  py::array_t<double> out({static_cast<py::ssize_t>(J.rows()), static_cast<py::ssize_t>(J.cols())});
  auto r = out.mutable_unchecked<2>();
  for (Eigen::Index i = 0; i < J.rows(); ++i)
    for (Eigen::Index j = 0; j < J.cols(); ++j) r(i, j) = J(i, j);
  return out;
}

// The options of `pkmopt workspace`, by keyword (docs/workspace.md).
py::dict workspace(const PyMachine& self, const py::object& orientation, double tilt_deg,
                   double yaw_range_deg, const std::string& mode, double orientation_step_deg,
                   const py::object& resolution_in, double tolerance, const py::object& min_margin,
                   const py::object& min_stiffness, const py::object& wrench_in, bool keep_points) {
  const Machine& machine = *self.machine;
  const auto start = std::chrono::steady_clock::now();
  WorkspaceOptions options;
  if (!orientation.is_none()) {
    if (!py::isinstance<py::sequence>(orientation) || py::isinstance<py::str>(orientation) ||
        py::len(orientation) != 3)
      throw InputError(fmt::format("orientation: expected 3 angles rx, ry, rz (deg), found {}",
                                   python_repr(orientation)));
    const py::sequence s = orientation.cast<py::sequence>();
    for (int k = 0; k < 3; ++k)
      options.orientations.nominal_angles(k) =
          deg_to_rad(finite_number(s[k], fmt::format("orientation[{}]", k)));
  }
  // One rule per limit, shared with the workspace command and study files.
  using namespace workspace_limits;
  auto check = [](const char* key, const ValueLimit& limit, double found) {
    if (!limit.accepts(found))
      throw InputError(fmt::format("{}: expected {}, found {}", key, limit.expected, found));
  };
  check("tilt_deg", kTiltDeg, tilt_deg);
  check("yaw_range_deg", kYawRangeDeg, yaw_range_deg);
  check("orientation_step_deg", kOrientationStepDeg, orientation_step_deg);
  options.orientations.tilt = deg_to_rad(tilt_deg);
  options.orientations.yaw_range = deg_to_rad(yaw_range_deg);
  options.orientations.orientation_step = deg_to_rad(orientation_step_deg);
  if (const std::int64_t count = orientation_count(options.orientations); count > kMaxOrientations)
    throw InputError(fmt::format(
        "orientation_step_deg: expected a step that samples at most {} orientations of the tilt "
        "and yaw range, found {} ({} orientations)",
        kMaxOrientations, orientation_step_deg, count));
  if (mode == "all") {
    options.orientations.mode = OrientationSet::Mode::kAll;
  } else if (mode == "some") {
    options.orientations.mode = OrientationSet::Mode::kSome;
  } else {
    throw InputError(fmt::format("mode: expected 'all' or 'some', found {}", quote_found(mode)));
  }
  std::optional<double> resolution;
  if (!resolution_in.is_none()) {
    resolution = length_number(resolution_in, "resolution");
    check("resolution", kResolution, *resolution);
  }
  check("tolerance", kTolerance, tolerance);
  options.resolution = resolution.value_or(0.02);
  if (!min_margin.is_none()) {
    const double v = finite_number(min_margin, "min_margin");
    check("min_margin", kMinMargin, v);
    options.min_singularity_margin = v;
  }
  if (!min_stiffness.is_none()) {
    const double v = finite_number(min_stiffness, "min_stiffness");
    check("min_stiffness", kMinStiffness, v);
    options.min_stiffness = v;
  }
  options.wrench = wrench_from_python(wrench_in);
  options.keep_points = keep_points;
  if (const std::string invalid = validate(options); !invalid.empty()) throw InputError(invalid);
  if (!workspace_search_box(machine, sample_orientations(options.orientations)))
    throw InputError(
        fmt::format("{}: model '{}' has no workspace search box", self.source, machine.model()));
  WorkspaceResult ws;
  VolumeAccuracy accuracy;
  {
    py::gil_scoped_release release;
    try {
      if (!resolution) {
        accuracy = choose_workspace_resolution(machine, options, tolerance);
        options.resolution = accuracy.resolution;
      }
      ws = compute_workspace(machine, options);
      if (resolution) accuracy = workspace_volume_accuracy(machine, options, ws.volume);
    } catch (const std::invalid_argument& e) {
      throw InputError(fmt::format("resolution: {}", e.what()));
    }
  }
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const WorkspaceRequest request{.machine_file = self.source,
                                 .model = std::string(machine.model()),
                                 .options = options,
                                 .tilt_deg = tilt_deg,
                                 .yaw_range_deg = yaw_range_deg,
                                 .orientation_step_deg = orientation_step_deg,
                                 .accuracy = accuracy};
  nlohmann::ordered_json summary = nlohmann::ordered_json::parse(workspace_summary_json(
      request, ws, WorkspaceSlice{}, SliceMetric::kSingularityMargin, seconds));
  summary.erase("slice");
  py::dict out = py::module_::import("json").attr("loads")(summary.dump());
  py::array_t<double> vertices(
      {static_cast<py::ssize_t>(ws.boundary.vertices.size()), py::ssize_t{3}});
  auto v = vertices.mutable_unchecked<2>();
  for (std::size_t i = 0; i < ws.boundary.vertices.size(); ++i)
    for (int k = 0; k < 3; ++k) v(static_cast<py::ssize_t>(i), k) = ws.boundary.vertices[i](k);
  py::array_t<int> faces({static_cast<py::ssize_t>(ws.boundary.triangles.size()), py::ssize_t{3}});
  auto f = faces.mutable_unchecked<2>();
  for (std::size_t i = 0; i < ws.boundary.triangles.size(); ++i)
    for (int k = 0; k < 3; ++k) f(static_cast<py::ssize_t>(i), k) = ws.boundary.triangles[i][k];
  out["vertices"] = vertices;
  out["faces"] = faces;
  if (keep_points) {
    const std::size_t np = ws.points.size();
    py::array_t<double> positions({static_cast<py::ssize_t>(np), py::ssize_t{3}});
    auto p = positions.mutable_unchecked<2>();
    py::dict point_metrics;
    std::vector<py::array_t<double>> columns;
    const char* keys[] = {"singularity_margin", "stiffness_min",  "max_leg_force",
                          "tcp_error_max",      "tcp_deflection", "stiffness_min_loaded",
                          "natural_frequency_1"};
    for (const char* key : keys) {
      columns.emplace_back(static_cast<py::ssize_t>(np));
      point_metrics[key] = columns.back();
    }
    for (std::size_t i = 0; i < np; ++i) {
      const WorkspacePoint& wp = ws.points[i];
      for (int k = 0; k < 3; ++k) p(static_cast<py::ssize_t>(i), k) = wp.position(k);
      const WorkspacePointMetrics& m = wp.metrics;
      const double values[] = {m.singularity_margin, m.stiffness_min,  m.max_leg_force,
                               m.tcp_error_max,      m.tcp_deflection, m.stiffness_min_loaded,
                               m.natural_frequency_1};
      for (std::size_t k = 0; k < columns.size(); ++k)
        columns[k].mutable_at(static_cast<py::ssize_t>(i)) = values[k];
    }
    point_metrics["position"] = positions;
    out["points"] = point_metrics;
  }
  return out;
}

}  // namespace

void bind_machine(py::module_& m) {
  const std::string machine_doc =
      "A machine model read from a machine file (docs/conventions.md; models: " +
      machine_model_names() +
      "). Immutable; its methods may be called from several Python threads.";
  py::class_<PyMachine> machine_class(m, "Machine", machine_doc.c_str());
  // Machines come from load_machine and machine_from_dict only: Machine.__new__(Machine) would
  // make an object without its C++ machine (methods on it crashed the interpreter).
  machine_class.attr("__new__") = py::staticmethod(py::cpp_function(
      [](const py::args&, const py::kwargs&) -> py::object {
        throw py::type_error(
            "pkmopt.Machine objects are made by pkmopt.load_machine(path) or "
            "pkmopt.machine_from_dict(dict), not by Machine() or Machine.__new__");
      },
      py::name("__new__")));
  machine_class
      .def_property_readonly(
          "model", [](const PyMachine& self) { return std::string(self.machine->model()); },
          "The `model:` name of the machine file.")
      .def_property_readonly(
          "num_actuators", [](const PyMachine& self) { return self.machine->num_actuators(); },
          "Number of actuators n (the length of q and tau).")
      .def_property_readonly(
          "revolute_actuators",
          [](const PyMachine& self) { return self.machine->revolute_actuators(); },
          "True when every actuator is revolute: q in degrees and tau in N*m; else q in m and "
          "tau in N, except for the axes `revolute_axes` marks.")
      .def_property_readonly(
          "revolute_axes",
          [](const PyMachine& self) {
            py::list out;
            for (int i = 0; i < self.machine->num_actuators(); ++i)
              out.append(self.machine->revolute_actuator(i));
            return out;
          },
          "One flag per actuator: True for a revolute drive or rotary axis (q in degrees, tau in "
          "N*m), False for a linear one (m, N). A serial 5-axis machine mixes both.")
      .def_property_readonly(
          "natural_frequency_count",
          [](const PyMachine& self) {
            const Capability<Dynamics> dynamics = self.machine->dynamics();
            return dynamics ? dynamics->natural_frequency_count() : 0;
          },
          "How many natural frequencies analyze gives (the platform DOF with a mass model, "
          "else 0).")
      .def_property_readonly(
          "source", [](const PyMachine& self) { return self.source; },
          "The machine file it was read from, or '<dict>'.")
      .def(
          "describe",
          [](const PyMachine& self) { return format_description(describe_machine(self.document)); },
          "The text `pkmopt describe` prints: degrees of freedom, drives and structure class.")
      .def("analyze", &analyze, py::arg("poses"), py::arg("wrench") = py::none(),
           py::arg("threads") = py::none(), py::arg("compliance") = false,
           py::arg("mode_shapes") = false, py::arg("out") = py::none(),
           R"(Every per-pose metric of `pkmopt analyze`, for many poses at once.

poses: float array of shape (N, 3) (x, y, z in m, base frame) or (N, 6) (and rx, ry, rz in
  degrees, R = Rz(rz) Ry(ry) Rx(rx)); a float64 C-contiguous array is read in place (no copy).
wrench: 6 numbers fx, fy, fz (N), mx, my, mz (N*m) at the TCP, base axes; default 0.
threads: OpenMP threads (default: all cores). The GIL is released while it runs.
compliance: also return 'compliance', the (N, 6, 6) compliance matrix C at the TCP
  (twist [m, rad] per wrench [N, N*m]).
mode_shapes: (machines with masses) also return 'mode_shapes', (N, modes, axes + 6): each mode's
  serial axes (m), TCP displacement (m) and rotation (rad), mass-normalised.
out: the dict an earlier call returned (as many poses, the same options): its arrays are
  overwritten instead of new ones allocated (repeated sweeps then touch no new memory).

Returns a dict of numpy arrays named as the CSV columns of `pkmopt analyze`, in its units:
'reachable' (bool), 'q' (N, n; m or deg), 'tau' (N, n; N or N*m, tension positive),
'stiffness_min' (N/m), 'singularity_margin', 'det_j', 'tcp_error_max' (m), 'tcp_deflection' (m),
'tcp_rotation_deflection_deg' (deg), 'stiffness_min_loaded' (N/m), 'stiffness_dir_x/y/z', and
when the machine has them 'leg_clearance' (m) with 'clearance_pair' (list of str) and
'natural_frequency_1'.. (Hz). The numbers are those `pkmopt analyze` writes, bit for bit.)")
      .def("ik", &ik, py::arg("pose"),
           "Inverse kinematics at a pose (3 or 6 numbers: m, deg): {'q': actuator coordinates "
           "(m or deg; None when a leg cannot close), 'reachable': within every actuator range "
           "and joint limit}.")
      .def("fk", &fk, py::arg("q"), py::arg("guess") = py::none(), py::arg("max_iterations") = 100,
           "Forward kinematics (damped Newton, as `pkmopt fk`): the pose for actuator "
           "coordinates q (m or deg) from `guess` (x, y, z, rx, ry, rz in m and deg; default "
           "the machine's home pose). Returns {'pose': array (x, y, z m, rx, ry, rz deg), "
           "'converged', 'iterations', 'residual' (max |q(pose) - q|, m or rad), 'message'}.")
      .def("jacobian", &jacobian, py::arg("pose"),
           "The inverse Jacobian J at a pose, a numpy (n, 6) array with q_dot = J [v; omega] "
           "(v in m/s, omega in rad/s, base axes, at the TCP; rows in m or rad per unit "
           "twist); J.T (6, n) maps actuator forces to the TCP wrench, J.T tau = w. None when a "
           "leg cannot close at the pose.")
      .def("workspace", &workspace, py::kw_only(), py::arg("orientation") = py::none(),
           py::arg("tilt_deg") = 0.0, py::arg("yaw_range_deg") = 0.0, py::arg("mode") = "all",
           py::arg("orientation_step_deg") = 5.0, py::arg("resolution") = py::none(),
           py::arg("tolerance") = 0.005, py::arg("min_margin") = py::none(),
           py::arg("min_stiffness") = py::none(), py::arg("wrench") = py::none(),
           py::arg("points") = false,
           R"(The workspace, as `pkmopt workspace` computes it (docs/workspace.md).

Keywords as the command's options: orientation (rx, ry, rz deg), tilt_deg, yaw_range_deg,
mode ('all' or 'some'), orientation_step_deg, resolution (m; default: the coarsest grid whose
volume meets `tolerance`), tolerance, min_margin, min_stiffness (N/m), wrench (N, N*m).
Returns the fields of the command's summary.json (volume in m^3, maps, boxes, ...) and the
boundary mesh: 'vertices' (V, 3) in m and 'faces' (F, 3) vertex indices, counter-clockwise seen
from outside; with points=True also 'points': every inside grid node's 'position' (P, 3) and
its metrics.)");

  m.def("load_machine", &load_machine_py, py::arg("path"),
        "Reads a machine file (YAML, docs/conventions.md) of any model. Bad input raises "
        "pkmopt.InputError with the message `pkmopt` prints (file, line, column, key, expected, "
        "found).");
  m.def("machine_from_dict", &machine_from_dict, py::arg("machine"),
        "A machine from a dict with the keys of a machine file (numbers, lists, dicts; numpy "
        "arrays allowed). The same checks and messages as a file, the key path in place of "
        "file and line; relative paths (a hybrid's module file) are taken from the working "
        "directory.");
}

}  // namespace pkmopt::python
