// pkmopt run STUDY.yaml --out DIR [--threads N] [--resume | --force] [--no-progress]
//
// The run itself is studies/run_study.hpp (result folder, journal, resume, result files).
#include <fmt/format.h>

#include <iostream>
#include <memory>

#include "app/commands.hpp"
#include "io/input_error.hpp"
#include "studies/run_study.hpp"

namespace pkmopt::cli {
namespace {

struct RunCommandOptions {
  std::string study_file;
  StudyRunOptions run;
  bool no_progress = false;
};

void run_study(const RunCommandOptions& opt) {
  StudyRunOptions options = opt.run;
  options.show_progress = !opt.no_progress;
  const StudyRunResult r = run_study_file(opt.study_file, options);
  if (r.design_study)
    std::cout << fmt::format(
        "{}: {}: {} design(s), {} evaluations ({} from the cache, {} failed), {:.3f} s, status "
        "{}\n",
        r.name, r.algorithm, r.designs, r.evaluations, r.from_cache, r.failed, r.wall_seconds,
        r.status);
  else
    std::cout << fmt::format("{}: {} on {}: {} design(s), {} evaluations, {:.3f} s, status {}\n",
                             r.name, r.algorithm, r.problem, r.designs, r.evaluations,
                             r.optimizer_seconds, r.status);
  // A run that ends without a usable result says so with exit status 3 (the files are written).
  const bool probably_wrong = r.status == "no_feasible_design" || r.status == "infeasible" ||
                              r.status == "diverging" || r.status == "evaluation_error" ||
                              r.status == "failed";
  if (!probably_wrong) {
    if (!r.message.empty()) std::cerr << "pkmopt: run: " << r.message << '\n';
    return;
  }
  std::string what =
      r.status == "no_feasible_design"
          ? "no feasible design: every evaluated design failed or violates a constraint" +
                (r.infeasibility.empty() ? std::string() : " (" + r.infeasibility + ")") +
                "; see evaluations.csv (columns feasible and failure) and summary.json "
                "(infeasibility); relax the constraints, widen the parameter ranges or check the "
                "task"
          : "the solver ended with status " + r.status + ": its point is not a usable result";
  if (!r.message.empty()) what += " (" + r.message + ")";
  throw ProbablyWrongResult("run: " + what);
}

}  // namespace

void add_run_command(CLI::App& app) {
  auto opt = std::make_shared<RunCommandOptions>();
  CLI::App* cmd = app.add_subcommand(
      "run", "Run a study: optimise the problem of a study file and write the Pareto front");
  cmd->add_option("study", opt->study_file, "Study file (YAML)")->required();
  cmd->add_option("--out", opt->run.out,
                  "Results folder (pareto.csv, summary.json, journal.txt...)")
      ->required();
  cmd->add_option("--threads", opt->run.threads, "Threads for parallel evaluation (0: all cores)");
  cmd->add_flag("--resume", opt->run.resume,
                "Continue the run in --out from its journal (same study file required)");
  cmd->add_flag("--force", opt->run.force, "Replace a previous run in --out");
  cmd->add_flag("--no-progress", opt->no_progress, "No progress bar or log lines on stderr");
  cmd->callback([opt] { run_study(*opt); });
}

}  // namespace pkmopt::cli
