// The design families of the leg-chain models (problems/design/machine_design.hpp has what a
// family is and the problem built on it; docs/design-studies.md has their parameter tables).
// Every family has the parameter `home_height` (m), the task lift.
//
//   delta        base_radius, platform_radius, upper_arm, rod (m), drive_min_deg, drive_max_deg
//                (deg, the drive range), home_height (m);
//                machine_size = envelope_volume = pi (r_b + r_a)^2 (2 r_a + l)
//                (r_b base radius, r_a upper arm, l rod: the cylinder swept by the cranks,
//                extended down by a rod length).
//   linear_delta guide_radius, platform_radius, rod, stroke (m; carriage travel q in
//                [0, stroke] along each guide from z = 0), inclination_deg (deg), home_height;
//                machine_size = envelope_volume = pi rho^2 (s cos(i) + l),
//                rho = max(r_g, |r_g - s sin(i)|) (the cylinder about the guide segments,
//                extended down by a rod length).
//   hexaglide    platform_radius (m), pair_separation_deg (deg; the semi-regular platform
//                turned 90 deg about z, as models/leg_chain/leg_chain.hpp), guide_offset (m: guide
//                i lies at y = b_i.y + guide_offset outwards), strut, stroke (m: carriages travel
//                q in [-stroke/2, stroke/2] along x), inclination_deg (deg), home_height (m);
//                machine_size = envelope_volume = pi rho^2 (s |sin(i)| + L),
//                rho = max_i sqrt((s/2 cos(i))^2 + (y_i - y_mean)^2), y_i the guide positions.
//   tripod_3prs  base_radius, platform_radius, strut, stroke (m: slide travel q in
//                [q_min, q_min + stroke], q_min from the template), home_height (m);
//                machine_size = envelope_volume (the cylinder about the slides' travel,
//                extended by a strut length). The head's inputs are z and the two tilts: the
//                task's x, y and rz are replaced by the parasitic ones
//                (models/leg_chain/leg_chain.hpp), so a tripod task is a column of z values times a
//                tilt cone.
//   tripod_3rps  base_radius, platform_radius, min_length, stroke (m: leg length q in
//                [min_length, min_length + stroke]), home_height (m); machine_size =
//                envelope_volume (the cylinder about the base joints, extended by the longest
//                leg). Its task, like the 3-PRS head's, is a column of z values times a tilt cone.
//
//   DesignFamily family = delta_family(DeltaDesign{}, delta_machine_file);
#pragma once

#include "models/leg_chain/leg_chain.hpp"
#include "problems/design/machine_design.hpp"

namespace pkmopt {

/// The families of the leg-chain models; the template supplies everything the parameters do
/// not set (its geometric fields are the parameter defaults).
/// `machine_file` writes a design as a machine file (DesignFamily::machine_file).
DesignFamily delta_family(const DeltaDesign& design_template,
                          DesignWriter<DeltaDesign> machine_file = {});
DesignFamily linear_delta_family(const LinearDeltaDesign& design_template,
                                 DesignWriter<LinearDeltaDesign> machine_file = {});
DesignFamily hexaglide_family(const HexaglideDesign& design_template,
                              DesignWriter<HexaglideDesign> machine_file = {});
DesignFamily tripod_3prs_family(const Tripod3PrsDesign& design_template,
                                DesignWriter<Tripod3PrsDesign> machine_file = {});
DesignFamily tripod_3rps_family(const Tripod3RpsDesign& design_template,
                                DesignWriter<Tripod3RpsDesign> machine_file = {});

}  // namespace pkmopt
