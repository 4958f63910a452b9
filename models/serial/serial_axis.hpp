// One feed axis of a serial chain (models/serial/serial_chain.hpp): its travel, drive stiffness,
// positioning error and moved mass. Used by serial machines (models/serial/serial_machine.hpp)
// and by the serial axes of hybrid machines (models/hybrid/hybrid_machine.hpp).
//
// Units follow the axis: a linear axis in m, N/m and m; a rotary one in rad, N*m/rad and rad.
#pragma once

namespace pkmopt {

struct SerialAxis {
  double min = 0.0;        ///< travel range, min <= max (m or rad)
  double max = 0.0;        ///< m or rad
  double stiffness = 0.0;  ///< drive stiffness along or about the axis (N/m, N*m/rad); 0 = rigid
  double error = 0.0;      ///< positioning error half-width (m or rad); 0 = exact
  /// kg: the mass this axis moves on its own (its carriage and what is fixed to it; the axes it
  /// carries count separately); 0 = massless.
  double mass = 0.0;
};

}  // namespace pkmopt
