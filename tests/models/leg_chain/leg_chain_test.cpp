// Tests of models/leg_chain/leg_chain: the family's formulas against finite differences, IK/FK
// round trips, equilibrium by virtual work, serial and parallel singularities, and the delta
// against published numbers and an independent implementation of published equations.
#include "models/leg_chain/leg_chain.hpp"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <memory>
#include <numbers>
#include <optional>
#include <vector>

#include "models/workspace/workspace.hpp"
#include "tests/sample_machines.hpp"

namespace pkmopt {
namespace {

constexpr double kPi = std::numbers::pi;

double wrap_angle_for_test(double a) { return std::remainder(a, 2.0 * kPi); }

using sample_machines::Uniform;  // seeded splitmix64, bit-reproducible

// The pose moved by h along platform DOF j: by the full twist h T e_j (T = m.twist_map at the
// pose): the TCP moves by h T_v e_j, the platform turns by h T_omega e_j about the base axes
// through the TCP (R <- exp(h T_omega e_j) R).
Pose moved(const LegChainMachine& m, const Pose& pose, int j, double h) {
  const Eigen::MatrixXd T = m.twist_map(pose);
  Pose out = pose;
  out.position += h * T.block(0, j, 3, 1);
  const Eigen::Vector3d omega = h * T.block(3, j, 3, 1);
  if (omega.norm() > 0.0) {
    out.angles =
        angles_from_rotation(rotation_from_vector(omega) * rotation_zyx<double>(pose.angles));
  }
  return out;
}

// Closure error of leg i at a platform pose taken as given (no projection): |P_i - c_i(q)| - L_i.
double closure(const LegChainMachine& m, int i, const Pose& pose, double q) {
  const LegChainLeg& leg = m.design().legs[static_cast<std::size_t>(i)];
  const Eigen::Matrix3d R = m.design().mobility == PlatformMobility::kTranslational
                                ? Eigen::Matrix3d::Identity()
                                : rotation_zyx<double>(pose.angles);
  const Eigen::Vector3d P = pose.position + R * (leg.platform_point - m.design().tcp);
  Eigen::Vector3d c, dc;
  m.actuated_point(i, q, c, dc);
  const double L = leg.kind == LegKind::kUPS ? q : leg.link_length;
  return (P - c).norm() - L;
}

// A random pose the platform can take near its home pose: position within +-dx, and rotations
// within +-dangle about the base axes (6-DOF), about e (Schoenflies), or rx, ry with the
// parasitic x, y, rz (planar legs).
Pose random_pose(const LegChainMachine& m, Uniform& u, double dx, double dangle) {
  Pose p = m.design().home;
  for (int k = 0; k < 3; ++k) p.position(k) += u(-dx, dx);
  switch (m.design().mobility) {
    case PlatformMobility::kSixDof:
      for (int k = 0; k < 3; ++k) p.angles(k) = u(-dangle, dangle);
      break;
    case PlatformMobility::kTranslational:
      break;
    case PlatformMobility::kSchoenflies:
      p.angles = angles_from_rotation(
          Eigen::AngleAxisd(u(-dangle, dangle), m.design().rotation_axis).toRotationMatrix());
      break;
    case PlatformMobility::kPlanarLegs: {
      p.angles = Eigen::Vector3d(u(-dangle, dangle), u(-dangle, dangle), 0.0);
      const auto actual = m.actual_pose(p);
      if (actual) p = *actual;
      break;
    }
  }
  return p;
}

// Random poses around the home pose that the machine reaches (IK exists, not singular).
std::vector<Pose> sample_poses(const LegChainMachine& m, std::uint64_t seed, int count, double dx,
                               double dangle) {
  Uniform u(seed);
  std::vector<Pose> poses;
  auto data = m.make_data();
  PoseMetrics metrics;
  for (int tries = 0; tries < 100 * count && static_cast<int>(poses.size()) < count; ++tries) {
    const Pose p = random_pose(m, u, dx, dangle);
    m.analyze(*data, p, Wrench::Zero(), metrics);
    if (m.inverse_kinematics(p) && !metrics.singular && metrics.singularity_margin > 1e-3) {
      poses.push_back(p);
    }
  }
  return poses;
}

// A Schoenflies (3T1R) test machine: four carriages on vertical guides at azimuths 90 k deg,
// radius 0.4 m, struts of 0.5 m (parallelogram pairs, bars parallel to e = z) to platform points
// at radius 0.12 m turned by +offset (even k) or -offset (odd k) from their guides, platform
// below the carriages. (Equal offsets would be singular at the centre: raising the platform and
// turning it about z would change the four strut ends alike. Offset 0: no strut has a lever arm
// about z - a parallel singularity.) Turned as a whole by Q (e = Q z).
LegChainDesign schoenflies_sample(double offset_deg = 60.0,
                                  const Eigen::Matrix3d& Q = Eigen::Matrix3d::Identity()) {
  LegChainDesign d;
  d.model = "schoenflies_sample";
  d.mobility = PlatformMobility::kSchoenflies;
  d.rotation_axis = Q * Eigen::Vector3d::UnitZ();
  for (int k = 0; k < 4; ++k) {
    const double a = deg_to_rad(90.0 * k);
    const double b = a + deg_to_rad(k % 2 == 0 ? offset_deg : -offset_deg);
    LegChainLeg leg;
    leg.kind = LegKind::kPUS;
    leg.base_point = Q * Eigen::Vector3d(0.4 * std::cos(a), 0.4 * std::sin(a), 0.0);
    leg.axis = Q * Eigen::Vector3d::UnitZ();
    leg.link_length = 0.5;
    leg.platform_point = Q * Eigen::Vector3d(0.12 * std::cos(b), 0.12 * std::sin(b), 0.0);
    leg.q_min = -0.5;
    leg.q_max = 1.0;
    leg.branch = -1;  // carriage above its platform point
    leg.E = 7e10;
    leg.area = 3e-5;
    leg.rods = 2;
    leg.actuator_stiffness = 2e7;
    leg.base_axis = -leg.axis;
    leg.platform_axis = leg.axis;
    d.legs.push_back(leg);
  }
  d.tcp = Q * Eigen::Vector3d(0, 0, -0.05);
  d.home.position = Q * Eigen::Vector3d(0, 0, 0.4 - 0.35 - 0.05);
  return d;
}

struct Named {
  const char* name;
  std::unique_ptr<LegChainMachine> machine;
  double dx, dangle;
};

std::vector<Named> named_models() {
  std::vector<Named> v;
  v.push_back({"delta", std::make_unique<LegChainMachine>(delta_design(DeltaDesign{})), 0.3, 0});
  v.push_back({"linear_delta",
               std::make_unique<LegChainMachine>(linear_delta_design(LinearDeltaDesign{})), 0.1,
               0});
  LinearDeltaDesign inclined;
  inclined.inclination = deg_to_rad(20);
  inclined.guide_radius = 0.35;
  v.push_back({"linear_delta_inclined",
               std::make_unique<LegChainMachine>(linear_delta_design(inclined)), 0.1, 0});
  v.push_back({"hexaglide", std::make_unique<LegChainMachine>(hexaglide_design(HexaglideDesign{})),
               0.1, 0.15});
  HexaglideDesign inclined_glide;
  inclined_glide.inclination = deg_to_rad(15);
  v.push_back({"hexaglide_inclined",
               std::make_unique<LegChainMachine>(hexaglide_design(inclined_glide)), 0.1, 0.15});
  v.push_back({"schoenflies", std::make_unique<LegChainMachine>(schoenflies_sample()), 0.08, 0.5});
  const Eigen::Matrix3d Q =
      Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, -0.5).normalized()).toRotationMatrix();
  v.push_back({"schoenflies_tilted_axis",
               std::make_unique<LegChainMachine>(schoenflies_sample(60.0, Q)), 0.08, 0.5});
  v.push_back({"tripod_3prs",
               std::make_unique<LegChainMachine>(tripod_3prs_design(Tripod3PrsDesign{})), 0.2,
               0.6});
  v.push_back({"tripod_3rps",
               std::make_unique<LegChainMachine>(tripod_3rps_design(Tripod3RpsDesign{})), 0.2,
               0.6});
  return v;
}

// ------------------------------------------------------------------------------------------
// Published delta numbers.

// R. L. Williams II, "The Delta Parallel Robot: Kinematics Solutions", Ohio University, 2015
// (www.ohio.edu/people/williar4/html/pdf/DeltaKin.pdf), examples for the ABB FlexPicker
// IRB 360 dimensions sB = 0.567, sP = 0.076, L = 0.524, l = 1.244 m, i.e. wB = sB sqrt(3)/6 =
// 0.164 m (centre to the drive pivots) and uP = sP sqrt(3)/3 = 0.044 m (TCP to the rod-pair
// centres). Williams' frame and angles are ours: pivot B1 = (0, -wB, 0) (azimuth -90 deg), B2 at
// 30 deg, B3 at 150 deg, z up, theta_i = 0 with the arm horizontal outwards and the elbow at
// z = -L sin(theta_i), i.e. positive theta lowers the elbow; the published IPK solutions are
// the elbow-out ones. Published (rounded to 0.1 deg):
//   IPK  P = (0, 0, -0.9) m      ->  theta = (-20.5, -20.5, -20.5) deg
//   IPK  P = (0.3, 0.5, -1.1) m  ->  theta = (47.5, -11.6, 21.4) deg
DeltaDesign williams_irb360() {
  DeltaDesign d;
  d.base_radius = 0.567 * std::sqrt(3.0) / 6.0;
  d.platform_radius = 0.076 * std::sqrt(3.0) / 3.0;
  d.upper_arm = 0.524;
  d.rod = 1.244;
  return d;
}

TEST(Delta, InverseKinematicsMatchesWilliamsPublishedExamples) {
  const LegChainMachine delta(delta_design(williams_irb360()));
  const struct {
    Eigen::Vector3d p;
    Eigen::Vector3d theta_deg;
  } cases[] = {{{0, 0, -0.9}, {-20.5, -20.5, -20.5}}, {{0.3, 0.5, -1.1}, {47.5, -11.6, 21.4}}};
  for (const auto& c : cases) {
    const auto q = delta.inverse_kinematics(Pose{c.p, Eigen::Vector3d::Zero()});
    ASSERT_TRUE(q.has_value());
    for (int i = 0; i < 3; ++i) {
      EXPECT_NEAR(rad_to_deg((*q)(i)), c.theta_deg(i), 0.05) << "leg " << i + 1;  // rounding
    }
  }
}

// FK of the published (rounded) angles must give the published position back, to within what
// the 0.05 deg rounding moves it: |dx| <= |J^-1| * 0.05 deg * sqrt(3).
TEST(Delta, ForwardKinematicsMatchesWilliamsPublishedExamples) {
  const LegChainMachine delta(delta_design(williams_irb360()));
  const struct {
    Eigen::Vector3d p;
    Eigen::Vector3d theta_deg;
  } cases[] = {{{0, 0, -0.9}, {-20.5, -20.5, -20.5}}, {{0.3, 0.5, -1.1}, {47.5, -11.6, 21.4}}};
  for (const auto& c : cases) {
    const Eigen::VectorXd q = deg_to_rad(c.theta_deg);
    const FkResult r = delta.forward_kinematics(q, std::nullopt);
    ASSERT_TRUE(r.converged) << r.message;
    Eigen::MatrixXd A, B, J;
    delta.jacobians(Pose{c.p, Eigen::Vector3d::Zero()}, A, B, J);
    const double bound = J.inverse().norm() * deg_to_rad(0.05) * std::sqrt(3.0);
    EXPECT_LT((r.pose.position - c.p).norm(), bound);
    EXPECT_LT(bound, 5e-3);  // the check is meaningful: a few mm at most
    EXPECT_EQ(r.pose.angles, Eigen::Vector3d::Zero());
  }
}

// The Trossen Robotics tutorial "Delta robot kinematics" (M. Zavatsky, 2009,
// forums.trossenrobotics.com/tutorials/introduction-129/delta-robot-kinematics-3276) publishes
// closed-form IK (delta_calcAngleYZ) and FK (delta_calcForward) in C for the sample geometry
// e = 115, f = 457.3, re = 232, rf = 112 (mm): f and e are the sides of the base and effector
// triangles, so base_radius = f / (2 sqrt 3), platform_radius = e / (2 sqrt 3); rf is the arm,
// re the rod. Its frame and angles are ours (leg 1 in the YZ plane at y < 0, theta > 0 lowers
// the elbow; legs 2 and 3 at +-120 deg). Re-implemented here from the tutorial, in mm.
bool trossen_angle_yz(double x0, double y0, double z0, double& theta) {
  const double e = 115.0, f = 457.3, re = 232.0, rf = 112.0;
  const double tan30 = 1.0 / std::sqrt(3.0);
  const double y1 = -0.5 * tan30 * f;
  y0 -= 0.5 * tan30 * e;
  const double a = (x0 * x0 + y0 * y0 + z0 * z0 + rf * rf - re * re - y1 * y1) / (2 * z0);
  const double b = (y1 - y0) / z0;
  const double d = -(a + b * y1) * (a + b * y1) + rf * (b * b * rf + rf);
  if (d < 0) return false;
  const double yj = (y1 - a * b - std::sqrt(d)) / (b * b + 1);
  const double zj = a + b * yj;
  theta = std::atan(-zj / (y1 - yj)) + ((yj > y1) ? kPi : 0.0);
  return true;
}

bool trossen_inverse(const Eigen::Vector3d& p, Eigen::Vector3d& theta) {
  const double c120 = -0.5, s120 = std::sqrt(3.0) / 2.0;
  const double x = p.x(), y = p.y(), z = p.z();
  return trossen_angle_yz(x, y, z, theta(0)) &&
         trossen_angle_yz(x * c120 + y * s120, y * c120 - x * s120, z, theta(1)) &&
         trossen_angle_yz(x * c120 - y * s120, y * c120 + x * s120, z, theta(2));
}

bool trossen_forward(const Eigen::Vector3d& theta, Eigen::Vector3d& p) {
  const double e = 115.0, f = 457.3, re = 232.0, rf = 112.0;
  const double tan30 = 1.0 / std::sqrt(3.0), tan60 = std::sqrt(3.0), sin30 = 0.5;
  const double t = (f - e) * tan30 / 2;
  const double y1 = -(t + rf * std::cos(theta(0))), z1 = -rf * std::sin(theta(0));
  const double y2 = (t + rf * std::cos(theta(1))) * sin30, x2 = y2 * tan60,
               z2 = -rf * std::sin(theta(1));
  const double y3 = (t + rf * std::cos(theta(2))) * sin30, x3 = -y3 * tan60,
               z3 = -rf * std::sin(theta(2));
  const double dnm = (y2 - y1) * x3 - (y3 - y1) * x2;
  const double w1 = y1 * y1 + z1 * z1, w2 = x2 * x2 + y2 * y2 + z2 * z2,
               w3 = x3 * x3 + y3 * y3 + z3 * z3;
  const double a1 = (z2 - z1) * (y3 - y1) - (z3 - z1) * (y2 - y1);
  const double b1 = -((w2 - w1) * (y3 - y1) - (w3 - w1) * (y2 - y1)) / 2.0;
  const double a2 = -(z2 - z1) * x3 + (z3 - z1) * x2;
  const double b2 = ((w2 - w1) * x3 - (w3 - w1) * x2) / 2.0;
  const double a = a1 * a1 + a2 * a2 + dnm * dnm;
  const double b = 2 * (a1 * b1 + a2 * (b2 - y1 * dnm) - z1 * dnm * dnm);
  const double c = (b2 - y1 * dnm) * (b2 - y1 * dnm) + b1 * b1 + dnm * dnm * (z1 * z1 - re * re);
  const double d = b * b - 4.0 * a * c;
  if (d < 0) return false;
  const double z0 = -0.5 * (b + std::sqrt(d)) / a;
  p = Eigen::Vector3d((a1 * z0 + b1) / dnm, (a2 * z0 + b2) / dnm, z0);
  return true;
}

TEST(Delta, AgreesWithTheTrossenTutorialEquations) {
  DeltaDesign d;
  d.base_radius = 457.3e-3 / (2.0 * std::sqrt(3.0));
  d.platform_radius = 115e-3 / (2.0 * std::sqrt(3.0));
  d.upper_arm = 112e-3;
  d.rod = 232e-3;
  d.theta_min = -kPi;
  d.theta_max = kPi;
  const LegChainMachine delta(delta_design(d));
  Uniform u(7);
  int compared = 0;
  for (int k = 0; k < 200; ++k) {
    const Eigen::Vector3d p(u(-0.12, 0.12), u(-0.12, 0.12), u(-0.30, -0.12));
    Eigen::Vector3d theta;
    const bool published_ok = trossen_inverse(p * 1e3, theta);
    const auto q = delta.inverse_kinematics(Pose{p, Eigen::Vector3d::Zero()});
    EXPECT_EQ(published_ok, q.has_value()) << p.transpose();
    if (!published_ok || !q) continue;
    ++compared;
    for (int i = 0; i < 3; ++i) EXPECT_NEAR(wrap_angle_for_test((*q)(i)-theta(i)), 0.0, 1e-12);
    Eigen::Vector3d p_published;
    ASSERT_TRUE(trossen_forward(theta, p_published));
    const FkResult r = delta.forward_kinematics(*q, std::nullopt);
    ASSERT_TRUE(r.converged) << r.message;
    EXPECT_NEAR((r.pose.position - p_published * 1e-3).norm(), 0.0, 1e-12);
    EXPECT_NEAR((r.pose.position - p).norm(), 0.0, 1e-12);
  }
  EXPECT_GT(compared, 100);
}

// ------------------------------------------------------------------------------------------
// The family on every named model.

TEST(LegChain, ConstraintJacobiansMatchFiniteDifferences) {
  for (const Named& nm : named_models()) {
    const LegChainMachine& m = *nm.machine;
    const int n = m.num_actuators();
    const auto poses = sample_poses(m, 11, 8, nm.dx, nm.dangle);
    ASSERT_EQ(poses.size(), 8u) << nm.name;
    const double h = 1e-6;
    for (const Pose& pose : poses) {
      Eigen::MatrixXd A, B, J;
      m.jacobians(pose, A, B, J);
      const Eigen::VectorXd q = *m.inverse_kinematics(pose);
      for (int i = 0; i < n; ++i) {
        // A = d closure / d twist at fixed q; B = -d closure / dq at a fixed pose.
        for (int j = 0; j < n; ++j) {
          const double fd = (closure(m, i, moved(m, pose, j, h), q(i)) -
                             closure(m, i, moved(m, pose, j, -h), q(i))) /
                            (2 * h);
          EXPECT_NEAR(A(i, j), fd, 1e-7) << nm.name << " A(" << i << "," << j << ")";
        }
        const double fdq =
            -(closure(m, i, pose, q(i) + h) - closure(m, i, pose, q(i) - h)) / (2 * h);
        EXPECT_NEAR(B(i, i), fdq, 1e-7) << nm.name << " B(" << i << ")";
      }
      // J = dq / d twist from the closed-form IK.
      for (int j = 0; j < n; ++j) {
        const Eigen::VectorXd fd = (*m.inverse_kinematics(moved(m, pose, j, h)) -
                                    *m.inverse_kinematics(moved(m, pose, j, -h))) /
                                   (2 * h);
        for (int i = 0; i < n; ++i) {
          EXPECT_NEAR(J(i, j), fd(i), 1e-6 * (1.0 + std::abs(J(i, j)))) << nm.name;
        }
      }
    }
  }
}

TEST(LegChain, TwistJacobianMatchesFiniteDifferencesOfTheInverseKinematics) {
  for (const Named& nm : named_models()) {
    const LegChainMachine& m = *nm.machine;
    auto data = m.make_data();
    const double h = 1e-6;
    for (const Pose& pose : sample_poses(m, 12, 4, nm.dx, nm.dangle)) {
      Eigen::MatrixXd J;
      ASSERT_TRUE(m.twist_jacobian(*data, pose, J)) << nm.name;
      ASSERT_EQ(J.rows(), m.num_actuators());
      ASSERT_EQ(J.cols(), 6);
      // Every twist the platform can make: xi = T e_j for each DOF j.
      const Eigen::MatrixXd JT = J * m.twist_map(pose);
      for (int j = 0; j < m.dof(); ++j) {
        const Eigen::VectorXd fd = (*m.inverse_kinematics(moved(m, pose, j, h)) -
                                    *m.inverse_kinematics(moved(m, pose, j, -h))) /
                                   (2 * h);
        for (int i = 0; i < m.num_actuators(); ++i) {
          EXPECT_NEAR(JT(i, j), fd(i), 1e-6 * (1.0 + std::abs(JT(i, j)))) << nm.name;
        }
      }
    }
  }
}

TEST(LegChain, InverseThenForwardKinematicsRoundTrips) {
  for (const Named& nm : named_models()) {
    const LegChainMachine& m = *nm.machine;
    for (const Pose& pose : sample_poses(m, 12, 20, nm.dx, nm.dangle)) {
      const Eigen::VectorXd q = *m.inverse_kinematics(pose);
      const FkResult r = m.forward_kinematics(q, std::nullopt);
      ASSERT_TRUE(r.converged) << nm.name << ": " << r.message;
      EXPECT_LE(r.residual, 1e-12);
      EXPECT_NEAR((r.pose.position - pose.position).norm(), 0.0, 1e-9) << nm.name;
      const Eigen::Matrix3d dR =
          rotation_zyx<double>(r.pose.angles).transpose() * rotation_zyx<double>(pose.angles);
      EXPECT_NEAR(rotation_vector(dR).norm(), 0.0, 1e-9) << nm.name;
      // IK of the FK pose reproduces q.
      EXPECT_NEAR((*m.inverse_kinematics(r.pose) - q).cwiseAbs().maxCoeff(), 0.0, 1e-9);
    }
  }
}

// J^T tau = T^T w, and by virtual work tau . dq = w . (T dxi) for a small motion dxi, with dq from
// the closed-form IK (central differences).
TEST(LegChain, ActuatorForcesBalanceTheWrenchByVirtualWork) {
  Uniform u(13);
  for (const Named& nm : named_models()) {
    const LegChainMachine& m = *nm.machine;
    const int n = m.num_actuators();
    auto data = m.make_data();
    for (const Pose& pose : sample_poses(m, 14, 6, nm.dx, nm.dangle)) {
      Wrench w;
      for (int k = 0; k < 6; ++k) w(k) = u(-100, 100);
      PoseMetrics metrics;
      m.analyze(*data, pose, w, metrics);
      ASSERT_FALSE(metrics.singular);
      Eigen::MatrixXd A, B, J;
      m.jacobians(pose, A, B, J);
      const Eigen::VectorXd w_dof = m.twist_map(pose).transpose() * w;
      EXPECT_NEAR((J.transpose() * metrics.tau - w_dof).norm(), 0.0, 1e-9 * (1 + w.norm()));
      const double h = 1e-6;
      for (int j = 0; j < n; ++j) {
        const Eigen::VectorXd dq = (*m.inverse_kinematics(moved(m, pose, j, h)) -
                                    *m.inverse_kinematics(moved(m, pose, j, -h))) /
                                   2.0;
        EXPECT_NEAR(metrics.tau.dot(dq), w_dof(j) * h, 1e-6 * h * (1 + metrics.tau.norm()))
            << nm.name;
      }
      // Rod forces: tension positive; a pull on the platform away from a leg's actuated point
      // along s_i stretches it.
      EXPECT_TRUE(metrics.tau.allFinite());
    }
  }
}

// The stiffness chain built physically: a force f at the TCP loads the links with f_l = A^-T f,
// they stretch by f_l / k_link, the actuators give dq = B f_l / k_act, and the platform moves by
// A^-1 (B dq + stretch). stiffness_min is the smallest f.dx / |f|^2 over force directions, i.e.
// 1 / the largest eigenvalue of that compliance.
TEST(LegChain, StiffnessMinMatchesTheSeriesChain) {
  for (const Named& nm : named_models()) {
    const LegChainMachine& m = *nm.machine;
    const int n = m.num_actuators();
    auto data = m.make_data();
    for (const Pose& pose : sample_poses(m, 15, 4, nm.dx, nm.dangle)) {
      PoseMetrics metrics;
      m.analyze(*data, pose, Wrench::Zero(), metrics);
      Eigen::MatrixXd A, B, J;
      m.jacobians(pose, A, B, J);
      const Eigen::VectorXd q = *m.inverse_kinematics(pose);
      const Eigen::MatrixXd T = m.twist_map(pose);
      Eigen::Matrix3d C;
      for (int k = 0; k < 3; ++k) {
        // A unit force along base axis k at the TCP: its DOF components T^T [e_k; 0].
        const Eigen::VectorXd f = T.transpose().col(k);
        const Eigen::VectorXd f_link = A.transpose().inverse() * f;
        Eigen::VectorXd dq(n), stretch(n);
        for (int i = 0; i < n; ++i) {
          const LegChainLeg& leg = m.design().legs[static_cast<std::size_t>(i)];
          const double length = leg.kind == LegKind::kUPS ? q(i) : leg.link_length;
          const double k_link =
              leg.axial_stiffness > 0 ? leg.axial_stiffness : leg.E * leg.area * leg.rods / length;
          stretch(i) = f_link(i) / k_link;
          const double tau = B(i, i) * f_link(i);
          dq(i) = leg.actuator_stiffness > 0 ? tau / leg.actuator_stiffness : 0.0;
        }
        const Eigen::VectorXd dx = T * (A.inverse() * (B * dq + stretch));
        C.col(k) = dx.head(3);
      }
      Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(0.5 * (C + C.transpose()));
      EXPECT_NEAR(metrics.stiffness_min, 1.0 / eig.eigenvalues()(2), 1e-9 * metrics.stiffness_min)
          << nm.name;
      EXPECT_NEAR((C - C.transpose()).norm(), 0.0, 1e-9 * C.norm());
    }
  }
}

// tcp_error_max against a brute force over the box vertices of dx = J^-1 dq.
TEST(LegChain, TcpErrorMaxIsTheWorstBoxVertex) {
  for (const Named& nm : named_models()) {
    const LegChainMachine& m = *nm.machine;
    const int n = m.num_actuators();
    auto data = m.make_data();
    for (const Pose& pose : sample_poses(m, 16, 3, nm.dx, nm.dangle)) {
      PoseMetrics metrics;
      m.analyze(*data, pose, Wrench::Zero(), metrics);
      Eigen::MatrixXd A, B, J;
      m.jacobians(pose, A, B, J);
      const Eigen::MatrixXd Jinv = m.twist_map(pose) * J.inverse();
      double best = 0;
      for (int v = 0; v < (1 << n); ++v) {
        Eigen::VectorXd dq(n);
        for (int i = 0; i < n; ++i) dq(i) = (v >> i & 1 ? 1.0 : -1.0) * m.design().actuator_error;
        best = std::max(best, (Jinv * dq).head(3).norm());
      }
      EXPECT_NEAR(metrics.tcp_error_max, best, 1e-12 * best) << nm.name;
      // singularity_margin = 1 / cond(J_h).
      Eigen::MatrixXd Jh = J;
      Jh.rightCols(n - m.first_rotational_dof()) /= m.characteristic_length();
      Eigen::JacobiSVD<Eigen::MatrixXd> svd(Jh);
      const auto& sv = svd.singularValues();
      EXPECT_NEAR(metrics.singularity_margin, sv(n - 1) / sv(0), 1e-9);
      EXPECT_NEAR(metrics.det_j, J.determinant(), 1e-9 * std::abs(J.determinant()));
    }
  }
}

// ------------------------------------------------------------------------------------------
// Singularities.

// Serial: leg 1's arm and rod aligned (the platform point on the extension of the crank).
TEST(Delta, SerialSingularityWhenArmAndRodAlign) {
  const DeltaDesign d;
  const LegChainMachine delta(delta_design(d));
  // The crank points down and inwards so that legs 2 and 3 reach the platform too.
  const double theta = deg_to_rad(100);
  const Eigen::Vector3d u(0, -1, 0);  // leg 1's azimuth -90 deg
  const Eigen::Vector3d crank_dir =
      std::cos(theta) * u - std::sin(theta) * Eigen::Vector3d::UnitZ();
  auto pose_at = [&](double extra) {
    // Platform point at distance upper_arm + rod - extra from the pivot along the crank
    // direction: the elbow bends by about sqrt(extra) out of the alignment.
    const Eigen::Vector3d P = d.base_radius * u + (d.upper_arm + d.rod - extra) * crank_dir;
    return Pose{P - d.platform_radius * u, Eigen::Vector3d::Zero()};
  };
  auto data = delta.make_data();
  auto& ld = static_cast<LegChainData&>(*data);
  PoseMetrics m;
  // Approaching the alignment the margin falls to 0 continuously.
  double previous = 1.0;
  for (double extra : {1e-2, 1e-4, 1e-6, 1e-9}) {
    delta.analyze(*data, pose_at(extra), Wrench::Zero(), m);
    ASSERT_TRUE(ld.ik_ok) << extra;
    EXPECT_FALSE(ld.serial_singular) << extra;
    EXPECT_LT(m.singularity_margin, previous);
    previous = m.singularity_margin;
  }
  EXPECT_LT(previous, 1e-3);
  delta.analyze(*data, pose_at(0.0), Wrench(Wrench::Constant(1.0)), m);
  EXPECT_TRUE(ld.serial_singular);
  EXPECT_FALSE(ld.parallel_singular);
  EXPECT_TRUE(m.singular);
  EXPECT_EQ(m.singularity_margin, 0.0);
  EXPECT_EQ(m.stiffness_min, 0.0);
  EXPECT_TRUE(std::isinf(m.tcp_error_max));
  EXPECT_TRUE(std::isinf(m.tau(0)));
  EXPECT_TRUE(m.q.allFinite());
  EXPECT_NEAR(m.q(0), theta, 1e-6);
}

// Parallel: the three rods parallel (all vertical): the platform can move sideways with the
// drives locked, det A = 0.
TEST(Delta, ParallelSingularityWhenRodsAreParallel) {
  DeltaDesign d;
  const double theta = deg_to_rad(40);
  d.platform_radius = d.base_radius + d.upper_arm * std::cos(theta);
  const LegChainMachine delta(delta_design(d));
  const Pose pose{{0, 0, -d.upper_arm * std::sin(theta) - d.rod}, Eigen::Vector3d::Zero()};
  auto data = delta.make_data();
  auto& ld = static_cast<LegChainData&>(*data);
  PoseMetrics m;
  delta.analyze(*data, pose, Wrench(Wrench::Constant(1.0)), m);
  EXPECT_TRUE(ld.parallel_singular);
  EXPECT_FALSE(ld.serial_singular);
  EXPECT_TRUE(m.singular);
  EXPECT_EQ(m.singularity_margin, 0.0);
  EXPECT_EQ(m.stiffness_min, 0.0);
  EXPECT_TRUE(std::isinf(m.tau(1)));
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(m.q(i), theta, 1e-9);
  // Off the singularity the margin is positive and grows.
  delta.analyze(*data, Pose{{0, 0, pose.position.z() + 0.05}, Eigen::Vector3d::Zero()},
                Wrench::Zero(), m);
  EXPECT_GT(m.singularity_margin, 1e-3);
}

// Linear delta: a rod perpendicular to its vertical guide is a serial singularity (the carriage
// moves the rod end sideways only).
TEST(LinearDelta, SerialSingularityWhenARodIsHorizontal) {
  const LinearDeltaDesign d;
  const LegChainMachine m(linear_delta_design(d));
  // Leg 1 (azimuth -90): carriage at (0, -guide_radius, q); rod horizontal towards the centre.
  const double q1 = 0.3;
  const Eigen::Vector3d P1(0, -d.guide_radius + d.rod, q1);
  const Pose pose{P1 - d.platform_radius * Eigen::Vector3d(0, -1, 0), Eigen::Vector3d::Zero()};
  auto data = m.make_data();
  auto& ld = static_cast<LegChainData&>(*data);
  PoseMetrics metrics;
  m.analyze(*data, pose, Wrench::Zero(), metrics);
  EXPECT_TRUE(ld.serial_singular);
  EXPECT_EQ(metrics.singularity_margin, 0.0);
  EXPECT_NEAR(metrics.q(0), q1, 1e-6);
}

// Hexaglide: every strut in the plane of the guides and of the platform joints (platform level
// with the guides) - the platform can move out of that plane with the carriages locked.
TEST(Hexaglide, ParallelSingularityWhenAllStrutsAreCoplanar) {
  const HexaglideDesign d;
  const LegChainMachine m(hexaglide_design(d));
  auto data = m.make_data();
  auto& ld = static_cast<LegChainData&>(*data);
  PoseMetrics metrics;
  m.analyze(*data, Pose{{0, 0, 0}, Eigen::Vector3d::Zero()}, Wrench::Zero(), metrics);
  ASSERT_TRUE(ld.ik_ok);
  EXPECT_TRUE(ld.parallel_singular);
  EXPECT_EQ(metrics.singularity_margin, 0.0);
  EXPECT_TRUE(std::isinf(metrics.tcp_error_max));
  m.analyze(*data, Pose{{0, 0, d.home_height}, Eigen::Vector3d::Zero()}, Wrench::Zero(), metrics);
  EXPECT_FALSE(metrics.singular);
}

// ------------------------------------------------------------------------------------------
// Schoenflies (3T1R) platforms.

TEST(Schoenflies, OnlyRotationsAboutTheAxisAreReachable) {
  const LegChainMachine m(schoenflies_sample());
  auto data = m.make_data();
  const Eigen::Vector3d p = m.design().home.position;
  const Pose turned{p, Eigen::Vector3d(0, 0, deg_to_rad(20))};
  EXPECT_TRUE(m.reachable(*data, turned));
  const Pose tilted{p, Eigen::Vector3d(deg_to_rad(1), 0, deg_to_rad(20))};
  EXPECT_FALSE(m.reachable(*data, tilted));
  // The tilted pose is analysed at its twist about e: R = Rot(z, phi) with the same turn of x.
  const auto actual = m.actual_pose(tilted);
  ASSERT_TRUE(actual.has_value());
  EXPECT_NEAR(actual->angles(0), 0.0, 1e-15);
  EXPECT_NEAR(actual->angles(1), 0.0, 1e-15);
  const Eigen::Matrix3d R_tilted = rotation_zyx<double>(tilted.angles);
  const Eigen::Matrix3d R_actual = rotation_zyx<double>(actual->angles);
  // Swing-twist: R_tilted = swing * twist with the swing turning about an axis orthogonal to e.
  const Eigen::AngleAxisd swing(R_tilted * R_actual.transpose());
  EXPECT_NEAR(swing.axis().dot(Eigen::Vector3d::UnitZ()) * std::sin(swing.angle()), 0.0, 1e-12);
  EXPECT_EQ(m.dof(), 4);
  EXPECT_EQ(m.first_rotational_dof(), 3);
}

// A machine turned as a whole by Q (e = Q z) has the same actuator coordinates at the turned
// pose, and the same metrics.
TEST(Schoenflies, TiltedAxisMachineIsTheTurnedMachine) {
  const Eigen::Matrix3d Q =
      Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, -0.5).normalized()).toRotationMatrix();
  const LegChainMachine upright(schoenflies_sample());
  const LegChainMachine turned(schoenflies_sample(60.0, Q));
  Uniform u(31);
  auto d1 = upright.make_data();
  auto d2 = turned.make_data();
  for (int k = 0; k < 10; ++k) {
    const Pose p = random_pose(upright, u, 0.08, 0.5);
    const Pose pq{Q * p.position,
                  angles_from_rotation(Q * rotation_zyx<double>(p.angles) * Q.transpose())};
    Wrench w;
    for (int j = 0; j < 6; ++j) w(j) = u(-50, 50);
    Wrench wq;
    wq << Q * w.head<3>(), Q * w.tail<3>();
    PoseMetrics m1, m2;
    upright.analyze(*d1, p, w, m1);
    turned.analyze(*d2, pq, wq, m2);
    EXPECT_EQ(m1.reachable, m2.reachable);
    EXPECT_NEAR((m1.q - m2.q).norm(), 0.0, 1e-12);
    EXPECT_NEAR((m1.tau - m2.tau).norm(), 0.0, 1e-9 * (1 + m1.tau.norm()));
    EXPECT_NEAR(m1.stiffness_min, m2.stiffness_min, 1e-8 * m1.stiffness_min);
    EXPECT_NEAR(m1.singularity_margin, m2.singularity_margin, 1e-9);
    EXPECT_NEAR(m1.tcp_error_max, m2.tcp_error_max, 1e-9 * m1.tcp_error_max);
  }
}

// Struts meeting the platform radially (offset 0): no strut has a moment about e, the platform
// turns about e with the carriages locked (the A column of omega_e is zero): det A = 0.
TEST(Schoenflies, ParallelSingularityWhenNoStrutTurnsThePlatform) {
  const LegChainMachine m(schoenflies_sample(0.0));
  auto data = m.make_data();
  auto& ld = static_cast<LegChainData&>(*data);
  PoseMetrics metrics;
  m.analyze(*data, m.design().home, Wrench(Wrench::Constant(1.0)), metrics);
  ASSERT_TRUE(ld.ik_ok);
  EXPECT_TRUE(ld.parallel_singular);
  EXPECT_FALSE(ld.serial_singular);
  EXPECT_NEAR(ld.A.col(3).norm(), 0.0, 1e-15);
  EXPECT_TRUE(metrics.singular);
  EXPECT_EQ(metrics.singularity_margin, 0.0);
  EXPECT_EQ(metrics.stiffness_min, 0.0);
  EXPECT_TRUE(std::isinf(metrics.tcp_error_max));
  EXPECT_TRUE(std::isinf(metrics.tau(0)));
  // With offsets of +-60 deg the same pose is well conditioned.
  const LegChainMachine offset(schoenflies_sample(60.0));
  offset.analyze(*offset.make_data(), offset.design().home, Wrench::Zero(), metrics);
  EXPECT_FALSE(metrics.singular);
  EXPECT_GT(metrics.singularity_margin, 1e-2);
}

// ------------------------------------------------------------------------------------------
// tripod_3prs (planar legs).

// Plane constraint residuals h_i of a pose taken as given.
Eigen::Vector3d plane_residuals(const LegChainMachine& m, const Pose& pose) {
  Eigen::Vector3d h;
  const Eigen::Matrix3d R = rotation_zyx<double>(pose.angles);
  for (int i = 0; i < 3; ++i) {
    const LegChainLeg& leg = m.design().legs[static_cast<std::size_t>(i)];
    h(i) = leg.plane_normal.dot(pose.position + R * (leg.platform_point - m.design().tcp) -
                                leg.base_point);
  }
  return h;
}

TEST(Tripod3Prs, ParasiticMotionKeepsEveryLegInItsPlane) {
  const LegChainMachine m(tripod_3prs_design(Tripod3PrsDesign{}));
  Uniform u(41);
  double largest_parasitic = 0.0;
  for (int k = 0; k < 50; ++k) {
    const Pose asked{Eigen::Vector3d(u(-1, 1), u(-1, 1), u(0.9, 1.5)),
                     Eigen::Vector3d(u(-0.7, 0.7), u(-0.7, 0.7), u(-1, 1))};
    const auto actual = m.actual_pose(asked);
    ASSERT_TRUE(actual.has_value());
    EXPECT_LT(plane_residuals(m, *actual).cwiseAbs().maxCoeff(), 1e-14);
    // z, rx, ry are kept; x, y, rz of the request do not matter.
    EXPECT_EQ(actual->position.z(), asked.position.z());
    EXPECT_EQ(actual->angles(0), asked.angles(0));
    EXPECT_EQ(actual->angles(1), asked.angles(1));
    Pose other = asked;
    other.position.head<2>() = Eigen::Vector2d(u(-1, 1), u(-1, 1));
    other.angles(2) = u(-1, 1);
    const auto actual_other = m.actual_pose(other);
    ASSERT_TRUE(actual_other.has_value());
    EXPECT_EQ(actual_other->position, actual->position);
    EXPECT_EQ(actual_other->angles, actual->angles);
    largest_parasitic = std::max(largest_parasitic, actual->position.head<2>().norm());
    // The platform moves along T: h stays 0 to second order.
    const double h = 1e-5;
    for (int j = 0; j < 3; ++j) {
      EXPECT_LT(plane_residuals(m, moved(m, *actual, j, h)).cwiseAbs().maxCoeff(), 1e-8);
    }
    // The 3-PRS with legs at 120 deg is a zero-torsion mechanism (Bonev, "Geometric analysis of
    // parallel mechanisms", PhD thesis, Laval 2002; I. A. Bonev, "Zero-torsion parallel
    // mechanisms", parallemic.org 2008): with the tool axis k = R z, R is the pure tilt about
    // z x k (no turn about the tool axis).
    const Eigen::Matrix3d R = rotation_zyx<double>(actual->angles);
    const Eigen::Vector3d k_axis = R.col(2);
    const Eigen::Vector3d tilt_axis = Eigen::Vector3d::UnitZ().cross(k_axis);
    const Eigen::Matrix3d pure_tilt =
        Eigen::AngleAxisd(std::atan2(tilt_axis.norm(), k_axis.z()), tilt_axis.normalized())
            .toRotationMatrix();
    EXPECT_NEAR((R - pure_tilt).norm(), 0.0, 1e-12);
  }
  EXPECT_GT(largest_parasitic, 1e-3);  // the parasitic motion is real (mm), not zero
}

// The 3-RPS head's platform points stay in the vertical planes through the head axis at
// azimuths a_i = -90, 30, 150 deg, as the 3-PRS head's. Closed form (the zero-torsion 3-RPS of
// Carretero, Podhorodeski, Nahon & Gosselin, J. Mech. Design 122(1), 2000): with the tool axis
// k = (cos phi sin theta, sin phi sin theta, cos theta), R = Rz(phi) Ry(theta) Rz(-phi) and the
// platform centre c = (-(r/2)(1 - cos theta) sin 2 phi, -(r/2)(1 - cos theta) cos 2 phi, z_c)
// (n_i . (c + R r u_i) = 0 with n_i . R u_i = sin(2 (a_i - phi)) (1 - cos theta) / 2, and for
// these azimuths sin 2a_i = cos a_i, cos 2a_i = sin a_i). A 3-PRS head with the same platform
// takes the same pose; the leg lengths are the distances from the base joints.
TEST(Tripod3Rps, ParasiticMotionIsTheClosedFormAndTheThreePrsHeads) {
  const Tripod3RpsDesign a3;
  const LegChainMachine rps(tripod_3rps_design(a3));
  Tripod3PrsDesign z3_design;
  z3_design.platform_radius = a3.platform_radius;
  z3_design.tool_length = a3.tool_length;
  const LegChainMachine prs(tripod_3prs_design(z3_design));
  const double r = a3.platform_radius;
  Uniform u(43);
  double largest = 0.0;
  for (int k = 0; k < 40; ++k) {
    const Pose asked{Eigen::Vector3d(u(-1, 1), u(-1, 1), u(0.9, 1.3)),
                     Eigen::Vector3d(u(-0.6, 0.6), u(-0.6, 0.6), u(-1, 1))};
    const auto actual = rps.actual_pose(asked);
    ASSERT_TRUE(actual.has_value());
    const Eigen::Matrix3d R = rotation_zyx<double>(actual->angles);
    const Eigen::Vector3d k_axis = R.col(2);
    const double theta = std::acos(std::clamp(k_axis.z(), -1.0, 1.0));
    const double phi = std::atan2(k_axis.y(), k_axis.x());
    const Eigen::Matrix3d expected_R = (Eigen::AngleAxisd(phi, Eigen::Vector3d::UnitZ()) *
                                        Eigen::AngleAxisd(theta, Eigen::Vector3d::UnitY()) *
                                        Eigen::AngleAxisd(-phi, Eigen::Vector3d::UnitZ()))
                                           .toRotationMatrix();
    EXPECT_NEAR((R - expected_R).norm(), 0.0, 1e-12);
    const Eigen::Vector3d c = actual->position - R * Eigen::Vector3d(0, 0, a3.tool_length);
    const double lift = 0.5 * r * (1.0 - std::cos(theta));
    EXPECT_NEAR(c.x(), -lift * std::sin(2 * phi), 1e-12);
    EXPECT_NEAR(c.y(), -lift * std::cos(2 * phi), 1e-12);
    largest = std::max(largest, c.head<2>().norm());
    const auto same = prs.actual_pose(asked);
    ASSERT_TRUE(same.has_value());
    EXPECT_NEAR((same->position - actual->position).norm(), 0.0, 1e-12);
    EXPECT_NEAR((same->angles - actual->angles).norm(), 0.0, 1e-12);
    const std::optional<Eigen::VectorXd> q = rps.inverse_kinematics(*actual);
    ASSERT_TRUE(q.has_value());
    for (int i = 0; i < 3; ++i) {
      const double a = deg_to_rad(-90.0 + 120.0 * i);
      const Eigen::Vector3d dir(std::cos(a), std::sin(a), 0.0);
      EXPECT_NEAR((*q)(i), (c + R * (r * dir) - a3.base_radius * dir).norm(), 1e-12);
    }
  }
  EXPECT_GT(largest, 1e-3);  // millimetres of parasitic motion: the check is not empty
}

// Serial singularity: a strut perpendicular to its slide (B_i = s_i . z = 0). With
// base_radius - platform_radius = strut the struts of a level platform are horizontal; with the
// strut longer by delta they are inclined by about sqrt(2 delta / strut). There the platform's
// own DOF (z, tilts) also move the strut ends across the struts only (the rows of A vanish with
// B), so J = B^-1 A stays bounded but the head loses its stiffness: stiffness_min falls to 0.
TEST(Tripod3Prs, SerialSingularityWhenAStrutIsPerpendicularToItsSlide) {
  auto analyze_with = [](double delta, PoseMetrics& metrics, bool& serial) {
    Tripod3PrsDesign d;
    d.base_radius = 0.35;
    d.platform_radius = 0.15;
    d.strut = 0.20 + delta;
    d.q_min = -1.0;
    d.q_max = 1.0;
    const LegChainMachine m(tripod_3prs_design(d));
    auto data = m.make_data();
    const double drop = std::sqrt(d.strut * d.strut - 0.04);  // joint below the carriage
    m.analyze(*data, Pose{{0, 0, 0.4 + drop + d.tool_length}, Eigen::Vector3d::Zero()},
              Wrench::Zero(), metrics);
    serial = static_cast<LegChainData&>(*data).serial_singular;
    EXPECT_NEAR(metrics.q(0), 0.4, 1e-7);
  };
  PoseMetrics metrics;
  bool serial = false;
  double previous_stiffness = std::numeric_limits<double>::infinity();
  for (const double delta : {1e-2, 1e-4, 1e-6}) {
    analyze_with(delta, metrics, serial);
    EXPECT_FALSE(serial) << delta;
    EXPECT_FALSE(metrics.singular) << delta;
    EXPECT_GT(metrics.singularity_margin, 0.0);
    EXPECT_LT(metrics.stiffness_min, 0.1 * previous_stiffness);
    previous_stiffness = metrics.stiffness_min;
  }
  analyze_with(0.0, metrics, serial);
  EXPECT_TRUE(serial);
  EXPECT_TRUE(metrics.singular);
  EXPECT_EQ(metrics.singularity_margin, 0.0);
  EXPECT_EQ(metrics.stiffness_min, 0.0);
  EXPECT_TRUE(std::isinf(metrics.tcp_error_max));
  EXPECT_TRUE(metrics.q.allFinite());
}

// Parallel singularity: tilting the default head about y at z = 1.2 m, det A changes sign near
// 72 deg (det B stays about 0.77): there the platform gains a motion with the slides locked.
TEST(Tripod3Prs, ParallelSingularityFoundWhereDetAChangesSign) {
  const LegChainMachine m(tripod_3prs_design(Tripod3PrsDesign{}));
  auto data = m.make_data();
  auto& ld = static_cast<LegChainData&>(*data);
  PoseMetrics metrics;
  auto det_a_at = [&](double ry) {
    m.analyze(*data, Pose{{0, 0, 1.2}, Eigen::Vector3d(0, ry, 0)}, Wrench::Zero(), metrics);
    return ld.det_a;
  };
  double lo = deg_to_rad(60), hi = deg_to_rad(85);
  ASSERT_GT(det_a_at(lo), 0.0);
  const double margin_far = metrics.singularity_margin;
  ASSERT_LT(det_a_at(hi), 0.0);
  for (int k = 0; k < 60; ++k) {
    const double mid = 0.5 * (lo + hi);
    (det_a_at(mid) > 0.0 ? lo : hi) = mid;
  }
  det_a_at(lo);
  EXPECT_TRUE(ld.ik_ok);
  EXPECT_TRUE(ld.parallel_singular);
  EXPECT_FALSE(ld.serial_singular);
  EXPECT_GT(std::abs(ld.det_b), 0.5);
  EXPECT_TRUE(metrics.singular);
  EXPECT_EQ(metrics.singularity_margin, 0.0);
  EXPECT_TRUE(std::isinf(metrics.tcp_error_max));
  EXPECT_NEAR(rad_to_deg(lo), 72.5, 1.0);
  // The margin falls towards it.
  det_a_at(lo - deg_to_rad(1));
  EXPECT_LT(metrics.singularity_margin, margin_far);
  EXPECT_LT(metrics.singularity_margin, 0.01);
  EXPECT_GT(metrics.singularity_margin, 0.0);
}

// The Sprint Z3 figures: A/B tilts within +-40 deg (every tool direction in the 40 deg cone)
// over a Z travel of at least 670 mm, with the default dimensions (joint limits, stroke and
// singularity margin included).
TEST(Tripod3Prs, DefaultsReachFortyDegreeTiltsOverTheZTravel) {
  const LegChainMachine m(tripod_3prs_design(Tripod3PrsDesign{}));
  auto data = m.make_data();
  PoseMetrics metrics;
  const double tilt = deg_to_rad(40);
  double z_lo = std::numeric_limits<double>::infinity(), z_hi = -z_lo, margin = 1.0;
  for (double z = 0.6; z <= 1.7; z += 0.005) {
    bool all = true;
    double worst = 1.0;
    for (int ring = 1; ring <= 4 && all; ++ring) {
      for (int k = 0; k < 24 && all; ++k) {
        const double phi = 2 * kPi * k / 24;
        const Eigen::Matrix3d R =
            Eigen::AngleAxisd(tilt * ring / 4, Eigen::Vector3d(std::cos(phi), std::sin(phi), 0))
                .toRotationMatrix();
        m.analyze(*data, Pose{{0, 0, z}, angles_from_rotation(R)}, Wrench::Zero(), metrics);
        all = metrics.reachable && !metrics.singular;
        worst = std::min(worst, metrics.singularity_margin);
      }
    }
    m.analyze(*data, Pose{{0, 0, z}, Eigen::Vector3d::Zero()}, Wrench::Zero(), metrics);
    if (all && metrics.reachable) {
      z_lo = std::min(z_lo, z);
      z_hi = std::max(z_hi, z);
      margin = std::min(margin, worst);
    }
  }
  EXPECT_GE(z_hi - z_lo, 0.670);
  EXPECT_GT(margin, 0.1);  // far from singular over that range
  // Beyond 40 deg the slide stroke and joint limits end it: at 60 deg nothing is reachable.
  m.analyze(*data, Pose{{0, 0, 1.2}, Eigen::Vector3d(0, deg_to_rad(60), 0)}, Wrench::Zero(),
            metrics);
  EXPECT_FALSE(metrics.reachable);
}

// ------------------------------------------------------------------------------------------
// Robustness.

TEST(LegChain, OutputsAreNeverNaN) {
  Uniform u(17);
  for (const Named& nm : named_models()) {
    const LegChainMachine& m = *nm.machine;
    auto data = m.make_data();
    PoseMetrics metrics;
    for (int k = 0; k < 300; ++k) {
      Pose p = m.design().home;
      for (int j = 0; j < 3; ++j) p.position(j) += u(-2, 2);
      for (int j = 0; j < 3; ++j) p.angles(j) = u(-1, 1);
      Wrench w;
      for (int j = 0; j < 6; ++j) w(j) = u(-10, 10);
      m.analyze(*data, p, w, metrics);
      EXPECT_TRUE(metrics.q.allFinite()) << nm.name;
      EXPECT_FALSE(metrics.tau.hasNaN());
      EXPECT_FALSE(std::isnan(metrics.stiffness_min) || std::isnan(metrics.singularity_margin) ||
                   std::isnan(metrics.det_j) || std::isnan(metrics.tcp_error_max));
      EXPECT_GE(metrics.singularity_margin, 0.0);
      EXPECT_LE(metrics.singularity_margin, 1.0);
      if (!m.inverse_kinematics(p)) {
        EXPECT_FALSE(metrics.reachable);
      }
      if (m.design().mobility == PlatformMobility::kTranslational ||
          m.design().mobility == PlatformMobility::kSchoenflies) {
        EXPECT_FALSE(metrics.reachable);  // rotated poses (about more than e)
      }
    }
  }
}

TEST(LegChain, ForwardKinematicsFailsCleanly) {
  DeltaDesign short_rods;
  short_rods.rod = 0.3;
  const LegChainMachine delta(delta_design(short_rods));
  // Horizontal cranks: the elbows are 1.19 m apart, the rods (0.3 m) cannot meet.
  const Eigen::VectorXd q = Eigen::VectorXd::Zero(3);
  FkOptions options;
  options.max_iterations = 50;
  const FkResult r = delta.forward_kinematics(q, std::nullopt, options);
  EXPECT_FALSE(r.converged);
  EXPECT_TRUE(r.pose.position.allFinite());
  EXPECT_FALSE(std::isnan(r.residual));
  EXPECT_FALSE(r.message.empty());
  EXPECT_FALSE(delta.forward_kinematics(Eigen::VectorXd::Constant(2, 0.1), std::nullopt).converged);
  Eigen::VectorXd nan_q = Eigen::VectorXd::Constant(3, std::nan(""));
  EXPECT_FALSE(delta.forward_kinematics(nan_q, std::nullopt).converged);
}

// Schoenflies and tripod FK (the 6 x 6 solve with the mobility equations) fail cleanly too:
// carriages too far apart for the struts.
TEST(LegChain, ForwardKinematicsOfTheSixBySixSolvesFailsCleanly) {
  const LegChainMachine schoenflies(schoenflies_sample());
  const LegChainMachine tripod(tripod_3prs_design(Tripod3PrsDesign{}));
  for (const LegChainMachine* m : {&schoenflies, &tripod}) {
    Eigen::VectorXd q = *m->inverse_kinematics(m->design().home);
    q(0) += 3.0;  // 3 m along its guide: leg 1 cannot reach the others' platform
    FkOptions options;
    options.max_iterations = 40;
    const FkResult r = m->forward_kinematics(q, std::nullopt, options);
    EXPECT_FALSE(r.converged) << m->model();
    EXPECT_TRUE(r.pose.position.allFinite() && r.pose.angles.allFinite());
    EXPECT_FALSE(std::isnan(r.residual));
    EXPECT_FALSE(r.message.empty());
    EXPECT_FALSE(m->forward_kinematics(Eigen::VectorXd::Constant(m->num_actuators(), std::nan("")),
                                       std::nullopt)
                     .converged);
  }
}

TEST(LegChain, ReachabilityChecksRangesAndJointLimits) {
  DeltaDesign d;
  d.theta_min = deg_to_rad(-10);
  d.theta_max = deg_to_rad(80);
  const LegChainMachine delta(delta_design(d));
  auto data = delta.make_data();
  // (0, 0, -0.9) needs theta = -20.5 deg: outside the drive range.
  EXPECT_FALSE(delta.reachable(*data, Pose{{0, 0, -0.9}, Eigen::Vector3d::Zero()}));
  EXPECT_TRUE(delta.reachable(*data, Pose{{0, 0, -1.2}, Eigen::Vector3d::Zero()}));
  EXPECT_FALSE(delta.reachable(*data, Pose{{0, 0, -1.2}, {0.01, 0, 0}}));             // rotation
  EXPECT_FALSE(delta.reachable(*data, Pose{{0, 0, -3.0}, Eigen::Vector3d::Zero()}));  // too far
  // Joint limits: the platform joint angle at (0.5, 0, -1.2) against a limit just below/above.
  Eigen::VectorXd base_angles, platform_angles;
  const Pose side{{0.5, 0, -1.2}, Eigen::Vector3d::Zero()};
  delta.joint_angles(side, base_angles, platform_angles);
  const double worst = platform_angles.maxCoeff();
  DeltaDesign tight = d, loose = d;
  tight.platform_max_angle = worst - 1e-6;
  loose.platform_max_angle = worst + 1e-6;
  const LegChainMachine tight_m(delta_design(tight)), loose_m(delta_design(loose));
  EXPECT_FALSE(tight_m.reachable(*tight_m.make_data(), side));
  EXPECT_TRUE(loose_m.reachable(*loose_m.make_data(), side));
  // The platform joint angle is the angle between the rod (pointing up from the platform) and
  // the platform's +z: for leg 2 at y = 0 ... check one leg by hand.
  const auto q = *delta.inverse_kinematics(side);
  Eigen::Vector3d c, dc;
  delta.actuated_point(0, q(0), c, dc);
  const Eigen::Vector3d up =
      (c - (side.position + d.platform_radius * Eigen::Vector3d(0, -1, 0))).normalized();
  EXPECT_NEAR(platform_angles(0), std::acos(up.z()), 1e-12);
}

TEST(LegChain, InvalidDesignsAreRejected) {
  DeltaDesign d;
  d.rod = -1;
  EXPECT_THROW(make_delta(d), std::invalid_argument);
  d = DeltaDesign{};
  d.theta_min = d.theta_max;
  EXPECT_THROW(make_delta(d), std::invalid_argument);
  d = DeltaDesign{};
  d.upper_arm = std::nan("");
  EXPECT_THROW(make_delta(d), std::invalid_argument);
  LegChainDesign six = hexaglide_design(HexaglideDesign{});
  six.legs.pop_back();
  EXPECT_THROW(make_leg_chain_machine(six), std::invalid_argument);
  LegChainDesign mixed = delta_design(DeltaDesign{});
  mixed.legs[0].kind = LegKind::kPUS;
  EXPECT_THROW(make_leg_chain_machine(mixed), std::invalid_argument);
}

// A 6-UPS member of the family reproduces the hexapod's leg lengths and Jacobian.
TEST(LegChain, UpsLegsGiveTheHexapodKinematics) {
  LegChainDesign d;
  d.model = "ups";
  const double r_b = 0.6, r_p = 0.25;
  for (int i = 0; i < 6; ++i) {
    const int k = i / 2;
    const double ab = deg_to_rad(120.0 * k + (i % 2 == 0 ? -10.0 : 10.0));
    const double ap = deg_to_rad(i % 2 == 0 ? 120.0 * k - 60.0 + 10.0 : 120.0 * k + 60.0 - 10.0);
    LegChainLeg leg;
    leg.kind = LegKind::kUPS;
    leg.base_point = Eigen::Vector3d(r_b * std::cos(ab), r_b * std::sin(ab), 0);
    leg.platform_point = Eigen::Vector3d(r_p * std::cos(ap), r_p * std::sin(ap), 0);
    leg.q_min = 0.7;
    leg.q_max = 1.15;
    leg.E = 2.1e11;
    leg.area = 3e-4;
    d.legs.push_back(leg);
  }
  d.tcp = Eigen::Vector3d(0, 0, -0.1);
  d.home.position = Eigen::Vector3d(0, 0, 0.8);
  const LegChainMachine m(d);
  const Pose pose{{0.02, -0.03, 0.85}, deg_to_rad(Eigen::Vector3d(3, -2, 5))};
  const Eigen::Matrix3d R = rotation_zyx<double>(pose.angles);
  Eigen::MatrixXd A, B, J;
  m.jacobians(pose, A, B, J);
  const Eigen::VectorXd q = *m.inverse_kinematics(pose);
  for (int i = 0; i < 6; ++i) {
    const LegChainLeg& leg = d.legs[static_cast<std::size_t>(i)];
    const Eigen::Vector3d ri = R * (leg.platform_point - d.tcp);
    const Eigen::Vector3d l = pose.position + ri - leg.base_point;
    EXPECT_NEAR(q(i), l.norm(), 1e-15);
    const Eigen::Vector3d s = l.normalized();
    EXPECT_NEAR((J.row(i).head(3).transpose() - s).norm(), 0.0, 1e-15);
    EXPECT_NEAR((J.row(i).tail(3).transpose() - ri.cross(s)).norm(), 0.0, 1e-15);
    EXPECT_EQ(B(i, i), 1.0);
  }
  // UPS coordinates are lengths: a leg length <= 0 means nothing (carriages may be negative).
  EXPECT_EQ(m.actuator_coordinates_requirement(q), "");
  Eigen::VectorXd bad = q;
  bad(3) = 0.0;
  EXPECT_EQ(m.actuator_coordinates_requirement(bad), "leg lengths > 0 (m) for the UPS legs");
  const LegChainMachine delta(delta_design(williams_irb360()));
  EXPECT_EQ(delta.actuator_coordinates_requirement(Eigen::Vector3d(-0.5, 0.0, -1.0)), "");
}

TEST(LegChain, WorkspaceOfTheDeltaUsesItsSearchBox) {
  const LegChainMachine delta(delta_design(williams_irb360()));
  const auto box = delta.workspace_search_box({Eigen::Matrix3d::Identity()});
  ASSERT_TRUE(box.has_value());
  ASSERT_FALSE(box->isEmpty());
  EXPECT_TRUE(box->contains(Eigen::Vector3d(0, 0, -0.9)));
  EXPECT_TRUE(delta.envelope_volume().has_value());
  WorkspaceOptions options;
  options.resolution = 0.1;
  options.compute_maps = false;
  options.compute_hull = false;
  const WorkspaceResult ws = compute_workspace(delta, options);
  EXPECT_GT(ws.volume, 0.05);
  EXPECT_FALSE(ws.touches_search_box);
}

// Capabilities (models/core/machine.hpp): reach_excess is the largest excess over an actuator
// range, computed here from the closed-form IK and the legs' ranges; planar legs have a parasitic
// motion whose twist basis is T of the pose analyzed last; nothing casts to a model's type.
TEST(LegChainCapabilities, ReachExcessAndParasiticMotion) {
  const LegChainMachine linear(linear_delta_design(LinearDeltaDesign{}));
  const LegChainDesign& d = linear.design();
  EXPECT_EQ(linear.parasitic_motion(), nullptr);
  EXPECT_EQ(linear.batch_analysis(), nullptr);
  int beyond = 0, within = 0;
  for (const double dz : {0.0, 0.05, 0.2, 0.5, -0.2, -0.4}) {
    Pose pose = d.home;
    pose.position.z() += dz;
    const std::optional<Eigen::VectorXd> q = linear.inverse_kinematics(pose);
    if (!q) continue;
    double expected = 0.0;
    for (std::size_t i = 0; i < d.legs.size(); ++i)
      expected = std::max({expected, d.legs[i].q_min - (*q)(static_cast<Eigen::Index>(i)),
                           (*q)(static_cast<Eigen::Index>(i)) - d.legs[i].q_max});
    const std::optional<double> excess = linear.reach_excess(pose);
    ASSERT_TRUE(excess.has_value()) << dz;
    EXPECT_DOUBLE_EQ(*excess, expected) << dz;
    auto data = linear.make_data();
    EXPECT_EQ(linear.reachable(*data, pose), expected == 0.0) << dz;
    (expected > 0.0 ? beyond : within) += 1;
  }
  EXPECT_GT(beyond, 0);
  EXPECT_GT(within, 0);
  const LegChainMachine tripod(tripod_3prs_design(Tripod3PrsDesign{}));
  const ParasiticMotion* parasitic = tripod.parasitic_motion();
  ASSERT_NE(parasitic, nullptr);
  Pose commanded = tripod.design().home;
  commanded.angles = {0.05, -0.03, 0.0};
  const std::optional<Pose> actual = parasitic->actual_pose(commanded);
  ASSERT_TRUE(actual.has_value());
  EXPECT_EQ(actual->position.z(), commanded.position.z());
  EXPECT_NE(actual->position.x(), commanded.position.x());  // the parasitic shift
  auto data = tripod.make_data();
  PoseMetrics m;
  tripod.analyze(*data, commanded, Wrench::Zero(), m);
  const Eigen::MatrixXd T = parasitic->twist_basis(*data);
  EXPECT_EQ(T.rows(), 6);
  EXPECT_EQ(T.cols(), 3);
  EXPECT_LT((T - tripod.twist_map(commanded)).norm(), 1e-12);
}

}  // namespace
}  // namespace pkmopt
