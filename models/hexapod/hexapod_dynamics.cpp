// The hexapod's dynamics (models/hexapod/hexapod.hpp): the legs' joint points, the TCP mass matrix,
// the natural modes, and the gravity and inertia wrench (models/dynamics/machine_dynamics.hpp).
#include <vector>

#include "models/dynamics/machine_dynamics.hpp"
#include "models/hexapod/hexapod.hpp"

namespace pkmopt {

namespace {

// The legs' joint points for the TCP pose (p, R): a_i and P_i = p + R (b_i - tcp).
std::vector<LegPoints> hexapod_leg_points(const HexapodDesign& design,
                                          const Eigen::Matrix<double, 3, 6>& platform_rel,
                                          const Eigen::Vector3d& p, const Mat3<double>& R) {
  std::vector<LegPoints> legs(6);
  for (int i = 0; i < 6; ++i) {
    legs[static_cast<std::size_t>(i)] = {.kind = LegBodyKind::kTelescopic,
                                         .joint = design.base_joints.col(i),
                                         .platform = p + R * platform_rel.col(i)};
  }
  return legs;
}

}  // namespace

std::vector<LegPoints> Hexapod::leg_points(const Pose& pose) const {
  return hexapod_leg_points(design_, platform_rel_, pose.position,
                            rotation_zyx<double>(pose.angles));
}

Matrix6d Hexapod::mass_matrix(const Pose& pose) const {
  const Mat3<double> R = rotation_zyx<double>(pose.angles);
  return tcp_mass_matrix(design_.masses, R, design_.tcp,
                         hexapod_leg_points(design_, platform_rel_, pose.position, R),
                         pose.position);
}

bool Hexapod::mass_matrix(MachineData& /*data*/, const Pose& pose, Matrix6d& M) const {
  if (!design_.masses.present) return false;
  M = mass_matrix(pose);
  return true;
}

bool Hexapod::mode_shapes(MachineData& data, const Pose& pose, PoseModes& out) const {
  if (!design_.masses.present) return false;
  auto& d = data_of<HexapodData>(data);
  const bool compliance_metrics = d.compliance_metrics;
  d.compliance_metrics = true;
  PoseMetrics metrics;
  compute_metrics(d, pose, Wrench::Zero(), metrics);
  d.compliance_metrics = compliance_metrics;
  if (!metrics.reachable || metrics.singular) return false;
  const NaturalModes modes = natural_modes(Eigen::MatrixXd(d.matrices.compliance),
                                           Eigen::MatrixXd(mass_matrix(pose)), true);
  if (!modes.ok) return false;
  out.frequencies = modes.frequencies;
  out.shapes = modes.shapes;  // the DOF are the TCP twist
  return true;
}

bool Hexapod::dynamic_wrench(MachineData& /*data*/, const Pose& pose, const Vector6d& xi,
                             const Vector6d& xi_dot, Wrench& w_dyn) const {
  if (!design_.masses.present) return false;
  const Mat3<double> R = rotation_zyx<double>(pose.angles);
  const std::vector<LegPoints> legs = hexapod_leg_points(design_, platform_rel_, pose.position, R);
  for (const LegPoints& leg : legs) {
    if ((leg.platform - leg.joint).norm() <= 0.0) return false;  // a leg of zero length
  }
  w_dyn = pkmopt::dynamic_wrench(design_.masses, R, design_.tcp, legs, pose.position, xi, xi_dot);
  return true;
}

bool Hexapod::carried_dynamics(MachineData& /*data*/, const Pose& pose, const Vector6d& xi,
                               const Vector6d& xi_dot, const Eigen::Vector3d& gravity,
                               Wrench& w_dyn, Eigen::Vector3d& net_force,
                               Eigen::Matrix<double, 9, 9>* kinetic) const {
  if (!design_.masses.present) return false;
  const Mat3<double> R = rotation_zyx<double>(pose.angles);
  const std::vector<LegPoints> legs = hexapod_leg_points(design_, platform_rel_, pose.position, R);
  for (const LegPoints& leg : legs) {
    if ((leg.platform - leg.joint).norm() <= 0.0) return false;
  }
  const MassModel& m = design_.masses;
  w_dyn = pkmopt::dynamic_wrench(m, R, design_.tcp, legs, pose.position, xi, xi_dot, gravity);
  net_force = net_dynamic_force(m, R, design_.tcp, legs, pose.position, xi, xi_dot, gravity);
  if (kinetic) *kinetic = carried_mass_matrix(m, R, design_.tcp, legs, pose.position);
  return true;
}

}  // namespace pkmopt
