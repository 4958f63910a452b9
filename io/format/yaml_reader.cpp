#include "io/format/yaml_reader.hpp"

#include <fmt/format.h>
#include <yaml-cpp/eventhandler.h>

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include "io/format/number_policy.hpp"

namespace pkmopt {
namespace {

std::string join(const std::vector<std::string>& names) {
  std::string out;
  for (std::size_t i = 0; i < names.size(); ++i) out += (i ? ", " : "") + names[i];
  return out;
}

bool parse_double(const std::string& text, double& value) {
  if (text.empty()) return false;
  const char* begin = text.c_str();
  char* end = nullptr;
  value = read_input_number(begin, &end);
  // "inf" and "nan" parse here and are rejected by the callers' finiteness checks.
  return end != begin && *end == '\0';
}

// Counts the documents of a YAML text through yaml-cpp's event parser, keeping only where each
// one starts.
class DocumentStarts final : public YAML::EventHandler {
 public:
  std::vector<YAML::Mark> starts;
  void OnDocumentStart(const YAML::Mark& mark) override { starts.push_back(mark); }
  void OnDocumentEnd() override {}
  void OnNull(const YAML::Mark&, YAML::anchor_t) override {}
  void OnAlias(const YAML::Mark&, YAML::anchor_t) override {}
  void OnScalar(const YAML::Mark&, const std::string&, YAML::anchor_t,
                const std::string&) override {}
  void OnSequenceStart(const YAML::Mark&, const std::string&, YAML::anchor_t,
                       YAML::EmitterStyle::value) override {}
  void OnSequenceEnd() override {}
  void OnMapStart(const YAML::Mark&, const std::string&, YAML::anchor_t,
                  YAML::EmitterStyle::value) override {}
  void OnMapEnd() override {}
};

// A machine or study file holds one document: a second one (after a '---' line) would be
// silently ignored by YAML::Load. Reads at most two documents (yaml-cpp 0.7's LoadAll never ends
// on some malformed texts, e.g. ", a", whose documents do not advance: that is reported too).
void check_single_document(const std::string& text, const std::string& file) {
  std::istringstream in(text);
  YAML::Parser parser(in);
  DocumentStarts documents;
  for (int k = 0; k < 2 && parser.HandleNextDocument(documents); ++k) {
  }
  if (documents.starts.size() < 2) return;
  const YAML::Mark first = documents.starts[0], second = documents.starts[1];
  const std::string where = second.line >= 0
                                ? location_prefix(file, second.line + 1, second.column + 1)
                                : location_prefix(file);
  if (second.pos == first.pos)
    throw InputError(where +
                     "malformed YAML: expected a map of keys, found text the YAML parser "
                     "cannot read (it does not advance past this point)");
  throw InputError(where +
                   "expected one YAML document, found a second one (a '---' line); a machine or "
                   "study file holds one document");
}

}  // namespace

YamlValue YamlValue::load_file(const std::string& path) {
  return load_string(read_input_file(path), path);
}

YamlValue YamlValue::load_string(const std::string& text, const std::string& file) {
  auto file_name = std::make_shared<const std::string>(file);
  require_utf8(text, file);
  YAML::Node node;
  try {
    node = YAML::Load(text);
    check_single_document(text, file);
  } catch (const YAML::Exception& e) {
    throw InputError(fmt::format("{}malformed YAML: {}",
                                 location_prefix(file, e.mark.line + 1, e.mark.column + 1), e.msg));
  }
  YamlValue root(node, file_name, "");
  if (root.line_ == 0) root.set_location(1, 1);
  return root;
}

YamlValue::YamlValue(YAML::Node node, std::shared_ptr<const std::string> file, std::string path)
    : node_(std::move(node)), file_(std::move(file)), path_(std::move(path)) {
  if (node_ && node_.Mark().line >= 0) {
    line_ = node_.Mark().line + 1;
    column_ = node_.Mark().column + 1;
  }
}

int YamlValue::line() const { return line_; }
int YamlValue::column() const { return column_; }

std::string YamlValue::child_path(std::string_view key) const {
  return path_.empty() ? std::string(key) : path_ + "." + std::string(key);
}

YamlValue YamlValue::child(const YAML::Node& node, const std::string& path) const {
  YamlValue v(node, file_, path);
  if (v.line_ == 0) v.set_location(line_, column_);
  return v;
}

std::string YamlValue::describe() const {
  if (!node_ || node_.IsNull()) return "nothing (null)";
  if (node_.IsScalar()) return quote_found(node_.Scalar());
  if (node_.IsSequence()) return fmt::format("a list of {}", node_.size());
  if (node_.IsMap()) return "a map";
  return "an unknown YAML node";
}

void YamlValue::fail(std::string_view expected, std::string_view found) const {
  throw InputError(fmt::format("{}{}expected {}, found {}", location_prefix(*file_, line_, column_),
                               path_.empty() ? "" : path_ + ": ", expected, found));
}

void YamlValue::fail(std::string_view message) const {
  throw InputError(fmt::format("{}{}{}", location_prefix(*file_, line_, column_),
                               path_.empty() ? "" : path_ + ": ", message));
}

void YamlValue::expect_map() const {
  if (!node_.IsMap()) fail("a map of keys", describe());
}

void YamlValue::check_keys(std::initializer_list<std::string_view> allowed) const {
  std::vector<std::string> names;
  for (auto a : allowed) names.emplace_back(a);
  check_keys(names);
}

void YamlValue::check_keys(const std::vector<std::string>& allowed) const {
  expect_map();
  for (auto it = node_.begin(); it != node_.end(); ++it) {
    const std::string key = it->first.Scalar();
    bool known = false;
    for (const auto& a : allowed) known = known || a == key;
    if (!known) {
      YamlValue key_value(it->first, file_, child_path(key));
      key_value.fail(
          fmt::format("unknown key {}; allowed keys here: {}", quote_found(key), join(allowed)));
    }
  }
  // Duplicate keys: yaml-cpp keeps both; reject them.
  std::vector<std::string> seen;
  for (auto it = node_.begin(); it != node_.end(); ++it) {
    const std::string key = it->first.Scalar();
    for (const auto& s : seen) {
      if (s == key) {
        YamlValue key_value(it->first, file_, child_path(key));
        key_value.fail(fmt::format("duplicate key '{}'", key));
      }
    }
    seen.push_back(key);
  }
}

bool YamlValue::has(std::string_view key) const {
  if (!node_.IsMap()) return false;
  for (auto it = node_.begin(); it != node_.end(); ++it) {
    if (it->first.Scalar() == key) return true;
  }
  return false;
}

YamlValue YamlValue::required(std::string_view key) const {
  expect_map();
  for (auto it = node_.begin(); it != node_.end(); ++it) {
    if (it->first.Scalar() == key) {
      YamlValue v = child(it->second, child_path(key));
      if (it->second.IsNull()) {
        v.set_location(it->first.Mark().line + 1, it->first.Mark().column + 1);
      }
      return v;
    }
  }
  fail(fmt::format("missing required key '{}'", key));
}

std::optional<YamlValue> YamlValue::optional(std::string_view key) const {
  if (!has(key)) return std::nullopt;
  return required(key);
}

std::vector<std::string> YamlValue::keys() const {
  expect_map();
  std::vector<std::string> out;
  for (auto it = node_.begin(); it != node_.end(); ++it) out.push_back(it->first.Scalar());
  return out;
}

std::vector<YamlValue> YamlValue::elements(int count) const {
  if (!node_.IsSequence()) {
    fail(count >= 0 ? fmt::format("a list of {}", count) : std::string("a list"), describe());
  }
  if (count >= 0 && static_cast<int>(node_.size()) != count) {
    fail(fmt::format("a list of {}", count), describe());
  }
  std::vector<YamlValue> out;
  for (std::size_t i = 0; i < node_.size(); ++i) {
    out.push_back(child(node_[i], fmt::format("{}[{}]", path_, i)));
  }
  return out;
}

double YamlValue::as_double() const {
  if (!node_.IsScalar()) fail("a finite number", describe());
  double value = 0.0;
  if (!parse_double(node_.Scalar(), value)) fail("a finite number", describe());
  if (!std::isfinite(value)) fail("a finite number", describe());
  if (!sane_input_number(value)) fail(kSaneNumberText, describe());
  return value;
}

double YamlValue::as_positive() const {
  const double v = as_double();
  if (!(v > 0.0)) fail("a number > 0", describe());
  return v;
}

double YamlValue::as_non_negative() const {
  const double v = as_double();
  if (!(v >= 0.0)) fail("a number >= 0", describe());
  return v;
}

double YamlValue::as_length() const {
  const double v = as_double();
  if (!sane_input_length(v)) fail(kLengthText, describe());
  return v;
}

double YamlValue::as_positive_length() const {
  const double v = as_positive();
  if (!sane_input_length(v)) fail("a length in (0, 1000] m", describe());
  return v;
}

long long YamlValue::as_int() const {
  if (!node_.IsScalar()) fail("an integer", describe());
  const std::string& text = node_.Scalar();
  char* end = nullptr;
  errno = 0;
  const long long value = std::strtoll(text.c_str(), &end, 10);
  if (text.empty() || *end != '\0' || errno == ERANGE) fail("an integer", describe());
  return value;
}

bool YamlValue::as_bool() const {
  if (node_.IsScalar()) {
    const std::string& t = node_.Scalar();
    if (t == "true" || t == "True" || t == "TRUE") return true;
    if (t == "false" || t == "False" || t == "FALSE") return false;
  }
  fail("true or false", describe());
}

std::string YamlValue::as_string() const {
  if (!node_.IsScalar()) fail("a string", describe());
  // The file is UTF-8 (checked when read), but yaml-cpp decodes the escapes \N and \_ of a
  // double-quoted scalar to single bytes (0x85, 0xA0) that are not: refused here, so that no
  // output (JSON above all) receives them.
  try {
    require_utf8(node_.Scalar(), "");
  } catch (const InputError&) {
    fail(
        "UTF-8 text (the escapes \\N and \\_ are not read as UTF-8: write the character "
        "itself)",
        "a string that is not UTF-8");
  }
  return node_.Scalar();
}

std::vector<double> YamlValue::as_doubles(int count) const {
  std::vector<double> out;
  for (const auto& e : elements(count)) out.push_back(e.as_double());
  return out;
}

std::vector<double> YamlValue::as_lengths(int count) const {
  std::vector<double> out;
  for (const auto& e : elements(count)) out.push_back(e.as_length());
  return out;
}

}  // namespace pkmopt
