// The `wrench:` of a study's task: typed by hand, or from a cutting model
// (problems/design/cutting_load).
//
//   wrench: [fx, fy, fz, mx, my, mz]          # N and N*m at the TCP, base axes
//   wrench:
//     turning: {diameter_mm: 120, depth_mm: 3, feed_mm_per_rev: 0.84, tool_life_min: 60,
//               C_v: 340, x_v: 0.15, y_v: 0.45, m: 0.2, K_v: 0.85,
//               C_p: 200, x_p: 1, y_p: 0.75, n_p: 0, K_p: 1.127,
//               radial_ratio: 0.5, axial_ratio: 0.2}        # the last two optional
//     approach_angle_deg: 26.57               # or `optimal` (atan(P_y / P_z)); default 0
//     rotation_deg: [rx, ry, rz]              # lathe frame -> base frame, R = Rz Ry Rx; default 0
//   wrench:
//     milling: {cutter_diameter_mm: 63, teeth: 5, cutting_speed: 220, feed_per_tooth_mm: 0.15,
//               width_mm: 40, depth_mm: 3, lead_angle_deg: 90, k_c1: 1700, m_c: 0.25,
//               radial_ratio: 0.3, axial_ratio: 0.2}        # lead angle, m_c, ratios optional
//     feed_direction: [1, 0, 0]               # base x-y plane; default [1, 0, 0]
//     factor: 1.8                              # optional, both models: a design factor (wear,
//                                              # interrupted cut) multiplying the wrench
//
// The turning force on the tool is Rot(rotation) Rx(approach) (P_x, P_y, P_z) (see
// problems/design/cutting_load.hpp for the lathe frame), with zero moments at the TCP; the milling
// force -F_t f + F_r (e_z x f) + F_a e_z with the cutting torque -F_t D_c / 2 e_z.
// Errors: InputError with file, line, column and key.
#pragma once

#include <string>
#include <string_view>

#include "io/format/yaml_reader.hpp"
#include "models/core/pose.hpp"

namespace pkmopt {

/// The task wrench and, for a cutting model, a one-line description of how it was obtained
/// ("turning: V 116.88 m/min, n 310 rev/min, P_z 5933 N, approach 26.57 deg").
struct TaskWrench {
  Wrench wrench = Wrench::Zero();
  std::string origin;  ///< empty for a hand-typed wrench
};

TaskWrench read_task_wrench(const YamlValue& value);

/// The docs table of a cutting model's keys ("turning" or "milling"), from the same field list
/// the reader uses.
std::string cutting_model_fields_markdown(std::string_view model);

}  // namespace pkmopt
