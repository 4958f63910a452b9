// Tests of problems/design/leg_chain_design: each family's machine_size is the envelope its header
// documents (computed here from the formulas), the template comes back as the defaults, and the
// parameters set what they name. The families' machine files are tested in
// tests/io/machine/machine_file_leg_chain_test.cpp; the problem built on a family in
// machine_design_test.cpp.
#include "problems/design/leg_chain_design.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include "models/core/pose.hpp"
#include "models/geometry/joint_layout.hpp"

namespace pkmopt {
namespace {

TEST(LegChainDesign, MachineSizeIsTheDocumentedEnvelopeOfEachFamily) {
  const double pi = std::numbers::pi;
  {  // linear delta: pi rho^2 (s cos i + l), rho = max(r_g, |r_g - s sin i|)
    const DesignFamily family = linear_delta_family(LinearDeltaDesign{});
    for (double inclination_deg : {0.0, 25.0, -15.0}) {
      const double r = 0.4, rod = 0.8, s = 0.7, i = deg_to_rad(inclination_deg);
      const std::vector<double> p = {r, 0.05, rod, s, i, 0.0};
      const double rho = std::max(r, std::abs(r - s * std::sin(i)));
      EXPECT_NEAR(family.machine_size(*family.build(p), p),
                  pi * rho * rho * (s * std::cos(i) + rod), 1e-12)
          << inclination_deg;
    }
  }
  {  // delta: pi (r_b + r_a)^2 (2 r_a + l)
    const DesignFamily family = delta_family(DeltaDesign{});
    const std::vector<double> p = {0.2, 0.05, 0.4, 0.9, deg_to_rad(-40), deg_to_rad(90), 0.0};
    EXPECT_NEAR(family.machine_size(*family.build(p), p), pi * 0.6 * 0.6 * (0.8 + 0.9), 1e-12);
  }
  {  // hexaglide: pi rho^2 (s |sin i| + L), rho = max_i |(s/2 cos i, y_i - mean y)|
    const DesignFamily family = hexaglide_family(HexaglideDesign{});
    const double s = 1.2, L = 0.7, incl = deg_to_rad(10), offset = 0.25;
    const std::vector<double> p = {0.2, deg_to_rad(20), offset, L, s, incl, 0.0};
    const Eigen::Matrix<double, 3, 6> b =
        Eigen::AngleAxisd(std::numbers::pi / 2, Eigen::Vector3d::UnitZ()).toRotationMatrix() *
        semi_regular_platform_joints(0.2, deg_to_rad(20));
    std::array<double, 6> y{};
    double mean = 0.0;
    for (int k = 0; k < 6; ++k) {
      y[static_cast<std::size_t>(k)] = b(1, k) + (b(1, k) >= 0.0 ? offset : -offset);
      mean += y[static_cast<std::size_t>(k)] / 6.0;
    }
    double rho = 0.0;
    for (double yk : y) rho = std::max(rho, std::hypot(s / 2 * std::cos(incl), yk - mean));
    EXPECT_NEAR(family.machine_size(*family.build(p), p),
                pi * rho * rho * (s * std::abs(std::sin(incl)) + L), 1e-12);
  }
}

TEST(LegChainDesign, FamiliesRecoverTheirTemplateAsDefaults) {
  // The default parameters rebuild the template machine: same metrics at its home pose.
  const HexaglideDesign hexaglide;
  const DesignFamily family = hexaglide_family(hexaglide);
  const std::unique_ptr<Machine> rebuilt = family.build(family.default_parameters());
  const std::unique_ptr<Machine> original = make_hexaglide(hexaglide);
  const Pose pose{{0.05, -0.03, 0.55}, {0.02, -0.01, 0.03}};
  PoseMetrics a, b;
  rebuilt->analyze(*rebuilt->make_data(), pose, Wrench::Constant(100.0), a);
  original->analyze(*original->make_data(), pose, Wrench::Constant(100.0), b);
  ASSERT_TRUE(b.reachable);
  EXPECT_NEAR((a.q - b.q).norm(), 0.0, 1e-12);
  EXPECT_NEAR(a.stiffness_min / b.stiffness_min, 1.0, 1e-12);
}

TEST(LegChainDesign, TripodFamilyRecoversItsTemplateAndSetsItsParameters) {
  const Tripod3PrsDesign tripod;
  const DesignFamily family = tripod_3prs_family(tripod);
  const Pose pose{{0.0, 0.0, 1.1}, {deg_to_rad(20), deg_to_rad(-15), 0.0}};
  PoseMetrics a, b;
  const std::unique_ptr<Machine> rebuilt = family.build(family.default_parameters());
  const std::unique_ptr<Machine> original = make_tripod_3prs(tripod);
  rebuilt->analyze(*rebuilt->make_data(), pose, Wrench::Constant(100.0), a);
  original->analyze(*original->make_data(), pose, Wrench::Constant(100.0), b);
  ASSERT_TRUE(b.reachable);
  EXPECT_NEAR((a.q - b.q).norm(), 0.0, 1e-12);
  EXPECT_NEAR(a.stiffness_min / b.stiffness_min, 1.0, 1e-12);
  // Each parameter lands in its field: the same machine as the design built by hand.
  Tripod3PrsDesign by_hand = tripod;
  by_hand.base_radius = 0.33;
  by_hand.platform_radius = 0.12;
  by_hand.strut = 0.62;
  by_hand.q_max = tripod.q_min + 0.8;
  const std::unique_ptr<Machine> built = family.build({0.33, 0.12, 0.62, 0.8, 0.0});
  const std::unique_ptr<Machine> expected = make_tripod_3prs(by_hand);
  built->analyze(*built->make_data(), pose, Wrench::Constant(100.0), a);
  expected->analyze(*expected->make_data(), pose, Wrench::Constant(100.0), b);
  EXPECT_EQ(a.reachable, b.reachable);
  EXPECT_NEAR((a.q - b.q).norm(), 0.0, 1e-12);
  EXPECT_NEAR(family.machine_size(*built, {0.33, 0.12, 0.62, 0.8, 0.0}),
              *expected->envelope_volume(), 1e-12);
}

}  // namespace
}  // namespace pkmopt
