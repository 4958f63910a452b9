// Output files that are either written whole or not at all.
//
// AtomicOutputFile writes to a temporary file beside the target and renames it over the
// target on commit(); if it is destroyed without commit (an error, an exception) the
// temporary is removed, so a failed command never leaves a half-written file.
//
// What an existing path is decides what is replaced (docs/conventions.md, "Outputs"): a regular
// file is replaced; a symbolic link is followed and its target replaced (the link stays; a
// dangling link's target is created); a character device (/dev/null) or a FIFO is written into
// as it is, never replaced (a FIFO nobody reads is an error); a folder, a block device or a
// socket is refused with an InputError.
//
//   AtomicOutputFile out("result.csv");   // throws InputError if the folder is not writable
//   out.stream() << "x,y,z\n";
//   out.commit();
#pragma once

#include <fstream>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

namespace pkmopt {

class AtomicOutputFile {
 public:
  explicit AtomicOutputFile(std::string path);
  ~AtomicOutputFile();
  AtomicOutputFile(const AtomicOutputFile&) = delete;
  AtomicOutputFile& operator=(const AtomicOutputFile&) = delete;

  std::ostream& stream();
  /// Flushes, closes and renames the temporary over the target (a device or FIFO: writes the
  /// bytes into it). Throws InputError on failure.
  void commit();
  /// After commit(): removes the file commit() moved into place (the target of a followed link,
  /// never the link; nothing for a device or FIFO), for commands whose outputs go together.
  void revert();

 private:
  std::string path_;
  std::string target_;  ///< the regular file replaced (a followed link's target)
  std::string temp_path_;
  std::ofstream file_;
  std::ostringstream buffer_;  ///< for a device or FIFO
  bool in_place_ = false;
  bool committed_ = false;
};

/// Writes a whole file atomically.
void write_file_atomically(const std::string& path, const std::string& content);

/// The outputs of one command, all or none: every file is written to its temporary first (a
/// path that cannot be written fails before any file is moved into place), then all are moved
/// into place; when one of those moves fails, the ones already moved are removed again. Throws
/// InputError naming the file.
using OutputFiles = std::vector<std::pair<std::string, std::string>>;  ///< (path, content)
void write_files_together(const OutputFiles& files);

}  // namespace pkmopt
