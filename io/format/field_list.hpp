// One description per config section: its keys listed once, everything else derived.
//
// A config struct describes its YAML keys in one function template, in the manner of Drake's
// `Serialize(Archive*)`: each key with the member it sets, its unit, its allowed values and a
// doc line. The same list then drives
//   - the strict reader (`read_fields`): every key optional unless marked required, unknown keys
//     and values out of bounds are InputErrors with file, line, column, key, expected and found;
//   - the writer of resolved files (`fields_flow_map`): every key with its value, in list order;
//   - the documentation (`fields_markdown`): a table key | allowed | unit | default | meaning,
//     which the docs carry verbatim (a test compares them).
//
// Example:
//   struct Options { std::size_t points = 21; double tolerance = 1e-8; };
//   template <class Fields> void describe_fields(Fields& f, Options& o) {
//     f.field("points", o.points, {.min = 2, .doc = "front points"});
//     f.field("tolerance", o.tolerance, {.min = 0, .min_exclusive = true, .doc = "..."});
//   }
//   Options o;
//   read_fields(section, o);                       // section: a YamlValue map; strict
//   std::string yaml = fields_flow_map(o);         // "{points: 21, tolerance: 1e-08}"
//   std::string table = fields_markdown(Options{});  // the docs table
//
// A member is a number, a bool, a text, an optional number, an [x, y, z] vector, a list of
// numbers (std::vector<double>, std::array<double, N>), a list of integers (std::array<int, N>),
// a 3 x N point list, or one of the views below that stand for several members or for a coded
// member: FieldRange (two members as one key `[low, high]`), FieldBounds (a number or
// `{min, max}`: a design parameter, fixed or free), FieldChoice (a member set by name),
// FieldColumn (one number per referenced member) and a std::vector<FieldRange> (one range per
// element).
//   FieldRange drive{d.theta_min, d.theta_max};
//   f.field("drive_range_deg", drive, {.min = -180, .max = 180, .degrees = true});
//   FieldChoice<int> branch{d.branch, {{"elbow_out", 1}, {"elbow_in", -1}}};
//   f.field("branch", branch, {.doc = "the elbow branch"});
#pragma once

#include <fmt/format.h>

#include <Eigen/Core>
#include <array>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <numbers>
#include <optional>
#include <string>
#include <string_view>
#include <type_traits>
#include <utility>
#include <vector>

#include "io/format/csv.hpp"
#include "io/format/number_policy.hpp"
#include "io/format/yaml_reader.hpp"

namespace pkmopt {

/// What a key accepts and means. Bounds apply to numbers (integers and reals).
struct FieldRule {
  double min = -std::numeric_limits<double>::infinity();
  double max = std::numeric_limits<double>::infinity();
  bool min_exclusive = false;  ///< value > min instead of >= min
  bool max_exclusive = false;  ///< value < max instead of <= max
  bool even = false;           ///< integers: even only
  bool required = false;       ///< a missing key is an error
  /// 0 means "not set": the writer leaves the key out and the docs say `unset`.
  bool zero_is_unset = false;
  /// +inf means "not set": the writer leaves the key out and the docs say `unlimited`.
  bool infinite_is_unset = false;
  /// The file holds degrees, the member radians (bounds are in degrees).
  bool degrees = false;
  /// Significant digits of written reals (0: the shortest text that round-trips).
  int digits = 0;
  std::string_view unit = {};          ///< "m", "deg", "N", "" for none
  std::string_view expected = {};      ///< overrides the generated "an integer >= 4" text
  std::string_view default_text = {};  ///< overrides the default shown in the docs ("1/n")
  std::string_view doc = {};           ///< one line for the docs
  /// The writer leaves the key out when this returns true (e.g. a value at its default).
  std::function<bool()> omit_when = {};
};

/// Two members read and written as one key `[low, high]` (a stroke, a drive range). Both ends are
/// checked against the rule's bounds (in file units; degrees converted like a number), and low <
/// high (low <= high when `closed`). Messages: "[low, high] with low < high (unit)" and "a range
/// within [min, max] unit", or the rule's `expected` for both.
struct FieldRange {
  double& low;
  double& high;
  bool closed = false;  ///< low == high allowed
  /// The ordering message says "found [low, high]" (the values) instead of "found a list of 2".
  bool found_values = false;
};

/// A member set by name: read as one of the names (several may give one value: synonyms), written
/// as the first name of its value (left out when no name has it).
template <class T>
struct FieldChoice {
  T& member;
  std::vector<std::pair<std::string_view, T>> options;
};

/// One number per referenced member (e.g. a per-axis stiffness): read as a list of exactly that
/// many numbers, each checked against the rule's bounds; written as `[a, b, ...]`.
struct FieldColumn {
  std::vector<double*> members;
};

/// A design parameter's bounds as one key: a number (fixed, min == max) or `{min: a, max: b}`
/// (free, a < b). Both ends are checked against the rule's bounds (file units, no conversion).
/// Messages: "max > min" at the max key, "values > 0" (the rule as "values ...", or its
/// `expected`) at the key. Written as the number when fixed, as `{min: a, max: b}` when free.
struct FieldBounds {
  double& min;
  double& max;
};

/// A text as a YAML scalar: plain when it reads back as that text (a letter, then letters,
/// digits and _ . / + - :, not ending in ':', not `null`), otherwise double-quoted with escapes.
inline std::string yaml_scalar(const std::string& text) {
  auto plain_char = [](char c) {
    return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '.' || c == '/' ||
           c == '+' || c == '-' || c == ':';
  };
  bool plain = !text.empty() && std::isalpha(static_cast<unsigned char>(text.front())) &&
               text.back() != ':' && text != "null" && text != "Null" && text != "NULL";
  for (char c : text) plain = plain && plain_char(c);
  if (plain) return text;
  std::string out = "\"";
  for (const char c : text) {
    const auto u = static_cast<unsigned char>(c);
    if (c == '"' || c == '\\') {
      out += '\\';
      out += c;
    } else if (c == '\n') {
      out += "\\n";
    } else if (c == '\t') {
      out += "\\t";
    } else if (u < 0x20 || u == 0x7f) {
      out += fmt::format("\\x{:02x}", u);
    } else {
      out += c;
    }
  }
  return out + "\"";
}

namespace field_detail {

template <class T>
struct IsChoice : std::false_type {};
template <class T>
struct IsChoice<FieldChoice<T>> : std::true_type {};

template <class T>
struct IsArray : std::false_type {};
template <std::size_t N>
struct IsArray<std::array<double, N>> : std::true_type {};

/// std::array<int, N>: a list of exactly N integers (grid counts).
template <class T>
struct IsIntArray : std::false_type {};
template <std::size_t N>
struct IsIntArray<std::array<int, N>> : std::true_type {};

/// Eigen::Matrix<double, 3, N> with a fixed N > 1: a list of N points [x, y, z].
template <class T>
struct IsPointList : std::false_type {};
template <int N, int O, int MR, int MC>
struct IsPointList<Eigen::Matrix<double, 3, N, O, MR, MC>> : std::bool_constant<(N > 1)> {};

template <class T>
constexpr bool kInteger = std::is_integral_v<T> && !std::is_same_v<T, bool>;

inline std::string bound_text(double v) { return format_number(v); }

/// "an integer >= 4", "an even integer >= 4", "a number > 0", "a number in [0, 1]", ...
template <class T>
std::string expected_text(const FieldRule& r) {
  if (!r.expected.empty()) return std::string(r.expected);
  if constexpr (std::is_same_v<T, bool>) {
    return "true or false";
  } else if constexpr (std::is_same_v<T, std::string>) {
    return "a text";
  } else if constexpr (std::is_same_v<T, std::vector<double>>) {
    return "a list of finite numbers";
  } else if constexpr (std::is_same_v<T, Eigen::Vector3d>) {
    return "[x, y, z]";
  } else {
    const std::string what =
        kInteger<T> ? (r.even ? "an even integer" : "an integer") : std::string("a number");
    const bool has_min = r.min > -std::numeric_limits<double>::infinity();
    const bool has_max = r.max < std::numeric_limits<double>::infinity();
    if (has_min && has_max)
      return fmt::format("{} in {}{}, {}{}", what, r.min_exclusive ? "(" : "[", bound_text(r.min),
                         bound_text(r.max), r.max_exclusive ? ")" : "]");
    if (has_min)
      return fmt::format("{} {} {}", what, r.min_exclusive ? ">" : ">=", bound_text(r.min));
    if (has_max)
      return fmt::format("{} {} {}", what, r.max_exclusive ? "<" : "<=", bound_text(r.max));
    return kInteger<T> ? what : "a finite number";
  }
}

inline bool bounded(const FieldRule& r) {
  return r.min > -std::numeric_limits<double>::infinity() ||
         r.max < std::numeric_limits<double>::infinity();
}

/// What one number of a list, column or range must be ("a number >= 0").
inline std::string element_text(FieldRule r) {
  r.expected = {};
  return expected_text<double>(r);
}

/// "values > 0", "values in [0, 120)" (what both ends of FieldBounds must be).
inline std::string bounds_values_text(const FieldRule& r) {
  if (!r.expected.empty()) return std::string(r.expected);
  const std::string e = element_text(r);
  if (e.rfind("a number ", 0) == 0) return "values " + e.substr(9);
  return "finite values";
}

/// What one integer of a list must be ("an integer in [1, 1000]").
inline std::string element_int_text(FieldRule r) {
  r.expected = {};
  return expected_text<int>(r);
}

/// "a list of 3 integers in [1, 1000]".
inline std::string int_list_text(const FieldRule& r, long long count) {
  if (!r.expected.empty()) return std::string(r.expected);
  const std::string e = element_int_text(r);
  const std::string n = std::to_string(count);
  if (e == "an integer") return "a list of " + n + " integers";
  return "a list of " + n + " integers " + e.substr(std::string("an integer ").size());
}

/// "a list of 6 finite numbers", "a list of numbers >= 0" (`count` < 0: any length).
inline std::string list_text(const FieldRule& r, long long count) {
  if (!r.expected.empty()) return std::string(r.expected);
  const std::string n = count >= 0 ? std::to_string(count) + " " : "";
  const std::string e = element_text(r);
  if (e == "a finite number") return "a list of " + n + "finite numbers";
  if (e.rfind("a number ", 0) == 0) return "a list of " + n + "numbers " + e.substr(9);
  return "a list of " + n + "numbers, each " + e;
}

/// "[low, high] with low < high" (+ " (unit)" in messages).
inline std::string range_order_text(const FieldRule& r, bool closed, bool with_unit) {
  if (!r.expected.empty()) return std::string(r.expected);
  std::string text = closed ? "[low, high] with low <= high" : "[low, high] with low < high";
  if (with_unit && !r.unit.empty()) text += fmt::format(" ({})", r.unit);
  return text;
}

/// "[-180, 180]", "(0, 90)" (the rule's bounds as an interval).
inline std::string interval_text(const FieldRule& r) {
  return fmt::format("{}{}, {}{}", r.min_exclusive ? "(" : "[", bound_text(r.min),
                     bound_text(r.max), r.max_exclusive ? ")" : "]");
}

/// The docs' allowed text of a range.
inline std::string range_text(const FieldRule& r, bool closed) {
  if (!r.expected.empty()) return std::string(r.expected);
  return range_order_text(r, closed, false) + (bounded(r) ? " within " + interval_text(r) : "");
}

template <class T>
std::string choice_text(const FieldRule& r, const FieldChoice<T>& c) {
  if (!r.expected.empty()) return std::string(r.expected);
  std::string text;
  for (std::size_t i = 0; i < c.options.size(); ++i)
    text += (i == 0                      ? ""
             : i + 1 == c.options.size() ? " or "
                                         : ", ") +
            std::string(c.options[i].first);
  return text;
}

/// The docs' allowed text of a member of any kind.
template <class T>
std::string allowed_text(const FieldRule& r, const T& member) {
  if constexpr (std::is_same_v<T, FieldRange>) {
    return range_text(r, member.closed);
  } else if constexpr (std::is_same_v<T, FieldBounds>) {
    return "a number (fixed) or {min, max} with min < max (free); " + bounds_values_text(r);
  } else if constexpr (IsIntArray<T>::value) {
    return int_list_text(r, static_cast<long long>(std::tuple_size_v<T>));
  } else if constexpr (IsChoice<T>::value) {
    return choice_text(r, member);
  } else if constexpr (std::is_same_v<T, FieldColumn>) {
    return list_text(r, -1);
  } else if constexpr (IsArray<T>::value) {
    return list_text(r, static_cast<long long>(std::tuple_size_v<T>));
  } else if constexpr (std::is_same_v<T, std::vector<FieldRange>>) {
    if (!r.expected.empty()) return "a list of " + std::string(r.expected);
    return "a list of " + range_text(r, !member.empty() && member.front().closed);
  } else if constexpr (IsPointList<T>::value) {
    if (!r.expected.empty()) return std::string(r.expected);
    return fmt::format("[[x, y, z] × {}]", T::ColsAtCompileTime);
  } else if constexpr (std::is_same_v<T, std::vector<Eigen::Vector2d>>) {
    if (!r.expected.empty()) return std::string(r.expected);
    return "[[x, y], ...]";
  } else {
    return expected_text<T>(r);
  }
}

template <class T>
bool within(const FieldRule& r, T value) {
  const double v = static_cast<double>(value);
  if (r.min_exclusive ? !(v > r.min) : !(v >= r.min)) return false;
  if (r.max_exclusive ? !(v < r.max) : !(v <= r.max)) return false;
  if constexpr (kInteger<T>) {
    if (r.even && value % 2 != 0) return false;
  }
  return true;
}

/// A real as written: degrees for angle fields, `digits` significant digits or the shortest text.
/// Angle fields: the shortest degree text that reads back (times pi/180) to the same radians,
/// so that 60 degrees read from a file is written as 60, not 59.99999999999999.
inline std::string real_text(double value, const FieldRule& r) {
  if (!r.degrees)
    return r.digits > 0 ? fmt::format("{:.{}g}", value, r.digits) : format_number(value);
  const double v = value * (180.0 / std::numbers::pi);
  if (r.digits > 0) return fmt::format("{:.{}g}", v, r.digits);
  if (!std::isfinite(v)) return format_number(v);
  for (int digits = 1; digits <= 17; ++digits) {
    const std::string text = fmt::format("{:.{}g}", v, digits);
    if (std::stod(text) * (std::numbers::pi / 180.0) == value)
      return format_number(std::stod(text));
  }
  return format_number(v);
}

template <class T>
std::string value_text(const T& value, const FieldRule& r = {}) {
  if constexpr (std::is_same_v<T, bool>) {
    return value ? "true" : "false";
  } else if constexpr (std::is_same_v<T, std::string>) {
    return yaml_scalar(value);
  } else if constexpr (std::is_same_v<T, std::vector<double>>) {
    std::string list;
    for (double v : value) list += (list.empty() ? "" : ", ") + format_number(v);
    return "[" + list + "]";
  } else if constexpr (std::is_same_v<T, Eigen::Vector3d>) {
    return fmt::format("[{}, {}, {}]", real_text(value.x(), r), real_text(value.y(), r),
                       real_text(value.z(), r));
  } else if constexpr (std::is_same_v<T, std::optional<double>>) {
    return value ? real_text(*value, r) : "";
  } else if constexpr (std::is_same_v<T, FieldRange>) {
    return fmt::format("[{}, {}]", real_text(value.low, r), real_text(value.high, r));
  } else if constexpr (std::is_same_v<T, FieldBounds>) {
    if (value.min == value.max) return real_text(value.min, r);
    return fmt::format("{{min: {}, max: {}}}", real_text(value.min, r), real_text(value.max, r));
  } else if constexpr (IsIntArray<T>::value) {
    std::string list;
    for (int v : value) list += (list.empty() ? "" : ", ") + std::to_string(v);
    return "[" + list + "]";
  } else if constexpr (IsChoice<T>::value) {
    for (const auto& [name, option] : value.options)
      if (option == value.member) return std::string(name);
    return "";
  } else if constexpr (std::is_same_v<T, FieldColumn>) {
    std::string list;
    for (const double* v : value.members) list += (list.empty() ? "" : ", ") + real_text(*v, r);
    return "[" + list + "]";
  } else if constexpr (IsArray<T>::value) {
    std::string list;
    for (double v : value) list += (list.empty() ? "" : ", ") + real_text(v, r);
    return "[" + list + "]";
  } else if constexpr (std::is_same_v<T, std::vector<FieldRange>>) {
    std::string list;
    for (const FieldRange& range : value) list += (list.empty() ? "" : ", ") + value_text(range, r);
    return "[" + list + "]";
  } else if constexpr (IsPointList<T>::value) {
    std::string list;
    for (int i = 0; i < value.cols(); ++i)
      list += (i == 0 ? "" : ", ") + value_text(Eigen::Vector3d(value.col(i)), r);
    return "[" + list + "]";
  } else if constexpr (std::is_same_v<T, std::vector<Eigen::Vector2d>>) {
    std::string list;
    for (const Eigen::Vector2d& v : value)
      list += fmt::format("{}[{}, {}]", list.empty() ? "" : ", ", real_text(v.x(), r),
                          real_text(v.y(), r));
    return "[" + list + "]";
  } else if constexpr (kInteger<T>) {
    return std::to_string(value);
  } else {
    return real_text(value, r);
  }
}

template <class T>
bool is_unset(const FieldRule& r, const T& value) {
  if constexpr (std::is_same_v<T, std::vector<double>> || std::is_same_v<T, std::string> ||
                std::is_same_v<T, std::vector<FieldRange>> ||
                std::is_same_v<T, std::vector<Eigen::Vector2d>>) {
    return r.zero_is_unset && value.empty();
  } else if constexpr (std::is_same_v<T, FieldColumn>) {
    return r.zero_is_unset && value.members.empty();
  } else if constexpr (IsChoice<T>::value) {
    for (const auto& option : value.options)
      if (option.second == value.member) return false;
    return true;
  } else if constexpr (std::is_same_v<T, bool> || std::is_same_v<T, Eigen::Vector3d> ||
                       std::is_same_v<T, FieldRange> || std::is_same_v<T, FieldBounds> ||
                       IsArray<T>::value || IsIntArray<T>::value || IsPointList<T>::value) {
    return false;
  } else if constexpr (std::is_same_v<T, std::optional<double>>) {
    return !value.has_value();
  } else {
    if constexpr (std::is_floating_point_v<T>) {
      if (r.infinite_is_unset && std::isinf(value)) return true;
    }
    return r.zero_is_unset && value == T{};
  }
}

/// The rule with the input policy's bounds on lengths (io/format/number_policy.hpp): a key in
/// metres holds at most +-1000 m (in mm +-1e6, in µm +-1e9) even where its own rule is unbounded.
inline FieldRule with_input_limits(const FieldRule& r) {
  double limit = 0.0;
  if (r.unit == "m") limit = kMaxInputLength;
  if (r.unit == "mm") limit = 1e3 * kMaxInputLength;
  if (r.unit == "µm") limit = 1e6 * kMaxInputLength;
  if (limit == 0.0) return r;
  FieldRule out = r;
  if (!(out.min > -limit)) out.min = -limit, out.min_exclusive = false;
  if (!(out.max < limit)) out.max = limit, out.max_exclusive = false;
  return out;
}

/// A number of a file converted to the member's unit (degrees to radians for angle fields).
inline double from_file(double x, const FieldRule& r) {
  return r.degrees ? x * (std::numbers::pi / 180.0) : x;
}

/// One number of a list: finite, within the rule's bounds (the message names the element).
inline double read_element(const YamlValue& e, const FieldRule& r) {
  const double x = e.as_double();
  if (!within(r, x)) e.fail(element_text(r), e.describe());
  return from_file(x, r);
}

inline void read_range(const YamlValue& v, const FieldRule& r, FieldRange& range) {
  const std::vector<double> x = v.as_doubles(2);
  const std::string values = fmt::format("[{}, {}]", format_number(x[0]), format_number(x[1]));
  const std::string found = range.found_values ? values : v.describe();
  if (range.closed ? !(x[0] <= x[1]) : !(x[0] < x[1]))
    v.fail(range_order_text(r, range.closed, true), found);
  if (!within(r, x[0]) || !within(r, x[1])) {
    if (!r.expected.empty()) v.fail(r.expected, found);
    v.fail(fmt::format("a range within {}{}", interval_text(r), r.unit.empty() ? "" : " ")
               .append(r.unit),
           values);
  }
  range.low = from_file(x[0], r);
  range.high = from_file(x[1], r);
}

inline void read_bounds(const YamlValue& v, const FieldRule& r, FieldBounds& bounds) {
  double lo = 0.0, hi = 0.0;
  if (v.is_map()) {
    v.check_keys({"min", "max"});
    lo = v.required("min").as_double();
    const YamlValue max = v.required("max");
    hi = max.as_double();
    if (!(lo < hi)) max.fail("max > min", max.describe());
  } else {
    lo = hi = v.as_double();
  }
  if (!within(r, lo) || !within(r, hi)) v.fail(bounds_values_text(r), v.describe());
  bounds.min = lo;
  bounds.max = hi;
}

}  // namespace field_detail

/// Reads the keys of one YAML map into the members a field list names (see the header comment).
class FieldReader {
 public:
  explicit FieldReader(const YamlValue& section) : section_(section) { section_.expect_map(); }

  template <class T>
  void field(std::string_view key, T& member, const FieldRule& declared = {}) {
    keys_.emplace_back(key);
    const std::optional<YamlValue> v = section_.optional(key);
    if (!v) {
      if (declared.required) section_.fail(fmt::format("missing required key '{}'", key));
      return;
    }
    // The declared rule first (its message), then the input policy's bounds on lengths.
    read_value(*v, member, declared);
    const FieldRule limited = field_detail::with_input_limits(declared);
    if (limited.min != declared.min || limited.max != declared.max) read_value(*v, member, limited);
  }

  /// A nested map under `key`: its keys checked, then `describe(reader)` reads them.
  template <class Describe>
  void section(std::string_view key, const FieldRule& rule, Describe&& describe) {
    keys_.emplace_back(key);
    const std::optional<YamlValue> v = section_.optional(key);
    if (!v) {
      if (rule.required) section_.fail(fmt::format("missing required key '{}'", key));
      return;
    }
    read_section(*v, describe);
  }

  template <class Describe>
  static void read_section(const YamlValue& value, Describe&& describe);

  /// A key read by hand next to the list: allowed here, documented by FieldDocs.
  void note(std::string_view key, std::string_view, std::string_view, std::string_view,
            std::string_view) {
    keys_.emplace_back(key);
  }

  /// Throws for any key of the map that no field named.
  void check_no_other_keys() const { section_.check_keys(keys_); }

  const YamlValue& section() const { return section_; }

 private:
  template <class T>
  static void read_value(const YamlValue& value, T& member, const FieldRule& rule) {
    const YamlValue* v = &value;
    if constexpr (std::is_same_v<T, bool>) {
      member = v->as_bool();
    } else if constexpr (std::is_same_v<T, std::string>) {
      member = v->as_string();
    } else if constexpr (std::is_same_v<T, std::vector<double>>) {
      member = v->as_doubles();
    } else if constexpr (std::is_same_v<T, Eigen::Vector3d>) {
      const std::vector<YamlValue> xyz = v->elements(3);
      for (int k = 0; k < 3; ++k) member(k) = field_detail::read_element(xyz[k], rule);
    } else if constexpr (std::is_same_v<T, FieldRange>) {
      field_detail::read_range(*v, rule, member);
    } else if constexpr (std::is_same_v<T, FieldBounds>) {
      field_detail::read_bounds(*v, rule, member);
    } else if constexpr (field_detail::IsIntArray<T>::value) {
      const std::vector<YamlValue> items = v->elements(static_cast<int>(member.size()));
      for (std::size_t i = 0; i < items.size(); ++i) {
        const long long n = items[i].as_int();
        if (!field_detail::within(rule, n) || n < std::numeric_limits<int>::min() ||
            n > std::numeric_limits<int>::max())
          items[i].fail(field_detail::element_int_text(rule), items[i].describe());
        member[i] = static_cast<int>(n);
      }
    } else if constexpr (field_detail::IsChoice<T>::value) {
      const std::string name = v->as_string();
      for (const auto& [option_name, option] : member.options) {
        if (option_name == name) {
          member.member = option;
          return;
        }
      }
      v->fail(field_detail::choice_text(rule, member), quote_found(name));
    } else if constexpr (std::is_same_v<T, FieldColumn>) {
      const std::vector<YamlValue> items = v->elements(static_cast<int>(member.members.size()));
      for (std::size_t i = 0; i < items.size(); ++i)
        *member.members[i] = field_detail::read_element(items[i], rule);
    } else if constexpr (field_detail::IsArray<T>::value) {
      const std::vector<YamlValue> items = v->elements(static_cast<int>(member.size()));
      for (std::size_t i = 0; i < items.size(); ++i)
        member[i] = field_detail::read_element(items[i], rule);
    } else if constexpr (std::is_same_v<T, std::vector<FieldRange>>) {
      const std::vector<YamlValue> items = v->elements(static_cast<int>(member.size()));
      for (std::size_t i = 0; i < items.size(); ++i)
        field_detail::read_range(items[i], rule, member[i]);
    } else if constexpr (std::is_same_v<T, std::vector<Eigen::Vector2d>>) {
      member.clear();
      for (const YamlValue& item : v->elements()) {
        const std::vector<double> xy = item.as_doubles(2);
        member.emplace_back(xy[0], xy[1]);
      }
    } else if constexpr (field_detail::IsPointList<T>::value) {
      const std::vector<YamlValue> items = v->elements(static_cast<int>(member.cols()));
      for (std::size_t i = 0; i < items.size(); ++i) {
        const std::vector<YamlValue> xyz = items[i].elements(3);
        for (int k = 0; k < 3; ++k)
          member(k, static_cast<Eigen::Index>(i)) = field_detail::read_element(xyz[k], rule);
      }
    } else if constexpr (std::is_same_v<T, std::optional<double>>) {
      const double x = v->as_double();
      if (!field_detail::within(rule, x))
        v->fail(field_detail::expected_text<double>(rule), v->describe());
      member = x;
    } else if constexpr (field_detail::kInteger<T>) {
      const long long n = v->as_int();
      if (!field_detail::within(rule, n) || (std::is_unsigned_v<T> && n < 0) ||
          static_cast<double>(n) > static_cast<double>(std::numeric_limits<T>::max()))
        v->fail(field_detail::expected_text<T>(rule), v->describe());
      member = static_cast<T>(n);
    } else {
      const double x = v->as_double();
      if (!field_detail::within(rule, x))
        v->fail(field_detail::expected_text<T>(rule), v->describe());
      member = static_cast<T>(field_detail::from_file(x, rule));
    }
  }

  const YamlValue section_;  // a copy: a reader made of a temporary (required(...)) outlives it
  std::vector<std::string> keys_;
};

/// Collects the keys of a field list (notes included), e.g. to reject unknown keys first.
class FieldKeys {
 public:
  template <class T>
  void field(std::string_view key, T&, const FieldRule& = {}) {
    keys.emplace_back(key);
  }
  void note(std::string_view key, std::string_view, std::string_view, std::string_view,
            std::string_view) {
    keys.emplace_back(key);
  }
  template <class Describe>
  void section(std::string_view key, const FieldRule&, Describe&&) {
    keys.emplace_back(key);
  }
  std::vector<std::string> keys;
};

template <class Describe>
void FieldReader::read_section(const YamlValue& value, Describe&& describe) {
  FieldKeys keys;
  describe(keys);
  value.check_keys(keys.keys);
  FieldReader reader(value);
  describe(reader);
}

/// Collects "key: value" items in list order (for resolved YAML files).
class FieldWriter {
 public:
  template <class T>
  void field(std::string_view key, T& member, const FieldRule& rule = {}) {
    if (field_detail::is_unset(rule, member)) return;
    if (rule.omit_when && rule.omit_when()) return;
    if constexpr (std::is_same_v<T, std::vector<double>>) {
      if (member.empty()) return;
    }
    items_.push_back(fmt::format("{}: {}", key, field_detail::value_text(member, rule)));
    nested_.push_back(false);
  }

  /// A key whose value text is made by hand (a form no field kind covers), written verbatim.
  void raw(std::string_view key, const std::string& text) {
    items_.push_back(fmt::format("{}: {}", key, text));
    nested_.push_back(false);
  }

  /// A nested map, written as a flow map `key: {a: 1}` (or indented in block text); left out
  /// when none of its keys is written.
  template <class Describe>
  void section(std::string_view key, const FieldRule& rule, Describe&& describe) {
    FieldWriter inner;
    describe(inner);
    if (inner.items_.empty() || (rule.omit_when && rule.omit_when())) return;
    items_.push_back(fmt::format("{}: {}", key, inner.flow_map()));
    nested_.push_back(true);
    block_keys_.emplace_back(key);
    block_writers_.push_back(std::move(inner));
  }

  /// "key: value" lines, nested maps as indented blocks (YAML block style).
  std::string block(int indent = 0) const {
    std::string out;
    const std::string pad(static_cast<std::size_t>(indent), ' ');
    std::size_t next_block = 0;
    for (std::size_t i = 0; i < items_.size(); ++i) {
      if (nested_[i]) {
        out += pad + block_keys_[next_block] + ":\n" + block_writers_[next_block].block(indent + 2);
        ++next_block;
      } else {
        out += pad + items_[i] + "\n";
      }
    }
    return out;
  }
  /// "key: value" lines, nested maps as flow maps `key: {a: 1}` (the style of machine files).
  std::string flow_lines() const {
    std::string out;
    for (const std::string& item : items_) out += item + "\n";
    return out;
  }
  void note(std::string_view, std::string_view, std::string_view, std::string_view,
            std::string_view) {}

  const std::vector<std::string>& items() const { return items_; }
  /// "{a: 1, b: 2}"
  std::string flow_map() const {
    std::string text;
    for (const std::string& item : items_) text += (text.empty() ? "" : ", ") + item;
    return "{" + text + "}";
  }

 private:
  std::vector<std::string> items_;
  std::vector<bool> nested_;
  std::vector<std::string> block_keys_;
  std::vector<FieldWriter> block_writers_;  ///< the nested maps, in order
};

/// A machine file written from a design: "model: NAME" and the design's keys from the field list
/// its reader takes, one line per key, sub-sections as flow maps (numbers in their shortest
/// round-trip form, angles in degrees to the 12 significant digits the lists give them).
template <typename Design>
std::string model_file_text(std::string_view model, Design design) {
  FieldWriter writer;
  describe_fields(writer, design);
  return "model: " + std::string(model) + "\n" + writer.flow_lines();
}

/// One documented key.
struct FieldDoc {
  std::string key, allowed, unit, default_value, doc;
};

/// Collects the documentation rows of a field list (run it on a default-constructed struct).
class FieldDocs {
 public:
  template <class T>
  void field(std::string_view key, T& member, const FieldRule& rule = {}) {
    FieldDoc d;
    d.key = prefix_ + std::string(key);
    d.allowed = field_detail::allowed_text(rule, member);
    d.unit = std::string(rule.unit);
    if (!rule.default_text.empty())
      d.default_value = std::string(rule.default_text);
    else if (rule.required)
      d.default_value = "required";
    else if (field_detail::is_unset(rule, member))
      d.default_value = rule.infinite_is_unset ? "unlimited" : "unset";
    else
      d.default_value = field_detail::value_text(member, rule);
    d.doc = std::string(rule.doc);
    rows_.push_back(std::move(d));
  }
  /// A key read by hand next to the list, documented here.
  void note(std::string_view key, std::string_view allowed, std::string_view unit,
            std::string_view default_value, std::string_view doc) {
    rows_.push_back({prefix_ + std::string(key), std::string(allowed), std::string(unit),
                     std::string(default_value), std::string(doc)});
  }
  /// A nested map: its keys documented as `key.inner`.
  template <class Describe>
  void section(std::string_view key, const FieldRule& rule, Describe&& describe) {
    if (!rule.doc.empty())
      rows_.push_back({prefix_ + std::string(key), "a map", "", rule.required ? "required" : "",
                       std::string(rule.doc)});
    const std::string saved = prefix_;
    prefix_ += std::string(key) + ".";
    describe(*this);
    prefix_ = saved;
  }

  const std::vector<FieldDoc>& rows() const { return rows_; }
  /// Keys after this are documented as `prefix` + key.
  void set_prefix(std::string prefix) { prefix_ = std::move(prefix); }
  /// The markdown table (header, separator, one row per key; a trailing newline).
  std::string markdown() const {
    std::string out =
        "| key | allowed | unit | default | meaning |\n| --- | --- | --- | --- | --- |\n";
    for (const FieldDoc& d : rows_)
      out += fmt::format("| `{}` | {} | {} | {} | {} |\n", d.key, d.allowed,
                         d.unit.empty() ? "–" : d.unit, d.default_value, d.doc);
    return out;
  }

 private:
  std::vector<FieldDoc> rows_;
  std::string prefix_;
};

/// Reads `value`'s keys from a map (unknown keys first, then each value; see the header).
template <class T>
void read_fields(const YamlValue& section, T& value) {
  FieldKeys keys;
  T scratch = value;
  describe_fields(keys, scratch);
  section.check_keys(keys.keys);
  FieldReader reader(section);
  describe_fields(reader, value);
}

/// The keys and values of `value` as a YAML flow map, in list order.
template <class T>
std::string fields_flow_map(T value) {
  FieldWriter writer;
  describe_fields(writer, value);
  return writer.flow_map();
}

/// The docs table of a field list, defaults from `value` (usually a default-constructed one).
template <class T>
std::string fields_markdown(T value) {
  FieldDocs docs;
  describe_fields(docs, value);
  return docs.markdown();
}

}  // namespace pkmopt
