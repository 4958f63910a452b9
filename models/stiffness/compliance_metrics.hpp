// The compliance metrics every model reports (models/core/machine.hpp): the 6x6 compliance, the TCP
// deflection under the analysed wrench, the worst direction of stiffness_min, and the loaded
// (tangent) stiffness with the geometric term of the leg forces.
//
// Twists [dp; dtheta] at the TCP (small rotation vector, base axes), wrenches [f; m] at the TCP.
//
// Geometric stiffness of a leg force (Griffis & Duffy 1993; Quennouelle & Gosselin 2009): a leg
// of current length l pulls on the platform point P = p + r with the tension f along the unit
// vector s from its other end. The wrench it needs from outside, f [s; r x s], changes with a
// platform displacement dx = [dp; dtheta] by
//     d(f [s; r x s]) = f K_g dx,
//     K_g = [ Pi/l          -Pi/l [r]x                      ]
//           [ [r]x Pi/l     [s]x [r]x - [r]x Pi/l [r]x       ],   Pi = I - s s^T,
// (ds = Pi/l (dp + dtheta x r), dr = dtheta x r). [s]x[r]x = r s^T - (s.r) I is not symmetric:
// summed over the legs its antisymmetric part is -[m]x/2 with m the moment of the wrench about
// the TCP, so the loaded stiffness is symmetric only when the wrench is a force through the TCP
// (the rotation vector is not a conservative coordinate under an external moment).
// A constraint force of fixed direction n at P (a revolute joint holding a leg in its plane)
// contributes f [0 0; 0 [n]x [r]x] (only its lever arm turns).
//
// Loaded stiffness on the platform DOF: K_T = K + T^T (sum of the geometric terms) T; the loaded
// compliance C_T = K_T^-1 = (I + C G)^-1 C (C = K^-1, G the geometric part), which needs no K.
//
// Example:
//   Matrix6d G = geometric_stiffness(tension, s, r, length);
//   fill_compliance_metrics(C, wrench, metrics);          // compliance, deflections, direction
//   metrics.stiffness_min_loaded = loaded_stiffness_min(C_dof, G_dof, T);
#pragma once

#include <Eigen/Core>

#include "models/core/machine.hpp"
#include "models/core/pose.hpp"

namespace pkmopt {

/// An m x m matrix on the platform DOF (m <= 6), no heap.
using DofMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, 6, 6>;
/// The 6 x m map T from the DOF twist to the full twist.
using TwistMap = Eigen::Matrix<double, 6, Eigen::Dynamic, 0, 6, 6>;

/// f K_g of a leg force (see the header comment), 6x6 at the TCP.
Matrix6d geometric_stiffness(double tension, const Eigen::Vector3d& s, const Eigen::Vector3d& r,
                             double length);

/// f [0 0; 0 [n]x [r]x] of a constraint force of fixed direction n at r from the TCP.
Matrix6d constraint_geometric_stiffness(double force, const Eigen::Vector3d& n,
                                        const Eigen::Vector3d& r);

/// From the 6x6 compliance C and the wrench w: matrices.compliance = C, tcp_deflection,
/// tcp_rotation_deflection and stiffness_min_direction (the eigenvector of C_tt of its largest
/// eigenvalue, largest component positive).
void fill_compliance_metrics(const Matrix6d& C, const Wrench& w, PoseMetrics& out,
                             PoseCompliance& matrices);

/// 1 / sigma_max of the translational block of T C_T T^T, C_T = (I + C G)^-1 C on the platform
/// DOF (C: m x m compliance, G: m x m geometric stiffness, T: 6 x m). 0 when K_T = C^-1 + G is
/// not positive definite (checked as C + C G C, symmetric part) or the solve fails.
/// `loaded_tt` (when given) receives the translational block of T C_T T^T (+inf entries when
/// unstable).
double loaded_stiffness_min(const DofMatrix& C, const DofMatrix& G, const TwistMap& T,
                            Eigen::Matrix3d* loaded_tt = nullptr);

/// The same on the full twist (6-DOF platforms, T = I), with fixed-size matrices.
double loaded_stiffness_min(const Matrix6d& C, const Matrix6d& G,
                            Eigen::Matrix3d* loaded_tt = nullptr);

/// 1 / sigma_max of a translational loaded compliance block (0 when not finite or zero).
double loaded_stiffness_of(const Eigen::Matrix3d& loaded_tt);

/// The metrics of a singular pose: compliance and deflections +inf, direction 0, loaded 0.
void set_singular_compliance_metrics(PoseMetrics& out, PoseCompliance& matrices);

/// Every metric of a singular pose (docs/conventions.md): singularity_margin and stiffness_min 0,
/// each tau_i and tcp_error_max +inf, and with `compliance_metrics` the compliance ones above.
void set_singular_metrics(PoseMetrics& out, bool compliance_metrics, PoseCompliance& matrices);

}  // namespace pkmopt
