// The study section of a hybrid machine (model: hybrid): serial axes as in its machine file
// carrying a module given as a design study's machine section of a design-family model; the
// module's parameters are the study's (problems/design/hybrid_design.hpp).
//
//   machine:
//     model: hybrid
//     serial: {code: "12", axes: [X, Y], range: [[-0.25, 0.25], [-0.25, 0.25]],
//              stiffness: [1.5e8, 1.5e8], error: [5e-6, 5e-6]}
//     parallel:
//       home: [0, 0, 0.9]                 # the module's reference point of the follow rule
//       machine:                          # the module's study section
//         model: tripod_3prs
//         parameters: {base_radius: {min: 0.2, max: 0.45}, ...}
//         struts: {...}
//
// Designs are written as hybrid machine files with the module inline (parallel.machine).
#pragma once

#include <memory>
#include <string>

#include "io/design/study_machine.hpp"

namespace pkmopt {

/// Reads a hybrid study section (throws InputError naming file, line, column and key).
std::unique_ptr<StudyMachine> read_hybrid_study_machine(const YamlValue& machine);

/// The docs table of the hybrid study section's keys.
std::string hybrid_study_machine_markdown();

}  // namespace pkmopt
