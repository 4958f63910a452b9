// Rigid-body dynamics of a parallel machine at a pose (docs/dynamics.md): the Cartesian mass
// matrix at the TCP, the wrench equivalent to gravity and inertia, and the undamped natural
// frequencies of the rigid platform on the elastic mechanism.
//
// Twist and its rate: xi = [v; omega] (TCP velocity, angular velocity; base axes), xi_dot =
// [a; alpha] its time derivative (the TCP's acceleration and the angular acceleration).
//
// Mass matrix: kinetic energy T = 1/2 xi^T M xi of every moving body,
//   M = M_platform + sum_i T_i^T M_P,i T_i,   T_i = [I, -[r_i]x] (r_i = P_i - TCP),
//   M_platform = [m I, -m [rho]x; m [rho]x, I_R - m [rho]x [rho]x],
// rho = R (centre_of_mass - tcp), I_R = R I R^T, M_P,i the leg's 3x3 mass matrix on the velocity
// of its platform point (models/dynamics/leg_dynamics.hpp).
//
// Gravity and inertia wrench at the TCP (virtual power):
//   w_dyn = [f; rho x f - I_R alpha - omega x I_R omega] + sum_i [f_P,i; r_i x f_P,i],
//   f = m (g - a_c), a_c = a + alpha x rho + omega x (omega x rho), and f_P,i the legs' forces
//   at P_i for v_P = v + omega x r_i, a_P = a + alpha x r_i + omega x (omega x r_i).
// The actuators then balance J^T tau_dyn = w + w_dyn (w the external wrench on the tool): the
// machine's static force solve with w + w_dyn.
//
// Natural frequencies: det(K - omega^2 M) = 0 on the platform's DOF twists (T the DOF basis,
// xi = T xi_dof, M_dof = T^T M T, C_dof = T^+ C T^+^T the compliance on the DOF). With the
// Cholesky factor M_dof = L L^T the eigenvalues mu of the symmetric S = L^T C_dof L are
// 1 / omega^2, so no stiffness matrix is inverted and a rigid direction (mu = 0) gives +inf;
// mode shapes xi_dof = L^-T y for the eigenvectors y of S, scaled to unit M-norm.
//
// Example:
//   pkmopt::Matrix6d M = pkmopt::tcp_mass_matrix(model, R, tcp, legs, tcp_position);
//   pkmopt::NaturalModes modes = pkmopt::natural_modes(C_dof, M_dof, /*shapes=*/false);
#pragma once

#include <Eigen/Core>
#include <vector>

#include "models/core/pose.hpp"
#include "models/dynamics/leg_dynamics.hpp"
#include "models/dynamics/mass_model.hpp"

namespace pkmopt {

/// The TCP mass matrix of the platform (rotation R, tcp and centre of mass in the platform
/// frame) and the legs (their joint points at the pose; `tcp_position` the TCP in the base frame).
Matrix6d tcp_mass_matrix(const MassModel& model, const Eigen::Matrix3d& R,
                         const Eigen::Vector3d& tcp, const std::vector<LegPoints>& legs,
                         const Eigen::Vector3d& tcp_position);

/// The gravity and inertia wrench at the TCP for the twist xi and its rate xi_dot.
Wrench dynamic_wrench(const MassModel& model, const Eigen::Matrix3d& R, const Eigen::Vector3d& tcp,
                      const std::vector<LegPoints>& legs, const Eigen::Vector3d& tcp_position,
                      const Vector6d& xi, const Vector6d& xi_dot);
/// The same with `gravity` (m/s^2, base frame) in place of model.gravity: for a base that
/// accelerates by a_base without turning, the dynamics relative to it are those of a fixed base
/// under g - a_base (the effective gravity of the translating frame).
Wrench dynamic_wrench(const MassModel& model, const Eigen::Matrix3d& R, const Eigen::Vector3d& tcp,
                      const std::vector<LegPoints>& legs, const Eigen::Vector3d& tcp_position,
                      const Vector6d& xi, const Vector6d& xi_dot, const Eigen::Vector3d& gravity);

/// The sum over the platform and every leg body of m (g - a_c) (N, base frame): the net force of
/// gravity and inertia on the whole mechanism for the twist xi and its rate xi_dot (relative to
/// a fixed base) under `gravity`. What a base carrying the mechanism must supply, besides the
/// tool's external force.
Eigen::Vector3d net_dynamic_force(const MassModel& model, const Eigen::Matrix3d& R,
                                  const Eigen::Vector3d& tcp, const std::vector<LegPoints>& legs,
                                  const Eigen::Vector3d& tcp_position, const Vector6d& xi,
                                  const Vector6d& xi_dot, const Eigen::Vector3d& gravity);

/// The kinetic energy of a mechanism whose base translates with velocity d (no rotation) while
/// the platform moves with the absolute twist xi: T = 1/2 [d; xi]^T Q [d; xi] (9x9, base axes).
/// Every leg body moves with d + A (v_P - d) and turns with W (v_P - d)
/// (models/dynamics/leg_dynamics.hpp, v_P - d the platform joint's velocity relative to the base),
/// so with M_P = sum m A^T A + W^T I W (the leg's mass matrix), N_P = sum m A and m_leg = sum m:
///   Q_xixi = M (tcp_mass_matrix),  Q_dd = sum_i M_P - N_P - N_P^T + m_leg I,
///   Q_dxi = sum_i (N_P - M_P) T_i.
/// A mechanism that moves rigidly with its base (xi = [d; 0]) then has T = 1/2 m_total |d|^2.
Eigen::Matrix<double, 9, 9> carried_mass_matrix(const MassModel& model, const Eigen::Matrix3d& R,
                                                const Eigen::Vector3d& tcp,
                                                const std::vector<LegPoints>& legs,
                                                const Eigen::Vector3d& tcp_position);

/// Natural frequencies (Hz, ascending; +inf for a rigid direction) and, on request, the mode
/// shapes (columns, DOF twists, unit M-norm; the largest component positive).
struct NaturalModes {
  Eigen::VectorXd frequencies;
  Eigen::MatrixXd shapes;
  bool ok = false;  ///< false when M_dof is not positive definite or C_dof not finite
};

/// The modes of det(C_dof^-1 - omega^2 M_dof) = 0 (C_dof symmetric positive semi-definite).
NaturalModes natural_modes(const Eigen::MatrixXd& compliance_dof, const Eigen::MatrixXd& mass_dof,
                           bool shapes);
/// The frequencies alone for a 6-DOF platform, on fixed-size matrices (no heap but the result).
NaturalModes natural_frequencies6(const Matrix6d& compliance, const Matrix6d& mass);

}  // namespace pkmopt
