#include "io/format/input_error.hpp"

#include <fcntl.h>
#include <fmt/format.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

namespace pkmopt {
namespace {

// Closes a descriptor on every path out of read_input_file.
struct Descriptor {
  int fd = -1;
  ~Descriptor() {
    if (fd >= 0) ::close(fd);
  }
};

const char* file_type_name(mode_t mode) {
  if (S_ISDIR(mode)) return "a directory";
  if (S_ISFIFO(mode)) return "a FIFO (named pipe)";
  if (S_ISCHR(mode)) return "a character device";
  if (S_ISBLK(mode)) return "a block device";
  if (S_ISSOCK(mode)) return "a socket";
  return "a special file";
}

}  // namespace

std::string location_prefix(std::string_view file, int line, int column) {
  if (line > 0 && column > 0) return fmt::format("{}:{}:{}: ", file, line, column);
  if (line > 0) return fmt::format("{}:{}: ", file, line);
  return fmt::format("{}: ", file);
}

std::string read_input_file(const std::string& path) {
  // O_NONBLOCK: opening a FIFO must not wait for a writer; the type check below refuses it.
  Descriptor d{::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC)};
  if (d.fd < 0) {
    const int error = errno;
    if (error == ENOENT || error == EACCES || error == ENOTDIR)
      throw InputError(
          fmt::format("{}: cannot open the file (does it exist and is it readable?)", path));
    throw InputError(fmt::format("{}: cannot open the file: {}", path, std::strerror(error)));
  }
  struct stat st {};
  if (::fstat(d.fd, &st) != 0) {
    throw InputError(fmt::format("{}: cannot read the file: {}", path, std::strerror(errno)));
  }
  if (!S_ISREG(st.st_mode)) {
    throw InputError(
        fmt::format("{}: expected a regular file, found {}", path, file_type_name(st.st_mode)));
  }
  if (static_cast<unsigned long long>(st.st_size) > kMaxInputFileBytes) {
    throw InputError(fmt::format("{}: expected an input file of at most 1 GiB, found {} bytes",
                                 path, static_cast<unsigned long long>(st.st_size)));
  }
  // Back to blocking reads for a regular file (O_NONBLOCK has no effect on them, but be plain).
  ::fcntl(d.fd, F_SETFL, ::fcntl(d.fd, F_GETFL) & ~O_NONBLOCK);
  std::string content;
  content.reserve(static_cast<std::size_t>(st.st_size));
  char buffer[1 << 16];
  while (true) {
    const ssize_t n = ::read(d.fd, buffer, sizeof buffer);
    if (n == 0) break;
    if (n < 0) {
      if (errno == EINTR) continue;
      throw InputError(fmt::format("{}: cannot read the file: {}", path, std::strerror(errno)));
    }
    // /proc files report size 0 and can produce bytes without end: the limit holds here too.
    if (content.size() + static_cast<std::size_t>(n) > kMaxInputFileBytes) {
      throw InputError(
          fmt::format("{}: expected an input file of at most 1 GiB, found more", path));
    }
    content.append(buffer, static_cast<std::size_t>(n));
  }
  return content;
}

void require_utf8(std::string_view text, std::string_view file) {
  std::size_t i = 0;
  int line = 1;
  std::size_t line_start = 0;
  while (i < text.size()) {
    const auto c = static_cast<unsigned char>(text[i]);
    std::size_t length = 0;
    unsigned int code = 0;
    unsigned int min_code = 0;
    if (c < 0x80) {
      if (c == '\n') {
        ++line;
        line_start = i + 1;
      }
      ++i;
      continue;
    }
    if ((c & 0xE0) == 0xC0) {
      length = 2, code = c & 0x1Fu, min_code = 0x80;
    } else if ((c & 0xF0) == 0xE0) {
      length = 3, code = c & 0x0Fu, min_code = 0x800;
    } else if ((c & 0xF8) == 0xF0) {
      length = 4, code = c & 0x07u, min_code = 0x10000;
    }
    bool valid = length > 0 && i + length <= text.size();
    for (std::size_t k = 1; valid && k < length; ++k) {
      const auto next = static_cast<unsigned char>(text[i + k]);
      valid = (next & 0xC0) == 0x80;
      code = (code << 6) | (next & 0x3Fu);
    }
    valid = valid && code >= min_code && code <= 0x10FFFF && !(code >= 0xD800 && code <= 0xDFFF);
    if (!valid) {
      const int column = static_cast<int>(i - line_start) + 1;
      throw InputError(fmt::format("{}expected UTF-8 text, found the byte 0x{:02x}",
                                   location_prefix(file, line, column), c));
    }
    i += length;
  }
}

std::string quote_found(std::string_view text) {
  constexpr std::size_t kMax = 60;
  std::string shown;
  for (char c : text.substr(0, kMax)) {
    const auto u = static_cast<unsigned char>(c);
    if (c == '\n') {
      shown += "\\n";
    } else if (c == '\r') {
      shown += "\\r";
    } else if (c == '\t') {
      shown += "\\t";
    } else if (u < 0x20 || u == 0x7f) {
      shown += fmt::format("\\x{:02x}", u);
    } else {
      shown += c;
    }
  }
  if (text.size() > kMax) shown += "...";
  return "'" + shown + "'";
}

}  // namespace pkmopt
