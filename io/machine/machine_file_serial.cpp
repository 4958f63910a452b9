#include "io/machine/machine_file_serial.hpp"

#include <fmt/format.h>

#include <set>
#include <string>
#include <vector>

#include "io/format/number_policy.hpp"
#include "io/machine/model_registry.hpp"
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

ModelEntry serial_model_entry() {
  ModelEntry entry;
  entry.name = "serial";
  entry.describe = [](const YamlValue& root, MachineDescription& d) {
    root.check_keys({"model", "name", "description", "code", "axes", "spindle"});
    describe_serial_axes(root, true, d);
  };
  return entry;
}

}  // namespace pkmopt
