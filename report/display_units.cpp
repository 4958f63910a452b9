#include "report/display_units.hpp"

namespace pkmopt {

double display_scale(std::string_view metric, std::string_view unit) {
  const bool micrometres = metric == "tcp_deflection_max" || metric == "tcp_error_max";
  return micrometres && unit == "m" ? 1e6 : 1.0;
}

ParetoFront in_display_units(const ParetoFront& front) {
  ParetoFront shown = front;
  for (std::size_t k = 0; k < shown.objectives.size(); ++k) {
    ParetoObjective& o = shown.objectives[k];
    const double scale = display_scale(o.name, o.unit);
    if (scale == 1.0) continue;
    o.unit = "µm";
    for (ParetoDesign& d : shown.designs) d.objectives[k] *= scale;
  }
  for (std::size_t k = 0; k < shown.constraints.size(); ++k) {
    ParetoConstraint& c = shown.constraints[k];
    const double scale = display_scale(c.metric, c.unit);
    if (scale == 1.0) continue;
    c.unit = "µm";
    c.bound *= scale;
    for (ParetoDesign& d : shown.designs) d.constraints[k] *= scale;
  }
  return shown;
}

}  // namespace pkmopt
