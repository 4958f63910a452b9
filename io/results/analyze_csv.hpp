// The output CSV of `pkmopt analyze`: one row per pose, the columns of docs/conventions.md.
//
//   x,y,z,rx,ry,rz,reachable,q_1..q_n,tau_1..tau_n,stiffness_min,singularity_margin,det_j,
//   tcp_error_max,tcp_deflection,tcp_rotation_deflection_deg,stiffness_min_loaded,
//   stiffness_dir_x,stiffness_dir_y,stiffness_dir_z[,leg_clearance,clearance_pair]
//   [,natural_frequency_1..n]
//   [,mode_k_axis_1..mode_k_axis_s,mode_k_dx,mode_k_dy,mode_k_dz,mode_k_drx,mode_k_dry,mode_k_drz
//   for k = 1..n][,C_11..C_66], then every other column of the pose file, unchanged.
// q_i in m for prismatic actuators and degrees for revolute ones; tau_i in N or N·m;
// tcp_deflection in m and tcp_rotation_deflection_deg in degrees under the analysed wrench;
// stiffness_min_loaded in N/m; stiffness_dir the unit force direction of stiffness_min;
// leg_clearance in m and clearance_pair ("3-4", the closest legs) when the machine file gives the
// legs' shape; natural_frequency_j in Hz, ascending, when the machine has a mass model; C_ab the
// compliance (row a, column b; m/N, m/(N·m), rad/N, rad/(N·m)) with `compliance`; mode_k_* the
// mass-normalised shape of mode k with `modes` (PoseModes: the serial axes of a hybrid machine in
// m, the TCP displacement in m and the platform rotation in rad, base axes; 0 where a pose has no
// modes). Numbers in the
// shortest text that reads back to the same double (format_number).
//
// Example:
//   const PoseTable poses = read_pose_csv("poses.csv");
//   const auto metrics = analyze_poses(machine, poses.poses, Wrench::Zero());
//   write_file_atomically("out.csv", analyze_csv(machine, poses, metrics));
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "io/format/pose_csv.hpp"
#include "models/core/capabilities.hpp"
#include "models/core/machine.hpp"

namespace pkmopt {

struct AnalyzeCsvOptions {
  /// When given (one per pose): add the 36 columns C_11..C_66 of each pose's compliance matrix.
  const std::vector<PoseCompliance>* compliance = nullptr;
  /// When given (one per pose, Machine::mode_shapes): after the natural frequencies, the mode
  /// shape columns of every mode k (k = 1..natural_frequency_count).
  const std::vector<PoseModes>* modes = nullptr;
};

/// The numeric columns of analyze_csv after x..rz, in file order: reachable (1 or 0), q_1..q_n,
/// tau_1..tau_n, ... (clearance_pair, a text column written after leg_clearance, is not one of
/// them). `modes` and `compliance` add the mode-shape and C_ab columns.
std::vector<std::string> analyze_value_columns(const Machine& machine, bool modes, bool compliance);

/// The values of one pose in the order of analyze_value_columns (out holds as many), in the
/// units of the CSV (q of revolute actuators and tcp_rotation_deflection_deg in degrees): the
/// numbers analyze_csv writes. `modes` / `compliance` may be null when those columns are not
/// asked for.
void analyze_values(const Machine& machine, const PoseMetrics& metrics, const PoseModes* modes,
                    const PoseCompliance* compliance, double* out);

/// The whole CSV text (header and one row per pose; `metrics[i]` belongs to `poses.poses[i]`).
std::string analyze_csv(const Machine& machine, const PoseTable& poses,
                        const std::vector<PoseMetrics>& metrics,
                        const AnalyzeCsvOptions& options = {});

/// The header line of analyze_csv (with its newline).
std::string analyze_csv_header(const Machine& machine, const PoseTable& poses,
                               const AnalyzeCsvOptions& options = {});

/// The row of pose `row` of `poses` (with its newline) from its metrics and, when the options ask
/// for them, its modes and compliance (`modes` / `compliance` may then not be null).
std::string analyze_csv_row(const Machine& machine, const PoseTable& poses, std::size_t row,
                            const PoseMetrics& metrics, const PoseModes* modes,
                            const PoseCompliance* compliance);

}  // namespace pkmopt
