// The units a person reads a design study in (the report, its plots, the terminal), against the
// SI units of the files (pareto.json, pareto.csv: m, N, N/m, m^3):
//
//   quantity in                      shown in   scale
//   N/m (stiffness)                  N/µm       1e-6
//   m of tcp_deflection*, tcp_error* µm         1e6
//   m (any other length)             mm         1e3
//   m^3 (volumes)                    l (litre)  1e3
//   N (forces)                       kN         1e-3
//   anything else (deg, Hz, kg, m^2, dimensionless) unchanged
//
// Example:
//   const ParetoFront shown = in_display_units(read_pareto_json("pareto.json"));
//   // shown.objectives[k].unit == "µm" for tcp_deflection_max, values times 1e6
#pragma once

#include <string>
#include <string_view>

#include "io/results/pareto_json.hpp"

namespace pkmopt {

/// A display unit: value_shown = scale * value_in_file.
struct EngineeringUnit {
  std::string unit;
  double scale = 1.0;
};

/// The display unit of a quantity called `name` (a metric or a parameter) given in `unit` (the
/// table above).
EngineeringUnit engineering_unit(std::string_view name, std::string_view unit);

/// engineering_unit(metric, unit).scale.
double display_scale(std::string_view metric, std::string_view unit);

/// The front with objective values, constraint values and bounds in display units and their
/// units renamed; designs' parameters, home heights, the task and everything else unchanged.
ParetoFront in_display_units(const ParetoFront& front);

}  // namespace pkmopt
