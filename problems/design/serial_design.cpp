#include "problems/design/serial_design.hpp"

#include <cctype>
#include <string>

namespace pkmopt {

DesignFamily serial_family(const SerialDesign& t, DesignWriter<SerialDesign> writer) {
  DesignFamily family;
  family.model = "serial";
  // The linear feed axes (indices into t.axes) and their names.
  std::vector<std::size_t> linear;
  int k = 0;
  for (const ChainElement& e : t.chain.elements()) {
    if (!e.variable) continue;
    if (k != t.spindle) {
      const std::size_t axis = static_cast<std::size_t>(k - (t.spindle >= 0 && k > t.spindle));
      if (e.motion <= 3) {
        linear.push_back(axis);
        std::string name = e.name.empty() ? "q" + std::to_string(axis + 1) : e.name;
        for (char& c : name) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
        const SerialAxis& a = t.axes[axis];
        family.parameters.push_back({name + "_travel", "m",
                                     "travel of the linear axis " + e.name +
                                         " (centred as in the "
                                         "template)",
                                     a.max - a.min, false, true});
      }
    }
    ++k;
  }
  family.parameters.push_back({"pivot", "m",
                               "tool tip to the last frame's origin along the tool axis",
                               t.tool_point.norm(), false, true});
  family.parameters.push_back(
      {"home_height", "m", "the task region is lifted by this along base z", 0.0, true, true});
  auto design = [t, linear](const std::vector<double>& p) {
    SerialDesign d = t;
    // The template's own values stay exactly as they are (its file reads back unchanged).
    for (std::size_t i = 0; i < linear.size(); ++i) {
      SerialAxis& a = d.axes[linear[i]];
      if (p.at(i) == a.max - a.min) continue;
      const double centre = 0.5 * (a.min + a.max);
      a.min = centre - 0.5 * p.at(i);
      a.max = centre + 0.5 * p.at(i);
    }
    const double pivot = p.at(linear.size());
    if (pivot != t.tool_point.norm())
      d.tool_point = (-pivot * t.tool_axis.normalized()).array() + 0.0;  // no -0
    return d;
  };
  family.build = [design](const std::vector<double>& p) -> std::unique_ptr<Machine> {
    return std::make_unique<SerialMachine>(design(p));
  };
  family.machine_size = envelope_machine_size;
  if (writer)
    family.machine_file = [design, writer](const std::vector<double>& p) {
      return writer(design(p));
    };
  return family;
}

}  // namespace pkmopt
