#include "studies/journal.hpp"

#include <fcntl.h>
#include <fmt/format.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "io/format/input_error.hpp"
#include "io/format/output_file.hpp"
#include "optimizer/indicators.hpp"

namespace pkmopt {
namespace {

constexpr std::string_view kJournalName = "pkmopt-journal";
constexpr int kJournalVersion = 2;  // 1: lines without checksums (still read)

std::string key_of(const std::vector<double>& x) {
  return std::string(reinterpret_cast<const char*>(x.data()), x.size() * sizeof(double));
}

// Appends `value` as printf's "%a" writes it (C99 hexadecimal, exact): "0x1.8p+1", "-0x0p+0",
// "0x0.0000000000001p-1022", "inf", "nan". std::to_chars writes the same digits without the "0x"
// and several times faster (the journal writes a line per evaluation).
void append_hex(std::string& out, double value) {
  if (!std::isfinite(value)) {
    char buffer[16];
    std::snprintf(buffer, sizeof buffer, "%a", value);
    out += buffer;
    return;
  }
  char buffer[48];
  char* at = buffer;
  if (std::signbit(value)) *at++ = '-';
  *at++ = '0';
  *at++ = 'x';
  const std::to_chars_result r =
      std::to_chars(at, buffer + sizeof buffer, std::fabs(value), std::chars_format::hex);
  out.append(buffer, r.ptr);
}

std::string header_line(std::uint64_t hash, std::size_t n, std::size_t m) {
  return fmt::format("{} {} {:016x} {} {}\n", kJournalName, kJournalVersion, hash, n, m);
}

void write_all(int fd, const std::string& text, const std::string& what) {
  std::size_t done = 0;
  while (done < text.size()) {
    const ssize_t written = ::write(fd, text.data() + done, text.size() - done);
    if (written < 0) {
      if (errno == EINTR) continue;
      throw InputError(fmt::format(
          "{}: write failed: {}; the journal holds every evaluation finished before: make room "
          "and continue with --resume",
          what, std::strerror(errno)));
    }
    done += static_cast<std::size_t>(written);
  }
}

int open_append(const std::string& path) {
  const int fd = ::open(path.c_str(), O_WRONLY | O_APPEND | O_CREAT | O_CLOEXEC, 0644);
  if (fd < 0)
    throw InputError(fmt::format("{}: cannot open for appending: {}", path, std::strerror(errno)));
  return fd;
}

bool is_feasible(const Problem& problem, const JournalEntry& entry) {
  if (!entry.note.empty()) return false;
  for (std::size_t i = 0; i < problem.num_objectives(); ++i)
    if (!std::isfinite(entry.fitness[i])) return false;
  return constraint_violation(problem, entry.fitness, 1e-6, 1e-8) == 0.0;
}

// Adds a point to a non-dominated set (minimisation).
void add_non_dominated(std::vector<std::vector<double>>& set, std::vector<double> point) {
  auto dominates = [](const std::vector<double>& a, const std::vector<double>& b) {
    bool strictly = false;
    for (std::size_t i = 0; i < a.size(); ++i) {
      if (a[i] > b[i]) return false;
      if (a[i] < b[i]) strictly = true;
    }
    return strictly;
  };
  for (const auto& s : set)
    if (dominates(s, point) || s == point) return;
  std::erase_if(set, [&](const std::vector<double>& s) { return dominates(point, s); });
  set.push_back(std::move(point));
}

std::string clock_text(double seconds) {
  if (!std::isfinite(seconds) || seconds < 0) return "?";
  const long long s = std::llround(seconds);
  if (s >= 3600) return fmt::format("{}h{:02}m{:02}s", s / 3600, s / 60 % 60, s % 60);
  if (s >= 60) return fmt::format("{}m{:02}s", s / 60, s % 60);
  return fmt::format("{}s", s);
}

}  // namespace

std::uint64_t study_hash(std::string_view text) {
  std::uint64_t hash = 14695981039346656037ull;
  for (unsigned char c : text) {
    hash ^= c;
    hash *= 1099511628211ull;
  }
  return hash;
}

std::string journal_line(const JournalEntry& entry) {
  std::string line;
  line.reserve(24 * (entry.x.size() + entry.fitness.size()) + entry.note.size() + 20);
  bool first = true;
  for (const std::vector<double>* numbers : {&entry.x, &entry.fitness})
    for (double v : *numbers) {
      if (!first) line += ' ';
      first = false;
      append_hex(line, v);
    }
  line += '\t';
  for (char c : entry.note) line += (c == '\t' || c == '\n' || c == '\r') ? ' ' : c;
  line += '\t';
  line += fmt::format("{:016x}\n", study_hash(line));
  return line;
}

std::string parse_journal_line(std::string_view line, std::size_t num_variables,
                               std::size_t fitness_size, JournalEntry& entry, bool checksummed) {
  if (!line.empty() && line.back() == '\r') line.remove_suffix(1);  // CRLF line ends
  const std::size_t tab = line.find('\t');
  if (tab == std::string_view::npos) return "no tab between the numbers and the note";
  std::string_view note = line.substr(tab + 1);
  if (checksummed) {
    const std::size_t last = line.rfind('\t');
    if (last == tab) return "no checksum at the end of the line";
    const std::string_view sum = line.substr(last + 1);
    if (sum.size() != 16 || sum.find_first_not_of("0123456789abcdef") != std::string_view::npos)
      return fmt::format("the checksum is not 16 hex digits: '{}'", sum.substr(0, 40));
    const std::uint64_t expected = std::strtoull(std::string(sum).c_str(), nullptr, 16);
    if (study_hash(line.substr(0, last + 1)) != expected)
      return "checksum mismatch (the line was changed after it was written)";
    note = line.substr(tab + 1, last - tab - 1);
  }
  const std::string numbers(line.substr(0, tab));
  entry.x.clear();
  entry.fitness.clear();
  const char* p = numbers.c_str();
  const char* end = p + numbers.size();
  std::vector<double> values;
  while (p < end) {
    while (p < end && *p == ' ') ++p;
    if (p >= end) break;
    char* next = nullptr;
    const double v = std::strtod(p, &next);
    if (next == p || (next < end && *next != ' '))
      return fmt::format("number {} is not a number", values.size() + 1);
    values.push_back(v);
    p = next;
  }
  if (values.size() != num_variables + fitness_size)
    return fmt::format("expected {} numbers ({} variables, {} fitness values), found {}",
                       num_variables + fitness_size, num_variables, fitness_size, values.size());
  for (std::size_t j = 0; j < num_variables; ++j)
    if (!std::isfinite(values[j])) return fmt::format("variable {} is not finite", j + 1);
  entry.x.assign(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(num_variables));
  entry.fitness.assign(values.begin() + static_cast<std::ptrdiff_t>(num_variables), values.end());
  entry.note = std::string(note);
  return {};
}

JournalContents read_journal(const std::string& path) {
  const std::string text = read_input_file(path);
  JournalContents contents;
  const std::size_t first_end = text.find('\n');
  std::string first =
      first_end == std::string::npos ? text.substr(0, 60) : text.substr(0, first_end);
  if (!first.empty() && first.back() == '\r') first.pop_back();
  std::istringstream header(first);
  std::string name, hash_text;
  int version = 0;
  header >> name >> version >> hash_text >> contents.num_variables >> contents.fitness_size;
  if (name != kJournalName || !header || (version != 1 && version != kJournalVersion) ||
      hash_text.size() != 16 ||
      hash_text.find_first_not_of("0123456789abcdef") != std::string::npos)
    throw InputError(
        fmt::format("{}:1: expected a pkmopt journal header '{} {} HASH N M', found {}", path,
                    kJournalName, kJournalVersion, quote_found(first)));
  contents.version = version;
  contents.study_hash = std::strtoull(hash_text.c_str(), nullptr, 16);
  std::size_t at = first_end + 1;
  contents.valid_bytes = at;
  std::size_t line_number = 1;
  while (at < text.size()) {
    const std::size_t end = text.find('\n', at);
    ++line_number;
    if (end == std::string::npos) {  // a last line cut by a kill (expected; not damage)
      contents.cut_last_line = true;
      break;
    }
    const std::string_view line = std::string_view(text).substr(at, end - at);
    if (!line.empty() && line.back() == '\r') contents.crlf = true;
    JournalEntry entry;
    const std::string problem = parse_journal_line(line, contents.num_variables,
                                                   contents.fitness_size, entry, version >= 2);
    if (problem.empty()) {
      contents.entries.push_back(std::move(entry));
    } else {
      contents.damaged.push_back({line_number, problem, std::string(line)});
    }
    at = end + 1;
    contents.valid_bytes = at;
  }
  return contents;
}

void JournaledProblem::recover(const std::string& journal_path, JournalContents& contents) const {
  namespace fs = std::filesystem;
  auto warn = [&](const std::string& text) {
    if (options_.warn) options_.warn(text);
  };
  constexpr std::size_t kShown = 10;
  for (std::size_t k = 0; k < contents.damaged.size() && k < kShown; ++k)
    warn(fmt::format("{}:{}: damaged journal line ({}): its design is evaluated again",
                     journal_path, contents.damaged[k].line, contents.damaged[k].problem));
  if (contents.damaged.size() > kShown)
    warn(fmt::format("{}: {} more damaged lines (all of them are in journal.damaged.txt)",
                     journal_path, contents.damaged.size() - kShown));
  const bool rewrite =
      !contents.damaged.empty() || contents.crlf || contents.version != kJournalVersion;
  if (!rewrite) {
    fs::resize_file(journal_path, contents.valid_bytes);  // drop a cut last line
    return;
  }
  if (!contents.damaged.empty()) {  // kept for inspection, never lost
    std::string kept;
    for (const JournalDamage& d : contents.damaged)
      kept += fmt::format("{}\t{}\t{}\n", d.line, d.problem, d.text);
    const int fd = open_append((fs::path(options_.directory) / "journal.damaged.txt").string());
    try {
      write_all(fd, kept, "journal.damaged.txt");
    } catch (...) {
      ::close(fd);
      throw;
    }
    ::close(fd);
  }
  std::string text =
      header_line(contents.study_hash, contents.num_variables, contents.fitness_size);
  for (const JournalEntry& entry : contents.entries) text += journal_line(entry);
  write_file_atomically(journal_path, text);
}

JournaledProblem::JournaledProblem(const Problem& inner, JournalOptions options)
    : ForwardingProblem(inner), options_(std::move(options)) {
  namespace fs = std::filesystem;
  const fs::path dir(options_.directory);
  const std::string journal_path = (dir / "journal.txt").string();
  const std::string csv_path = (dir / "evaluations.csv").string();
  const std::size_t n = inner.num_variables(), m = inner.fitness_size();
  if (options_.resume && fs::exists(journal_path)) {
    JournalContents contents = read_journal(journal_path);
    if (contents.study_hash != options_.study_hash)
      throw InputError(fmt::format(
          "{}: --resume: the journal belongs to another version of the study (study hash {:016x}, "
          "the study file now gives {:016x}); the study file changed since the run started: "
          "restore it, or start over with --force",
          journal_path, contents.study_hash, options_.study_hash));
    if (contents.num_variables != n || contents.fitness_size != m)
      throw InputError(
          fmt::format("{}: --resume: the journal has {} variables and {} fitness "
                      "values per line, the study {} and {}",
                      journal_path, contents.num_variables, contents.fitness_size, n, m));
    recover(journal_path, contents);
    entries_ = std::move(contents.entries);
  } else {
    write_file_atomically(journal_path, header_line(options_.study_hash, n, m));
  }
  loaded_ = entries_.size();
  for (std::size_t k = 0; k < entries_.size(); ++k) {
    index_.emplace(key_of(entries_[k].x), k);
    if (!entries_[k].note.empty()) ++failed_;
    note_feasible(entries_[k]);
  }
  if (options_.csv_row) {
    std::string csv = options_.csv_header + "\n";
    for (std::size_t k = 0; k < entries_.size(); ++k)
      csv += options_.csv_row(k, entries_[k]) + "\n";
    write_file_atomically(csv_path, csv);
    csv_fd_ = open_append(csv_path);
  }
  journal_fd_ = open_append(journal_path);
  terminal_ = ::isatty(STDERR_FILENO) != 0;
  start_ = last_report_ = std::chrono::steady_clock::now();
}

JournaledProblem::~JournaledProblem() {
  if (journal_fd_ >= 0) ::close(journal_fd_);
  if (csv_fd_ >= 0) ::close(csv_fd_);
}

const JournalEntry* JournaledProblem::find(const std::vector<double>& x) const {
  std::lock_guard lock(mutex_);
  const auto it = index_.find(key_of(x));
  return it == index_.end() ? nullptr : &entries_[it->second];
}

long long JournaledProblem::requests() const {
  std::lock_guard lock(mutex_);
  return requests_;
}
long long JournaledProblem::cache_hits() const {
  std::lock_guard lock(mutex_);
  return cache_hits_;
}
long long JournaledProblem::failed() const {
  std::lock_guard lock(mutex_);
  return failed_;
}

void JournaledProblem::append(std::span<const JournalEntry> fresh) const {
  // Called with mutex_ held.
  std::string journal, csv;
  for (const JournalEntry& entry : fresh) {
    const std::size_t k = entries_.size();
    entries_.push_back(entry);
    index_.emplace(key_of(entry.x), k);
    if (!entry.note.empty()) ++failed_;
    note_feasible(entry);
    journal += journal_line(entry);
    if (options_.csv_row) csv += options_.csv_row(k, entry) + "\n";
  }
  write_all(journal_fd_, journal, "journal.txt");
  if (csv_fd_ >= 0) write_all(csv_fd_, csv, "evaluations.csv");
}

std::vector<std::vector<double>> JournaledProblem::serve(std::span<const std::vector<double>> xs,
                                                         int threads) const {
  std::vector<std::vector<double>> result(xs.size());
  long long generation = 0;
  std::vector<std::size_t> misses;  // positions in xs of the first request of each new design
  std::vector<std::ptrdiff_t> source(xs.size(), -1);  // earlier position in xs with the same x
  {
    std::lock_guard lock(mutex_);
    generation = batches_++;
    std::unordered_map<std::string, std::size_t> in_batch;
    for (std::size_t k = 0; k < xs.size(); ++k) {
      ++requests_;
      const std::string key = key_of(xs[k]);
      if (const auto it = index_.find(key); it != index_.end()) {
        JournalEntry& known = entries_[it->second];
        result[k] = known.fitness;
        if (known.generation < 0) known.generation = generation;  // loaded, asked again
        ++cache_hits_;
      } else if (const auto b = in_batch.find(key); b != in_batch.end()) {
        source[k] = static_cast<std::ptrdiff_t>(b->second);
        ++cache_hits_;
      } else {
        in_batch.emplace(key, k);
        misses.push_back(k);
      }
    }
  }
  std::vector<JournalEntry> fresh(misses.size());
  auto evaluate_one = [&](std::size_t i) {
    const std::vector<double>& x = xs[misses[i]];
    if (options_.evaluate) {
      fresh[i] = options_.evaluate(x);
    } else {
      fresh[i].fitness = inner().fitness(x);
    }
    fresh[i].x = x;
    fresh[i].generation = generation;
  };
  const int thread_count = resolve_thread_count(threads);
  if (options_.evaluate_batch) {
    if (!misses.empty()) {
      std::vector<std::vector<double>> todo;
      todo.reserve(misses.size());
      for (std::size_t i : misses) todo.push_back(xs[i]);
      std::lock_guard lock(batch_mutex_);
      fresh = options_.evaluate_batch(todo);
      if (fresh.size() != misses.size())
        throw std::logic_error(fmt::format("evaluate_batch returned {} entries for {} designs",
                                           fresh.size(), misses.size()));
      for (std::size_t i = 0; i < misses.size(); ++i) {
        fresh[i].x = xs[misses[i]];
        fresh[i].generation = generation;
      }
    }
  } else if (thread_count <= 1 || inner().thread_safety() == ThreadSafety::none ||
             misses.size() < 2) {
    for (std::size_t i = 0; i < misses.size(); ++i) evaluate_one(i);
  } else {
    std::exception_ptr first_error;
    const long long count = static_cast<long long>(misses.size());
#pragma omp parallel for num_threads(thread_count) schedule(dynamic)
    for (long long i = 0; i < count; ++i) {
      try {
        evaluate_one(static_cast<std::size_t>(i));
      } catch (...) {
#pragma omp critical(pkmopt_journal_error)
        if (!first_error) first_error = std::current_exception();
      }
    }
    if (first_error) std::rethrow_exception(first_error);
  }
  for (std::size_t i = 0; i < misses.size(); ++i) {
    if (fresh[i].fitness.size() != inner().fitness_size())
      throw std::runtime_error(fmt::format("problem '{}': fitness returned {} values, expected {}",
                                           inner().name(), fresh[i].fitness.size(),
                                           inner().fitness_size()));
    result[misses[i]] = fresh[i].fitness;
  }
  for (std::size_t k = 0; k < xs.size(); ++k)
    if (source[k] >= 0) result[k] = result[static_cast<std::size_t>(source[k])];
  {
    std::lock_guard lock(mutex_);
    // Another thread (single fitness calls) may have recorded one of these meanwhile.
    std::vector<JournalEntry> unseen;
    for (JournalEntry& entry : fresh)
      if (!index_.contains(key_of(entry.x))) unseen.push_back(std::move(entry));
    append(unseen);
  }
  report_progress(false);
  if (options_.on_batch) {
    JournalProgress progress;
    {
      std::lock_guard lock(mutex_);
      merge_front();
      progress = {.requests = requests_,
                  .expected_requests = options_.expected_requests,
                  .cache_hits = cache_hits_,
                  .failed = failed_,
                  .distinct = entries_.size(),
                  .feasible_front = feasible_front_.size()};
    }
    options_.on_batch(progress);
  }
  return result;
}

std::vector<double> JournaledProblem::fitness(const std::vector<double>& x) const {
  const std::vector<double> one[1] = {x};
  return serve(one, 1).front();
}

std::vector<std::vector<double>> JournaledProblem::batch_fitness(
    std::span<const std::vector<double>> xs, int threads) const {
  return serve(xs, threads);
}

void JournaledProblem::note_feasible(const JournalEntry& entry) const {
  // Called with mutex_ held (or from the constructor).
  if (!(options_.show_progress || options_.on_batch) || !is_feasible(inner(), entry)) return;
  pending_front_.emplace_back(
      entry.fitness.begin(), entry.fitness.begin() + static_cast<std::ptrdiff_t>(num_objectives()));
}

void JournaledProblem::merge_front() const {
  // Called with mutex_ held. Only when the front is shown or reported: keeping it up to date
  // after every evaluation cost more than the rest of the journal (a front of thousands of
  // designs on a many-objective problem).
  for (std::vector<double>& point : pending_front_)
    add_non_dominated(feasible_front_, std::move(point));
  pending_front_.clear();
}

void JournaledProblem::report_progress(bool force) const {
  if (!options_.show_progress) return;
  std::lock_guard lock(mutex_);
  const auto now = std::chrono::steady_clock::now();
  const double since = std::chrono::duration<double>(now - last_report_).count();
  const double interval = terminal_ ? 0.25 : options_.log_interval_seconds;
  if (!force && since < interval) return;
  last_report_ = now;
  merge_front();
  const double elapsed = std::chrono::duration<double>(now - start_).count();
  std::string hv = "-";
  if (!feasible_front_.empty() && num_objectives() >= 2 &&
      (num_objectives() <= 3 || feasible_front_.size() <= 64)) {
    const double value = hypervolume(feasible_front_, reference_point_from(feasible_front_));
    if (std::isfinite(value)) hv = fmt::format("{:.4g}", value);
  }
  std::string count = fmt::format("{} evaluations", requests_);
  std::string remaining;
  if (options_.expected_requests > 0) {
    const double fraction = std::min(
        1.0, static_cast<double>(requests_) / static_cast<double>(options_.expected_requests));
    count = fmt::format("{}/{} evaluations ({:.0f}%)", requests_, options_.expected_requests,
                        100.0 * fraction);
    if (fraction > 0.0)
      remaining = fmt::format(", ~{} left", clock_text(elapsed * (1.0 - fraction) / fraction));
    if (terminal_) {
      const int width = 20;
      const int filled = static_cast<int>(fraction * width);
      count = "[" + std::string(static_cast<std::size_t>(filled), '#') +
              std::string(static_cast<std::size_t>(width - filled), '.') + "] " + count;
    }
  }
  const std::string text = fmt::format(
      "{}, {} cached, {} failed, {} feasible non-dominated, hypervolume {}, {}{}", count,
      cache_hits_, failed_, feasible_front_.size(), hv, clock_text(elapsed), remaining);
  if (terminal_) {
    std::fprintf(stderr, "\r\033[2K%s", text.c_str());
    progress_line_open_ = true;
  } else {
    std::fprintf(stderr, "pkmopt: run: %s\n", text.c_str());
  }
  std::fflush(stderr);
}

void JournaledProblem::finish() const {
  report_progress(true);
  std::lock_guard lock(mutex_);
  if (progress_line_open_) {
    std::fputc('\n', stderr);
    progress_line_open_ = false;
  }
  if (options_.csv_row && csv_fd_ >= 0) {
    // Every generation is known now: the file again, whole (the same rows as appended, with the
    // generations of the rows loaded from the journal filled in).
    std::string csv = options_.csv_header + "\n";
    for (std::size_t k = 0; k < entries_.size(); ++k)
      csv += options_.csv_row(k, entries_[k]) + "\n";
    ::close(csv_fd_);
    csv_fd_ = -1;
    write_file_atomically((std::filesystem::path(options_.directory) / "evaluations.csv").string(),
                          csv);
  }
}

}  // namespace pkmopt
