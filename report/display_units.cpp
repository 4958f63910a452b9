#include "report/display_units.hpp"

namespace pkmopt {

EngineeringUnit engineering_unit(std::string_view name, std::string_view unit) {
  if (unit == "N/m") return {"N/µm", 1e-6};
  if (unit == "m") {
    const bool micrometres = name.starts_with("tcp_deflection") || name.starts_with("tcp_error");
    return micrometres ? EngineeringUnit{"µm", 1e6} : EngineeringUnit{"mm", 1e3};
  }
  if (unit == "m^3") return {"l", 1e3};
  if (unit == "N") return {"kN", 1e-3};
  return {std::string(unit), 1.0};
}

double display_scale(std::string_view metric, std::string_view unit) {
  return engineering_unit(metric, unit).scale;
}

ParetoFront in_display_units(const ParetoFront& front) {
  ParetoFront shown = front;
  for (std::size_t k = 0; k < shown.objectives.size(); ++k) {
    ParetoObjective& o = shown.objectives[k];
    const EngineeringUnit e = engineering_unit(o.name, o.unit);
    o.unit = e.unit;
    if (e.scale == 1.0) continue;
    for (ParetoDesign& d : shown.designs) d.objectives[k] *= e.scale;
  }
  for (std::size_t k = 0; k < shown.constraints.size(); ++k) {
    ParetoConstraint& c = shown.constraints[k];
    const EngineeringUnit e = engineering_unit(c.metric, c.unit);
    c.unit = e.unit;
    if (e.scale == 1.0) continue;
    c.bound *= e.scale;
    for (ParetoDesign& d : shown.designs) d.constraints[k] *= e.scale;
  }
  return shown;
}

}  // namespace pkmopt
