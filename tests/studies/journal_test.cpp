// Tests of studies/journal: bit-exact checksummed journal lines, cut and damaged lines, CR LF,
// version 1 journals, cache, resume and refusal.
#include "studies/journal.hpp"

#include <gtest/gtest.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <bit>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "io/format/input_error.hpp"
#include "tests/scratch_dir.hpp"

namespace pkmopt {
namespace {

namespace fs = std::filesystem;

// f = [x0^2 + x1, x0 - x1 | g = x0 - 0.5]; counts its own evaluations.
class CountedPair : public Problem {
 public:
  Bounds bounds() const override { return {{-1.0, -1.0}, {1.0, 1.0}}; }
  std::size_t num_objectives() const override { return 2; }
  std::size_t num_inequality() const override { return 1; }
  std::vector<double> fitness(const std::vector<double>& x) const override {
    ++calls;
    return {x[0] * x[0] + x[1], x[0] - x[1], x[0] - 0.5};
  }
  std::string name() const override { return "counted-pair"; }
  mutable std::atomic<int> calls{0};
};

// Every test has its own scratch folder; fresh_dir(name) is a new folder in it.
class StudyJournal : public scratch::ScratchDirTest {
 protected:
  fs::path fresh_dir(const std::string& name) const {
    fs::create_directories(dir_ / name);
    return dir_ / name;
  }
};

std::string read_text(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

std::size_t line_count(const fs::path& path) {
  const std::string text = read_text(path);
  return static_cast<std::size_t>(std::count(text.begin(), text.end(), '\n'));
}

JournalOptions options_for(const fs::path& dir, std::uint64_t hash, bool resume) {
  JournalOptions options;
  options.directory = dir.string();
  options.study_hash = hash;
  options.resume = resume;
  options.csv_header = "index,x_1,x_2";
  options.csv_row = [](std::size_t k, const JournalEntry& e) {
    return std::to_string(k) + "," + std::to_string(e.x[0]) + "," + std::to_string(e.x[1]);
  };
  return options;
}

TEST_F(StudyJournal, LinesAreBitExact) {
  JournalEntry entry;
  entry.x = {0.1, -0.0, 5e-324, 1.0 / 3.0};
  entry.fitness = {std::numeric_limits<double>::infinity(), 1e20, -2.5e-300};
  entry.note = "singular\tat pose 3\n";
  const std::string line = journal_line(entry);
  ASSERT_EQ(line.back(), '\n');
  JournalEntry back;
  ASSERT_EQ(parse_journal_line(std::string_view(line).substr(0, line.size() - 1), 4, 3, back), "");
  ASSERT_EQ(back.x.size(), 4u);
  ASSERT_EQ(back.fitness.size(), 3u);
  for (std::size_t j = 0; j < 4; ++j)
    EXPECT_EQ(std::bit_cast<std::uint64_t>(back.x[j]), std::bit_cast<std::uint64_t>(entry.x[j]));
  for (std::size_t i = 0; i < 3; ++i)
    EXPECT_EQ(std::bit_cast<std::uint64_t>(back.fitness[i]),
              std::bit_cast<std::uint64_t>(entry.fitness[i]));
  EXPECT_EQ(back.note, "singular at pose 3 ");
  // Wrong counts, cut lines and changed bytes are rejected with the reason.
  const std::string_view whole = std::string_view(line).substr(0, line.size() - 1);
  EXPECT_EQ(parse_journal_line(whole, 3, 3, back),
            "expected 6 numbers (3 variables, 3 fitness values), found 7");
  EXPECT_EQ(parse_journal_line(whole.substr(0, 20), 4, 3, back),
            "no tab between the numbers and the note");
  std::string changed(whole);
  changed[2] = changed[2] == '1' ? '2' : '1';
  EXPECT_EQ(parse_journal_line(changed, 4, 3, back),
            "checksum mismatch (the line was changed after it was written)");
  // CR LF line ends are read as LF.
  EXPECT_EQ(parse_journal_line(std::string(whole) + "\r", 4, 3, back), "");
  // Version 1 lines (no checksum) are read when asked.
  const std::string v1 = std::string(whole.substr(0, whole.rfind('\t')));
  EXPECT_EQ(parse_journal_line(v1, 4, 3, back, false), "");
  EXPECT_EQ(back.note, "singular at pose 3 ");
}

// The journal writes its numbers as printf's "%a" does (the format journal.txt has always had);
// it uses std::to_chars for speed. Checked here against printf itself: normal, subnormal,
// signed zeros, extremes, infinities and NaN, and 200,000 random bit patterns.
TEST_F(StudyJournal, NumbersAreWrittenAsPrintfHexadecimal) {
  std::vector<double> values = {0.0,
                                -0.0,
                                1.0,
                                -1.5,
                                0.1,
                                5e-324,
                                -5e-324,
                                2.2250738585072009e-308,
                                std::numeric_limits<double>::min(),
                                std::numeric_limits<double>::max(),
                                -std::numeric_limits<double>::max(),
                                std::numeric_limits<double>::infinity(),
                                -std::numeric_limits<double>::infinity(),
                                std::numeric_limits<double>::quiet_NaN()};
  std::uint64_t state = 0x9e3779b97f4a7c15ULL;
  for (int k = 0; k < 200000; ++k) {
    state ^= state << 13;
    state ^= state >> 7;
    state ^= state << 17;
    values.push_back(std::bit_cast<double>(state));
  }
  for (double v : values) {
    JournalEntry entry;
    entry.x = {v};
    const std::string line = journal_line(entry);
    char expected[64];
    std::snprintf(expected, sizeof expected, "%a", v);
    ASSERT_EQ(line.substr(0, line.find('\t')), expected)
        << "bits " << std::hex << std::bit_cast<std::uint64_t>(v);
  }
}

TEST_F(StudyJournal, StudyHashIsFnv1a) {
  // FNV-1a 64 of "" and "a" (the published test vectors of the algorithm).
  EXPECT_EQ(study_hash(""), 0xcbf29ce484222325ull);
  EXPECT_EQ(study_hash("a"), 0xaf63dc4c8601ec8cull);
}

TEST_F(StudyJournal, CachesIdenticalDesignsAndRecordsEachOnce) {
  const fs::path dir = fresh_dir("cache");
  CountedPair inner;
  JournaledProblem journaled(inner, options_for(dir, 7, false));
  const std::vector<std::vector<double>> batch = {{0.1, 0.2}, {0.3, 0.4}, {0.1, 0.2}};
  const auto first = journaled.batch_fitness(batch, 2);
  EXPECT_EQ(inner.calls.load(), 2);
  EXPECT_EQ(first[0], first[2]);
  EXPECT_EQ(first[1], inner.fitness({0.3, 0.4}));
  inner.calls = 0;
  EXPECT_EQ(journaled.fitness({0.3, 0.4}), first[1]);
  EXPECT_EQ(inner.calls.load(), 0);
  EXPECT_EQ(journaled.requests(), 4);
  EXPECT_EQ(journaled.cache_hits(), 2);
  EXPECT_EQ(journaled.entries().size(), 2u);
  EXPECT_EQ(line_count(dir / "journal.txt"), 3u);      // header + 2 evaluations
  EXPECT_EQ(line_count(dir / "evaluations.csv"), 3u);  // header + 2 evaluations
}

TEST_F(StudyJournal, GenerationIsTheRequestThatFirstAskedAndResumesToTheSame) {
  const fs::path dir = fresh_dir("generation");
  auto options = [&](bool resume) {
    JournalOptions o = options_for(dir, 11, resume);
    o.csv_header = "index,generation";
    o.csv_row = [](std::size_t k, const JournalEntry& e) {
      return std::to_string(k) + "," + (e.generation >= 0 ? std::to_string(e.generation) : "");
    };
    return o;
  };
  const std::vector<std::vector<double>> first = {{0.1, 0.2}, {0.3, 0.4}};
  const std::vector<std::vector<double>> second = {{0.3, 0.4}, {0.5, 0.6}};
  const CountedPair problem;
  {
    JournaledProblem j(problem, options(false));
    j.batch_fitness(first, 1);   // request 0: two new designs
    j.batch_fitness(second, 1);  // request 1: one from the cache, one new
    j.fitness({0.7, 0.8});       // request 2
    ASSERT_EQ(j.entries().size(), 4u);
    EXPECT_EQ(j.entries()[0].generation, 0);
    EXPECT_EQ(j.entries()[1].generation, 0);
    EXPECT_EQ(j.entries()[2].generation, 1);
    EXPECT_EQ(j.entries()[3].generation, 2);
    j.finish();
  }
  const std::string uninterrupted = read_text(dir / "evaluations.csv");
  EXPECT_EQ(uninterrupted, "index,generation\n0,0\n1,0\n2,1\n3,2\n");
  // Resumed: the loaded entries have no generation until the run asks for them again; the same
  // requests give the same numbers, and the file at the end is the uninterrupted run's.
  JournaledProblem again(problem, options(true));
  EXPECT_EQ(again.entries()[0].generation, -1);
  EXPECT_EQ(read_text(dir / "evaluations.csv"), "index,generation\n0,\n1,\n2,\n3,\n");
  again.batch_fitness(first, 1);
  again.batch_fitness(second, 1);
  again.fitness({0.7, 0.8});
  again.finish();
  EXPECT_EQ(problem.calls.load(), 4);  // nothing evaluated twice
  EXPECT_EQ(read_text(dir / "evaluations.csv"), uninterrupted);
}

TEST_F(StudyJournal, ResumeServesRecordedDesignsAndDropsACutLine) {
  const fs::path dir = fresh_dir("resume");
  CountedPair inner;
  {
    JournaledProblem journaled(inner, options_for(dir, 11, false));
    journaled.batch_fitness(std::vector<std::vector<double>>{{0.1, 0.2}, {0.3, 0.4}}, 1);
  }
  // A kill in the middle of a line leaves it without its newline.
  std::ofstream(dir / "journal.txt", std::ios::app) << "0x1.8p-1 0x1";
  const JournalContents contents = read_journal((dir / "journal.txt").string());
  EXPECT_EQ(contents.entries.size(), 2u);
  EXPECT_EQ(contents.study_hash, 11u);

  inner.calls = 0;
  JournaledProblem resumed(inner, options_for(dir, 11, true));
  EXPECT_EQ(resumed.loaded_entries(), 2u);
  const auto f = resumed.batch_fitness(
      std::vector<std::vector<double>>{{0.1, 0.2}, {0.3, 0.4}, {0.5, 0.6}}, 1);
  EXPECT_EQ(inner.calls.load(), 1);  // only the new design
  EXPECT_EQ(f[2], inner.fitness({0.5, 0.6}));
  EXPECT_EQ(resumed.entries().size(), 3u);
  EXPECT_EQ(read_journal((dir / "journal.txt").string()).entries.size(), 3u);
  EXPECT_EQ(line_count(dir / "journal.txt"), 4u);  // the cut line is gone
  const std::string csv = read_text(dir / "evaluations.csv");
  EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 4);
  EXPECT_EQ(csv.substr(0, 14), "index,x_1,x_2\n");
}

// on_batch sees the counts after each batch is journaled; a throw from it stops the caller with
// the batch already in the journal, and a resumed run re-evaluates none of it.
TEST_F(StudyJournal, OnBatchReportsCountsAndMayStopTheRun) {
  const fs::path dir = fresh_dir("on_batch");
  CountedPair inner;
  std::vector<JournalProgress> seen;
  JournalOptions options = options_for(dir, 13, false);
  options.expected_requests = 5;
  options.on_batch = [&](const JournalProgress& p) {
    seen.push_back(p);
    if (seen.size() == 2) throw std::runtime_error("interrupted");
  };
  {
    JournaledProblem journaled(inner, options);
    journaled.batch_fitness(std::vector<std::vector<double>>{{0.1, 0.2}, {0.1, 0.2}, {0.9, 0.0}},
                            1);
    ASSERT_EQ(seen.size(), 1u);
    EXPECT_EQ(seen[0].requests, 3);
    EXPECT_EQ(seen[0].expected_requests, 5);
    EXPECT_EQ(seen[0].cache_hits, 1);
    EXPECT_EQ(seen[0].distinct, 2u);
    EXPECT_EQ(seen[0].feasible_front, 1u);  // (0.9, 0) violates x0 <= 0.5
    EXPECT_THROW(journaled.fitness({0.3, 0.4}), std::runtime_error);
    EXPECT_EQ(seen[1].requests, 4);
  }
  EXPECT_EQ(read_journal((dir / "journal.txt").string()).entries.size(), 3u);
  inner.calls = 0;
  JournaledProblem resumed(inner, options_for(dir, 13, true));
  resumed.fitness({0.3, 0.4});
  EXPECT_EQ(inner.calls.load(), 0);
}

// A damaged line in the middle is reported with its line number, kept in journal.damaged.txt, and
// only its design is evaluated again; the lines after it still count (never a silent cut).
TEST_F(StudyJournal, DamagedMiddleLineIsReportedAndOnlyItIsReevaluated) {
  const fs::path dir = fresh_dir("damaged");
  CountedPair inner;
  const std::vector<std::vector<double>> designs = {{0.1, 0.2}, {0.3, 0.4}, {0.5, 0.6}};
  {
    JournaledProblem journaled(inner, options_for(dir, 17, false));
    journaled.batch_fitness(designs, 1);
  }
  std::string text = read_text(dir / "journal.txt");
  const std::size_t line3 = text.find('\n', text.find('\n') + 1) + 1;  // the second entry
  text[line3 + 3] = text[line3 + 3] == '3' ? '4' : '3';
  std::ofstream(dir / "journal.txt", std::ios::binary | std::ios::trunc) << text;

  const JournalContents contents = read_journal((dir / "journal.txt").string());
  ASSERT_EQ(contents.entries.size(), 2u);
  ASSERT_EQ(contents.damaged.size(), 1u);
  EXPECT_EQ(contents.damaged[0].line, 3u);

  std::vector<std::string> warnings;
  JournalOptions options = options_for(dir, 17, true);
  options.warn = [&](const std::string& w) { warnings.push_back(w); };
  inner.calls = 0;
  JournaledProblem resumed(inner, options);
  EXPECT_EQ(resumed.loaded_entries(), 2u);
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_EQ(warnings[0], (dir / "journal.txt").string() +
                             ":3: damaged journal line (checksum mismatch (the line was changed "
                             "after it was written)): its design is evaluated again");
  const auto f = resumed.batch_fitness(designs, 1);
  EXPECT_EQ(inner.calls.load(), 1);  // only the damaged one
  EXPECT_EQ(f[1], inner.fitness({0.3, 0.4}));
  EXPECT_EQ(read_journal((dir / "journal.txt").string()).damaged.size(), 0u);
  EXPECT_EQ(read_journal((dir / "journal.txt").string()).entries.size(), 3u);
  const std::string kept = read_text(dir / "journal.damaged.txt");
  EXPECT_EQ(kept.substr(0, 2), "3\t");
  EXPECT_EQ(std::count(kept.begin(), kept.end(), '\n'), 1);
}

// A journal whose line ends were turned into CR LF (a copy through another system) loses nothing.
TEST_F(StudyJournal, CrlfJournalResumesWithEveryEntry) {
  const fs::path dir = fresh_dir("crlf");
  CountedPair inner;
  const std::vector<std::vector<double>> designs = {{0.1, 0.2}, {0.3, 0.4}};
  {
    JournaledProblem journaled(inner, options_for(dir, 19, false));
    journaled.batch_fitness(designs, 1);
  }
  std::string crlf;
  for (char c : read_text(dir / "journal.txt"))
    crlf += c == '\n' ? std::string("\r\n") : std::string(1, c);
  std::ofstream(dir / "journal.txt", std::ios::binary | std::ios::trunc) << crlf;
  std::vector<std::string> warnings;
  JournalOptions options = options_for(dir, 19, true);
  options.warn = [&](const std::string& w) { warnings.push_back(w); };
  inner.calls = 0;
  JournaledProblem resumed(inner, options);
  EXPECT_EQ(resumed.loaded_entries(), 2u);
  EXPECT_TRUE(warnings.empty());
  resumed.batch_fitness(designs, 1);
  EXPECT_EQ(inner.calls.load(), 0);
  const std::string after = read_text(dir / "journal.txt");
  EXPECT_EQ(after.find('\r'), std::string::npos);  // rewritten with LF
  EXPECT_EQ(resumed.failed(), 0);
}

// Journals written before lines had checksums (version 1) are resumed and upgraded.
TEST_F(StudyJournal, VersionOneJournalIsReadAndUpgraded) {
  const fs::path dir = fresh_dir("v1");
  std::ofstream(dir / "journal.txt", std::ios::binary)
      << "pkmopt-journal 1 0000000000000017 2 3\n"
      << "0x1.999999999999ap-4 0x1.999999999999ap-3 0x1.eb851eb851eb8p-3 -0x1.999999999999ap-4 "
         "-0x1.999999999999ap-2\t\n";
  CountedPair inner;
  JournaledProblem resumed(inner, options_for(dir, 0x17, true));
  EXPECT_EQ(resumed.loaded_entries(), 1u);
  resumed.fitness({0.1, 0.2});
  EXPECT_EQ(inner.calls.load(), 0);
  const JournalContents contents = read_journal((dir / "journal.txt").string());
  EXPECT_EQ(contents.version, 2);
  EXPECT_EQ(contents.entries.size(), 1u);
}

// A journal that cannot be written (here: a file size limit, as a full disk) is bad input for the
// run's folder (exit status 2 from the command line), with the file and the system's reason.
TEST_F(StudyJournal, WriteFailureIsAnInputErrorNamingTheFile) {
  const fs::path dir = fresh_dir("full");
  const pid_t child = ::fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    std::signal(SIGXFSZ, SIG_IGN);  // write() then fails with EFBIG instead of killing us
    CountedPair inner;
    int code = 1;
    try {
      JournaledProblem journaled(inner, options_for(dir, 23, false));
      const rlimit limit{4096, 4096};
      ::setrlimit(RLIMIT_FSIZE, &limit);
      std::vector<std::vector<double>> batch;
      for (int k = 0; k < 200; ++k) batch.push_back({0.001 * k, -0.001 * k});
      journaled.batch_fitness(batch, 1);
    } catch (const InputError& error) {
      const std::string what = error.what();
      code = what.find("journal.txt: write failed: File too large") != std::string::npos &&
                     what.find("--resume") != std::string::npos
                 ? 0
                 : 2;
    } catch (...) {
      code = 3;
    }
    ::_exit(code);
  }
  int status = 0;
  ASSERT_EQ(::waitpid(child, &status, 0), child);
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 0) << "1: no error, 2: another message, 3: not an InputError";
}

TEST_F(StudyJournal, ResumeRefusesAnotherStudy) {
  const fs::path dir = fresh_dir("refuse");
  CountedPair inner;
  { JournaledProblem journaled(inner, options_for(dir, 1, false)); }
  try {
    JournaledProblem resumed(inner, options_for(dir, 2, true));
    FAIL() << "no error";
  } catch (const InputError& error) {
    EXPECT_EQ(std::string(error.what()),
              (dir / "journal.txt").string() +
                  ": --resume: the journal belongs to another version of the study (study hash "
                  "0000000000000001, the study file now gives 0000000000000002); the study file "
                  "changed since the run started: restore it, or start over with --force");
  }
}

TEST_F(StudyJournal, JournalDoesNotDependOnThreads) {
  std::vector<std::vector<double>> batch;
  for (int k = 0; k < 40; ++k) batch.push_back({std::sin(k) * 0.9, std::cos(3 * k) * 0.9});
  std::string texts[2];
  for (int t = 1; t <= 2; ++t) {
    const fs::path dir = fresh_dir("threads" + std::to_string(t));
    CountedPair inner;
    JournaledProblem journaled(inner, options_for(dir, 3, false));
    journaled.batch_fitness(batch, t);
    texts[t - 1] = read_text(dir / "journal.txt");
  }
  EXPECT_EQ(texts[0], texts[1]);
}

}  // namespace
}  // namespace pkmopt
