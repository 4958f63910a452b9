// Distributed evaluation with MPI: `mpirun -np N pkmopt run STUDY --out DIR` runs the optimizer
// and the journal on rank 0 and evaluates designs on ranks 1..N-1.
//
// Every rank reads the same study file. Rank 0 checks the result folder, opens the journal and
// runs the optimizer exactly as without MPI; the designs of a batch that the journal does not hold
// go to an MpiDispatcher, which hands them to the workers a chunk at a time (guided
// self-scheduling: the designs left over twice the number of workers, at least as many as the
// worker has threads, so chunks shrink as the batch runs out; each worker holds at most two
// chunks, so a slow design holds back only its own worker) and puts every result back at its
// design's place in the batch. Which
// rank evaluated what, and in which order results arrive, changes nothing: the journal, the front
// and every file are the same for any number of ranks and threads.
//
// Workers (serve_as_worker) load the study, greet rank 0 with their study hash (a worker that read
// another file, or could not read it, is refused with its rank and message), then evaluate what
// rank 0 sends until it says stop. A worker that does not answer within the timeout ends the run
// with a WorkerFault naming its rank and the designs it held; a worker that dies makes mpirun stop
// every rank with SIGTERM, and rank 0 then says which worker died (on the same host) and what it
// held. Either way the journal holds every evaluation of the batches before, and `--resume`
// continues with or without MPI and with any number of ranks.
//
// Messages (MPI_COMM_WORLD, bytes): worker -> 0 hello {ok, threads, pid, study hash, variables,
// fitness size, host, error}; 0 -> worker task {task id, count, x...}; worker -> 0 result {task
// id, per design fitness and note, or an error}; 0 -> worker stop {}.
//
// Example (app/commands/cmd_run.cpp):
//   MpiSession session;                       // MPI_Init_thread; MPI_Finalize at the end
//   if (session.rank() > 0) serve_as_worker(load_evaluator, threads);
//   else { MpiDispatcher dispatcher(load_evaluator(), 600.0); ... dispatcher.evaluate(xs) ... }
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

#include "models/core/process_share.hpp"
#include "studies/journal.hpp"

namespace pkmopt {

/// How a launcher (mpirun, srun) started this process, from its environment, before MPI is
/// initialised: OMPI_COMM_WORLD_RANK/SIZE (Open MPI), PMIX_RANK with PMIX_SIZE or
/// OMPI_UNIVERSE_SIZE, PMI_RANK/PMI_SIZE (Slurm's PMI, MPICH).
struct MpiLaunch {
  bool launched = false;
  int rank = 0;
  int size = 1;
};
MpiLaunch mpi_launch_from_environment();

/// What a rank needs to evaluate the designs of a study (every rank loads it from the same file).
struct StudyEvaluator {
  std::uint64_t study_hash = 0;
  std::size_t num_variables = 0;
  std::size_t fitness_size = 0;
  bool thread_safe = true;  ///< evaluate may run on several threads at once
  /// One design: its fitness and failure note (JournalEntry::x and generation are not used).
  std::function<JournalEntry(const std::vector<double>& x)> evaluate;
};

/// A worker failed (did not answer in time, sent a message that cannot be read): the run stops
/// with exit status 4 and the journal intact.
class WorkerFault : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// MPI_Init_thread (MPI_THREAD_FUNNELED) on construction, MPI_Finalize on destruction. Throws
/// InputError when pkmopt was built without MPI. `with_workers`: ranks 1..N-1 serve rank 0
/// (serve_as_worker), and rank 0 tells them to stop when it ends before it dispatched anything.
class MpiSession {
 public:
  explicit MpiSession(bool with_workers = false);
  ~MpiSession();
  MpiSession(const MpiSession&) = delete;
  MpiSession& operator=(const MpiSession&) = delete;
  int rank() const { return rank_; }
  int size() const { return size_; }
  /// Ends this rank at once with `status`, without MPI_Finalize (which would wait for a worker
  /// that hangs); mpirun then stops every other rank and exits with `status`.
  [[noreturn]] void abort(int status) const;

 private:
  int rank_ = 0;
  int size_ = 1;
  bool with_workers_ = false;
};

/// Every rank of MPI_COMM_WORLD as a part of a ProcessShare (models/core/process_share.hpp): the
/// ranks run `pkmopt workspace` or `pkmopt analyze` in lockstep, each computing its share.
class MpiShare final : public ProcessShare {
 public:
  explicit MpiShare(const MpiSession& session) : rank_(session.rank()), size_(session.size()) {}
  int parts() const override { return size_; }
  int part() const override { return rank_; }
  std::vector<std::vector<char>> all_gather(std::span<const char> mine) const override;

 private:
  int rank_ = 0;
  int size_ = 1;
};

/// Rank 0's side: hands designs to ranks 1..size-1.
class MpiDispatcher {
 public:
  /// Waits for every worker's hello (at most `timeout_seconds`) and checks it against `local`
  /// (the study rank 0 loaded): InputError "MPI rank R: ..." when a worker could not load the
  /// study or loaded another one; WorkerFault when one does not greet in time. Installs a
  /// SIGTERM handler that reports the designs in flight.
  MpiDispatcher(const StudyEvaluator& local, double timeout_seconds);
  /// Tells every worker to stop; restores the SIGTERM handler.
  ~MpiDispatcher();
  MpiDispatcher(const MpiDispatcher&) = delete;
  MpiDispatcher& operator=(const MpiDispatcher&) = delete;

  /// Fitness and note of every design, result[k] for xs[k]. A design whose evaluation threw on
  /// its worker rethrows that message here (std::runtime_error) once the others are back, as the
  /// local evaluation would; a worker silent for timeout_seconds throws WorkerFault.
  std::vector<JournalEntry> evaluate(std::span<const std::vector<double>> xs);

  int workers() const;

 private:
  struct State;
  std::unique_ptr<State> state_;
};

/// Worker ranks: loads the study with `load` (its InputError goes to rank 0, which reports it),
/// then evaluates the chunks rank 0 sends (on up to `threads` threads) until it says stop.
void serve_as_worker(const std::function<StudyEvaluator()>& load, int threads);

}  // namespace pkmopt
