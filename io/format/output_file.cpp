#include "io/format/output_file.hpp"

#include <fcntl.h>
#include <fmt/format.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <memory>

#include "io/format/input_error.hpp"

namespace pkmopt {
namespace {

namespace fs = std::filesystem;

// What an output path names: where the temporary goes and the file it replaces, or a device or
// FIFO to write into as it is (docs/conventions.md, "Outputs").
struct OutputTarget {
  std::string replaced;   // the regular file (new or existing) the temporary is renamed over
  bool in_place = false;  // a character device or a FIFO: written directly, never replaced
};

OutputTarget resolve_output(const std::string& path) {
  struct stat link_info {};
  if (::lstat(path.c_str(), &link_info) != 0) return {path, false};  // a new file
  struct stat info {};
  const bool followed = ::stat(path.c_str(), &info) == 0;
  if (S_ISLNK(link_info.st_mode)) {
    if (!followed) {  // a dangling link: its target is created, the link kept
      std::error_code ec;
      fs::path target = fs::read_symlink(path, ec);
      if (ec)
        throw InputError(fmt::format("{}: cannot read the symbolic link: {}", path, ec.message()));
      if (target.is_relative()) target = fs::path(path).parent_path() / target;
      return {target.string(), false};
    }
    if (S_ISREG(info.st_mode)) {  // the link's target is replaced, the link kept
      std::error_code ec;
      const fs::path target = fs::canonical(path, ec);
      if (ec)
        throw InputError(
            fmt::format("{}: cannot follow the symbolic link: {}", path, ec.message()));
      return {target.string(), false};
    }
  } else {
    info = link_info;
  }
  if (S_ISREG(info.st_mode)) return {path, false};
  if (S_ISCHR(info.st_mode) || S_ISFIFO(info.st_mode)) return {path, true};
  const char* kind = S_ISDIR(info.st_mode)    ? "a folder"
                     : S_ISBLK(info.st_mode)  ? "a block device"
                     : S_ISSOCK(info.st_mode) ? "a socket"
                                              : "a special file";
  throw InputError(fmt::format(
      "{}: expected a file to write (or a character device or FIFO to write into), found {}", path,
      kind));
}

}  // namespace

AtomicOutputFile::AtomicOutputFile(std::string path) : path_(std::move(path)) {
  const OutputTarget target = resolve_output(path_);
  in_place_ = target.in_place;
  target_ = target.replaced;
  if (in_place_) return;  // written on commit, from the buffer
  temp_path_ = fmt::format("{}.tmp.{}", target_, static_cast<long>(::getpid()));
  file_.open(temp_path_, std::ios::binary | std::ios::trunc);
  if (!file_) {
    throw InputError(
        fmt::format("{}: cannot write the output file (does its folder exist?)", path_));
  }
}

AtomicOutputFile::~AtomicOutputFile() {
  if (!committed_ && !in_place_) {
    file_.close();
    std::remove(temp_path_.c_str());
  }
}

std::ostream& AtomicOutputFile::stream() {
  if (in_place_) return buffer_;
  return file_;
}

void AtomicOutputFile::commit() {
  if (in_place_) {
    // A device or FIFO: opened without blocking (a FIFO nobody reads is an error, not a hang),
    // then written whole.
    const int fd = ::open(path_.c_str(), O_WRONLY | O_NONBLOCK | O_CLOEXEC);
    if (fd < 0)
      throw InputError(
          fmt::format("{}: cannot write into it: {}", path_,
                      errno == ENXIO ? "no process reads this FIFO" : std::strerror(errno)));
    ::fcntl(fd, F_SETFL, ::fcntl(fd, F_GETFL) & ~O_NONBLOCK);
    const std::string bytes = buffer_.str();
    std::size_t done = 0;
    while (done < bytes.size()) {
      const ssize_t n = ::write(fd, bytes.data() + done, bytes.size() - done);
      if (n < 0 && errno == EINTR) continue;
      if (n <= 0) {
        const int saved = errno;
        ::close(fd);
        throw InputError(fmt::format("{}: writing failed: {}", path_, std::strerror(saved)));
      }
      done += static_cast<std::size_t>(n);
    }
    ::close(fd);
    committed_ = true;
    return;
  }
  file_.flush();
  const bool ok = static_cast<bool>(file_);
  file_.close();
  if (!ok) throw InputError(fmt::format("{}: writing the output file failed", path_));
  std::error_code ec;
  std::filesystem::rename(temp_path_, target_, ec);
  if (ec) {
    throw InputError(
        fmt::format("{}: cannot move the output file into place: {}", path_, ec.message()));
  }
  committed_ = true;
}

void AtomicOutputFile::revert() {
  if (!committed_ || in_place_) return;
  std::error_code ec;
  std::filesystem::remove(target_, ec);
}

void write_file_atomically(const std::string& path, const std::string& content) {
  AtomicOutputFile out(path);
  out.stream() << content;
  out.commit();
}

void write_files_together(const OutputFiles& files) {
  std::vector<std::unique_ptr<AtomicOutputFile>> outputs;
  for (const auto& [path, content] : files) {
    outputs.push_back(std::make_unique<AtomicOutputFile>(path));
    outputs.back()->stream() << content;
  }
  std::size_t committed = 0;
  try {
    for (; committed < outputs.size(); ++committed) outputs[committed]->commit();
  } catch (...) {
    for (std::size_t k = 0; k < committed; ++k) outputs[k]->revert();
    throw;
  }
}

}  // namespace pkmopt
