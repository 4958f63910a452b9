// The synthesis search (the budget's rounds, the ranking, each structure's own NSGA-II) and its
// result folder through `pkmopt run`.
#include "studies/synthesis_run.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <mutex>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "io/format/input_error.hpp"
#include "io/machine/machine_file.hpp"
#include "optimizer/archive.hpp"
#include "optimizer/indicators.hpp"
#include "optimizer/nsga2.hpp"
#include "tests/scratch_dir.hpp"

namespace pkmopt {
namespace {

namespace fs = std::filesystem;

TEST(SynthesisRun, SuccessiveHalvingPlanByHand) {
  SynthesisAllocation halving;
  halving.floor_generations = 15;
  // 6 structures, P = 40, G = 60: B = 6 * 40 * 61 = 14640; the floor spends 6 * 40 * 16 = 3840;
  // the rest, 10800, goes to rounds of 3, 2 and 1 structures, 3600 each: 30, 45 and 90
  // generations.
  const AllocationPlan plan = plan_allocation(6, 40, 60, halving);
  EXPECT_EQ(plan.budget, 14640);
  EXPECT_EQ(plan.structures, (std::vector<std::size_t>{6, 3, 2, 1}));
  EXPECT_EQ(plan.generations, (std::vector<std::size_t>{15, 30, 45, 90}));
  EXPECT_EQ(plan.planned(), 14640);
  // 5 structures, P = 20, G = 30, floor 8: B = 3100, floor 900, rounds of 3, 2, 1 share 2200:
  // floor(2200 / (3 * 3 * 20)) = 12, floor(2200 / (3 * 2 * 20)) = 18, floor(2200 / 60) = 36.
  halving.floor_generations = 8;
  const AllocationPlan five = plan_allocation(5, 20, 30, halving);
  EXPECT_EQ(five.structures, (std::vector<std::size_t>{5, 3, 2, 1}));
  EXPECT_EQ(five.generations, (std::vector<std::size_t>{8, 12, 18, 36}));
  EXPECT_LE(five.planned(), five.budget);
  EXPECT_EQ(five.planned(), 100 + 20 * (5 * 8 + 3 * 12 + 2 * 18 + 36));
  // One structure, or the equal rule: the optimizer's generations for each.
  EXPECT_EQ(plan_allocation(1, 40, 60, halving).generations, (std::vector<std::size_t>{60}));
  SynthesisAllocation equal;
  equal.rule = "equal";
  const AllocationPlan same = plan_allocation(4, 10, 12, equal);
  EXPECT_EQ(same.structures, (std::vector<std::size_t>{4}));
  EXPECT_EQ(same.generations, (std::vector<std::size_t>{12}));
  EXPECT_EQ(same.planned(), same.budget);
  // A floor of every generation leaves nothing to move.
  halving.floor_generations = 12;
  const AllocationPlan all_floor = plan_allocation(4, 10, 12, halving);
  EXPECT_EQ(all_floor.generations, (std::vector<std::size_t>{12, 0, 0}));
}

TEST(SynthesisRun, ScoresByHand) {
  // Fronts (minimised): A (0, 1), B (1, 0), C (0.5, 0.5), D (0.9, 0.9) dominated by C.
  // Normalised to the merged front {A, C, B} (ideal 0, nadir 1), reference 1.1:
  //   HV(A, C, B) = 0.5 * 0.1 + 0.5 * 0.6 + 0.1 * 1.1 = 0.46
  //   without A:  0.6 * 0.6 + 0.1 * 1.1 - 0.1 * 0.6 = 0.41  -> exclusive 0.05
  //   without C:  A, B and D: 0.11 + 0.11 + 0.04 - 0.01 - 0.02 - 0.02 + 0.01 = 0.22
  //                                                       -> exclusive 0.24
  //   without D:  the same front                           -> exclusive 0
  // and D's own front: (1.1 - 0.9)^2 = 0.04.
  const StructureScores s = score_structures({{{0, 1}}, {{1, 0}}, {{0.5, 0.5}}, {{0.9, 0.9}}});
  EXPECT_NEAR(s.exclusive[0], 0.05, 1e-12);
  EXPECT_NEAR(s.exclusive[1], 0.05, 1e-12);
  EXPECT_NEAR(s.exclusive[2], 0.24, 1e-12);
  EXPECT_NEAR(s.exclusive[3], 0.0, 1e-12);
  EXPECT_NEAR(s.own[3], 0.04, 1e-12);
  EXPECT_NEAR(s.own[0], 0.11, 1e-12);  // (1.1 - 0) * (1.1 - 1)
  // No feasible design anywhere: every score 0.
  const StructureScores none = score_structures({{}, {}});
  EXPECT_EQ(none.exclusive, (std::vector<double>{0, 0}));
}

// A problem that keeps every feasible objective vector it evaluates.
class Recording final : public ForwardingProblem {
 public:
  using ForwardingProblem::ForwardingProblem;
  std::vector<std::vector<double>> batch_fitness(std::span<const std::vector<double>> xs,
                                                 int threads) const override {
    auto fs = inner().batch_fitness(xs, threads);
    for (const auto& f : fs) keep(f);
    return fs;
  }
  std::vector<double> fitness(const std::vector<double>& x) const override {
    auto f = ForwardingProblem::fitness(x);
    keep(f);
    return f;
  }
  std::vector<std::vector<double>> feasible;

 private:
  void keep(const std::vector<double>& f) const {
    const std::size_t m = num_objectives();
    for (std::size_t k = 0; k < f.size(); ++k)
      if (k < m ? !std::isfinite(f[k]) : !(f[k] <= 0.0)) return;
    const std::lock_guard lock(mutex_);
    const_cast<Recording*>(this)->feasible.emplace_back(f.begin(), f.begin() + m);
  }
  mutable std::mutex mutex_;
};

double front_hypervolume(const std::vector<std::vector<double>>& points,
                         const std::vector<double>& reference) {
  std::vector<std::vector<double>> inside;
  for (const auto& p : points)
    if (p[0] < reference[0] && p[1] < reference[1]) inside.push_back(p);
  if (inside.empty()) return 0.0;
  std::vector<std::vector<double>> front;
  for (std::size_t k : non_dominated_indices(inside)) front.push_back(inside[k]);
  return hypervolume(front, reference);
}

const char* kStudy = R"(study: small
candidates: [hexapod, delta, linear_delta]
task:
  region: {shape: box, centre: [0, 0, 0], size: [0.3, 0.3, 0.2], points: [2, 2, 2]}
  wrench: [300, 300, -1000, 0, 0, 0]
objectives:
  - maximize: stiffness_min
  - minimize: machine_size
constraints:
  - task_reachable
  - {metric: singularity_margin, min: 0.02}
optimizer: {algorithm: nsga2, population: 12, generations: 10, seed: 5}
allocation: {floor_generations: 3}
)";

TEST(SynthesisRun, EachStructureContinuesItsOwnRunAndLosesNothing) {
  const SynthesisStudy study = load_synthesis_study(YamlValue::load_string(kStudy, "small.yaml"));
  ASSERT_EQ(study.searched().size(), 3u);
  std::vector<std::unique_ptr<Recording>> recorders;
  std::vector<const Problem*> problems;
  for (std::size_t k : study.searched()) {
    recorders.push_back(
        std::make_unique<Recording>(study.candidates[k].study->optimization_problem()));
    problems.push_back(recorders.back().get());
  }
  const SynthesisSearch search = search_structures(study, problems, 1, {});
  // Rounds: 3 structures x 3 generations, then 2 x 8, then 1 x 16 (B = 396, floor 144, rest 252
  // over 2 rounds: floor(126 / (2 * 12)) = 5 ... as plan_allocation says).
  EXPECT_EQ(search.plan.structures, (std::vector<std::size_t>{3, 2, 1}));
  ASSERT_EQ(search.runs.size(), 3u);
  long long spent = 0;
  std::size_t kept = 0;
  for (std::size_t k = 0; k < 3; ++k) {
    const StructureRun& run = search.runs[k];
    const SynthesisCandidate& c = study.candidates[run.candidate];
    spent += run.evaluations;
    kept += run.kept ? 1 : 0;
    EXPECT_EQ(run.evaluations, 12LL * static_cast<long long>(run.generations + 1)) << c.name;
    EXPECT_GE(run.generations, 3u) << c.name << ": every structure gets the floor";
    // Its search is the separate run of as many generations, bit for bit.
    Nsga2Options options = study.nsga2;
    options.seed = c.seed;
    options.generations = run.generations;
    options.threads = 1;
    Recording alone(c.study->optimization_problem());
    const FrontResult separate = run_nsga2(alone, options);
    EXPECT_EQ(separate.x, run.front.x) << c.name;
    EXPECT_EQ(separate.fitness, run.front.fitness) << c.name;
    // Its archive is as good in hypervolume as the separate run of the same evaluations, and at
    // least as good as the separate run of G generations when it ran at least G.
    options.generations = study.nsga2.generations;
    Recording plain(c.study->optimization_problem());
    run_nsga2(plain, options);
    std::vector<std::vector<double>> all = recorders[k]->feasible;
    all.insert(all.end(), plain.feasible.begin(), plain.feasible.end());
    if (all.empty()) continue;
    const std::vector<double> reference = reference_point_from(all);
    const double in_synthesis = front_hypervolume(recorders[k]->feasible, reference);
    EXPECT_DOUBLE_EQ(in_synthesis, front_hypervolume(alone.feasible, reference)) << c.name;
    if (run.generations >= study.nsga2.generations) {
      EXPECT_GE(in_synthesis, front_hypervolume(plain.feasible, reference)) << c.name;
    }
  }
  EXPECT_EQ(kept, 1u);
  EXPECT_LE(spent, search.plan.budget);
  EXPECT_EQ(spent, search.plan.planned());
  // The same seed gives the same search on two threads.
  std::vector<const Problem*> direct;
  for (std::size_t k : study.searched())
    direct.push_back(&study.candidates[k].study->optimization_problem());
  const SynthesisSearch two = search_structures(study, direct, 2, {});
  for (std::size_t k = 0; k < 3; ++k) {
    EXPECT_EQ(two.runs[k].front.x, search.runs[k].front.x);
    EXPECT_EQ(two.runs[k].generations, search.runs[k].generations);
  }
}

// A CSV file as rows of cells (quoted cells may hold commas).
std::vector<std::vector<std::string>> read_csv(const fs::path& path) {
  std::ifstream in(path);
  std::vector<std::vector<std::string>> rows;
  std::string line;
  while (std::getline(in, line)) {
    std::vector<std::string> cells(1);
    bool quoted = false;
    for (std::size_t i = 0; i < line.size(); ++i) {
      const char c = line[i];
      if (c == '"') {
        if (quoted && i + 1 < line.size() && line[i + 1] == '"') {
          cells.back() += '"';
          ++i;
        } else {
          quoted = !quoted;
        }
      } else if (c == ',' && !quoted) {
        cells.emplace_back();
      } else {
        cells.back() += c;
      }
    }
    rows.push_back(cells);
  }
  return rows;
}

std::size_t column(const std::vector<std::string>& header, const std::string& name) {
  const auto it = std::find(header.begin(), header.end(), name);
  if (it == header.end()) throw std::runtime_error("no column " + name);
  return static_cast<std::size_t>(it - header.begin());
}

class SynthesisCli : public scratch::ScratchDirTest {};

TEST_F(SynthesisCli, MergedFrontCandidatesTableAndOwnFolders) {
  const std::string study = write("small.yaml", kStudy);
  const fs::path out = dir_ / "out";
  const cli_runner::CliRun r = run_cli("run " + study + " --out " + out.string() + " --threads 2");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("synthesis (nsga2 per structure)"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("candidate"), std::string::npos);
  EXPECT_NE(r.err.find("round 1 of 3"), std::string::npos) << r.err;

  // Every feasible evaluation of the run, from each structure's evaluations.csv.
  std::vector<std::vector<double>> feasible;  // (stiffness_min, machine_size), user sign
  for (const char* name : {"hexapod", "delta", "linear_delta"}) {
    const auto rows = read_csv(out / "candidates" / name / "evaluations.csv");
    ASSERT_GT(rows.size(), 1u) << name;
    const std::size_t s = column(rows[0], "stiffness_min"), v = column(rows[0], "machine_size"),
                      ok = column(rows[0], "feasible");
    for (std::size_t k = 1; k < rows.size(); ++k)
      if (rows[k][ok] == "1") feasible.push_back({std::stod(rows[k][s]), std::stod(rows[k][v])});
  }
  ASSERT_FALSE(feasible.empty());
  // The merged front: no design dominated by any feasible evaluation of the run, and every
  // non-dominated feasible evaluation's objectives on it.
  const auto front = read_csv(out / "pareto.csv");
  ASSERT_GT(front.size(), 1u);
  const std::size_t s = column(front[0], "stiffness_min"), v = column(front[0], "machine_size"),
                    arch = column(front[0], "architecture"),
                    file = column(front[0], "machine_file");
  std::map<std::string, std::size_t> per_architecture;
  for (std::size_t k = 1; k < front.size(); ++k) {
    const double stiffness = std::stod(front[k][s]), size = std::stod(front[k][v]);
    for (const auto& e : feasible) {
      const bool dominated = e[0] >= stiffness && e[1] <= size && (e[0] > stiffness || e[1] < size);
      ASSERT_FALSE(dominated) << "design " << front[k][0] << " is dominated";
    }
    ++per_architecture[front[k][arch]];
    // Its machine file loads as the architecture's model.
    const std::unique_ptr<Machine> machine = load_machine_file((out / front[k][file]).string());
    EXPECT_EQ(std::string(machine->model()), front[k][arch]);
  }
  std::vector<std::vector<double>> minimised;
  for (const auto& e : feasible) minimised.push_back({-e[0], e[1]});
  for (std::size_t k : non_dominated_indices(minimised)) {
    bool on_front = false;
    for (std::size_t j = 1; j < front.size(); ++j)
      on_front =
          on_front ||
          (std::abs(std::stod(front[j][s]) - feasible[k][0]) <= 1e-12 * std::abs(feasible[k][0]) &&
           std::abs(std::stod(front[j][v]) - feasible[k][1]) <= 1e-12 * std::abs(feasible[k][1]));
    EXPECT_TRUE(on_front) << feasible[k][0] << " N/m, " << feasible[k][1] << " m^3";
  }

  // candidates.csv: a row per candidate, the merged-front counts add up, shares and folders.
  const auto table = read_csv(out / "candidates.csv");
  ASSERT_EQ(table.size(), 4u);
  const std::size_t name = column(table[0], "candidate"), merged = column(table[0], "merged_front"),
                    status = column(table[0], "status"), folder = column(table[0], "folder");
  std::size_t total = 0;
  for (std::size_t k = 1; k < table.size(); ++k) {
    EXPECT_EQ(table[k][status], "searched");
    EXPECT_EQ(std::stoul(table[k][merged]), per_architecture[table[k][name]]) << table[k][name];
    total += std::stoul(table[k][merged]);
    EXPECT_TRUE(fs::exists(out / table[k][folder] / "pareto.json"));
  }
  EXPECT_EQ(total, front.size() - 1);
  const nlohmann::json candidates = nlohmann::json::parse(std::ifstream(out / "candidates.json"));
  EXPECT_EQ(candidates["task_motion"], "3T0R");
  const nlohmann::json summary = nlohmann::json::parse(std::ifstream(out / "summary.json"));
  EXPECT_EQ(summary["kind"], "synthesis");
  EXPECT_EQ(summary["allocation"]["rounds_structures"], (std::vector<int>{3, 2, 1}));
  EXPECT_LE(summary["evaluations"].get<long long>(),
            summary["allocation"]["budget"].get<long long>());

  // Each structure's folder is its own study: run alone from its study.resolved.yaml (its seed
  // and the generations this run gave it), it writes the same front.
  const fs::path hexapod = out / "candidates" / "hexapod";
  const cli_runner::CliRun alone = run_cli("run " + (hexapod / "study.resolved.yaml").string() +
                                           " --out " + (dir_ / "alone").string());
  ASSERT_EQ(alone.status, 0) << alone.err;
  EXPECT_EQ(cli_runner::read_text(dir_ / "alone" / "pareto.csv"),
            cli_runner::read_text(hexapod / "pareto.csv"));

  // One thread writes the same journals, in the same order, and the same fronts.
  const fs::path one = dir_ / "one-thread";
  ASSERT_EQ(run_cli("run " + study + " --out " + one.string() + " --threads 1").status, 0);
  for (const char* name : {"hexapod", "delta", "linear_delta"}) {
    EXPECT_EQ(cli_runner::read_text(one / "candidates" / name / "journal.txt"),
              cli_runner::read_text(out / "candidates" / name / "journal.txt"))
        << name;
    EXPECT_EQ(cli_runner::read_text(one / "candidates" / name / "evaluations.csv"),
              cli_runner::read_text(out / "candidates" / name / "evaluations.csv"))
        << name;
  }
  EXPECT_EQ(cli_runner::read_text(one / "pareto.csv"), cli_runner::read_text(out / "pareto.csv"));

  // --resume serves every evaluation from the journals and writes the same files.
  const std::string before = cli_runner::read_text(out / "pareto.csv");
  const std::string candidates_before = cli_runner::read_text(out / "candidates.csv");
  const cli_runner::CliRun resumed =
      run_cli("run " + study + " --out " + out.string() + " --resume --threads 1");
  ASSERT_EQ(resumed.status, 0) << resumed.err;
  EXPECT_EQ(cli_runner::read_text(out / "pareto.csv"), before);
  EXPECT_EQ(cli_runner::read_text(out / "candidates.csv"), candidates_before);
  const std::size_t evaluations = std::stoul(resumed.out.substr(resumed.out.find("front, ") + 7));
  EXPECT_NE(resumed.out.find(std::to_string(evaluations) + " evaluations (" +
                             std::to_string(evaluations) + " from the cache"),
            std::string::npos)
      << resumed.out;

  // A folder holding the synthesis is not overwritten without --resume or --force.
  const cli_runner::CliRun again = run_cli("run " + study + " --out " + out.string());
  EXPECT_EQ(again.status, 2);
  EXPECT_NE(again.err.find("holds a previous run (candidates/)"), std::string::npos) << again.err;
  EXPECT_EQ(cli_runner::read_text(out / "pareto.csv"), before);
}

TEST_F(SynthesisCli, ValidateListsCandidatesAndDrops) {
  std::string text = kStudy;
  text.replace(text.find("[hexapod, delta, linear_delta]"), 30, "auto");
  const cli_runner::CliRun r = run_cli("validate " + write("auto.yaml", text));
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("synthesis study 'small' is valid"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("task motion: 3T0R (x, y, z)"), std::string::npos);
  EXPECT_NE(r.out.find("candidates: 10 searched, 2 dropped"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("search   hexaglide"), std::string::npos);
  EXPECT_NE(r.out.find("dropped  tripod_3prs (3-PRS tripod head): no x, y"), std::string::npos)
      << r.out;
  EXPECT_NE(r.out.find("round 1: 10 structure(s) x 3 generations"), std::string::npos) << r.out;
  // Bad input: one line, exit 2, nothing written.
  text.replace(text.find("auto"), 4, "[hexapod, cube]");
  const fs::path out = dir_ / "bad";
  const cli_runner::CliRun bad =
      run_cli("run " + write("bad.yaml", text) + " --out " + out.string());
  EXPECT_EQ(bad.status, 2);
  EXPECT_NE(bad.err.find("pkmopt: error: "), std::string::npos);
  EXPECT_FALSE(fs::exists(out));
}

}  // namespace
}  // namespace pkmopt
