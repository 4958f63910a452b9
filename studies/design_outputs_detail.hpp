// Shared by studies/design_outputs.cpp (evaluations.csv rows, measuring designs, choosing the
// front) and studies/design_front_files.cpp (pareto.csv, pareto.json, summary.json). Not part of
// the public interface: studies/design_study.hpp is.
#pragma once

#include <cstddef>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "studies/design_study.hpp"

namespace pkmopt::design_outputs_detail {

/// -1 for a maximised objective (minimised internally as -M), +1 otherwise.
double sense_sign(Sense sense);
/// The constraint columns: g_<metric>_max / g_<metric>_min, then g_task_reachable.
std::vector<std::string> constraint_names(const DesignStudy& study);
/// Indices (into study.parameters) of the variables, in variable order.
std::vector<int> free_parameter_indices(const DesignStudy& study);
/// A finite number, or null.
nlohmann::json json_number(double value);
/// True when [objectives | constraint rows] is feasible as evaluations.csv says: finite
/// objectives and every row <= 0.
bool feasible_fitness(const std::vector<double>& fitness, std::size_t m);

// A design measured for the outputs, whichever problem the study has.
struct MeasuredDesign {
  std::vector<double> x;
  std::vector<double> parameters;  // every parameter, file units (study.parameters order)
  double home_height = 0.0;        // m
  DesignMetrics metrics{};
  std::vector<double> aggregate;  // [objectives internal | constraint rows]
  std::string failure;
  std::string machine_file;  // YAML of the machine (when asked for)
  int actuator = -1;         // chosen catalog entry (hexapod studies choosing the cheapest)
  bool ok() const { return failure.empty(); }
};

// The designs of the front (measured again with the aggregate metrics, machine files when the
// study writes them) and the archive they were chosen from.
struct FrontSelection {
  std::vector<MeasuredDesign> designs;
  std::size_t feasible_evaluations = 0;  // distinct feasible designs (aggregate metrics)
  std::size_t archive_size = 0;          // of them non-dominated
};

/// The front of the run (studies/design_study.hpp, write_design_outputs): the non-dominated set
/// of every feasible journal entry, thinned to output.front_size; a single objective: the
/// solver's answer.
FrontSelection select_design_front(const DesignStudy& study, const RunOutcome& outcome,
                                   const DesignRunFacts& facts);

}  // namespace pkmopt::design_outputs_detail
