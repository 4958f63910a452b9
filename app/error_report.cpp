#include "app/error_report.hpp"

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <iostream>
#include <string_view>
#include <vector>

#include "io/input_error.hpp"
#include "io/number_policy.hpp"

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
    return "expected the options and arguments listed by --help, found unknown " + list;
  }
  if (command == &app && what.find("subcommand is required") != std::string::npos) {
    std::string names;
    for (const CLI::App* sub : app.get_subcommands([](CLI::App*) { return true; }))
      names += (names.empty() ? "" : ", ") + sub->get_name();
    return std::string("expected a command (") + names + "), found " +
           (argc > 1 ? quote_found(argv[1]) : std::string("none"));
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
void report(const char* kind, const std::string& message) noexcept {
  std::string line = message;
  for (char& c : line)
    if (c == '\n' || c == '\r') c = ' ';
  std::fprintf(stderr, "pkmopt: %s: %s\n", kind, line.c_str());
  std::fflush(stderr);
}

// Every real-valued option of every command obeys the input number policy
// (io/number_policy.hpp): finite, within +-1e15, not subnormal.
void check_real_options(CLI::App& app) {
  const CLI::Validator sane(
      [](std::string& text) -> std::string {
        char* end = nullptr;
        const double v = std::strtod(text.c_str(), &end);
        if (end == text.c_str() || *end != '\0') return {};  // CLI11 reports a non-number
        if (sane_input_number(v)) return {};
        return "expected " + std::string(kSaneNumberText) + ", found " + text;
      },
      "", "sane number");
  for (CLI::Option* option : app.get_options()) {
    if (option->get_type_name() == "FLOAT") option->check(sane);
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
