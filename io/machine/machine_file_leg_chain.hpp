// Machine files (YAML) of the leg-chain models: delta, linear_delta, hexaglide, tripod_3prs,
// tripod_3rps, and the generic form `model: leg_chain` (any mobility, an explicit list of legs).
//
// Strict like the hexapod reader (io/machine/machine_file.hpp): unknown keys, missing required
// keys, wrong counts, non-finite numbers and impossible values throw InputError naming file, line,
// column and key. Angles are in degrees in the files (drive ranges, joint limits, inclinations,
// the delta's actuator_error_deg). docs/machines.md lists every key with its unit.
//
// Each model's keys are described once (io/format/field_list.hpp, `describe_fields` below): the
// readers, the writers (`*_machine_file`, below) and the docs tables of
// docs/machines.md come from those lists. Alternatives and cross-key checks (E and area or
// axial_stiffness, platform or platform_joints, the generic form's legs and actuator error) are
// read by hand next to them.
//
//   model: delta
//   base_radius: 0.164          # m
//   platform_radius: 0.044      # m
//   upper_arm: 0.524            # m
//   rod: 1.244                  # m
//   drive_range_deg: [-60, 100]
//   rods: {E: 7.0e10, area: 5.0e-5}   # per rod (2 per parallelogram), or {axial_stiffness: N/m}
//   # optional link compliance (docs/stiffness.md): rods 0.1 m apart, elastic cranks
//   #   rods: {E: 7.0e10, area: 5.0e-5, parallelogram_width: 0.1}
//   #   crank_section: {E: 7.0e10, G: 2.6e10, outer_diameter: 0.05, inner_diameter: 0.04}
//
// The models register in io/machine/model_registry.hpp (leg_chain_model_entries). Example:
//   YamlValue root = YamlValue::load_file("examples/delta.yaml");
//   DeltaDesign design = read_delta_design(root);
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <string_view>

#include "io/format/yaml_reader.hpp"
#include "models/leg_chain/leg_chain.hpp"

namespace pkmopt {

DeltaDesign read_delta_design(const YamlValue& root);
LinearDeltaDesign read_linear_delta_design(const YamlValue& root);
HexaglideDesign read_hexaglide_design(const YamlValue& root);
Tripod3PrsDesign read_tripod_3prs_design(const YamlValue& root);
Tripod3RpsDesign read_tripod_3rps_design(const YamlValue& root);
/// The generic form `model: leg_chain` (mobility, rotation_axis, tool, legs list; see
/// docs/machines.md).
LegChainDesign read_leg_chain_design(const YamlValue& root);

/// The docs table of a model's machine-file keys (`model`: delta, linear_delta, hexaglide,
/// tripod_3prs or leg_chain, whose table has the legs' keys as `legs[].KEY`), from the field
/// list its reader and writer use. Throws std::invalid_argument for another model.
std::string leg_chain_machine_fields_markdown(std::string_view model);

/// A beam section in a file (`section:`, `crank_section:`): a circular tube {E, G, outer_diameter,
/// inner_diameter} (inner 0 or absent: a solid rod) or the values {E, G, A, Iy, Iz, J}; written
/// as the values. `target` is set by the reader (resolve_beam_section, located errors for a
/// section half given or mixed forms) and written from.
struct BeamSectionFields {
  std::optional<BeamSection>& target;
  double E = 0.0, G = 0.0, outer_diameter = 0.0, inner_diameter = 0.0;
  double A = 0.0, Iy = 0.0, Iz = 0.0, J = 0.0;
};
/// The section a `section:` map read into `fields` gives (throws InputError at the map's keys).
BeamSection resolve_beam_section(const YamlValue& map, const BeamSectionFields& fields);

/// A leg of the generic form with the keys of its kind and of the platform mobility (`all`: every
/// key, for the docs).
struct LegChainLegFields {
  LegChainLeg& leg;
  PlatformMobility mobility = PlatformMobility::kSixDof;
  bool all = false;
};

/// The field lists of the machine files (io/format/field_list.hpp): instantiated in
/// io/machine/machine_file_leg_chain.cpp for its readers and docs, and for FieldWriter.
template <class Fields>
void describe_fields(Fields& f, DeltaDesign& design);
template <class Fields>
void describe_fields(Fields& f, LinearDeltaDesign& design);
template <class Fields>
void describe_fields(Fields& f, HexaglideDesign& design);
template <class Fields>
void describe_fields(Fields& f, Tripod3PrsDesign& design);
template <class Fields>
void describe_fields(Fields& f, Tripod3RpsDesign& design);
/// The generic form's top-level keys (its legs and actuator error are read by hand).
template <class Fields>
void describe_fields(Fields& f, LegChainDesign& design);
template <class Fields>
void describe_fields(Fields& f, LegChainLegFields& leg);
template <class Fields>
void describe_fields(Fields& f, BeamSectionFields& section);

/// The machine files of designs, every key written (model_file_text, io/format/field_list.hpp):
/// reading a written file gives the same machine.
std::string delta_machine_file(const DeltaDesign& design);
std::string linear_delta_machine_file(const LinearDeltaDesign& design);
std::string hexaglide_machine_file(const HexaglideDesign& design);
std::string tripod_3prs_machine_file(const Tripod3PrsDesign& design);
std::string tripod_3rps_machine_file(const Tripod3RpsDesign& design);
/// The generic `model: leg_chain` file of a design, its legs as flow maps (RUS legs: the actuator
/// error as actuator_error_deg).
std::string leg_chain_machine_file(const LegChainDesign& design);

}  // namespace pkmopt
