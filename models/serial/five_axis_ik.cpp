#include "models/serial/five_axis_ik.hpp"

#include <Eigen/Geometry>
#include <Eigen/LU>
#include <cmath>
#include <stdexcept>

namespace pkmopt {
namespace {

constexpr double kTolerance = 1e-12;

Eigen::Vector3d unit_axis(int motion) {
  Eigen::Vector3d e = Eigen::Vector3d::Zero();
  e((motion - 1) % 3) = 1.0;
  return e;
}

Eigen::Matrix3d rotation_of(int motion, double value) {
  return elementary_motion<double>(motion, value).topLeftCorner<3, 3>();
}

// Subproblem 1: the angle about the unit axis w that turns u onto v (their parts normal to w); the
// angle `free_angle` when u has no such part (any angle will do).
double subproblem1(const Eigen::Vector3d& w, const Eigen::Vector3d& u, const Eigen::Vector3d& v,
                   double free_angle, bool& free) {
  const Eigen::Vector3d u_n = u - w * w.dot(u);
  const Eigen::Vector3d v_n = v - w * w.dot(v);
  free = u_n.norm() <= 1e-9 || v_n.norm() <= 1e-9;
  if (free) return free_angle;
  return std::atan2(w.dot(u_n.cross(v_n)), u_n.dot(v_n));
}

}  // namespace

std::vector<FiveAxisSolution> five_axis_inverse_kinematics(const SerialChain& chain, int spindle,
                                                           const Eigen::Vector3d& r_tool,
                                                           const Eigen::Vector3d& a_tool,
                                                           const Eigen::Vector3d& r0,
                                                           const Eigen::Vector3d& a0,
                                                           double free_angle) {
  // The feed axes by kind, and the constant rotations around the two rotary ones.
  std::vector<int> rotary, linear;  // indices among the variables
  std::vector<int> rotary_motion;
  Eigen::Matrix3d M[3] = {Eigen::Matrix3d::Identity(), Eigen::Matrix3d::Identity(),
                          Eigen::Matrix3d::Identity()};
  int k = 0;
  for (const ChainElement& e : chain.elements()) {
    const int stage = static_cast<int>(rotary.size());
    if (!e.variable) {
      if (e.motion >= 4) M[stage] = M[stage] * rotation_of(e.motion, e.value);
      continue;
    }
    if (k == spindle) {
      // The spindle is held at 0 (an identity element).
    } else if (e.motion >= 4) {
      rotary.push_back(k);
      rotary_motion.push_back(e.motion);
    } else {
      linear.push_back(k);
    }
    ++k;
  }
  if (rotary.size() != 2 || linear.size() != 3)
    throw std::invalid_argument(
        "five_axis_inverse_kinematics: expected two rotary and three linear feed axes besides the "
        "spindle, found " +
        std::to_string(rotary.size()) + " rotary and " + std::to_string(linear.size()) +
        " linear in '" + chain.code() + "'");

  // Orientation: R(w1, t1) R(w2, t2) p = q (subproblem 2).
  const Eigen::Vector3d w1 = unit_axis(rotary_motion[0]);
  const Eigen::Vector3d w2 = M[1] * unit_axis(rotary_motion[1]);
  const Eigen::Vector3d p = M[1] * M[2] * a_tool.normalized();
  const Eigen::Vector3d q = M[0].transpose() * a0.normalized();
  const double c12 = w1.dot(w2);
  const Eigen::Vector3d w12 = w1.cross(w2);
  if (w12.squaredNorm() <= kTolerance)
    throw std::invalid_argument(
        "five_axis_inverse_kinematics: the two rotary axes are parallel in '" + chain.code() + "'");
  const double alpha = (c12 * w2.dot(p) - w1.dot(q)) / (c12 * c12 - 1.0);
  const double beta = (c12 * w1.dot(q) - w2.dot(p)) / (c12 * c12 - 1.0);
  const double gamma2 = (p.squaredNorm() - alpha * alpha - beta * beta - 2.0 * alpha * beta * c12) /
                        w12.squaredNorm();
  std::vector<double> gammas;
  if (gamma2 > 1e-12) {
    gammas = {std::sqrt(gamma2), -std::sqrt(gamma2)};
  } else if (gamma2 > -1e-12) {
    gammas = {0.0};
  }

  std::vector<FiveAxisSolution> solutions;
  for (const double gamma : gammas) {
    const Eigen::Vector3d z = alpha * w1 + beta * w2 + gamma * w12;
    bool free2 = false, free1 = false;
    const double t2 = subproblem1(w2, p, z, 0.0, free2);
    const double t1 = subproblem1(w1, z, q, free_angle, free1);
    FiveAxisSolution s;
    s.q = Eigen::VectorXd::Zero(chain.num_variables());
    s.q(rotary[0]) = t1;
    s.q(rotary[1]) = t2;
    s.singular = free1 || free2;
    // Position: r0 = c + D x, affine in the linear axes with the rotary ones set.
    const Eigen::Vector3d c = chain.tool_point(s.q, r_tool);
    Eigen::Matrix3d D;
    for (int j = 0; j < 3; ++j) {
      Eigen::VectorXd unit = s.q;
      unit(linear[static_cast<std::size_t>(j)]) = 1.0;
      D.col(j) = chain.tool_point(unit, r_tool) - c;
    }
    const Eigen::FullPivLU<Eigen::Matrix3d> lu(D);
    if (lu.rank() < 3) continue;
    const Eigen::Vector3d x = lu.solve(r0 - c);
    for (int j = 0; j < 3; ++j) s.q(linear[static_cast<std::size_t>(j)]) = x(j);
    // A second branch that repeats the first (gamma near 0) is not a second solution.
    bool repeated = false;
    for (const FiveAxisSolution& other : solutions)
      repeated = repeated || (other.q - s.q).cwiseAbs().maxCoeff() <= 1e-9;
    if (!repeated) solutions.push_back(s);
  }
  return solutions;
}

}  // namespace pkmopt
