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

namespace {

// Reads the records of a CSV text one by one (RFC 4180 quoting; a quoted field may span lines),
// counting lines for the messages.
class RecordReader {
 public:
  RecordReader(std::string_view text, const std::string& file) : text_(text), file_(file) {}
  // The next record into `cells` (its first line in `record_line`; `blank` when it is an empty
  // line); false at the end of the text.
  bool next(std::vector<std::string>& cells, int& record_line, bool& blank) {
    cells.clear();
    if (pos_ >= text_.size()) return false;
    record_line = line_;
    std::string cell;
    bool in_quotes = false;
    bool was_quoted = false;
    int quote_line = line_;
    while (pos_ < text_.size()) {
      const char c = text_[pos_];
      if (in_quotes) {
        if (c == '"') {
          if (pos_ + 1 < text_.size() && text_[pos_ + 1] == '"') {
            cell += '"';
            pos_ += 2;
            continue;
          }
          in_quotes = false;
          ++pos_;
          continue;
        }
        if (c == '\n') ++line_;
        cell += c;
        ++pos_;
        continue;
      }
      if (c == '"' && trim(cell).empty()) {
        in_quotes = true;
        was_quoted = true;
        quote_line = line_;
        cell.clear();
        ++pos_;
        continue;
      }
      if (c == ',') {
        cells.push_back(cell);
        cell.clear();
        was_quoted = false;
        ++pos_;
        continue;
      }
      if (c == '\r' || c == '\n') {
        if (c == '\r' && pos_ + 1 < text_.size() && text_[pos_ + 1] == '\n') ++pos_;
        ++pos_;
        ++line_;
        break;
      }
      cell += c;
      ++pos_;
    }
    if (in_quotes) {
      throw InputError(fmt::format("{}unterminated quoted field (expected a closing '\"')",
                                   location_prefix(file_, quote_line)));
    }
    cells.push_back(cell);
    blank = cells.size() == 1 && trim(cells[0]).empty() && !was_quoted;
    return true;
  }

 private:
  std::string_view text_;
  const std::string& file_;
  std::size_t pos_ = 0;
  int line_ = 1;
};

// A header's names are non-empty and used once.
void check_header(const std::vector<std::string>& header, const std::string& file,
                  int record_line) {
  for (std::size_t i = 0; i < header.size(); ++i) {
    if (header[i].empty()) {
      throw InputError(fmt::format("{}column {}: expected a column name, found an empty one",
                                   location_prefix(file, record_line), i + 1));
    }
    for (std::size_t j = 0; j < i; ++j) {
      if (header[i] == header[j]) {
        throw InputError(fmt::format("{}column {}: duplicate column name {}",
                                     location_prefix(file, record_line), i + 1,
                                     quote_found(header[i])));
      }
    }
  }
}

}  // namespace

CsvTable parse_csv(const std::string& text_in, const std::string& file) {
  require_utf8(text_in, file);
  std::string_view text(text_in);
  if (text.substr(0, 3) == "\xEF\xBB\xBF") text.remove_prefix(3);
  CsvTable table;
  table.file = file;

  RecordReader reader(text, file);

  std::vector<std::string> cells;
  int record_line = 0;
  bool blank = false;
  bool have_header = false;
  while (reader.next(cells, record_line, blank)) {
    if (blank) continue;
    if (!have_header) {
      for (auto& c : cells) table.header.push_back(trim(c));
      table.header_line = record_line;
      have_header = true;
      check_header(table.header, file, record_line);
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
