// What rank 0 of a distributed run says when mpirun stops it with SIGTERM (a rank died, or the
// job was cancelled): which worker ended first (on this host) and which designs each worker held,
// on one line, then exit status 4. The handler is async-signal-safe: it only reads the slots,
// /proc and writes one buffer, so the dispatcher keeps each worker's slot up to date as it sends
// and receives (studies/distribute.cpp).
#pragma once

#include <signal.h>
#include <sys/types.h>

#include <cstddef>
#include <span>
#include <string>

namespace pkmopt {

/// One worker as the SIGTERM handler sees it; slot r is rank r (slot 0 unused).
struct WorkerSlot {
  static constexpr std::size_t kLabel = 480;
  pid_t pid = 0;
  bool same_host = false;                  ///< on rank 0's host: /proc tells whether it ended
  volatile sig_atomic_t label_length = 0;  ///< 0: holds nothing
  char label[kLabel] = {};                 ///< the designs it holds, in words
};

/// The designs a worker holds, for the handler (cut to WorkerSlot::kLabel - 1 bytes).
void set_label(WorkerSlot& slot, const std::string& text);
/// The label as text (for messages outside the handler).
std::string label_of(const WorkerSlot& slot);

/// Installs the SIGTERM handler that reports `slots`; stop_reporting_on_sigterm(slots) puts the
/// previous handler back. The slots must outlive the report.
void report_stop_on_sigterm(std::span<WorkerSlot> slots);
void stop_reporting_on_sigterm(std::span<WorkerSlot> slots);

}  // namespace pkmopt
