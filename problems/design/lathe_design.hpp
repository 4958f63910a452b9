// The design family of the 16K20F3 lathe conversion (models/leg_chain/lathe_conversion.hpp) for the
// generic machine design problem (problems/design/machine_design.hpp), and its machine-file writer.
//
// Parameters (file units; angles none):
//   strut_length  m  the constant strut length L of both parallelogram pairs (PUS legs)
//   guide_y       m  y of the carriages' hinge line (may be negative)
//   leg_base_y    m  y of the overhead beam carrying the electro-cylinders' base joints
//   home_height   m  the task lift along base z (as for every family; 0 for the lathe study)
// Everything else comes from the template design (Lathe16k20f3Design).
//
// machine_size (m^3) of this family is L^3, the cube of the strut length: the study's size
// objective is the strut length itself (a monotone measure of it, in the metric's unit m^3), not
// an envelope volume - the conversion's question is how short the struts can be. L = size^(1/3).
//
// The machine file written for a parameter vector is the `model: lathe_16k20f3` file of
// io/machine/machine_file_lathe.hpp (every key written).
//
// Example:
//   MachineDesignSpec spec;
//   spec.family = lathe_16k20f3_family(Lathe16k20f3Design{});
//   spec.parameters = default_ranges(spec.family);
//   spec.parameters[spec.family.index_of("strut_length")] = {0.5, 0.9};
#pragma once

#include <string>

#include "models/leg_chain/lathe_conversion.hpp"
#include "problems/design/machine_design.hpp"

namespace pkmopt {

/// The family around a template design (its strut_length, guide_y and leg_base_y are the
/// parameter defaults).
DesignFamily lathe_16k20f3_family(const Lathe16k20f3Design& design_template,
                                  DesignWriter<Lathe16k20f3Design> machine_file = {});

}  // namespace pkmopt
