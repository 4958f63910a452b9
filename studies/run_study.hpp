// Running a study file: the result folder, the journal, the optimizer and the result files.
//
// run_study_file(path, options) does what `pkmopt run STUDY.yaml --out DIR` does: it loads the
// study (a design study when the file has `machine:`, else a benchmark study), checks DIR
// against resume/force (a folder holding a run, i.e. journal.txt, summary.json or pareto.csv,
// is never overwritten without one of them), writes DIR/study.resolved.yaml, runs the optimizer
// through a JournaledProblem (studies/journal.hpp: DIR/journal.txt and DIR/evaluations.csv grow
// as the run goes; `resume` continues a killed run) and writes pareto.csv, pareto.json (design
// studies), summary.json and designs/<id>.yaml. Bad input throws InputError before anything is
// written.
//
// Example:
//   StudyRunOptions options;
//   options.out = "results/quick";
//   const StudyRunResult result = run_study_file("studies/library/hexapod-quick.yaml", options);
#pragma once

#include <cstddef>
#include <functional>
#include <string>

#include "io/format/yaml_reader.hpp"
#include "studies/distribute.hpp"
#include "studies/journal.hpp"

namespace pkmopt {

/// The most OpenMP threads a run may ask for (far more would exhaust the runtime's stacks).
inline constexpr int kMaxStudyThreads = 512;

struct StudyRunOptions {
  std::string out;            ///< the result folder (created when missing)
  int threads = 0;            ///< OpenMP threads for batch evaluations (0: all cores), <= 512
  bool resume = false;        ///< continue the run in `out` from its journal
  bool force = false;         ///< replace a previous run in `out`
  bool show_progress = true;  ///< progress line / log lines on stderr
  /// Notes for the user ("no journal in DIR: starting a new run"); default: stderr.
  std::function<void(const std::string&)> message;
  /// Called after every batch of evaluations with the counts so far (studies/journal.hpp); may
  /// throw to stop the run, which then resumes from its journal.
  std::function<void(const JournalProgress&)> progress;
  /// Under mpirun (studies/distribute.hpp): rank 0 runs the study and hands the designs to the
  /// other ranks, which evaluate them on `threads` threads each and write nothing.
  const MpiSession* mpi = nullptr;
  /// How long a worker may stay silent while it holds designs before the run stops (s).
  double worker_timeout_seconds = 600.0;
};

/// What a finished run says about itself (the files in `out` hold the results).
struct StudyRunResult {
  bool design_study = false;
  bool synthesis = false;        ///< an architecture synthesis (studies/synthesis_study.hpp)
  std::string candidates_table;  ///< synthesis: the candidates in a terminal table
  std::string name;       ///< the study's name
  std::string algorithm;  ///< as in the study file (nsga2, nlopt:SLSQP, ...)
  std::string problem;    ///< the problem's name (benchmark studies)
  std::string status;     ///< ok, no_feasible_design, or the single solver's status
  std::string message;    ///< the optimizer's message (empty when it has none)
  /// Design studies without a feasible design: the most frequent violated constraints and
  /// failure reasons with their counts, in words.
  std::string infeasibility;
  std::size_t designs = 0;    ///< points of the front
  long long evaluations = 0;  ///< fitness evaluations requested by the optimizer
  std::size_t from_cache = 0;
  std::size_t failed = 0;
  double optimizer_seconds = 0.0;
  double wall_seconds = 0.0;
  bool resumed = false;
  bool worker = false;  ///< this process was an MPI worker: it evaluated designs, wrote nothing
  int mpi_workers = 0;  ///< MPI ranks that evaluated designs (0: evaluated on this process)
};

/// Runs a study file into options.out (see the header comment). Throws InputError.
StudyRunResult run_study_file(const std::string& study_file, const StudyRunOptions& options);
/// The same for a parsed study file (e.g. one built in memory: YamlValue with no file).
StudyRunResult run_study(const YamlValue& study, const StudyRunOptions& options);

}  // namespace pkmopt
