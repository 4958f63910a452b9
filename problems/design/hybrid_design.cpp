#include "problems/design/hybrid_design.hpp"

#include <memory>
#include <stdexcept>

namespace pkmopt {

DesignFamily hybrid_family(const HybridDesign& carrier, const DesignFamily& module,
                           HybridWriter writer) {
  if (carrier.axes.empty()) throw std::invalid_argument("hybrid_family: the carrier has no axes");
  if (module.model == "hybrid")
    throw std::invalid_argument("hybrid_family: a hybrid module cannot be carried");
  DesignFamily family;
  family.model = "hybrid";
  family.parameters = module.parameters;
  family.translational = module.translational;
  auto design = [carrier, build = module.build](const std::vector<double>& p) {
    HybridDesign d = carrier;
    d.module = build(p);
    return d;
  };
  family.build = [design](const std::vector<double>& p) -> std::unique_ptr<Machine> {
    return std::make_unique<HybridMachine>(design(p));
  };
  family.machine_size = envelope_machine_size;
  if (writer && module.machine_file)
    family.machine_file = [carrier, writer,
                           module_file = module.machine_file](const std::vector<double>& p) {
      return writer(carrier, module_file(p));
    };
  return family;
}

}  // namespace pkmopt
