#include "studies/synthesis_study.hpp"

#include <fmt/format.h>
#include <yaml-cpp/yaml.h>

#include <Eigen/SVD>
#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>
#include <stdexcept>

#include "io/format/csv.hpp"
#include "io/format/input_error.hpp"
#include "io/machine/machine_description.hpp"
#include "io/machine/machine_file.hpp"
#include "io/machine/model_registry.hpp"
#include "pkmopt/version.hpp"
#include "problems/design/design_metrics.hpp"
#include "studies/design_study_sections.hpp"
#include "studies/journal.hpp"

namespace pkmopt {

using namespace design_study_detail;

namespace {

constexpr std::array<const char*, 6> kMotionNames = {
    "x", "y", "z", "tilt about x", "tilt about y", "yaw about z"};

// The allocation section in file units (0: the default floor).
struct AllocationSection {
  int rule = 0;  // 0 successive_halving, 1 equal
  int floor_generations = 0;
};

template <class Fields>
void describe_fields(Fields& f, AllocationSection& a) {
  FieldChoice<int> rule{a.rule, {{"successive_halving", 0}, {"equal", 1}}};
  f.field("rule", rule,
          {.doc = "successive_halving: after the floor, each round keeps the better half of the "
                  "structures (by their share of the merged front) and gives them the rest of "
                  "the budget; equal: every structure runs the optimizer's generations"});
  f.field("floor_generations", a.floor_generations,
          {.min = 0,
           .max = 100000,
           .default_text = "generations / 4, rounded up",
           .doc = "generations every structure runs before any is dropped (at most generations)"});
}

// The motions the task needs: the axes its region extends along, and its rotations.
TaskMotion task_motion_of(const DesignTask& task, double tilt_deg, double yaw_deg) {
  TaskMotion motion;
  if (task.region) {
    const Eigen::Vector3d extent = task.region->position_hi - task.region->position_lo;
    for (int a = 0; a < 3; ++a) motion.needed[static_cast<std::size_t>(a)] = extent(a) > 1e-12;
  }
  motion.needed[3] = motion.needed[4] = tilt_deg > 0.0;
  motion.needed[5] = yaw_deg > 0.0;
  return motion;
}

// The motions a platform of these degrees of freedom makes, by pkmopt's conventions.
std::array<bool, 6> platform_motions(const PlatformDofs& dofs) {
  std::array<bool, 6> m{};
  if (dofs.translations >= 3) m[0] = m[1] = m[2] = true;
  if (dofs.translations == 2) m[0] = m[1] = true;
  if (dofs.translations == 1) m[2] = true;
  if (dofs.rotations >= 3) m[3] = m[4] = m[5] = true;
  if (dofs.rotations == 2) m[3] = m[4] = true;
  if (dofs.rotations == 1) m[5] = true;
  return m;
}

std::string motion_words(const std::array<bool, 6>& motions) {
  std::string words;
  for (std::size_t k = 0; k < 6; ++k)
    if (motions[k]) words += (words.empty() ? "" : ", ") + std::string(kMotionNames[k]);
  return words.empty() ? "none" : words;
}

std::string motion_type(const std::array<bool, 6>& motions) {
  int t = 0, r = 0;
  for (std::size_t k = 0; k < 3; ++k) t += motions[k] ? 1 : 0;
  for (std::size_t k = 3; k < 6; ++k) r += motions[k] ? 1 : 0;
  return fmt::format("{}T{}R", t, r);
}

// A candidate before its study is loaded.
struct CandidateSource {
  SynthesisCandidate candidate;
  std::optional<YamlValue> machine;  // the machine section
  std::string entry_yaml;            // the resolved list entry of a dropped candidate
};

SynthesisScale scale_of(const DesignTask& task, double tilt_deg, double yaw_deg) {
  SynthesisScale scale;
  scale.tilt_deg = tilt_deg;
  scale.yaw_deg = yaw_deg;
  if (task.region) {
    const Eigen::Vector3d extent = task.region->position_hi - task.region->position_lo;
    scale.size = extent.maxCoeff();
    scale.height = extent(2);
  }
  return scale;
}

// Whether the study measures a metric that needs masses: an objective or constraint on
// natural_frequency_min or moving_mass (the shapes are checked where the study is loaded).
bool needs_masses(const YamlValue& root) {
  auto mass_metric = [](const YamlValue& v) {
    if (!v.is_scalar()) return false;
    const std::string name = v.as_string();
    return name == design_metric_name(DesignMetric::natural_frequency_min) ||
           name == design_metric_name(DesignMetric::moving_mass);
  };
  for (const char* section : {"objectives", "constraints"}) {
    const std::optional<YamlValue> list = root.optional(section);
    if (!list || !list->is_sequence()) continue;
    for (const YamlValue& item : list->elements()) {
      if (!item.is_map()) continue;
      for (const char* key : {"minimize", "maximize", "metric"})
        if (const std::optional<YamlValue> v = item.optional(key); v && mass_metric(*v))
          return true;
    }
  }
  return false;
}

// The candidates a model offers for this task, with their generated machine sections.
std::vector<CandidateSource> model_candidates(const ModelEntry& entry,
                                              const SynthesisScale& scale) {
  std::vector<CandidateSource> out;
  for (const SynthesisTemplate& t : entry.synthesis(scale)) {
    CandidateSource source;
    source.candidate.name = t.name;
    source.candidate.model = entry.name;
    source.candidate.structure = t.structure;
    source.candidate.origin = "scaled from the task";
    source.candidate.task_centre = t.task_centre;
    source.machine =
        YamlValue::load_string(t.machine_yaml, "candidate " + t.name + " (scaled from the task)");
    source.entry_yaml = t.name;
    out.push_back(std::move(source));
  }
  return out;
}

std::string synthesis_model_names() {
  std::string names;
  for (const ModelEntry* e : registered_models())
    if (e->synthesis) names += (names.empty() ? "" : ", ") + e->name;
  return names;
}

std::string flow_yaml(const YAML::Node& node) {
  YAML::Emitter out;
  out << YAML::Flow << node;
  return out.c_str();
}

// `candidates:` into candidate sources (names unique).
std::vector<CandidateSource> read_candidates(const YamlValue& list, const SynthesisScale& scale) {
  std::vector<CandidateSource> sources;
  if (list.is_scalar()) {
    if (list.as_string() != "auto")
      list.fail("auto or a list of candidates (model names or {name, machine, task_centre})",
                list.describe());
    for (const ModelEntry* entry : registered_models())
      if (entry->synthesis)
        for (CandidateSource& s : model_candidates(*entry, scale)) sources.push_back(std::move(s));
    return sources;
  }
  const std::vector<YamlValue> entries = list.elements();
  if (entries.empty()) list.fail("auto or a list of at least one candidate", "an empty list");
  std::vector<std::pair<std::string, YamlValue>> names;
  for (const YamlValue& e : entries) {
    std::vector<CandidateSource> from_entry;
    if (e.is_scalar()) {
      // A model (every structure it offers) or one structure by its name.
      const std::string name = e.as_string();
      const ModelEntry* entry = find_model(name);
      if (entry != nullptr && entry->synthesis) {
        from_entry = model_candidates(*entry, scale);
      } else {
        std::string structures;
        for (const ModelEntry* model : registered_models())
          if (model->synthesis)
            for (CandidateSource& s : model_candidates(*model, scale)) {
              structures += (structures.empty() ? "" : ", ") + s.candidate.name;
              if (s.candidate.name == name) from_entry.push_back(std::move(s));
            }
        if (from_entry.empty())
          e.fail(fmt::format("a model that offers structures to a synthesis ({}), one of its "
                             "structures ({}) or a map {{name, machine, task_centre}}",
                             synthesis_model_names(), structures),
                 quote_found(name));
      }
    } else {
      e.check_keys({"name", "machine", "task_centre"});
      const YamlValue machine = e.required("machine");
      machine.expect_map();
      const std::string model = machine.required("model").as_string();
      const ModelEntry* entry = find_model(model);
      CandidateSource source;
      source.candidate.model = model;
      source.candidate.name = model;
      if (auto name = e.optional("name")) {
        source.candidate.name = name->as_string();
        if (source.candidate.name.empty()) name->fail("a non-empty name", "''");
        for (char c : source.candidate.name)
          if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '_'))
            name->fail("a name of letters, digits, '-' and '_' (it names a folder)",
                       quote_found(source.candidate.name));
      }
      source.candidate.origin = "the study file";
      source.candidate.structure = model;
      if (entry != nullptr && entry->synthesis) {
        const std::vector<SynthesisTemplate> templates = entry->synthesis(scale);
        if (!templates.empty()) {
          source.candidate.structure = templates.front().structure;
          source.candidate.task_centre = templates.front().task_centre;
        }
      }
      if (auto centre = e.optional("task_centre")) {
        const std::vector<double> c = centre->as_lengths(3);
        source.candidate.task_centre = {c[0], c[1], c[2]};
      } else if (entry == nullptr || !entry->synthesis) {
        e.fail(fmt::format("task_centre (the model {} has no place for a synthesis task)", model),
               e.describe());
      }
      source.machine = machine;
      source.entry_yaml = flow_yaml(e.node());
      from_entry.push_back(std::move(source));
    }
    for (CandidateSource& s : from_entry) {
      for (const auto& [name, where] : names)
        if (name == s.candidate.name)
          e.fail(fmt::format("a candidate name not used before (line {} has '{}'); give one with "
                             "{{name: ..., machine: ...}}",
                             where.line(), name),
                 quote_found(s.candidate.name));
      names.emplace_back(s.candidate.name, e);
      sources.push_back(std::move(s));
    }
  }
  return sources;
}

// The reason the rules drop a structure whose platform has these degrees of freedom, or "".
std::string rule_reason(const PlatformDofs& dofs, const TaskMotion& motion) {
  const std::array<bool, 6> makes = platform_motions(dofs);
  std::array<bool, 6> missing{};
  bool any = false;
  for (std::size_t k = 0; k < 6; ++k) {
    missing[k] = motion.needed[k] && !makes[k];
    any = any || missing[k];
  }
  if (!any) return "";
  return fmt::format("no {}: the task needs {} ({}), the platform makes {} ({}) only",
                     motion_words(missing), motion.words(), motion.type(), motion_words(makes),
                     motion_type(makes));
}

// The platform's degrees of freedom from the model's study section (models that give them
// whatever the file, as the parallel ones); nullopt when the model describes its files instead.
std::optional<PlatformDofs> section_dofs(const CandidateSource& source) {
  const ModelEntry* entry = find_model(source.candidate.model);
  if (entry == nullptr || !entry->platform_dofs) return std::nullopt;
  return entry->platform_dofs(*source.machine);
}

// The middle design (every free parameter at the middle of its range) of a loaded candidate:
// its machine file and the task's home_height lift.
struct MiddleDesign {
  std::string file;
  double lift = 0.0;
};

MiddleDesign middle_design(const DesignStudy& study) {
  const DesignProblem& problem = *study.problem;
  const Bounds bounds = problem.bounds();
  std::vector<double> x(bounds.lower.size());
  for (std::size_t j = 0; j < x.size(); ++j) x[j] = 0.5 * (bounds.lower[j] + bounds.upper[j]);
  const std::vector<double> parameters = problem.design_parameters(x);
  return {study.machine->machine_file(parameters), problem.home_height(parameters)};
}

// The degrees of freedom `pkmopt describe` gives the middle design (serial and hybrid machines).
std::optional<PlatformDofs> described_dofs(const DesignStudy& study) {
  const ModelEntry* entry = find_model(study.model);
  if (entry == nullptr || !entry->describe) return std::nullopt;
  try {
    MachineDescription d;
    entry->describe(YamlValue::load_string(middle_design(study).file, "the middle design"), d);
    return PlatformDofs{d.translations, d.rotations};
  } catch (const std::exception&) {
    return std::nullopt;
  }
}

// The numeric mobility check of a loaded candidate (see the header comment): "" when it may be
// searched, else why not; `note` says what was found.
std::string rank_reason(const DesignStudy& study, const TaskMotion& motion, std::string& note) {
  const DesignProblem& problem = *study.problem;
  std::unique_ptr<Machine> machine;
  double lift = 0.0;
  try {
    const MiddleDesign middle = middle_design(study);
    machine = load_machine(YamlValue::load_string(middle.file, "the middle design"));
    lift = middle.lift;
  } catch (const std::exception& error) {
    note = fmt::format("not checked: the middle design cannot be built ({})", error.what());
    return "";
  }
  std::vector<std::size_t> needed;
  for (std::size_t k = 0; k < 6; ++k)
    if (motion.needed[k]) needed.push_back(k);
  if (needed.empty()) {
    note = "the task needs no motion";
    return "";
  }
  const std::vector<Pose>& poses = problem.task().poses;
  const std::size_t samples = std::min<std::size_t>(9, poses.size());
  std::unique_ptr<MachineData> data = machine->make_data();
  std::size_t checked = 0, full = 0;
  long best_rank = -1;
  for (std::size_t s = 0; s < samples; ++s) {
    const std::size_t k = samples == 1 ? 0 : s * (poses.size() - 1) / (samples - 1);
    Pose pose = poses[k];
    pose.position.z() += lift;
    Eigen::MatrixXd J;
    if (!machine->twist_jacobian(*data, pose, J) || !J.allFinite()) continue;
    Eigen::MatrixXd JS(J.rows(), static_cast<Eigen::Index>(needed.size()));
    for (std::size_t c = 0; c < needed.size(); ++c)
      JS.col(static_cast<Eigen::Index>(c)) = J.col(static_cast<Eigen::Index>(needed[c]));
    const Eigen::VectorXd sigma = Eigen::JacobiSVD<Eigen::MatrixXd>(JS).singularValues();
    long rank = 0;
    for (Eigen::Index i = 0; i < sigma.size(); ++i)
      if (sigma(i) > 1e-9 * sigma(0)) ++rank;
    ++checked;
    if (rank == static_cast<long>(needed.size())) ++full;
    best_rank = std::max(best_rank, rank);
  }
  if (checked == 0) {
    note = fmt::format("not checked: the middle design closes its legs at none of {} task poses",
                       samples);
    return "";
  }
  note = fmt::format("J S of rank {} of {} at {} of {} checked task poses", best_rank,
                     needed.size(), full, checked);
  if (full > 0) return "";
  return fmt::format(
      "its inverse Jacobian on the task's motions ({}) has rank {} of {} at every checked task "
      "pose ({}): the actuators cannot control them",
      motion.words(), best_rank, needed.size(), checked);
}

// The machine section of a resolved study, indented under a list entry.
std::string indented_machine(const std::string& machine_yaml) {
  // "machine:\n  model: ...\n" -> "    machine:\n      model: ...\n"
  std::istringstream in(machine_yaml);
  std::string line, out;
  while (std::getline(in, line)) out += "    " + line + "\n";
  return out;
}

// The shared part of a candidate's resolved study: from "objectives:" up to "optimizer:".
std::string goals_yaml(const std::string& resolved) {
  const std::size_t a = resolved.find("\nobjectives:");
  const std::size_t b = resolved.find("\noptimizer:");
  if (a == std::string::npos || b == std::string::npos || b < a) return "";
  return resolved.substr(a + 1, b - a);
}

}  // namespace

std::string TaskMotion::type() const { return motion_type(needed); }
std::string TaskMotion::words() const { return motion_words(needed); }

std::vector<std::size_t> SynthesisStudy::searched() const {
  std::vector<std::size_t> out;
  for (std::size_t k = 0; k < candidates.size(); ++k)
    if (candidates[k].searched) out.push_back(k);
  return out;
}

bool is_synthesis_study(const YamlValue& root) { return root.is_map() && root.has("candidates"); }

std::uint64_t candidate_seed(std::uint64_t study_seed, const std::string& name) {
  std::uint64_t z = study_seed ^ study_hash(name);
  // SplitMix64 (Steele, Lea & Flood 2014): one step.
  z += 0x9E3779B97F4A7C15ull;
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  z ^= z >> 31;
  return z == 0 ? 1 : z;
}

namespace {

// What screening the candidates gathers on the way.
struct Screening {
  std::string goals;                      // the shared objectives and constraints, resolved
  std::string dropped;                    // "name: why; ..." of the dropped ones
  std::optional<InputError> first_error;  // of a registry structure that could not be loaded
  bool loaded_any = false;
};

// Rules, loading and the rank check for one candidate (see the header comment); appends it to
// study.candidates.
void screen_candidate(const YamlValue& root, SynthesisStudy& study, CandidateSource& source,
                      Screening& screening) {
  SynthesisCandidate& c = source.candidate;
  const std::optional<PlatformDofs> dofs = section_dofs(source);
  if (dofs) c.dropped = rule_reason(*dofs, study.motion);
  std::shared_ptr<DesignStudy> design;
  if (c.dropped.empty()) {
    // A structure generated from the registry that cannot measure the study's goals (a metric
    // its model does not compute) is dropped with the reason; an error in a section the user
    // wrote stops the study.
    try {
      design = std::make_shared<DesignStudy>(
          load_design_study_part(root, study.name + "/" + c.name, *source.machine, c.task_centre));
    } catch (const InputError& error) {
      if (c.origin != "scaled from the task") throw;
      if (!screening.first_error) screening.first_error = error;
      c.dropped = std::string("cannot be measured: ") + error.what();
      c.mobility = "not checked";
    }
  }
  if (design) {
    if (!dofs)
      if (const std::optional<PlatformDofs> described = described_dofs(*design))
        c.dropped = rule_reason(*described, study.motion);
    if (c.dropped.empty())
      c.dropped = rank_reason(*design, study.motion, c.mobility);
    else
      c.mobility = "dropped by the rules";
    if (screening.goals.empty()) screening.goals = goals_yaml(design->resolved_yaml);
    if (design->optimizer.nsga2() != nullptr) study.nsga2 = *design->optimizer.nsga2();
    screening.loaded_any = true;
    c.study = std::move(design);
  } else if (c.mobility.empty()) {
    c.mobility = "dropped by the rules";
  }
  c.searched = c.dropped.empty();
  if (!c.searched) {
    c.study.reset();
    screening.dropped +=
        fmt::format("{}{}: {}", screening.dropped.empty() ? "" : "; ", c.name, c.dropped);
  }
  study.candidates.push_back(c);
}

// Every candidate's seed (its design study carries it).
void seed_candidates(SynthesisStudy& study) {
  for (SynthesisCandidate& c : study.candidates) {
    c.seed = candidate_seed(study.nsga2.seed, c.name);
    if (!c.study) continue;
    if (auto* spec = std::get_if<Nsga2Spec>(&c.study->optimizer.algorithm))
      spec->options.seed = c.seed;
    c.study->optimizer.seed = c.seed;
  }
}

// `allocation:` (the floor defaults to a quarter of the generations) and `output:`.
void read_allocation_and_output(const YamlValue& root, SynthesisStudy& study,
                                AllocationSection& allocation, OutputSection& output) {
  if (auto a = root.optional("allocation")) read_fields(*a, allocation);
  study.allocation.rule = allocation.rule == 0 ? "successive_halving" : "equal";
  const std::size_t generations = study.nsga2.generations;
  if (allocation.floor_generations == 0)
    allocation.floor_generations = static_cast<int>((generations + 3) / 4);
  if (static_cast<std::size_t>(allocation.floor_generations) > generations)
    root.required("allocation")
        .required("floor_generations")
        .fail(fmt::format("at most the optimizer's generations ({})", generations),
              std::to_string(allocation.floor_generations));
  study.allocation.floor_generations = static_cast<std::size_t>(allocation.floor_generations);
  if (auto section = root.optional("output")) read_fields(*section, output);
  study.write_designs = output.designs;
  study.front_size = static_cast<std::size_t>(output.front_size);
}

// study.resolved.yaml: the candidates (searched ones with their resolved sections, dropped ones
// as written, with why), then the shared sections.
std::string resolved_synthesis_yaml(const SynthesisStudy& study,
                                    const std::vector<CandidateSource>& sources,
                                    const std::string& task_yaml, const std::string& goals,
                                    const AllocationSection& allocation,
                                    const OutputSection& output) {
  std::string yaml = fmt::format("# {} resolved: every default filled in (pkmopt {})\n",
                                 nlohmann::json(study.name).dump(), kVersion);
  yaml += "study: " + nlohmann::json(study.name).dump() + "\n";
  yaml += "description: " + nlohmann::json(study.description).dump() + "\n";
  yaml += fmt::format("# task motion type {} ({})\n", study.motion.type(), study.motion.words());
  yaml += "candidates:\n";
  for (std::size_t k = 0; k < study.candidates.size(); ++k) {
    const SynthesisCandidate& c = study.candidates[k];
    if (!c.searched) {
      yaml += "  # dropped: " + c.dropped + "\n";
      yaml += "  - " + sources[k].entry_yaml + "\n";
      continue;
    }
    yaml += "  - name: " + nlohmann::json(c.name).dump() + "\n";
    yaml += fmt::format("    task_centre: [{}, {}, {}]\n", format_number(c.task_centre[0]),
                        format_number(c.task_centre[1]), format_number(c.task_centre[2]));
    yaml += indented_machine(c.study->machine->resolved_yaml);
  }
  yaml += task_yaml + goals;
  OptimizerSpec spec;
  spec.seed = study.nsga2.seed;
  spec.algorithm = Nsga2Spec{study.nsga2};
  yaml += "optimizer: " + optimizer_section_yaml(spec) + "\n";
  yaml += "allocation: " + fields_flow_map(allocation) + "\n";
  yaml += "output: " + fields_flow_map(output) + "\n";
  return yaml;
}

}  // namespace

SynthesisStudy load_synthesis_study(const YamlValue& root) {
  root.check_keys({"study", "description", "candidates", "task", "objectives", "constraints",
                   "optimizer", "allocation", "output"});
  SynthesisStudy study;
  study.name = root.required("study").as_string();
  if (auto v = root.optional("description")) study.description = v->as_string();

  // The task alone (no machine): its motions and size.
  DesignTask task;
  DesignStudy task_study;
  std::string task_yaml;
  read_task(root.required("task"), task, task_study, task_yaml);
  study.motion = task_motion_of(task, task_study.task_tilt_deg, task_study.task_yaw_deg);
  SynthesisScale scale = scale_of(task, task_study.task_tilt_deg, task_study.task_yaw_deg);
  scale.masses = needs_masses(root);

  const YamlValue optimizer = root.required("optimizer");
  optimizer.expect_map();
  const YamlValue algorithm = optimizer.required("algorithm");
  if (algorithm.as_string() != "nsga2")
    algorithm.fail("nsga2 (a synthesis runs NSGA-II on every structure)", algorithm.describe());

  std::vector<CandidateSource> sources = read_candidates(root.required("candidates"), scale);
  Screening screening;
  for (CandidateSource& source : sources) screen_candidate(root, study, source, screening);
  // No structure could be loaded: the shared sections are wrong (the same error for all).
  if (!screening.loaded_any && screening.first_error) throw *screening.first_error;
  if (study.searched().empty())
    root.required("candidates")
        .fail(fmt::format("at least one structure that makes the task's motions ({}: {})",
                          study.motion.type(), study.motion.words()),
              "every candidate dropped (" + screening.dropped + ")");
  seed_candidates(study);
  AllocationSection allocation;
  OutputSection output;
  read_allocation_and_output(root, study, allocation, output);
  study.resolved_yaml =
      resolved_synthesis_yaml(study, sources, task_yaml, screening.goals, allocation, output);
  return study;
}

std::string synthesis_fields_markdown(std::string_view section) {
  if (section == "allocation") return fields_markdown(AllocationSection{});
  throw std::invalid_argument("synthesis_fields_markdown: unknown section '" +
                              std::string(section) + "'");
}

}  // namespace pkmopt
