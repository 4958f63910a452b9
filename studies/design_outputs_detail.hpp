// Shared by studies/design_outputs.cpp (evaluations.csv rows, measuring designs, choosing the
// front) and studies/design_front_files.cpp (pareto.csv, pareto.json, summary.json). Not part of
// the public interface: studies/design_study.hpp is.
#pragma once

#include <fmt/format.h>

#include <cstddef>
#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

#include "io/format/csv.hpp"
#include "io/format/output_file.hpp"
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
  std::string drives;        // every drive's entry (a catalog with each_drive), in words
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

/// The files write_design_outputs writes (pareto.csv, pareto.json, summary.json and
/// designs/<id>.yaml in `directory`), not yet written, with the front they show.
struct DesignFiles {
  OutputFiles files;
  DesignOutputSummary summary;
  FrontSelection selection;
};
DesignFiles design_output_files(const std::string& directory, const DesignStudy& study,
                                const RunOutcome& outcome, const DesignRunFacts& facts);

// Why the run's designs were infeasible: failures by reason and violated constraint rows by
// name, counted over the distinct evaluations (summary.json "infeasibility" and the warning of a
// run without a feasible design).
struct Infeasibility {
  std::size_t evaluations = 0;
  std::size_t feasible = 0;
  std::vector<std::pair<std::string, std::size_t>> failures;  // reason, count (most first)
  std::vector<std::pair<std::string, std::size_t>> violated;  // constraint, count (most first)

  nlohmann::json json() const {
    nlohmann::json j;
    j["evaluations"] = evaluations;
    j["feasible"] = feasible;
    j["failed"] = nlohmann::json::object();
    for (const auto& [reason, n] : failures) j["failed"][reason] = n;
    j["violated"] = nlohmann::json::object();
    for (const auto& [name, n] : violated) j["violated"][name] = n;
    return j;
  }
  // "g_task_reachable > 0 in 4412, g_leg_force_max_max > 0 in 311 of 4880 evaluations; 57
  // failed ('...' 40, ...)": the three most frequent of each.
  std::string text() const {
    std::string t;
    for (std::size_t k = 0; k < violated.size() && k < 3; ++k)
      t += fmt::format("{}{} > 0 in {}", k ? ", " : "", violated[k].first, violated[k].second);
    t += fmt::format("{}{} evaluations", t.empty() ? "" : " of ", evaluations);
    std::size_t failed = 0;
    for (const auto& f : failures) failed += f.second;
    if (failed > 0) {
      t += fmt::format("; {} failed (", failed);
      for (std::size_t k = 0; k < failures.size() && k < 3; ++k)
        t += fmt::format("{}{} {}", k ? ", " : "", quote_found(failures[k].first),
                         failures[k].second);
      t += failures.size() > 3 ? ", ...)" : ")";
    }
    return t;
  }
};

Infeasibility count_infeasibility(const DesignStudy& study,
                                  const std::vector<JournalEntry>& entries);

}  // namespace pkmopt::design_outputs_detail
