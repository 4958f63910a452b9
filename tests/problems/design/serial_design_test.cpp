// The serial 5-axis design family (problems/design/serial_design.hpp) and the serial machine's
// envelope it measures with.
#include "problems/design/serial_design.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "models/serial/serial_machine.hpp"

namespace pkmopt {
namespace {

// A C/A fork head at the end of X, Y, Z (123646): the tool tip 0.25 m below the A axis.
SerialDesign head_template() {
  SerialDesign d;
  d.chain = SerialChain::from_code("123646");
  std::vector<ChainElement> elements = d.chain.elements();
  const char* names[] = {"X", "Y", "Z", "C", "A", "S"};
  for (std::size_t k = 0; k < elements.size(); ++k) elements[k].name = names[k];
  d.chain = SerialChain(elements);
  d.spindle = 5;
  d.axes = {{.min = -0.4, .max = 0.4, .stiffness = 1.5e8},
            {.min = -0.3, .max = 0.5, .stiffness = 1.5e8},
            {.min = -0.1, .max = 0.6, .stiffness = 1.2e8},
            {.min = -200 * M_PI / 180, .max = 200 * M_PI / 180, .stiffness = 1e6},
            {.min = -100 * M_PI / 180, .max = 100 * M_PI / 180, .stiffness = 1e6}};
  d.tool_point = {0, 0, -0.25};
  d.characteristic_length = 0.2;
  return d;
}

TEST(SerialDesignFamily, ParametersSetTravelsAndPivot) {
  const SerialDesign t = head_template();
  const DesignFamily family = serial_family(t);
  ASSERT_EQ(family.parameters.size(), 5u);
  EXPECT_EQ(family.parameters[0].name, "x_travel");
  EXPECT_EQ(family.parameters[1].name, "y_travel");
  EXPECT_EQ(family.parameters[2].name, "z_travel");
  EXPECT_EQ(family.parameters[3].name, "pivot");
  EXPECT_EQ(family.parameters[4].name, "home_height");
  EXPECT_DOUBLE_EQ(family.parameters[1].default_value, 0.8);
  EXPECT_DOUBLE_EQ(family.parameters[3].default_value, 0.25);
  // The template's own values give the template exactly.
  const auto same = family.build(family.default_parameters());
  const auto& d0 = dynamic_cast<const SerialMachine&>(*same).design();
  EXPECT_EQ(d0.axes[2].min, -0.1);
  EXPECT_EQ(d0.tool_point, t.tool_point);
  // Travels centred where the template's ranges are; the pivot along -tool_axis.
  const auto built = family.build({0.6, 0.4, 0.5, 0.15, 0.0});
  const SerialDesign& d = dynamic_cast<const SerialMachine&>(*built).design();
  EXPECT_DOUBLE_EQ(d.axes[0].min, -0.3);
  EXPECT_DOUBLE_EQ(d.axes[0].max, 0.3);
  EXPECT_DOUBLE_EQ(d.axes[1].min, -0.1);  // centre 0.1
  EXPECT_DOUBLE_EQ(d.axes[1].max, 0.3);
  EXPECT_DOUBLE_EQ(d.axes[2].min, 0.25 - 0.25);  // centre 0.25
  EXPECT_DOUBLE_EQ(d.axes[2].max, 0.5);
  EXPECT_EQ(d.axes[3].min, t.axes[3].min);  // rotary ranges as in the template
  EXPECT_DOUBLE_EQ(d.tool_point.z(), -0.15);
  EXPECT_EQ(d.tool_point.x(), 0.0);
  EXPECT_FALSE(std::signbit(d.tool_point.x()));
  // machine_size: the linear travel box grown by the tool's reach, (0.6 + 0.3)(0.4 + 0.3)(0.5 +
  // 0.3) m^3.
  EXPECT_NEAR(family.machine_size(*built, {0.6, 0.4, 0.5, 0.15, 0.0}), 0.9 * 0.7 * 0.8, 1e-12);
}

}  // namespace
}  // namespace pkmopt
