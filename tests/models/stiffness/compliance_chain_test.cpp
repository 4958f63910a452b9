// Tests of models/stiffness/compliance_chain: the drive train's compliance against hand sums, the
// screw term along the stroke, the torsion seen through the lead, and the validation messages.
#include "models/stiffness/compliance_chain.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

namespace pkmopt {
namespace {

constexpr double kPi = std::numbers::pi;

ScrewDrive full_drive() {
  return ScrewDrive{.E = 2.1e11,
                    .root_diameter = 0.028,
                    .free_length_at_min = 0.15,
                    .free_length_at_max = 0.60,
                    .nut_stiffness = 8e8,
                    .bearing_stiffness = 1.2e9,
                    .torsional_stiffness = 4000,
                    .lead = 0.01};
}

TEST(ScrewDrive, ChainIsTheSumOfItsElementsInSeries) {
  const ScrewDrive d = full_drive();
  // Hand sum at mid-stroke (q = 0.925 of [0.7, 1.15]): free screw length 0.375 m.
  const double area = kPi * 0.028 * 0.028 / 4;                  // 6.1575e-4 m^2
  const double screw = 0.375 / (2.1e11 * area);                 // m/N
  const double torsion = std::pow(0.01 / (2 * kPi), 2) / 4000;  // (lead/2pi)^2 / k_t
  const double expected = screw + 1 / 8e8 + 1 / 1.2e9 + torsion;
  EXPECT_NEAR(drive_compliance(d, 0.925, 0.7, 1.15, false), expected, 1e-15 * expected * 10);
  // The torsion term alone: a 4000 N m/rad motor through a 10 mm lead is 1.58e9 N/m.
  const ScrewDrive motor{.torsional_stiffness = 4000, .lead = 0.01};
  EXPECT_NEAR(1.0 / drive_compliance(motor, 0.0, 0.0, 1.0, false),
              4000 * std::pow(2 * kPi / 0.01, 2), 1e-6 * 1.58e9);
  // No element: rigid.
  EXPECT_EQ(drive_compliance(ScrewDrive{}, 0.9, 0.7, 1.15, false), 0.0);
}

TEST(ScrewDrive, ScrewTermFollowsTheFreeLengthAlongTheStroke) {
  const ScrewDrive screw{
      .E = 2.1e11, .root_diameter = 0.028, .free_length_at_min = 0.15, .free_length_at_max = 0.60};
  const double EA = 2.1e11 * kPi * 0.028 * 0.028 / 4;
  for (int k = 0; k <= 10; ++k) {
    const double q = 0.7 + 0.045 * k;
    const double length = 0.15 + 0.45 * (q - 0.7) / 0.45;
    EXPECT_NEAR(drive_compliance(screw, q, 0.7, 1.15, false), length / EA, 1e-13 * length / EA)
        << "q = " << q;
  }
  // The nut moving towards the bearing as the actuator extends: the screw stiffens.
  const ScrewDrive reversed{
      .E = 2.1e11, .root_diameter = 0.028, .free_length_at_min = 0.60, .free_length_at_max = 0.15};
  EXPECT_GT(drive_compliance(reversed, 0.7, 0.7, 1.15, false),
            drive_compliance(reversed, 1.15, 0.7, 1.15, false));
  EXPECT_NEAR(drive_compliance(reversed, 1.15, 0.7, 1.15, false), 0.15 / EA, 1e-13 * 0.15 / EA);
}

TEST(ScrewDrive, RevoluteDrivesHaveTheMotorTorsionOnly) {
  const ScrewDrive motor{.torsional_stiffness = 2.5e4};
  EXPECT_DOUBLE_EQ(drive_compliance(motor, 0.3, -1.0, 1.0, true), 1.0 / 2.5e4);
  EXPECT_NO_THROW(check_screw_drive(motor, "drive", true));
  EXPECT_THROW(check_screw_drive(full_drive(), "drive", true), std::invalid_argument);
}

TEST(ScrewDrive, IncompleteOrNegativeValuesAreRefused) {
  auto message = [](const ScrewDrive& d) {
    try {
      check_screw_drive(d, "legs.drive", false);
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_EQ(message(full_drive()), "");
  EXPECT_EQ(message(ScrewDrive{.E = 2.1e11}),
            "legs.drive: the screw needs both E and root_diameter");
  EXPECT_EQ(message(ScrewDrive{.E = 2.1e11, .root_diameter = 0.02}),
            "legs.drive: the screw needs its free length (free_length_at_min, free_length_at_max)");
  EXPECT_EQ(message(ScrewDrive{.free_length_at_min = 0.1}),
            "legs.drive: free lengths are those of a screw: give E and root_diameter too");
  EXPECT_EQ(message(ScrewDrive{.torsional_stiffness = 4000}),
            "legs.drive: the motor torsion acts through the lead: give torsional_stiffness and "
            "lead together");
  EXPECT_EQ(message(ScrewDrive{.nut_stiffness = -1}),
            "legs.drive.nut_stiffness must be a finite number >= 0");
}

}  // namespace
}  // namespace pkmopt
