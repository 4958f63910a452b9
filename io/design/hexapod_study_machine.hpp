// The hexapod's `machine:` section of a design study (io/design/study_machine.hpp):
//
//   machine:
//     model: hexapod
//     parameters:                             # every key optional; a number = fixed,
//       base_radius: {min: 0.45, max: 0.75}   #   {min, max} = free (m; *_deg in degrees)
//       platform_radius: 0.25
//       base_pair_separation_deg: 20
//       platform_pair_separation_deg: {min: 10, max: 40}
//       min_length: 0.70
//       stroke: 0.45
//       home_height: 0.0                      # lifts the task region along z (m)
//     legs: {E: 2.1e11, area: 3.0e-4, actuator_stiffness: 2.0e8}   # or {axial_stiffness: k}
//     joints: {base_max_angle_deg: 45, platform_max_angle_deg: 45} # optional
//     tool: {tcp: [0, 0, -0.10]}                                    # optional
//     actuator_error: 1.0e-5                                        # optional (m)
//
// The hexapod's problem (problems/design/hexapod_design.hpp) has a smooth formulation for gradient
// solvers and may choose the legs' actuators from a catalog: a study constraint
//   {actuator: NAME, catalog: FILE}      the legs are that entry: leg_force_max <= its rating
//                                        (and, with a task a_max, actuator_force_dynamic_max <=
//                                        its peak rating), stroke <= its stroke;
//   {actuator: cheapest, catalog: FILE}  the optimiser chooses, for every design, the cheapest
//                                        entry that carries the legs: actuator_overload <= 0,
//                                        stroke <= the longest entry's stroke.
// The catalog path is resolved against the study file's folder and written absolute.
#pragma once

#include <memory>
#include <string>

#include "io/design/actuator_catalog_file.hpp"
#include "io/design/study_machine.hpp"
#include "io/format/yaml_reader.hpp"

namespace pkmopt {

/// The hexapod's study section. Throws InputError.
std::unique_ptr<StudyMachine> read_hexapod_study_machine(const YamlValue& machine);

/// The docs table of the hexapod's study section (defaults: the sample hexapod).
std::string hexapod_study_machine_markdown();

}  // namespace pkmopt
