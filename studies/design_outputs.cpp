#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>
#include <stdexcept>

#include "io/design/actuator_catalog_file.hpp"
#include "io/design/task_wrench_file.hpp"
#include "io/format/csv.hpp"
#include "io/format/input_error.hpp"
#include "io/format/output_file.hpp"
#include "io/machine/machine_file.hpp"
#include "optimizer/front_thinning.hpp"
#include "optimizer/indicators.hpp"
#include "pkmopt/version.hpp"
#include "studies/design_outputs_detail.hpp"
#include "studies/design_study.hpp"

namespace pkmopt {

std::string_view design_metric_unit(DesignMetric metric) {
  switch (metric) {
    case DesignMetric::stiffness_min:
    case DesignMetric::stiffness_min_loaded:
      return "N/m";
    case DesignMetric::tcp_deflection_max:
    case DesignMetric::leg_clearance_min:
    case DesignMetric::task_margin:
      return "m";
    case DesignMetric::leg_force_max:
    case DesignMetric::actuator_force_dynamic_max:
      return "N";
    case DesignMetric::tcp_error_max:
      return "m";
    case DesignMetric::natural_frequency_min:
      return "Hz";
    case DesignMetric::moving_mass:
      return "kg";
    case DesignMetric::workspace_volume:
    case DesignMetric::machine_size:
    case DesignMetric::swept_volume:
      return "m^3";
    case DesignMetric::footprint:
      return "m^2";
    case DesignMetric::actuator_overload:
      return "N";
    case DesignMetric::singularity_margin:
    case DesignMetric::conditioning_index:
    case DesignMetric::actuator_cost:
    case DesignMetric::task_singularity_free:
    case DesignMetric::drive_cost:
    case DesignMetric::drive_overload:
      return "";
  }
  return "";
}

namespace design_outputs_detail {

double sense_sign(Sense sense) { return sense == Sense::maximize ? -1.0 : 1.0; }

std::vector<std::string> constraint_names(const DesignStudy& study) {
  std::vector<std::string> names;
  for (const DesignConstraint& c : study.constraints())
    names.push_back(fmt::format("g_{}_{}", design_metric_name(c.metric),
                                c.relation == Relation::less_equal ? "max" : "min"));
  if (study.require_reachable()) names.emplace_back("g_task_reachable");
  return names;
}

// Indices (into study.parameters) of the variables, in variable order.
std::vector<int> free_parameter_indices(const DesignStudy& study) {
  return study.problem->free_parameters();
}

// Every parameter of a variable vector in file units (study.parameters order).
std::vector<double> file_parameters(const DesignStudy& study, const std::vector<double>& x) {
  std::vector<double> values = study.problem->design_parameters(x);
  for (std::size_t i = 0; i < values.size(); ++i)
    if (study.parameters[i].unit == "deg") values[i] = rad_to_deg(values[i]);
  return values;
}

MeasuredDesign measure_design(const DesignStudy& study, const std::vector<double>& x,
                              bool machine_file) {
  MeasuredDesign d;
  d.x = x;
  d.parameters = file_parameters(study, x);
  DesignRecord record = study.problem->measure(x);
  d.home_height = record.home_height;
  d.metrics = record.metrics;
  d.aggregate = std::move(record.aggregate);
  d.failure = std::move(record.failure);
  d.actuator = record.actuator;
  d.drives = record.drives;
  if (machine_file && d.failure.empty())
    d.machine_file = study.machine->machine_file(record.parameters);
  return d;
}

}  // namespace design_outputs_detail

using namespace design_outputs_detail;

JournalOptions design_journal_options(const DesignStudy& study) {
  const bool aggregate = study.aggregate();
  JournalOptions options;
  std::string header = "index,generation";
  const std::vector<int> free = free_parameter_indices(study);
  for (int i : free) header += "," + study.parameters[static_cast<std::size_t>(i)].name;
  for (const DesignObjective& o : study.objectives())
    header += fmt::format(",{}", design_metric_name(o.metric));
  if (aggregate)
    for (const std::string& name : constraint_names(study)) header += "," + name;
  else
    header += ",g_max";
  header += ",feasible,failure";
  options.csv_header = header;
  const DesignStudy* s = &study;
  if (aggregate)
    options.evaluate = [s](const std::vector<double>& x) {
      const MeasuredDesign d = measure_design(*s, x, false);
      JournalEntry entry;
      entry.fitness = d.aggregate;
      entry.note = d.failure;
      return entry;
    };
  options.csv_row = [s, free, aggregate](std::size_t index, const JournalEntry& e) {
    const std::vector<DesignObjective>& objectives = s->objectives();
    std::string row = std::to_string(index) + ',' +
                      (e.generation >= 0 ? std::to_string(e.generation) : std::string());
    const std::vector<double> parameters = file_parameters(*s, e.x);
    for (int i : free) row += "," + format_number(parameters[static_cast<std::size_t>(i)]);
    const bool failed = !e.note.empty();
    bool feasible = !failed;
    for (std::size_t k = 0; k < objectives.size(); ++k) {
      const double f = e.fitness[k];
      feasible = feasible && std::isfinite(f);
      row += failed || !std::isfinite(f) ? ","
                                         : "," + format_number(sense_sign(objectives[k].sense) * f);
    }
    double g_max = -std::numeric_limits<double>::infinity();
    for (std::size_t r = objectives.size(); r < e.fitness.size(); ++r) {
      const double g = e.fitness[r];
      feasible = feasible && g <= 0.0;
      g_max = std::max(g_max, g);
      if (aggregate) row += failed || !std::isfinite(g) ? "," : "," + format_number(g);
    }
    if (!aggregate)
      row += e.fitness.size() == objectives.size() || !std::isfinite(g_max)
                 ? ","
                 : "," + format_number(g_max);
    row += feasible ? ",1," : ",0,";
    row += csv_field(e.note);
    return row;
  };
  return options;
}

namespace design_outputs_detail {

nlohmann::json json_number(double value) {
  return std::isfinite(value) ? nlohmann::json(value) : nlohmann::json(nullptr);
}

}  // namespace design_outputs_detail

namespace design_outputs_detail {

// True when a fitness vector [objectives | constraint rows] is feasible as evaluations.csv says:
// finite objectives and every row <= 0 (a NaN row is not).
bool feasible_fitness(const std::vector<double>& fitness, std::size_t m) {
  for (std::size_t k = 0; k < fitness.size(); ++k)
    if (k < m ? !std::isfinite(fitness[k]) : !(fitness[k] <= 0.0)) return false;
  return true;
}

// Measures designs in parallel (the result's order is the input's whatever the threads).
std::vector<MeasuredDesign> measure_designs(const DesignStudy& study,
                                            const std::vector<std::vector<double>>& xs,
                                            bool machine_files, int threads) {
  std::vector<MeasuredDesign> measured(xs.size());
  const long long count = static_cast<long long>(xs.size());
#pragma omp parallel for num_threads(resolve_thread_count(threads)) schedule(dynamic)
  for (long long k = 0; k < count; ++k)
    measured[static_cast<std::size_t>(k)] =
        measure_design(study, xs[static_cast<std::size_t>(k)], machine_files);
  return measured;
}

// The front is the non-dominated set of every feasible design the run evaluated (the journal's
// archive, whichever algorithm ran), thinned to output.front_size when that is set
// (optimizer/front_thinning.hpp). A single-objective run keeps its solver's answer.
FrontSelection select_design_front(const DesignStudy& study, const RunOutcome& outcome,
                                   const DesignRunFacts& facts) {
  const std::size_t m = study.objectives().size();
  std::vector<std::vector<double>> xs;
  std::vector<std::vector<double>> fitness;
  if (facts.journal && m >= 2) {
    for (const JournalEntry& e : facts.journal->entries())
      if (e.note.empty() && feasible_fitness(e.fitness, m)) {
        xs.push_back(e.x);
        fitness.push_back(e.fitness);
      }
  } else {
    xs = outcome.front.x;
    fitness = outcome.front.fitness;
  }
  if (!study.aggregate() && m >= 2) {
    // The smooth formulation journals epigraph bounds: measure the candidates' aggregate metrics.
    const std::vector<MeasuredDesign> measured = measure_designs(study, xs, false, facts.threads);
    xs.clear();
    fitness.clear();
    for (const MeasuredDesign& d : measured)
      if (d.ok() && feasible_fitness(d.aggregate, m)) {
        xs.push_back(d.x);
        fitness.push_back(d.aggregate);
      }
  }
  FrontSelection selection;
  selection.feasible_evaluations = xs.size();
  ObjectiveSet candidates;
  for (const std::vector<double>& f : fitness)
    candidates.emplace_back(f.begin(), f.begin() + static_cast<std::ptrdiff_t>(m));
  std::vector<std::vector<double>> chosen;
  for (std::size_t k :
       select_front(candidates, m >= 2 ? study.front_size : 0, &selection.archive_size))
    chosen.push_back(xs[k]);
  selection.designs = measure_designs(study, chosen, study.write_designs, facts.threads);
  // A failed design never enters the front (a single-objective solver's answer may fail).
  std::erase_if(selection.designs, [](const MeasuredDesign& d) { return !d.ok(); });
  return selection;
}

}  // namespace design_outputs_detail
}  // namespace pkmopt
