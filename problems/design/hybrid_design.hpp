// The design family of a hybrid machine (models/hybrid/hybrid_machine.hpp): serial axes that stay
// as given carrying a parallel module whose own design family sets its dimensions.
//
// Parameters: the module family's, with their names, units and defaults (home_height among them:
// the task region is lifted along the world z, which is the module's when the carrier turns
// nothing). The serial chain, the axes (travel, stiffness, error, mass), the module's reference
// point `home` and gravity come from the carrier template; the template's module is replaced by
// the module family's machine of each parameter vector.
//
// machine_size (m^3) is HybridMachine::envelope_volume: the module's envelope, taken as the cube of
// its volume, swept over the axes' travel box. It needs a module whose machines have an envelope
// (every family of pkmopt's parallel models).
//
// The machine file of a parameter vector is the hybrid's file with the module written inline
// (parallel.machine): `machine_file` gets the carrier and the module family's file text.
//
// Example:
//   HybridDesign carrier;                                  // chain "12", axes, home
//   carrier.chain = SerialChain::from_code("12");
//   carrier.axes = {{.min = -0.2, .max = 0.2}, {.min = -0.2, .max = 0.2}};
//   carrier.home = {0, 0, 0.9};
//   DesignFamily family = hybrid_family(carrier, tripod_3prs_family(Tripod3PrsDesign{}));
#pragma once

#include <functional>
#include <string>

#include "models/hybrid/hybrid_machine.hpp"
#include "problems/design/machine_design.hpp"

namespace pkmopt {

/// Writes a hybrid design with its module inline: (carrier, the module's machine file text).
using HybridWriter = std::function<std::string(const HybridDesign&, const std::string&)>;

/// The family of `carrier`'s axes carrying `module`'s machines. Throws std::invalid_argument when
/// the carrier has no axes or the module family builds hybrid machines.
DesignFamily hybrid_family(const HybridDesign& carrier, const DesignFamily& module,
                           HybridWriter machine_file = {});

}  // namespace pkmopt
