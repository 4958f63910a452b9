// Tests of problems/design/cutting_load: the turning model against the seeds' worked example, the
// approach-angle projection, and the milling model against its geometric definition.
#include "problems/design/cutting_load.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <stdexcept>

namespace pkmopt {
namespace {

// The seeds' turning case (steel, handbook coefficients): D 120 mm, t 3 mm, s 0.84 mm/rev,
// T 60 min, C_v 340, x 0.15, y 0.45, m 0.2, K_v 0.85, C_p 200, x_p 1, y_p 0.75, n_p 0,
// K_p = 1 * 0.98 * 1.15. The seeds report V = 116.88 m/min, n ~ 310 rev/min, P_z ~ 5933 N and,
// at the optimal approach angle alpha = arccot 2 ~ 26.6 deg, a machine-frame force ~ 6633 N.
TurningConditions seeds_turning_case() {
  TurningConditions c;
  c.diameter_mm = 120.0;
  c.depth_mm = 3.0;
  c.feed_mm_per_rev = 0.84;
  c.tool_life_min = 60.0;
  c.C_v = 340.0;
  c.x_v = 0.15;
  c.y_v = 0.45;
  c.m = 0.2;
  c.K_v = 0.85;
  c.C_p = 200.0;
  c.x_p = 1.0;
  c.y_p = 0.75;
  c.n_p = 0.0;
  c.K_p = 1.0 * 0.98 * 1.15;
  return c;
}

TEST(TurningLoad, ReproducesTheSeedsWorkedExample) {
  const TurningLoad load = turning_load(seeds_turning_case());
  // m/min: the formula gives 116.889; the seeds print 116.88 (cut to two decimals).
  EXPECT_NEAR(load.cutting_speed, 116.88, 0.01);
  EXPECT_NEAR(load.spindle_speed, 310.0, 0.5);  // rev/min, "n ~ 310"
  EXPECT_NEAR(load.tangential, 5933.0, 0.5);    // N, "P_z ~ 5933"
  EXPECT_DOUBLE_EQ(load.radial, 0.5 * load.tangential);
  EXPECT_DOUBLE_EQ(load.axial, 0.2 * load.tangential);
}

TEST(TurningLoad, OptimalApproachAngleIsArccot2AndGives6633N) {
  const TurningLoad load = turning_load(seeds_turning_case());
  const double alpha = optimal_approach_angle(load);
  EXPECT_NEAR(alpha, std::atan(0.5), 1e-15);  // arccot 2
  EXPECT_NEAR(alpha * 180.0 / std::numbers::pi, 26.565, 0.001);
  const Eigen::Vector3d f = turning_machine_force(load, alpha);
  EXPECT_NEAR(f.z(), 6633.0, 0.5);        // the seeds' machine-frame force
  EXPECT_NEAR(f.y(), 0.0, 1e-9 * f.z());  // all in-plane force along machine z
  EXPECT_DOUBLE_EQ(f.x(), load.axial);
  // The z force is largest there: a scan of approach angles never exceeds it.
  for (int k = -90; k <= 90; ++k) {
    const double a = k * std::numbers::pi / 180.0;
    EXPECT_LE(turning_machine_force(load, a).z(), f.z() * (1.0 + 1e-15));
  }
}

TEST(TurningLoad, ProjectionIsARotation) {
  const TurningLoad load = turning_load(seeds_turning_case());
  for (double a : {-1.0, -0.3, 0.0, 0.4, 1.2, 3.0}) {
    const Eigen::Vector3d f = turning_machine_force(load, a);
    EXPECT_NEAR(f.norm(), load.tool_frame_force().norm(), 1e-9);
  }
  EXPECT_TRUE(turning_machine_force(load, 0.0).isApprox(load.tool_frame_force(), 1e-15));
}

TEST(TurningLoad, RejectsUnusableConditions) {
  TurningConditions c = seeds_turning_case();
  c.depth_mm = 0.0;
  EXPECT_EQ(check_turning_conditions(c), "depth_mm: expected a finite number > 0, found 0");
  EXPECT_THROW(turning_load(c), std::invalid_argument);
  c = seeds_turning_case();
  c.x_v = std::nan("");
  EXPECT_EQ(check_turning_conditions(c), "x_v: expected a finite number, found nan");
  c = seeds_turning_case();
  c.radial_ratio = -0.1;
  EXPECT_EQ(check_turning_conditions(c), "radial_ratio: expected a finite number >= 0, found -0.1");
  EXPECT_EQ(check_turning_conditions(seeds_turning_case()), "");
}

MillingConditions steel_face_milling() {
  MillingConditions c;
  c.cutter_diameter_mm = 63.0;
  c.teeth = 5;
  c.cutting_speed = 220.0;
  c.feed_per_tooth_mm = 0.15;
  c.width_mm = 40.0;
  c.depth_mm = 3.0;
  c.lead_angle_deg = 90.0;
  c.k_c1 = 1700.0;  // unalloyed steel, N/mm^2 at h = 1 mm
  c.m_c = 0.25;
  return c;
}

// Mean of f_z sin(kappa) sin(phi) over phi in [0, phi_e] by the midpoint rule.
double numeric_mean_chip_thickness(const MillingConditions& c) {
  const double phi_e = std::acos(1.0 - 2.0 * c.width_mm / c.cutter_diameter_mm);
  const int n = 200000;
  double sum = 0.0;
  for (int k = 0; k < n; ++k) sum += std::sin((k + 0.5) * phi_e / n);
  return c.feed_per_tooth_mm * std::sin(c.lead_angle_deg * std::numbers::pi / 180.0) * sum / n;
}

TEST(MillingLoad, MeanChipThicknessIsTheArcAverage) {
  MillingConditions c = steel_face_milling();
  for (double width : {2.0, 10.0, 31.5, 40.0, 63.0}) {
    for (double lead : {45.0, 75.0, 90.0}) {
      c.width_mm = width;
      c.lead_angle_deg = lead;
      EXPECT_NEAR(milling_load(c).mean_chip_thickness, numeric_mean_chip_thickness(c), 1e-10)
          << width << " " << lead;
    }
  }
  // Full slot, square shoulder: h_m = 2 f_z / pi.
  c.width_mm = c.cutter_diameter_mm;
  c.lead_angle_deg = 90.0;
  EXPECT_NEAR(milling_load(c).mean_chip_thickness, 2.0 * c.feed_per_tooth_mm / std::numbers::pi,
              1e-15);
}

TEST(MillingLoad, PowerAndForcesAreConsistent) {
  const MillingConditions c = steel_face_milling();
  const MillingLoad load = milling_load(c);
  EXPECT_NEAR(load.spindle_speed, 1000.0 * 220.0 / (std::numbers::pi * 63.0), 1e-9);
  EXPECT_NEAR(load.table_feed, 0.15 * 5 * load.spindle_speed, 1e-9);
  EXPECT_NEAR(load.specific_force, 1700.0 * std::pow(load.mean_chip_thickness, -0.25), 1e-9);
  // Metal removal rate Q (cm^3/min) times k_c gives the power: P_c = Q k_c / 60000.
  const double removal_rate = c.depth_mm * c.width_mm * load.table_feed / 1000.0;
  EXPECT_NEAR(load.power_kw, removal_rate * load.specific_force / 60000.0, 1e-12);
  // The tangential force at the rim times the cutting speed is that power.
  EXPECT_NEAR(load.tangential * c.cutting_speed / 60.0, load.power_kw * 1000.0, 1e-9);
  EXPECT_DOUBLE_EQ(load.radial, 0.3 * load.tangential);
  EXPECT_DOUBLE_EQ(load.axial, 0.2 * load.tangential);
  // A plausible order for this cut (a few kW, a few kN).
  EXPECT_GT(load.power_kw, 1.0);
  EXPECT_LT(load.power_kw, 30.0);
}

TEST(MillingLoad, WrenchDirections) {
  const MillingLoad load = milling_load(steel_face_milling());
  const Wrench w = milling_wrench(load, Eigen::Vector3d(2.0, 0.0, 0.0));
  EXPECT_NEAR(w(0), -load.tangential, 1e-12);
  EXPECT_NEAR(w(1), load.radial, 1e-12);
  EXPECT_NEAR(w(2), load.axial, 1e-12);
  EXPECT_EQ(w.tail<3>(), Eigen::Vector3d(0.0, 0.0, -load.spindle_torque));
  EXPECT_NEAR(load.spindle_torque, load.tangential * 0.063 / 2.0, 1e-12);
  const Wrench turned = milling_wrench(load, Eigen::Vector3d(0.0, -1.0, 0.0));
  EXPECT_NEAR(turned(0), load.radial, 1e-12);
  EXPECT_NEAR(turned(1), load.tangential, 1e-12);
  EXPECT_NEAR(turned.head<3>().norm(), w.head<3>().norm(), 1e-9);
  EXPECT_THROW(milling_wrench(load, Eigen::Vector3d::Zero()), std::invalid_argument);
  EXPECT_THROW(milling_wrench(load, Eigen::Vector3d(1.0, 0.0, 0.5)), std::invalid_argument);
}

TEST(MillingLoad, RejectsUnusableConditions) {
  MillingConditions c = steel_face_milling();
  c.width_mm = 70.0;
  EXPECT_EQ(check_milling_conditions(c),
            "width_mm: expected at most cutter_diameter_mm (63), found 70");
  c = steel_face_milling();
  c.teeth = 0;
  EXPECT_EQ(check_milling_conditions(c), "teeth: expected an integer >= 1, found 0");
  c = steel_face_milling();
  c.lead_angle_deg = 120.0;
  EXPECT_EQ(check_milling_conditions(c), "lead_angle_deg: expected an angle in (0, 90], found 120");
  EXPECT_THROW(milling_load(c), std::invalid_argument);
  EXPECT_EQ(check_milling_conditions(steel_face_milling()), "");
}

}  // namespace
}  // namespace pkmopt
