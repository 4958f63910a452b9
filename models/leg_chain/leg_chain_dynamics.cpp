// The dynamics of a leg-chain machine (models/leg_chain/leg_chain.hpp, docs/dynamics.md): its legs'
// moving bodies at a pose, the TCP mass matrix, the gravity and inertia wrench of the inverse
// dynamics, and the natural frequencies on the platform's degrees of freedom.
#include <Eigen/Cholesky>
#include <vector>

#include "models/dynamics/machine_dynamics.hpp"
#include "models/leg_chain/leg_chain.hpp"

namespace pkmopt {

namespace {

LegBodyKind body_kind(const LegChainLeg& leg) {
  return leg.kind == LegKind::kUPS   ? LegBodyKind::kTelescopic
         : leg.kind == LegKind::kPUS ? LegBodyKind::kCarriage
                                     : LegBodyKind::kCrank;
}

}  // namespace

double LegChainMachine::moving_mass() const {
  std::vector<LegBodyKind> kinds;
  for (const LegChainLeg& leg : design_.legs) kinds.push_back(body_kind(leg));
  return pkmopt::moving_mass(design_.masses, kinds);
}

std::vector<LegPoints> LegChainMachine::leg_points(const LegChainData& d) const {
  // The legs' bodies from the joint points of the pose: UPS base joint, PUS carriage joint,
  // RUS elbow (d.c), the platform joints P_i = p + r_i.
  std::vector<LegPoints> legs(design_.legs.size());
  for (std::size_t i = 0; i < legs.size(); ++i) {
    const LegChainLeg& leg = design_.legs[i];
    const int j = static_cast<int>(i);
    LegPoints& p = legs[i];
    p.kind = body_kind(leg);
    p.joint = d.c.col(j);
    p.platform = d.position + d.r.col(j);
    p.axis = leg.axis.normalized();
    p.pivot = leg.base_point;
  }
  return legs;
}

NaturalModes LegChainMachine::natural_modes_of(const LegChainData& d, bool shapes) const {
  const Matrix6d M =
      tcp_mass_matrix(design_.masses, d.rotation, design_.tcp, leg_points(d), d.position);
  // On the DOF: M_dof = T^T M T, C_dof = T^+ C T^+T (exact for the axial model, C = T C_dof T^T;
  // with link compliance the constrained directions are condensed out).
  const Eigen::MatrixXd T = d.T;
  const Eigen::MatrixXd T_plus = (T.transpose() * T).ldlt().solve(T.transpose());
  const Eigen::MatrixXd M_dof = T.transpose() * M * T;
  const Eigen::MatrixXd C_dof = T_plus * d.matrices.compliance * T_plus.transpose();
  return natural_modes(C_dof, M_dof, shapes);
}

bool LegChainMachine::mode_shapes(MachineData& data, const Pose& pose, PoseModes& out) const {
  if (!design_.masses.present) return false;
  auto& d = data_of<LegChainData>(data);
  const bool compliance_metrics = d.compliance_metrics;
  d.compliance_metrics = true;
  PoseMetrics metrics;
  analyze(d, pose, Wrench::Zero(), metrics);
  d.compliance_metrics = compliance_metrics;
  if (!metrics.reachable || metrics.singular) return false;
  const NaturalModes modes = natural_modes_of(d, true);
  if (!modes.ok) return false;
  out.frequencies = modes.frequencies;
  out.shapes = d.T * modes.shapes;  // DOF coordinates -> the TCP twist
  return true;
}

bool LegChainMachine::mass_matrix(MachineData& data, const Pose& pose, Matrix6d& M) const {
  if (!design_.masses.present) return false;
  auto& d = data_of<LegChainData>(data);
  compute_kinematics(d, pose);
  if (!d.ik_ok || !d.pose_ok || d.constraint_singular) return false;
  M = tcp_mass_matrix(design_.masses, d.rotation, design_.tcp, leg_points(d), d.position);
  return true;
}

bool LegChainMachine::dynamic_wrench(MachineData& data, const Pose& pose, const Vector6d& xi,
                                     const Vector6d& xi_dot, Wrench& w_dyn) const {
  Eigen::Vector3d net_force;
  return carried_dynamics(data, pose, xi, xi_dot, design_.masses.gravity, w_dyn, net_force,
                          nullptr);
}

bool LegChainMachine::carried_dynamics(MachineData& data, const Pose& pose, const Vector6d& xi,
                                       const Vector6d& xi_dot, const Eigen::Vector3d& gravity,
                                       Wrench& w_dyn, Eigen::Vector3d& net_force,
                                       Eigen::Matrix<double, 9, 9>* kinetic) const {
  if (!design_.masses.present) return false;
  auto& d = data_of<LegChainData>(data);
  compute_kinematics(d, pose);
  if (!d.ik_ok || !d.pose_ok || d.constraint_singular) return false;
  // The platform moves only along its own twists: project xi and xi_dot on the columns of T.
  const Eigen::MatrixXd T = d.T;
  const Eigen::MatrixXd projector = T * (T.transpose() * T).ldlt().solve(T.transpose());
  const Vector6d xi_p = projector * xi, xi_dot_p = projector * xi_dot;
  const std::vector<LegPoints> legs = leg_points(d);
  const MassModel& m = design_.masses;
  w_dyn =
      pkmopt::dynamic_wrench(m, d.rotation, design_.tcp, legs, d.position, xi_p, xi_dot_p, gravity);
  net_force =
      net_dynamic_force(m, d.rotation, design_.tcp, legs, d.position, xi_p, xi_dot_p, gravity);
  if (kinetic) *kinetic = carried_mass_matrix(m, d.rotation, design_.tcp, legs, d.position);
  return true;
}

}  // namespace pkmopt
