#include "studies/run_lock.hpp"

#include <fcntl.h>
#include <fmt/format.h>
#include <sys/file.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <string_view>

#include "io/format/input_error.hpp"

namespace pkmopt {
namespace {

// The PID written by the holder ("?" when the file cannot be read or is empty).
std::string holder_pid(int fd) {
  char buffer[32] = {};
  const ssize_t got = ::pread(fd, buffer, sizeof buffer - 1, 0);
  std::string text = got > 0 ? std::string(buffer, static_cast<std::size_t>(got)) : "";
  while (!text.empty() && (text.back() == '\n' || text.back() == ' ')) text.pop_back();
  const bool digits = !text.empty() && text.find_first_not_of("0123456789") == std::string::npos;
  return digits ? text : "?";
}

// NAME.tmp.PID with PID all digits.
bool is_temporary_name(std::string_view name) {
  const std::size_t at = name.rfind(".tmp.");
  if (at == std::string_view::npos || at == 0) return false;
  const std::string_view pid = name.substr(at + 5);
  return !pid.empty() && pid.find_first_not_of("0123456789") == std::string_view::npos;
}

}  // namespace

RunLock::RunLock(const std::string& directory)
    : path_((std::filesystem::path(directory) / "run.lock").string()) {
  fd_ = ::open(path_.c_str(), O_RDWR | O_CREAT | O_CLOEXEC | O_NOFOLLOW, 0644);
  if (fd_ < 0)
    throw InputError(
        fmt::format("{}: cannot create the run lock: {}", path_, std::strerror(errno)));
  if (::flock(fd_, LOCK_EX | LOCK_NB) != 0) {
    const int error = errno;
    const std::string pid = holder_pid(fd_);
    ::close(fd_);
    fd_ = -1;
    if (error == EWOULDBLOCK)
      throw InputError(fmt::format(
          "{}: another pkmopt run (PID {}) is writing this folder; wait for it to finish or stop "
          "it, then run again (with --resume to continue its journal)",
          path_, pid));
    throw InputError(fmt::format("{}: cannot lock: {}", path_, std::strerror(error)));
  }
  const std::string pid = fmt::format("{}\n", static_cast<long>(::getpid()));
  if (::ftruncate(fd_, 0) != 0 ||
      ::pwrite(fd_, pid.data(), pid.size(), 0) != static_cast<ssize_t>(pid.size())) {
    const int error = errno;
    ::close(fd_);
    fd_ = -1;
    throw InputError(fmt::format("{}: cannot write the run lock: {}", path_, std::strerror(error)));
  }
}

RunLock::~RunLock() {
  if (fd_ >= 0) ::close(fd_);  // closing releases the lock; the file stays (it is harmless)
}

std::size_t remove_stale_temporaries(const std::string& directory) {
  namespace fs = std::filesystem;
  std::size_t removed = 0;
  for (const fs::path& dir : {fs::path(directory), fs::path(directory) / "designs"}) {
    std::error_code ec;
    if (!fs::is_directory(dir, ec)) continue;
    for (const fs::directory_entry& entry : fs::directory_iterator(dir, ec)) {
      if (!entry.is_regular_file(ec)) continue;
      if (!is_temporary_name(entry.path().filename().string())) continue;
      if (fs::remove(entry.path(), ec)) ++removed;
    }
  }
  return removed;
}

}  // namespace pkmopt
