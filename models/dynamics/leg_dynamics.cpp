#include "models/dynamics/leg_dynamics.hpp"

#include <cmath>

#include "models/core/linalg.hpp"

namespace pkmopt {
namespace {

// A link along s: inertia tensor I_t (I - s s^T) about its centre.
Eigen::Matrix3d link_inertia(double I_t, const Eigen::Vector3d& s) {
  return I_t * (Eigen::Matrix3d::Identity() - s * s.transpose());
}

// A body with its velocity and acceleration (v_c = A v_P, omega = W v_P).
void set_body(LegBody& b, double mass, const Eigen::Matrix3d& inertia, const Eigen::Matrix3d& A,
              const Eigen::Matrix3d& W, const Eigen::Vector3d& centre, const Eigen::Vector3d& v_P,
              const Eigen::Vector3d& acceleration, const Eigen::Vector3d& angular_acceleration) {
  b.mass = mass;
  b.inertia = inertia;
  b.A = A;
  b.W = W;
  b.centre = centre;
  b.velocity = A * v_P;
  b.angular_velocity = W * v_P;
  b.acceleration = acceleration;
  b.angular_acceleration = angular_acceleration;
}

}  // namespace

bool leg_bodies(const LegPoints& leg, const LegMasses& m, const Eigen::Vector3d& v_P,
                const Eigen::Vector3d& a_P, LegBody (&bodies)[2]) {
  const Eigen::Matrix3d I3 = Eigen::Matrix3d::Identity();
  const Eigen::Vector3d d = leg.platform - leg.joint;
  const double length = d.norm();
  if (!(length > 0.0) || !std::isfinite(length)) return false;
  const Eigen::Vector3d s = d / length;
  switch (leg.kind) {
    case LegBodyKind::kTelescopic: {
      const double q = length;
      const Eigen::Matrix3d Pi = I3 - s * s.transpose();
      const Eigen::Vector3d s_dot = Pi * v_P / q;
      const double q_dot = s.dot(v_P);
      const double q_ddot = s_dot.dot(v_P) + s.dot(a_P);
      const Eigen::Vector3d s_ddot = (a_P - q_ddot * s - 2.0 * q_dot * s_dot) / q;
      const Eigen::Matrix3d W = cross_matrix(s) / q;
      const Eigen::Vector3d alpha = s.cross(s_ddot);
      const double e1 = m.cylinder.centre, e2 = m.rod.centre;
      set_body(bodies[0], m.cylinder.mass, link_inertia(m.cylinder.inertia, s), (e1 / q) * Pi, W,
               leg.joint + e1 * s, v_P, e1 * s_ddot, alpha);
      set_body(bodies[1], m.rod.mass, link_inertia(m.rod.inertia, s), I3 - (e2 / q) * Pi, W,
               leg.platform - e2 * s, v_P, a_P - e2 * s_ddot, alpha);
      return true;
    }
    case LegBodyKind::kCarriage: {
      const Eigen::Vector3d& u = leg.axis;
      const double su = s.dot(u);
      if (!(std::abs(su) > 1e-12)) return false;
      const double L = length;
      const Eigen::Matrix3d drive = u * s.transpose() / su;  // carriage velocity per v_P
      const Eigen::Matrix3d Q = I3 - drive;                  // d_dot per v_P
      const Eigen::Vector3d d_dot = Q * v_P;
      const double q_ddot = (s.dot(a_P) + d_dot.squaredNorm() / L) / su;
      const Eigen::Vector3d d_ddot = a_P - q_ddot * u;
      const double e = m.link.centre;
      set_body(bodies[0], m.carriage, Eigen::Matrix3d::Zero(), drive, Eigen::Matrix3d::Zero(),
               leg.joint, v_P, q_ddot * u, Eigen::Vector3d::Zero());
      set_body(bodies[1], m.link.mass, link_inertia(m.link.inertia, s), drive + (e / L) * Q,
               cross_matrix(s) * Q / L, leg.joint + e * s, v_P, q_ddot * u + (e / L) * d_ddot,
               s.cross(d_ddot) / L);
      return true;
    }
    case LegBodyKind::kCrank: {
      const Eigen::Vector3d& w = leg.axis;
      const Eigen::Vector3d c = leg.joint - leg.pivot;
      const double crank = c.norm();
      const Eigen::Vector3d t = w.cross(c);
      const double st = s.dot(t);
      if (!(std::abs(st) > 1e-12 * crank) || !(crank > 0.0)) return false;
      const double L = length;
      const Eigen::Matrix3d drive = t * s.transpose() / st;  // elbow velocity per v_P
      const Eigen::Matrix3d Q = I3 - drive;
      const double q_dot = s.dot(v_P) / st;
      const Eigen::Vector3d d_dot = Q * v_P;
      const Eigen::Vector3d wwc = w.cross(t);
      const double q_ddot =
          (s.dot(a_P) - q_dot * q_dot * s.dot(wwc) + d_dot.squaredNorm() / L) / st;
      const Eigen::Vector3d c_ddot = q_ddot * t + q_dot * q_dot * wwc;
      const Eigen::Vector3d d_ddot = a_P - c_ddot;
      const double k = m.crank.centre / crank;
      set_body(bodies[0], m.crank.mass, m.crank.inertia * w * w.transpose(), k * drive,
               w * s.transpose() / st, leg.pivot + k * c, v_P, k * c_ddot, q_ddot * w);
      const double e = m.link.centre;
      set_body(bodies[1], m.link.mass, link_inertia(m.link.inertia, s), drive + (e / L) * Q,
               cross_matrix(s) * Q / L, leg.joint + e * s, v_P, c_ddot + (e / L) * d_ddot,
               s.cross(d_ddot) / L);
      return true;
    }
  }
  return false;
}

Eigen::Matrix3d leg_mass_matrix(const LegPoints& leg, const LegMasses& masses) {
  if (leg.kind == LegBodyKind::kTelescopic) {
    // Closed form of the sum below: the cylinder (e1/q) Pi, the rod s s^T + (1 - e2/q) Pi and
    // the turn [s]x / q give alpha Pi + m_rod s s^T.
    const Eigen::Vector3d d = leg.platform - leg.joint;
    const double q = d.norm();
    if (!(q > 0.0) || !std::isfinite(q)) return Eigen::Matrix3d::Zero();
    const Eigen::Vector3d s = d / q;
    const double k1 = masses.cylinder.centre / q, k2 = 1.0 - masses.rod.centre / q;
    const double alpha = masses.cylinder.mass * k1 * k1 + masses.rod.mass * k2 * k2 +
                         (masses.cylinder.inertia + masses.rod.inertia) / (q * q);
    const Eigen::Matrix3d ss = s * s.transpose();
    return alpha * (Eigen::Matrix3d::Identity() - ss) + masses.rod.mass * ss;
  }
  LegBody bodies[2];
  Eigen::Matrix3d M = Eigen::Matrix3d::Zero();
  if (!leg_bodies(leg, masses, Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero(), bodies)) return M;
  for (const LegBody& b : bodies) {
    M.noalias() += b.mass * b.A.transpose() * b.A;
    M.noalias() += b.W.transpose() * b.inertia * b.W;
  }
  return M;
}

double moving_mass(const MassModel& model, const std::vector<LegBodyKind>& legs) {
  double total = model.platform.mass;
  for (const LegBodyKind kind : legs) {
    const LegMasses& m = model.legs;
    total += kind == LegBodyKind::kTelescopic ? m.cylinder.mass + m.rod.mass
             : kind == LegBodyKind::kCarriage ? m.carriage + m.link.mass
                                              : m.crank.mass + m.link.mass;
  }
  return total;
}

Eigen::Vector3d leg_dynamic_force(const LegPoints& leg, const LegMasses& masses,
                                  const Eigen::Vector3d& v_P, const Eigen::Vector3d& a_P,
                                  const Eigen::Vector3d& gravity) {
  LegBody bodies[2];
  Eigen::Vector3d f = Eigen::Vector3d::Zero();
  if (!leg_bodies(leg, masses, v_P, a_P, bodies)) return f;
  for (const LegBody& b : bodies) {
    const Eigen::Vector3d Iw = b.inertia * b.angular_velocity;
    f += b.A.transpose() * (b.mass * (gravity - b.acceleration));
    f -= b.W.transpose() * (b.inertia * b.angular_acceleration + b.angular_velocity.cross(Iw));
  }
  return f;
}

}  // namespace pkmopt
