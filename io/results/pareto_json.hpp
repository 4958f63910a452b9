// pareto.json, the front of a design study (schema "pkmopt-pareto-1", docs/export.md): its
// reader, its writer, and the CSV export of the front.
//
// Units are those of pareto.json: parameters in file units (m, degrees for *_deg), objectives
// in the user's sign and units (N/m, m^3, N, ...), constraint values g in metric units with
// g <= 0 satisfied. A non-finite value (null in pareto.json) is NaN in memory, null in JSON and
// an empty cell in CSV.
//
// Example:
//   const pkmopt::ParetoFront front = pkmopt::read_pareto_json("results/pareto.json");
//   const std::string csv = pkmopt::pareto_csv(front);
#pragma once

#include <Eigen/Core>
#include <array>
#include <optional>
#include <string>
#include <utility>
#include <vector>

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
  /// The extent of the task positions before a design's home_height lift (m; optional keys
  /// positions_min, positions_max).
  std::optional<std::pair<Eigen::Vector3d, Eigen::Vector3d>> positions;
};

/// How the front was chosen from the run (optional key "front_selection").
struct ParetoSelection {
  std::string rule;                 ///< in words
  double evaluations = 0;           ///< distinct evaluations of the run
  double feasible_evaluations = 0;  ///< of them feasible
  double archive_size = 0;          ///< of them non-dominated (before thinning)
};

/// The hypervolume of the non-dominated feasible designs found after the first
/// evaluations[k] evaluations (optional key "convergence"; the reference point of summary.json,
/// in the product of the objective units).
struct ParetoConvergence {
  std::vector<double> evaluations;
  std::vector<double> hypervolume;
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
  std::optional<std::string> knee;          ///< id of the knee design
  std::optional<std::string> compromise;    ///< id of the design nearest the ideal point
  std::vector<std::string> high_trade_off;  ///< ids of the high-trade-off designs
  /// The catalog actuators were chosen from (pareto.json "actuator_catalog"), if any.
  std::optional<std::string> actuator_catalog;
  std::optional<ParetoSelection> selection;
  std::optional<ParetoConvergence> convergence;

  /// Index of the design with this id, or -1.
  int design_index(const std::string& id) const;
  /// True when a free parameter is called home_height (then it is not a separate column).
  bool home_height_is_parameter() const;
};

/// Reads and checks a pareto.json file. Every missing key, wrong type, unknown format, name
/// that does not match the lists at the top, repeated id or unknown knee, compromise or
/// high-trade-off id throws InputError
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

}  // namespace pkmopt
