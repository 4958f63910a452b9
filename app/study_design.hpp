// Design study files for `pkmopt run`: a machine with free parameters, a task, objectives,
// constraints, an optimizer and output options -> a HexapodDesignProblem, its Pareto front and
// the result folder. A study file is a design study when it has a `machine:` key.
//
//   study: hexapod-quick                      # name, required
//   description: "..."                        # optional
//   machine:
//     model: hexapod                          # only hexapod so far
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
//   task:
//     region: {shape: box, centre: [0, 0, 0.9], size: [0.3, 0.3, 0.2], points: [3, 3, 3]}
//          #  {shape: cylinder, centre: [...], radius: r, height: h, rings: 2, per_ring: 6,
//          #   layers: 3}
//     orientations: {tilt_deg: 20, yaw_deg: 0, step_deg: 10}         # optional
//     wrench: [fx, fy, fz, mx, my, mz]                                # N, N*m; optional
//     workspace: {resolution: 0.05, tilt_deg: 0, yaw_deg: 0, step_deg: 5}  # optional
//   objectives:                               # list, at least one
//     - maximize: stiffness_min
//     - minimize: machine_size
//   constraints:                              # optional list
//     - {metric: leg_force_max, max: 10500}   # metric <= 10500
//     - {metric: singularity_margin, min: 0.05}
//     - task_reachable
//   optimizer: {algorithm: nsga2, population: 24, generations: 20, seed: 1}
//   output: {designs: true}                   # optional: write designs/<id>.yaml
//
// nsga2 uses the aggregate (derivative-free) formulation; every other algorithm the smooth one
// (see problems/hexapod_design.hpp).
//
// Outputs in DIR: pareto.csv (id, free parameters in file units, objectives in user sign and
// units, constraint values, feasible, failure), summary.json (as for benchmark studies, with
// objective names), designs/<id>.yaml (machine files for `pkmopt analyze`).
#pragma once

#include <memory>
#include <string>

#include "app/study_benchmark.hpp"
#include "problems/hexapod_design.hpp"

namespace pkmopt {

struct DesignStudy {
  std::string name;
  std::unique_ptr<HexapodDesignProblem> problem;
  OptimizerSpec optimizer;
  bool write_designs = true;
};

/// True when the file's root map has a `machine:` key (throws InputError for a bad file).
bool is_design_study_file(const std::string& path);

/// Loads and validates a design study (throws InputError naming file, line, column and key).
DesignStudy load_design_study(const std::string& path);

/// Writes pareto.csv, summary.json and designs/<id>.yaml into `directory`.
void write_design_outputs(const std::string& directory, const DesignStudy& study,
                          const RunOutcome& outcome, int threads);

}  // namespace pkmopt
