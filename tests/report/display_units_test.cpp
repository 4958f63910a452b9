// Tests of report/display_units: the µm metrics scaled for the report, everything else untouched.
#include "report/display_units.hpp"

#include <gtest/gtest.h>

namespace pkmopt {
namespace {

TEST(DisplayUnits, DeflectionAndErrorInMicrometresTheRestAsInTheFile) {
  ParetoFront front;
  front.objectives = {{"tcp_deflection_max", "minimize", "m"},
                      {"stiffness_min", "maximize", "N/m"},
                      {"tcp_error_max", "minimize", "m"}};
  front.constraints = {{"g_tcp_deflection_max_max", "tcp_deflection_max", "max", 2e-5, "m"},
                       {"g_leg_force_max_max", "leg_force_max", "max", 1e4, "N"}};
  ParetoDesign d;
  d.objectives = {1.25e-5, 3e7, 4e-6};
  d.constraints = {-7.5e-6, -100.0};
  front.designs = {d};
  const ParetoFront shown = in_display_units(front);
  EXPECT_EQ(shown.objectives[0].unit, "µm");
  EXPECT_DOUBLE_EQ(shown.designs[0].objectives[0], 12.5);
  EXPECT_EQ(shown.objectives[1].unit, "N/m");
  EXPECT_EQ(shown.designs[0].objectives[1], 3e7);
  EXPECT_EQ(shown.objectives[2].unit, "µm");
  EXPECT_DOUBLE_EQ(shown.designs[0].objectives[2], 4.0);
  EXPECT_EQ(shown.constraints[0].unit, "µm");
  EXPECT_DOUBLE_EQ(shown.constraints[0].bound, 20.0);
  EXPECT_DOUBLE_EQ(shown.designs[0].constraints[0], -7.5);
  EXPECT_EQ(shown.constraints[1].bound, 1e4);
  EXPECT_EQ(shown.designs[0].constraints[1], -100.0);
  // A file already in other units is left alone.
  EXPECT_EQ(display_scale("tcp_deflection_max", "mm"), 1.0);
}

}  // namespace
}  // namespace pkmopt
