// Tests of report/display_units: engineering units for the report, the files' SI units in.
#include "report/display_units.hpp"

#include <gtest/gtest.h>

namespace pkmopt {
namespace {

TEST(DisplayUnits, EngineeringUnitsOfEachKindOfQuantity) {
  EXPECT_EQ(engineering_unit("stiffness_min", "N/m").unit, "N/µm");
  EXPECT_EQ(engineering_unit("stiffness_min", "N/m").scale, 1e-6);
  EXPECT_EQ(engineering_unit("tcp_deflection_max", "m").unit, "µm");
  EXPECT_EQ(engineering_unit("tcp_error_max", "m").scale, 1e6);
  EXPECT_EQ(engineering_unit("base_radius", "m").unit, "mm");
  EXPECT_EQ(engineering_unit("leg_clearance_min", "m").scale, 1e3);
  EXPECT_EQ(engineering_unit("workspace_volume", "m^3").unit, "l");
  EXPECT_EQ(engineering_unit("workspace_volume", "m^3").scale, 1e3);
  EXPECT_EQ(engineering_unit("leg_force_max", "N").unit, "kN");
  EXPECT_EQ(engineering_unit("leg_force_max", "N").scale, 1e-3);
  for (const char* unit : {"deg", "Hz", "kg", "m^2", ""}) {
    EXPECT_EQ(engineering_unit("x", unit).unit, unit);
    EXPECT_EQ(engineering_unit("x", unit).scale, 1.0);
  }
  // A file already in other units is left alone.
  EXPECT_EQ(display_scale("tcp_deflection_max", "mm"), 1.0);
}

TEST(DisplayUnits, ObjectivesAndConstraintsScaledTheRestAsInTheFile) {
  ParetoFront front;
  front.objectives = {{"tcp_deflection_max", "minimize", "m"},
                      {"stiffness_min", "maximize", "N/m"},
                      {"singularity_margin", "maximize", ""}};
  front.constraints = {{"g_tcp_deflection_max_max", "tcp_deflection_max", "max", 2e-5, "m"},
                       {"g_leg_force_max_max", "leg_force_max", "max", 1e4, "N"}};
  front.parameters = {{"base_radius", "m", 0.4, 0.8}};
  ParetoDesign d;
  d.parameters = {0.5};
  d.home_height = 0.2;
  d.objectives = {1.25e-5, 3e7, 0.1};
  d.constraints = {-7.5e-6, -100.0};
  front.designs = {d};
  const ParetoFront shown = in_display_units(front);
  EXPECT_EQ(shown.objectives[0].unit, "µm");
  EXPECT_DOUBLE_EQ(shown.designs[0].objectives[0], 12.5);
  EXPECT_EQ(shown.objectives[1].unit, "N/µm");
  EXPECT_DOUBLE_EQ(shown.designs[0].objectives[1], 30.0);
  EXPECT_EQ(shown.objectives[2].unit, "");
  EXPECT_EQ(shown.designs[0].objectives[2], 0.1);
  EXPECT_EQ(shown.constraints[0].unit, "µm");
  EXPECT_DOUBLE_EQ(shown.constraints[0].bound, 20.0);
  EXPECT_DOUBLE_EQ(shown.designs[0].constraints[0], -7.5);
  EXPECT_EQ(shown.constraints[1].unit, "kN");
  EXPECT_DOUBLE_EQ(shown.constraints[1].bound, 10.0);
  EXPECT_DOUBLE_EQ(shown.designs[0].constraints[1], -0.1);
  // Parameters and the home height stay in file units (machine files are built from them).
  EXPECT_EQ(shown.parameters[0].unit, "m");
  EXPECT_EQ(shown.designs[0].parameters[0], 0.5);
  EXPECT_EQ(shown.designs[0].home_height, 0.2);
}

}  // namespace
}  // namespace pkmopt
