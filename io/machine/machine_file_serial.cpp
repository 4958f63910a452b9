#include "io/machine/machine_file_serial.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <memory>
#include <set>
#include <string>
#include <string_view>
#include <vector>

#include "io/format/number_policy.hpp"
#include "io/machine/model_registry.hpp"
#include "models/core/pose.hpp"
#include "models/serial/serial_chain.hpp"

namespace pkmopt {

SerialChain chain_of_code(const YamlValue& code) {
  SerialChain chain;
  try {
    chain = SerialChain::from_code(code.as_string());
  } catch (const std::invalid_argument& e) {
    code.fail(e.what());
  }
  for (const ChainElement& e : chain.elements()) {
    if (e.variable) continue;
    const bool translation = e.motion <= 3;
    if (!sane_input_number(e.value) || (translation && !sane_input_length(e.value)))
      code.fail(fmt::format("constants that are {} (motion {}: {})",
                            translation ? kLengthText : kSaneNumberText, e.motion,
                            translation ? "m" : "deg"),
                quote_found(chain.code()));
  }
  return chain;
}

namespace {

struct SerialPart {
  SerialChain chain;
  std::vector<std::string> axes;
  int spindle = -1;  // index of the spindle axis among the variables, -1 if none
};

SerialPart read_serial(const YamlValue& map, bool allow_spindle) {
  SerialPart part;
  part.chain = chain_of_code(map.required("code"));
  const int n = part.chain.num_variables();
  if (const auto axes = map.optional("axes")) {
    for (const YamlValue& a : axes->elements(n)) part.axes.push_back(a.as_string());
    std::set<std::string> unique(part.axes.begin(), part.axes.end());
    if (static_cast<int>(unique.size()) != n) axes->fail("distinct axis names", axes->describe());
  } else {
    for (int i = 0; i < n; ++i) part.axes.push_back(fmt::format("q{}", i + 1));
  }
  if (allow_spindle) {
    if (const auto spindle = map.optional("spindle")) {
      const std::string name = spindle->as_string();
      for (int i = 0; i < n; ++i) {
        if (part.axes[static_cast<std::size_t>(i)] == name) part.spindle = i;
      }
      if (part.spindle < 0) spindle->fail("one of the names in 'axes'", "'" + name + "'");
      int motion = 0, k = 0;
      for (const ChainElement& e : part.chain.elements()) {
        if (e.variable && k++ == part.spindle) motion = e.motion;
      }
      if (motion < 4) spindle->fail("a rotary axis (motion 4, 5 or 6)", "'" + name + "'");
    }
  }
  return part;
}

void add_serial(MachineDescription& d, const SerialPart& part) {
  int k = 0;
  std::string axes;
  for (const ChainElement& e : part.chain.elements()) {
    if (!e.variable) {
      axes += fmt::format(" ({}:{:g})", e.motion, e.value);
      continue;
    }
    const bool spindle = k == part.spindle;
    axes += fmt::format(" {}({}{})", part.axes[static_cast<std::size_t>(k)], e.motion,
                        spindle ? ", spindle" : "");
    if (!spindle) {
      ++d.serial_drives;
      (e.motion <= 3 ? d.translations : d.rotations) += 1;
    }
    ++k;
  }
  d.details.push_back("code: " + part.chain.code());
  d.details.push_back("axes:" + axes);
}

}  // namespace

int describe_serial_axes(const YamlValue& map, bool allow_spindle, MachineDescription& d) {
  const SerialPart part = read_serial(map, allow_spindle);
  add_serial(d, part);
  return part.chain.num_variables();
}

namespace {

// The keys of a serial machine file.
const std::vector<std::string>& serial_keys() {
  static const std::vector<std::string> keys = {
      "model", "name",      "description", "code", "axes",      "spindle",
      "range", "stiffness", "error",       "tool", "tool_axis", "characteristic_length"};
  return keys;
}

// A value of a rotary (degrees in the file) or linear (m) axis.
double axis_value(const YamlValue& v, bool rotary) {
  if (rotary) {
    const double deg = v.as_double();
    if (!sane_input_number(deg)) v.fail(std::string(kSaneNumberText) + " (degrees)", v.describe());
    return deg_to_rad(deg);
  }
  return v.as_length();
}

// One entry per feed axis of `key`, each read by `read` (rotary or not).
template <class Read>
void read_per_axis(const YamlValue& root, std::string_view key, const std::vector<bool>& rotary,
                   Read&& read) {
  const auto list = root.optional(key);
  if (!list) return;
  const std::vector<YamlValue> values = list->elements(static_cast<int>(rotary.size()));
  for (std::size_t i = 0; i < values.size(); ++i) read(values[i], rotary[i], i);
}

}  // namespace

SerialDesign read_serial_design(const YamlValue& root) {
  root.check_keys(serial_keys());
  const SerialPart part = read_serial(root, true);
  SerialDesign design;
  std::vector<ChainElement> elements = part.chain.elements();
  int k = 0;
  std::vector<bool> rotary;
  for (ChainElement& e : elements) {
    if (!e.variable) {
      if (e.motion >= 4) e.value = deg_to_rad(e.value);
      continue;
    }
    e.name = part.axes[static_cast<std::size_t>(k)];
    if (k != part.spindle) rotary.push_back(e.motion >= 4);
    ++k;
  }
  design.chain = SerialChain(std::move(elements));
  design.spindle = part.spindle;
  const YamlValue code = root.required("code");
  const auto rotaries = std::count(rotary.begin(), rotary.end(), true);
  if (rotaries != 2 || rotary.size() != 5)
    code.fail(
        "a 5-axis chain: two rotary and three linear feed axes besides the spindle (other chains "
        "are for `pkmopt describe` only)",
        fmt::format("'{}' with {} rotary and {} linear feed axes", part.chain.code(), rotaries,
                    rotary.size() - static_cast<std::size_t>(rotaries)));
  design.axes.resize(rotary.size());
  {
    const YamlValue range = root.required("range");
    const std::vector<YamlValue> pairs = range.elements(static_cast<int>(rotary.size()));
    for (std::size_t i = 0; i < pairs.size(); ++i) {
      const std::vector<YamlValue> ends = pairs[i].elements(2);
      SerialAxis& a = design.axes[i];
      a.min = axis_value(ends[0], rotary[i]);
      a.max = axis_value(ends[1], rotary[i]);
      if (a.min > a.max)
        pairs[i].fail(fmt::format("[min, max] with min <= max ({})", rotary[i] ? "deg" : "m"),
                      fmt::format("[{}, {}]", ends[0].as_string(), ends[1].as_string()));
    }
  }
  read_per_axis(root, "stiffness", rotary, [&](const YamlValue& v, bool, std::size_t i) {
    const double k_i = v.as_non_negative();
    if (!sane_input_number(k_i) && k_i != 0.0) v.fail(std::string(kSaneNumberText), v.describe());
    design.axes[i].stiffness = k_i;
  });
  read_per_axis(root, "error", rotary, [&](const YamlValue& v, bool is_rotary, std::size_t i) {
    const double e = axis_value(v, is_rotary);
    if (e < 0.0) v.fail(fmt::format("an error >= 0 ({})", is_rotary ? "deg" : "m"), v.describe());
    design.axes[i].error = e;
  });
  if (const auto tool = root.optional("tool")) {
    const std::vector<double> p = tool->as_lengths(3);
    design.tool_point = Eigen::Vector3d(p[0], p[1], p[2]);
  }
  if (const auto axis = root.optional("tool_axis")) {
    const std::vector<double> a = axis->as_doubles(3);
    design.tool_axis = Eigen::Vector3d(a[0], a[1], a[2]);
    if (!(design.tool_axis.norm() > 1e-9) || !sane_input_number(design.tool_axis.norm()))
      axis->fail("a nonzero direction [x, y, z]", axis->describe());
  }
  if (const auto length = root.optional("characteristic_length"))
    design.characteristic_length = length->as_positive_length();
  try {
    SerialMachine check(design);  // the constructor's own checks (parallel rotary axes, ...)
  } catch (const std::invalid_argument& e) {
    code.fail(e.what());
  }
  return design;
}

ModelEntry serial_model_entry() {
  ModelEntry entry;
  entry.name = "serial";
  entry.load = [](const YamlValue& root) -> std::unique_ptr<Machine> {
    return std::make_unique<SerialMachine>(read_serial_design(root));
  };
  entry.describe = [](const YamlValue& root, MachineDescription& d) {
    root.check_keys(serial_keys());
    describe_serial_axes(root, true, d);
    // A file with ranges is a machine: every value is checked as fk and analyze would.
    if (root.has("range")) (void)read_serial_design(root);
  };
  return entry;
}

}  // namespace pkmopt
