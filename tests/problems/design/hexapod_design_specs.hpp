// A hexapod design spec shared by the tests of problems/design/hexapod_design: a 2x2x2 box task
// with a 15 deg tilt cone and a milling load, seven free parameters, in the smooth formulation.
#pragma once

#include "problems/design/hexapod_design.hpp"

namespace pkmopt::test_specs {

inline HexapodDesignSpec smooth_spec() {
  HexapodDesignSpec spec;
  spec.formulation = DesignFormulation::smooth;
  spec.task.poses = box_task_poses({0.02, -0.01, 0.9}, {0.1, 0.1, 0.05}, {2, 2, 2}, deg_to_rad(15),
                                   deg_to_rad(10), deg_to_rad(15));
  spec.task.wrench << 300, -200, -4000, 15, -25, 10;
  spec.parameters[kBaseRadius] = {0.5, 0.7};
  spec.parameters[kPlatformRadius] = {0.2, 0.3};
  spec.parameters[kBasePairSeparation] = {deg_to_rad(10), deg_to_rad(40)};
  spec.parameters[kPlatformPairSeparation] = {deg_to_rad(10), deg_to_rad(40)};
  spec.parameters[kMinLength] = {0.6, 0.8};
  spec.parameters[kStroke] = {0.3, 0.6};
  spec.parameters[kHomeHeight] = {-0.1, 0.1};
  spec.objectives = {{DesignMetric::leg_force_max, Sense::minimize},
                     {DesignMetric::machine_size, Sense::maximize}};
  spec.constraints = {{DesignMetric::leg_force_max, Relation::less_equal, 5000.0},
                      {DesignMetric::machine_size, Relation::greater_equal, 0.5}};
  return spec;
}

}  // namespace pkmopt::test_specs
