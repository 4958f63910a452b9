// Tests of io/format/yaml_reader: strict reading of YAML with every message carrying file, line and
// column (1-based, counted by hand in the texts below), the dotted key path, what was expected
// and what was found.
#include "io/format/yaml_reader.hpp"

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "io/format/input_error.hpp"
#include "tests/scratch_dir.hpp"

namespace pkmopt {
namespace {

// The message of `read` on the root of `text` (file name m.yaml).
template <class Read>
std::string error_of(const std::string& text, Read read) {
  try {
    read(YamlValue::load_string(text, "m.yaml"));
  } catch (const InputError& e) {
    return e.what();
  }
  return "no error";
}

const char* const kText =
    "model: hexapod\n"                        // line 1
    "legs: {min_length: 0.7, stroke: abc}\n"  // line 2: stroke's value at column 33
    "tool:\n"                                 // line 3
    "  tcp: [0, 0, -0.1]\n"                   // line 4: the list at column 8
    "count: 12\n"                             // line 5
    "flag: true\n"                            // line 6
    "empty:\n";                               // line 7

TEST(YamlReader, ValuesKeysAndPaths) {
  const YamlValue root = YamlValue::load_string(kText, "m.yaml");
  EXPECT_EQ(root.file(), "m.yaml");
  EXPECT_EQ(root.path(), "");
  EXPECT_TRUE(root.is_map());
  EXPECT_EQ(root.keys(),
            (std::vector<std::string>{"model", "legs", "tool", "count", "flag", "empty"}));
  EXPECT_TRUE(root.has("legs"));
  EXPECT_FALSE(root.has("legs.min_length"));
  EXPECT_EQ(root.required("model").as_string(), "hexapod");
  const YamlValue min_length = root.required("legs").required("min_length");
  EXPECT_EQ(min_length.path(), "legs.min_length");
  EXPECT_EQ(min_length.line(), 2);
  EXPECT_EQ(min_length.column(), 20);
  EXPECT_EQ(min_length.as_double(), 0.7);
  EXPECT_EQ(min_length.as_positive(), 0.7);
  EXPECT_EQ(min_length.as_non_negative(), 0.7);
  const YamlValue tcp = root.required("tool").required("tcp");
  EXPECT_EQ(tcp.path(), "tool.tcp");
  EXPECT_EQ(tcp.as_doubles(3), (std::vector<double>{0, 0, -0.1}));
  const std::vector<YamlValue> elements = tcp.elements();
  ASSERT_EQ(elements.size(), 3u);
  EXPECT_EQ(elements[2].path(), "tool.tcp[2]");
  EXPECT_EQ(root.required("count").as_int(), 12);
  EXPECT_TRUE(root.required("flag").as_bool());
  EXPECT_TRUE(root.required("empty").is_null());
  EXPECT_FALSE(root.optional("absent").has_value());
  ASSERT_TRUE(root.optional("count").has_value());
  EXPECT_EQ(root.optional("count")->as_int(), 12);
  EXPECT_EQ(root.required("legs").describe(), "a map");
  EXPECT_EQ(tcp.describe(), "a list of 3");
  EXPECT_EQ(root.required("model").describe(), "'hexapod'");
  EXPECT_EQ(root.required("empty").describe(), "nothing (null)");
}

TEST(YamlReader, MessagesNameFileLineColumnKeyExpectedAndFound) {
  EXPECT_EQ(error_of(kText,
                     [](const YamlValue& r) { r.required("legs").required("stroke").as_double(); }),
            "m.yaml:2:33: legs.stroke: expected a finite number, found 'abc'");
  EXPECT_EQ(
      error_of(kText, [](const YamlValue& r) { r.required("tool").required("tcp").as_doubles(2); }),
      "m.yaml:4:8: tool.tcp: expected a list of 2, found a list of 3");
  EXPECT_EQ(error_of(kText, [](const YamlValue& r) { r.required("model").as_int(); }),
            "m.yaml:1:8: model: expected an integer, found 'hexapod'");
  EXPECT_EQ(error_of(kText, [](const YamlValue& r) { r.required("count").as_bool(); }),
            "m.yaml:5:8: count: expected true or false, found '12'");
  EXPECT_EQ(error_of(kText, [](const YamlValue& r) { r.required("legs").as_string(); }),
            "m.yaml:2:7: legs: expected a string, found a map");
  EXPECT_EQ(error_of("x: -1\n", [](const YamlValue& r) { r.required("x").as_positive(); }),
            "m.yaml:1:4: x: expected a number > 0, found '-1'");
  EXPECT_EQ(error_of("x: -1\n", [](const YamlValue& r) { r.required("x").as_non_negative(); }),
            "m.yaml:1:4: x: expected a number >= 0, found '-1'");
  EXPECT_EQ(error_of("x: .inf\n", [](const YamlValue& r) { r.required("x").as_double(); }),
            "m.yaml:1:4: x: expected a finite number, found '.inf'");
  // A missing key is reported at the map; an empty value at its key.
  EXPECT_EQ(error_of(kText, [](const YamlValue& r) { r.required("tool").required("axis"); }),
            "m.yaml:4:3: tool: missing required key 'axis'");
  EXPECT_EQ(error_of(kText, [](const YamlValue& r) { r.required("empty").as_double(); }),
            "m.yaml:7:1: empty: expected a finite number, found nothing (null)");
  // Strict maps: an unknown key points at the key and lists the allowed ones; repeated keys.
  EXPECT_EQ(error_of(kText,
                     [](const YamlValue& r) {
                       r.required("legs").check_keys({"min_length", "max_length"});
                     }),
            "m.yaml:2:25: legs.stroke: unknown key 'stroke'; allowed keys here: min_length, "
            "max_length");
  EXPECT_EQ(error_of("a: 1\nb: 2\na: 3\n",
                     [](const YamlValue& r) {
                       r.check_keys({"a", "b"});
                     }),
            "m.yaml:3:1: a: duplicate key 'a'");
  EXPECT_EQ(error_of("- 1\n- 2\n", [](const YamlValue& r) { r.check_keys({"a"}); }),
            "m.yaml:1:1: expected a map of keys, found a list of 2");
  EXPECT_EQ(
      error_of(kText, [](const YamlValue& r) { r.required("legs").fail("a custom message"); }),
      "m.yaml:2:7: legs: a custom message");
}

TEST(YamlReader, FilesAndMalformedText) {
  const scratch::ScratchDir dir;
  const std::string file = dir.write("machine.yaml", "model: hexapod\nbase: [1, 2\n");
  try {
    YamlValue::load_file(file);
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()).rfind(file + ":3:1: malformed YAML", 0), 0u) << e.what();
  }
  try {
    YamlValue::load_file((dir / "none.yaml").string());
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("none.yaml: cannot open the file"), std::string::npos)
        << e.what();
  }
  const YamlValue good = YamlValue::load_file(dir.write("good.yaml", "a: [1.5, 2]\n"));
  EXPECT_EQ(good.file(), (dir / "good.yaml").string());
  EXPECT_EQ(good.required("a").as_doubles(), (std::vector<double>{1.5, 2.0}));
}

}  // namespace
}  // namespace pkmopt

namespace pkmopt {
namespace {

// A study description "\N\L\P" made `task-poses` exit 1 (nlohmann::json refused the byte 0x85 that
// yaml-cpp decodes \N to): a string that is not UTF-8 after decoding is refused where it is read.
TEST(YamlReader, EscapesThatDecodeToBytesThatAreNotUtf8) {
  for (const char* escaped : {"\"\\N\"", "\"a\\_b\""}) {
    const std::string message =
        error_of(std::string("description: ") + escaped + "\n",
                 [](const YamlValue& v) { (void)v.required("description").as_string(); });
    EXPECT_NE(message.find("m.yaml:1:14: description: expected UTF-8 text"), std::string::npos)
        << message;
  }
  // \L and \P decode to U+2028 and U+2029, valid UTF-8.
  EXPECT_EQ(error_of("description: \"\\L\\P\"\n",
                     [](const YamlValue& v) { (void)v.required("description").as_string(); }),
            "no error");
}

}  // namespace
}  // namespace pkmopt
