// Tests of io/format/input_error: the "file:line:column: " prefix of every input error, reading a
// whole input file, and how found values are quoted in messages.
#include "io/format/input_error.hpp"

#include <gtest/gtest.h>

#include <string>

#include "tests/scratch_dir.hpp"

namespace pkmopt {
namespace {

TEST(InputError, LocationPrefix) {
  EXPECT_EQ(location_prefix("m.yaml", 4, 12), "m.yaml:4:12: ");
  EXPECT_EQ(location_prefix("poses.csv", 7), "poses.csv:7: ");
  EXPECT_EQ(location_prefix("poses.csv", 7, 0), "poses.csv:7: ");
  EXPECT_EQ(location_prefix("poses.csv"), "poses.csv: ");
  EXPECT_EQ(location_prefix("poses.csv", 0, 3), "poses.csv: ");  // no column without a line
  EXPECT_EQ(kExitInputError, 2);
  EXPECT_EQ(kExitInternalError, 1);
}

TEST(InputError, ReadInputFile) {
  const scratch::ScratchDir dir;
  const std::string text = std::string("a\r\nb\0c", 6);
  EXPECT_EQ(read_input_file(dir.write("f.bin", text)), text);  // bytes as stored
  const std::string missing = (dir / "missing.yaml").string();
  try {
    read_input_file(missing);
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()),
              missing + ": cannot open the file (does it exist and is it readable?)");
  }
}

TEST(InputError, QuoteFound) {
  EXPECT_EQ(quote_found("abc"), "'abc'");
  EXPECT_EQ(quote_found(""), "''");
  EXPECT_EQ(quote_found("a\nb\tc\rd"), "'a\\nb\\tc\\rd'");
  // At most 60 characters, then "...".
  EXPECT_EQ(quote_found(std::string(60, 'x')), "'" + std::string(60, 'x') + "'");
  EXPECT_EQ(quote_found(std::string(61, 'x')), "'" + std::string(60, 'x') + "...'");
}

}  // namespace
}  // namespace pkmopt
