// pkmopt run STUDY.yaml --out DIR [--threads N]
#include <fmt/format.h>

#include <iostream>
#include <memory>

#include "app/commands.hpp"
#include "app/input_error.hpp"
#include "app/study_benchmark.hpp"
#include "app/study_design.hpp"

namespace pkmopt::cli {
namespace {

struct RunCommandOptions {
  std::string study_file;
  std::string out;
  int threads = 0;
};

void run_study(const RunCommandOptions& opt) {
  if (opt.threads < 0)
    throw InputError(fmt::format("--threads: expected an integer >= 0, found {}", opt.threads));
  if (is_design_study_file(opt.study_file)) {
    const DesignStudy design = load_design_study(opt.study_file);
    const RunOutcome outcome = run_optimizer(*design.problem, design.optimizer, opt.threads);
    write_design_outputs(opt.out, design, outcome, opt.threads);
    std::cout << fmt::format("{}: {}: {} design(s), {} evaluations, {:.3f} s, status {}\n",
                             design.name, design.optimizer.algorithm, outcome.front.x.size(),
                             outcome.front.fitness_evaluations, outcome.front.seconds,
                             outcome.status);
    return;
  }
  const BenchmarkStudy study = load_benchmark_study(opt.study_file);
  const RunOutcome outcome = run_optimizer(*study.problem, study.optimizer, opt.threads);
  const ObjectiveSet reference_front =
      study.problem->num_objectives() >= 2 ? study.problem->reference_front(1000) : ObjectiveSet{};
  write_run_outputs(opt.out, study.name, *study.problem, study.optimizer, outcome, opt.threads,
                    study.reference_point, reference_front);
  std::cout << fmt::format("{}: {} on {}: {} design(s), {} evaluations, {:.3f} s, status {}\n",
                           study.name, study.optimizer.algorithm, study.problem->name(),
                           outcome.front.x.size(), outcome.front.fitness_evaluations,
                           outcome.front.seconds, outcome.status);
  if (!outcome.front.message.empty()) std::cerr << "pkmopt: run: " << outcome.front.message << '\n';
}

}  // namespace

void add_run_command(CLI::App& app) {
  auto opt = std::make_shared<RunCommandOptions>();
  CLI::App* cmd = app.add_subcommand(
      "run", "Run a study: optimise the problem of a study file and write the Pareto front");
  cmd->add_option("study", opt->study_file, "Study file (YAML)")->required();
  cmd->add_option("--out", opt->out, "Results folder (pareto.csv, summary.json)")->required();
  cmd->add_option("--threads", opt->threads, "Threads for parallel evaluation (0: all cores)");
  cmd->callback([opt] { run_study(*opt); });
}

}  // namespace pkmopt::cli
