// Workspace bounds of the leg-chain machine: the search box of reachable TCP positions and the
// envelope (footprint) volume of the actuated points.
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <optional>
#include <vector>

#include "models/leg_chain/leg_chain.hpp"
#include "models/leg_chain/leg_chain_detail.hpp"

namespace pkmopt {
namespace {

using detail::kInf;
using detail::kPi;

}  // namespace

std::optional<Eigen::AlignedBox3d> LegChainMachine::workspace_search_box(
    const std::vector<Eigen::Matrix3d>& orientations) const {
  // Leg i keeps its platform point P_i within reach of the set of its actuated points:
  //   UPS: ball of radius q_max about a_i; PUS: within L_i of the guide segment;
  //   RUS: within r_i + L_i of the pivot. The TCP is P_i - R (b_i - tcp).
  Eigen::AlignedBox3d united;
  const int n = num_actuators();
  for (const Eigen::Matrix3d& R_in : orientations) {
    // The rotation the platform takes for R_in (projected for 3- and 4-DOF platforms).
    Pose asked{Eigen::Vector3d::Zero(), angles_from_rotation(R_in)};
    Eigen::Vector3d p_actual;
    Eigen::Matrix3d R;
    if (!resolve_pose(asked, p_actual, R) && design_.mobility == PlatformMobility::kPlanarLegs) {
      continue;
    }
    Eigen::AlignedBox3d box(Eigen::Vector3d::Constant(-kInf), Eigen::Vector3d::Constant(kInf));
    for (int i = 0; i < n; ++i) {
      const LegChainLeg& leg = design_.legs[static_cast<std::size_t>(i)];
      const Eigen::Vector3d offset = -R * platform_rel_.col(i);
      Eigen::AlignedBox3d leg_box;
      switch (leg.kind) {
        case LegKind::kUPS: {
          const Eigen::Vector3d reach = Eigen::Vector3d::Constant(leg.q_max);
          leg_box = Eigen::AlignedBox3d(leg.base_point - reach, leg.base_point + reach);
          break;
        }
        case LegKind::kPUS: {
          const Eigen::Vector3d reach = Eigen::Vector3d::Constant(leg.link_length);
          const Eigen::Vector3d a = leg.base_point + leg.q_min * leg.axis;
          const Eigen::Vector3d b = leg.base_point + leg.q_max * leg.axis;
          leg_box = Eigen::AlignedBox3d(a.cwiseMin(b) - reach, a.cwiseMax(b) + reach);
          break;
        }
        case LegKind::kRUS: {
          const Eigen::Vector3d reach =
              Eigen::Vector3d::Constant(leg.crank_length + leg.link_length);
          leg_box = Eigen::AlignedBox3d(leg.base_point - reach, leg.base_point + reach);
          break;
        }
      }
      leg_box.translate(offset);
      box = box.intersection(leg_box);
    }
    if (design_.mobility == PlatformMobility::kPlanarLegs && !box.isEmpty()) {
      // x and y are parasitic (the given ones are ignored): the box is the parasitic x, y at the
      // ends of the z range (one point for vertical leg planes).
      Eigen::AlignedBox3d planar;
      for (const double z : {box.min().z(), box.max().z()}) {
        asked.position.z() = z;
        if (resolve_pose(asked, p_actual, R)) planar.extend(p_actual);
      }
      if (planar.isEmpty()) continue;
      box.min().head<2>() = planar.min().head<2>();
      box.max().head<2>() = planar.max().head<2>();
    }
    if (!box.isEmpty()) united.extend(box);
    if (design_.mobility == PlatformMobility::kTranslational) break;
  }
  return united;
}

std::optional<double> LegChainMachine::envelope_volume() const {
  // Vertical cylinder about the centroid of the actuated points' reach: radius the largest
  // horizontal distance an actuated point reaches (stroke ends, crank circle), height the z
  // extent of those points plus the longest link (UPS: max_length).
  std::vector<Eigen::Vector3d> points;
  double link = 0.0;
  for (const LegChainLeg& leg : design_.legs) {
    switch (leg.kind) {
      case LegKind::kUPS:
        points.push_back(leg.base_point);
        link = std::max(link, leg.q_max);
        break;
      case LegKind::kPUS:
        points.push_back(leg.base_point + leg.q_min * leg.axis);
        points.push_back(leg.base_point + leg.q_max * leg.axis);
        link = std::max(link, leg.link_length);
        break;
      case LegKind::kRUS: {
        const Eigen::Vector3d n0 = leg.axis.cross(leg.crank_zero);
        for (int k = 0; k < 72; ++k) {
          const double a = 2.0 * kPi * k / 72.0;
          points.push_back(leg.base_point +
                           leg.crank_length * (std::cos(a) * leg.crank_zero + std::sin(a) * n0));
        }
        link = std::max(link, leg.link_length);
        break;
      }
    }
  }
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  for (const auto& p : points) centroid += p;
  centroid /= static_cast<double>(points.size());
  double radius = 0.0, zmin = kInf, zmax = -kInf;
  for (const auto& p : points) {
    radius = std::max(radius, (p - centroid).head<2>().norm());
    zmin = std::min(zmin, p.z());
    zmax = std::max(zmax, p.z());
  }
  return kPi * radius * radius * (zmax - zmin + link);
}

}  // namespace pkmopt
