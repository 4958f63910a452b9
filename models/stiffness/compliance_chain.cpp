#include "models/stiffness/compliance_chain.hpp"

#include <cmath>
#include <numbers>
#include <stdexcept>

#include "models/core/require.hpp"

namespace pkmopt {

bool ScrewDrive::any() const {
  return E > 0.0 || root_diameter > 0.0 || free_length_at_min > 0.0 || free_length_at_max > 0.0 ||
         nut_stiffness > 0.0 || bearing_stiffness > 0.0 || torsional_stiffness > 0.0 || lead > 0.0;
}

double drive_compliance(const ScrewDrive& d, double q, double q_min, double q_max, bool revolute) {
  double c = 0.0;
  if (revolute) return d.torsional_stiffness > 0.0 ? 1.0 / d.torsional_stiffness : 0.0;
  if (d.has_screw()) {
    const double t = q_max > q_min ? (q - q_min) / (q_max - q_min) : 0.0;
    const double length = d.free_length_at_min + (d.free_length_at_max - d.free_length_at_min) * t;
    const double area = std::numbers::pi * d.root_diameter * d.root_diameter / 4.0;
    c += std::max(length, 0.0) / (d.E * area);
  }
  if (d.nut_stiffness > 0.0) c += 1.0 / d.nut_stiffness;
  if (d.bearing_stiffness > 0.0) c += 1.0 / d.bearing_stiffness;
  if (d.torsional_stiffness > 0.0) {
    const double arm = d.lead / (2.0 * std::numbers::pi);  // m per rad
    c += arm * arm / d.torsional_stiffness;
  }
  return c;
}

void check_screw_drive(const ScrewDrive& d, const std::string& where, bool revolute) {
  const std::pair<const char*, double> values[] = {{"E", d.E},
                                                   {"root_diameter", d.root_diameter},
                                                   {"free_length_at_min", d.free_length_at_min},
                                                   {"free_length_at_max", d.free_length_at_max},
                                                   {"nut_stiffness", d.nut_stiffness},
                                                   {"bearing_stiffness", d.bearing_stiffness},
                                                   {"torsional_stiffness", d.torsional_stiffness},
                                                   {"lead", d.lead}};
  for (const auto& [name, value] : values)
    require(std::isfinite(value) && value >= 0.0,
            where + "." + name + " must be a finite number >= 0");
  if (revolute) {
    require(!d.has_screw() && d.E == 0.0 && d.root_diameter == 0.0 && d.free_length_at_min == 0.0 &&
                d.free_length_at_max == 0.0 && d.nut_stiffness == 0.0 &&
                d.bearing_stiffness == 0.0 && d.lead == 0.0,
            where + ": a revolute actuator has only torsional_stiffness (N·m/rad)");
    return;
  }
  require((d.E > 0.0) == (d.root_diameter > 0.0),
          where + ": the screw needs both E and root_diameter");
  require(d.has_screw() || (d.free_length_at_min == 0.0 && d.free_length_at_max == 0.0),
          where + ": free lengths are those of a screw: give E and root_diameter too");
  require(!d.has_screw() || d.free_length_at_min > 0.0 || d.free_length_at_max > 0.0,
          where + ": the screw needs its free length (free_length_at_min, free_length_at_max)");
  require((d.torsional_stiffness > 0.0) == (d.lead > 0.0),
          where +
              ": the motor torsion acts through the lead: give torsional_stiffness and lead "
              "together");
}

}  // namespace pkmopt
