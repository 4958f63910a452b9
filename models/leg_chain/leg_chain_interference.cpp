// The links' interference of a leg-chain machine (models/leg_chain/leg_chain.hpp, LinkShapes).
#include <array>
#include <cmath>
#include <span>
#include <stdexcept>
#include <string>

#include "models/leg_chain/leg_chain.hpp"
#include "models/leg_chain/leg_chain_detail.hpp"

namespace pkmopt {

namespace {

void require(bool ok, const std::string& message) {
  if (!ok) throw std::invalid_argument(message);
}

bool size_ok(double x) { return std::isfinite(x) && x >= 0.0; }

// At most a crank and two rods per leg, six legs.
using LinkBodies = std::array<Capsule, 18>;

// The link capsules of the kinematics in d; returns how many.
int link_bodies(const LegChainDesign& design, const LegChainData& d, LinkBodies& out) {
  const LinkShapes& shape = design.shapes;
  int n = 0;
  for (std::size_t i = 0; i < design.legs.size(); ++i) {
    const LegChainLeg& leg = design.legs[i];
    const int index = static_cast<int>(i);
    const Eigen::Vector3d c = d.c.col(index);
    const Eigen::Vector3d P = d.position + d.r.col(index);
    if (leg.kind == LegKind::kRUS && shape.crank_diameter > 0.0)
      out[static_cast<std::size_t>(n++)] = {leg.base_point, c,    0.5 * shape.crank_diameter,
                                            index,          true, false};
    if (!(shape.link_diameter > 0.0)) continue;
    const double r = 0.5 * shape.link_diameter;
    // A UPS leg runs from its base joint; a strut or rod from its carriage or elbow.
    const bool on_base = leg.kind == LegKind::kUPS;
    if (leg.parallelogram_width > 0.0) {
      const Eigen::Vector3d h = 0.5 * leg.parallelogram_width * leg.parallelogram_axis;
      out[static_cast<std::size_t>(n++)] = {c + h, P + h, r, index, on_base, true};
      out[static_cast<std::size_t>(n++)] = {c - h, P - h, r, index, on_base, true};
    } else {
      out[static_cast<std::size_t>(n++)] = {c, P, r, index, on_base, true};
    }
  }
  return n;
}

}  // namespace

void check_link_shapes(const LegChainDesign& design) {
  const LinkShapes& s = design.shapes;
  require(size_ok(s.link_diameter), "link_diameter must be a finite number >= 0 (m)");
  require(size_ok(s.crank_diameter), "crank_diameter must be a finite number >= 0 (m)");
  require(size_ok(s.min_clearance), "min_clearance must be a finite number >= 0 (m)");
  bool crank = false;
  for (const LegChainLeg& leg : design.legs) crank = crank || leg.kind == LegKind::kRUS;
  require(!(s.crank_diameter > 0.0) || crank,
          "crank_diameter needs a crank (RUS) leg; this machine has none");
  check_machine_bodies(s.bodies);
  bool cranks = false, links = false;  // bodies not jointed to the platform, resp. the base
  for (const LegChainLeg& leg : design.legs) {
    cranks = cranks || (leg.kind == LegKind::kRUS && s.crank_diameter > 0.0);
    links = links || (leg.kind != LegKind::kUPS && s.link_diameter > 0.0);
  }
  check_solids_have_leg_bodies(s.bodies, cranks, links,
                               "the platform plate sees the cranks (crank_diameter), the base "
                               "plate the struts and rods on carriages or cranks (link_diameter)");
  require(!s.bodies.present() || s.present(),
          "bodies are checked against the links: give link_diameter (or crank_diameter)");
}

Clearance LegChainMachine::clearance_from_kinematics(const LegChainData& d) const {
  if (!design_.shapes.present() || !d.ik_ok) return {};
  LinkBodies bodies;
  const int n = link_bodies(design_, d, bodies);
  const std::span<const Capsule> links(bodies.data(), static_cast<std::size_t>(n));
  Clearance c = pkmopt::leg_clearance(links);
  if (design_.shapes.bodies.present())
    body_clearance(links, design_.shapes.bodies, d.rotation, d.position - d.rotation * design_.tcp,
                   c);
  return c;
}

bool LegChainMachine::links_apart(const LegChainData& d) const {
  if (!design_.shapes.present()) return true;
  if (!d.ik_ok) return false;
  LinkBodies bodies;
  const int n = link_bodies(design_, d, bodies);
  const std::span<const Capsule> links(bodies.data(), static_cast<std::size_t>(n));
  const double need = design_.shapes.min_clearance;
  return legs_apart(links, need) && (!design_.shapes.bodies.present() ||
                                     bodies_apart(links, design_.shapes.bodies, d.rotation,
                                                  d.position - d.rotation * design_.tcp, need));
}

Clearance LegChainMachine::leg_clearance(const Pose& pose) const {
  if (!design_.shapes.present()) return {};
  const auto data = make_data();
  auto& d = data_of<LegChainData>(*data);
  compute_kinematics(d, pose);
  return clearance_from_kinematics(d);
}

}  // namespace pkmopt
