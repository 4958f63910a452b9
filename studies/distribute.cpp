#include "studies/distribute.hpp"

#include <fmt/format.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <limits>
#include <thread>

#include "io/format/input_error.hpp"
#include "studies/stop_report.hpp"

#ifdef PKMOPT_HAVE_MPI
#include <mpi.h>
#endif

namespace pkmopt {
namespace {

bool read_int_env(const char* name, int& value) {
  const char* text = std::getenv(name);
  if (text == nullptr || *text == '\0') return false;
  char* end = nullptr;
  errno = 0;
  const long v = std::strtol(text, &end, 10);
  if (errno != 0 || *end != '\0' || v < 0 || v > 1'000'000'000) return false;
  value = static_cast<int>(v);
  return true;
}

}  // namespace

MpiLaunch mpi_launch_from_environment() {
  MpiLaunch launch;
  const std::pair<const char*, const char*> pairs[] = {
      {"OMPI_COMM_WORLD_RANK", "OMPI_COMM_WORLD_SIZE"},
      {"PMIX_RANK", "OMPI_UNIVERSE_SIZE"},
      {"PMIX_RANK", "PMIX_SIZE"},
      {"PMI_RANK", "PMI_SIZE"},
  };
  for (const auto& [rank_name, size_name] : pairs) {
    int rank = 0, size = 0;
    if (read_int_env(rank_name, rank) && read_int_env(size_name, size) && size >= 1 &&
        rank < size) {
      launch.launched = true;
      launch.rank = rank;
      launch.size = size;
      return launch;
    }
  }
  return launch;
}

#ifndef PKMOPT_HAVE_MPI

MpiSession::MpiSession(bool) {
  throw InputError(
      "started by mpirun, but this pkmopt was built without MPI (install libopenmpi-dev and "
      "rebuild with -DPKMOPT_WITH_MPI=ON), so every rank would do the whole work");
}
MpiSession::~MpiSession() = default;
void MpiSession::abort(int status) const { std::_Exit(status); }

std::vector<std::vector<char>> MpiShare::all_gather(std::span<const char> mine) const {
  return {std::vector<char>(mine.begin(), mine.end())};
}

struct MpiDispatcher::State {};
MpiDispatcher::MpiDispatcher(const StudyEvaluator&, double) {
  throw InputError("run: this pkmopt was built without MPI");
}
MpiDispatcher::~MpiDispatcher() = default;
std::vector<JournalEntry> MpiDispatcher::evaluate(std::span<const std::vector<double>>) {
  return {};
}
int MpiDispatcher::workers() const { return 0; }
void serve_as_worker(const std::function<StudyEvaluator()>&, int) {}

#else

namespace {

constexpr int kHelloTag = 11;
constexpr int kTaskTag = 12;
constexpr int kResultTag = 13;
constexpr int kStopTag = 14;
constexpr int kChunksInFlight = 2;  // per worker: the next chunk waits while one is evaluated

// ---- Byte buffers -------------------------------------------------------------------------------

class Writer {
 public:
  template <typename T>
  void put(const T& value) {
    const auto* p = reinterpret_cast<const char*>(&value);
    bytes_.insert(bytes_.end(), p, p + sizeof(T));
  }
  void put_doubles(const std::vector<double>& v) {
    put<std::uint64_t>(v.size());
    const auto* p = reinterpret_cast<const char*>(v.data());
    bytes_.insert(bytes_.end(), p, p + v.size() * sizeof(double));
  }
  void put_string(const std::string& s) {
    put<std::uint64_t>(s.size());
    bytes_.insert(bytes_.end(), s.begin(), s.end());
  }
  const std::vector<char>& bytes() const { return bytes_; }

 private:
  std::vector<char> bytes_;
};

class Reader {
 public:
  Reader(const std::vector<char>& bytes, std::string what)
      : bytes_(bytes), what_(std::move(what)) {}
  template <typename T>
  T get() {
    need(sizeof(T));
    T value;
    std::memcpy(&value, bytes_.data() + at_, sizeof(T));
    at_ += sizeof(T);
    return value;
  }
  std::vector<double> get_doubles() {
    const auto n = get<std::uint64_t>();
    if (n > (bytes_.size() - at_) / sizeof(double)) fail();
    std::vector<double> v(n);
    std::memcpy(v.data(), bytes_.data() + at_, n * sizeof(double));
    at_ += n * sizeof(double);
    return v;
  }
  std::string get_string() {
    const auto n = get<std::uint64_t>();
    need(n);
    std::string s(bytes_.data() + at_, n);
    at_ += n;
    return s;
  }

 private:
  void need(std::size_t n) const {
    if (n > bytes_.size() - at_) fail();
  }
  [[noreturn]] void fail() const {
    throw WorkerFault(
        fmt::format("run: {}: a message that cannot be read (MPI ranks of different "
                    "pkmopt builds?)",
                    what_));
  }
  const std::vector<char>& bytes_;
  std::string what_;
  std::size_t at_ = 0;
};

void send_bytes(const std::vector<char>& bytes, int to, int tag) {
  MPI_Send(bytes.data(), static_cast<int>(bytes.size()), MPI_BYTE, to, tag, MPI_COMM_WORLD);
}

std::vector<char> receive_bytes(const MPI_Status& probed) {
  int count = 0;
  MPI_Get_count(&probed, MPI_BYTE, &count);
  std::vector<char> bytes(static_cast<std::size_t>(count));
  MPI_Recv(bytes.data(), count, MPI_BYTE, probed.MPI_SOURCE, probed.MPI_TAG, MPI_COMM_WORLD,
           MPI_STATUS_IGNORE);
  return bytes;
}

// Waits for a message from `source` (or any) with `tag` (or any): polls, yielding the core to
// other processes for the first 2 ms, then sleeping a little longer each time nothing came (up
// to 250 us), so that an idle rank leaves its core to the busy ones. Returns false when
// `deadline_reached()` says stop first.
template <typename Deadline>
bool wait_for_message(int source, int tag, MPI_Status& status, Deadline deadline_reached) {
  const auto start = std::chrono::steady_clock::now();
  auto pause = std::chrono::microseconds(20);
  for (long long polls = 1;; ++polls) {
    int flag = 0;
    MPI_Iprobe(source, tag, MPI_COMM_WORLD, &flag, &status);
    if (flag) return true;
    if ((polls & 15) == 0 && deadline_reached()) return false;
    if (std::chrono::steady_clock::now() - start < std::chrono::milliseconds(2)) {
      std::this_thread::yield();
      continue;
    }
    std::this_thread::sleep_for(pause);
    pause = std::min(pause * 2, std::chrono::microseconds(250));
  }
}

bool g_workers_stopped = false;  // rank 0 told every worker to stop

std::string design_text(const std::vector<double>& x) {
  std::string s = "[";
  for (std::size_t j = 0; j < x.size(); ++j) {
    if (j == 6) {
      s += fmt::format(", ... {} values", x.size());
      break;
    }
    s += fmt::format("{}{:.6g}", j ? ", " : "", x[j]);
  }
  return s + "]";
}

std::string host_name() {
  char name[MPI_MAX_PROCESSOR_NAME] = {};
  int length = 0;
  MPI_Get_processor_name(name, &length);
  return std::string(name, static_cast<std::size_t>(std::max(length, 0)));
}

struct Hello {
  bool ok = false;
  int threads = 1;
  long long pid = 0;
  std::uint64_t hash = 0;
  std::uint64_t variables = 0;
  std::uint64_t fitness_size = 0;
  std::string host;
  std::string error;
};

void stop_workers(int size) {
  for (int r = 1; r < size; ++r) MPI_Send(nullptr, 0, MPI_BYTE, r, kStopTag, MPI_COMM_WORLD);
  g_workers_stopped = true;
}

}  // namespace

MpiSession::MpiSession(bool with_workers) : with_workers_(with_workers) {
  int initialized = 0;
  MPI_Initialized(&initialized);
  if (!initialized) {
    int provided = 0;
    MPI_Init_thread(nullptr, nullptr, MPI_THREAD_FUNNELED, &provided);
  }
  PMPI_Comm_rank(MPI_COMM_WORLD, &rank_);
  MPI_Comm_size(MPI_COMM_WORLD, &size_);
}

MpiSession::~MpiSession() {
  // Rank 0 that ended before it handed out any work (bad input, a folder it may not write):
  // the workers wait for a word from it.
  if (rank_ == 0 && with_workers_ && !g_workers_stopped) stop_workers(size_);
  int finalized = 0;
  MPI_Finalized(&finalized);
  if (!finalized) PMPI_Finalize();
}

void MpiSession::abort(int status) const {
  // Not MPI_Abort: Open MPI 4.1's mpirun may crash while it handles one (PMIx_server_finalize)
  // and then exits 139. A rank that ends without MPI_Finalize makes mpirun stop every other rank
  // and exit with this rank's status.
  std::fflush(stdout);
  std::fflush(stderr);
  std::_Exit(status);
}

std::vector<std::vector<char>> MpiShare::all_gather(std::span<const char> mine) const {
  if (mine.size() > static_cast<std::size_t>(std::numeric_limits<int>::max()))
    throw std::runtime_error("MPI share: a part of more than 2 GB");
  const int count = static_cast<int>(mine.size());
  std::vector<int> counts(static_cast<std::size_t>(size_)), offsets(counts.size());
  MPI_Allgather(&count, 1, MPI_INT, counts.data(), 1, MPI_INT, MPI_COMM_WORLD);
  long long total = 0;
  for (std::size_t p = 0; p < counts.size(); ++p) {
    offsets[p] = static_cast<int>(total);
    total += counts[p];
    if (total > std::numeric_limits<int>::max())
      throw std::runtime_error("MPI share: more than 2 GB in all");
  }
  std::vector<char> all(static_cast<std::size_t>(total));
  MPI_Allgatherv(mine.data(), count, MPI_BYTE, all.data(), counts.data(), offsets.data(), MPI_BYTE,
                 MPI_COMM_WORLD);
  std::vector<std::vector<char>> parts(counts.size());
  for (std::size_t p = 0; p < counts.size(); ++p)
    parts[p].assign(all.begin() + offsets[p], all.begin() + offsets[p] + counts[p]);
  return parts;
}

struct MpiDispatcher::State {
  double timeout = 600.0;
  int size = 1;
  std::vector<Hello> hellos;      // by rank
  std::vector<WorkerSlot> slots;  // by rank, for the SIGTERM handler
  long long next_task = 0;
  long long batches = 0;
};

MpiDispatcher::MpiDispatcher(const StudyEvaluator& local, double timeout_seconds)
    : state_(std::make_unique<State>()) {
  State& s = *state_;
  s.timeout = timeout_seconds;
  MPI_Comm_size(MPI_COMM_WORLD, &s.size);
  s.hellos.resize(static_cast<std::size_t>(s.size));
  s.slots = std::vector<WorkerSlot>(static_cast<std::size_t>(s.size));
  const std::string here = host_name();
  const auto start = std::chrono::steady_clock::now();
  // Loading the study may take a while on a busy cluster node: at least a minute to greet.
  const double greeting_timeout = std::max(s.timeout, 60.0);
  auto too_late = [&] {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() >
           greeting_timeout;
  };
  std::string first_error;
  for (int greeted = 1; greeted < s.size; ++greeted) {
    MPI_Status status;
    if (!wait_for_message(MPI_ANY_SOURCE, kHelloTag, status, too_late)) {
      std::string missing;
      for (int r = 1; r < s.size; ++r)
        if (s.hellos[static_cast<std::size_t>(r)].pid == 0)
          missing += (missing.empty() ? "" : ", ") + std::to_string(r);
      throw WorkerFault(fmt::format(
          "run: MPI rank(s) {} did not report within {} s of the start (a worker that cannot "
          "start, or a slow shared file system)",
          missing, greeting_timeout));
    }
    const std::vector<char> bytes = receive_bytes(status);
    const int r = status.MPI_SOURCE;
    Reader in(bytes, fmt::format("MPI rank {}", r));
    Hello& h = s.hellos[static_cast<std::size_t>(r)];
    h.ok = in.get<std::uint8_t>() != 0;
    h.threads = std::max(1, in.get<std::int32_t>());
    h.pid = in.get<std::int64_t>();
    h.hash = in.get<std::uint64_t>();
    h.variables = in.get<std::uint64_t>();
    h.fitness_size = in.get<std::uint64_t>();
    h.host = in.get_string();
    h.error = in.get_string();
    WorkerSlot& slot = s.slots[static_cast<std::size_t>(r)];
    slot.pid = static_cast<pid_t>(h.pid);
    slot.same_host = h.host == here;
    if (!first_error.empty()) continue;
    if (!h.ok)
      first_error = fmt::format("MPI rank {} ({}): {}", r, h.host, h.error);
    else if (h.hash != local.study_hash || h.variables != local.num_variables ||
             h.fitness_size != local.fitness_size)
      first_error = fmt::format(
          "MPI rank {} ({}): expected the study file rank 0 read (hash {:016x}), found another "
          "one (hash {:016x}): every rank must read the same study and machine files",
          r, h.host, local.study_hash, h.hash);
  }
  if (!first_error.empty()) {
    stop_workers(s.size);
    s.size = 1;  // stopped already
    throw InputError(first_error);
  }
  report_stop_on_sigterm(s.slots);
}

MpiDispatcher::~MpiDispatcher() {
  State& s = *state_;
  stop_reporting_on_sigterm(s.slots);
  if (s.size > 1) stop_workers(s.size);
}

int MpiDispatcher::workers() const { return state_->size - 1; }

std::vector<JournalEntry> MpiDispatcher::evaluate(std::span<const std::vector<double>> xs) {
  State& s = *state_;
  const long long batch = ++s.batches;
  std::vector<JournalEntry> results(xs.size());
  struct Flight {
    long long task = 0;
    std::size_t first = 0;
    std::size_t count = 0;
    // Sent without blocking: a large chunk goes by rendezvous, and a worker that hangs would hold
    // rank 0 in MPI_Send forever. The bytes stay here until the worker has answered.
    std::vector<char> bytes;
    MPI_Request request = MPI_REQUEST_NULL;
  };
  const std::size_t workers = static_cast<std::size_t>(s.size);
  std::vector<std::vector<Flight>> flights(workers);  // per rank, oldest first
  std::vector<std::chrono::steady_clock::time_point> heard(workers);
  std::size_t next = 0, in_flight = 0;
  std::string first_error;
  auto label = [&](int r) {
    std::string text;
    for (const Flight& f : flights[static_cast<std::size_t>(r)])
      text += fmt::format("{}batch {} design{} {}{} (x = {}{})", text.empty() ? "" : ", ", batch,
                          f.count > 1 ? "s" : "", f.first + 1,
                          f.count > 1 ? fmt::format("-{}", f.first + f.count) : std::string(),
                          design_text(xs[f.first]), f.count > 1 ? ", ..." : "");
    set_label(s.slots[static_cast<std::size_t>(r)], text.empty() ? std::string() : text);
  };
  for (;;) {
    if (first_error.empty())
      for (int r = 1; r < s.size && next < xs.size(); ++r) {
        auto& queue = flights[static_cast<std::size_t>(r)];
        while (static_cast<int>(queue.size()) < kChunksInFlight && next < xs.size()) {
          // Guided self-scheduling: a chunk is the remaining designs over twice the workers, at
          // least the worker's threads; chunks shrink as the batch runs out, so a slow design
          // holds back little, and cheap designs cost few messages.
          const std::size_t remaining = xs.size() - next;
          const std::size_t threads =
              static_cast<std::size_t>(s.hellos[static_cast<std::size_t>(r)].threads);
          const std::size_t guided = (remaining + 2 * (workers - 1) - 1) / (2 * (workers - 1));
          const std::size_t count = std::min(remaining, std::max(threads, guided));
          Writer out;
          out.put<std::int64_t>(s.next_task);
          out.put<std::uint32_t>(static_cast<std::uint32_t>(count));
          for (std::size_t k = next; k < next + count; ++k) out.put_doubles(xs[k]);
          if (queue.empty()) heard[static_cast<std::size_t>(r)] = std::chrono::steady_clock::now();
          queue.push_back({s.next_task++, next, count, out.bytes(), MPI_REQUEST_NULL});
          Flight& sent = queue.back();
          MPI_Isend(sent.bytes.data(), static_cast<int>(sent.bytes.size()), MPI_BYTE, r, kTaskTag,
                    MPI_COMM_WORLD, &sent.request);
          next += count;
          ++in_flight;
          label(r);
        }
      }
    if (in_flight == 0) break;
    MPI_Status status;
    int late = 0;
    auto too_late = [&] {
      const auto now = std::chrono::steady_clock::now();
      for (int r = 1; r < s.size; ++r)
        if (!flights[static_cast<std::size_t>(r)].empty() &&
            std::chrono::duration<double>(now - heard[static_cast<std::size_t>(r)]).count() >
                s.timeout) {
          late = r;
          return true;
        }
      return false;
    };
    if (!wait_for_message(MPI_ANY_SOURCE, kResultTag, status, too_late)) {
      const WorkerSlot& slot = s.slots[static_cast<std::size_t>(late)];
      throw WorkerFault(fmt::format(
          "run: MPI rank {} (pid {} on {}) did not answer within --worker-timeout {} s; it held "
          "{}; the run stops and the journal holds every evaluation of the batches before: "
          "continue with --resume (with a longer --worker-timeout if the evaluation is merely "
          "slow)",
          late, slot.pid, s.hellos[static_cast<std::size_t>(late)].host, s.timeout,
          label_of(slot)));
    }
    const int r = status.MPI_SOURCE;
    const std::vector<char> bytes = receive_bytes(status);
    Reader in(bytes, fmt::format("MPI rank {}", r));
    auto& queue = flights[static_cast<std::size_t>(r)];
    const auto task = in.get<std::int64_t>();
    if (queue.empty() || queue.front().task != task)
      throw WorkerFault(
          fmt::format("run: MPI rank {} answered task {}, which it did not hold", r, task));
    Flight flight = std::move(queue.front());
    queue.erase(queue.begin());
    MPI_Wait(&flight.request, MPI_STATUS_IGNORE);  // answered: its task was received
    --in_flight;
    heard[static_cast<std::size_t>(r)] = std::chrono::steady_clock::now();
    const bool failed = in.get<std::uint8_t>() != 0;
    if (failed) {
      const std::string message = in.get_string();
      if (first_error.empty()) first_error = message;
    } else {
      for (std::size_t k = flight.first; k < flight.first + flight.count; ++k) {
        results[k].fitness = in.get_doubles();
        results[k].note = in.get_string();
      }
    }
    label(r);
  }
  if (!first_error.empty()) throw std::runtime_error(first_error);
  return results;
}

void serve_as_worker(const std::function<StudyEvaluator()>& load, int threads) {
  StudyEvaluator evaluator;
  Hello hello;
  try {
    evaluator = load();
    hello.ok = true;
  } catch (const std::exception& e) {
    hello.error = e.what();
  }
  threads = std::max(1, threads);
  if (!evaluator.thread_safe) threads = 1;
  Writer greeting;
  greeting.put<std::uint8_t>(hello.ok ? 1 : 0);
  greeting.put<std::int32_t>(threads);
  greeting.put<std::int64_t>(static_cast<std::int64_t>(::getpid()));
  greeting.put<std::uint64_t>(evaluator.study_hash);
  greeting.put<std::uint64_t>(evaluator.num_variables);
  greeting.put<std::uint64_t>(evaluator.fitness_size);
  greeting.put_string(host_name());
  greeting.put_string(hello.error);
  send_bytes(greeting.bytes(), 0, kHelloTag);
  for (;;) {
    MPI_Status status;
    wait_for_message(0, MPI_ANY_TAG, status, [] { return false; });
    const std::vector<char> bytes = receive_bytes(status);
    if (status.MPI_TAG == kStopTag) return;
    if (status.MPI_TAG != kTaskTag) continue;
    Reader in(bytes, "rank 0");
    const auto task = in.get<std::int64_t>();
    const auto count = in.get<std::uint32_t>();
    std::vector<std::vector<double>> xs(count);
    for (auto& x : xs) x = in.get_doubles();
    std::vector<JournalEntry> entries(count);
    std::string error = hello.ok ? std::string() : "run: " + hello.error;
    if (hello.ok) {
      std::exception_ptr first;
      const long long n = static_cast<long long>(count);
#pragma omp parallel for num_threads(threads) schedule(dynamic) if (n > 1)
      for (long long k = 0; k < n; ++k) {
        try {
          entries[static_cast<std::size_t>(k)] =
              evaluator.evaluate(xs[static_cast<std::size_t>(k)]);
        } catch (...) {
#pragma omp critical(pkmopt_worker_error)
          if (!first) first = std::current_exception();
        }
      }
      if (first) {
        try {
          std::rethrow_exception(first);
        } catch (const std::exception& e) {
          error = e.what();
        } catch (...) {
          error = "an exception that is not a std::exception";
        }
      }
    }
    Writer out;
    out.put<std::int64_t>(task);
    out.put<std::uint8_t>(error.empty() ? 0 : 1);
    if (!error.empty()) {
      out.put_string(error);
    } else {
      for (const JournalEntry& e : entries) {
        out.put_doubles(e.fitness);
        out.put_string(e.note);
      }
    }
    send_bytes(out.bytes(), 0, kResultTag);
  }
}

#endif

}  // namespace pkmopt
