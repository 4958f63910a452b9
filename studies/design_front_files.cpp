// pareto.csv, pareto.json and summary.json of a design study (write_design_outputs,
// studies/design_study.hpp); the front itself is chosen in studies/design_outputs.cpp.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>

#include "io/design/actuator_catalog_file.hpp"
#include "io/format/csv.hpp"
#include "io/format/input_error.hpp"
#include "io/format/output_file.hpp"
#include "optimizer/archive.hpp"
#include "optimizer/decision.hpp"
#include "optimizer/indicators.hpp"
#include "pkmopt/version.hpp"
#include "studies/design_outputs_detail.hpp"

namespace pkmopt {

using namespace design_outputs_detail;

Infeasibility design_outputs_detail::count_infeasibility(const DesignStudy& study,
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

namespace {

// What the writers of one front share.
struct FrontFiles {
  const DesignStudy& study;
  const std::vector<MeasuredDesign>& front;
  std::size_t m = 0;                         // objectives
  std::vector<int> free = {};                // free parameters (indices into study.parameters)
  bool home_free = false;                    // home_height is a free parameter
  std::vector<std::string> g_names = {};     // constraint columns
  const ActuatorCatalog* catalog = nullptr;  // {actuator: cheapest, catalog: FILE}, or null
  ObjectiveSet objectives = {};              // the front's objective vectors, internal sign
};

std::string design_id(std::size_t k) { return fmt::format("d{:04}", k); }

// The chosen catalog actuator of a design (pareto.json) and its name (pareto.csv).
nlohmann::json actuator_json(const FrontFiles& f, const MeasuredDesign& d) {
  if (d.actuator < 0) return nullptr;
  const ActuatorEntry& e = f.catalog->entries[static_cast<std::size_t>(d.actuator)];
  const double force = d.metrics[static_cast<int>(DesignMetric::leg_force_max)];
  double reserve = e.max_force / force;
  nlohmann::json a = {{"name", e.name},
                      {"type", e.type},
                      {"max_force", e.max_force},
                      {"stroke", e.stroke},
                      {"max_speed", e.max_speed},
                      {"cost", d.metrics[static_cast<int>(DesignMetric::actuator_cost)]},
                      {"leg_force_max", json_number(force)}};
  if (f.study.task().acceleration_max > 0.0) {
    // Sized for the rapid moves too: the accelerated force against the peak rating.
    const double peak = e.peak_force.value_or(e.max_force);
    const double dynamic = d.metrics[static_cast<int>(DesignMetric::actuator_force_dynamic_max)];
    a["peak_force"] = peak;
    a["actuator_force_dynamic_max"] = json_number(dynamic);
    reserve = std::min(reserve, peak / dynamic);
  }
  a["force_reserve"] = json_number(reserve);
  return a;
}

// One design: its pareto.csv row (with the newline) and its pareto.json object.
std::pair<std::string, nlohmann::json> design_row(const FrontFiles& f, std::size_t k) {
  const MeasuredDesign& d = f.front[k];
  const std::string id = design_id(k);
  nlohmann::json design;
  design["id"] = id;
  std::string csv = id;
  nlohmann::json parameters = nlohmann::json::object();
  for (int i : f.free) {
    const double value = d.parameters[static_cast<std::size_t>(i)];
    csv += ',' + format_number(value);
    parameters[f.study.parameters[static_cast<std::size_t>(i)].name] = json_number(value);
  }
  if (!f.home_free) csv += ',' + format_number(d.home_height);
  design["parameters"] = parameters;
  design["home_height"] = json_number(d.home_height);
  nlohmann::json objective_values = nlohmann::json::object();
  for (const DesignObjective& o : f.study.objectives()) {
    const double value = d.metrics[static_cast<int>(o.metric)];
    csv += ',' + format_number(value);
    objective_values[std::string(design_metric_name(o.metric))] = json_number(value);
  }
  design["objectives"] = objective_values;
  nlohmann::json constraint_values = nlohmann::json::object();
  bool feasible = true;
  for (std::size_t r = 0; r < f.g_names.size(); ++r) {
    const double g = d.aggregate[f.m + r];
    csv += ',' + format_number(g);
    constraint_values[f.g_names[r]] = json_number(g);
    feasible = feasible && g <= 0.0;
  }
  design["constraints"] = constraint_values;
  if (f.catalog) {
    design["actuator"] = actuator_json(f, d);
    csv += ',' + (design["actuator"].is_null()
                      ? std::string()
                      : csv_field(design["actuator"]["name"].get<std::string>()));
  }
  if (f.study.problem->prices_each_drive()) {
    design["drives"] = d.drives;
    csv += ',' + csv_field(d.drives);
  }
  design["feasible"] = feasible;
  csv += feasible ? ",1,\"\"\n" : ",0,\"\"\n";
  if (f.study.write_designs) design["machine_file"] = "designs/" + id + ".yaml";
  return {csv, design};
}

std::string pareto_csv_header(const FrontFiles& f) {
  std::string csv = "id";
  for (int i : f.free) csv += ',' + f.study.parameters[static_cast<std::size_t>(i)].name;
  if (!f.home_free) csv += ",home_height";
  for (const DesignObjective& o : f.study.objectives())
    csv += ',' + std::string(design_metric_name(o.metric));
  for (const std::string& g : f.g_names) csv += ',' + g;
  if (f.catalog) csv += ",actuator";
  if (f.study.problem->prices_each_drive()) csv += ",drives";
  return csv + ",feasible,failure\n";
}

// The hypervolume (up to `reference`, internal sign) of the non-dominated feasible designs
// found after the first n evaluations, at about 40 values of n (pareto.json "convergence").
nlohmann::json convergence_json(const DesignStudy& study, const JournaledProblem& journal,
                                const std::vector<double>& reference) {
  const std::size_t m = study.objectives().size();
  const std::vector<JournalEntry>& entries = journal.entries();
  const std::size_t step = std::max<std::size_t>(1, (entries.size() + 39) / 40);
  ParetoArchive archive;
  std::vector<double> evaluations, volumes;
  for (std::size_t k = 0; k < entries.size(); ++k) {
    const JournalEntry& e = entries[k];
    if (e.note.empty() && feasible_fitness(e.fitness, m))
      archive.insert({}, std::vector<double>(e.fitness.begin(),
                                             e.fitness.begin() + static_cast<std::ptrdiff_t>(m)));
    if ((k + 1) % step == 0 || k + 1 == entries.size()) {
      evaluations.push_back(static_cast<double>(k + 1));
      volumes.push_back(archive.empty() ? 0.0
                                        : hypervolume(archive.objective_vectors(), reference));
    }
  }
  return {{"evaluations", evaluations}, {"hypervolume", volumes}};
}

nlohmann::json parameter_list_json(const DesignStudy& study, nlohmann::json& fixed) {
  nlohmann::json list = nlohmann::json::array();
  fixed = nlohmann::json::object();
  for (const StudyParameter& p : study.parameters) {
    if (!p.free())
      fixed[p.name] = p.min;
    else
      list.push_back({{"name", p.name}, {"unit", p.unit}, {"min", p.min}, {"max", p.max}});
  }
  return list;
}

nlohmann::json objective_list_json(const DesignStudy& study) {
  nlohmann::json list = nlohmann::json::array();
  for (const DesignObjective& o : study.objectives())
    list.push_back({{"name", design_metric_name(o.metric)},
                    {"sense", o.sense == Sense::maximize ? "maximize" : "minimize"},
                    {"unit", design_metric_unit(o.metric)}});
  return list;
}

nlohmann::json constraint_list_json(const FrontFiles& f) {
  nlohmann::json list = nlohmann::json::array();
  const std::vector<DesignConstraint>& spec = f.study.constraints();
  for (std::size_t r = 0; r < spec.size(); ++r) {
    const DesignConstraint& c = spec[r];
    list.push_back({{"name", f.g_names[r]},
                    {"metric", design_metric_name(c.metric)},
                    {"kind", c.relation == Relation::less_equal ? "max" : "min"},
                    {"bound", c.bound},
                    {"unit", design_metric_unit(c.metric)}});
  }
  if (f.study.require_reachable())
    list.push_back({{"name", "g_task_reachable"},
                    {"metric", "task_reachable"},
                    {"kind", "reachable"},
                    {"bound", 0},
                    {"unit", ""}});
  return list;
}

nlohmann::json task_json(const DesignStudy& study) {
  const Wrench& wrench = study.task().wrench;
  nlohmann::json task = {{"centre", study.task_centre},
                         {"wrench", std::vector<double>(wrench.data(), wrench.data() + 6)},
                         {"tilt_deg", study.task_tilt_deg},
                         {"yaw_deg", study.task_yaw_deg}};
  const std::vector<Pose>& poses = study.task().poses;
  if (!poses.empty()) {
    Eigen::Vector3d lo = poses.front().position, hi = lo;
    for (const Pose& p : poses) {
      lo = lo.cwiseMin(p.position);
      hi = hi.cwiseMax(p.position);
    }
    task["positions_min"] = {lo.x(), lo.y(), lo.z()};
    task["positions_max"] = {hi.x(), hi.y(), hi.z()};
  }
  return task;
}

// summary.json: the run's facts, the hypervolume in user sign and units, the infeasibility.
DesignOutputSummary make_summary(std::string& text, const DesignStudy& study,
                                 const RunOutcome& outcome, const DesignRunFacts& facts,
                                 const FrontSelection& selection, const ObjectiveSet& objectives,
                                 const std::vector<double>& reference, const nlohmann::json& knee) {
  const std::size_t m = study.objectives().size();
  const std::vector<MeasuredDesign>& front = selection.designs;
  const std::vector<DesignObjective>& objectives_spec = study.objectives();
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
  summary["mpi_ranks"] = facts.mpi_ranks;
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
  summary["objectives"] = objective_list_json(study);
  if (!reference.empty()) {
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

  text = summary.dump(2) + "\n";
  return result;
}

}  // namespace

namespace design_outputs_detail {

DesignFiles design_output_files(const std::string& directory, const DesignStudy& study,
                                const RunOutcome& outcome, const DesignRunFacts& facts) {
  DesignFiles out;
  out.selection = select_design_front(study, outcome, facts);
  const FrontSelection& selection = out.selection;
  FrontFiles f{.study = study, .front = selection.designs};
  f.m = study.objectives().size();
  f.free = free_parameter_indices(study);
  for (const StudyParameter& p : study.parameters)
    if (p.name == "home_height") f.home_free = p.free();
  f.g_names = constraint_names(study);
  // A catalog pricing every drive gives each design its drive_cost, not one entry.
  if (!study.problem->prices_each_drive()) f.catalog = study.problem->actuator_catalog();
  for (const MeasuredDesign& d : f.front)
    f.objectives.emplace_back(d.aggregate.begin(),
                              d.aggregate.begin() + static_cast<std::ptrdiff_t>(f.m));

  std::string csv = pareto_csv_header(f);
  nlohmann::json designs = nlohmann::json::array();
  OutputFiles& files = out.files;
  if (study.write_designs) std::filesystem::create_directories(directory + "/designs");
  for (std::size_t k = 0; k < f.front.size(); ++k) {
    auto [row, design] = design_row(f, k);
    csv += row;
    designs.push_back(std::move(design));
    if (study.write_designs)
      files.emplace_back(directory + "/designs/" + design_id(k) + ".yaml", f.front[k].machine_file);
  }
  nlohmann::json knee = nullptr, compromise = nullptr;
  nlohmann::json high_trade_off = nlohmann::json::array();
  if (!f.objectives.empty()) {
    knee = design_id(knee_point(f.objectives));
    compromise = design_id(compromise_point(f.objectives));
    for (std::size_t k : high_trade_off_points(f.objectives).points)
      high_trade_off.push_back(design_id(k));
  }
  std::vector<double> reference;  // the hypervolume's, internal sign
  if (!f.objectives.empty() && f.m >= 2) reference = reference_point_from(f.objectives);

  // pareto.json (pkmopt-pareto-1, docs/design-studies.md)
  nlohmann::json pareto;
  pareto["format"] = "pkmopt-pareto-1";
  pareto["pkmopt_version"] = kVersion;
  pareto["study"] = study.name;
  pareto["description"] = study.description;
  pareto["model"] = study.model;
  nlohmann::json fixed;
  pareto["parameters"] = parameter_list_json(study, fixed);
  pareto["fixed_parameters"] = fixed;
  pareto["objectives"] = objective_list_json(study);
  pareto["constraints"] = constraint_list_json(f);
  if (f.catalog)
    pareto["actuator_catalog"] = {
        {"name", f.catalog->name},
        {"entries", f.catalog->entries.size()},
        {"cost", f.catalog->entries.front().cost ? "catalog cost" : "rank by force rating"}};
  if (const ActuatorCatalog* catalog = study.problem->actuator_catalog();
      catalog != nullptr && study.problem->prices_each_drive())
    pareto["drive_catalog"] = {{"name", catalog->name},
                               {"entries", catalog->entries.size()},
                               {"rotary_entries", catalog->rotary_entries.size()},
                               {"cost", "every drive: catalog cost, alike drives one entry"}};
  pareto["task"] = task_json(study);
  pareto["designs"] = designs;
  pareto["knee"] = knee;
  pareto["compromise"] = compromise;
  pareto["high_trade_off"] = high_trade_off;
  if (facts.journal && f.m >= 2) {
    pareto["front_selection"] = {{"rule", front_rule_text(study.front_size, f.m)},
                                 {"evaluations", facts.journal->entries().size()},
                                 {"feasible_evaluations", selection.feasible_evaluations},
                                 {"archive_size", selection.archive_size}};
    if (!reference.empty() && study.aggregate())
      pareto["convergence"] = convergence_json(study, *facts.journal, reference);
  }

  std::string summary;
  out.summary =
      make_summary(summary, study, outcome, facts, selection, f.objectives, reference, knee);
  files.emplace_back(directory + "/pareto.csv", std::move(csv));
  files.emplace_back(directory + "/pareto.json", pareto.dump(2) + "\n");
  files.emplace_back(directory + "/summary.json", std::move(summary));
  return out;
}

}  // namespace design_outputs_detail

DesignOutputSummary write_design_outputs(const std::string& directory, const DesignStudy& study,
                                         const RunOutcome& outcome, const DesignRunFacts& facts,
                                         const OutputFiles& also) {
  design_outputs_detail::DesignFiles out =
      design_outputs_detail::design_output_files(directory, study, outcome, facts);
  OutputFiles files = also;
  files.insert(files.end(), out.files.begin(), out.files.end());
  write_files_together(files);
  return out.summary;
}

}  // namespace pkmopt
