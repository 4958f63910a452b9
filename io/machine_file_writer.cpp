#include "io/machine_file_writer.hpp"

#include <fmt/format.h>

#include "io/csv.hpp"
#include "io/field_list.hpp"
#include "io/machine_file_lathe.hpp"
#include "io/machine_file_leg_chain.hpp"

namespace pkmopt {
namespace {

// "model: NAME" and the design's keys from the field list its reader takes, one line per key,
// sub-sections as flow maps (numbers in their shortest round-trip form, angles in degrees to the
// 12 significant digits the lists give them).
template <typename Design>
std::string machine_file(const char* model, Design design) {
  FieldWriter writer;
  describe_fields(writer, design);
  return fmt::format("model: {}\n", model) + writer.flow_lines();
}

}  // namespace

std::string delta_machine_file(const DeltaDesign& d) { return machine_file("delta", d); }

std::string linear_delta_machine_file(const LinearDeltaDesign& d) {
  return machine_file("linear_delta", d);
}

std::string hexaglide_machine_file(const HexaglideDesign& d) {
  return machine_file("hexaglide", d);
}

std::string tripod_3prs_machine_file(const Tripod3PrsDesign& d) {
  return machine_file("tripod_3prs", d);
}

std::string lathe_16k20f3_machine_file(const Lathe16k20f3Design& d) {
  return machine_file("lathe_16k20f3", d);
}

std::string leg_chain_machine_file(const LegChainDesign& d) {
  std::string text = machine_file("leg_chain", d);
  text += "legs:\n";
  bool revolute = false;
  for (const LegChainLeg& leg : d.legs) {
    LegChainLeg copy = leg;
    LegChainLegFields fields{copy, d.mobility};
    FieldWriter writer;
    describe_fields(writer, fields);
    text += "  - " + writer.flow_map() + "\n";
    revolute = revolute || leg.kind == LegKind::kRUS;
  }
  if (revolute)
    return text + fmt::format("actuator_error_deg: {:.12g}\n", rad_to_deg(d.actuator_error));
  return text + "actuator_error: " + format_number(d.actuator_error) + "\n";
}

}  // namespace pkmopt
