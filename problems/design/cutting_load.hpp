// Cutting loads: the task wrench of a machining study from cutting conditions instead of a
// hand-typed force.
//
// Turning (the empirical model of the Russian machining handbooks, used by the lathe study):
//   cutting speed     V   = C_v / (T^m * t^x * s^y) * K_v                  m/min
//   spindle speed     n   = 1000 V / (pi D)                                rev/min
//   tangential force  P_z = 10 * C_p * t^x_p * s^y_p * V^n_p * K_p        N
//   radial force      P_y = radial_ratio * P_z   (about 0.5)               N
//   axial force       P_x = axial_ratio * P_z    (about 0.2)               N
// with t the depth of cut (mm), s the feed (mm/rev), T the tool life (min), D the workpiece
// diameter (mm). The force on the tool is (P_x, P_y, P_z) in the tool frame: x along the
// spindle axis against the feed, y radially outward from the spindle axis through the tool
// tip, z along the workpiece surface velocity at the tip (a right-handed frame for a spindle
// turning positively about +x). A cutter mounted at approach angle alpha, i.e. the tool turned
// by alpha about the spindle axis x, loads the machine (frame of alpha = 0) with
//   F_machine = Rx(alpha) (P_x, P_y, P_z) = (P_x, P_y cos a - P_z sin a, P_y sin a + P_z cos a).
// The machine-z component P_z cos a + P_y sin a is largest, sqrt(P_y^2 + P_z^2), at
// tan a = P_y / P_z (a = arccot 2 for P_y = P_z / 2); there the whole in-plane force lies along
// the machine's z axis and the y component vanishes (`optimal_approach_angle`).
// Example (the lathe-conversion study's cut: steel, D 120 mm, t 3 mm, s 0.84 mm/rev, T 60 min):
//   V = 116.88 m/min, n = 310 rev/min, P_z = 5933 N; at a = 26.57 deg the z force is 6633 N.
//
// Milling (specific cutting force after Kienzle, as in tool makers' handbooks, with the
// geometric mean chip thickness of Altintas, "Manufacturing Automation", ch. 2): a cutter of
// diameter D_c (mm) with z_n teeth, cutting speed v_c (m/min), feed per tooth f_z (mm), radial
// width a_e (mm, engaged from one side), axial depth a_p (mm), entering angle kappa_r:
//   spindle speed        n   = 1000 v_c / (pi D_c)                           rev/min
//   table feed           v_f = f_z z_n n                                     mm/min
//   engagement angle     phi_e = arccos(1 - 2 a_e / D_c)                     rad
//   mean chip thickness  h_m = f_z sin(kappa_r) (1 - cos phi_e) / phi_e      mm
//                        (the mean of f_z sin(kappa_r) sin(phi) over 0..phi_e)
//   specific force       k_c = k_c1 h_m^(-m_c)                               N/mm^2
//   net power            P_c = a_p a_e v_f k_c / (60 * 10^6)                 kW
//   mean tangential force F_t = 60000 P_c / v_c                              N
//                        (the tangential force at the cutter rim that needs P_c)
//   F_r = radial_ratio F_t, F_a = axial_ratio F_t                            N
//   spindle torque       M_c = F_t D_c / 2000                                N*m
// The milling wrench on the tool (base axes, at the TCP, tool axis along base z, feed along
// the unit vector f in the base x-y plane): F = -F_t f + F_r (e_z x f) + F_a e_z, and the
// cutting torque reacted by the spindle housing on the platform, M = -M_c e_z (spindle turning
// positively about +z; the cut resists the rotation).
// (A representative mean load: the tangential force resists the feed, the radial force acts
// across it, the axial force pushes the tool back along its axis.)
#pragma once

#include <Eigen/Core>
#include <string>

#include "models/core/pose.hpp"

namespace pkmopt {

/// Conditions and coefficients of the empirical turning model (units as in the formulas).
struct TurningConditions {
  double diameter_mm = 0.0;      ///< D, workpiece diameter
  double depth_mm = 0.0;         ///< t, depth of cut
  double feed_mm_per_rev = 0.0;  ///< s
  double tool_life_min = 60.0;   ///< T
  double C_v = 0.0;              ///< speed coefficient
  double x_v = 0.0;              ///< exponent of t in V
  double y_v = 0.0;              ///< exponent of s in V
  double m = 0.0;                ///< exponent of T in V
  double K_v = 1.0;              ///< speed correction factor
  double C_p = 0.0;              ///< force coefficient
  double x_p = 1.0;              ///< exponent of t in P_z
  double y_p = 0.75;             ///< exponent of s in P_z
  double n_p = 0.0;              ///< exponent of V in P_z
  double K_p = 1.0;              ///< force correction factor (product of the handbook factors)
  double radial_ratio = 0.5;     ///< P_y / P_z
  double axial_ratio = 0.2;      ///< P_x / P_z
};

/// Result of the turning model.
struct TurningLoad {
  double cutting_speed = 0.0;  ///< V, m/min
  double spindle_speed = 0.0;  ///< n, rev/min
  double tangential = 0.0;     ///< P_z, N
  double radial = 0.0;         ///< P_y, N
  double axial = 0.0;          ///< P_x, N
  /// (P_x, P_y, P_z) in the tool frame, N.
  Eigen::Vector3d tool_frame_force() const { return {axial, radial, tangential}; }
};

/// Empty when the conditions are usable; otherwise what is wrong (name, value, expected).
std::string check_turning_conditions(const TurningConditions& c);

/// The turning model. Throws std::invalid_argument for conditions check_turning_conditions
/// rejects.
TurningLoad turning_load(const TurningConditions& c);

/// Rx(alpha) * force: the tool-frame force seen in the machine frame for approach angle alpha
/// (rad) about the spindle axis x.
Eigen::Vector3d turning_machine_force(const TurningLoad& load, double approach_angle);

/// The approach angle (rad) at which the machine-z force is largest: atan2(P_y, P_z).
double optimal_approach_angle(const TurningLoad& load);

/// Conditions of the milling model (units as in the formulas).
struct MillingConditions {
  double cutter_diameter_mm = 0.0;  ///< D_c
  int teeth = 0;                    ///< z_n
  double cutting_speed = 0.0;       ///< v_c, m/min
  double feed_per_tooth_mm = 0.0;   ///< f_z
  double width_mm = 0.0;            ///< a_e, radial engagement (<= D_c)
  double depth_mm = 0.0;            ///< a_p, axial depth
  double lead_angle_deg = 90.0;     ///< kappa_r (90 for a square shoulder cutter)
  double k_c1 = 0.0;                ///< specific cutting force at h = 1 mm, N/mm^2
  double m_c = 0.25;                ///< rise of the specific cutting force
  double radial_ratio = 0.3;        ///< F_r / F_t
  double axial_ratio = 0.2;         ///< F_a / F_t
};

struct MillingLoad {
  double spindle_speed = 0.0;        ///< n, rev/min
  double table_feed = 0.0;           ///< v_f, mm/min
  double mean_chip_thickness = 0.0;  ///< h_m, mm
  double specific_force = 0.0;       ///< k_c, N/mm^2
  double power_kw = 0.0;             ///< P_c, kW
  double tangential = 0.0;           ///< F_t, N
  double radial = 0.0;               ///< F_r, N
  double axial = 0.0;                ///< F_a, N
  double spindle_torque = 0.0;       ///< M_c, N*m
};

/// Empty when the conditions are usable; otherwise what is wrong.
std::string check_milling_conditions(const MillingConditions& c);

/// The milling model. Throws std::invalid_argument for rejected conditions.
MillingLoad milling_load(const MillingConditions& c);

/// The wrench on the tool at the TCP (base axes) for a cut fed along `feed_direction` (any
/// non-zero vector in the base x-y plane; normalised here), tool axis along base z:
/// F = -F_t f + F_r (e_z x f) + F_a e_z, moment -M_c e_z. Throws std::invalid_argument for a
/// feed direction that is zero, non-finite or not in the x-y plane.
Wrench milling_wrench(const MillingLoad& load, const Eigen::Vector3d& feed_direction);

}  // namespace pkmopt
