// Benchmarks of models/stiffness/virtual_joint: the per-pose cost of the VJM platform stiffness of
// a 3-PRS tripod (three legs: actuator spring, revolute, elastic strut, spherical joint) and of a
// delta (motor spring, elastic crank, parallelogram rod pair), single thread. The leg geometry of
// every pose is computed beforehand; the timed loop is what a leg-chain model would add per pose:
// describe the three legs, eliminate their passive joints, sum at the TCP (and invert for the
// compliance).
#include <benchmark/benchmark.h>

#include <Eigen/Geometry>
#include <Eigen/LU>
#include <array>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <vector>

#include "bench/uniform_stream.hpp"
#include "models/stiffness/virtual_joint.hpp"

namespace {

using Eigen::Vector3d;

Vector3d polar(double radius, double deg) {
  const double a = deg * std::numbers::pi / 180.0;
  return {radius * std::cos(a), radius * std::sin(a), 0.0};
}

// One pose of a tripod: per leg the carriage c, revolute axis n, platform point P; and the TCP.
struct TripodPose {
  std::array<Vector3d, 3> c, n, P;
  Vector3d tcp;
};

// Sprint Z3-like 3-PRS geometry (base radius 0.30, platform 0.15, strut 0.55, tool 0.20), random
// platform poses z in [0.7, 1.0], rx, ry within +-25 deg (the revolute axes are the tangential
// directions made orthogonal to the struts).
std::vector<TripodPose> tripod_poses(std::size_t count) {
  pkmopt::sample_machines::Uniform u(7);
  std::vector<TripodPose> poses(count);
  for (TripodPose& p : poses) {
    const Eigen::Matrix3d R = (Eigen::AngleAxisd(u(-0.44, 0.44), Vector3d::UnitY()) *
                               Eigen::AngleAxisd(u(-0.44, 0.44), Vector3d::UnitX()))
                                  .toRotationMatrix();
    const Vector3d p0(u(-0.02, 0.02), u(-0.02, 0.02), u(0.7, 1.0));
    p.tcp = p0 + R * Vector3d(0, 0, 0.2);
    for (std::size_t i = 0; i < 3; ++i) {
      const double az = -90.0 + 120.0 * static_cast<double>(i);
      p.P[i] = p0 + R * polar(0.15, az);
      const Vector3d g = polar(0.30, az);
      const double h2 = (p.P[i] - g).head<2>().squaredNorm();
      p.c[i] = g + Vector3d(0, 0, p.P[i].z() - std::sqrt(0.55 * 0.55 - h2));
      const Vector3d s = (p.P[i] - p.c[i]).normalized(), t = polar(1.0, az + 90.0);
      p.n[i] = (t - t.dot(s) * s).normalized();
    }
  }
  return poses;
}

void BM_VjmTripodPlatformStiffness(benchmark::State& state) {
  const std::vector<TripodPose> poses = tripod_poses(4096);
  const pkmopt::BeamSection strut = pkmopt::tube_section(2.1e11, 8.1e10, 0.06, 0.045);
  const bool invert = state.range(0) != 0;
  std::size_t k = 0;
  for (auto _ : state) {
    const TripodPose& p = poses[k++ & 4095];
    std::array<pkmopt::LegCompliance, 3> legs;
    pkmopt::VjmLeg leg;
    for (std::size_t i = 0; i < 3; ++i) {
      leg.clear();
      leg.add_actuated_prismatic(p.c[i], Vector3d::UnitZ(), 2.0e8);
      leg.add_revolute(p.c[i], p.n[i]);
      leg.add_beam(strut, (p.P[i] - p.c[i]).norm(), p.c[i], p.P[i] - p.c[i], p.n[i]);
      leg.add_spherical(p.P[i]);
      legs[i] = leg.stiffness(p.tcp);
    }
    pkmopt::Matrix6d K = pkmopt::platform_stiffness(legs, p.tcp);
    if (invert) K = K.inverse();
    benchmark::DoNotOptimize(K.data());
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()));
}
BENCHMARK(BM_VjmTripodPlatformStiffness)->ArgName("invert")->Arg(0)->Arg(1);

// Delta (ABB IRB 360-like): the legs' elbows for random TCP positions, then per pose three legs of
// motor spring, crank beam and a parallelogram of two rods.
void BM_VjmDeltaPlatformStiffness(benchmark::State& state) {
  struct DeltaPose {
    std::array<Vector3d, 3> o, w, e, P;
    Vector3d tcp;
  };
  pkmopt::sample_machines::Uniform u(9);
  std::vector<DeltaPose> poses(4096);
  for (DeltaPose& p : poses) {
    p.tcp = Vector3d(u(-0.2, 0.2), u(-0.2, 0.2), u(-1.25, -1.1));
    for (std::size_t i = 0; i < 3; ++i) {
      const double phi = -90.0 + 120.0 * static_cast<double>(i);
      const Vector3d d = polar(1.0, phi);
      p.w[i] = polar(1.0, phi + 90.0);
      p.o[i] = 0.164 * d;
      p.P[i] = p.tcp + 0.044 * d;
      const Vector3d q = p.P[i] - p.o[i];
      const double A = 2 * 0.524 * q.dot(d), B = -2 * 0.524 * q.z();
      const double C = q.squaredNorm() + 0.524 * 0.524 - 1.244 * 1.244;
      const double th = std::atan2(B, A) - std::acos(C / std::hypot(A, B));
      p.e[i] = p.o[i] + 0.524 * (std::cos(th) * d - std::sin(th) * Vector3d::UnitZ());
    }
  }
  const pkmopt::BeamSection crank{7e10, 2.6e10, 6e-4, 1.2e-7, 3.0e-7, 2.0e-7};
  std::size_t k = 0;
  for (auto _ : state) {
    const DeltaPose& p = poses[k++ & 4095];
    std::array<pkmopt::LegCompliance, 3> legs;
    pkmopt::VjmLeg leg;
    for (std::size_t i = 0; i < 3; ++i) {
      const Vector3d h = 0.05 * p.w[i];
      const std::array<pkmopt::TwoForceMember, 2> rods{
          pkmopt::TwoForceMember{p.e[i] + h, p.P[i] + h, 5e6},
          pkmopt::TwoForceMember{p.e[i] - h, p.P[i] - h, 5e6}};
      leg.clear();
      leg.add_actuated_revolute(p.o[i], p.w[i], 1.5e5);
      leg.add_beam(crank, 0.524, p.o[i], p.e[i] - p.o[i], p.w[i]);
      leg.add_two_force_members(rods);
      legs[i] = leg.stiffness(p.tcp);
    }
    const pkmopt::Matrix6d K = pkmopt::platform_stiffness(legs, p.tcp);
    benchmark::DoNotOptimize(K.data());
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()));
}
BENCHMARK(BM_VjmDeltaPlatformStiffness);

}  // namespace
