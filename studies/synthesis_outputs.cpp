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

// Each searched structure's own result folder (its files appended to `files`).
std::vector<Part> structure_parts(const std::string& directory, SynthesisStudy& study,
                                  const SynthesisSearch& search, const SynthesisFacts& facts,
                                  OutputFiles& files) {
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
  return parts;
}

// The merged front: every structure's front, non-dominated together, thinned if asked.
struct MergedFront {
  std::string csv;
  nlohmann::json pareto;
  ObjectiveSet objectives;  // minimised, of the kept designs
  std::size_t designs = 0;
};

// One merged-front design: its pareto.csv row and pareto.json entry (its machine file appended to
// `files`).
std::pair<std::string, nlohmann::json> merged_design(const std::string& directory,
                                                     const SynthesisStudy& study, const Part& part,
                                                     std::size_t j, std::size_t n, std::size_t m,
                                                     std::size_t constraints, OutputFiles& files) {
  const std::vector<DesignObjective>& objectives = part.candidate->study->objectives();
  const MeasuredDesign& d = part.files.selection.designs[j];
  const DesignStudy& s = *part.candidate->study;
  const std::string id = merged_id(n);
  std::string row = id + "," + csv_field(part.candidate->name) + "," + s.model;
  nlohmann::json design = {{"id", id}, {"architecture", part.candidate->name}, {"model", s.model}};
  nlohmann::json values = nlohmann::json::array(), g = nlohmann::json::array();
  for (std::size_t i = 0; i < m; ++i) {
    const double v = sense_sign(objectives[i].sense) * d.aggregate[i];
    values.push_back(json_number(v));
    row += "," + format_number(v);
  }
  for (std::size_t i = 0; i < constraints; ++i) {
    const double v = m + i < d.aggregate.size() ? d.aggregate[m + i] : 0.0;
    g.push_back(json_number(v));
    row += "," + format_number(v);
  }
  design["objectives"] = values;
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
  row += "," + format_number(d.home_height) + "," + csv_field(parameter_text) + ",";
  if (study.write_designs) {
    design["machine_file"] = "designs/" + id + ".yaml";
    files.emplace_back(directory + "/designs/" + id + ".yaml",
                       "# " + part.candidate->structure + ", design " + structure_id(j) +
                           " of candidates/" + part.candidate->name + "\n" + d.machine_file);
    row += "designs/" + id + ".yaml";
  }
  row += "," + structure_id(j);
  if (s.problem->prices_each_drive()) {
    design["drives"] = d.drives;
    row += "," + csv_field(d.drives);
  }
  return {row + "\n", design};
}

MergedFront merged_front(const std::string& directory, const SynthesisStudy& study,
                         std::vector<Part>& parts, OutputFiles& files) {
  const DesignStudy& first = *parts.front().candidate->study;
  const std::vector<DesignObjective>& objectives = first.objectives();
  const std::size_t m = objectives.size();
  const std::vector<std::string> g_names = constraint_names(first);
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
  MergedFront out;
  out.designs = keep.size();
  out.csv = "id,architecture,model";
  for (const DesignObjective& o : objectives)
    out.csv += "," + std::string(design_metric_name(o.metric));
  for (const std::string& g : g_names) out.csv += "," + g;
  out.csv += ",home_height,parameters,machine_file,structure_design";
  out.csv += first.problem->prices_each_drive() ? ",drives\n" : "\n";
  nlohmann::json designs = nlohmann::json::array();
  if (study.write_designs && !keep.empty())
    std::filesystem::create_directories(directory + "/designs");
  for (std::size_t n = 0; n < keep.size(); ++n) {
    const auto [k, j] = origin[keep[n]];
    ++parts[k].merged;
    out.objectives.push_back(pool[keep[n]]);
    auto [row, design] = merged_design(directory, study, parts[k], j, n, m, g_names.size(), files);
    out.csv += row;
    designs.push_back(std::move(design));
  }
  nlohmann::json architectures = nlohmann::json::array();
  for (const Part& part : parts)
    architectures.push_back({{"name", part.candidate->name},
                             {"model", part.candidate->model},
                             {"structure", part.candidate->structure}});
  auto id_of = [&](std::size_t k) { return nlohmann::json(merged_id(k)); };
  out.pareto = {{"format", "pkmopt-synthesis-front-1"},
                {"pkmopt_version", kVersion},
                {"study", study.name},
                {"description", study.description},
                {"task_motion", study.motion.type()},
                {"objectives", objectives_json(objectives)},
                {"constraints", g_names},
                {"architectures", architectures},
                {"designs", designs},
                {"knee", out.objectives.empty() ? nlohmann::json(nullptr)
                                                : id_of(knee_point(out.objectives))},
                {"compromise", out.objectives.empty() ? nlohmann::json(nullptr)
                                                      : id_of(compromise_point(out.objectives))},
                {"front_selection",
                 {{"rule", front_rule_text(study.front_size, m)},
                  {"candidate_designs", pool.size()},
                  {"non_dominated", non_dominated}}}};
  return out;
}

// The candidates table: candidates.csv, candidates.json and the terminal's rows.
struct CandidatesTable {
  std::string csv;
  nlohmann::json json = nlohmann::json::array();
  std::vector<std::vector<std::string>> terminal;
  std::string infeasibility;  // the structures without a feasible design, their main causes
};

void add_dropped(const SynthesisCandidate& c, std::size_t m, nlohmann::json& j,
                 CandidatesTable& table) {
  j["status"] = "dropped";
  j["reason"] = c.dropped;
  table.csv += fmt::format("{},{},{},dropped,{},{},,,,,,,,,", csv_field(c.name), c.model,
                           csv_field(c.structure), csv_field(c.dropped), csv_field(c.mobility));
  for (std::size_t i = 0; i < m; ++i) table.csv += ",";
  table.csv += ",,,,\n";
  std::vector<std::string> row = {c.name, "dropped", "-", "-"};
  for (std::size_t i = 0; i < m; ++i) row.emplace_back("-");
  row.push_back(c.dropped);
  table.terminal.push_back(row);
}

void add_searched(const SynthesisCandidate& c, const Part& part, std::size_t merged_total,
                  nlohmann::json& j, CandidatesTable& table) {
  const std::vector<DesignObjective>& objectives = c.study->objectives();
  const std::size_t m = objectives.size();
  const StructureRun& run = *part.run;
  std::string binding_text, failure_text, bounds_text;
  const nlohmann::json binding = binding_json(part, m, binding_text);
  const nlohmann::json at_bounds = bounds_json(part, bounds_text);
  const nlohmann::json failures = failure_json(part, failure_text);
  const std::vector<double> best = best_values(part, objectives);
  const double share = static_cast<double>(part.merged) /
                       static_cast<double>(std::max<std::size_t>(1, merged_total));
  const double exclusive = run.exclusive.empty() ? 0.0 : run.exclusive.back();
  const std::size_t own = part.files.selection.designs.size();
  nlohmann::json best_json = nlohmann::json::object();
  for (std::size_t i = 0; i < m; ++i)
    best_json[std::string(design_metric_name(objectives[i].metric))] = json_number(best[i]);
  j.update({{"status", "searched"},
            {"seed", c.seed},
            {"generations", run.generations},
            {"evaluations", run.evaluations},
            {"rounds", run.rounds},
            {"kept_to_the_end", run.kept},
            {"exclusive_hypervolume_by_round", run.exclusive},
            {"feasible_evaluations", part.infeasibility.feasible},
            {"distinct_evaluations", part.infeasibility.evaluations},
            {"own_front", own},
            {"merged_front", part.merged},
            {"merged_share", share},
            {"best", best_json},
            {"constraints", binding},
            {"at_bounds", at_bounds},
            {"failures", failures},
            {"folder", "candidates/" + c.name}});
  table.csv +=
      fmt::format("{},{},{},searched,,{},{},{},{},{},{},{},{},{},{}", csv_field(c.name), c.model,
                  csv_field(c.structure), csv_field(c.mobility), run.generations, run.evaluations,
                  run.rounds, run.kept ? 1 : 0, part.infeasibility.feasible, own, part.merged,
                  format_number(share), format_number(exclusive));
  for (double b : best) table.csv += "," + (std::isfinite(b) ? format_number(b) : "");
  table.csv += fmt::format(",{},{},{},candidates/{}\n", csv_field(binding_text),
                           csv_field(bounds_text), csv_field(failure_text), c.name);
  std::vector<std::string> row = {c.name, run.kept ? "searched" : "dropped by budget",
                                  std::to_string(run.generations),
                                  fmt::format("{} ({:.0f}%)", part.merged, 100.0 * share)};
  for (double b : best) row.push_back(std::isfinite(b) ? fmt::format("{:.4g}", b) : "-");
  std::string note = own == 0 ? "no feasible design: " + failure_text : binding_text;
  if (own > 0 && !bounds_text.empty()) note += (note.empty() ? "" : "; ") + bounds_text;
  row.push_back(note.empty() ? "-" : note);
  table.terminal.push_back(row);
  if (own == 0)
    table.infeasibility += fmt::format("{}{}: {}", table.infeasibility.empty() ? "" : "; ", c.name,
                                       part.infeasibility.text());
}

CandidatesTable candidates_table(const SynthesisStudy& study, const std::vector<Part>& parts,
                                 const std::vector<DesignObjective>& objectives,
                                 std::size_t merged_total) {
  CandidatesTable table;
  table.csv =
      "candidate,model,structure,status,reason,mobility,generations,evaluations,rounds,kept,"
      "feasible_evaluations,own_front,merged_front,merged_share,exclusive_hypervolume";
  for (const DesignObjective& o : objectives)
    table.csv += ",best_" + std::string(design_metric_name(o.metric));
  table.csv += ",binding,at_bounds,failures,folder\n";
  std::vector<std::string> head = {"candidate", "status", "generations", "merged front"};
  for (const DesignObjective& o : objectives) {
    const std::string_view unit = design_metric_unit(o.metric);
    head.push_back(fmt::format("best {} ({})", design_metric_name(o.metric),
                               unit.empty() ? std::string("-") : std::string(unit)));
  }
  head.emplace_back("binding constraints, bounds / failures / reason");
  table.terminal.push_back(head);
  for (const SynthesisCandidate& c : study.candidates) {
    nlohmann::json j = {{"candidate", c.name},          {"model", c.model},
                        {"structure", c.structure},     {"origin", c.origin},
                        {"task_centre", c.task_centre}, {"mobility", c.mobility}};
    const Part* part = nullptr;
    for (const Part& p : parts)
      if (p.candidate == &c) part = &p;
    if (part == nullptr)
      add_dropped(c, objectives.size(), j, table);
    else
      add_searched(c, *part, merged_total, j, table);
    table.json.push_back(std::move(j));
  }
  return table;
}

// summary.json of the synthesis.
nlohmann::json summary_json(const SynthesisStudy& study, const SynthesisSearch& search,
                            const SynthesisFacts& facts, const MergedFront& front,
                            const std::vector<DesignObjective>& objectives) {
  const std::size_t m = objectives.size();
  long long evaluations = 0;
  for (const StructureRun& run : search.runs) evaluations += run.evaluations;
  const std::size_t searched = study.searched().size();
  nlohmann::json summary = {{"study", study.name},
                            {"description", study.description},
                            {"version", kVersion},
                            {"kind", "synthesis"},
                            {"task_motion", study.motion.type()},
                            {"algorithm", "nsga2"},
                            {"seed", study.nsga2.seed},
                            {"population", study.nsga2.population},
                            {"generations", study.nsga2.generations},
                            {"threads", resolve_thread_count(facts.threads)},
                            {"resumed", facts.resumed},
                            {"allocation",
                             {{"rule", study.allocation.rule},
                              {"floor_generations", study.allocation.floor_generations},
                              {"budget", search.plan.budget},
                              {"planned", search.plan.planned()},
                              {"rounds_structures", search.plan.structures},
                              {"rounds_generations", search.plan.generations}}},
                            {"evaluations", evaluations},
                            {"searched", searched},
                            {"dropped", study.candidates.size() - searched},
                            {"points", front.designs},
                            {"objectives", objectives_json(objectives)},
                            {"status", front.designs == 0 ? "no_feasible_design" : "ok"}};
  if (front.designs > 0 && m >= 2) {
    const std::vector<double> reference = reference_point_from(front.objectives);
    std::vector<double> user(m);
    for (std::size_t i = 0; i < m; ++i) user[i] = sense_sign(objectives[i].sense) * reference[i];
    summary["reference_point"] = user;
    summary["hypervolume"] = json_number(hypervolume(front.objectives, reference));
  }
  summary["knee"] = front.pareto["knee"];
  summary["search_seconds"] = search.seconds;
  summary["wall_seconds"] = facts.wall_seconds;
  return summary;
}

}  // namespace

SynthesisOutputSummary write_synthesis_outputs(const std::string& directory, SynthesisStudy& study,
                                               const SynthesisSearch& search,
                                               const SynthesisFacts& facts,
                                               const OutputFiles& also) {
  OutputFiles files = also;
  std::vector<Part> parts = structure_parts(directory, study, search, facts, files);
  const std::vector<DesignObjective>& objectives = parts.front().candidate->study->objectives();
  const MergedFront front = merged_front(directory, study, parts, files);
  const CandidatesTable table = candidates_table(study, parts, objectives, front.designs);
  const nlohmann::json summary = summary_json(study, search, facts, front, objectives);
  files.emplace_back(directory + "/pareto.csv", front.csv);
  files.emplace_back(directory + "/pareto.json", front.pareto.dump(2) + "\n");
  files.emplace_back(directory + "/candidates.csv", table.csv);
  files.emplace_back(directory + "/candidates.json",
                     nlohmann::json({{"study", study.name},
                                     {"task_motion", study.motion.type()},
                                     {"task_motions", study.motion.words()},
                                     {"candidates", table.json}})
                             .dump(2) +
                         "\n");
  files.emplace_back(directory + "/summary.json", summary.dump(2) + "\n");
  write_files_together(files);

  SynthesisOutputSummary result;
  result.designs = front.designs;
  result.status = front.designs == 0 ? "no_feasible_design" : "ok";
  result.infeasibility = table.infeasibility;
  result.table = terminal_table(table.terminal);
  return result;
}

}  // namespace pkmopt
