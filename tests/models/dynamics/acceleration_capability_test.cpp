// Tests of models/dynamics/acceleration_capability: the bound is the exact maximum over the ball
// |a| <= a_max of the forces the inverse dynamics gives (Machine::dynamic_wrench with the TCP at
// rest and accelerating by a, then the static solve) — the maximiser built from the forces of
// the three unit accelerations, and no sampled direction beyond it — on random hexapods and a
// linear delta; no masses or a singular pose give false; the compliance flag is restored.
#include "models/dynamics/acceleration_capability.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "io/machine/machine_file.hpp"
#include "models/hexapod/hexapod.hpp"
#include "models/leg_chain/leg_chain.hpp"
#include "tests/sample_machines.hpp"

namespace pkmopt {
namespace {

using sample_machines::Uniform;

std::string source_path(const std::string& relative) {
  return std::string(PKMOPT_SOURCE_DIR) + "/" + relative;
}

// The actuator forces with the TCP at rest accelerating by a (no angular acceleration).
Eigen::VectorXd accelerated_forces(const Machine& machine, MachineData& data, const Pose& pose,
                                   const Wrench& wrench, const Eigen::Vector3d& a) {
  Vector6d xi_dot = Vector6d::Zero();
  xi_dot.head<3>() = a;
  Wrench w_dyn;
  EXPECT_TRUE(machine.dynamics());
  if (!machine.dynamics()) return Eigen::VectorXd();
  EXPECT_TRUE(machine.dynamics()->dynamic_wrench(data, pose, Vector6d::Zero(), xi_dot, w_dyn));
  PoseMetrics m;
  machine.analyze(data, pose, wrench + w_dyn, m);
  return m.tau;
}

// For each actuator, its worst acceleration a_max G_i/|G_i| (signed to add to the static force)
// reaches the bound, and 400 directions on the sphere stay within it.
void expect_exact_bound(const Machine& machine, const Pose& pose, const Wrench& wrench,
                        double a_max, Uniform& u) {
  const auto data = machine.make_data();
  Eigen::VectorXd bound;
  ASSERT_TRUE(acceleration_force_bound(machine, *data, pose, wrench, a_max, bound));
  const Eigen::VectorXd tau0 = accelerated_forces(machine, *data, pose, wrench, {0, 0, 0});
  Eigen::MatrixXd G(tau0.size(), 3);  // d tau / d a, by linearity (exact up to rounding)
  for (int k = 0; k < 3; ++k) {
    G.col(k) = accelerated_forces(machine, *data, pose, wrench, Eigen::Vector3d::Unit(k)) - tau0;
  }
  for (Eigen::Index i = 0; i < tau0.size(); ++i) {
    const Eigen::Vector3d g = G.row(i).transpose();
    const Eigen::Vector3d worst = a_max * g.normalized() * (tau0(i) >= 0 ? 1.0 : -1.0);
    const double reached = std::abs(accelerated_forces(machine, *data, pose, wrench, worst)(i));
    EXPECT_NEAR(reached, bound(i), 1e-9 * bound(i)) << "actuator " << i;
  }
  for (int k = 0; k < 400; ++k) {
    const Eigen::Vector3d a =
        a_max * Eigen::Vector3d(u(-1, 1), u(-1, 1), u(-1, 1)).normalized() * u(0.5, 1.0);
    const Eigen::VectorXd tau = accelerated_forces(machine, *data, pose, wrench, a);
    EXPECT_TRUE((tau.cwiseAbs().array() <= bound.array() * (1 + 1e-12)).all()) << k;
  }
}

TEST(AccelerationCapability, BoundIsTheExactWorstCaseForRandomHexapods) {
  Uniform u(91);
  for (int g = 0; g < 5; ++g) {
    HexapodDesign design = sample_machines::random_hexapod_design(u);
    design.masses = sample_machines::random_hexapod_masses(u);
    const Hexapod hexapod(design);
    const Wrench w =
        (Wrench() << u(-800, 800), u(-800, 800), u(-800, 800), u(-60, 60), u(-60, 60), u(-60, 60))
            .finished();
    expect_exact_bound(hexapod, sample_machines::random_pose(u), w, u(5, 20), u);
  }
}

TEST(AccelerationCapability, BoundIsTheExactWorstCaseForALinearDelta) {
  const auto machine = load_machine_file(source_path("examples/linear_delta.yaml"));
  LegChainDesign design = dynamic_cast<const LegChainMachine&>(*machine).design();
  sample_machines::add_linear_delta_masses(design);
  const LegChainMachine delta(design);
  Uniform u(92);
  expect_exact_bound(delta, design.home, (Wrench() << 40, -70, 120, 0, 0, 0).finished(), 19.6, u);
}

TEST(AccelerationCapability, NoMassesOrASingularPoseGiveFalse) {
  HexapodDesign design = sample_machines::conventions_hexapod_design();
  const Hexapod bare(design);
  const auto data = bare.make_data();
  Eigen::VectorXd bound;
  const Pose home{{0, 0, 0.9}, {0, 0, 0}};
  EXPECT_FALSE(acceleration_force_bound(bare, *data, home, Wrench::Zero(), 9.81, bound));
  Uniform u(93);
  design.masses = sample_machines::random_hexapod_masses(u);
  const Hexapod heavy(design);
  const auto heavy_data = heavy.make_data();
  heavy_data->compliance_metrics = true;
  EXPECT_TRUE(acceleration_force_bound(heavy, *heavy_data, home, Wrench::Zero(), 9.81, bound));
  EXPECT_TRUE(heavy_data->compliance_metrics);
  // Fichter's singularity: the platform turned by 90 degrees about z at the central position.
  const Pose turned{{0, 0, 0.9}, {0, 0, deg_to_rad(90.0)}};
  PoseMetrics m;
  heavy.analyze(*heavy_data, turned, Wrench::Zero(), m);
  ASSERT_TRUE(m.singular);
  EXPECT_FALSE(acceleration_force_bound(heavy, *heavy_data, turned, Wrench::Zero(), 9.81, bound));
}

}  // namespace
}  // namespace pkmopt
