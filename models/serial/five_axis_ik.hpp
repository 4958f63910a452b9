// Inverse kinematics of 5-axis machines by coordinate code (models/serial/serial_chain.hpp): the
// axis values that put the tool point at r_0 with the tool axis along a_0, every solution branch,
// in closed form.
//
// The chain has two rotary feed axes (motions 4..6), three linear feed axes (motions 1..3) and
// optionally a spindle (a rotary axis about the tool axis, held at 0: it does not move the tool
// point or axis); constant elements anywhere. This covers the table-table (641236: C, A on the
// table), head-head and table-head families, whatever the order of the axes.
//
// Orientation: translations do not turn, so the tool axis is a_0 = M0 R1(t1) M1 R2(t2) M2 a_tool,
// M0..M2 the constant rotations between the rotary axes. With w1 the first axis, w2 = M1 e_2
// (the second, seen from after the first) and p = M1 M2 a_tool, q = M0^T a_0, this is
// R(w1, t1) R(w2, t2) p = q: two successive rotations about axes through one point, the
// Paden–Kahan subproblem 2 (Murray, Li & Sastry, "A Mathematical Introduction to Robotic
// Manipulation", CRC 1994, sec. 3.2.1). With z = R(w2, t2) p = R(w1, -t1) q,
//   z = alpha w1 + beta w2 + gamma (w1 x w2),
//   alpha = ((w1.w2)(w2.p) - w1.q) / ((w1.w2)^2 - 1),
//   beta  = ((w1.w2)(w1.q) - w2.p) / ((w1.w2)^2 - 1),
//   gamma^2 = (|p|^2 - alpha^2 - beta^2 - 2 alpha beta (w1.w2)) / |w1 x w2|^2,
// two branches (gamma = +-sqrt), one when gamma = 0, none when gamma^2 < 0 (the axis cannot be
// reached); each angle then from subproblem 1, t = atan2(w.(u' x v'), u'.v') with u', v' the
// parts of u, v normal to w.
// Position: with the rotary axes set, the tool point is affine in the linear axes,
// r_0 = c + D x (D 3 x 3: the tool point's motion per unit of each linear axis), so x solves
// D x = r_0 - c.
// Singular: when a_0 lies along the first rotary axis (w1 x q = 0, e.g. A = 0 for 641236) the first
// axis turns without moving the tool axis: t1 is free and takes `free_angle`; the solution is
// marked singular. D singular (linear axes not independent) gives no solution.
//
// Example:
//   SerialChain chain = SerialChain::from_code("641236");
//   auto solutions = five_axis_inverse_kinematics(chain, 5, {0, 0, 0.1}, {0, 0, 1}, r0, a0);
#pragma once

#include <Eigen/Core>
#include <vector>

#include "models/serial/serial_chain.hpp"

namespace pkmopt {

/// One solution of the inverse kinematics.
struct FiveAxisSolution {
  Eigen::VectorXd q;      ///< one value per variable element of the chain (spindle 0), m and rad
  bool singular = false;  ///< the first rotary axis was free (see the header comment)
};

/// Every solution (at most two, or one when singular) that puts the tool point r_tool and tool
/// axis a_tool (in the chain's last frame) at r0 with the axis along a0 (unit, chain frame 0).
/// `spindle` is the index among the chain's variables of the spindle, -1 for none. Rotary values
/// in (-pi, pi]. Throws std::invalid_argument when the chain is not a 5-axis chain (two rotary
/// and three linear feed axes besides the spindle).
std::vector<FiveAxisSolution> five_axis_inverse_kinematics(const SerialChain& chain, int spindle,
                                                           const Eigen::Vector3d& r_tool,
                                                           const Eigen::Vector3d& a_tool,
                                                           const Eigen::Vector3d& r0,
                                                           const Eigen::Vector3d& a0,
                                                           double free_angle = 0.0);

}  // namespace pkmopt
