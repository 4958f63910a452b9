#include "app/cli_args.hpp"

#include <fmt/format.h>

#include <cmath>
#include <cstdlib>

#include "io/input_error.hpp"

namespace pkmopt {

std::vector<double> parse_number_list(std::string_view option, const std::string& text,
                                      std::size_t count) {
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
    const double v = item.empty() ? 0.0 : std::strtod(item.c_str(), &end);
    if (item.empty() || end != item.c_str() + item.size()) {
      fail(fmt::format(" (item {} is not a number)", values.size() + 1));
    }
    if (!std::isfinite(v)) fail(fmt::format(" (item {} is not finite)", values.size() + 1));
    values.push_back(v);
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  if (values.size() != count) fail(fmt::format(" ({} numbers)", values.size()));
  return values;
}

void bad_option(std::string_view option, std::string_view expected, double found) {
  throw InputError(fmt::format("{}: expected {}, found {}", option, expected, found));
}

}  // namespace pkmopt
