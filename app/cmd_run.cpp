// pkmopt run STUDY.yaml --out DIR [--threads N] [--resume | --force] [--no-progress]
//
// Every evaluation goes through a JournaledProblem (app/study_journal.hpp): DIR/journal.txt and
// DIR/evaluations.csv grow as the run goes, identical designs come from the cache, and
// `--resume` continues a killed run from its journal. A DIR that holds a run (journal.txt,
// summary.json or pareto.csv) is never overwritten without --resume or --force.
#include <fmt/format.h>

#include <chrono>
#include <filesystem>
#include <iostream>
#include <memory>

#include "app/commands.hpp"
#include "app/csv.hpp"
#include "app/input_error.hpp"
#include "app/output_file.hpp"
#include "app/study_benchmark.hpp"
#include "app/study_design.hpp"
#include "app/study_journal.hpp"

namespace pkmopt::cli {
namespace {

namespace fs = std::filesystem;

struct RunCommandOptions {
  std::string study_file;
  std::string out;
  int threads = 0;
  bool resume = false;
  bool force = false;
  bool no_progress = false;
};

// Checks DIR against --resume / --force and creates it. Returns true when a journal is resumed.
bool prepare_output_directory(const RunCommandOptions& opt) {
  const fs::path dir(opt.out);
  const bool has_journal = fs::exists(dir / "journal.txt");
  const bool holds_run =
      has_journal || fs::exists(dir / "summary.json") || fs::exists(dir / "pareto.csv");
  if (holds_run && !opt.resume && !opt.force)
    throw InputError(fmt::format(
        "--out: '{}' holds a previous run ({}); continue it with --resume or replace it with "
        "--force",
        opt.out, has_journal ? "journal.txt" : "summary.json or pareto.csv"));
  if (opt.force) {
    for (const char* name : {"journal.txt", "evaluations.csv", "pareto.csv", "pareto.json",
                             "summary.json", "study.resolved.yaml"})
      fs::remove(dir / name);
    if (fs::is_directory(dir / "designs"))
      for (const fs::directory_entry& e : fs::directory_iterator(dir / "designs"))
        if (e.path().extension() == ".yaml" && e.path().filename().string().starts_with("d"))
          fs::remove(e.path());
  }
  std::error_code error;
  fs::create_directories(dir, error);
  if (error || !fs::is_directory(dir))
    throw InputError(fmt::format("--out: cannot create the folder '{}': {}", opt.out,
                                 error ? error.message() : "not a folder"));
  if (opt.resume && !has_journal)
    std::cerr << fmt::format("pkmopt: run: no journal in '{}': starting a new run\n", opt.out);
  return opt.resume && has_journal;
}

long long expected_requests(const OptimizerSpec& spec) {
  if (spec.algorithm == "nsga2")
    return static_cast<long long>(spec.nsga2.population * (spec.nsga2.generations + 1));
  return 0;
}

void fill_journal_options(JournalOptions& options, const RunCommandOptions& opt,
                          const std::string& resolved_yaml, const OptimizerSpec& spec) {
  options.directory = opt.out;
  options.study_hash = study_hash(resolved_yaml);
  options.resume = opt.resume;
  options.expected_requests = expected_requests(spec);
  options.show_progress = !opt.no_progress;
  options.threads = opt.threads;
}

// evaluations.csv of a benchmark study: x_j, f_i, constraint rows c_k, feasible.
void benchmark_csv(JournalOptions& options, const Problem& problem) {
  std::string header = "index";
  for (std::size_t j = 0; j < problem.num_variables(); ++j) header += fmt::format(",x_{}", j + 1);
  for (std::size_t i = 0; i < problem.num_objectives(); ++i) header += fmt::format(",f_{}", i + 1);
  for (std::size_t k = 0; k < problem.num_constraints(); ++k) header += fmt::format(",c_{}", k + 1);
  options.csv_header = header + ",feasible,failure";
  const Problem* p = &problem;
  options.csv_row = [p](std::size_t index, const JournalEntry& e) {
    std::string row = std::to_string(index);
    for (double v : e.x) row += "," + format_number(v);
    bool finite = true;
    for (double v : e.fitness) {
      finite = finite && std::isfinite(v);
      row += std::isfinite(v) || std::isinf(v) ? "," + format_number(v) : ",";
    }
    const bool feasible = finite && e.note.empty() && constraint_violation(*p, e.fitness) == 0.0;
    return row + (feasible ? ",1," : ",0,") + csv_field(e.note);
  };
}

void run_study(const RunCommandOptions& opt) {
  const auto wall_start = std::chrono::steady_clock::now();
  if (opt.threads < 0)
    throw InputError(fmt::format("--threads: expected an integer >= 0, found {}", opt.threads));
  if (opt.resume && opt.force)
    throw InputError("--resume and --force: expected one of them, found both");
  if (is_design_study_file(opt.study_file)) {
    const DesignStudy design = load_design_study(opt.study_file);
    const bool resumed = prepare_output_directory(opt);
    JournalOptions options = design_journal_options(design);
    fill_journal_options(options, opt, design.resolved_yaml, design.optimizer);
    JournaledProblem journaled(design.optimization_problem(), options);
    write_file_atomically((fs::path(opt.out) / "study.resolved.yaml").string(),
                          design.resolved_yaml);
    const RunOutcome outcome = run_optimizer(journaled, design.optimizer, opt.threads);
    journaled.finish();
    DesignRunFacts facts;
    facts.threads = opt.threads;
    facts.resumed = resumed;
    facts.journal = &journaled;
    facts.wall_seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
    write_design_outputs(opt.out, design, outcome, facts);
    std::cout << fmt::format(
        "{}: {}: {} design(s), {} evaluations ({} from the cache, {} failed), {:.3f} s, status "
        "{}\n",
        design.name, design.optimizer.algorithm, outcome.front.x.size(),
        outcome.front.fitness_evaluations, journaled.cache_hits(), journaled.failed(),
        facts.wall_seconds, outcome.status);
    if (!outcome.front.message.empty())
      std::cerr << "pkmopt: run: " << outcome.front.message << '\n';
    return;
  }
  const BenchmarkStudy study = load_benchmark_study(opt.study_file);
  const bool resumed = prepare_output_directory(opt);
  JournalOptions options;
  fill_journal_options(options, opt, study.resolved_yaml, study.optimizer);
  benchmark_csv(options, *study.problem);
  JournaledProblem journaled(*study.problem, options);
  write_file_atomically((fs::path(opt.out) / "study.resolved.yaml").string(), study.resolved_yaml);
  const RunOutcome outcome = run_optimizer(journaled, study.optimizer, opt.threads);
  journaled.finish();
  const ObjectiveSet reference_front =
      study.problem->num_objectives() >= 2 ? study.problem->reference_front(1000) : ObjectiveSet{};
  nlohmann::json extra;
  extra["resumed"] = resumed;
  extra["evaluations_from_cache"] = journaled.cache_hits();
  extra["evaluations_distinct"] = journaled.entries().size();
  extra["evaluations_loaded_from_journal"] = journaled.loaded_entries();
  extra["evaluations_new"] = journaled.entries().size() - journaled.loaded_entries();
  extra["evaluations_failed"] = journaled.failed();
  extra["wall_seconds"] =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
  write_run_outputs(opt.out, study.name, *study.problem, study.optimizer, outcome, opt.threads,
                    study.reference_point, reference_front, extra);
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
  cmd->add_option("--out", opt->out, "Results folder (pareto.csv, summary.json, journal.txt...)")
      ->required();
  cmd->add_option("--threads", opt->threads, "Threads for parallel evaluation (0: all cores)");
  cmd->add_flag("--resume", opt->resume,
                "Continue the run in --out from its journal (same study file required)");
  cmd->add_flag("--force", opt->force, "Replace a previous run in --out");
  cmd->add_flag("--no-progress", opt->no_progress, "No progress bar or log lines on stderr");
  cmd->callback([opt] { run_study(*opt); });
}

}  // namespace pkmopt::cli
