// The machine-file keys of the solids checked against the legs (models/geometry/solid_bodies.hpp):
//
//   bodies:
//     platform: {radius: 0.30, z: [0, 0.04]}              # a disc plate, platform frame
//     base: {polygon: [[0.7, 0], [-0.35, 0.6], [-0.35, -0.6]], z: [-0.05, 0]}   # base frame
//     tool: {diameter: 0.12, from: [0, 0, 0], to: [0, 0, -0.30]}              # spindle
//
// Example (inside a describe_fields template):
//   describe_machine_bodies(f, d.bodies);
#pragma once

#include <string_view>

#include "io/format/field_list.hpp"
#include "models/geometry/solid_bodies.hpp"
#include "models/leg_chain/leg_chain.hpp"

namespace pkmopt {

/// `radius` or `polygon`, and `z`, of a plate in `frame` ("platform", "base").
template <class Fields>
void describe_plate(Fields& h, ConvexPrism& p, std::string_view radius_doc,
                    std::string_view polygon_doc, std::string_view z_doc) {
  h.field("radius", p.radius,
          {.min = 0, .min_exclusive = true, .zero_is_unset = true, .unit = "m", .doc = radius_doc});
  h.field("polygon", p.polygon, {.zero_is_unset = true, .unit = "m", .doc = polygon_doc});
  FieldRange z{p.z_min, p.z_max};
  h.field("z", z, {.required = true, .unit = "m", .doc = z_doc, .omit_when = [&p] {
                     return !p.present();
                   }});
}

/// The top-level `bodies` section (every key optional; they need the legs' shape).
template <class Fields>
void describe_machine_bodies(Fields& f, MachineBodies& b) {
  f.section(
      "bodies",
      {.doc = "solids checked against the legs' shape for the interference check (leg_clearance): "
              "each is checked against the leg bodies not jointed to it"},
      [&](auto& g) {
        g.section("platform",
                  {.doc = "the platform plate (platform frame), checked against the leg bodies on "
                          "the base side (a leg's cylinder, a crank)"},
                  [&](auto& h) {
                    describe_plate(h, b.platform,
                                   "a disc of this radius about the platform's z axis",
                                   "or a convex polygon [[x, y], ...] in the platform's x-y plane, "
                                   "vertices in order around it",
                                   "[z_min, z_max]: the plate's faces along the platform's z");
                  });
        g.section("base",
                  {.doc = "the base plate (base frame), checked against the leg bodies on the "
                          "platform side (a leg's rod, a delta's rods, a strut)"},
                  [&](auto& h) {
                    describe_plate(h, b.base, "a disc of this radius about the base's z axis",
                                   "or a convex polygon [[x, y], ...] in the base's x-y plane, "
                                   "vertices in order around it",
                                   "[z_min, z_max]: the plate's faces along the base's z");
                  });
        g.section("tool",
                  {.doc = "the tool or spindle as a cylinder (platform frame), checked against "
                          "every leg body"},
                  [&](auto& h) {
                    ToolBody& t = b.tool;
                    h.field("diameter", t.diameter,
                            {.min = 0,
                             .min_exclusive = true,
                             .zero_is_unset = true,
                             .unit = "m",
                             .doc = "outer diameter of the cylinder"});
                    const auto absent = [&t] { return !t.present(); };
                    h.field("from", t.from,
                            {.unit = "m", .doc = "one end of its axis", .omit_when = absent});
                    h.field("to", t.to,
                            {.unit = "m", .doc = "the other end of its axis", .omit_when = absent});
                  });
      });
}

/// The top-level keys of a leg-chain machine's link shapes: link_diameter, crank_diameter (models
/// with cranks), min_clearance and bodies (models/leg_chain/leg_chain.hpp, LinkShapes).
template <class Fields>
void describe_link_shapes(Fields& f, LinkShapes& s, bool cranks) {
  const FieldRule size{.min = 0, .min_exclusive = true, .zero_is_unset = true, .unit = "m"};
  FieldRule link = size;
  link.doc =
      "each strut or rod (each rod of a parallelogram pair) as a capsule of this diameter from "
      "joint centre to joint centre, for the interference check (leg_clearance); unset: not "
      "checked";
  f.field("link_diameter", s.link_diameter, link);
  if (cranks) {
    FieldRule crank = size;
    crank.doc = "each crank as a capsule of this diameter from its pivot to the elbow";
    f.field("crank_diameter", s.crank_diameter, crank);
  }
  f.field("min_clearance", s.min_clearance,
          {.min = 0,
           .unit = "m",
           .doc = "with a link shape: a pose is reachable only when the links' surfaces are at "
                  "least this far apart (leg_clearance >= min_clearance)",
           .omit_when = [&s] { return s.min_clearance == 0.0; }});
  describe_machine_bodies(f, s.bodies);
}

}  // namespace pkmopt
