#include "io/machine/machine_file_serial.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <memory>
#include <set>
#include <string>
#include <string_view>
#include <vector>

#include "io/format/csv.hpp"
#include "io/format/field_list.hpp"
#include "io/format/number_policy.hpp"
#include "io/machine/model_registry.hpp"
#include "models/core/pose.hpp"
#include "models/serial/serial_chain.hpp"
#include "problems/design/serial_design.hpp"

namespace pkmopt {

// A constant rotation (rad) as the degrees the reader converts back to exactly that value when
// one exists (any value read from a file): 12 significant digits if they do, else the shortest
// text of the double nearest to it among the neighbours of rad_to_deg(rad).
std::string degrees_text(double rad) {
  auto back = [](const std::string& text) {
    return deg_to_rad(std::strtod(text.c_str(), nullptr));
  };
  const double deg = rad_to_deg(rad);
  const std::string twelve = fmt::format("{:.12g}", deg);
  if (back(twelve) == rad) return twelve;
  std::string best = format_number(deg);
  double best_miss = std::abs(back(best) - rad);
  double up = deg;
  double down = deg;
  for (int k = 0; k < 8 && best_miss > 0.0; ++k) {
    up = std::nextafter(up, std::numeric_limits<double>::infinity());
    down = std::nextafter(down, -std::numeric_limits<double>::infinity());
    for (const double x : {up, down}) {
      const std::string text = format_number(x);
      const double miss = std::abs(back(text) - rad);
      if (miss < best_miss) {
        best = text;
        best_miss = miss;
      }
    }
  }
  return best;
}

// The chain as the reader's `serial.code`: a digit per element, constants as "k:v" (m, deg).
std::string serial_code_text(const SerialChain& chain) {
  std::string code;
  for (const ChainElement& e : chain.elements()) {
    if (!code.empty()) code += ' ';
    code += static_cast<char>('0' + e.motion);
    if (!e.variable) code += ":" + (e.motion >= 4 ? degrees_text(e.value) : format_number(e.value));
  }
  return code;
}

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

std::string serial_design_to_yaml(const SerialDesign& design) {
  auto list = [](const std::vector<std::string>& items) {
    std::string out;
    for (const std::string& item : items) out += (out.empty() ? "" : ", ") + item;
    return "[" + out + "]";
  };
  std::vector<std::string> names, ranges, stiffness, errors;
  std::vector<bool> rotary;
  std::string spindle;
  int k = 0;
  for (const ChainElement& e : design.chain.elements()) {
    if (!e.variable) continue;
    const std::string name = e.name.empty() ? fmt::format("q{}", k + 1) : e.name;
    names.push_back(yaml_scalar(name));
    if (k == design.spindle)
      spindle = name;
    else
      rotary.push_back(e.motion >= 4);
    ++k;
  }
  auto value = [](double v, bool is_rotary) {
    return is_rotary ? degrees_text(v) : format_number(v);
  };
  for (std::size_t i = 0; i < design.axes.size(); ++i) {
    const SerialAxis& a = design.axes[i];
    ranges.push_back("[" + value(a.min, rotary[i]) + ", " + value(a.max, rotary[i]) + "]");
    stiffness.push_back(format_number(a.stiffness));
    errors.push_back(value(a.error, rotary[i]));
  }
  auto vec = [](const Eigen::Vector3d& v) {
    return fmt::format("[{}, {}, {}]", format_number(v(0)), format_number(v(1)),
                       format_number(v(2)));
  };
  std::string out = "model: serial\n";
  out += "code: \"" + serial_code_text(design.chain) + "\"\n";
  out += "axes: " + list(names) + "\n";
  if (!spindle.empty()) out += "spindle: " + yaml_scalar(spindle) + "\n";
  out += "range: " + list(ranges) + "\n";
  out += "stiffness: " + list(stiffness) + "\n";
  out += "error: " + list(errors) + "\n";
  out += "tool: " + vec(design.tool_point) + "\n";
  out += "tool_axis: " + vec(design.tool_axis) + "\n";
  out += "characteristic_length: " + format_number(design.characteristic_length) + "\n";
  return out;
}

namespace {

// The design-family template without a study section: the 5-axis machining centre 641236 of
// examples/serial_641236.yaml.
constexpr const char* kSerialTemplate =
    "model: serial\ncode: \"641236\"\naxes: [C, A, X, Y, Z, S]\nspindle: S\n"
    "range: [[-360, 360], [-120, 30], [-0.4, 0.4], [-0.4, 0.4], [-0.2, 0.5]]\n"
    "stiffness: [1.0e6, 2.0e6, 1.5e8, 1.5e8, 1.2e8]\n"
    "error: [0.0014, 0.0014, 5.0e-6, 5.0e-6, 5.0e-6]\ntool: [0, 0, 0]\n"
    "characteristic_length: 0.2\n";

// Architecture synthesis: the classic 5-axis machining centres by coordinate code, the same
// drive stiffnesses and errors as the other structures' ball-screw axes (X, Y 1.5e8 N/m, Z
// 1.2e8 N/m, 5 um; rotary axes 5 arc seconds): a table that turns (C) and tilts (A) under a
// spindle moving X, Y, Z (641236, the part 0.1 scale above where C meets A), and a fork head
// that turns (C) and tilts (A) the spindle at the end of X, Y, Z (123646, the tilt axis `pivot`
// above the tool tip).
std::vector<SynthesisTemplate> serial_synthesis(const SynthesisScale& scale) {
  const double s = std::max(scale.size, 0.1) / 0.3;
  auto range = [s](double lo, double hi) {
    return fmt::format("{{min: {:.4g}, max: {:.4g}}}", lo * s, hi * s);
  };
  SynthesisTemplate table;
  table.name = "serial_table_ca";
  table.structure = "5-axis machining centre, C/A tilting table (641236)";
  table.task_centre = {0.0, 0.0, 0.1 * s};
  table.machine_yaml = fmt::format(
      "model: serial\n"
      "parameters: {{x_travel: {}, y_travel: {}, z_travel: {}, pivot: 0, home_height: {}}}\n"
      "code: \"641236\"\naxes: [C, A, X, Y, Z, S]\nspindle: S\n"
      "range: [[-360, 360], [-120, 30], [-0.4, 0.4], [-0.4, 0.4], [{:.4g}, {:.4g}]]\n"
      "stiffness: [1.0e6, 2.0e6, 1.5e8, 1.5e8, 1.2e8]\n"
      "error: [0.0014, 0.0014, 5.0e-6, 5.0e-6, 5.0e-6]\ntool: [0, 0, 0]\n"
      "characteristic_length: 0.2\n",
      range(0.3, 1.2), range(0.3, 1.2), range(0.2, 0.9), range(-0.1, 0.1), 0.1 * s - 0.35 * s,
      0.1 * s + 0.35 * s);
  SynthesisTemplate head;
  head.name = "serial_head_ca";
  head.structure = "5-axis machining centre, C/A fork head (123646)";
  head.task_centre = {0.0, 0.0, 0.0};
  head.machine_yaml = fmt::format(
      "model: serial\n"
      "parameters: {{x_travel: {}, y_travel: {}, z_travel: {}, pivot: {{min: 0.15, max: 0.35}}, "
      "home_height: {}}}\n"
      "code: \"123646\"\naxes: [X, Y, Z, C, A, S]\nspindle: S\n"
      "range: [[-0.4, 0.4], [-0.4, 0.4], [{:.4g}, {:.4g}], [-200, 200], [-100, 100]]\n"
      "stiffness: [1.5e8, 1.5e8, 1.2e8, 1.0e6, 1.0e6]\n"
      "error: [5.0e-6, 5.0e-6, 5.0e-6, 0.0014, 0.0014]\ntool: [0, 0, -0.25]\n"
      "characteristic_length: 0.2\n",
      range(0.3, 1.2), range(0.3, 1.2), range(0.2, 0.9), range(-0.1, 0.1), 0.25 - 0.35 * s,
      0.25 + 0.35 * s);
  return {table, head};
}

}  // namespace

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
  entry.design_family = [](const YamlValue* machine) {
    return serial_family(machine ? read_serial_design(*machine)
                                 : read_serial_design(YamlValue::load_string(
                                       kSerialTemplate, "the serial design family's template")),
                         serial_design_to_yaml);
  };
  entry.synthesis = serial_synthesis;
  return entry;
}

}  // namespace pkmopt
