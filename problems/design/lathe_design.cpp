#include "problems/design/lathe_design.hpp"

#include <fmt/format.h>

#include <cmath>

namespace pkmopt {
DesignFamily lathe_16k20f3_family(const Lathe16k20f3Design& t,
                                  DesignWriter<Lathe16k20f3Design> writer) {
  DesignFamily family;
  family.model = "lathe_16k20f3";
  family.parameters = {
      {"strut_length", "m", "strut length (machine_size = L³)", t.strut_length, false, false},
      {"guide_y", "m", "the carriages' hinge line across the bed", t.guide_y, true, true},
      {"leg_base_y", "m", "the cylinders' beam position", t.leg_base_y, true, true},
      {"home_height", "m", "the task region is lifted by this along base z", 0.0, true, true}};
  family.parameter_keys = {"strut_length", "guide_y", "leg_base_y"};
  auto design = [t](const std::vector<double>& p) {
    Lathe16k20f3Design d = t;
    d.strut_length = p.at(0);
    d.guide_y = p.at(1);
    d.leg_base_y = p.at(2);
    return d;
  };
  family.build = [design](const std::vector<double>& p) { return make_lathe_16k20f3(design(p)); };
  if (writer)
    family.machine_file = [design, writer](const std::vector<double>& p) {
      return writer(design(p));
    };
  family.machine_size = [](const Machine&, const std::vector<double>& p) {
    return p.at(0) * p.at(0) * p.at(0);
  };
  return family;
}

}  // namespace pkmopt
