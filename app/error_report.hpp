// How the command line reports errors: one line "pkmopt: error: ..." per error, CLI11's parse
// errors in pkmopt's words ("--threads: expected an integer, found 'abc'"), the input number
// policy on every real-valued option, and output that could not be written.
//
// Exit status (docs/conventions.md): 0 success, 2 bad input (files, options, values) or an output
// that could not be written, 3 a result written but probably wrong, 1 an internal fault.
//
//   check_real_options(app);                 // before app.parse
//   report("error", "m.yaml:3:7: ...");      // "pkmopt: error: m.yaml:3:7: ..." on stderr
#pragma once

#include <CLI/CLI.hpp>
#include <string>

namespace pkmopt::cli {

/// "pkmopt: <kind>: <message>" on stderr, on one line (newlines in the message become spaces).
/// C stdio, which reports a failed write by its return value: the exit status stays the one the
/// message belongs to even when stderr is a full disk or closed.
void report(const char* kind, const std::string& message) noexcept;

/// Stops `report` from printing: an MPI worker rank (rank 0 reports what every rank would).
void silence_reports() noexcept;

/// Adds the input number policy (io/format/number_policy.hpp: finite, within +-1e15, not subnormal)
/// to every real-valued (FLOAT) option of the app and its subcommands, and refuses an empty value
/// ("--threads ''") for every option that takes one.
void check_real_options(CLI::App& app);

/// The names of the subcommands given ("run", "" for none).
std::string command_path(CLI::App& app);

/// The one-line message of a CLI11 parse error: "run: --threads: expected an integer, found
/// 'abc' (see 'pkmopt run --help')".
std::string parse_error_message(CLI::App& app, const CLI::ParseError& error, int argc, char** argv);

/// Flushes standard output (std::cout and C stdio); false on a write error (errno tells which).
bool flush_stdout();

/// Reports that standard output could not be written; returns the exit status 2.
int output_error();

}  // namespace pkmopt::cli
