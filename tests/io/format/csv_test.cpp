// Tests of io/format/csv: reading with exact error locations, round-trip number formatting.
#include "io/format/csv.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "io/format/input_error.hpp"

namespace pkmopt {
namespace {

std::string error_of(const std::string& text) {
  try {
    parse_csv(text, "poses.csv");
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(Csv, ReadsQuotedFieldsCrLfBomAndBlankLines) {
  const CsvTable t =
      parse_csv("\xEF\xBB\xBFx,y,z,label\r\n1,2,3,\"a,\"\"b\"\"\"\r\n\r\n4,5,6,c\n", "f.csv");
  ASSERT_EQ(t.header.size(), 4u);
  EXPECT_EQ(t.header[0], "x");
  ASSERT_EQ(t.rows.size(), 2u);
  EXPECT_EQ(t.rows[0].cells[3], "a,\"b\"");
  EXPECT_EQ(t.rows[0].line, 2);
  EXPECT_EQ(t.rows[1].line, 4);
  EXPECT_EQ(t.number(t.rows[1], 2), 6.0);
}

TEST(Csv, ErrorsNameLineColumnExpectedAndFound) {
  EXPECT_EQ(error_of("x,y,z\n1,2,3\n1,2\n"),
            "poses.csv:3: expected 3 fields as in the header, found 2");
  EXPECT_EQ(error_of(""), "poses.csv: expected a header line, found an empty file");
  EXPECT_EQ(error_of("x,y,x\n"), "poses.csv:1: column 3: duplicate column name 'x'");
  EXPECT_EQ(error_of("x,y\n\"1,2\n"),
            "poses.csv:2: unterminated quoted field (expected a closing '\"')");
  const CsvTable t = parse_csv("x,y,z\n1,abc,3\n1,nan,2\n", "poses.csv");
  try {
    t.number(t.rows[0], 1);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(), "poses.csv:2: column 2 'y': expected a finite number, found 'abc'");
  }
  EXPECT_THROW(t.number(t.rows[1], 1), InputError);
  try {
    t.require_column("rx");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(), "poses.csv:1: expected a column 'rx' in the header, found 'x,y,z'");
  }
}

TEST(Csv, NumbersRoundTrip) {
  for (double v : {0.1, 1.0 / 3.0, -2.5e-300, 1e22, 6.02214076e23, 0.0}) {
    EXPECT_EQ(std::strtod(format_number(v).c_str(), nullptr), v);
  }
  EXPECT_EQ(format_number(std::numeric_limits<double>::infinity()), "inf");
  EXPECT_EQ(format_number(1.0), "1");
  EXPECT_EQ(csv_field("a,b"), "\"a,b\"");
  EXPECT_EQ(csv_field("plain"), "plain");
}

}  // namespace
}  // namespace pkmopt
