// Actuator catalogs for tests: the seeds' SEW CMS electric cylinders as in
// studies/library/catalogs/sew-cms.yaml (one entry per stroke variant; no costs, accuracy or
// stiffness).
#pragma once

#include "problems/design/actuator_catalog.hpp"

namespace pkmopt::sample_catalogs {

inline ActuatorCatalog sew_cms() {
  ActuatorCatalog c;
  c.name = "sew-cms";
  c.entries = {{"CMS50S/70", "electric_cylinder", 5300, 0.070, 0.375, {}, {}, {}, {}},
               {"CMS50S/150", "electric_cylinder", 5300, 0.150, 0.375, {}, {}, {}, {}},
               {"CMS50S/300", "electric_cylinder", 5300, 0.300, 0.375, {}, {}, {}, {}},
               {"CMS63S/100", "electric_cylinder", 10500, 0.100, 0.45, {}, {}, {}, {}},
               {"CMS63S/200", "electric_cylinder", 10500, 0.200, 0.45, {}, {}, {}, {}},
               {"CMS71L/200", "electric_cylinder", 20000, 0.200, 0.5, {}, {}, {}, {}},
               {"CMS71L/350", "electric_cylinder", 17000, 0.350, 0.5, {}, {}, {}, {}}};
  return c;
}

}  // namespace pkmopt::sample_catalogs
