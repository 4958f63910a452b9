// Tests of problems/design/lathe_design: the 16K20F3 conversion's design family (parameters,
// builder, machine_size = L^3, machine-file writer) inside the generic machine design problem.
#include "problems/design/lathe_design.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "io/format/yaml_reader.hpp"
#include "io/machine/machine_file_lathe.hpp"
#include "io/machine/machine_file_lathe.hpp"

namespace pkmopt {
namespace {

TEST(LatheDesign, FamilyParametersAndBuilder) {
  const Lathe16k20f3Design t;
  const DesignFamily family = lathe_16k20f3_family(t);
  EXPECT_EQ(family.model, "lathe_16k20f3");
  EXPECT_FALSE(family.translational);
  ASSERT_EQ(family.parameters.size(), 4u);
  EXPECT_EQ(family.index_of("strut_length"), 0);
  EXPECT_EQ(family.index_of("guide_y"), 1);
  EXPECT_EQ(family.index_of("leg_base_y"), 2);
  EXPECT_EQ(family.index_of("home_height"), 3);
  const std::vector<double> p = {0.65, 0.18, -0.05, 0.0};
  const auto machine = family.build(p);
  Lathe16k20f3Design expected = t;
  expected.strut_length = 0.65;
  expected.guide_y = 0.18;
  expected.leg_base_y = -0.05;
  const auto reference = make_lathe_16k20f3(expected);
  // Same machine: same actuator coordinates at a task pose.
  const Pose pose{{0.2, 0.3, 0.1}, Eigen::Vector3d::Zero()};
  PoseMetrics a, b;
  auto da = machine->make_data();
  auto db = reference->make_data();
  machine->analyze(*da, pose, Wrench::Zero(), a);
  reference->analyze(*db, pose, Wrench::Zero(), b);
  EXPECT_EQ(a.q, b.q);
  // machine_size is the cube of the strut length.
  EXPECT_DOUBLE_EQ(family.machine_size(*machine, p), 0.65 * 0.65 * 0.65);
  // The machine file loads back to the same design.
  const Lathe16k20f3Design read = read_lathe_16k20f3_design(YamlValue::load_string(
      lathe_16k20f3_family(t, lathe_16k20f3_machine_file).machine_file(p), "family.yaml"));
  EXPECT_EQ(lathe_16k20f3_machine_file(read), lathe_16k20f3_machine_file(expected));
}

TEST(LatheDesign, ReachabilityRowFollowsTheStrutLength) {
  MachineDesignSpec spec;
  spec.family = lathe_16k20f3_family(Lathe16k20f3Design{});
  spec.parameters = default_ranges(spec.family);
  spec.parameters[0] = {0.45, 0.80};
  // The study's task box (tool tip over x -0.5..0.5, y 0..0.4, z 0..0.18).
  spec.task.poses = box_task_poses({0.0, 0.2, 0.09}, {0.5, 0.2, 0.09}, {3, 3, 3}, 0.0, 0.0);
  spec.task.wrench << 1186.63, 0.0, 6633.45, 0.0, 0.0, 0.0;
  spec.objectives = {{DesignMetric::machine_size, Sense::minimize},
                     {DesignMetric::stiffness_min, Sense::maximize}};
  spec.constraints = {{DesignMetric::leg_force_max, Relation::less_equal, 17000.0}};
  const MachineDesignProblem problem(spec);
  const MachineDesignEvaluation design = problem.evaluate({0.73});
  ASSERT_TRUE(design.ok()) << design.failure;
  EXPECT_TRUE(design.reachable);
  EXPECT_NEAR(design.metrics[static_cast<int>(DesignMetric::machine_size)], 0.73 * 0.73 * 0.73,
              1e-15);
  EXPECT_LT(design.metrics[static_cast<int>(DesignMetric::leg_force_max)], 17000.0);
  const MachineDesignEvaluation short_struts = problem.evaluate({0.60});
  ASSERT_TRUE(short_struts.ok()) << short_struts.failure;
  EXPECT_FALSE(short_struts.reachable);
  EXPECT_GT(short_struts.reach_violation, 0.0);
}

}  // namespace
}  // namespace pkmopt
