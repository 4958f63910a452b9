#include "studies/synthesis_outputs.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <nlohmann/json.hpp>
#include <sstream>

#include "io/format/csv.hpp"
#include "optimizer/decision.hpp"
#include "optimizer/front_thinning.hpp"
#include "optimizer/indicators.hpp"
#include "pkmopt/version.hpp"
#include "studies/design_outputs_detail.hpp"

namespace pkmopt {

using namespace design_outputs_detail;

namespace {

// A constraint is binding on a structure's front when some design lies within this share of
// its bound.
constexpr double kBindingShare = 0.01;

std::string merged_id(std::size_t k) { return fmt::format("m{:04}", k); }
std::string structure_id(std::size_t k) { return fmt::format("d{:04}", k); }

// The resolved study of a structure with the generations it ran.
void set_generations(DesignStudy& study, std::size_t generations) {
  auto* spec = std::get_if<Nsga2Spec>(&study.optimizer.algorithm);
  if (spec == nullptr) return;
  spec->options.generations = generations;
  const std::size_t a = study.resolved_yaml.find("\noptimizer: ");
  if (a == std::string::npos) return;
  const std::size_t b = study.resolved_yaml.find('\n', a + 1);
  study.resolved_yaml.replace(a + 1, b - a - 1,
                              "optimizer: " + optimizer_section_yaml(study.optimizer));
}

// One searched structure's results.
struct Part {
  const SynthesisCandidate* candidate = nullptr;
  const StructureRun* run = nullptr;
  const JournaledProblem* journal = nullptr;
  DesignFiles files;
  Infeasibility infeasibility;
  std::size_t merged = 0;  // its designs on the merged front
};

// A constraint row in words: "singularity_margin ≥ 0.02", "task reachable".
std::vector<std::string> constraint_words(const DesignStudy& study) {
  std::vector<std::string> words;
  for (const DesignConstraint& c : study.constraints()) {
    const std::string_view unit = design_metric_unit(c.metric);
    words.push_back(fmt::format(
        "{} {} {}{}", design_metric_name(c.metric), c.relation == Relation::less_equal ? "≤" : "≥",
        format_number(c.bound), unit.empty() ? "" : " " + std::string(unit)));
  }
  if (study.require_reachable()) words.emplace_back("task reachable");
  return words;
}

// Why a structure's designs failed: failures by reason and violated constraints, with their
// share of its evaluations, most frequent first.
nlohmann::json failure_json(const Part& part, std::string& text) {
  const DesignStudy& study = *part.candidate->study;
  const std::vector<std::string> names = constraint_names(study);
  const std::vector<std::string> words = constraint_words(study);
  const Infeasibility& inf = part.infeasibility;
  const double n = std::max<double>(1.0, static_cast<double>(inf.evaluations));
  std::vector<std::pair<std::string, std::size_t>> reasons;
  for (const auto& [name, count] : inf.violated) {
    std::string what = name;
    for (std::size_t i = 0; i < names.size(); ++i)
      if (names[i] == name)
        what = i < study.constraints().size() ? "not " + words[i] : "task not reachable";
    reasons.emplace_back(what, count);
  }
  for (const auto& [reason, count] : inf.failures) reasons.emplace_back(reason, count);
  std::stable_sort(reasons.begin(), reasons.end(),
                   [](const auto& a, const auto& b) { return a.second > b.second; });
  nlohmann::json list = nlohmann::json::array();
  text.clear();
  for (std::size_t k = 0; k < reasons.size(); ++k) {
    const double share = 100.0 * static_cast<double>(reasons[k].second) / n;
    list.push_back({{"reason", reasons[k].first},
                    {"designs", reasons[k].second},
                    {"percent", std::round(share * 10.0) / 10.0}});
    if (k < 3)
      text += fmt::format("{}{}: {:.0f}%", text.empty() ? "" : "; ", reasons[k].first, share);
  }
  return list;
}

// The constraints a structure's front presses on: the smallest margin over its front designs.
nlohmann::json binding_json(const Part& part, std::size_t m, std::string& text) {
  const DesignStudy& study = *part.candidate->study;
  const std::vector<std::string> words = constraint_words(study);
  nlohmann::json list = nlohmann::json::array();
  text.clear();
  const std::vector<MeasuredDesign>& front = part.files.selection.designs;
  for (std::size_t i = 0; i < study.constraints().size(); ++i) {
    if (front.empty()) break;
    const DesignConstraint& c = study.constraints()[i];
    double smallest = std::numeric_limits<double>::infinity();
    for (const MeasuredDesign& d : front) smallest = std::min(smallest, -d.aggregate[m + i]);
    const double relative = smallest / std::max(std::abs(c.bound), 1e-300);
    const bool binding = relative < kBindingShare;
    list.push_back({{"constraint", words[i]},
                    {"smallest_margin", json_number(smallest)},
                    {"smallest_margin_relative", json_number(relative)},
                    {"binding", binding}});
    if (binding)
      text += fmt::format("{}{} (margin {:.2g}%)", text.empty() ? "" : "; ", words[i],
                          100.0 * relative);
  }
  return list;
}

// The design-space bounds a structure's front presses on: a free parameter within 1 % of its
// range from a bound in at least half of the front's designs ("the search wants more room").
nlohmann::json bounds_json(const Part& part, std::string& text) {
  const DesignStudy& study = *part.candidate->study;
  const std::vector<MeasuredDesign>& front = part.files.selection.designs;
  nlohmann::json list = nlohmann::json::array();
  text.clear();
  if (front.empty()) return list;
  for (std::size_t i = 0; i < study.parameters.size(); ++i) {
    const StudyParameter& p = study.parameters[i];
    if (!p.free()) continue;
    const double slack = 0.01 * (p.max - p.min);
    std::size_t low = 0, high = 0;
    for (const MeasuredDesign& d : front) {
      low += d.parameters.at(i) <= p.min + slack ? 1 : 0;
      high += d.parameters.at(i) >= p.max - slack ? 1 : 0;
    }
    for (const auto& [count, lower] : {std::pair{low, true}, std::pair{high, false}}) {
      const double share = static_cast<double>(count) / static_cast<double>(front.size());
      if (share < 0.5) continue;
      const double bound = lower ? p.min : p.max;
      list.push_back({{"parameter", p.name},
                      {"bound", lower ? "min" : "max"},
                      {"value", bound},
                      {"unit", p.unit},
                      {"share", share}});
      text += fmt::format("{}{} at its {} {} {} ({:.0f}% of its front)", text.empty() ? "" : "; ",
                          p.name, lower ? "lower bound" : "upper bound", format_number(bound),
                          p.unit, 100.0 * share);
    }
  }
  return list;
}

// The best value of each objective on a structure's own front (user sign), NaN when empty.
std::vector<double> best_values(const Part& part, const std::vector<DesignObjective>& objectives) {
  std::vector<double> best(objectives.size(), std::numeric_limits<double>::quiet_NaN());
  for (const MeasuredDesign& d : part.files.selection.designs)
    for (std::size_t i = 0; i < objectives.size(); ++i) {
      const double v = sense_sign(objectives[i].sense) * d.aggregate[i];
      const bool better = std::isnan(best[i]) ||
                          (objectives[i].sense == Sense::maximize ? v > best[i] : v < best[i]);
      if (better) best[i] = v;
    }
  return best;
}

nlohmann::json objectives_json(const std::vector<DesignObjective>& objectives) {
  nlohmann::json list = nlohmann::json::array();
  for (const DesignObjective& o : objectives)
    list.push_back({{"name", design_metric_name(o.metric)},
                    {"sense", o.sense == Sense::maximize ? "maximize" : "minimize"},
                    {"unit", design_metric_unit(o.metric)}});
  return list;
}

// A row of the terminal table, padded.
std::string table_row(const std::vector<std::string>& cells, const std::vector<std::size_t>& w) {
  std::string row;
  for (std::size_t k = 0; k < cells.size(); ++k)
    row += fmt::format("{:<{}}", cells[k], k + 1 < cells.size() ? w[k] + 2 : 0);
  while (!row.empty() && row.back() == ' ') row.pop_back();
  return row + "\n";
}

std::string terminal_table(const std::vector<std::vector<std::string>>& rows) {
  std::vector<std::size_t> widths(rows.front().size(), 0);
  for (const auto& r : rows)
    for (std::size_t k = 0; k + 1 < r.size(); ++k) widths[k] = std::max(widths[k], r[k].size());
  std::string out;
  for (const auto& r : rows) out += table_row(r, widths);
  return out;
}

}  // namespace

SynthesisOutputSummary write_synthesis_outputs(const std::string& directory, SynthesisStudy& study,
                                               const SynthesisSearch& search,
                                               const SynthesisFacts& facts,
                                               const OutputFiles& also) {
  OutputFiles files = also;
  const std::vector<std::size_t> searched = study.searched();
  std::vector<Part> parts(searched.size());
  for (std::size_t k = 0; k < searched.size(); ++k) {
    SynthesisCandidate& c = study.candidates[searched[k]];
    Part& part = parts[k];
    part.candidate = &c;
    part.run = &search.runs[k];
    part.journal = facts.journals.at(k);
    set_generations(*c.study, part.run->generations);
    RunOutcome outcome;
    outcome.front = part.run->front;
    outcome.status = "ok";
    DesignRunFacts run_facts;
    run_facts.threads = facts.threads;
    run_facts.resumed = facts.resumed;
    run_facts.wall_seconds = facts.wall_seconds;
    run_facts.journal = part.journal;
    const std::string folder = directory + "/candidates/" + c.name;
    part.files = design_output_files(folder, *c.study, outcome, run_facts);
    files.insert(files.end(), part.files.files.begin(), part.files.files.end());
    files.emplace_back(folder + "/study.resolved.yaml", c.study->resolved_yaml);
    part.infeasibility = count_infeasibility(*c.study, part.journal->entries());
  }
  const DesignStudy& first = *parts.front().candidate->study;
  const std::vector<DesignObjective>& objectives = first.objectives();
  const std::size_t m = objectives.size();
  const std::vector<std::string> g_names = constraint_names(first);

  // The merged front: every structure's front, non-dominated together, thinned if asked.
  std::vector<std::vector<double>> pool;
  std::vector<std::pair<std::size_t, std::size_t>> origin;  // (part, design on its front)
  for (std::size_t k = 0; k < parts.size(); ++k)
    for (std::size_t j = 0; j < parts[k].files.selection.designs.size(); ++j) {
      const MeasuredDesign& d = parts[k].files.selection.designs[j];
      pool.emplace_back(d.aggregate.begin(), d.aggregate.begin() + static_cast<std::ptrdiff_t>(m));
      origin.emplace_back(k, j);
    }
  std::size_t non_dominated = 0;
  const std::vector<std::size_t> keep = pool.empty()
                                            ? std::vector<std::size_t>{}
                                            : select_front(pool, study.front_size, &non_dominated);

  std::string csv = "id,architecture,model";
  for (const DesignObjective& o : objectives)
    csv += "," + std::string(design_metric_name(o.metric));
  for (const std::string& g : g_names) csv += "," + g;
  csv += ",home_height,parameters,machine_file,structure_design\n";
  nlohmann::json designs = nlohmann::json::array();
  ObjectiveSet merged_objectives;
  if (study.write_designs && !keep.empty())
    std::filesystem::create_directories(directory + "/designs");
  for (std::size_t n = 0; n < keep.size(); ++n) {
    const auto [k, j] = origin[keep[n]];
    Part& part = parts[k];
    ++part.merged;
    const MeasuredDesign& d = part.files.selection.designs[j];
    const DesignStudy& s = *part.candidate->study;
    const std::string id = merged_id(n);
    merged_objectives.push_back(pool[keep[n]]);
    std::string row = id + "," + csv_field(part.candidate->name) + "," + s.model;
    nlohmann::json design;
    design["id"] = id;
    design["architecture"] = part.candidate->name;
    design["model"] = s.model;
    nlohmann::json values = nlohmann::json::array();
    for (std::size_t i = 0; i < m; ++i) {
      const double v = sense_sign(objectives[i].sense) * d.aggregate[i];
      values.push_back(json_number(v));
      row += "," + format_number(v);
    }
    design["objectives"] = values;
    nlohmann::json g = nlohmann::json::array();
    for (std::size_t i = 0; i < g_names.size(); ++i) {
      const double v = m + i < d.aggregate.size() ? d.aggregate[m + i] : 0.0;
      g.push_back(json_number(v));
      row += "," + format_number(v);
    }
    design["constraints"] = g;
    design["home_height"] = d.home_height;
    nlohmann::json parameters = nlohmann::json::object();
    std::string parameter_text;
    for (std::size_t p = 0; p < s.parameters.size() && p < d.parameters.size(); ++p) {
      parameters[s.parameters[p].name] = d.parameters[p];
      parameter_text += fmt::format("{}{}={}", parameter_text.empty() ? "" : " ",
                                    s.parameters[p].name, format_number(d.parameters[p]));
    }
    design["parameters"] = parameters;
    design["structure_design"] =
        "candidates/" + part.candidate->name + "/pareto.json#" + structure_id(j);
    row += "," + format_number(d.home_height) + "," + csv_field(parameter_text);
    if (study.write_designs) {
      design["machine_file"] = "designs/" + id + ".yaml";
      files.emplace_back(directory + "/designs/" + id + ".yaml",
                         "# " + part.candidate->structure + ", design " + structure_id(j) +
                             " of candidates/" + part.candidate->name + "\n" + d.machine_file);
      row += ",designs/" + id + ".yaml";
    } else {
      row += ",";
    }
    row += "," + structure_id(j) + "\n";
    csv += row;
    designs.push_back(std::move(design));
  }

  nlohmann::json pareto;
  pareto["format"] = "pkmopt-synthesis-front-1";
  pareto["pkmopt_version"] = kVersion;
  pareto["study"] = study.name;
  pareto["description"] = study.description;
  pareto["task_motion"] = study.motion.type();
  pareto["objectives"] = objectives_json(objectives);
  pareto["constraints"] = g_names;
  nlohmann::json architectures = nlohmann::json::array();
  for (const Part& part : parts)
    architectures.push_back({{"name", part.candidate->name},
                             {"model", part.candidate->model},
                             {"structure", part.candidate->structure}});
  pareto["architectures"] = architectures;
  pareto["designs"] = designs;
  pareto["knee"] = merged_objectives.empty()
                       ? nlohmann::json(nullptr)
                       : nlohmann::json(merged_id(knee_point(merged_objectives)));
  pareto["compromise"] = merged_objectives.empty()
                             ? nlohmann::json(nullptr)
                             : nlohmann::json(merged_id(compromise_point(merged_objectives)));
  pareto["front_selection"] = {{"rule", front_rule_text(study.front_size, m)},
                               {"candidate_designs", pool.size()},
                               {"non_dominated", non_dominated}};

  // The candidates table.
  std::string candidates_csv =
      "candidate,model,structure,status,reason,mobility,generations,evaluations,rounds,kept,"
      "feasible_evaluations,own_front,merged_front,merged_share,exclusive_hypervolume";
  for (const DesignObjective& o : objectives)
    candidates_csv += ",best_" + std::string(design_metric_name(o.metric));
  candidates_csv += ",binding,at_bounds,failures,folder\n";
  nlohmann::json candidates = nlohmann::json::array();
  std::vector<std::vector<std::string>> table;
  {
    std::vector<std::string> head = {"candidate", "status", "generations", "merged front"};
    for (const DesignObjective& o : objectives)
      head.push_back(fmt::format("best {} ({})", design_metric_name(o.metric),
                                 design_metric_unit(o.metric).empty()
                                     ? std::string("-")
                                     : std::string(design_metric_unit(o.metric))));
    head.emplace_back("binding constraints, bounds / failures / reason");
    table.push_back(head);
  }
  const double merged_total = static_cast<double>(std::max<std::size_t>(1, keep.size()));
  std::string infeasibility;
  for (const SynthesisCandidate& c : study.candidates) {
    nlohmann::json j;
    j["candidate"] = c.name;
    j["model"] = c.model;
    j["structure"] = c.structure;
    j["origin"] = c.origin;
    j["task_centre"] = c.task_centre;
    j["mobility"] = c.mobility;
    const Part* part = nullptr;
    for (const Part& p : parts)
      if (p.candidate == &c) part = &p;
    if (part == nullptr) {
      j["status"] = "dropped";
      j["reason"] = c.dropped;
      candidates_csv +=
          fmt::format("{},{},{},dropped,{},{},,,,,,,,,", csv_field(c.name), c.model,
                      csv_field(c.structure), csv_field(c.dropped), csv_field(c.mobility));
      for (std::size_t i = 0; i < m; ++i) candidates_csv += ",";
      candidates_csv += ",,,,\n";
      std::vector<std::string> row = {c.name, "dropped", "-", "-"};
      for (std::size_t i = 0; i < m; ++i) row.emplace_back("-");
      row.push_back(c.dropped);
      table.push_back(row);
      candidates.push_back(std::move(j));
      continue;
    }
    const StructureRun& run = *part->run;
    std::string binding_text, failure_text, bounds_text;
    const nlohmann::json binding = binding_json(*part, m, binding_text);
    const nlohmann::json at_bounds = bounds_json(*part, bounds_text);
    const nlohmann::json failures = failure_json(*part, failure_text);
    const std::vector<double> best = best_values(*part, objectives);
    const double share = static_cast<double>(part->merged) / merged_total;
    const double exclusive = run.exclusive.empty() ? 0.0 : run.exclusive.back();
    const std::size_t own = part->files.selection.designs.size();
    j["status"] = "searched";
    j["seed"] = c.seed;
    j["generations"] = run.generations;
    j["evaluations"] = run.evaluations;
    j["rounds"] = run.rounds;
    j["kept_to_the_end"] = run.kept;
    j["exclusive_hypervolume_by_round"] = run.exclusive;
    j["feasible_evaluations"] = part->infeasibility.feasible;
    j["distinct_evaluations"] = part->infeasibility.evaluations;
    j["own_front"] = own;
    j["merged_front"] = part->merged;
    j["merged_share"] = share;
    nlohmann::json best_json = nlohmann::json::object();
    for (std::size_t i = 0; i < m; ++i)
      best_json[std::string(design_metric_name(objectives[i].metric))] = json_number(best[i]);
    j["best"] = best_json;
    j["constraints"] = binding;
    j["at_bounds"] = at_bounds;
    j["failures"] = failures;
    j["folder"] = "candidates/" + c.name;
    candidates_csv +=
        fmt::format("{},{},{},searched,,{},{},{},{},{},{},{},{},{},{}", csv_field(c.name), c.model,
                    csv_field(c.structure), csv_field(c.mobility), run.generations, run.evaluations,
                    run.rounds, run.kept ? 1 : 0, part->infeasibility.feasible, own, part->merged,
                    format_number(share), format_number(exclusive));
    for (double b : best) candidates_csv += "," + (std::isfinite(b) ? format_number(b) : "");
    candidates_csv += fmt::format(",{},{},{},candidates/{}\n", csv_field(binding_text),
                                  csv_field(bounds_text), csv_field(failure_text), c.name);
    std::vector<std::string> row = {c.name, run.kept ? "searched" : "dropped by budget",
                                    std::to_string(run.generations),
                                    fmt::format("{} ({:.0f}%)", part->merged, 100.0 * share)};
    for (double b : best) row.push_back(std::isfinite(b) ? fmt::format("{:.4g}", b) : "-");
    std::string note = own == 0 ? "no feasible design: " + failure_text : binding_text;
    if (own > 0 && !bounds_text.empty()) note += (note.empty() ? "" : "; ") + bounds_text;
    row.push_back(note.empty() ? "-" : note);
    table.push_back(row);
    if (own == 0)
      infeasibility += fmt::format("{}{}: {}", infeasibility.empty() ? "" : "; ", c.name,
                                   part->infeasibility.text());
    candidates.push_back(std::move(j));
  }

  nlohmann::json summary;
  summary["study"] = study.name;
  summary["description"] = study.description;
  summary["version"] = kVersion;
  summary["kind"] = "synthesis";
  summary["task_motion"] = study.motion.type();
  summary["algorithm"] = "nsga2";
  summary["seed"] = study.nsga2.seed;
  summary["population"] = study.nsga2.population;
  summary["generations"] = study.nsga2.generations;
  summary["threads"] = resolve_thread_count(facts.threads);
  summary["resumed"] = facts.resumed;
  summary["allocation"] = {{"rule", study.allocation.rule},
                           {"floor_generations", study.allocation.floor_generations},
                           {"budget", search.plan.budget},
                           {"planned", search.plan.planned()},
                           {"rounds_structures", search.plan.structures},
                           {"rounds_generations", search.plan.generations}};
  long long evaluations = 0;
  for (const StructureRun& run : search.runs) evaluations += run.evaluations;
  summary["evaluations"] = evaluations;
  summary["searched"] = searched.size();
  summary["dropped"] = study.candidates.size() - searched.size();
  summary["points"] = keep.size();
  summary["objectives"] = objectives_json(objectives);
  const bool empty = keep.empty();
  summary["status"] = empty ? "no_feasible_design" : "ok";
  if (!empty && m >= 2) {
    const std::vector<double> reference = reference_point_from(merged_objectives);
    std::vector<double> user(m);
    for (std::size_t i = 0; i < m; ++i) user[i] = sense_sign(objectives[i].sense) * reference[i];
    summary["reference_point"] = user;
    summary["hypervolume"] = json_number(hypervolume(merged_objectives, reference));
  }
  summary["knee"] = pareto["knee"];
  summary["search_seconds"] = search.seconds;
  summary["wall_seconds"] = facts.wall_seconds;

  files.emplace_back(directory + "/pareto.csv", std::move(csv));
  files.emplace_back(directory + "/pareto.json", pareto.dump(2) + "\n");
  files.emplace_back(directory + "/candidates.csv", std::move(candidates_csv));
  files.emplace_back(directory + "/candidates.json",
                     nlohmann::json({{"study", study.name},
                                     {"task_motion", study.motion.type()},
                                     {"task_motions", study.motion.words()},
                                     {"candidates", candidates}})
                             .dump(2) +
                         "\n");
  files.emplace_back(directory + "/summary.json", summary.dump(2) + "\n");
  write_files_together(files);

  SynthesisOutputSummary result;
  result.designs = keep.size();
  result.status = empty ? "no_feasible_design" : "ok";
  result.infeasibility = infeasibility;
  result.table = terminal_table(table);
  return result;
}

}  // namespace pkmopt
