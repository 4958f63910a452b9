// The files of `pkmopt trajectory`: the path it reads, the sample table, the singular poses and
// the summary text.
//
//   read_path_csv        a path file (io/format/pose_csv.hpp): t (s, strictly increasing), x,y,z
//   (m),
//                        optional rx,ry,rz (deg); at least 2 rows; InputError naming file, line
//                        and column otherwise.
//   trajectory_csv       one row per sample:
//                          t (s), x,y,z (m), rx,ry,rz (deg), vx,vy,vz (m/s), wx,wy,wz (deg/s,
//                          angular velocity in base axes), ax,ay,az (m/s^2), alpha_x,alpha_y,
//                          alpha_z (deg/s^2, angular acceleration), reachable, singular (0/1),
//                          q_1..q_n, q_dot_1..q_dot_n, q_dot_fd_1..q_dot_fd_n, tau_1..tau_n
//                          (N or N*m, under the wrench), with masses tau_dyn_1..tau_dyn_n
//                          (wrench, gravity and inertia), singularity_margin, det_j
//                          [,leg_clearance,clearance_pair with a leg shape]
//                          [,mode_distance (m),real_modes,failed_paths with `modes`]
//                        and, with `jacobian`, J_r_c (r = 1..n, c = 1..6; SI units, +inf where
//                        the Jacobian failed). q in m and m/s for prismatic actuators, deg and
//                        deg/s for revolute ones.
//   singular_poses_csv   t,x,y,z,rx,ry,rz,kind,singularity_margin,det_j_before,det_j_after with
//                        kind `sample` or `det_j_sign_change` (units as above).
//   trajectory_summary_text  the lines `pkmopt trajectory` prints: sample count, time span,
//                        reachable samples, min singularity_margin; per actuator the range of q
//                        and the max |q_dot|; the max |q_dot - q_dot_fd| over interior samples;
//                        every singular pose; the TCP's peak speed and acceleration; per
//                        actuator the peak |tau| and, with masses, the peak and RMS tau_dyn
//                        and the peak power.
//   drive_check_text     whether a catalog entry carries every actuator along the path.
//   assembly_modes_text  the nearest other assembly mode along the path, and warnings where it
//                        comes nearer than a threshold or where paths failed.
// Numbers in the CSVs in the shortest text that reads back to the same double (format_number);
// docs/trajectory.md describes every column.
//
// Example:
//   const TrajectoryResult run = evaluate_trajectory(machine, helix, times);
//   write_file_atomically("path.csv", trajectory_csv(machine, run, /*jacobian=*/false));
//   std::cout << trajectory_summary_text(machine, run,
//                                        summarize_trajectory(run, machine.num_actuators()));
#pragma once

#include <string>

#include "models/core/machine.hpp"
#include "models/motion/trajectory.hpp"
#include "models/motion/trajectory_modes.hpp"
#include "problems/design/actuator_catalog.hpp"

namespace pkmopt {

/// The path of a path file, linearly interpolated between its samples.
SampledPath read_path_csv(const std::string& path);

/// The sample table (header and one row per sample of `result`).
std::string trajectory_csv(const Machine& machine, const TrajectoryResult& result, bool jacobian,
                           const TrajectoryModes* modes = nullptr);

/// The singular poses of `result` (header and one row per pose).
std::string singular_poses_csv(const TrajectoryResult& result);

/// The summary text, every line ending in a newline; `summary` is summarize_trajectory(result).
/// The time span is that of the first and last sample (result.samples must not be empty).
std::string trajectory_summary_text(const Machine& machine, const TrajectoryResult& result,
                                    const TrajectorySummary& summary);

/// The duty of actuator i along the path (summarize_trajectory): the peak and RMS of tau_dyn
/// (of tau when the machine has no masses), the peak |q_dot| and the span of q.
DriveDuty actuator_duty(const TrajectorySummary& summary, int i);

/// The lines saying, per actuator, whether `entry` carries its duty (peak force, RMS force,
/// speed, stroke; problems/design/actuator_catalog.hpp), and a last verdict line. `carries` is set
/// to whether it carries every actuator. For machines with linear actuators.
std::string drive_check_text(const ActuatorEntry& entry, const TrajectorySummary& summary,
                             bool& carries);

/// The summary lines of the assembly modes along `result` (`modes` of the same samples): the
/// smallest distance to another mode and where, the range of the real mode count, and a
/// "warning:" line each for samples nearer than `warn_below` (m), for samples where the tracked
/// pose was not found and for samples where paths failed.
std::string assembly_modes_text(const TrajectoryResult& result, const TrajectoryModes& modes,
                                double warn_below);

}  // namespace pkmopt
