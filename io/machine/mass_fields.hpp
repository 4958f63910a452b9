// The field list of a machine file's mass model (models/dynamics/mass_model.hpp, docs/dynamics.md):
//
//   masses:
//     platform: {mass: 45.0, centre_of_mass: [0, 0, -0.05], inertia: [1.2, 1.2, 2.0, 0, 0, 0]}
//     legs:
//       cylinder: {mass: 6.0, centre: 0.2, inertia: 0.08}   # UPS legs: from the base joint
//       rod: {mass: 3.0, centre: 0.25, inertia: 0.05}       # from the platform joint
//   gravity: [0, 0, -9.81]
//
// Which leg bodies a model has (`bodies`): UPS cylinder and rod, PUS carriage and link, RUS crank
// and link; the reader rejects the others like any unknown key. read_mass_fields runs the model's
// checks (a positive mass, a positive definite inertia) with the error at `masses`.
//
// Example (inside a model's describe_fields):
//   MassFields masses{d.masses, kTelescopicBodies};
//   describe_mass_section(f, masses);
//   ...
//   check_mass_fields(root, d.masses);  // after reading
#pragma once

#include <array>
#include <stdexcept>
#include <string>
#include <type_traits>

#include "io/format/field_list.hpp"
#include "io/format/yaml_reader.hpp"
#include "models/dynamics/mass_model.hpp"

namespace pkmopt {

/// The leg bodies a model's legs have.
struct LegBodies {
  bool telescopic = false;  ///< UPS: cylinder, rod
  bool carriage = false;    ///< PUS: carriage, link
  bool crank = false;       ///< RUS: crank, link
};
inline constexpr LegBodies kTelescopicBodies{.telescopic = true};
inline constexpr LegBodies kCarriageBodies{.carriage = true};
inline constexpr LegBodies kCrankBodies{.crank = true};
inline constexpr LegBodies kAllBodies{.telescopic = true, .carriage = true, .crank = true};

/// The mass model of a machine file with the platform's inertia as written.
struct MassFields {
  MassModel& model;
  LegBodies bodies;
  std::array<double, 6> inertia{};
};

/// `masses:` {platform, legs} and `gravity`, written only when the model is present.
template <class Fields>
void describe_mass_section(Fields& f, MassFields& m) {
  m.inertia = inertia_components(m.model.platform.inertia);
  const FieldRule non_negative{.min = 0};
  auto rule = [&](std::string_view unit, std::string_view doc) {
    FieldRule r = non_negative;
    r.unit = unit;
    r.doc = doc;
    r.zero_is_unset = true;
    return r;
  };
  auto link = [&](auto& g, const char* key, LinkMass& body, std::string_view from,
                  std::string_view inertia_doc) {
    g.section(key, {}, [&](auto& h) {
      h.field("mass", body.mass, rule("kg", "its mass"));
      h.field("centre", body.centre, rule("m", from));
      h.field("inertia", body.inertia, rule("kg·m²", inertia_doc));
    });
  };
  const std::string_view perpendicular =
      "moment of inertia about its centre of mass, for turns perpendicular to the link (a thin "
      "rod: m·l²/12)";
  f.section("masses",
            {.doc = "the moving masses (docs/dynamics.md); natural frequencies and dynamic forces "
                    "need them",
             .omit_when = [&m] { return !m.model.present; }},
            [&](auto& g) {
              g.section("platform", {.required = true}, [&](auto& h) {
                h.field("mass", m.model.platform.mass,
                        {.min = 0,
                         .min_exclusive = true,
                         .required = true,
                         .unit = "kg",
                         .doc = "platform with spindle, tool holder and tool"});
                h.field("centre_of_mass", m.model.platform.centre_of_mass,
                        {.unit = "m", .doc = "in the platform frame"});
                h.field("inertia", m.inertia,
                        {.required = true,
                         .unit = "kg·m²",
                         .doc = "[Ixx, Iyy, Izz, Ixy, Ixz, Iyz]: the inertia tensor's entries "
                                "about the centre of mass, platform axes"});
              });
              g.section("legs", {.doc = "the moving bodies of every leg"}, [&](auto& h) {
                if (m.bodies.telescopic) {
                  link(h, "cylinder", m.model.legs.cylinder,
                       "UPS: centre of mass from the base joint along the leg", perpendicular);
                  link(h, "rod", m.model.legs.rod,
                       "UPS: centre of mass from the platform joint along the leg", perpendicular);
                }
                if (m.bodies.carriage) {
                  h.section("carriage", {}, [&](auto& k) {
                    k.field("mass", m.model.legs.carriage,
                            rule("kg", "PUS: the carriage on its guide"));
                  });
                }
                if (m.bodies.crank) {
                  link(h, "crank", m.model.legs.crank,
                       "RUS: centre of mass from the pivot along the crank",
                       "moment of inertia about its centre of mass, about the crank axis");
                }
                if (m.bodies.carriage || m.bodies.crank) {
                  link(h, "link", m.model.legs.link,
                       "PUS: from the carriage joint; RUS: from the elbow (both rods of a pair "
                       "together)",
                       perpendicular);
                }
              });
              if constexpr (std::is_same_v<std::decay_t<decltype(g)>, FieldReader>) {
                m.model.platform.inertia = inertia_tensor(m.inertia);
                m.model.present = true;
              }
            });
  f.field("gravity", m.model.gravity,
          {.unit = "m/s²",
           .default_text = "[0, 0, -9.81]",
           .doc = "base frame (with masses)",
           .omit_when = [&m] {
             return !m.model.present || m.model.gravity == Eigen::Vector3d(0, 0, -9.81);
           }});
}

/// After the list has read `root` into `model`: the model's checks (InputError at `masses`);
/// `gravity` without `masses` is an error at `gravity`.
inline void check_mass_fields(const YamlValue& root, const MassModel& model) {
  const std::optional<YamlValue> section = root.optional("masses");
  if (!section) {
    if (auto g = root.optional("gravity")) g->fail("no gravity without masses (it acts on them)");
    return;
  }
  try {
    check_mass_model(model, "");
  } catch (const std::invalid_argument& e) {
    section->fail(e.what());
  }
}

}  // namespace pkmopt
