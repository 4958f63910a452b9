// Machine files written from designs: the `model:` files of the leg-chain models (delta,
// linear_delta, hexaglide, tripod_3prs) and of the 16K20F3 lathe conversion, with the keys their
// readers take (io/machine_file_leg_chain.hpp, io/machine_file_lathe.hpp; the hexapod's writer is
// hexapod_design_to_yaml in io/machine_file.hpp). Numbers are written in their shortest round-trip
// form and angles in degrees to 12 significant digits, so reading a written file gives the same
// machine. The keys, their order and their forms come from the field lists the readers use
// (`describe_fields` in io/machine_file_leg_chain.hpp and io/machine_file_lathe.hpp).
//
// Example:
//   write_file_atomically("d.yaml", delta_machine_file(DeltaDesign{}));
//   const DesignFamily family = delta_family(DeltaDesign{}, delta_machine_file);
//   write_file_atomically("e.yaml", family.machine_file(parameters));
#pragma once

#include <string>

#include "models/lathe_conversion.hpp"
#include "models/leg_chain.hpp"

namespace pkmopt {

std::string delta_machine_file(const DeltaDesign& design);
std::string linear_delta_machine_file(const LinearDeltaDesign& design);
std::string hexaglide_machine_file(const HexaglideDesign& design);
std::string tripod_3prs_machine_file(const Tripod3PrsDesign& design);
/// The `model: lathe_16k20f3` machine file of a design, every key written.
std::string lathe_16k20f3_machine_file(const Lathe16k20f3Design& design);
/// The generic `model: leg_chain` file of a design, its legs as flow maps (RUS legs: the actuator
/// error as actuator_error_deg).
std::string leg_chain_machine_file(const LegChainDesign& design);

}  // namespace pkmopt
