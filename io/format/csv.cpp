#include "io/format/csv.hpp"

#include <fmt/format.h>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include "io/format/input_error.hpp"
#include "io/format/number_policy.hpp"

namespace pkmopt {
namespace {

std::string trim(std::string_view s) {
  std::size_t b = 0, e = s.size();
  while (b < e && (s[b] == ' ' || s[b] == '\t')) ++b;
  while (e > b && (s[e - 1] == ' ' || s[e - 1] == '\t')) --e;
  return std::string(s.substr(b, e - b));
}

}  // namespace

int CsvTable::column(std::string_view name) const {
  for (std::size_t i = 0; i < header.size(); ++i) {
    if (header[i] == name) return static_cast<int>(i);
  }
  return -1;
}

int CsvTable::require_column(std::string_view name) const {
  const int index = column(name);
  if (index < 0) {
    std::string found;
    for (std::size_t i = 0; i < header.size(); ++i) found += (i ? "," : "") + header[i];
    throw InputError(fmt::format("{}expected a column '{}' in the header, found {}",
                                 location_prefix(file, header_line), name, quote_found(found)));
  }
  return index;
}

double CsvTable::number(const CsvRow& row, int col) const {
  const std::string text = trim(row.cells.at(static_cast<std::size_t>(col)));
  const char* begin = text.c_str();
  char* end = nullptr;
  const double value = text.empty() ? 0.0 : read_input_number(begin, &end);
  if (text.empty() || end != begin + text.size() || !std::isfinite(value)) {
    throw InputError(fmt::format(
        "{}column {} {}: expected a finite number, found {}", location_prefix(file, row.line),
        col + 1, quote_found(header[static_cast<std::size_t>(col)]), quote_found(text)));
  }
  if (!sane_input_number(value)) {
    throw InputError(fmt::format(
        "{}column {} {}: expected {}, found {}", location_prefix(file, row.line), col + 1,
        quote_found(header[static_cast<std::size_t>(col)]), kSaneNumberText, quote_found(text)));
  }
  return value;
}

CsvTable parse_csv(const std::string& text_in, const std::string& file) {
  require_utf8(text_in, file);
  std::string_view text(text_in);
  if (text.substr(0, 3) == "\xEF\xBB\xBF") text.remove_prefix(3);
  CsvTable table;
  table.file = file;

  std::size_t pos = 0;
  int line = 1;
  // Parse one record starting at pos; returns false at end of input.
  auto next_record = [&](std::vector<std::string>& cells, int& record_line, bool& blank) {
    cells.clear();
    if (pos >= text.size()) return false;
    record_line = line;
    std::string cell;
    bool in_quotes = false;
    bool was_quoted = false;
    int quote_line = line;
    while (pos < text.size()) {
      const char c = text[pos];
      if (in_quotes) {
        if (c == '"') {
          if (pos + 1 < text.size() && text[pos + 1] == '"') {
            cell += '"';
            pos += 2;
            continue;
          }
          in_quotes = false;
          ++pos;
          continue;
        }
        if (c == '\n') ++line;
        cell += c;
        ++pos;
        continue;
      }
      if (c == '"' && trim(cell).empty()) {
        in_quotes = true;
        was_quoted = true;
        quote_line = line;
        cell.clear();
        ++pos;
        continue;
      }
      if (c == ',') {
        cells.push_back(cell);
        cell.clear();
        was_quoted = false;
        ++pos;
        continue;
      }
      if (c == '\r' || c == '\n') {
        if (c == '\r' && pos + 1 < text.size() && text[pos + 1] == '\n') ++pos;
        ++pos;
        ++line;
        break;
      }
      cell += c;
      ++pos;
    }
    if (in_quotes) {
      throw InputError(fmt::format("{}unterminated quoted field (expected a closing '\"')",
                                   location_prefix(file, quote_line)));
    }
    cells.push_back(cell);
    blank = cells.size() == 1 && trim(cells[0]).empty() && !was_quoted;
    return true;
  };

  std::vector<std::string> cells;
  int record_line = 0;
  bool blank = false;
  bool have_header = false;
  while (next_record(cells, record_line, blank)) {
    if (blank) continue;
    if (!have_header) {
      for (auto& c : cells) table.header.push_back(trim(c));
      table.header_line = record_line;
      have_header = true;
      for (std::size_t i = 0; i < table.header.size(); ++i) {
        if (table.header[i].empty()) {
          throw InputError(fmt::format("{}column {}: expected a column name, found an empty one",
                                       location_prefix(file, record_line), i + 1));
        }
        for (std::size_t j = 0; j < i; ++j) {
          if (table.header[i] == table.header[j]) {
            throw InputError(fmt::format("{}column {}: duplicate column name {}",
                                         location_prefix(file, record_line), i + 1,
                                         quote_found(table.header[i])));
          }
        }
      }
      continue;
    }
    if (cells.size() != table.header.size()) {
      throw InputError(fmt::format("{}expected {} fields as in the header, found {}",
                                   location_prefix(file, record_line), table.header.size(),
                                   cells.size()));
    }
    table.rows.push_back(CsvRow{record_line, cells});
  }
  if (!have_header) {
    throw InputError(
        fmt::format("{}expected a header line, found an empty file", location_prefix(file)));
  }
  return table;
}

CsvTable read_csv_file(const std::string& path) { return parse_csv(read_input_file(path), path); }

std::string format_number(double value) {
  if (std::isnan(value)) return "nan";  // never written by pkmopt outputs; kept for safety
  if (std::isinf(value)) return value > 0 ? "inf" : "-inf";
  return fmt::format("{}", value);
}

std::string csv_field(std::string_view text) {
  if (text.find_first_of(",\"\r\n") == std::string_view::npos) return std::string(text);
  std::string out = "\"";
  for (char c : text) {
    if (c == '"') out += '"';
    out += c;
  }
  out += '"';
  return out;
}

}  // namespace pkmopt
