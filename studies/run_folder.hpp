// The result folder of a run (`pkmopt run STUDY --out DIR`): checked against --resume and
// --force, created, locked (studies/run_lock.hpp) and cleared of a replaced run.
//
// A folder holding a run (journal.txt, summary.json, pareto.csv, or the candidates/ folder of an
// architecture synthesis) is never overwritten without --resume or --force; a folder of other
// files is never written into. --force removes the previous run's files (and candidates/);
// temporaries a killed run left are removed.
//
// Example:
//   const PreparedDirectory prepared = prepare_output_directory(options);
//   if (prepared.resumed) ...  // DIR held a journal and --resume was given
#pragma once

#include <memory>

#include "studies/run_lock.hpp"
#include "studies/run_study.hpp"

namespace pkmopt {

struct PreparedDirectory {
  std::unique_ptr<RunLock> lock;  ///< held for the run
  bool resumed = false;           ///< a journal is resumed
};

/// Prepares options.out (see the header comment); throws InputError. options.message must be set.
PreparedDirectory prepare_output_directory(const StudyRunOptions& options);

}  // namespace pkmopt
