// Metrics shared by every design problem (problems/design/design_metrics.hpp): task_margin.
#include "problems/design/design_metrics.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "models/core/pose.hpp"
#include "models/serial/serial_machine.hpp"

namespace pkmopt {
namespace {

// The 5-axis machining centre 641236 (C, A table; X, Y, Z head; S spindle) with X, Y in
// [-0.4, 0.4] and Z in [-0.2, 0.5] m. With the tool vertical the table stays level (A = 0, C
// free) and the tool point is (X, Y, Z): only the linear travels limit the task.
SerialMachine table_machine() {
  SerialDesign d;
  d.chain = SerialChain::from_code("641236");
  d.spindle = 5;
  d.axes = {{.min = -2 * M_PI, .max = 2 * M_PI, .stiffness = 1e6},
            {.min = -120 * M_PI / 180, .max = 30 * M_PI / 180, .stiffness = 2e6},
            {.min = -0.4, .max = 0.4, .stiffness = 1.5e8},
            {.min = -0.4, .max = 0.4, .stiffness = 1.5e8},
            {.min = -0.2, .max = 0.5, .stiffness = 1.2e8}};
  d.characteristic_length = 0.2;
  return SerialMachine(d);
}

std::vector<Pose> box_poses(const Eigen::Vector3d& centre, const Eigen::Vector3d& half) {
  return box_task_poses(centre, half, {2, 2, 2}, 0.0, 0.0);
}

TEST(TaskMargin, LinearTravelsByHand) {
  const SerialMachine machine = table_machine();
  // A 0.2 x 0.2 x 0.1 m box centred at z = 0.1: x and y can grow by 0.4 - 0.1 = 0.3, z up by
  // 0.5 - 0.15 = 0.35 and down by 0.05 - (-0.2) = 0.25: the margin is 0.25 m.
  const std::vector<Pose> poses = box_poses({0, 0, 0.1}, {0.1, 0.1, 0.05});
  EXPECT_NEAR(task_margin(machine, poses, 1.0), 0.25, 1.0 / 65536 + 1e-12);
  // Moved 0.1 along x: x now limits, 0.4 - 0.2 = 0.2.
  EXPECT_NEAR(task_margin(machine, box_poses({0.1, 0, 0.1}, {0.1, 0.1, 0.05}), 1.0), 0.2,
              1.0 / 65536 + 1e-12);
  // A limit below the margin is returned as it is; a task beyond the travel has margin 0.
  EXPECT_EQ(task_margin(machine, poses, 0.1), 0.1);
  EXPECT_EQ(task_margin(machine, box_poses({0.35, 0, 0.1}, {0.1, 0.1, 0.05}), 1.0), 0.0);
  // A flat task (no extent along z) grows along x and y only: 0.3.
  EXPECT_NEAR(task_margin(machine, box_task_poses({0, 0, 0.1}, {0.1, 0.1, 0}, {2, 2, 1}, 0, 0), 1.0),
              0.3, 1.0 / 65536 + 1e-12);
  EXPECT_EQ(task_margin(machine, {}, 1.0), 0.0);
}

TEST(TaskMargin, LimitIsTheTasksLargestExtent) {
  EXPECT_DOUBLE_EQ(task_margin_limit(box_poses({0, 0, 1}, {0.15, 0.1, 0.05})), 0.3);
  EXPECT_DOUBLE_EQ(task_margin_limit(box_poses({0, 0, 1}, {0.01, 0.01, 0.01})), 0.1);
  EXPECT_DOUBLE_EQ(task_margin_limit({}), 0.1);
}

}  // namespace
}  // namespace pkmopt
