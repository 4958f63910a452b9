// Strict YAML reading with messages that carry file, line, column, key, expected and found.
//
// A YamlValue wraps a yaml-cpp node together with the file name and its dotted key path.
// Reading a map is strict: call `check_keys({...})` with the allowed keys and every other key
// is an error pointing at that key's line and column.
//
//   YamlValue root = YamlValue::load_file("machine.yaml");       // throws InputError
//   root.check_keys({"model", "legs"});
//   std::string model = root.required("model").as_string();
//   double min_length = root.required("legs").required("min_length").as_double();
//     // -> "machine.yaml:5:16: legs.min_length: expected a finite number, found 'abc'"
#pragma once

#include <yaml-cpp/yaml.h>

#include <initializer_list>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "io/format/input_error.hpp"

namespace pkmopt {

class YamlValue {
 public:
  /// Parses a file; a missing, unreadable or malformed file throws InputError.
  static YamlValue load_file(const std::string& path);
  /// Parses text (the `file` name is used in messages only).
  static YamlValue load_string(const std::string& text, const std::string& file);

  YamlValue(YAML::Node node, std::shared_ptr<const std::string> file, std::string path);

  const std::string& file() const { return *file_; }
  /// The dotted key path of this value ("legs.min_length", "base_joints[2]"); "" at the root.
  const std::string& path() const { return path_; }
  const YAML::Node& node() const { return node_; }
  int line() const;    ///< 1-based, 0 if unknown
  int column() const;  ///< 1-based, 0 if unknown

  bool is_map() const { return node_.IsMap(); }
  bool is_sequence() const { return node_.IsSequence(); }
  bool is_scalar() const { return node_.IsScalar(); }
  bool is_null() const { return !node_ || node_.IsNull(); }

  /// Throws unless this is a map; then throws for any key not in `allowed`.
  void check_keys(std::initializer_list<std::string_view> allowed) const;
  void check_keys(const std::vector<std::string>& allowed) const;
  /// Throws unless this is a map.
  void expect_map() const;

  bool has(std::string_view key) const;
  /// The value under a key of this map; throws "missing required key" if absent.
  YamlValue required(std::string_view key) const;
  std::optional<YamlValue> optional(std::string_view key) const;
  /// Keys of this map in file order.
  std::vector<std::string> keys() const;

  /// Elements of a sequence (throws unless a sequence; `count` >= 0 checks the length).
  std::vector<YamlValue> elements(int count = -1) const;

  double as_double() const;           ///< finite number
  double as_positive() const;         ///< finite number > 0 ("expected a number > 0")
  double as_non_negative() const;     ///< finite number >= 0 ("expected a number >= 0")
  double as_length() const;           ///< a length in metres within +-1000 m
  double as_positive_length() const;  ///< a length in metres in (0, 1000]
  long long as_int() const;
  bool as_bool() const;
  std::string as_string() const;
  /// A sequence of finite numbers (`count` >= 0 checks the length).
  std::vector<double> as_doubles(int count = -1) const;
  std::vector<double> as_lengths(int count = -1) const;  ///< each one as_length()

  /// Throws InputError "file:line:col: path: expected <expected>, found <found>".
  [[noreturn]] void fail(std::string_view expected, std::string_view found) const;
  /// Throws InputError "file:line:col: path: <message>".
  [[noreturn]] void fail(std::string_view message) const;
  /// A short description of what this value is, for "found ..." ('abc', a map, a list of 3).
  std::string describe() const;

 private:
  YamlValue child(const YAML::Node& node, const std::string& path) const;
  std::string child_path(std::string_view key) const;

  YAML::Node node_;
  std::shared_ptr<const std::string> file_;
  std::string path_;
  int line_ = 0;
  int column_ = 0;

 public:
  /// Overrides the location used in messages (keys point at the key, not the value).
  void set_location(int line, int column) {
    line_ = line;
    column_ = column;
  }
};

}  // namespace pkmopt
