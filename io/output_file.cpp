#include "io/output_file.hpp"

#include <fmt/format.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>

#include "io/input_error.hpp"

namespace pkmopt {

AtomicOutputFile::AtomicOutputFile(std::string path) : path_(std::move(path)) {
  temp_path_ = fmt::format("{}.tmp.{}", path_, static_cast<long>(::getpid()));
  stream_.open(temp_path_, std::ios::binary | std::ios::trunc);
  if (!stream_) {
    throw InputError(
        fmt::format("{}: cannot write the output file (does its folder exist?)", path_));
  }
}

AtomicOutputFile::~AtomicOutputFile() {
  if (!committed_) {
    stream_.close();
    std::remove(temp_path_.c_str());
  }
}

void AtomicOutputFile::commit() {
  stream_.flush();
  const bool ok = static_cast<bool>(stream_);
  stream_.close();
  if (!ok) throw InputError(fmt::format("{}: writing the output file failed", path_));
  std::error_code ec;
  std::filesystem::rename(temp_path_, path_, ec);
  if (ec) {
    throw InputError(
        fmt::format("{}: cannot move the output file into place: {}", path_, ec.message()));
  }
  committed_ = true;
}

void write_file_atomically(const std::string& path, const std::string& content) {
  AtomicOutputFile out(path);
  out.stream() << content;
  out.commit();
}

}  // namespace pkmopt
