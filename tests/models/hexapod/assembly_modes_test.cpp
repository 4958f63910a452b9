// Tests of models/hexapod/assembly_modes: Dietmaier's platform has exactly 40 real assembly
// modes, the ones PHCpack published; on random geometries every real solution satisfies the leg
// equations to 1e-10, their number is even and at most 40, every path is accounted for, and the
// pose the lengths were made from is among them; relabelling the legs and moving the base frame
// change nothing but the frame. The solver of one geometry (AssemblyModeSolver) finds what the 40
// paths find.
#include "models/hexapod/assembly_modes.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <random>
#include <stdexcept>
#include <vector>

namespace pkmopt {
namespace {

#include "models/hexapod/dietmaier_start.inc"

using Points = Eigen::Matrix<double, 3, 6>;
using Lengths = Eigen::Matrix<double, 6, 1>;

struct Geometry {
  Points a, b;
  Lengths L;
};

Geometry dietmaier_geometry() {
  Geometry g;
  for (int i = 0; i < 6; ++i) {
    for (int k = 0; k < 3; ++k) {
      g.a(k, i) = kDietmaierBase[i][k];
      g.b(k, i) = kDietmaierPlatform[i][k];
    }
    g.L(i) = kDietmaierLengths[i];
  }
  return g;
}

// The distance between two poses: position difference plus the rotation difference's norm.
double pose_distance(const AssemblyMode& x, const Eigen::Vector3d& p, const Eigen::Matrix3d& R) {
  return (x.position - p).norm() + (x.rotation - R).norm();
}

// The index of the mode nearest (p, R), and its distance.
std::pair<std::size_t, double> nearest(const AssemblyModes& modes, const Eigen::Vector3d& p,
                                       const Eigen::Matrix3d& R) {
  std::size_t best = 0;
  double best_d = INFINITY;
  for (std::size_t k = 0; k < modes.real.size(); ++k) {
    const double d = pose_distance(modes.real[k], p, R);
    if (d < best_d) {
      best_d = d;
      best = k;
    }
  }
  return {best, best_d};
}

TEST(AssemblyModes, DietmaiersPlatformHasFortyRealModes) {
  const Geometry g = dietmaier_geometry();
  const AssemblyModes modes = all_assembly_modes(g.a, g.b, g.L);
  EXPECT_EQ(modes.paths, 40u);
  EXPECT_EQ(modes.failed, 0u) << (modes.failures.empty() ? "" : modes.failures.front());
  EXPECT_EQ(modes.complex_count, 0u);
  EXPECT_EQ(modes.at_infinity, 0u);
  ASSERT_EQ(modes.real.size(), 40u);
  // Each of PHCpack's 40 solutions is found once. PHCpack solved the polynomials with their
  // coefficients printed to 10 digits, and several of these modes are close to a singularity
  // (PHCpack's rco down to 4e-6), so its solutions differ from the exact system's by up to a few
  // 1e-6; ours solve the exact system to 1e-10 (the residual below).
  std::vector<int> matched(40, 0);
  for (const auto& row : kDietmaierSolutions) {
    const Eigen::Vector3d n(row[0], row[1], row[2]), a1(row[3], row[4], row[5]),
        a2(row[6], row[7], row[8]);
    Eigen::Matrix3d R;
    R << a1, a2, a1.cross(a2);
    const auto [k, d] = nearest(modes, n, R);
    EXPECT_LT(d, 2e-5);
    ++matched[k];
  }
  for (int m : matched) EXPECT_EQ(m, 1);
  for (const AssemblyMode& m : modes.real) EXPECT_LT(m.residual, 1e-10);
}

// A random platform (base and platform points in a 1 m cube, machine-like scale) and a random
// pose; the lengths are those of the pose.
Geometry random_geometry(std::mt19937_64& engine, Eigen::Vector3d& p, Eigen::Matrix3d& R) {
  std::uniform_real_distribution<double> u(-0.5, 0.5);
  Geometry g;
  for (int i = 0; i < 6; ++i)
    for (int k = 0; k < 3; ++k) {
      g.a(k, i) = u(engine);
      g.b(k, i) = 0.5 * u(engine);
    }
  p = Eigen::Vector3d(u(engine), u(engine), 1.0 + u(engine));
  R = Eigen::AngleAxisd(u(engine), Eigen::Vector3d(u(engine), u(engine), u(engine)).normalized())
          .toRotationMatrix();
  for (int i = 0; i < 6; ++i) g.L(i) = (p + R * g.b.col(i) - g.a.col(i)).norm();
  return g;
}

TEST(AssemblyModes, RandomPlatformsGiveEveryRealModeAccountedFor) {
  std::mt19937_64 engine(42);
  for (int trial = 0; trial < 12; ++trial) {
    Eigen::Vector3d p;
    Eigen::Matrix3d R;
    const Geometry g = random_geometry(engine, p, R);
    const AssemblyModes modes = all_assembly_modes(g.a, g.b, g.L);
    EXPECT_EQ(modes.failed, 0u) << trial << ": "
                                << (modes.failures.empty() ? "" : modes.failures.front());
    EXPECT_EQ(modes.real.size() + modes.complex_count + modes.at_infinity + modes.failed, 40u);
    EXPECT_EQ(modes.real.size() % 2, 0u) << trial;
    EXPECT_EQ(modes.complex_count % 2, 0u) << trial;
    for (const AssemblyMode& m : modes.real) {
      EXPECT_LT(m.residual, 1e-10) << trial;
      EXPECT_LT((m.rotation.transpose() * m.rotation - Eigen::Matrix3d::Identity()).norm(), 1e-10);
      EXPECT_GT(m.rotation.determinant(), 0.0);
    }
    EXPECT_LT(nearest(modes, p, R).second, 1e-8) << trial << ": the generating pose is missing";
  }
}

TEST(AssemblyModes, RelabellingAndMovingTheBaseChangeOnlyTheFrame) {
  std::mt19937_64 engine(7);
  Eigen::Vector3d p;
  Eigen::Matrix3d R;
  const Geometry g = random_geometry(engine, p, R);
  const AssemblyModes modes = all_assembly_modes(g.a, g.b, g.L);
  ASSERT_GE(modes.real.size(), 2u);
  // Legs relabelled.
  const std::array<int, 6> order{3, 0, 5, 1, 4, 2};
  Geometry h;
  for (int i = 0; i < 6; ++i) {
    h.a.col(i) = g.a.col(order[i]);
    h.b.col(i) = g.b.col(order[i]);
    h.L(i) = g.L(order[i]);
  }
  const AssemblyModes relabelled = all_assembly_modes(h.a, h.b, h.L);
  ASSERT_EQ(relabelled.real.size(), modes.real.size());
  for (const AssemblyMode& m : modes.real)
    EXPECT_LT(nearest(relabelled, m.position, m.rotation).second, 1e-8);
  // The base frame moved: a' = Q a + t; each mode (p, R) becomes (Q p + t, Q R).
  const Eigen::Matrix3d Q =
      Eigen::AngleAxisd(0.7, Eigen::Vector3d(1.0, -2.0, 0.5).normalized()).toRotationMatrix();
  const Eigen::Vector3d t(0.3, -1.2, 2.0);
  Geometry moved = g;
  for (int i = 0; i < 6; ++i) moved.a.col(i) = Q * g.a.col(i) + t;
  const AssemblyModes in_moved = all_assembly_modes(moved.a, moved.b, moved.L);
  ASSERT_EQ(in_moved.real.size(), modes.real.size());
  for (const AssemblyMode& m : modes.real)
    EXPECT_LT(nearest(in_moved, Q * m.position + t, Q * m.rotation).second, 1e-8);
}

// The same solutions of two solves, matched one to one.
void expect_same_modes(const AssemblyModes& x, const AssemblyModes& y, int trial) {
  EXPECT_EQ(x.failed, 0u) << trial << ": " << (x.failures.empty() ? "" : x.failures.front());
  EXPECT_EQ(y.failed, 0u) << trial << ": " << (y.failures.empty() ? "" : y.failures.front());
  // A path to a complex solution beyond 1e7 leg lengths may end as complex in one solve and at
  // infinity in the other (both count it so, header); the real ones and the total agree.
  EXPECT_EQ(x.complex_count + x.at_infinity, y.complex_count + y.at_infinity) << trial;
  EXPECT_EQ(x.paths, 40u) << trial;
  EXPECT_EQ(y.paths, 40u) << trial;
  ASSERT_EQ(x.real.size(), y.real.size()) << trial;
  for (const AssemblyMode& m : x.real)
    EXPECT_LT(nearest(y, m.position, m.rotation).second, 1e-8) << trial;
}

TEST(AssemblyModes, OneGeometrysSolverFindsWhatTheFortyPathsFind) {
  std::mt19937_64 engine(1234);
  std::uniform_real_distribution<double> u(-0.5, 0.5);
  for (int trial = 0; trial < 5; ++trial) {
    Eigen::Vector3d p;
    Eigen::Matrix3d R;
    const Geometry g = random_geometry(engine, p, R);
    const AssemblyModeSolver solver(g.a, g.b, g.L);
    EXPECT_GE(solver.finite_solutions(), 38u) << trial;  // a general geometry: 40, some huge
    for (int pose = 0; pose < 3; ++pose) {
      // Another pose of the same machine, up to 0.2 m and 0.4 rad away.
      const Eigen::Vector3d q = p + 0.4 * Eigen::Vector3d(u(engine), u(engine), u(engine));
      const Eigen::Matrix3d S =
          Eigen::AngleAxisd(0.8 * u(engine),
                            Eigen::Vector3d(u(engine), u(engine), u(engine)).normalized()) *
          R;
      Lengths L;
      for (int i = 0; i < 6; ++i) L(i) = (q + S * g.b.col(i) - g.a.col(i)).norm();
      const AssemblyModes fast = solver.solve(L);
      expect_same_modes(fast, all_assembly_modes(g.a, g.b, L), trial);
      EXPECT_LT(nearest(fast, q, S).second, 1e-8) << trial << ": the generating pose is missing";
      for (const AssemblyMode& m : fast.real) EXPECT_LT(m.residual, 1e-10);
    }
  }
}

TEST(AssemblyModes, SolverOfDietmaiersPlatformFindsItsFortyRealModes) {
  const Geometry g = dietmaier_geometry();
  // Started from other lengths: the 40 real modes are found at his lengths all the same.
  const AssemblyModeSolver solver(g.a, g.b, 1.1 * g.L);
  const AssemblyModes modes = solver.solve(g.L);
  EXPECT_EQ(modes.failed, 0u);
  EXPECT_EQ(modes.real.size(), 40u);
}

// Joints on two circles in symmetric pairs (the sample machines' layout): base 0.6, platform
// 0.25; with `triangle` the platform joints coincide in pairs (a 6-3 platform).
Geometry paired_geometry(bool triangle, const Eigen::Vector3d& p, const Eigen::Matrix3d& R) {
  Geometry g;
  for (int i = 0; i < 6; ++i) {
    const double base_angle = (i / 2) * 2.0 * M_PI / 3.0 + (i % 2 ? 0.17 : -0.17);
    g.a.col(i) << 0.6 * std::cos(base_angle), 0.6 * std::sin(base_angle), 0.0;
    const double platform_angle =
        triangle ? ((i + 1) % 6 / 2) * 2.0 * M_PI / 3.0 + M_PI / 3.0
                 : (i / 2) * 2.0 * M_PI / 3.0 + M_PI / 3.0 + (i % 2 ? -0.17 : 0.17);
    g.b.col(i) << 0.25 * std::cos(platform_angle), 0.25 * std::sin(platform_angle), 0.0;
  }
  for (int i = 0; i < 6; ++i) g.L(i) = (p + R * g.b.col(i) - g.a.col(i)).norm();
  return g;
}

TEST(AssemblyModes, SpecialGeometriesGiveTheirOwnCountOrSayTheSetIsNotFinite) {
  const Eigen::Vector3d p(0.02, -0.01, 0.9);
  const Eigen::Matrix3d R =
      Eigen::AngleAxisd(0.1, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  // The 6-3 platform: 16 finite solutions (Nanua, Waldron & Murthy 1990), the pose among them;
  // with a planar base every solution has its mirror image in the base plane.
  const Geometry six_three = paired_geometry(true, p, R);
  for (const AssemblyModes& modes :
       {all_assembly_modes(six_three.a, six_three.b, six_three.L),
        AssemblyModeSolver(six_three.a, six_three.b, six_three.L).solve(six_three.L)}) {
    EXPECT_EQ(modes.failed, 0u);
    EXPECT_EQ(modes.real.size() + modes.complex_count, 16u);
    EXPECT_EQ(modes.at_infinity, 24u);
    EXPECT_FALSE(modes.architecture_singular);
    EXPECT_LT(nearest(modes, p, R).second, 1e-8);
    for (const AssemblyMode& m : modes.real) {
      const Eigen::Matrix3d mirror = Eigen::Vector3d(1, 1, -1).asDiagonal() * m.rotation *
                                     Eigen::Vector3d(1, 1, -1).asDiagonal();
      EXPECT_LT(
          nearest(modes, Eigen::Vector3d(m.position.x(), m.position.y(), -m.position.z()), mirror)
              .second,
          1e-8);
    }
  }
  // Planar with symmetric pairs: 28 finite solutions, 12 at infinity (a regression pin of this
  // solver's count, the same from both starts).
  const Geometry planar = paired_geometry(false, p, R);
  const AssemblyModes planar_modes = all_assembly_modes(planar.a, planar.b, planar.L);
  EXPECT_EQ(planar_modes.failed, 0u);
  EXPECT_EQ(planar_modes.real.size() + planar_modes.complex_count, 28u);
  EXPECT_EQ(AssemblyModeSolver(planar.a, planar.b, planar.L).finite_solutions(), 28u);
  // Similar base and platform (the platform the base scaled by 1/2): singular at every pose, the
  // solutions form curves; said, and the paths that end on them fail.
  Geometry similar = planar;
  similar.b = 0.5 * planar.a;
  for (int i = 0; i < 6; ++i) similar.L(i) = (p + R * similar.b.col(i) - similar.a.col(i)).norm();
  const AssemblyModes curves = all_assembly_modes(similar.a, similar.b, similar.L);
  EXPECT_TRUE(curves.architecture_singular);
  EXPECT_GT(curves.failed, 0u);
  EXPECT_TRUE(
      AssemblyModeSolver(similar.a, similar.b, similar.L).solve(similar.L).architecture_singular);
  EXPECT_FALSE(all_assembly_modes(planar.a, planar.b, planar.L).architecture_singular);
}

TEST(AssemblyModes, BadInputIsRefused) {
  Geometry g = dietmaier_geometry();
  g.L(2) = 0.0;
  EXPECT_THROW(all_assembly_modes(g.a, g.b, g.L), std::invalid_argument);
  g = dietmaier_geometry();
  g.a(1, 1) = NAN;
  EXPECT_THROW(all_assembly_modes(g.a, g.b, g.L), std::invalid_argument);
  EXPECT_THROW(AssemblyModeSolver(g.a, g.b, g.L), std::invalid_argument);
  g = dietmaier_geometry();
  const AssemblyModeSolver solver(g.a, g.b, g.L);
  Lengths L = g.L;
  L(4) = -1.0;
  EXPECT_THROW(solver.solve(L), std::invalid_argument);
  L(4) = INFINITY;
  EXPECT_THROW(solver.solve(L), std::invalid_argument);
}

}  // namespace
}  // namespace pkmopt
