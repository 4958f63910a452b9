// Reports of a design study's results: reading DIR/pareto.json (written by `pkmopt run`, schema
// "pkmopt-pareto-1", see docs/export.md) and rendering the Pareto front as CSV, normalised JSON,
// Pareto plots (SVG, PNG) and one self-contained HTML report (`pkmopt export`).
//
// Units are those of pareto.json: parameters in file units (m, degrees for *_deg), objectives
// in the user's sign and units (N/m, m^3, N, ...), constraint values g in metric units with
// g <= 0 satisfied. A non-finite value (null in pareto.json) is NaN in memory, null in JSON, an
// empty cell in CSV, and is left out of the plots.
//
// The knee design's workspace slice: its machine file (designs/<id>.yaml, in the machine's base
// frame) is cut by the plane z = task.centre[2] + home_height (the task centre's height in that
// frame) at constant orientation R = I (rx = ry = rz = 0), coloured by singularity_margin, with
// the task wrench used for max_leg_force.
//
//   const pkmopt::ParetoFront front = pkmopt::read_pareto_json("results/pareto.json");
//   const std::string csv = pkmopt::pareto_csv(front);
//   const std::string svg = pkmopt::pareto_plot_svg(front);
//   const auto slice = pkmopt::knee_workspace_slice(front, "results");
//   const std::string html = pkmopt::report_html(front, slice ? &*slice : nullptr);
#pragma once

#include <Eigen/Core>
#include <array>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "models/workspace/workspace.hpp"

namespace pkmopt {

struct ParetoParameter {
  std::string name;
  std::string unit;
  double min = 0.0, max = 0.0;
};

struct ParetoObjective {
  std::string name;
  std::string sense;  ///< "minimize" or "maximize"
  std::string unit;
};

struct ParetoConstraint {
  std::string name;    ///< column name, e.g. g_leg_force_max_max
  std::string metric;  ///< e.g. leg_force_max, task_reachable
  std::string kind;    ///< "max", "min" or "reachable"
  double bound = 0.0;
  std::string unit;
};

struct ParetoTask {
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();  ///< m, task frame
  std::array<double, 6> wrench{};                    ///< N, N*m at the TCP, base axes
  double tilt_deg = 0.0, yaw_deg = 0.0;
};

/// The catalog actuator chosen for a design (studies with {actuator: cheapest, catalog: FILE}).
struct ParetoActuator {
  std::string name;
  double max_force = 0.0;      ///< N
  double stroke = 0.0;         ///< m
  double cost = 0.0;           ///< relative (the catalog's cost, or the rank by force rating)
  double force_reserve = 0.0;  ///< max_force / leg_force_max (NaN when the file has null)
};

struct ParetoDesign {
  std::string id;
  std::vector<double> parameters;   ///< in the order of ParetoFront::parameters
  double home_height = 0.0;         ///< m
  std::vector<double> objectives;   ///< in the order of ParetoFront::objectives
  std::vector<double> constraints;  ///< in the order of ParetoFront::constraints
  bool feasible = false;
  std::optional<std::string> machine_file;  ///< relative to the results folder
  std::optional<ParetoActuator> actuator;   ///< when the front chose actuators and one carries
};

/// The contents of a pareto.json file.
struct ParetoFront {
  std::string file;  ///< the path it was read from (for messages)
  std::string format = "pkmopt-pareto-1";
  std::string pkmopt_version, study, description, model;
  std::vector<ParetoParameter> parameters;
  std::vector<std::pair<std::string, double>> fixed_parameters;
  std::vector<ParetoObjective> objectives;
  std::vector<ParetoConstraint> constraints;
  ParetoTask task;
  std::vector<ParetoDesign> designs;
  std::optional<std::string> knee;  ///< id of the knee design
  /// The catalog actuators were chosen from (pareto.json "actuator_catalog"), if any.
  std::optional<std::string> actuator_catalog;

  /// Index of the design with this id, or -1.
  int design_index(const std::string& id) const;
  /// True when a free parameter is called home_height (then it is not a separate column).
  bool home_height_is_parameter() const;
};

/// Reads and checks a pareto.json file. Every missing key, wrong type, unknown format, name
/// that does not match the lists at the top, repeated id or unknown knee throws InputError
/// "FILE: KEY: expected X, found Y" (JSON syntax errors: "FILE:LINE:COL: expected JSON, found
/// ..."). Keys not in the schema are ignored.
ParetoFront read_pareto_json(const std::string& path);

/// One row per design: id, free parameters, home_height (unless a free parameter), objectives,
/// constraint values, actuator (when the front chose catalog actuators), feasible (0/1),
/// knee (0/1).
std::string pareto_csv(const ParetoFront& front);

/// The front as pareto.json text again, keys in schema order, 2-space indent, numbers that
/// round-trip, non-finite values as null.
std::string pareto_json(const ParetoFront& front);

/// Scatter plot of objective `x_objective` against `y_objective` (feasible designs filled,
/// infeasible ones as rings, the knee red); axes named with unit and sense, with ticks.
/// Standalone SVG file (with its xmlns) and 8-bit RGB PNG.
std::string pareto_plot_svg(const ParetoFront& front, int x_objective = 0, int y_objective = 1);
std::string pareto_plot_png(const ParetoFront& front, int x_objective = 0, int y_objective = 1);

/// The knee design's workspace slice (see the header comment), or nullopt when there is no knee
/// or it has no machine file. Throws InputError if the machine file cannot be read.
/// `pixels` is the number of pixels along the longer side.
std::optional<WorkspaceSlice> knee_workspace_slice(const ParetoFront& front,
                                                   const std::string& results_dir,
                                                   int pixels = 160);

/// The self-contained HTML report: no external scripts, fonts, styles or URLs. Holds the Pareto
/// scatter (first two objectives; with one objective a strip) and, for three or more
/// objectives, a parallel-coordinates view, both as inline SVG with one element per design;
/// hovering shows that design's parameters, objectives and constraints; the knee design's table
/// and its workspace slice (a PNG as a data: URI) when `knee_slice` is given.
std::string report_html(const ParetoFront& front, const WorkspaceSlice* knee_slice);

/// Base64 (RFC 4648, with padding).
std::string base64(const std::string& bytes);

/// Helpers shared with other HTML/SVG writers (`pkmopt compare`): text with & < > " escaped for
/// HTML and XML; an objective's axis label "name [unit] (max|min)"; the HTML table of one
/// design's free and fixed parameters, objectives and constraints (as in the export report's
/// knee section).
std::string html_escape(std::string_view text);
std::string objective_axis_label(const ParetoObjective& objective);
std::string design_table_html(const ParetoFront& front, const ParetoDesign& design);

}  // namespace pkmopt
