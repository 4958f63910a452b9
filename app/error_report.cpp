#include "app/error_report.hpp"

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <iostream>
#include <string_view>
#include <vector>

#include "app/commands.hpp"
#include "io/format/input_error.hpp"
#include "io/format/number_policy.hpp"

namespace pkmopt::cli {
namespace {

// The deepest subcommand given (the app itself when none is).
CLI::App* given_command(CLI::App& app) {
  CLI::App* sub = &app;
  while (!sub->get_subcommands().empty()) sub = sub->get_subcommands().front();
  return sub;
}

// "an integer" for CLI11's INT, ...: what an option's value must be, in words.
std::string expected_value(const CLI::Option* option) {
  const std::string type = option != nullptr ? option->get_type_name() : "";
  if (type == "INT") return "an integer";
  if (type == "UINT") return "a non-negative integer";
  if (type == "FLOAT") return "a number";
  if (type.empty() || type == "TEXT") return "a value";
  return "a value of the form " + type;
}

// Edit distance with adjacent transpositions (optimal string alignment: "rnu" is one edit
// from "run"), for "did you mean".
std::size_t edit_distance(std::string_view a, std::string_view b) {
  std::vector<std::vector<std::size_t>> d(a.size() + 1, std::vector<std::size_t>(b.size() + 1));
  for (std::size_t i = 0; i <= a.size(); ++i) d[i][0] = i;
  for (std::size_t j = 0; j <= b.size(); ++j) d[0][j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i)
    for (std::size_t j = 1; j <= b.size(); ++j) {
      d[i][j] = std::min(
          {d[i - 1][j] + 1, d[i][j - 1] + 1, d[i - 1][j - 1] + (a[i - 1] == b[j - 1] ? 0 : 1)});
      if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1])
        d[i][j] = std::min(d[i][j], d[i - 2][j - 2] + 1);
    }
  return d[a.size()][b.size()];
}

// "; did you mean '--out'?" when one of `names` is close to `given` (at most 2 edits, and at
// most half its length), else "".
std::string did_you_mean(std::string_view given, const std::vector<std::string>& names) {
  std::string best;
  std::size_t best_distance = 3;
  for (const std::string& name : names) {
    const std::size_t d = edit_distance(given, name);
    if (d < best_distance && 2 * d <= name.size()) {
      best = name;
      best_distance = d;
    }
  }
  return best.empty() ? std::string() : "; did you mean '" + best + "'?";
}

// The long option names of a command ("--out", "--threads", ...).
std::vector<std::string> option_names(const CLI::App& command) {
  std::vector<std::string> names;
  for (const CLI::Option* option : command.get_options())
    for (const std::string& name : option->get_lnames()) names.push_back("--" + name);
  return names;
}

// CLI11's parse errors in the words of every other pkmopt message: what was expected, what was
// found. Unknown texts are kept as CLI11 wrote them.
std::string parse_error_text(CLI::App& app, const CLI::ParseError& error, int argc, char** argv) {
  CLI::App* command = given_command(app);
  const std::string what = error.what();
  // Arguments no option or positional takes are the first thing to report (CLI11 checks the
  // required options before them, which blames a missing --out for a misspelt --ouy).
  const std::vector<std::string> extras = command->remaining(true);
  if (!extras.empty() && command != &app) {
    std::string list;
    for (const std::string& e : extras) list += (list.empty() ? "" : " ") + quote_found(e);
    std::string hint;
    for (const std::string& e : extras) {
      const std::string given = e.substr(0, e.find('='));  // --ouy=x
      if (given.starts_with("-") && hint.empty())
        hint = did_you_mean(given, option_names(*command));
    }
    return "expected the options and arguments listed by --help, found unknown " + list + hint;
  }
  if (command == &app && what.find("subcommand is required") != std::string::npos) {
    std::string names;
    std::vector<std::string> list;
    for (const CLI::App* sub : app.get_subcommands([](CLI::App*) { return true; })) {
      names += (names.empty() ? "" : ", ") + sub->get_name();
      list.push_back(sub->get_name());
    }
    return std::string("expected a command (") + names + "), found " +
           (argc > 1 ? quote_found(argv[1]) + did_you_mean(argv[1], list) : std::string("none"));
  }
  constexpr std::string_view kConvert = "Could not convert: ";
  if (what.starts_with(kConvert)) {  // "Could not convert: --threads = abc"
    const std::string rest = what.substr(kConvert.size());
    const std::size_t eq = rest.find(" = ");
    if (eq != std::string::npos) {
      const std::string name = rest.substr(0, eq);
      return name + ": expected " + expected_value(command->get_option_no_throw(name)) +
             ", found " + quote_found(rest.substr(eq + 3));
    }
  }
  // "--threads: 1 required INT missing"
  if (const std::size_t at = what.find(" required ");
      at != std::string::npos && what.ends_with(" missing")) {
    const std::size_t colon = what.find(": ");
    if (colon != std::string::npos && colon < at) {
      const std::string name = what.substr(0, colon);
      return name + ": expected " + expected_value(command->get_option_no_throw(name)) +
             " after it, found nothing";
    }
  }
  return what;
}

}  // namespace

// "pkmopt: <kind>: <message>" on stderr, on one line. C stdio, which reports a failed write
// (stderr a full disk, a closed descriptor) by its return value instead of an exception: the
// exit status is then still the one the message belongs to.
namespace {
bool g_silent = false;
}  // namespace

void silence_reports() noexcept { g_silent = true; }

void report(const char* kind, const std::string& message) noexcept {
  if (g_silent) return;
  std::string line = message;
  for (char& c : line)
    if (c == '\n' || c == '\r') c = ' ';
  std::fprintf(stderr, "pkmopt: %s: %s\n", kind, line.c_str());
  std::fflush(stderr);
}

// Every real-valued option of every command obeys the input number policy
// (io/format/number_policy.hpp): finite, within +-1e15, not subnormal; no option takes an empty
// value.
void check_real_options(CLI::App& app) {
  const CLI::Validator sane = cli::number_check(sane_input_number, kSaneNumberText, "sane number");
  // An option given an empty value ("--threads ''") is not given a value: refused, whatever its
  // type (CLI11 would read '' as 0 or as an empty text).
  const CLI::Validator non_empty(
      [](std::string& text) -> std::string {
        return text.empty() ? "expected a value, found an empty string" : std::string();
      },
      "", "non-empty");
  for (CLI::Option* option : app.get_options()) {
    if (option->get_type_name() == "FLOAT") option->check(sane);
    if (option->get_type_size_max() > 0 && option->get_expected_max() > 0 &&
        option->get_name() != "--help" && option->get_name() != "--version")
      option->check(non_empty);
  }
  for (CLI::App* sub : app.get_subcommands([](CLI::App*) { return true; }))
    check_real_options(*sub);
}

// The names of the subcommands given, for "pkmopt: error: run: ..." and its --help hint.
std::string command_path(CLI::App& app) {
  std::string path;
  for (CLI::App* sub = &app; !sub->get_subcommands().empty();) {
    sub = sub->get_subcommands().front();
    path += (path.empty() ? "" : " ") + sub->get_name();
  }
  return path;
}

// Output written to standard output (std::cout and C stdio) reached it; false on a full disk,
// a closed descriptor or any other write error, with errno describing it.
bool flush_stdout() {
  std::cout.flush();
  const bool cout_ok = !std::cout.fail();
  errno = 0;
  const bool stdio_ok = std::fflush(stdout) == 0 && !std::ferror(stdout);
  return cout_ok && stdio_ok;
}

int output_error() {
  const int saved = errno;
  report("error", std::string("cannot write to standard output") +
                      (saved != 0 ? std::string(": ") + std::strerror(saved) : std::string()));
  return kExitInputError;
}

std::string parse_error_message(CLI::App& app, const CLI::ParseError& error, int argc,
                                char** argv) {
  const std::string command = command_path(app);
  return (command.empty() ? std::string() : command + ": ") +
         parse_error_text(app, error, argc, argv) + " (see 'pkmopt " +
         (command.empty() ? "" : command + " ") + "--help')";
}

}  // namespace pkmopt::cli
