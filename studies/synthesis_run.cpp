#include "studies/synthesis_run.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <mutex>
#include <numeric>

#include "io/format/input_error.hpp"
#include "optimizer/archive.hpp"
#include "optimizer/indicators.hpp"
#include "optimizer/nsga2.hpp"
#include "studies/run_folder.hpp"
#include "studies/synthesis_outputs.hpp"

namespace pkmopt {
namespace {

// A problem that keeps the feasible non-dominated objective vectors of every evaluation.
class ArchivingProblem final : public ForwardingProblem {
 public:
  explicit ArchivingProblem(const Problem& inner) : ForwardingProblem(inner) {}

  std::vector<double> fitness(const std::vector<double>& x) const override {
    std::vector<double> f = ForwardingProblem::fitness(x);
    record(f);
    return f;
  }
  std::vector<std::vector<double>> batch_fitness(std::span<const std::vector<double>> xs,
                                                 int threads) const override {
    // The inner problem's own batch (a journal records the batch in its order, whatever the
    // threads); ForwardingProblem would evaluate the designs one by one through fitness().
    std::vector<std::vector<double>> fs = inner().batch_fitness(xs, threads);
    for (const std::vector<double>& f : fs) record(f);
    return fs;
  }
  StructureFront front() const {
    const std::lock_guard lock(mutex_);
    return archive_.objective_vectors();
  }
  std::size_t feasible() const {
    const std::lock_guard lock(mutex_);
    return feasible_;
  }

 private:
  void record(const std::vector<double>& f) const {
    const std::size_t m = num_objectives();
    for (std::size_t k = 0; k < f.size(); ++k)
      if (k < m ? !std::isfinite(f[k]) : !(f[k] <= 0.0)) return;
    const std::lock_guard lock(mutex_);
    ++feasible_;
    archive_.insert({}, std::vector<double>(f.begin(), f.begin() + static_cast<std::ptrdiff_t>(m)));
  }
  mutable std::mutex mutex_;
  mutable ParetoArchive archive_;
  mutable std::size_t feasible_ = 0;
};

// Hypervolume of the points below the reference (others add nothing).
double clipped_hypervolume(const std::vector<std::vector<double>>& points,
                           const std::vector<double>& reference) {
  std::vector<std::vector<double>> inside;
  for (const std::vector<double>& p : points) {
    bool below = true;
    for (std::size_t i = 0; i < p.size(); ++i) below = below && p[i] < reference[i];
    if (below) inside.push_back(p);
  }
  if (inside.empty()) return 0.0;
  std::vector<std::vector<double>> front;
  for (std::size_t k : non_dominated_indices(inside)) front.push_back(inside[k]);
  return hypervolume(front, reference);
}

}  // namespace

long long AllocationPlan::planned() const {
  if (structures.empty()) return 0;
  const long long P = static_cast<long long>(population);
  long long total = static_cast<long long>(structures.front()) * P;
  for (std::size_t r = 0; r < structures.size(); ++r)
    total += static_cast<long long>(structures[r] * generations[r]) * P;
  return total;
}

AllocationPlan plan_allocation(std::size_t n, std::size_t population, std::size_t generations,
                               const SynthesisAllocation& allocation) {
  AllocationPlan plan;
  plan.population = population;
  const long long P = static_cast<long long>(population);
  plan.budget = static_cast<long long>(n) * P * static_cast<long long>(generations + 1);
  if (n == 0) return plan;
  if (allocation.rule == "equal" || n == 1) {
    plan.structures = {n};
    plan.generations = {generations};
    return plan;
  }
  const std::size_t floor = std::min(allocation.floor_generations, generations);
  plan.structures = {n};
  plan.generations = {floor};
  std::vector<std::size_t> later;
  for (std::size_t s = (n + 1) / 2;; s = (s + 1) / 2) {
    later.push_back(s);
    if (s == 1) break;
  }
  const long long rest =
      plan.budget - static_cast<long long>(n) * P * static_cast<long long>(floor + 1);
  const long long rounds = static_cast<long long>(later.size());
  for (std::size_t s : later) {
    plan.structures.push_back(s);
    plan.generations.push_back(
        static_cast<std::size_t>(std::max(0LL, rest / (rounds * static_cast<long long>(s) * P))));
  }
  return plan;
}

StructureScores score_structures(const std::vector<StructureFront>& fronts) {
  StructureScores scores;
  scores.exclusive.assign(fronts.size(), 0.0);
  scores.own.assign(fronts.size(), 0.0);
  std::vector<std::vector<double>> all;
  for (const StructureFront& f : fronts) all.insert(all.end(), f.begin(), f.end());
  if (all.empty()) return scores;
  std::vector<std::vector<double>> merged;
  for (std::size_t k : non_dominated_indices(all)) merged.push_back(all[k]);
  const std::size_t m = merged.front().size();
  std::vector<double> ideal(m, std::numeric_limits<double>::infinity());
  std::vector<double> nadir(m, -std::numeric_limits<double>::infinity());
  for (const std::vector<double>& p : merged)
    for (std::size_t i = 0; i < m; ++i) {
      ideal[i] = std::min(ideal[i], p[i]);
      nadir[i] = std::max(nadir[i], p[i]);
    }
  auto normalised = [&](const std::vector<std::vector<double>>& points) {
    std::vector<std::vector<double>> out = points;
    for (std::vector<double>& p : out)
      for (std::size_t i = 0; i < m; ++i) {
        const double range = nadir[i] - ideal[i];
        p[i] = (p[i] - ideal[i]) / (range > 0.0 ? range : 1.0);
      }
    return out;
  };
  const std::vector<double> reference(m, 1.1);
  const double whole = clipped_hypervolume(normalised(merged), reference);
  for (std::size_t s = 0; s < fronts.size(); ++s) {
    std::vector<std::vector<double>> others;
    for (std::size_t t = 0; t < fronts.size(); ++t)
      if (t != s) others.insert(others.end(), fronts[t].begin(), fronts[t].end());
    scores.exclusive[s] = std::max(0.0, whole - clipped_hypervolume(normalised(others), reference));
    scores.own[s] = clipped_hypervolume(normalised(fronts[s]), reference);
  }
  return scores;
}

SynthesisSearch search_structures(const SynthesisStudy& study,
                                  const std::vector<const Problem*>& problems, int threads,
                                  const std::function<void(const std::string&)>& log) {
  const auto start = std::chrono::steady_clock::now();
  const std::vector<std::size_t> searched = study.searched();
  if (problems.size() != searched.size())
    throw std::invalid_argument("search_structures: one problem per searched candidate");
  const std::size_t n = searched.size();
  SynthesisSearch result;
  result.plan = plan_allocation(n, study.nsga2.population, study.nsga2.generations,
                                study.allocation);
  std::vector<std::unique_ptr<ArchivingProblem>> archived;
  std::vector<std::unique_ptr<Nsga2Search>> searches(n);
  result.runs.resize(n);
  for (std::size_t k = 0; k < n; ++k) {
    archived.push_back(std::make_unique<ArchivingProblem>(*problems[k]));
    result.runs[k].candidate = searched[k];
  }
  std::vector<std::size_t> alive(n);
  std::iota(alive.begin(), alive.end(), 0);
  for (std::size_t r = 0; r < result.plan.structures.size(); ++r) {
    std::string line = fmt::format("round {} of {}:", r + 1, result.plan.structures.size());
    for (std::size_t k : alive) {
      const SynthesisCandidate& c = study.candidates[searched[k]];
      if (!searches[k]) {
        Nsga2Options options = study.nsga2;
        options.seed = c.seed;
        options.threads = threads;
        searches[k] = std::make_unique<Nsga2Search>(*archived[k], options);
      }
      searches[k]->advance(result.plan.generations[r]);
      ++result.runs[k].rounds;
      line += fmt::format(" {} {} generations,", c.name, searches[k]->generations());
    }
    std::vector<StructureFront> fronts;
    for (std::size_t k = 0; k < n; ++k) fronts.push_back(archived[k]->front());
    const StructureScores scores = score_structures(fronts);
    for (std::size_t k : alive) result.runs[k].exclusive.push_back(scores.exclusive[k]);
    line.back() = ';';
    line += " exclusive hypervolume";
    for (std::size_t k : alive)
      line += fmt::format(" {} {:.3f}", study.candidates[searched[k]].name, scores.exclusive[k]);
    if (r + 1 < result.plan.structures.size()) {
      std::vector<std::size_t> order = alive;
      std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
        if (scores.exclusive[a] != scores.exclusive[b])
          return scores.exclusive[a] > scores.exclusive[b];
        if (scores.own[a] != scores.own[b]) return scores.own[a] > scores.own[b];
        return archived[a]->feasible() > archived[b]->feasible();
      });
      order.resize(std::min(order.size(), result.plan.structures[r + 1]));
      std::sort(order.begin(), order.end());
      for (std::size_t k : alive)
        if (!std::binary_search(order.begin(), order.end(), k)) result.runs[k].kept = false;
      alive = order;
      line += "; continuing:";
      for (std::size_t k : alive) line += " " + study.candidates[searched[k]].name;
    }
    if (log) log(line);
  }
  for (std::size_t k = 0; k < n; ++k) {
    StructureRun& run = result.runs[k];
    run.generations = searches[k]->generations();
    run.evaluations = searches[k]->fitness_evaluations();
    run.front = searches[k]->front();
  }
  result.seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

StudyRunResult run_synthesis_study(const YamlValue& root, const StudyRunOptions& opt,
                                   std::chrono::steady_clock::time_point wall_start) {
  SynthesisStudy study = load_synthesis_study(root);
  const PreparedDirectory prepared = prepare_output_directory(opt);
  std::vector<std::unique_ptr<JournaledProblem>> journals;
  std::vector<const Problem*> problems;
  for (std::size_t k : study.searched()) {
    const SynthesisCandidate& c = study.candidates[k];
    const std::string directory = opt.out + "/candidates/" + c.name;
    std::filesystem::create_directories(directory);
    JournalOptions journal = design_journal_options(*c.study);
    journal.directory = directory;
    journal.study_hash = study_hash(c.study->resolved_yaml);
    journal.resume = opt.resume;
    journal.threads = opt.threads;
    journal.on_batch = opt.progress;
    journal.warn = opt.message;
    journals.push_back(
        std::make_unique<JournaledProblem>(c.study->optimization_problem(), std::move(journal)));
    problems.push_back(journals.back().get());
  }
  const SynthesisSearch search = search_structures(
      study, problems, opt.threads,
      opt.show_progress ? opt.message : std::function<void(const std::string&)>());
  for (const auto& journal : journals) journal->finish();
  SynthesisFacts facts;
  facts.threads = opt.threads;
  facts.resumed = prepared.resumed;
  for (const auto& journal : journals) facts.journals.push_back(journal.get());
  facts.wall_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
  const SynthesisOutputSummary written =
      write_synthesis_outputs(opt.out, study, search, facts,
                              {{opt.out + "/study.resolved.yaml", study.resolved_yaml}});
  StudyRunResult result;
  result.design_study = true;
  result.synthesis = true;
  result.name = study.name;
  result.algorithm = "nsga2";
  result.status = written.status;
  result.infeasibility = written.infeasibility;
  result.designs = written.designs;
  result.candidates_table = written.table;
  for (const StructureRun& run : search.runs) result.evaluations += run.evaluations;
  for (const auto& journal : journals) {
    result.from_cache += static_cast<std::size_t>(journal->cache_hits());
    result.failed += static_cast<std::size_t>(journal->failed());
  }
  result.optimizer_seconds = search.seconds;
  result.wall_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
  result.resumed = prepared.resumed;
  return result;
}

}  // namespace pkmopt
