// Architecture synthesis benchmarks (studies/library/milling-synthesis): one design evaluation of
// each searched structure's middle design (one thread), and the whole seven-structure study as
// `pkmopt run` does it on every core (wall time, one iteration: about two minutes on two
// cores).
#include <benchmark/benchmark.h>
#include <unistd.h>

#include <filesystem>
#include <string>
#include <vector>

#include "bench/middle_design.hpp"
#include "io/format/yaml_reader.hpp"
#include "studies/run_study.hpp"
#include "studies/synthesis_study.hpp"

namespace {

const std::string kStudy =
    std::string(PKMOPT_SOURCE_DIR) + "/studies/library/milling-synthesis/study.yaml";

// Arg k: the k-th searched structure of the study.
void BM_SynthesisDesignEvaluation(benchmark::State& state) {
  const pkmopt::SynthesisStudy study =
      pkmopt::load_synthesis_study(pkmopt::YamlValue::load_file(kStudy));
  const std::vector<std::size_t> searched = study.searched();
  const auto k = static_cast<std::size_t>(state.range(0));
  if (k >= searched.size()) {
    state.SkipWithError("no such structure");
    return;
  }
  const pkmopt::SynthesisCandidate& c = study.candidates[searched[k]];
  pkmopt_bench::evaluate_middle_design(state, c.study->optimization_problem());
  state.SetLabel(c.name);
  state.counters["task_poses"] = static_cast<double>(c.study->task().poses.size());
}
BENCHMARK(BM_SynthesisDesignEvaluation)->DenseRange(0, 6)->Unit(benchmark::kMillisecond);

// The whole study (7 structures, 34,020 evaluations) on every core, into a fresh folder.
void BM_MillingSynthesisStudy(benchmark::State& state) {
  const std::filesystem::path out = std::filesystem::temp_directory_path() /
                                    ("pkmopt_synthesis_bench_" + std::to_string(::getpid()));
  long long evaluations = 0;
  for (auto _ : state) {
    std::filesystem::remove_all(out);
    pkmopt::StudyRunOptions options;
    options.out = out.string();
    options.show_progress = false;
    options.message = [](const std::string&) {};
    const pkmopt::StudyRunResult result = pkmopt::run_study_file(kStudy, options);
    evaluations = result.evaluations;
  }
  std::filesystem::remove_all(out);
  state.counters["evaluations"] = static_cast<double>(evaluations);
}
BENCHMARK(BM_MillingSynthesisStudy)->Iterations(1)->Unit(benchmark::kSecond)->UseRealTime();

}  // namespace
