// Tests of models/dynamics/leg_dynamics: the leg bodies' velocities, accelerations, mass matrix and
// dynamic force against an independent model written here: the legs' own inverse kinematics
// (the carriage position and the crank angle solved from the constant link length) along a path
// P(t) = P0 + v t + a t^2 / 2 of the platform point, differentiated by finite differences.
#include "models/dynamics/leg_dynamics.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace pkmopt {
namespace {

using Eigen::Vector3d;

// The geometry of one leg of each kind and its own inverse kinematics.
struct TestLeg {
  LegBodyKind kind;
  Vector3d base;        // UPS: base joint; PUS: guide point at q = 0; RUS: pivot
  Vector3d axis;        // PUS: guide direction; RUS: crank axis (unit)
  Vector3d crank_zero;  // RUS: crank vector at q = 0 (perpendicular to axis)
  double link = 0.0;    // PUS, RUS: link length

  // The joint points with P at `P`, on the branch nearest to `previous` (q).
  LegPoints at(const Vector3d& P, double& q) const {
    LegPoints leg{.kind = kind, .joint = base, .platform = P, .axis = axis, .pivot = base};
    if (kind == LegBodyKind::kCarriage) {
      const Vector3d g = P - base;
      const double along = axis.dot(g);
      const double root = std::sqrt(along * along - (g.squaredNorm() - link * link));
      q = along - root;  // the carriage behind P
      leg.joint = base + q * axis;
    } else if (kind == LegBodyKind::kCrank) {
      // |P - O - c(q)| = L with c(q) = cos q c0 + sin q (w x c0): A cos q + B sin q = D.
      const Vector3d g = P - base;
      const Vector3d c0 = crank_zero, c1 = axis.cross(crank_zero);
      const double A = 2 * g.dot(c0), B = 2 * g.dot(c1);
      const double D = g.squaredNorm() + c0.squaredNorm() - link * link;
      const double phase = std::atan2(B, A), r = std::hypot(A, B);
      const double delta = std::acos(D / r);
      q = phase + delta;  // one branch, followed continuously along the short path
      leg.joint = base + std::cos(q) * c0 + std::sin(q) * c1;
    }
    return leg;
  }
};

LegMasses sample_masses() {
  LegMasses m;
  m.cylinder = {.mass = 7.0, .centre = 0.2, .inertia = 0.35};
  m.rod = {.mass = 3.5, .centre = 0.3, .inertia = 0.12};
  m.carriage = 4.0;
  m.link = {.mass = 2.5, .centre = 0.35, .inertia = 0.09};
  m.crank = {.mass = 1.5, .centre = 0.1, .inertia = 0.004};
  return m;
}

std::vector<TestLeg> sample_legs() {
  return {
      {LegBodyKind::kTelescopic, {0.4, -0.1, 0.0}, Vector3d::Zero(), Vector3d::Zero(), 0.0},
      {LegBodyKind::kCarriage,
       {0.5, 0.2, -0.3},
       Vector3d(0.2, -0.3, 1.0).normalized(),
       Vector3d::Zero(),
       0.9},
      {LegBodyKind::kCrank,
       {0.3, 0.1, 1.6},
       Vector3d(-0.2, 1.0, 0.1).normalized(),
       Vector3d::Zero(),
       0.9},
  };
}

// The crank vector at q = 0 for the RUS leg: 0.25 m, perpendicular to its axis.
void finish(std::vector<TestLeg>& legs) {
  for (TestLeg& leg : legs) {
    if (leg.kind != LegBodyKind::kCrank) continue;
    leg.crank_zero = 0.25 * leg.axis.cross(Vector3d(1, 0, 0)).normalized();
  }
}

// The platform point's path and the leg's bodies along it.
struct Path {
  Vector3d P0, v, a;
  Vector3d at(double t) const { return P0 + v * t + 0.5 * a * t * t; }
};

constexpr double kH = 1e-5;

TEST(LegDynamics, VelocitiesAndAccelerationsMatchFiniteDifferencesOfTheLegsOwnIk) {
  std::vector<TestLeg> legs = sample_legs();
  finish(legs);
  const LegMasses masses = sample_masses();
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (const TestLeg& leg : legs) {
    for (int trial = 0; trial < 5; ++trial) {
      const Path path{Vector3d(0.1 * u(rng), 0.1 * u(rng), 0.8 + 0.1 * u(rng)),
                      Vector3d(u(rng), u(rng), u(rng)), Vector3d(3 * u(rng), 3 * u(rng), u(rng))};
      double q = 0.0;
      LegBody bodies[2], minus[2], plus[2];
      ASSERT_TRUE(leg_bodies(leg.at(path.at(0), q), masses, path.v, path.a, bodies));
      Vector3d zero = Vector3d::Zero();
      ASSERT_TRUE(leg_bodies(leg.at(path.at(-kH), q), masses, zero, zero, minus));
      ASSERT_TRUE(leg_bodies(leg.at(path.at(kH), q), masses, zero, zero, plus));
      for (int b = 0; b < 2; ++b) {
        const Vector3d v_fd = (plus[b].centre - minus[b].centre) / (2 * kH);
        const Vector3d a_fd = (plus[b].centre - 2 * bodies[b].centre + minus[b].centre) / (kH * kH);
        EXPECT_LE((bodies[b].velocity - v_fd).norm(), 1e-7 * (1 + v_fd.norm()))
            << "kind " << int(leg.kind) << " body " << b;
        EXPECT_LE((bodies[b].acceleration - a_fd).norm(), 2e-4 * (1 + a_fd.norm()))
            << "kind " << int(leg.kind) << " body " << b;
      }
      // The link's angular velocity from the turn of its direction: omega = s x s_dot.
      auto direction = [&](double t) {
        double qq = 0;
        const LegPoints p = leg.at(path.at(t), qq);
        return Vector3d((p.platform - p.joint).normalized());
      };
      const Vector3d s = direction(0);
      const Vector3d s_dot = (direction(kH) - direction(-kH)) / (2 * kH);
      const Vector3d s_ddot = (direction(kH) - 2 * s + direction(-kH)) / (kH * kH);
      EXPECT_LE((bodies[1].angular_velocity - s.cross(s_dot)).norm(), 1e-7 * (1 + s_dot.norm()));
      EXPECT_LE((bodies[1].angular_acceleration - s.cross(s_ddot)).norm(),
                2e-4 * (1 + s_ddot.norm()));
    }
  }
}

// The kinetic energy 1/2 v_P^T M_P v_P equals the sum over the bodies of 1/2 m |v_c|^2 +
// 1/2 omega^T I omega with the velocities from finite differences; the dynamic force's power
// equals -dT/dt (no gravity) and the gravity's power d/dt sum m g . c, both along the path.
TEST(LegDynamics, MassMatrixAndForceAgreeWithEnergyAlongThePath) {
  std::vector<TestLeg> legs = sample_legs();
  finish(legs);
  const LegMasses masses = sample_masses();
  const Vector3d g(0.3, -0.2, -9.81);
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (const TestLeg& leg : legs) {
    for (int trial = 0; trial < 5; ++trial) {
      const Path path{Vector3d(0.1 * u(rng), 0.1 * u(rng), 0.8 + 0.1 * u(rng)),
                      Vector3d(u(rng), u(rng), u(rng)), Vector3d(3 * u(rng), 3 * u(rng), u(rng))};
      // Kinetic energy at t from central differences of the body positions and directions.
      auto energy = [&](double t) {
        double q = 0;
        LegBody m0[2], m1[2], p1[2];
        const Vector3d z = Vector3d::Zero();
        EXPECT_TRUE(leg_bodies(leg.at(path.at(t - kH), q), masses, z, z, m1));
        EXPECT_TRUE(leg_bodies(leg.at(path.at(t), q), masses, z, z, m0));
        EXPECT_TRUE(leg_bodies(leg.at(path.at(t + kH), q), masses, z, z, p1));
        double T = 0.0;
        for (int b = 0; b < 2; ++b) {
          const Vector3d v = (p1[b].centre - m1[b].centre) / (2 * kH);
          T += 0.5 * m0[b].mass * v.squaredNorm();
        }
        // Rotation: the link's direction s (and the crank's angle about its axis).
        const LegPoints lp = leg.at(path.at(t), q), lm = leg.at(path.at(t - kH), q),
                        lq = leg.at(path.at(t + kH), q);
        const Vector3d s = (lp.platform - lp.joint).normalized();
        const Vector3d s_dot =
            ((lq.platform - lq.joint).normalized() - (lm.platform - lm.joint).normalized()) /
            (2 * kH);
        const Vector3d omega = s.cross(s_dot);
        const double I_t = leg.kind == LegBodyKind::kTelescopic
                               ? masses.cylinder.inertia + masses.rod.inertia
                               : masses.link.inertia;
        T += 0.5 * I_t * omega.squaredNorm();
        if (leg.kind == LegBodyKind::kCrank) {
          const Vector3d c = lp.joint - lp.pivot;
          const Vector3d c_dot = (lq.joint - lm.joint) / (2 * kH);
          const double rate = leg.axis.dot(c.cross(c_dot)) / c.squaredNorm();
          T += 0.5 * masses.crank.inertia * rate * rate;
        }
        return T;
      };
      double q = 0;
      const LegPoints now = leg.at(path.at(0), q);
      const Eigen::Matrix3d M_P = leg_mass_matrix(now, masses);
      EXPECT_NEAR(0.5 * path.v.dot(M_P * path.v), energy(0.0), 1e-7 * energy(0.0));
      EXPECT_LE((M_P - M_P.transpose()).norm(), 1e-12 * M_P.norm());
      // -dT/dt = power of the inertia forces (no gravity).
      const double h = 1e-4;
      const double dT = (energy(h) - energy(-h)) / (2 * h);
      const Vector3d f_inertia = leg_dynamic_force(now, masses, path.v, path.a, Vector3d::Zero());
      EXPECT_NEAR(f_inertia.dot(path.v), -dT, 1e-5 * (1 + std::abs(dT)));
      // Gravity's power: d/dt sum m g . c.
      auto potential = [&](double t) {
        double qq = 0;
        LegBody b[2];
        const Vector3d z = Vector3d::Zero();
        EXPECT_TRUE(leg_bodies(leg.at(path.at(t), qq), masses, z, z, b));
        return b[0].mass * g.dot(b[0].centre) + b[1].mass * g.dot(b[1].centre);
      };
      const double dV = (potential(kH) - potential(-kH)) / (2 * kH);
      const Vector3d f_gravity =
          leg_dynamic_force(now, masses, Vector3d::Zero(), Vector3d::Zero(), g);
      EXPECT_NEAR(f_gravity.dot(path.v), dV, 1e-6 * (1 + std::abs(dV)));
    }
  }
}

// Massless legs add nothing; a degenerate leg (P at its joint) is refused.
TEST(LegDynamics, MasslessAndDegenerateLegs) {
  const LegPoints leg{.kind = LegBodyKind::kTelescopic,
                      .joint = Vector3d(0, 0, 0),
                      .platform = Vector3d(0.1, 0.2, 0.9)};
  EXPECT_EQ(leg_mass_matrix(leg, LegMasses{}).norm(), 0.0);
  EXPECT_EQ(leg_dynamic_force(leg, LegMasses{}, Vector3d(1, 2, 3), Vector3d(4, 5, 6),
                              Vector3d(0, 0, -9.81))
                .norm(),
            0.0);
  LegBody bodies[2];
  const LegPoints degenerate{.kind = LegBodyKind::kTelescopic};
  EXPECT_FALSE(leg_bodies(degenerate, sample_masses(), Vector3d::Zero(), Vector3d::Zero(), bodies));
}

}  // namespace
}  // namespace pkmopt
