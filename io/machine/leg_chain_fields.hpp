// The rules and pieces shared by the field lists of the leg-chain machine files
// (io/machine/machine_file_leg_chain.cpp: the named models;
// io/machine/machine_file_leg_chain_generic.cpp: the generic form `model: leg_chain`): angle
// limits, link stiffness and sections, drives, joints, tool, and the located checks the readers run
// after a list has read its values. Internal to those two files; the public interface is
// io/machine/machine_file_leg_chain.hpp.
#pragma once

#include <Eigen/Core>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <type_traits>

#include "io/format/field_list.hpp"
#include "io/format/yaml_reader.hpp"
#include "io/machine/compliance_fields.hpp"
#include "io/machine/machine_file_leg_chain.hpp"

namespace pkmopt::leg_chain_fields {

// Rules shared by the models' field lists.
inline FieldRule positive(std::string_view unit, std::string_view doc) {
  return {.min = 0, .min_exclusive = true, .required = true, .unit = unit, .doc = doc};
}

inline FieldRule non_negative(std::string_view unit, std::string_view doc) {
  return {.min = 0, .required = true, .unit = unit, .doc = doc};
}

// A joint angle limit in degrees, (0, 180], unlimited when absent; written to 12 digits.
inline FieldRule angle_limit(std::string_view doc) {
  return {.min = 0,
          .max = 180,
          .min_exclusive = true,
          .infinite_is_unset = true,
          .degrees = true,
          .digits = 12,
          .unit = "deg",
          .expected = "an angle in degrees in (0, 180]",
          .doc = doc};
}

// A guide inclination in degrees, (-90, 90).
inline FieldRule inclination(std::string_view doc) {
  return {.min = -90,
          .max = 90,
          .min_exclusive = true,
          .max_exclusive = true,
          .degrees = true,
          .digits = 12,
          .unit = "deg",
          .expected = "an angle in degrees in (-90, 90)",
          .doc = doc};
}

// An actuator stiffness in series with the links: written when > 0, absent = a rigid drive.
inline FieldRule drive_stiffness(LinkStiffness& k, std::string_view unit, std::string_view doc) {
  return {.min = 0,
          .min_exclusive = true,
          .zero_is_unset = true,
          .unit = unit,
          .doc = doc,
          .omit_when = [&k] { return !(k.actuator_stiffness > 0.0); }};
}

template <class Fields>
void describe_model(Fields& f, std::string_view model) {
  f.note("model", model, "", "required", "the machine model");
  f.note("name", "a text", "", "none", "free text");
  f.note("description", "a text", "", "none", "free text");
}

// The docs lines of a link stiffness: E, area and axial_stiffness.
struct LinkStiffnessDocs {
  std::string_view E, area, axial_stiffness;
};

// `{E, area}`, `{axial_stiffness}` or `{section}` of a link (the readers check the choice); the
// members are those of a LinkStiffness or of one leg of the generic form.
template <class Fields>
void describe_link_stiffness(Fields& g, double& E, double& area, double& axial_stiffness,
                             const std::optional<BeamSection>& section,
                             const LinkStiffnessDocs& docs) {
  g.field("E", E,
          {.min = 0,
           .min_exclusive = true,
           .unit = "Pa",
           .default_text = "required (or axial_stiffness, or section)",
           .doc = docs.E,
           .omit_when = [&] { return axial_stiffness > 0.0 || section.has_value(); }});
  g.field("area", area,
          {.min = 0,
           .min_exclusive = true,
           .unit = "m²",
           .default_text = "required (or axial_stiffness, or section)",
           .doc = docs.area,
           .omit_when = [&] { return axial_stiffness > 0.0 || section.has_value(); }});
  g.field("axial_stiffness", axial_stiffness,
          {.min = 0,
           .min_exclusive = true,
           .zero_is_unset = true,
           .unit = "N/m",
           .default_text = "required (or E and area, or section)",
           .doc = docs.axial_stiffness,
           .omit_when = [&section] { return section.has_value(); }});
}

// `section:` or `crank_section:`, a beam section (BeamSectionFields): read into `target` with the
// located checks of resolve_beam_section, written and documented from it.
template <class Fields>
void describe_beam_section(Fields& g, std::string_view key, std::optional<BeamSection>& target,
                           std::string_view doc) {
  BeamSectionFields fields{target};
  if (target) {
    fields.E = target->E;
    fields.G = target->G;
    fields.A = target->A;
    fields.Iy = target->Iy;
    fields.Iz = target->Iz;
    fields.J = target->J;
  }
  g.section(key, {.doc = doc}, [&](auto& h) {
    describe_fields(h, fields);
    if constexpr (std::is_same_v<std::decay_t<decltype(h)>, FieldReader>)
      target = resolve_beam_section(h.section(), fields);
  });
}

inline FieldRule width_rule(std::string_view doc) {
  return {.min = 0, .min_exclusive = true, .zero_is_unset = true, .unit = "m", .doc = doc};
}

// A named model's links; `section_doc` says what a section changes, `pairs` adds the
// parallelogram width (deltas).
template <class Fields>
void describe_links(Fields& f, std::string_view key, LinkStiffness& k, std::string_view per,
                    std::string_view section_doc, bool pairs) {
  f.section(key, {.required = true}, [&](auto& g) {
    describe_link_stiffness(g, k.E, k.area, k.axial_stiffness, k.section,
                            {"Young's modulus of the links (with area)", per,
                             "constant axial stiffness of a link instead of E and area"});
    describe_beam_section(g, "section", k.section, section_doc);
    describe_joint_stiffness(g, k.base_joint_stiffness, k.platform_joint_stiffness);
    if (pairs)
      g.field("parallelogram_width", k.parallelogram_width,
              width_rule("distance between the two rods of a pair (along the bars): the pairs "
                         "then hold the orientation elastically; unset: rigidly"));
  });
}

// `drive:` the actuators' drive train, in series with their `*_stiffness`.
template <class Fields>
void describe_drive(Fields& f, ScrewDrive& drive, std::string_view doc) {
  f.section("drive", {.doc = doc}, [&](auto& g) { describe_screw_drive(g, drive); });
}

template <class Fields>
void describe_joints(Fields& f, std::string_view base_key, double& base_limit,
                     std::string_view base_doc, double& platform_limit,
                     std::string_view platform_doc) {
  f.section("joints", {}, [&](auto& g) {
    g.field(base_key, base_limit, angle_limit(base_doc));
    g.field("platform_max_angle_deg", platform_limit, angle_limit(platform_doc));
  });
}

template <class Fields>
void describe_tool(Fields& f, Eigen::Vector3d& tcp) {
  f.section("tool", {}, [&](auto& g) {
    g.field("tcp", tcp, {.unit = "m", .doc = "the TCP in the platform frame"});
  });
}

template <class Fields>
void describe_characteristic_length(Fields& f, std::optional<double>& length) {
  f.field("characteristic_length", length,
          {.min = 0,
           .min_exclusive = true,
           .unit = "m",
           .default_text = "mean distance from the TCP to the platform joints",
           .doc = "L of J_h in singularity_margin (unused by 3-DOF translational machines)"});
}

inline FieldRule stroke_rule(std::string_view doc) {
  return {.required = true, .unit = "m", .doc = doc};
}

// The choice of `{E, area}`, `{axial_stiffness}` or `{section}`, after the list has read the
// values.
inline void check_links(const YamlValue& section) {
  const bool has_axial = section.has("axial_stiffness");
  const bool has_e = section.has("E");
  const bool has_area = section.has("area");
  if (section.has("section")) {
    for (const char* key : {"E", "area", "axial_stiffness"})
      if (section.has(key))
        section.required(key).fail(
            "either a section (its E and A give the axial stiffness) or E and area "
            "(or axial_stiffness), not both");
    return;
  }
  if (has_axial && (has_e || has_area)) {
    section.required("axial_stiffness").fail("either axial_stiffness or E and area, not both");
  }
  if (has_axial) return;
  if (!has_e && !has_area) {
    section.fail(
        "missing the link stiffness: give axial_stiffness (N/m), or E (Pa) and area (m^2)");
  }
  (void)section.required("E");  // both are needed: names the missing one
  (void)section.required("area");
}

inline void check_non_zero(const YamlValue& map, const char* key, const Eigen::Vector3d& v) {
  if (auto value = map.optional(key)) {
    if (!(v.norm() > 1e-12)) value->fail("a non-zero vector", value->describe());
  }
}

// Runs the machine's own validation and turns its message into an InputError at `root`.
template <typename Design, typename Make>
void validate(const YamlValue& root, const Design& design, Make make) {
  try {
    (void)make(design);
  } catch (const std::invalid_argument& e) {
    root.fail(e.what());
  }
}

// The design a reader starts from: the model's defaults with the links' stiffness unset (the
// file gives it) and a rigid drive unless the file gives its stiffness.
template <typename Design>
Design reader_start() {
  Design d;
  d.stiffness = {0.0, 0.0, 0.0, 0.0};
  return d;
}

template <typename Design>
std::string markdown_of(Design d) {
  FieldDocs docs;
  describe_fields(docs, d);
  return docs.markdown();
}

/// The docs table of the generic form (io/machine/machine_file_leg_chain_generic.cpp).
std::string generic_fields_markdown();

}  // namespace pkmopt::leg_chain_fields
