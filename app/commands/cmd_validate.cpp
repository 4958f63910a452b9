// pkmopt validate STUDY.yaml: checks a design or benchmark study file without running it.
//
// Prints a short summary (free parameters, objectives, constraints, task poses, optimizer) and
// exits 0, or prints the exact error (file:line:col: key: expected X, found Y) and exits 2.
#include <fmt/format.h>

#include <iostream>
#include <memory>

#include "app/commands.hpp"
#include "studies/benchmark_study.hpp"
#include "studies/design_study.hpp"

namespace pkmopt::cli {
namespace {

std::string optimizer_text(const OptimizerSpec& spec) {
  if (const Nsga2Options* nsga2 = spec.nsga2())
    return fmt::format("{} (population {}, generations {}, seed {}: {} evaluations)", spec.name(),
                       nsga2->population, nsga2->generations, spec.seed,
                       nsga2->population * (nsga2->generations + 1));
  return fmt::format("{} (seed {})", spec.name(), spec.seed);
}

void validate_study(const std::string& path) {
  if (is_design_study_file(path)) {
    const DesignStudy study = load_design_study(path);
    std::string text =
        fmt::format("{}: design study '{}' (model {}) is valid\n", path, study.name, study.model);
    std::string free;
    std::size_t n_free = 0;
    for (const StudyParameter& p : study.parameters) {
      if (!p.free()) continue;
      ++n_free;
      free += fmt::format(" {} [{}, {}]", p.name, p.min, p.max);
    }
    text += fmt::format("  free parameters ({}):{}", n_free, free);
    text += fmt::format("\n  objectives ({}):", study.objectives().size());
    for (const DesignObjective& o : study.objectives())
      text += fmt::format(" {} {}", o.sense == Sense::maximize ? "maximize" : "minimize",
                          design_metric_name(o.metric));
    text += fmt::format("\n  constraints ({}):",
                        study.constraints().size() + (study.require_reachable() ? 1 : 0));
    if (study.require_reachable()) text += " task_reachable";
    for (const DesignConstraint& c : study.constraints())
      text += fmt::format(" {} {} {}", design_metric_name(c.metric),
                          c.relation == Relation::less_equal ? "<=" : ">=", c.bound);
    if (study.problem && study.problem->spec().actuator_catalog) {
      const ActuatorCatalog& catalog = *study.problem->spec().actuator_catalog;
      text += fmt::format(
          "\n  actuators: each design's cheapest entry of catalog '{}' ({} entries, "
          "{}) that carries its legs",
          catalog.name, catalog.entries.size(),
          catalog.entries.front().cost ? "by cost" : "by force rating");
    }
    const std::size_t poses = study.task().poses.size();
    text +=
        fmt::format("\n  task: {} poses ({} positions x {} orientations)\n", poses,
                    study.task_positions, poses / std::max<std::size_t>(1, study.task_positions));
    text += fmt::format("  optimizer: {}, {} formulation\n", optimizer_text(study.optimizer),
                        study.aggregate() ? "aggregate" : "smooth");
    std::cout << text;
    return;
  }
  const BenchmarkStudy study = load_benchmark_study(path);
  std::cout << fmt::format(
      "{}: benchmark study '{}' is valid\n  problem: {} ({} variables, {} objectives, {} "
      "constraints)\n  optimizer: {}\n",
      path, study.name, study.problem->name(), study.problem->num_variables(),
      study.problem->num_objectives(), study.problem->num_constraints(),
      optimizer_text(study.optimizer));
}

}  // namespace

void add_validate_command(CLI::App& app) {
  auto path = std::make_shared<std::string>();
  CLI::App* cmd =
      app.add_subcommand("validate", "Check a study file (design or benchmark) without running it");
  cmd->add_option("study", *path, "Study file (YAML)")->required();
  cmd->callback([path] { validate_study(*path); });
}

}  // namespace pkmopt::cli
