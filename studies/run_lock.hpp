// The lock of a result folder: one `pkmopt run` writes a folder at a time.
//
// RunLock takes an advisory lock (flock, exclusive) on DIR/run.lock for as long as it lives and
// writes the holder's PID into the file. A second run on the same folder (on this machine, or on
// another one through a file system that supports flock, e.g. NFSv4) is refused with an InputError
// naming the PID that holds it; the lock is released by the kernel when the holder exits, killed
// or not, so a stale run.lock never blocks a resume.
//
// remove_stale_temporaries(DIR) removes the temporaries of atomic writes (NAME.tmp.PID, see
// io/format/output_file.hpp) left in DIR and DIR/designs by a run that was killed mid-write; call
// it with the lock held (no other writer can own them then). It returns how many it removed.
//
// Example:
//   RunLock lock("results/quick");        // throws InputError when another run holds it
//   remove_stale_temporaries("results/quick");
#pragma once

#include <cstddef>
#include <string>

namespace pkmopt {

class RunLock {
 public:
  explicit RunLock(const std::string& directory);
  ~RunLock();
  RunLock(const RunLock&) = delete;
  RunLock& operator=(const RunLock&) = delete;

  const std::string& path() const { return path_; }

 private:
  std::string path_;
  int fd_ = -1;
};

std::size_t remove_stale_temporaries(const std::string& directory);

}  // namespace pkmopt
