#include "io/input_error.hpp"

#include <fmt/format.h>

#include <fstream>
#include <sstream>

namespace pkmopt {

std::string location_prefix(std::string_view file, int line, int column) {
  if (line > 0 && column > 0) return fmt::format("{}:{}:{}: ", file, line, column);
  if (line > 0) return fmt::format("{}:{}: ", file, line);
  return fmt::format("{}: ", file);
}

std::string read_input_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    throw InputError(
        fmt::format("{}: cannot open the file (does it exist and is it readable?)", path));
  }
  std::stringstream buffer;
  buffer << in.rdbuf();
  if (in.bad()) throw InputError(fmt::format("{}: cannot read the file", path));
  return buffer.str();
}

std::string quote_found(std::string_view text) {
  constexpr std::size_t kMax = 60;
  std::string shown;
  for (char c : text.substr(0, kMax)) {
    if (c == '\n') {
      shown += "\\n";
    } else if (c == '\r') {
      shown += "\\r";
    } else if (c == '\t') {
      shown += "\\t";
    } else {
      shown += c;
    }
  }
  if (text.size() > kMax) shown += "...";
  return "'" + shown + "'";
}

}  // namespace pkmopt
