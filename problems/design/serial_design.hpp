// The design family of a serial 5-axis machine (models/serial/serial_machine.hpp) for the generic
// machine design problem (problems/design/machine_design.hpp).
//
// Parameters (file units):
//   <axis>_travel  m  for each linear feed axis (x_travel for an axis named X): the width of its
//                     range, centred where the template's range is centred
//   pivot          m  the tool point at pivot along -tool_axis from the last frame's origin: on a
//                     machine whose head tilts, the distance from the tilt axis to the tool tip
//                     (the lever of the rotary axes' compliance); 0 puts the tool point on it.
//                     At the template's |tool point| the template's tool point stays as it is
//   home_height    m  the task lift along base z (as for every family)
// Everything else (the chain, the rotary ranges, every stiffness and error, the tool axis and
// characteristic length) comes from the template. machine_size is SerialMachine::envelope_volume
// (the linear travel box grown by the tool's reach).
//
// Example:
//   DesignFamily family = serial_family(read_serial_design(root), serial_design_to_yaml);
//   // parameters: x_travel, y_travel, z_travel, pivot, home_height
#pragma once

#include "models/serial/serial_machine.hpp"
#include "problems/design/machine_design.hpp"

namespace pkmopt {

/// The family around a template design (its linear travels and |tool point| are the defaults).
DesignFamily serial_family(const SerialDesign& design_template,
                           DesignWriter<SerialDesign> machine_file = {});

}  // namespace pkmopt
