// CSV files read and written by the CLI (pose files, measurement files, results).
//
// Reading: RFC 4180 fields (quotes, "" escapes, CRLF or LF, an optional UTF-8 BOM); the first
// non-empty line is the header; empty lines are skipped; every row must have as many fields as
// the header. Errors throw InputError naming file, line and column:
//   poses.csv:7: column 3 'z': expected a finite number, found 'abc'
// Writing: numbers with the shortest text that round-trips (format_number), fields quoted
// only when they need it.
//
//   CsvTable poses = read_csv_file("poses.csv");
//   int x = poses.require_column("x");
//   for (const CsvRow& row : poses.rows) double value = poses.number(row, x);
#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace pkmopt {

struct CsvRow {
  int line = 0;  ///< 1-based line number in the file
  std::vector<std::string> cells;
};

struct CsvTable {
  std::string file;
  int header_line = 0;
  std::vector<std::string> header;
  std::vector<CsvRow> rows;

  /// Index of a column, or -1.
  int column(std::string_view name) const;
  /// Index of a column; throws InputError naming the file and the columns found if absent.
  int require_column(std::string_view name) const;
  /// The cell as a finite number; throws InputError with line, column and the cell text.
  double number(const CsvRow& row, int column) const;
};

/// Reads a whole CSV file. Throws InputError (missing/unreadable file, no header, duplicate
/// column names, ragged rows, unterminated quotes).
CsvTable read_csv_file(const std::string& path);
/// Parses CSV text (`file` is used in messages).
CsvTable parse_csv(const std::string& text, const std::string& file);

/// Shortest text that reads back as the same double; "inf"/"-inf" for infinities.
std::string format_number(double value);
/// A field quoted if it contains a comma, quote, CR or LF.
std::string csv_field(std::string_view text);

}  // namespace pkmopt
