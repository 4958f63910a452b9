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

#include "io/actuator_catalog_file.hpp"
#include "io/csv.hpp"
#include "io/input_error.hpp"
#include "io/machine_file.hpp"
#include "io/machine_file_lathe.hpp"
#include "io/machine_file_leg_chain.hpp"
#include "io/machine_file_writer.hpp"
#include "io/output_file.hpp"
#include "io/task_wrench_file.hpp"
#include "optimizer/front_thinning.hpp"
#include "optimizer/indicators.hpp"
#include "pkmopt/version.hpp"
#include "problems/lathe_design.hpp"
#include "studies/design_study.hpp"

namespace pkmopt {

std::string_view design_metric_unit(DesignMetric metric) {
  switch (metric) {
    case DesignMetric::stiffness_min:
    case DesignMetric::stiffness_min_loaded:
      return "N/m";
    case DesignMetric::tcp_deflection_max:
    case DesignMetric::leg_clearance_min:
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
      return "";
  }
  return "";
}

namespace {

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
  return study.problem ? study.problem->free_parameters()
                       : study.machine_problem->free_parameters();
}

// Every parameter of a variable vector in file units (study.parameters order).
std::vector<double> file_parameters(const DesignStudy& study, const std::vector<double>& x) {
  std::vector<double> values;
  if (study.problem) {
    const std::array<double, kNumDesignParameters> p = study.problem->parameters_of(x);
    for (int i = 0; i < kNumDesignParameters; ++i)
      values.push_back(design_parameter_in_degrees(i) ? rad_to_deg(p[i]) : p[i]);
  } else {
    const std::vector<double> p = study.machine_problem->parameters_of(x);
    const DesignFamily& family = study.machine_problem->family();
    for (std::size_t i = 0; i < p.size(); ++i) values.push_back(family.parameters[i].to_file(p[i]));
  }
  return values;
}

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

MeasuredDesign measure_design(const DesignStudy& study, const std::vector<double>& x,
                              bool machine_file) {
  MeasuredDesign d;
  d.x = x;
  d.parameters = file_parameters(study, x);
  if (study.problem) {
    const DesignEvaluation ev = study.problem->evaluate(x);
    d.home_height = ev.parameters[kHomeHeight];
    d.metrics = ev.metrics;
    d.aggregate = study.problem->aggregate_fitness(ev);
    d.failure = ev.failure;
    d.actuator = ev.actuator;
    if (machine_file && ev.ok())
      d.machine_file = hexapod_design_to_yaml(study.problem->design_of(ev.parameters));
  } else {
    const MachineDesignProblem& problem = *study.machine_problem;
    const MachineDesignEvaluation ev = problem.evaluate(x);
    d.home_height = problem.home_height_of(ev.parameters);
    d.metrics = ev.metrics;
    d.aggregate = problem.aggregate_fitness(ev);
    d.failure = ev.failure;
    if (machine_file && ev.ok())
      d.machine_file = family_machine_file(problem.family().design(ev.parameters));
  }
  return d;
}

}  // namespace

JournalOptions design_journal_options(const DesignStudy& study) {
  const bool aggregate = study.aggregate();
  JournalOptions options;
  std::string header = "index";
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
    std::string row = std::to_string(index);
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

namespace {

nlohmann::json json_number(double value) {
  return std::isfinite(value) ? nlohmann::json(value) : nlohmann::json(nullptr);
}

}  // namespace

namespace {

// True when a fitness vector [objectives | constraint rows] is feasible as evaluations.csv says:
// finite objectives and every row <= 0 (a NaN row is not).
bool feasible_fitness(const std::vector<double>& fitness, std::size_t m) {
  for (std::size_t k = 0; k < fitness.size(); ++k)
    if (k < m ? !std::isfinite(fitness[k]) : !(fitness[k] <= 0.0)) return false;
  return true;
}

// The designs of the front (measured again with the aggregate metrics, machine files when the
// study writes them) and the archive they were chosen from.
struct FrontSelection {
  std::vector<MeasuredDesign> designs;
  std::size_t feasible_evaluations = 0;  // distinct feasible designs (aggregate metrics)
  std::size_t archive_size = 0;          // of them non-dominated
};

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
  selection.archive_size = select_front(candidates, 0).size();
  std::vector<std::vector<double>> chosen;
  for (std::size_t k : select_front(candidates, m >= 2 ? study.front_size : 0))
    chosen.push_back(xs[k]);
  selection.designs = measure_designs(study, chosen, study.write_designs, facts.threads);
  // A failed design never enters the front (a single-objective solver's answer may fail).
  std::erase_if(selection.designs, [](const MeasuredDesign& d) { return !d.ok(); });
  return selection;
}

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
                                  const std::vector<JournalEntry>& entries) {
  const std::size_t m = study.objectives().size();
  const std::vector<std::string> names =
      study.aggregate() ? constraint_names(study) : std::vector<std::string>{"g_max"};
  std::map<std::string, std::size_t> failures;
  std::vector<std::size_t> violated(names.size(), 0);
  Infeasibility result;
  result.evaluations = entries.size();
  for (const JournalEntry& e : entries) {
    if (!e.note.empty()) {
      ++failures[e.note];
      continue;
    }
    if (feasible_fitness(e.fitness, m)) ++result.feasible;
    for (std::size_t r = m; r < e.fitness.size(); ++r)
      if (!(e.fitness[r] <= 0.0)) {
        if (study.aggregate()) {
          ++violated[r - m];
        } else {
          ++violated[0];
          break;
        }
      }
  }
  auto by_count = [](const auto& a, const auto& b) {
    return a.second != b.second ? a.second > b.second : a.first < b.first;
  };
  result.failures.assign(failures.begin(), failures.end());
  std::sort(result.failures.begin(), result.failures.end(), by_count);
  for (std::size_t r = 0; r < names.size(); ++r)
    if (violated[r] > 0) result.violated.emplace_back(names[r], violated[r]);
  std::sort(result.violated.begin(), result.violated.end(), by_count);
  return result;
}

}  // namespace

DesignOutputSummary write_design_outputs(const std::string& directory, const DesignStudy& study,
                                         const RunOutcome& outcome, const DesignRunFacts& facts) {
  namespace fs = std::filesystem;
  const std::vector<DesignObjective>& objectives_spec = study.objectives();
  const std::vector<DesignConstraint>& constraints_spec = study.constraints();
  const std::size_t m = objectives_spec.size();
  const std::vector<int> free = free_parameter_indices(study);
  const int home_index = [&] {
    for (std::size_t i = 0; i < study.parameters.size(); ++i)
      if (study.parameters[i].name == "home_height") return static_cast<int>(i);
    return -1;
  }();
  const bool home_free =
      home_index >= 0 && study.parameters[static_cast<std::size_t>(home_index)].free();

  const FrontSelection selection = select_design_front(study, outcome, facts);
  const std::vector<MeasuredDesign>& front = selection.designs;
  ObjectiveSet objectives;  // internal (minimised) sign
  for (const MeasuredDesign& d : front)
    objectives.emplace_back(d.aggregate.begin(),
                            d.aggregate.begin() + static_cast<std::ptrdiff_t>(m));
  const std::vector<std::string> g_names = constraint_names(study);
  auto id_of = [](std::size_t k) { return fmt::format("d{:04}", k); };
  // The catalog the optimiser chose actuators from ({actuator: cheapest, catalog: FILE}).
  const ActuatorCatalog* catalog = study.problem && study.problem->spec().actuator_catalog
                                       ? &*study.problem->spec().actuator_catalog
                                       : nullptr;

  // pareto.csv
  std::ostringstream csv;
  csv << "id";
  for (int i : free) csv << ',' << study.parameters[static_cast<std::size_t>(i)].name;
  if (!home_free) csv << ",home_height";
  for (const DesignObjective& o : objectives_spec) csv << ',' << design_metric_name(o.metric);
  for (const std::string& g : g_names) csv << ',' << g;
  if (catalog) csv << ",actuator";
  csv << ",feasible,failure\n";
  if (study.write_designs) fs::create_directories(fs::path(directory) / "designs");
  nlohmann::json designs = nlohmann::json::array();
  for (std::size_t k = 0; k < front.size(); ++k) {
    const MeasuredDesign& d = front[k];
    const std::string id = id_of(k);
    nlohmann::json design;
    design["id"] = id;
    csv << id;
    nlohmann::json parameters = nlohmann::json::object();
    for (int i : free) {
      const double value = d.parameters[static_cast<std::size_t>(i)];
      csv << ',' << format_number(value);
      parameters[study.parameters[static_cast<std::size_t>(i)].name] = json_number(value);
    }
    if (!home_free) csv << ',' << format_number(d.home_height);
    design["parameters"] = parameters;
    design["home_height"] = json_number(d.home_height);
    nlohmann::json objective_values = nlohmann::json::object();
    for (const DesignObjective& o : objectives_spec) {
      const double value = d.metrics[static_cast<int>(o.metric)];
      csv << ',' << format_number(value);
      objective_values[std::string(design_metric_name(o.metric))] = json_number(value);
    }
    design["objectives"] = objective_values;
    nlohmann::json constraint_values = nlohmann::json::object();
    bool feasible = true;
    for (std::size_t r = 0; r < g_names.size(); ++r) {
      const double g = d.aggregate[m + r];
      csv << ',' << format_number(g);
      constraint_values[g_names[r]] = json_number(g);
      feasible = feasible && g <= 0.0;
    }
    design["constraints"] = constraint_values;
    if (catalog) {
      if (d.actuator >= 0) {
        const ActuatorEntry& e = catalog->entries[static_cast<std::size_t>(d.actuator)];
        const double force = d.metrics[static_cast<int>(DesignMetric::leg_force_max)];
        double reserve = e.max_force / force;
        csv << ',' << csv_field(e.name);
        design["actuator"] = {{"name", e.name},
                              {"type", e.type},
                              {"max_force", e.max_force},
                              {"stroke", e.stroke},
                              {"max_speed", e.max_speed},
                              {"cost", d.metrics[static_cast<int>(DesignMetric::actuator_cost)]},
                              {"leg_force_max", json_number(force)}};
        if (study.problem && study.problem->spec().task.acceleration_max > 0.0) {
          // Sized for the rapid moves too: the accelerated force against the peak rating.
          const double peak = e.peak_force.value_or(e.max_force);
          const double dynamic =
              d.metrics[static_cast<int>(DesignMetric::actuator_force_dynamic_max)];
          design["actuator"]["peak_force"] = peak;
          design["actuator"]["actuator_force_dynamic_max"] = json_number(dynamic);
          reserve = std::min(reserve, peak / dynamic);
        }
        design["actuator"]["force_reserve"] = json_number(reserve);
      } else {
        csv << ",";
        design["actuator"] = nullptr;
      }
    }
    design["feasible"] = feasible;
    csv << ',' << (feasible ? 1 : 0) << ",\"\"\n";
    if (study.write_designs) {
      write_file_atomically(directory + "/designs/" + id + ".yaml", d.machine_file);
      design["machine_file"] = "designs/" + id + ".yaml";
    }
    designs.push_back(design);
  }

  // pareto.json (pkmopt-pareto-1, docs/design-studies.md)
  nlohmann::json pareto;
  pareto["format"] = "pkmopt-pareto-1";
  pareto["pkmopt_version"] = kVersion;
  pareto["study"] = study.name;
  pareto["description"] = study.description;
  pareto["model"] = study.model;
  nlohmann::json parameter_list = nlohmann::json::array();
  nlohmann::json fixed = nlohmann::json::object();
  for (const StudyParameter& p : study.parameters) {
    if (!p.free())
      fixed[p.name] = p.min;
    else
      parameter_list.push_back(
          {{"name", p.name}, {"unit", p.unit}, {"min", p.min}, {"max", p.max}});
  }
  pareto["parameters"] = parameter_list;
  pareto["fixed_parameters"] = fixed;
  nlohmann::json objective_list = nlohmann::json::array();
  for (const DesignObjective& o : objectives_spec)
    objective_list.push_back({{"name", design_metric_name(o.metric)},
                              {"sense", o.sense == Sense::maximize ? "maximize" : "minimize"},
                              {"unit", design_metric_unit(o.metric)}});
  pareto["objectives"] = objective_list;
  nlohmann::json constraint_list = nlohmann::json::array();
  for (std::size_t r = 0; r < constraints_spec.size(); ++r) {
    const DesignConstraint& c = constraints_spec[r];
    constraint_list.push_back({{"name", g_names[r]},
                               {"metric", design_metric_name(c.metric)},
                               {"kind", c.relation == Relation::less_equal ? "max" : "min"},
                               {"bound", c.bound},
                               {"unit", design_metric_unit(c.metric)}});
  }
  if (study.require_reachable())
    constraint_list.push_back({{"name", "g_task_reachable"},
                               {"metric", "task_reachable"},
                               {"kind", "reachable"},
                               {"bound", 0},
                               {"unit", ""}});
  pareto["constraints"] = constraint_list;
  if (catalog) {
    pareto["actuator_catalog"] = {
        {"name", catalog->name},
        {"entries", catalog->entries.size()},
        {"cost", catalog->entries.front().cost ? "catalog cost" : "rank by force rating"}};
  }
  const Wrench& wrench = study.task().wrench;
  pareto["task"] = {{"centre", study.task_centre},
                    {"wrench", std::vector<double>(wrench.data(), wrench.data() + 6)},
                    {"tilt_deg", study.task_tilt_deg},
                    {"yaw_deg", study.task_yaw_deg}};
  pareto["designs"] = designs;
  nlohmann::json knee = nullptr;
  if (!objectives.empty()) knee = id_of(knee_point(objectives));
  pareto["knee"] = knee;

  // summary.json: hypervolume in user sign and units.
  nlohmann::json summary;
  summary["study"] = study.name;
  summary["description"] = study.description;
  summary["model"] = study.model;
  summary["version"] = kVersion;
  summary["algorithm"] = study.optimizer.name();
  summary["formulation"] = study.aggregate() ? "aggregate" : "smooth";
  summary["status"] = front.empty() ? std::string("no_feasible_design") : outcome.status;
  summary["message"] = outcome.front.message;
  summary["seed"] = study.optimizer.seed;
  summary["threads"] = resolve_thread_count(facts.threads);
  summary["resumed"] = facts.resumed;
  summary["evaluations"] = outcome.front.fitness_evaluations;
  summary["gradient_evaluations"] = outcome.front.gradient_evaluations;
  if (facts.journal) {
    const JournaledProblem& j = *facts.journal;
    summary["evaluations_from_cache"] = j.cache_hits();
    summary["evaluations_distinct"] = j.entries().size();
    summary["evaluations_loaded_from_journal"] = j.loaded_entries();
    summary["evaluations_new"] = j.entries().size() - j.loaded_entries();
    summary["evaluations_failed"] = j.failed();
  }
  summary["subproblems"] = outcome.front.subproblems;
  summary["failed_subproblems"] = outcome.front.failed_subproblems;
  summary["dominated_subproblems"] = outcome.front.dominated_subproblems;
  if (outcome.single) {
    summary["solver_status"] = outcome.status;
    summary["iterations"] = outcome.single->iterations;
  }
  summary["points"] = front.size();
  summary["feasible_evaluations"] = selection.feasible_evaluations;
  summary["archive_size"] = selection.archive_size;
  summary["front_rule"] = front_rule_text(study.front_size, m);
  summary["objectives"] = objective_list;
  if (!objectives.empty() && m >= 2) {
    const std::vector<double> reference = reference_point_from(objectives);
    std::vector<double> user_reference(m);
    for (std::size_t i = 0; i < m; ++i)
      user_reference[i] = sense_sign(objectives_spec[i].sense) * reference[i];
    summary["reference_point"] = user_reference;
    summary["reference_point_rule"] =
        "front's worst value of each objective moved 10% of the front's range (1 when the "
        "range is 0) further away from the front";
    summary["hypervolume"] = json_number(hypervolume(objectives, reference));
  } else {
    summary["reference_point"] = nullptr;
    summary["hypervolume"] = nullptr;
    summary["hypervolume_missing"] =
        m < 2 ? "a single objective has no hypervolume" : "no feasible design: the front is empty";
  }
  summary["knee"] = knee;
  DesignOutputSummary result;
  result.designs = front.size();
  result.status = summary["status"].get<std::string>();
  if (facts.journal) {
    const Infeasibility infeasibility = count_infeasibility(study, facts.journal->entries());
    summary["infeasibility"] = infeasibility.json();
    if (front.empty()) result.infeasibility = infeasibility.text();
  }
  summary["time_seconds"] = outcome.front.seconds;
  summary["wall_seconds"] = facts.wall_seconds;

  write_file_atomically(directory + "/pareto.csv", csv.str());
  write_file_atomically(directory + "/pareto.json", pareto.dump(2) + "\n");
  write_file_atomically(directory + "/summary.json", summary.dump(2) + "\n");
  return result;
}

}  // namespace pkmopt
