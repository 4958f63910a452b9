// The evaluation journal of `pkmopt run`: every evaluation recorded as it happens, a cache of
// identical evaluations, resume after a kill, evaluations.csv and the progress display.
//
// JournaledProblem decorates the problem a study optimises (a ForwardingProblem: only fitness and
// batch fitness differ from the inner problem). Every fitness request goes through it: a design x
// seen before (bit-identical) is served from the cache; the others are evaluated (in parallel for
// batches), appended to DIR/journal.txt and to DIR/evaluations.csv in request order (one write per
// batch), then returned. Because the optimizers are deterministic for a given seed, re-running a
// killed study with the journal loaded replays the same requests: everything recorded comes from
// the cache, the rest is evaluated and appended, and the run ends with the same front as one never
// killed. Gradients are not journaled (recomputed on resume).
//
// DIR/journal.txt (text, append-only, bit-exact):
//   pkmopt-journal 2 <study hash, 16 hex digits> <n variables> <fitness size>
//   <x_1> ... <x_n> <f_1> ... <f_m>\t<note>\t<checksum>   one line per distinct evaluation
// Numbers are C99 hexadecimal floats (printf %a: exact), the note is the failure reason (empty
// when the evaluation succeeded; tabs and newlines replaced by spaces), the checksum the FNV-1a
// 64 hash (16 hex digits) of the line up to and including the second tab. On resume a last line
// without its newline (cut by a kill) is dropped silently; a damaged line (bad checksum, wrong
// number count) is reported through JournalOptions::warn, copied to DIR/journal.damaged.txt and
// dropped, so only its design is evaluated again; the lines after it are kept. CR LF line ends
// are read. Journals of version 1 (no checksums) are read and rewritten as version 2.
//
// DIR/evaluations.csv: its header and rows come from the caller (`csv_header`, `csv_row`); on
// resume it is rewritten from the journal, then appended to; finish() rewrites it whole once more
// so that every row carries its JournalEntry::generation (loaded rows get theirs when the resumed
// run asks for them again).
//
// Progress (stderr): on a terminal one line redrawn in place (evaluations done / expected,
// hypervolume of the feasible non-dominated evaluated points, elapsed, remaining); otherwise a
// plain log line every `log_interval_seconds`. The hypervolume's reference point is the nadir of
// those points plus 10% of their range (it moves as the front grows).
//
// Example:
//   JournalOptions options;
//   options.directory = "out"; options.study_hash = study_hash(resolved_yaml_text);
//   options.resume = true;
//   JournaledProblem journaled(problem, options);   // throws InputError on a foreign journal
//   FrontResult front = run_nsga2(journaled, nsga2_options);
//   journaled.finish();
#pragma once

#include <chrono>
#include <cstdint>
#include <functional>
#include <mutex>
#include <span>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

#include "optimizer/problem.hpp"

namespace pkmopt {

/// One recorded evaluation.
struct JournalEntry {
  std::vector<double> x;
  std::vector<double> fitness;
  std::string note;  ///< failure reason; empty when the evaluation succeeded
  /// The request (a call of fitness or batch_fitness; NSGA-II: 0 the initial population, g the
  /// offspring of generation g) that first asked for this design in this run, counted from 0;
  /// -1 for an entry read from the journal that the resumed run has not asked for yet. Not
  /// stored in journal.txt: a resumed run, making the same requests, finds the same numbers.
  long long generation = -1;
};

/// FNV-1a 64-bit hash of a text (stable across runs and machines).
std::uint64_t study_hash(std::string_view text);

/// A journal line for an entry (with its checksum and newline) and its reader: the empty string
/// for a good line, else what is wrong with it. Exposed for tests.
std::string journal_line(const JournalEntry& entry);
std::string parse_journal_line(std::string_view line, std::size_t num_variables,
                               std::size_t fitness_size, JournalEntry& entry,
                               bool checksummed = true);

/// A journal line that cannot be read (1-based line number, the reason, its text).
struct JournalDamage {
  std::size_t line = 0;
  std::string problem;
  std::string text;
};

/// The entries of a journal file. A cut last line (a kill mid-write) is not counted; damaged
/// lines are listed and skipped, the lines after them still count. Throws InputError when the
/// header is missing or does not match.
struct JournalContents {
  int version = 0;
  std::uint64_t study_hash = 0;
  std::size_t num_variables = 0;
  std::size_t fitness_size = 0;
  std::vector<JournalEntry> entries;
  std::vector<JournalDamage> damaged;
  bool crlf = false;            ///< some lines end in CR LF
  bool cut_last_line = false;   ///< the file ends without a newline
  std::size_t valid_bytes = 0;  ///< bytes up to the last newline
};
JournalContents read_journal(const std::string& path);

/// The counts of a run so far, given to JournalOptions::on_batch.
struct JournalProgress {
  long long requests = 0;           ///< fitness requests (cache hits included)
  long long expected_requests = 0;  ///< JournalOptions::expected_requests (0: unknown)
  long long cache_hits = 0;
  long long failed = 0;            ///< distinct evaluations with a failure note
  std::size_t distinct = 0;        ///< entries recorded (loaded ones included)
  std::size_t feasible_front = 0;  ///< feasible non-dominated designs among them
};

struct JournalOptions {
  std::string directory;
  std::uint64_t study_hash = 0;
  bool resume = false;  ///< load DIR/journal.txt if present (refused if its hash differs)
  /// evaluations.csv: header line (without newline) and one row (without newline) per entry;
  /// no evaluations.csv when csv_row is empty.
  std::string csv_header;
  std::function<std::string(std::size_t index, const JournalEntry&)> csv_row;
  /// Evaluates one design with its failure note; default: inner.fitness(x) with an empty note.
  std::function<JournalEntry(const std::vector<double>& x)> evaluate;
  /// Evaluates the designs of a batch that are not in the journal, result[k] for xs[k] (fitness
  /// and note), e.g. on other MPI ranks (studies/distribute.hpp); default: `evaluate` on this
  /// process's threads. Called with one batch at a time (never concurrently).
  std::function<std::vector<JournalEntry>(std::span<const std::vector<double>> xs)> evaluate_batch;
  /// Progress: expected number of fitness requests (0: unknown), whether to show it.
  long long expected_requests = 0;
  bool show_progress = false;
  double log_interval_seconds = 5.0;
  int threads = 0;  ///< for the display only; batches use the threads the optimizer passes
  /// Called after every batch, once its evaluations are journaled, from the thread that called
  /// fitness or batch_fitness. It may throw to stop the run (e.g. on an interrupt): the journal
  /// then holds every evaluation finished before, and a resumed run re-evaluates none of them.
  std::function<void(const JournalProgress&)> on_batch;
  /// Warnings while resuming (a damaged line: "DIR/journal.txt:LINE: damaged journal line
  /// (REASON): its design is evaluated again"); none when empty.
  std::function<void(const std::string&)> warn;
};

class JournaledProblem final : public ForwardingProblem {
 public:
  /// Opens (or, with resume, reloads and truncates to its last complete line) DIR/journal.txt
  /// and DIR/evaluations.csv. Throws InputError when resuming a journal of another study.
  JournaledProblem(const Problem& inner, JournalOptions options);
  ~JournaledProblem() override;
  JournaledProblem(const JournaledProblem&) = delete;
  JournaledProblem& operator=(const JournaledProblem&) = delete;

  /// Served from the cache or evaluated and journaled; everything else is forwarded.
  std::vector<double> fitness(const std::vector<double>& x) const override;
  std::vector<std::vector<double>> batch_fitness(std::span<const std::vector<double>> xs,
                                                 int threads) const override;

  /// Entries recorded so far (loaded ones first), in journal order.
  const std::vector<JournalEntry>& entries() const { return entries_; }
  /// The recorded entry of a design, or nullptr.
  const JournalEntry* find(const std::vector<double>& x) const;
  long long requests() const;    ///< fitness requests (cache hits included)
  long long cache_hits() const;  ///< requests served from the cache
  std::size_t loaded_entries() const { return loaded_; }  ///< entries read from the journal
  long long failed() const;  ///< distinct evaluations with a failure note
  /// Ends the progress line (on a terminal) and prints a last log line; rewrites
  /// evaluations.csv with every entry's generation (atomically).
  void finish() const;

 private:
  std::vector<std::vector<double>> serve(std::span<const std::vector<double>> xs,
                                         int threads) const;
  void append(std::span<const JournalEntry> fresh) const;
  void report_progress(bool force) const;
  void note_feasible(const JournalEntry& entry) const;
  void merge_front() const;
  void recover(const std::string& journal_path, JournalContents& contents) const;

  JournalOptions options_;
  int journal_fd_ = -1;
  mutable int csv_fd_ = -1;  // closed by finish()
  mutable std::mutex mutex_;
  mutable std::mutex batch_mutex_;  // one evaluate_batch call at a time
  mutable std::vector<JournalEntry> entries_;
  mutable std::unordered_map<std::string, std::size_t> index_;  // bytes of x -> entry
  mutable long long requests_ = 0;
  mutable long long batches_ = 0;  // calls of fitness and batch_fitness: JournalEntry::generation
  mutable long long cache_hits_ = 0;
  mutable long long failed_ = 0;
  std::size_t loaded_ = 0;
  bool terminal_ = false;
  std::chrono::steady_clock::time_point start_;
  mutable std::chrono::steady_clock::time_point last_report_;
  mutable bool progress_line_open_ = false;
  mutable std::vector<std::vector<double>> feasible_front_;  // user-independent internal sign
  mutable std::vector<std::vector<double>> pending_front_;   // feasible, not merged in yet
};

}  // namespace pkmopt
