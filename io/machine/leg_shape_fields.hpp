// The machine-file keys of a leg's outer shape (models/geometry/leg_interference.hpp), inside
// `legs`:
//
//   legs: {..., diameter: 0.08}                       # one capsule joint centre to joint centre
//   legs: {..., cylinder: {diameter: 0.1, length: 0.6}, rod: {diameter: 0.06}}
//   min_clearance: 0.005                              # top level, m, default 0
//
// Example (inside a describe_fields template):
//   f.section("legs", {...}, [&](auto& g) { describe_leg_shape(g, d.leg_shape); });
//   describe_min_clearance(f, d.min_clearance);
#pragma once

#include "io/format/field_list.hpp"
#include "models/geometry/leg_interference.hpp"

namespace pkmopt {

/// `diameter`, or `cylinder: {diameter, length}` with `rod: {diameter}` (every key optional).
template <class Fields>
void describe_leg_shape(Fields& g, LegShape& s) {
  const FieldRule size{.min = 0, .min_exclusive = true, .zero_is_unset = true, .unit = "m"};
  FieldRule diameter = size;
  diameter.doc =
      "the leg as one capsule (a cylinder with round ends) of this diameter from joint centre to "
      "joint centre, for the interference check (leg_clearance); unset: not checked";
  g.field("diameter", s.diameter, diameter);
  g.section("cylinder",
            {.doc = "the leg's cylinder on the base joint (instead of diameter), checked as a "
                    "capsule over its axis (conservative at its ends)"},
            [&](auto& h) {
              FieldRule d = size;
              d.doc = "outer diameter of the cylinder";
              h.field("diameter", s.cylinder_diameter, d);
              FieldRule l = size;
              l.doc = "length from the base joint centre along the leg";
              h.field("length", s.cylinder_length, l);
            });
  g.section("rod", {.doc = "the rod from the platform joint into the cylinder"}, [&](auto& h) {
    FieldRule d = size;
    d.doc = "outer diameter of the rod";
    h.field("diameter", s.rod_diameter, d);
  });
}

/// Top-level `min_clearance` (m, default 0).
template <class Fields>
void describe_min_clearance(Fields& f, double& min_clearance) {
  f.field("min_clearance", min_clearance,
          {.min = 0,
           .unit = "m",
           .doc = "with a leg shape: a pose is reachable only when the legs' surfaces are at least "
                  "this far apart (leg_clearance >= min_clearance)",
           .omit_when = [&min_clearance] { return min_clearance == 0.0; }});
}

}  // namespace pkmopt
