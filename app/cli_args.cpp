#include "app/cli_args.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>

#include "app/commands.hpp"
#include "io/format/input_error.hpp"
#include "io/format/number_policy.hpp"

namespace pkmopt {

std::vector<double> parse_number_list(std::string_view option, const std::string& text,
                                      std::size_t count, double max_magnitude) {
  std::vector<double> values;
  auto fail = [&](std::string_view why) {
    throw InputError(fmt::format("{}: expected {} comma-separated finite numbers, found {}{}",
                                 option, count, quote_found(text), why));
  };
  std::size_t start = 0;
  while (true) {
    const std::size_t comma = text.find(',', start);
    std::string item =
        text.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
    while (!item.empty() && item.front() == ' ') item.erase(item.begin());
    while (!item.empty() && item.back() == ' ') item.pop_back();
    char* end = nullptr;
    const double v = item.empty() ? 0.0 : read_input_number(item.c_str(), &end);
    if (item.empty() || end != item.c_str() + item.size()) {
      fail(fmt::format(" (item {} is not a number)", values.size() + 1));
    }
    if (!std::isfinite(v)) fail(fmt::format(" (item {} is not finite)", values.size() + 1));
    if (!sane_input_number(v) || std::abs(v) > max_magnitude) {
      fail(fmt::format(" (item {} is outside +-{:g}{})", values.size() + 1,
                       std::min(max_magnitude, kMaxInputMagnitude),
                       std::abs(v) > 0.0 && std::abs(v) < kMinInputMagnitude
                           ? " or below 1e-30 in magnitude"
                           : ""));
    }
    values.push_back(v);
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  if (values.size() != count) fail(fmt::format(" ({} numbers)", values.size()));
  return values;
}

std::vector<double> parse_wrench_option(const std::string& text) {
  return parse_number_list("--wrench", text, 6, kMaxInputForce);
}

void bad_option(std::string_view option, std::string_view expected, double found) {
  throw InputError(fmt::format("{}: expected {}, found {}", option, expected, found));
}

namespace cli {

CLI::Validator number_check(bool (*accept)(double), std::string_view expected,
                            const std::string& name) {
  return CLI::Validator(
      [accept, expected](std::string& text) -> std::string {
        char* end = nullptr;
        const double v = read_input_number(text.c_str(), &end);
        if (end == text.c_str() || *end != '\0') return {};  // CLI11 reports a non-number
        if (accept(v)) return {};
        return "expected " + std::string(expected) + ", found " + text;
      },
      "", name);
}

CLI::Validator length_in_metres() {
  return number_check(sane_input_length, kLengthText, "length in metres");
}

}  // namespace cli

void require_results_folder(const std::string& dir) {
  namespace fs = std::filesystem;
  if (!fs::is_directory(fs::path(dir)))
    throw InputError(fmt::format("{}: expected a results folder of `pkmopt run`, found {}", dir,
                                 fs::exists(fs::path(dir)) ? "a file" : "no such folder"));
}

void require_not_a_folder(std::string_view option, const std::string& path) {
  if (!path.empty() && std::filesystem::is_directory(std::filesystem::path(path)))
    throw InputError(
        fmt::format("{}: expected a file name, found the folder {}", option, quote_found(path)));
}

}  // namespace pkmopt
