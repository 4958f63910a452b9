// The units a report shows: lengths designers read in micrometres (the TCP deflection under the
// cutting load, the TCP error) are shown in µm; everything else as pareto.json has it (SI).
//
// Example:
//   const ParetoFront shown = in_display_units(read_pareto_json("pareto.json"));
//   // shown.objectives[k].unit == "µm" for tcp_deflection_max, values times 1e6
#pragma once

#include <string_view>

#include "io/pareto_json.hpp"

namespace pkmopt {

/// The display scale of a metric given in `unit` (1e6 for the µm metrics in m, else 1).
double display_scale(std::string_view metric, std::string_view unit);

/// The front with objective values, constraint values and bounds of the µm metrics scaled and
/// their units renamed; designs, parameters and everything else unchanged.
ParetoFront in_display_units(const ParetoFront& front);

}  // namespace pkmopt
