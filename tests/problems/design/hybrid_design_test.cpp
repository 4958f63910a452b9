// The hybrid design family (problems/design/hybrid_design.hpp): the module family's parameters,
// the carrier's axes, and the hybrid's envelope.
#include "problems/design/hybrid_design.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "models/hybrid/hybrid_machine.hpp"
#include "problems/design/leg_chain_design.hpp"

namespace pkmopt {
namespace {

TEST(HybridDesignFamily, ModuleParametersOnTheCarriersAxes) {
  const DesignFamily module = tripod_3prs_family(Tripod3PrsDesign{});
  HybridDesign carrier;
  carrier.chain = SerialChain::from_code("12");
  carrier.axes = {{.min = -0.3, .max = 0.3, .stiffness = 1.5e8},
                  {.min = -0.2, .max = 0.2, .stiffness = 1.5e8}};
  carrier.home = {0, 0, 0.9};
  const DesignFamily family = hybrid_family(carrier, module);
  EXPECT_EQ(family.model, "hybrid");
  ASSERT_EQ(family.parameters.size(), module.parameters.size());
  for (std::size_t k = 0; k < module.parameters.size(); ++k)
    EXPECT_EQ(family.parameters[k].name, module.parameters[k].name);
  EXPECT_GE(family.index_of("home_height"), 0);
  std::vector<double> p = module.default_parameters();
  p[static_cast<std::size_t>(module.index_of("strut"))] = 0.5;
  const auto machine = family.build(p);
  const auto& hybrid = dynamic_cast<const HybridMachine&>(*machine);
  EXPECT_EQ(hybrid.num_serial(), 2);
  EXPECT_EQ(hybrid.design().home, carrier.home);
  // The module is the module family's machine of the same parameters: the same envelope.
  const auto alone = module.build(p);
  const double V = *alone->envelope_volume();
  EXPECT_NEAR(*hybrid.module().envelope_volume(), V, 1e-15 * V);
  // machine_size: the module's volume as a cube of side a = V^(1/3), swept over the travel box
  // (0.6 along x, 0.4 along y, none along z): (a + 0.6)(a + 0.4) a.
  const double a = std::cbrt(V);
  EXPECT_NEAR(family.machine_size(*machine, p), (a + 0.6) * (a + 0.4) * a, 1e-12);
  // No axes, or a hybrid as the module: refused.
  HybridDesign bare = carrier;
  bare.axes.clear();
  EXPECT_THROW(hybrid_family(bare, module), std::invalid_argument);
  EXPECT_THROW(hybrid_family(carrier, family), std::invalid_argument);
}

}  // namespace
}  // namespace pkmopt
