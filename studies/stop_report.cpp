#include "studies/stop_report.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>

#include "io/format/input_error.hpp"

namespace pkmopt {
namespace {

WorkerSlot* g_slots = nullptr;
int g_slot_count = 0;
struct sigaction g_previous_term = {};

// The handler's message, composed in one buffer and written with one write(2): mpirun forwards a
// rank's stderr while it tears the job down, and a second write may not reach the terminal.
char g_message[8192];
std::size_t g_message_length = 0;

// The decimal digits of v >= 0 at `out` (at most 20); returns how many. Async-signal-safe.
std::size_t decimal(char* out, long long v) {
  char digits[24];
  std::size_t n = 0;
  do {
    digits[n++] = static_cast<char>('0' + v % 10);
    v /= 10;
  } while (v > 0 && n < 20);
  for (std::size_t i = 0; i < n; ++i) out[i] = digits[n - 1 - i];
  return n;
}

void add_text(const char* text, std::size_t n) {
  n = std::min(n, sizeof g_message - 1 - g_message_length);
  std::memcpy(g_message + g_message_length, text, n);
  g_message_length += n;
}
void add_text(const char* text) { add_text(text, std::strlen(text)); }

void add_int(long long v) {
  char digits[24];
  add_text(digits, decimal(digits, v));
}

void add_slot(int rank, const WorkerSlot& slot) {
  add_text("rank ");
  add_int(rank);
  add_text(" (pid ");
  add_int(slot.pid);
  add_text(") held ");
  const int length = slot.label_length;
  if (length > 0 && length < static_cast<int>(WorkerSlot::kLabel))
    add_text(slot.label, static_cast<std::size_t>(length));
  else
    add_text("no design");
}

// A process of this host that ended before mpirun's SIGTERM reached rank 0: gone (mpirun reaps a
// rank that dies at once, then stops the others), or a zombie whose exit status (the last field
// of /proc/PID/stat, as waitpid reports it) is not "killed by SIGTERM". Async-signal-safe (kill,
// open, read, close).
bool process_died(pid_t pid) {
  if (pid <= 0) return false;
  if (::kill(pid, 0) != 0 && errno == ESRCH) return true;  // ended and reaped by mpirun already
  char path[64] = "/proc/";
  const std::size_t at = 6 + decimal(path + 6, pid);
  std::memcpy(path + at, "/stat", 6);
  const int fd = ::open(path, O_RDONLY);
  if (fd < 0) return false;
  char stat[1024];
  const ssize_t got = ::read(fd, stat, sizeof stat - 1);
  ::close(fd);
  if (got <= 0) return false;
  ssize_t close_paren = -1;  // "pid (comm) S ...": the state follows the last ')'
  for (ssize_t i = got - 1; i > 0 && close_paren < 0; --i)
    if (stat[i] == ')') close_paren = i;
  if (close_paren < 0 || close_paren + 2 >= got) return false;
  const char state = stat[close_paren + 2];
  if (state != 'Z' && state != 'X') return false;
  ssize_t end = got;
  while (end > 0 && (stat[end - 1] == '\n' || stat[end - 1] == ' ')) --end;
  ssize_t begin = end;
  while (begin > 0 && stat[begin - 1] >= '0' && stat[begin - 1] <= '9') --begin;
  if (begin == end) return true;
  long long status = 0;
  for (ssize_t i = begin; i < end; ++i) status = status * 10 + (stat[i] - '0');
  return (status & 0x7f) != SIGTERM;
}

extern "C" void on_terminate(int) {
  // Async-signal-safe: kill, open, read, close, write and _exit only.
  g_message_length = 0;
  add_text(
      "pkmopt: error: run: stopped by mpirun (SIGTERM: a rank died or the job was "
      "cancelled); ");
  bool dead_found = false;
  for (int r = 1; r < g_slot_count; ++r) {
    const WorkerSlot& slot = g_slots[r];
    if (!slot.same_host || !process_died(slot.pid)) continue;
    add_text(dead_found ? "; ended first: " : "ended first: ");
    add_slot(r, slot);
    dead_found = true;
  }
  bool listed = false;
  for (int r = 1; r < g_slot_count; ++r) {
    const WorkerSlot& slot = g_slots[r];
    if (slot.label_length == 0 || (slot.same_host && process_died(slot.pid))) continue;
    add_text(listed || dead_found ? "; still running: " : "still running: ");
    add_slot(r, slot);
    listed = true;
  }
  if (!dead_found && !listed) add_text("no design was in flight");
  add_text(
      "; the journal holds every evaluation of the batches before: continue with "
      "--resume\n");
  const char* text = g_message;
  std::size_t left = g_message_length;
  while (left > 0) {
    const ssize_t w = ::write(STDERR_FILENO, text, left);
    if (w <= 0) break;
    text += w;
    left -= static_cast<std::size_t>(w);
  }
  ::_exit(kExitWorkerFault);
}

}  // namespace

void set_label(WorkerSlot& slot, const std::string& text) {
  slot.label_length = 0;
  const std::size_t n = std::min(text.size(), WorkerSlot::kLabel - 1);
  std::memcpy(slot.label, text.data(), n);
  slot.label_length = static_cast<sig_atomic_t>(n);
}

std::string label_of(const WorkerSlot& slot) {
  return std::string(slot.label, static_cast<std::size_t>(slot.label_length));
}

void report_stop_on_sigterm(std::span<WorkerSlot> slots) {
  g_slots = slots.data();
  g_slot_count = static_cast<int>(slots.size());
  struct sigaction action = {};
  action.sa_handler = on_terminate;
  sigemptyset(&action.sa_mask);
  sigaction(SIGTERM, &action, &g_previous_term);
}

void stop_reporting_on_sigterm(std::span<WorkerSlot> slots) {
  if (g_slots != slots.data()) return;
  sigaction(SIGTERM, &g_previous_term, nullptr);
  g_slots = nullptr;
  g_slot_count = 0;
}

}  // namespace pkmopt
