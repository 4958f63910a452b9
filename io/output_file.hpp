// Output files that are either written whole or not at all.
//
// AtomicOutputFile writes to a temporary file beside the target and renames it over the
// target on commit(); if it is destroyed without commit (an error, an exception) the
// temporary is removed, so a failed command never leaves a half-written file.
//
//   AtomicOutputFile out("result.csv");   // throws InputError if the folder is not writable
//   out.stream() << "x,y,z\n";
//   out.commit();
#pragma once

#include <fstream>
#include <string>

namespace pkmopt {

class AtomicOutputFile {
 public:
  explicit AtomicOutputFile(std::string path);
  ~AtomicOutputFile();
  AtomicOutputFile(const AtomicOutputFile&) = delete;
  AtomicOutputFile& operator=(const AtomicOutputFile&) = delete;

  std::ostream& stream() { return stream_; }
  /// Flushes, closes and renames the temporary over the target. Throws InputError on failure.
  void commit();

 private:
  std::string path_;
  std::string temp_path_;
  std::ofstream stream_;
  bool committed_ = false;
};

/// Writes a whole file atomically.
void write_file_atomically(const std::string& path, const std::string& content);

}  // namespace pkmopt
