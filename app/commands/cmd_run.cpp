// pkmopt run STUDY.yaml --out DIR [--threads N] [--resume | --force] [--no-progress]
//                             [--worker-timeout S]
//
// The run itself is studies/run_study.hpp (result folder, journal, resume, result files); under
// mpirun, rank 0 runs it and the other ranks evaluate designs (studies/distribute.hpp).
#include <fmt/format.h>

#include <iostream>
#include <memory>

#include "app/commands.hpp"
#include "app/error_report.hpp"
#include "io/format/input_error.hpp"
#include "studies/distribute.hpp"
#include "studies/run_study.hpp"

namespace pkmopt::cli {
namespace {

struct RunCommandOptions {
  std::string study_file;
  StudyRunOptions run;
  bool no_progress = false;
  bool threads_given = false;
};

void report_result(const StudyRunResult& r);

void run_study(const RunCommandOptions& opt) {
  StudyRunOptions options = opt.run;
  options.show_progress = !opt.no_progress;
  if (!(options.worker_timeout_seconds > 0.0))
    throw InputError(
        fmt::format("run: --worker-timeout: expected a positive number of seconds, "
                    "found {}",
                    options.worker_timeout_seconds));
  if (!mpi_launch_from_environment().launched) {
    report_result(run_study_file(opt.study_file, options));
    return;
  }
  // Started by mpirun: one thread per rank unless --threads says otherwise (N ranks on a node
  // would otherwise each start a thread per core).
  const MpiSession session(/*with_workers=*/true);
  options.mpi = &session;
  if (!opt.threads_given && session.size() > 1) options.threads = 1;
  StudyRunResult r;
  try {
    r = run_study_file(opt.study_file, options);
  } catch (const WorkerFault& e) {
    std::cout.flush();
    report("error", e.what());
    session.abort(kExitWorkerFault);  // a silent worker would never reach MPI_Finalize
  }
  if (!r.worker) report_result(r);
}

void report_result(const StudyRunResult& r) {
  if (r.synthesis)
    std::cout << fmt::format(
        "{}: synthesis ({} per structure): {} design(s) on the merged front, {} evaluations ({} "
        "from the cache, {} failed), {:.3f} s, status {}\n{}",
        r.name, r.algorithm, r.designs, r.evaluations, r.from_cache, r.failed, r.wall_seconds,
        r.status, r.candidates_table);
  else if (r.design_study)
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
                (r.synthesis ? "; see candidates.csv (failures) and each structure's "
                               "candidates/NAME/evaluations.csv"
                             : "; see evaluations.csv (columns feasible and failure) and "
                               "summary.json (infeasibility)") +
                "; relax the constraints, widen the parameter ranges or check the "
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
  cmd->add_option(
      "--threads", opt->run.threads,
      "Threads for parallel evaluation (0: all cores; under mpirun: per rank, default 1)");
  cmd->add_flag("--resume", opt->run.resume,
                "Continue the run in --out from its journal (same study file required)");
  cmd->add_flag("--force", opt->run.force, "Replace a previous run in --out");
  cmd->add_flag("--no-progress", opt->no_progress, "No progress bar or log lines on stderr");
  cmd->add_option("--worker-timeout", opt->run.worker_timeout_seconds,
                  "Under mpirun: seconds a worker rank may hold designs without answering before "
                  "the run stops (exit 4, journal intact)")
      ->capture_default_str();
  cmd->callback([opt, cmd] {
    opt->threads_given = cmd->count("--threads") > 0;
    run_study(*opt);
  });
}

}  // namespace pkmopt::cli
