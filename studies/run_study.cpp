#include "studies/run_study.hpp"

#include <fmt/format.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>

#include "io/format/csv.hpp"
#include "io/format/input_error.hpp"
#include "io/format/output_file.hpp"
#include "studies/benchmark_study.hpp"
#include "studies/design_study.hpp"
#include "studies/journal.hpp"
#include "studies/run_folder.hpp"
#include "studies/synthesis_run.hpp"

namespace pkmopt {
namespace {

namespace fs = std::filesystem;

// study.resolved.yaml goes into place with the run's results, never without them.
std::string resolved_path(const StudyRunOptions& opt) {
  return (fs::path(opt.out) / "study.resolved.yaml").string();
}

void fill_journal_options(JournalOptions& options, const StudyRunOptions& opt,
                          const std::string& resolved_yaml, const OptimizerSpec& spec) {
  options.directory = opt.out;
  options.study_hash = study_hash(resolved_yaml);
  options.resume = opt.resume;
  options.expected_requests = spec.expected_requests();
  options.show_progress = opt.show_progress;
  options.threads = opt.threads;
  options.on_batch = opt.progress;
  options.warn = opt.message;
}

// evaluations.csv of a benchmark study: x_j, f_i, constraint rows c_k, feasible.
void benchmark_csv(JournalOptions& options, const Problem& problem) {
  std::string header = "index,generation";
  for (std::size_t j = 0; j < problem.num_variables(); ++j) header += fmt::format(",x_{}", j + 1);
  for (std::size_t i = 0; i < problem.num_objectives(); ++i) header += fmt::format(",f_{}", i + 1);
  for (std::size_t k = 0; k < problem.num_constraints(); ++k) header += fmt::format(",c_{}", k + 1);
  options.csv_header = header + ",feasible,failure";
  const Problem* p = &problem;
  options.csv_row = [p](std::size_t index, const JournalEntry& e) {
    std::string row = std::to_string(index) + ',' +
                      (e.generation >= 0 ? std::to_string(e.generation) : std::string());
    for (double v : e.x) row += "," + format_number(v);
    bool finite = true;
    for (double v : e.fitness) {
      finite = finite && std::isfinite(v);
      row += std::isfinite(v) || std::isinf(v) ? "," + format_number(v) : ",";
    }
    const bool feasible = finite && e.note.empty() && benchmark_feasible(*p, e.fitness);
    return row + (feasible ? ",1," : ",0,") + csv_field(e.note);
  };
}

StudyRunResult run_result(const std::string& name, const OptimizerSpec& spec,
                          const RunOutcome& outcome, const JournaledProblem& journaled,
                          bool resumed, double wall_seconds) {
  StudyRunResult result;
  result.name = name;
  result.algorithm = spec.name();
  result.status = outcome.status;
  result.message = outcome.front.message;
  result.designs = outcome.front.x.size();
  result.evaluations = outcome.front.fitness_evaluations;
  result.from_cache = journaled.cache_hits();
  result.failed = journaled.failed();
  result.optimizer_seconds = outcome.front.seconds;
  result.wall_seconds = wall_seconds;
  result.resumed = resumed;
  return result;
}

// What a rank needs to evaluate the study's designs; the closure keeps the study alive.
StudyEvaluator evaluator_of(std::shared_ptr<const void> owner, const Problem& problem,
                            const JournalOptions& journal, const std::string& resolved_yaml) {
  StudyEvaluator ev;
  ev.study_hash = study_hash(resolved_yaml);
  ev.num_variables = problem.num_variables();
  ev.fitness_size = problem.fitness_size();
  ev.thread_safe = problem.thread_safety() == ThreadSafety::basic;
  ev.evaluate = [owner = std::move(owner), evaluate = journal.evaluate,
                 p = &problem](const std::vector<double>& x) {
    if (evaluate) return evaluate(x);
    JournalEntry entry;
    entry.fitness = p->fitness(x);
    return entry;
  };
  return ev;
}

StudyEvaluator load_evaluator(const YamlValue& root) {
  if (is_synthesis_study(root)) throw InputError("a synthesis study runs on one process");
  if (root.is_map() && root.has("machine")) {
    auto design = std::make_shared<DesignStudy>(load_design_study(root));
    const JournalOptions journal = design_journal_options(*design);
    return evaluator_of(design, design->optimization_problem(), journal, design->resolved_yaml);
  }
  auto study = std::make_shared<BenchmarkStudy>(load_benchmark_study(root));
  return evaluator_of(study, *study->problem, JournalOptions{}, study->resolved_yaml);
}

// Rank 0 of an MPI run with workers: hands the journal's new designs to them.
std::unique_ptr<MpiDispatcher> dispatch_to_workers(const StudyRunOptions& opt,
                                                   const Problem& problem, JournalOptions& journal,
                                                   const std::string& resolved_yaml) {
  if (opt.mpi == nullptr || opt.mpi->size() <= 1) return nullptr;
  auto dispatcher = std::make_unique<MpiDispatcher>(
      evaluator_of(nullptr, problem, journal, resolved_yaml), opt.worker_timeout_seconds);
  journal.evaluate_batch = [d = dispatcher.get()](std::span<const std::vector<double>> xs) {
    return d->evaluate(xs);
  };
  return dispatcher;
}

}  // namespace

StudyRunResult run_study_file(const std::string& study_file, const StudyRunOptions& options) {
  return run_study(YamlValue::load_file(study_file), options);
}

namespace {

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// A design study: the problem of its machine, journaled, optimised, and its result files.
StudyRunResult run_design_study(const YamlValue& root, const StudyRunOptions& opt,
                                std::chrono::steady_clock::time_point wall_start) {
  const DesignStudy design = load_design_study(root);
  const PreparedDirectory prepared = prepare_output_directory(opt);
  const bool resumed = prepared.resumed;
  JournalOptions journal_options = design_journal_options(design);
  fill_journal_options(journal_options, opt, design.resolved_yaml, design.optimizer);
  const std::unique_ptr<MpiDispatcher> workers = dispatch_to_workers(
      opt, design.optimization_problem(), journal_options, design.resolved_yaml);
  JournaledProblem journaled(design.optimization_problem(), journal_options);
  const RunOutcome outcome = run_optimizer(journaled, design.optimizer, opt.threads);
  journaled.finish();
  DesignRunFacts facts;
  facts.threads = opt.threads;
  facts.mpi_ranks = workers ? workers->workers() + 1 : 1;
  facts.resumed = resumed;
  facts.journal = &journaled;
  facts.wall_seconds = seconds_since(wall_start);
  const DesignOutputSummary written = write_design_outputs(
      opt.out, design, outcome, facts, {{resolved_path(opt), design.resolved_yaml}});
  StudyRunResult result =
      run_result(design.name, design.optimizer, outcome, journaled, resumed, facts.wall_seconds);
  result.design_study = true;
  result.designs = written.designs;
  result.status = written.status;
  result.infeasibility = written.infeasibility;
  result.mpi_workers = workers ? workers->workers() : 0;
  return result;
}

// A benchmark study: the problem, journaled, optimised, its front the archive of every
// evaluation, and its result files.
StudyRunResult run_benchmark_study(const YamlValue& root, const StudyRunOptions& opt,
                                   std::chrono::steady_clock::time_point wall_start) {
  const BenchmarkStudy study = load_benchmark_study(root);
  const PreparedDirectory prepared = prepare_output_directory(opt);
  const bool resumed = prepared.resumed;
  JournalOptions journal_options;
  fill_journal_options(journal_options, opt, study.resolved_yaml, study.optimizer);
  benchmark_csv(journal_options, *study.problem);
  const std::unique_ptr<MpiDispatcher> workers =
      dispatch_to_workers(opt, *study.problem, journal_options, study.resolved_yaml);
  JournaledProblem journaled(*study.problem, journal_options);
  RunOutcome outcome = run_optimizer(journaled, study.optimizer, opt.threads);
  journaled.finish();
  nlohmann::json extra;
  if (study.problem->num_objectives() >= 2) {
    // The front is the archive of every evaluation, whichever algorithm ran.
    std::vector<std::vector<double>> xs, fitness;
    for (const JournalEntry& e : journaled.entries())
      if (e.note.empty()) {
        xs.push_back(e.x);
        fitness.push_back(e.fitness);
      }
    ArchivedFront archived = archive_front(*study.problem, xs, fitness, study.front_size);
    outcome.front.x = std::move(archived.front.x);
    outcome.front.fitness = std::move(archived.front.fitness);
    extra["feasible_evaluations"] = archived.feasible_evaluations;
    extra["archive_size"] = archived.archive_size;
  }
  extra["front_rule"] = front_rule_text(study.front_size, study.problem->num_objectives());
  const ObjectiveSet reference_front =
      study.problem->num_objectives() >= 2 ? study.problem->reference_front(1000) : ObjectiveSet{};
  extra["resumed"] = resumed;
  extra["mpi_ranks"] = workers ? workers->workers() + 1 : 1;
  extra["evaluations_from_cache"] = journaled.cache_hits();
  extra["evaluations_distinct"] = journaled.entries().size();
  extra["evaluations_loaded_from_journal"] = journaled.loaded_entries();
  extra["evaluations_new"] = journaled.entries().size() - journaled.loaded_entries();
  extra["evaluations_failed"] = journaled.failed();
  extra["wall_seconds"] = seconds_since(wall_start);
  write_run_outputs(opt.out, study.name, *study.problem, study.optimizer, outcome, opt.threads,
                    study.reference_point, reference_front, extra,
                    {{resolved_path(opt), study.resolved_yaml}});
  StudyRunResult result = run_result(study.name, study.optimizer, outcome, journaled, resumed,
                                     seconds_since(wall_start));
  result.problem = study.problem->name();
  result.mpi_workers = workers ? workers->workers() : 0;
  return result;
}

}  // namespace

StudyRunResult run_study(const YamlValue& root, const StudyRunOptions& options) {
  StudyRunOptions opt = options;
  if (!opt.message)
    opt.message = [](const std::string& text) { std::cerr << "pkmopt: run: " << text << '\n'; };
  const auto wall_start = std::chrono::steady_clock::now();
  if (opt.threads < 0 || opt.threads > kMaxStudyThreads)
    throw InputError(
        fmt::format("--threads: expected an integer in [0, {}] (0: all cores), found {}",
                    kMaxStudyThreads, opt.threads));
  if (opt.resume && opt.force)
    throw InputError("--resume and --force: expected one of them, found both");
  // The other ranks wait for rank 0's word whatever the study: a rank that ended on its own with
  // an error would make mpirun stop rank 0 before it has said why. A synthesis study gives them
  // nothing to load, and rank 0 refuses it.
  if (opt.mpi != nullptr && opt.mpi->rank() > 0) {
    serve_as_worker([&root] { return load_evaluator(root); }, opt.threads);
    StudyRunResult worker;
    worker.worker = true;
    return worker;
  }
  if (is_synthesis_study(root) && opt.mpi != nullptr && opt.mpi->size() > 1)
    throw InputError(fmt::format(
        "mpirun: expected one process for a synthesis study (its structures are searched one "
        "after another on the threads of one process), found {} processes",
        opt.mpi->size()));
  if (is_synthesis_study(root)) return run_synthesis_study(root, opt, wall_start);
  if (root.is_map() && root.has("machine")) return run_design_study(root, opt, wall_start);
  return run_benchmark_study(root, opt, wall_start);
}

}  // namespace pkmopt
