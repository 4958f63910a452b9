// Errors in what a user gave pkmopt: files, options, values.
//
// Every bad input becomes one InputError whose message names the file, the line and column
// (1-based) or the key, what was expected and what was found, e.g.
//   machine.yaml:4:12: legs.min_length: expected a finite number, found 'abc'
// The CLI prints the message to stderr and exits with status 2 (kExitInputError); internal
// failures exit with status 1.
#pragma once

#include <cstddef>
#include <stdexcept>
#include <string>
#include <string_view>

namespace pkmopt {

inline constexpr int kExitInputError = 2;
inline constexpr int kExitInternalError = 1;
/// A command that finished and wrote its output, but whose result is probably wrong (a
/// calibration that did not converge or rejected most poses): exit status 3.
inline constexpr int kExitProbablyWrong = 3;
/// A distributed run stopped because a worker process failed (an MPI rank that died or did not
/// answer in time): the journal is intact and `--resume` continues. Exit status 4.
inline constexpr int kExitWorkerFault = 4;

/// Thrown by a command after its output is written when the result is probably wrong; the CLI
/// prints "pkmopt: warning: <message>" and exits with kExitProbablyWrong.
class ProbablyWrongResult : public std::runtime_error {
 public:
  explicit ProbablyWrongResult(const std::string& message) : std::runtime_error(message) {}
};

class InputError : public std::runtime_error {
 public:
  explicit InputError(const std::string& message) : std::runtime_error(message) {}
};

/// "file:line:col: " (line and column 1-based; omitted when <= 0).
std::string location_prefix(std::string_view file, int line = 0, int column = 0);

/// Inputs larger than this are refused before they are read ("larger than 1 GiB").
inline constexpr std::size_t kMaxInputFileBytes = std::size_t{1} << 30;

/// The whole content of a regular file; throws InputError "path: cannot open the file ..." when
/// it is missing or unreadable, "path: expected a regular file, found a directory" (a FIFO, a
/// device, a socket) without reading it, and "path: ... larger than 1 GiB" for a file (or a
/// /proc file that keeps producing bytes) past kMaxInputFileBytes.
std::string read_input_file(const std::string& path);

/// Throws InputError "file:line:col: expected UTF-8 text, found the byte 0xff" at the first
/// byte of `text` that is not part of a valid UTF-8 sequence (overlong forms, surrogates and
/// code points above U+10FFFF included).
void require_utf8(std::string_view text, std::string_view file);

/// A short, printable rendering of a found value for messages ('abc', 'a very lo...').
std::string quote_found(std::string_view text);

}  // namespace pkmopt
