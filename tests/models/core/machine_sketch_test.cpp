// Tests of the machines' sketches (Machine::sketch, models/core/machine_sketch.hpp) on every
// example
// machine: the drawn legs are the legs of the kinematics. Checked against analyze at the same
// pose and against the geometry that must not change between poses:
//   * a leg drawn as one actuated line (UPS, the hexapod) is as long as analyze's q_i;
//   * a PUS leg's carriage (base point to carriage) is |q_i| long and lies on its guide, its strut
//     keeps its length from pose to pose;
//   * a RUS leg's crank and rod keep their lengths from pose to pose;
//   * the platform joints keep their distances from pose to pose (a rigid platform);
//   * the TCP drawn is the pose's TCP (machines that take the requested pose).
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <map>
#include <memory>
#include <string>

#include "io/machine/machine_file.hpp"
#include "models/core/machine.hpp"
#include "report/machine_drawing.hpp"

namespace pkmopt {
namespace {

std::unique_ptr<Machine> example(const std::string& name) {
  return load_machine_file((std::filesystem::path(PKMOPT_SOURCE_DIR) / "examples" / name).string());
}

double length(const MachineSketch::Line& l) { return (l.to - l.from).norm(); }

// The lines of each leg by part.
std::map<int, std::map<MachineSketch::Part, MachineSketch::Line>> legs_of(const MachineSketch& s) {
  std::map<int, std::map<MachineSketch::Part, MachineSketch::Line>> legs;
  for (const auto& l : s.lines)
    if (l.leg >= 0) legs[l.leg][l.part] = l;
  return legs;
}

class SketchOfEveryExample : public ::testing::TestWithParam<std::string> {};

TEST_P(SketchOfEveryExample, DrawsTheLegsOfTheKinematics) {
  const auto machine = example(GetParam());
  const auto home = drawing_pose(*machine);
  ASSERT_TRUE(home.has_value()) << GetParam();
  Pose moved = *home;
  moved.position += Eigen::Vector3d(0.01, -0.005, 0.01);
  moved.angles += Eigen::Vector3d(0.02, -0.01, 0.0);
  auto data = machine->make_data();
  if (!machine->reachable(*data, moved)) moved = *home;

  MachineSketch a, b;
  ASSERT_TRUE(machine->sketch(*machine->make_data(), *home, a)) << GetParam();
  ASSERT_TRUE(machine->sketch(*machine->make_data(), moved, b)) << GetParam();
  EXPECT_TRUE(a.reachable);
  const int n = machine->num_actuators();
  PoseMetrics metrics;
  machine->analyze(*data, *home, Wrench::Zero(), metrics);
  ASSERT_TRUE(metrics.reachable);

  const auto legs_a = legs_of(a), legs_b = legs_of(b);
  // Hybrid machines number their module's legs after the serial axes.
  const int first_leg = n - static_cast<int>(legs_a.size());
  ASSERT_GE(first_leg, 0);
  for (const auto& [leg, parts] : legs_a) {
    SCOPED_TRACE(GetParam() + ", leg " + std::to_string(leg));
    ASSERT_GE(leg, first_leg);
    ASSERT_LT(leg, n);
    const double q = metrics.q(leg);
    const auto& actuator = parts.at(MachineSketch::Part::kActuator);
    const auto& other = legs_b.at(leg);
    if (parts.count(MachineSketch::Part::kGuide)) {  // PUS
      EXPECT_NEAR(length(actuator), std::abs(q), 1e-9);
      const auto& guide = parts.at(MachineSketch::Part::kGuide);
      const Eigen::Vector3d u = (guide.to - guide.from).normalized();
      const Eigen::Vector3d off = actuator.to - guide.from;
      EXPECT_NEAR((off - off.dot(u) * u).norm(), 0.0, 1e-9) << "carriage off its guide";
      EXPECT_NEAR(length(parts.at(MachineSketch::Part::kLink)),
                  length(other.at(MachineSketch::Part::kLink)), 1e-9);
    } else if (parts.count(MachineSketch::Part::kLink)) {  // RUS
      EXPECT_NEAR(length(actuator), length(other.at(MachineSketch::Part::kActuator)), 1e-9);
      EXPECT_NEAR(length(parts.at(MachineSketch::Part::kLink)),
                  length(other.at(MachineSketch::Part::kLink)), 1e-9);
    } else {  // UPS, hexapod
      EXPECT_NEAR(length(actuator), q, 1e-9);
    }
    // Every leg ends at its platform joint.
    const auto& last =
        parts.count(MachineSketch::Part::kLink) ? parts.at(MachineSketch::Part::kLink) : actuator;
    EXPECT_NEAR((last.to - a.platform_joints.at(static_cast<std::size_t>(leg - first_leg))).norm(),
                0.0, 1e-9);
  }
  // A rigid platform.
  ASSERT_EQ(a.platform_joints.size(), b.platform_joints.size());
  for (std::size_t i = 0; i < a.platform_joints.size(); ++i)
    for (std::size_t j = i + 1; j < a.platform_joints.size(); ++j)
      EXPECT_NEAR((a.platform_joints[i] - a.platform_joints[j]).norm(),
                  (b.platform_joints[i] - b.platform_joints[j]).norm(), 1e-9);
  // The TCP where it was asked for (parasitic machines choose some coordinates themselves).
  if (GetParam() != "tripod_3prs.yaml" && GetParam() != "hybrid_gantry_3prs.yaml") {
    EXPECT_NEAR((a.tcp - home->position).norm(), 0.0, 1e-9);
  }
}

INSTANTIATE_TEST_SUITE_P(Examples, SketchOfEveryExample,
                         ::testing::Values("hexapod.yaml", "hexapod_legs.yaml", "delta.yaml",
                                           "linear_delta.yaml", "hexaglide.yaml",
                                           "tripod_3prs.yaml", "schoenflies_4pus.yaml",
                                           "hybrid_long_axis_hexapod.yaml",
                                           "hybrid_gantry_3prs.yaml"));

TEST(MachineSketch, APoseOutOfReachIsDrawnAndSaidSo) {
  const auto machine = example("hexapod.yaml");
  MachineSketch s;
  // 2 m above the base: every leg beyond its 1.15 m maximum, drawn anyway.
  ASSERT_TRUE(machine->sketch(*machine->make_data(), Pose{{0, 0, 2.0}, {0, 0, 0}}, s));
  EXPECT_FALSE(s.reachable);
  EXPECT_EQ(s.base_joints.size(), 6u);
  EXPECT_EQ(s.platform_joints.size(), 6u);
  EXPECT_FALSE(machine->sketch(*machine->make_data(), Pose{{0, 0, NAN}, {0, 0, 0}}, s));
}

}  // namespace
}  // namespace pkmopt
