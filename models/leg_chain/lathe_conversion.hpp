// The 16K20F3 lathe conversion: the cross slide of a 16K20F3 CNC lathe replaced by a 2-PUS +
// 2-UPS Schoenflies (3T1R) strut mechanism carrying a 12-position turret, as a named member of
// the leg-chain family (models/leg_chain/leg_chain.hpp), plus the design steps of the original
// conversion study (their strut-length formula, the task, the minimal strut length by bisection).
//
// Frame (base = lathe frame, docs/conventions.md units): origin on the spindle axis halfway between
// the centres; x along the spindle axis towards the tailstock (along the bed's guideways), y
// horizontal across the bed towards the operator (the stock cross-slide direction), z up. The
// carriage guideways lie at z = -centre_height. This is the frame of the cutting model
// (problems/design/cutting_load.hpp: the machine frame of approach angle 0 has y radially outward
// through the tool tip and z along the surface velocity), so a turning wrench from
// `wrench: {turning: ..., approach_angle_deg: optimal}` applies unchanged.
//
// Mechanism (studies/library/lathe-16k20f3/README.md has the drawing):
//   legs 0, 1  PUS: two carriages on the bed's front guideway (guide line through
//              (0, guide_y, guide_z), direction +x, q = carriage position x in m), each carrying a
//              constant-length parallelogram strut pair (two rods, bars parallel to x) to the
//              turret housing's lower front edge at b = (-/+ strut_joint_spread,
//              strut_joint_y, strut_joint_z). Carriage 0 runs on the headstock side of its joint
//              (branch +1, s.u > 0), carriage 1 on the tailstock side (branch -1): a "Lambda".
//   legs 2, 3  UPS: two electro-cylinders (variable length q in m) from an overhead beam fixed
//              to the bed, base joints at (leg_base_x, leg_base_y -/+ leg_base_spacing / 2,
//              leg_base_z), to the housing's top at (0, -/+ leg_joint_spacing / 2, leg_joint_z).
// The parallelogram bars parallel to x keep the turret from turning about y and z, so the
// platform (the turret housing) has the Schoenflies mobility about e = x, the spindle axis:
// DOF (x, y, z, phi), phi the turn of the housing about x. The struts set x (carriages moving
// together) and the distance from the guide line (carriages moving apart); the legs set the
// position across it and phi. The turret indexes its 12 tools about its own axis parallel to x;
// the working tool's tip is the TCP, at tool_reach from the turret centre (the platform origin)
// in the direction -(0, cos a0, sin a0), a0 = approach_angle: at phi = 0 the tool points at the
// spindle axis from approach angle a0 (the cutting model's alpha), and phi changes the approach
// angle to a0 + phi (rx of a pose = phi).
//
// Stiffness: struts E * area * 2 / L (two rods per pair), the carriage drives (ball screw along
// the bed, like the stock Z drive) carriage_stiffness in series; legs E * leg_area / q in series
// with leg_actuator_stiffness. Optionally the drive trains in detail (carriage_drive, leg_drive:
// ball screw whose free length follows the carriage position or the leg length, nut, bearing,
// motor torsion; models/stiffness/compliance_chain.hpp) and the joints' axial stiffness, all in
// series. The parallelogram bars are taken as rigid (leg_chain.hpp).
//
// The conversion study's strut-length formula (`seeds_strut_length`), with the inputs as the
// study defines them: the strut runs from the carriage hinge (a base joint) to the strut joint of
// the turret housing (a platform joint) when the tool tip is at its farthest position, the
// largest part's radius plus the tool-approach clearance from the part axis in y and in z:
//   L = sqrt(X_K^2 + (Y_D + D_max/2 + Y_xx - Y_I)^2 + (Z_D + D_max/2 + Z_xx - Z_I)^2)
// with Y_D, Z_D the part axis seen from the hinge line, Y_I, Z_I the tool tip seen from the
// platform joint (the turret's geometry) and X_K the strut's offset along the guideway, which its
// largest inclination fixes: X_K = L cos(strut_max_angle), so L = sqrt(dy^2 + dz^2) /
// sin(strut_max_angle) (`seeds_strut_length_at_inclination`; `seeds_strut_inputs` reads the
// inputs off a design). For this design that gives 0.5277 m for the study's region and 0.7205 m
// for the 400 mm cross travel, the minimal strut lengths below to 1e-5 m: the far corner of the
// task with the strut at its largest inclination is what binds. All in m.
// `minimal_strut_length` computes the shortest strut with which the whole
// mechanism reaches every pose of a task (bisection on strut_length; reachability is monotone in
// it while the carriage travel does not bind: a longer strut reaches farther from the guide line
// and leans more towards it, but pushes the carriages farther out along x).
//
// Example:
//   pkmopt::Lathe16k20f3Design d;                       // the study's design
//   auto machine = pkmopt::make_lathe_16k20f3(d);
//   auto poses = pkmopt::lathe_task_poses(pkmopt::LatheTask{});   // tool tip over the task box
//   auto l_min = pkmopt::minimal_strut_length(d, poses, 0.4, 0.8, 1e-6);   // 0.7205 m
#pragma once

#include <Eigen/Core>
#include <cmath>
#include <memory>
#include <optional>
#include <vector>

#include "models/core/machine.hpp"
#include "models/core/pose.hpp"
#include "models/leg_chain/leg_chain.hpp"
#include "models/stiffness/compliance_chain.hpp"

namespace pkmopt {

/// The conversion's geometry (m, rad, N/m, Pa, m^2). Defaults: the design of the study
/// (studies/library/lathe-16k20f3/README.md says where each number comes from).
struct Lathe16k20f3Design {
  double centre_height = 0.215;  ///< spindle axis above the guideways (16K20: 215 mm)
  // Turret (platform frame: origin at the turret centre, axes parallel to the base axes at phi=0)
  double tool_reach = 0.16;  ///< turret centre to the working tool's tip (0: TCP = centre)
  double approach_angle = std::atan(0.5);  ///< a0, rad: arccot 2, the cutting model's optimum
  // Struts (PUS): guide line, platform joints, length, carriage travel
  double strut_length = 0.73;
  double guide_y = 0.10;             ///< y of the carriages' hinge line
  double guide_z = -0.175;           ///< z of the hinge line (40 mm above the ways)
  double strut_joint_spread = 0.10;  ///< x half-distance of the two platform strut joints
  double strut_joint_y = 0.15;       ///< platform strut joints, platform frame y
  double strut_joint_z = -0.10;      ///< ... and z
  double carriage_min = -1.4;        ///< carriage travel along x (both carriages)
  double carriage_max = 1.4;
  double strut_max_angle = 70.0 * kDegToRad;  ///< max angle strut / guide (hinge limit)
  double strut_E = 2.1e11;                    ///< steel tubes
  double strut_area = 4.0e-4;                 ///< per rod (2 rods per pair)
  double carriage_stiffness = 1.5e8;          ///< carriage drive (ball screw), N/m
  /// The carriage's drive train in series with carriage_stiffness (free length at the carriage
  /// positions carriage_min and carriage_max); unset: none.
  ScrewDrive carriage_drive{};
  double strut_base_joint_stiffness = 0.0;      ///< carriage hinge, axial, per rod (N/m; 0 rigid)
  double strut_platform_joint_stiffness = 0.0;  ///< housing ball joint, axial, per rod (N/m)
  // Legs (UPS): overhead base joints, platform joints, length range
  double leg_base_x = 0.0;
  double leg_base_y = 0.10;
  double leg_base_z = 1.60;
  double leg_base_spacing = 0.40;   ///< y distance between the two base joints
  double leg_joint_spacing = 0.40;  ///< y distance between the two platform joints
  double leg_joint_z = 0.10;        ///< platform joints, platform frame z
  double leg_min_length = 1.235;
  double leg_max_length = 1.585;
  double leg_max_angle = 40.0 * kDegToRad;  ///< U joint at the beam, from -z
  double leg_E = 2.1e11;
  double leg_area = 1.5e-3;               ///< cylinder housing section
  double leg_actuator_stiffness = 1.0e8;  ///< screw and nut of the electro-cylinder, N/m
  /// The cylinders' drive train in series with leg_actuator_stiffness (free length at the leg
  /// lengths leg_min_length and leg_max_length); unset: none.
  ScrewDrive leg_drive{};
  double leg_base_joint_stiffness = 0.0;      ///< U joint at the beam, axial (N/m; 0 rigid)
  double leg_platform_joint_stiffness = 0.0;  ///< joint at the housing, axial (N/m)
  double actuator_error = 1e-5;               ///< m
  /// Turret housing with turret and tools, carriages and struts, cylinders and rods
  /// (models/dynamics/mass_model.hpp); `present` false: none.
  MassModel masses;
  LinkShapes shapes;  ///< interference check of struts and legs (LegChainDesign::shapes)
};

/// The leg-chain design (model name "lathe_16k20f3", mobility kSchoenflies, e = x). Throws
/// std::invalid_argument for impossible values (non-positive lengths, empty ranges).
LegChainDesign lathe_16k20f3_design(const Lathe16k20f3Design& d);
std::unique_ptr<Machine> make_lathe_16k20f3(const Lathe16k20f3Design& d);

/// The inputs of the conversion study's strut-length formula (m; see the header comment).
struct SeedsStrutInputs {
  double X_K = 0.0;    ///< strut offset along the guideway (x), hinge to platform joint
  double Y_D = 0.0;    ///< part axis y, from the carriage hinge line
  double Z_D = 0.0;    ///< part axis z, from the carriage hinge line
  double D_max = 0.0;  ///< largest part diameter
  double Y_xx = 0.0;   ///< tool-approach clearance along y
  double Z_xx = 0.0;   ///< ... along z
  double Y_I = 0.0;    ///< tool tip y, from the platform strut joint
  double Z_I = 0.0;    ///< tool tip z, from the platform strut joint
};
/// L = sqrt(X_K^2 + (Y_D + D_max/2 + Y_xx - Y_I)^2 + (Z_D + D_max/2 + Z_xx - Z_I)^2).
double seeds_strut_length(const SeedsStrutInputs& in);
/// The formula's inputs from a design (X_K left 0): Y_D = -guide_y, Z_D = -guide_z (the part axis
/// is the frame's x axis); the tool tip from the strut joint at phi = 0,
/// Y_I = -(tool_reach cos a0 + strut_joint_y), Z_I = -(tool_reach sin a0 + strut_joint_z); D_max
/// and the clearances as given (for a cross travel T instead of the largest part, Y_xx =
/// T - D_max / 2).
SeedsStrutInputs seeds_strut_inputs(const Lathe16k20f3Design& d, double D_max, double Y_xx,
                                    double Z_xx);
/// The formula with X_K from the strut's largest inclination to the guideway:
/// X_K = L cos(max_angle), so L = sqrt(dy^2 + dz^2) / sin(max_angle) (in.X_K is not read).
struct SeedsStrutLength {
  double length = 0.0;  ///< L (m)
  double X_K = 0.0;     ///< L cos(max_angle) (m)
};
SeedsStrutLength seeds_strut_length_at_inclination(const SeedsStrutInputs& in, double max_angle);

/// The task: the working tool's tip over a box of the lathe frame at phi = 0 (approach angle a0).
/// Defaults: x over the 1000 mm between centres, y over the promised 400 mm cross travel from the
/// spindle axis out, z from the axis up to the largest part's radius plus 20 mm clearance.
struct LatheTask {
  Eigen::Vector3d lower{-0.5, 0.0, 0.0};
  Eigen::Vector3d upper{0.5, 0.40, 0.18};
  Eigen::Vector3i counts{5, 5, 3};  ///< grid points per axis (>= 2 each; 1 = the lower value)
};
/// The grid of TCP poses (rotation I) of a task box.
std::vector<Pose> lathe_task_poses(const LatheTask& task);

/// Every pose reachable by the machine of `d`.
bool lathe_reaches(const Lathe16k20f3Design& d, const std::vector<Pose>& poses);

/// The shortest strut_length in [lower, upper] with which the machine reaches every pose, by
/// bisection to `tolerance` (m); nullopt when even `upper` does not reach them all. Returns the
/// upper end of the final bracket (so the returned length reaches the task).
std::optional<double> minimal_strut_length(Lathe16k20f3Design d, const std::vector<Pose>& poses,
                                           double lower, double upper, double tolerance);

}  // namespace pkmopt
