// Shared by the libFuzzer targets: each input is written to a file in a private scratch folder
// (so the readers are driven exactly as the command line drives them, file reading included),
// and only pkmopt's InputError may come out of a reader. Any other exception, a crash, a
// sanitizer report, a hang or running out of memory is a finding.
//
//   extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
//     fuzz::expect_input_errors([&] { pkmopt::load_machine_file(fuzz::write_input(data, size)); });
//     return 0;
//   }
#pragma once

#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "io/format/input_error.hpp"

namespace fuzz {

/// The scratch folder of this fuzzing process (created on first use, removed at exit).
inline const std::filesystem::path& scratch() {
  static const std::filesystem::path dir = [] {
    std::filesystem::path d =
        std::filesystem::temp_directory_path() / ("pkmopt-fuzz-" + std::to_string(::getpid()));
    std::filesystem::create_directories(d);
    std::atexit([] {
      std::error_code ec;
      std::filesystem::remove_all(scratch(), ec);
    });
    return d;
  }();
  return dir;
}

/// Writes the input to scratch()/name and returns its path.
inline std::string write_input(const std::uint8_t* data, std::size_t size,
                               const std::string& name = "input") {
  const std::filesystem::path path = scratch() / name;
  std::ofstream(path, std::ios::binary | std::ios::trunc)
      .write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  return path.string();
}

/// Copies a file shipped with pkmopt (path relative to the source tree) into scratch(), for
/// inputs that name other files (a calibration file names its machine and measurements).
inline void stage(const std::string& source_relative, const std::string& name) {
  std::filesystem::copy_file(std::filesystem::path(PKMOPT_SOURCE_DIR) / source_relative,
                             scratch() / name, std::filesystem::copy_options::overwrite_existing);
}

/// Runs a reader; an InputError (the documented answer to bad input) is expected.
template <class Read>
void expect_input_errors(Read&& read) {
  try {
    read();
  } catch (const pkmopt::InputError&) {
  }
}

}  // namespace fuzz
