// Link compliance of the leg-chain machines by the virtual-joint method
// (models/stiffness/virtual_joint.hpp, docs/stiffness.md "Link compliance"): the checks of the
// design's link sections and parallelogram widths, the VjmLeg of every leg at a pose, and the
// compliance metrics of analyze from the legs' summed 6x6 stiffness at the TCP.
//
// Each leg, from the base to the platform, at the pose's kinematics (LegChainData):
//   actuator   a virtual spring with the actuator side's compliance c_act (1/actuator_stiffness +
//              the drive train at q): along the rod s (UPS), along the guide u (PUS), about the
//              crank axis w through the pivot (RUS; rad/(N*m));
//   crank      RUS with a crank_section: a beam from the pivot to the elbow (local y = w);
//   link       planar legs: the revolute joint about n at the link's foot (carriage, elbow or base
//              joint), the strut a beam (local y = n), a spherical joint at the platform point;
//              other single links with a link_section: universal joint at the foot, beam,
//              spherical joint (a U-S link carries only its axial force: the bending adds
//              nothing, which the tests check);
//              pairs (rods = 2, parallelogram_width w > 0): two rods with ball joints at both
//              ends, c +- w/2 e to P +- w/2 e (e the bars' direction), each of axial compliance
//              L/(E A) + its joints;
//              otherwise a two-force member from the foot to the platform point with the link's
//              axial compliance (rods and joints), as in the axial model;
//   joints     the joints' axial compliance: springs along s (per rod for pairs).
// `rods` equal links on one line (no width) share the load: the section's E and G times rods.
// analyze eliminates the passive joints in closed form (VjmLeg::stiffness_for_wrenches): the leg
// transmits the forces through P along s and n (planar legs), along s (single links), or along
// the two rods' lines (pairs); vjm_leg also describes the passive joints for
// VjmLeg::stiffness(), the general elimination, which the tests compare.
#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <array>
#include <cmath>
#include <stdexcept>
#include <string>

#include "models/core/require.hpp"
#include "models/leg_chain/leg_chain.hpp"
#include "models/leg_chain/leg_chain_detail.hpp"
#include "models/stiffness/compliance_metrics.hpp"
#include "models/stiffness/virtual_joint.hpp"

namespace pkmopt {

using detail::kInf;
using detail::VecM;

namespace {

bool section_ok(const BeamSection& s) {
  for (const double v : {s.E, s.G, s.A, s.Iy, s.Iz, s.J})
    if (!(std::isfinite(v) && v > 0.0)) return false;
  return true;
}

// The joints' axial compliance along one rod (m/N).
double joint_compliance(const LegChainLeg& leg) {
  double c = 0.0;
  if (leg.base_joint_stiffness > 0.0) c += 1.0 / leg.base_joint_stiffness;
  if (leg.platform_joint_stiffness > 0.0) c += 1.0 / leg.platform_joint_stiffness;
  return c;
}

// The link's own axial compliance of one rod of length L (m/N): the section, axial_stiffness
// shared by the rods, or E and area.
double rod_compliance(const LegChainLeg& leg, double L) {
  if (leg.link_section) return L / (leg.link_section->E * leg.link_section->A);
  if (leg.axial_stiffness > 0.0) return leg.rods / leg.axial_stiffness;
  return L / (leg.E * leg.area);
}

// C = K^-1 of a symmetric positive definite 6x6 K by its Cholesky factor (C = L^-T L^-1, exactly
// symmetric); false when a pivot is not positive (K not positive definite).
bool spd_inverse(const Matrix6d& K, Matrix6d& C) {
  double L[6][6] = {};
  for (int j = 0; j < 6; ++j) {
    double d = K(j, j);
    for (int k = 0; k < j; ++k) d -= L[j][k] * L[j][k];
    if (!(d > 0.0) || !std::isfinite(d)) return false;
    L[j][j] = std::sqrt(d);
    for (int i = j + 1; i < 6; ++i) {
      double v = K(i, j);
      for (int k = 0; k < j; ++k) v -= L[i][k] * L[j][k];
      L[i][j] = v / L[j][j];
    }
  }
  double Li[6][6] = {};  // L^-1, lower triangular
  for (int j = 0; j < 6; ++j) {
    Li[j][j] = 1.0 / L[j][j];
    for (int i = j + 1; i < 6; ++i) {
      double v = 0.0;
      for (int k = j; k < i; ++k) v += L[i][k] * Li[k][j];
      Li[i][j] = -v / L[i][i];
    }
  }
  for (int c = 0; c < 6; ++c) {
    for (int r = c; r < 6; ++r) {
      double v = 0.0;
      for (int k = r; k < 6; ++k) v += Li[k][r] * Li[k][c];
      C(r, c) = C(c, r) = v;
    }
  }
  return C.allFinite();
}

// The section of `rods` equal links on one line.
BeamSection shared_section(const BeamSection& s, int rods) {
  BeamSection out = s;
  out.E *= rods;
  out.G *= rods;
  return out;
}

}  // namespace

void LegChainMachine::validate_link_compliance() {
  const int n = num_actuators();
  const PlatformMobility mobility = design_.mobility;
  int widths = 0, pairs = 0;
  for (int i = 0; i < n; ++i) {
    LegChainLeg& leg = design_.legs[static_cast<std::size_t>(i)];
    const std::string name = "leg " + std::to_string(i + 1) + ": ";
    require(!leg.link_section || section_ok(*leg.link_section),
            name + "link_section: E, G, A, Iy, Iz and J must be finite numbers > 0");
    require(!leg.crank_section || leg.kind == LegKind::kRUS,
            name + "a crank_section needs a RUS leg");
    require(!leg.crank_section || section_ok(*leg.crank_section),
            name + "crank_section: E, G, A, Iy, Iz and J must be finite numbers > 0");
    require(std::isfinite(leg.parallelogram_width) && leg.parallelogram_width >= 0.0,
            name + "parallelogram_width must be a finite number >= 0");
    require(leg.parallelogram_axis.allFinite(), name + "parallelogram_axis must be finite");
    if (leg.rods == 2) ++pairs;
    if (leg.link_section || leg.crank_section || leg.parallelogram_width > 0.0) vjm_ = true;
    if (!(leg.parallelogram_width > 0.0)) continue;
    ++widths;
    require(leg.rods == 2, name + "parallelogram_width needs rods = 2 (a parallelogram pair)");
    require(leg.kind != LegKind::kUPS, name + "parallelogram_width needs a PUS or RUS leg");
    require(
        mobility == PlatformMobility::kTranslational || mobility == PlatformMobility::kSchoenflies,
        name + "parallelogram_width needs a translational or schoenflies platform");
    Eigen::Vector3d& e = leg.parallelogram_axis;
    const Eigen::Vector3d required = leg.kind == LegKind::kRUS ? leg.axis
                                     : mobility == PlatformMobility::kSchoenflies
                                         ? design_.rotation_axis
                                         : Eigen::Vector3d::Zero();
    if (e.isZero()) e = required;
    require(e.norm() > 1e-12,
            name + "parallelogram_axis is needed: the direction of the pair's bars (base frame)");
    e.normalize();
    require(required.isZero() || e.cross(required).norm() <= 1e-9,
            name + "parallelogram_axis must be parallel to " +
                (leg.kind == LegKind::kRUS ? "the crank axis" : "the rotation axis"));
  }
  if (!vjm_) return;
  switch (mobility) {
    case PlatformMobility::kSixDof:
      vjm_full_ = true;
      break;
    case PlatformMobility::kPlanarLegs:
      for (const LegChainLeg& leg : design_.legs)
        require(leg.link_section.has_value(),
                "planar legs with link compliance: every leg needs a link_section (the strut's "
                "bending carries its revolute joint's constraint)");
      vjm_full_ = true;
      break;
    case PlatformMobility::kTranslational:
      require(widths == 0 || widths == n, "parallelogram_width: on every leg or on none");
      vjm_full_ = widths == n;
      break;
    case PlatformMobility::kSchoenflies:
      require(widths == 0 || widths == pairs,
              "parallelogram_width: on every pair (rods = 2) or on none");
      vjm_full_ = widths > 0;
      break;
  }
}

void LegChainMachine::vjm_leg(const LegChainData& d, int i, VjmLeg& out,
                              TransmittedWrenches& wrenches, bool passive_joints) const {
  const LegChainLeg& leg = design_.legs[static_cast<std::size_t>(i)];
  const Eigen::Vector3d c = d.c.col(i), s = d.s.col(i);
  const Eigen::Vector3d P = d.position + d.r.col(i);
  const double length = leg.kind == LegKind::kUPS ? d.q(i) : leg.link_length;
  const double c_act = d.actuator_compliance(i);
  const double c_joint = joint_compliance(leg);
  // A unit force along the line through `point` along `dir`, at the TCP.
  const auto line = [&d](const Eigen::Vector3d& point, const Eigen::Vector3d& dir) {
    Vector6d w;
    w << dir, (point - d.position).cross(dir);
    return w;
  };
  out.clear();
  switch (leg.kind) {
    case LegKind::kUPS:
      if (c_act > 0.0) out.add_spring(c, s, false, c_act);
      break;
    case LegKind::kPUS:
      if (c_act > 0.0) out.add_spring(c, leg.axis, false, c_act);
      break;
    case LegKind::kRUS:
      if (c_act > 0.0) out.add_spring(leg.base_point, leg.axis, true, c_act);
      if (leg.crank_section)
        out.add_beam(*leg.crank_section, leg.crank_length, leg.base_point, c - leg.base_point,
                     leg.axis);
      break;
  }
  if (leg.parallelogram_width > 0.0) {
    // Two rods with ball joints at both ends, the bars rigid: they transmit the forces along
    // their lines, each meeting its own axial compliance.
    const Eigen::Vector3d h = 0.5 * leg.parallelogram_width * leg.parallelogram_axis;
    const double c_rod = rod_compliance(leg, length) + c_joint;
    const std::array<TwoForceMember, 2> rods{TwoForceMember{c + h, P + h, 1.0 / c_rod},
                                             TwoForceMember{c - h, P - h, 1.0 / c_rod}};
    if (passive_joints) out.add_two_force_members(rods);
    wrenches.basis.resize(6, 2);
    wrenches.compliance.setZero(2, 2);
    for (int j = 0; j < 2; ++j) {
      const TwoForceMember& rod = rods[static_cast<std::size_t>(j)];
      wrenches.basis.col(j) = line(rod.b, (rod.b - rod.a).normalized());
      wrenches.compliance(j, j) = c_rod;
    }
    return;
  }
  const double line_joints = c_joint / leg.rods;
  if (design_.mobility == PlatformMobility::kPlanarLegs || leg.link_section) {
    // A beam from the foot c to the platform point, a spherical joint at P, and at the foot the
    // revolute joint about n (planar legs: the leg transmits the forces through P along s and n)
    // or a universal joint (the force along s only).
    const bool planar = design_.mobility == PlatformMobility::kPlanarLegs;
    const Eigen::Vector3d y = planar ? leg.plane_normal : s.unitOrthogonal();
    out.add_beam(shared_section(*leg.link_section, leg.rods), length, c, s, y);
    if (line_joints > 0.0) out.add_spring(c, s, false, line_joints);
    if (passive_joints) {
      if (planar) {
        out.add_revolute(c, y);
      } else {
        out.add_universal(c, y, s.cross(y));
      }
      out.add_spherical(P);
    }
    wrenches.basis.resize(6, planar ? 2 : 1);
    wrenches.basis.col(0) = line(P, s);
    if (planar) wrenches.basis.col(1) = line(P, y);
    wrenches.compliance.resize(0, 0);
    return;
  }
  // A two-force member with the link's axial compliance (rods and joints).
  const double c_line = rod_compliance(leg, length) / leg.rods + line_joints;
  if (passive_joints) out.add_two_force_member(c, P, 1.0 / c_line);
  wrenches.basis.resize(6, 1);
  wrenches.basis.col(0) = line(P, s);
  wrenches.compliance.setConstant(1, 1, c_line);
}

bool LegChainMachine::vjm_stiffness(const LegChainData& d, Matrix6d& K) const {
  K.setZero();
  VjmLeg leg;
  TransmittedWrenches wrenches;
  try {
    for (int i = 0; i < num_actuators(); ++i) {
      vjm_leg(d, i, leg, wrenches, false);
      const LegCompliance k = leg.stiffness_for_wrenches(d.position, wrenches);
      if (k.rigid) return false;
      K += k.stiffness;
    }
  } catch (const std::invalid_argument&) {
    return false;  // a zero rod or axis at this pose
  }
  return K.allFinite();
}

bool LegChainMachine::compute_vjm_metrics(LegChainData& d, const VecM& f, const Wrench& wrench,
                                          PoseMetrics& out) const {
  Matrix6d K;
  if (!vjm_stiffness(d, K)) return false;
  Matrix6d C6;
  DofMatrix C_dof;
  if (vjm_full_) {
    if (!spd_inverse(K, C6)) return false;
  } else {
    // The orientation held by the mobility (parallelograms without widths): on the DOF.
    const DofMatrix K_dof = d.T.transpose() * K * d.T;
    const Eigen::LLT<DofMatrix> llt(K_dof);
    if (llt.info() != Eigen::Success) return false;
    C_dof = llt.solve(DofMatrix::Identity(K_dof.rows(), K_dof.cols()));
    C_dof = 0.5 * (C_dof + C_dof.transpose()).eval();
    C6 = d.T * C_dof * d.T.transpose();
    if (!C6.allFinite()) return false;
  }
  const Eigen::Matrix3d Ctt = C6.topLeftCorner<3, 3>();
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig3;
  eig3.computeDirect(Ctt, Eigen::EigenvaluesOnly);
  const double c_max = eig3.eigenvalues()(2);
  out.stiffness_min = c_max > 0.0 ? 1.0 / c_max : kInf;
  d.compliance_tt = Ctt;
  if (!d.compliance_metrics) return true;
  fill_compliance_metrics(C6, wrench, out, d.matrices);
  const Matrix6d G6 = full_twist_geometric_stiffness(d, f, wrench);
  if (vjm_full_) {
    out.stiffness_min_loaded = loaded_stiffness_min(C6, G6, &d.matrices.loaded_compliance_tt);
  } else {
    const DofMatrix G_dof = d.T.transpose() * G6 * d.T;
    out.stiffness_min_loaded =
        loaded_stiffness_min(C_dof, G_dof, d.T, &d.matrices.loaded_compliance_tt);
  }
  return true;
}

}  // namespace pkmopt
