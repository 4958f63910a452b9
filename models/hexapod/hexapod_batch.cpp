#include "models/hexapod/hexapod_batch.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>

// The AVX2 + FMA kernel is built with GCC's target pragma; other compilers (clang, for the fuzz
// targets) use the baseline kernel only.
#if (defined(__x86_64__) || defined(__i386__)) && defined(__GNUC__) && !defined(__clang__)
#include <immintrin.h>
#define PKMOPT_BATCH_X86 1
#endif

// Packs of four doubles are passed by value between always-inlined helpers only; the ABI note
// about 32-byte vectors without AVX does not concern any call that survives inlining.
#pragma GCC diagnostic ignored "-Wpsabi"

namespace pkmopt {
namespace {

// Poses per block: one AVX register of doubles per pack.
constexpr int kLanes = 4;
typedef double v4 __attribute__((vector_size(32)));
typedef std::int64_t m4 __attribute__((vector_size(32)));  // lane masks: all ones or zero

#define PKMOPT_INLINE inline __attribute__((always_inline))

constexpr double kEps = std::numeric_limits<double>::epsilon();
// Jacobi rotates (p, q) in a lane while a_pq^2 > kJacobiTol2 * |a_pp a_qq|.
constexpr double kJacobiTol2 = kEps * kEps;
constexpr int kMaxSweeps = 30;
// Below this 1/cond(J_h) the scalar path (SVD) computes the margin; see hexapod.cpp.
constexpr double kRcondFast = 1e-2;

// What the kernel needs of the design, as doubles ready to broadcast.
struct BatchConstants {
  double base[3][6];      // a_i
  double platform[3][6];  // b_i - tcp
  double min_length, max_length;
  double base_axis[3], platform_axis[3];
  double cos_base_limit, cos_platform_limit;  // -2: unlimited
  double inv_characteristic_length, characteristic_length;
  double r_bound[6][2];  // |b_i - tcp|^2 / L^2, |b_i - tcp| / L^2 (the loaded-stiffness bound)
  bool constant_stiffness;
  double constant_compliance;  // 1 / axial_stiffness
  bool has_strut_EA;           // E and area given (and no axial_stiffness)
  double EA;                   // E * area
  bool has_actuator;
  double actuator_compliance;  // 1 / actuator_stiffness
  bool has_chain;              // drive train or joint compliances given
  double chain_compliance;     // nut, bearing, motor torsion and joints (constant part)
  bool has_screw;
  double screw_length_min, screw_length_slope;  // free length l0 + slope (q - min_length)
  double screw_inv_EA;                          // 1 / (E_s pi d^2 / 4)
  double actuator_error;
  // The mass model (natural frequencies): platform mass, centre of mass - tcp and inertia in
  // platform axes; the UPS legs' cylinder and rod (mass, centre) and their summed inertia.
  bool masses;
  double platform_mass, com[3], platform_inertia[3][3];
  double cylinder_mass, cylinder_centre, rod_mass, rod_centre, leg_inertia;
  // The legs' shape (models/geometry/leg_interference.hpp): one capsule per leg (radius
  // capsule_radius), or a cylinder (radius, length along the leg) and, when rod_radius > 0, a rod.
  bool interference, two_bodies;
  double capsule_radius, cylinder_radius, cylinder_length, rod_radius, min_clearance;

  explicit BatchConstants(const Hexapod& hexapod) {
    const HexapodDesign& d = hexapod.design();
    for (int c = 0; c < 3; ++c) {
      for (int i = 0; i < 6; ++i) {
        base[c][i] = d.base_joints(c, i);
        platform[c][i] = hexapod.platform_rel_tcp()(c, i);
      }
      base_axis[c] = d.joints.base_axis(c);
      platform_axis[c] = d.joints.platform_axis(c);
    }
    min_length = d.min_length;
    max_length = d.max_length;
    // As in the Hexapod constructor.
    cos_base_limit =
        d.joints.base_max_angle >= std::numbers::pi ? -2.0 : std::cos(d.joints.base_max_angle);
    cos_platform_limit = d.joints.platform_max_angle >= std::numbers::pi
                             ? -2.0
                             : std::cos(d.joints.platform_max_angle);
    characteristic_length = hexapod.characteristic_length();
    inv_characteristic_length = 1.0 / characteristic_length;
    for (int i = 0; i < 6; ++i) {
      const double r = hexapod.platform_rel_tcp().col(i).norm();
      const double L2 = characteristic_length * characteristic_length;
      r_bound[i][0] = r * r / L2;
      r_bound[i][1] = r / L2;
    }
    constant_stiffness = d.stiffness.axial_stiffness > 0.0;
    constant_compliance = constant_stiffness ? 1.0 / d.stiffness.axial_stiffness : 0.0;
    has_strut_EA = !constant_stiffness && d.stiffness.E > 0.0 && d.stiffness.area > 0.0;
    EA = d.stiffness.E * d.stiffness.area;
    has_actuator = d.stiffness.actuator_stiffness > 0.0;
    actuator_compliance = has_actuator ? 1.0 / d.stiffness.actuator_stiffness : 0.0;
    // The drive train: its constant part (nut, bearing, torsion) is the drive's compliance
    // without the screw; the screw's free length is linear in the leg length.
    const ScrewDrive& drive = d.stiffness.drive;
    ScrewDrive no_screw = drive;
    no_screw.E = no_screw.root_diameter = 0.0;
    chain_compliance = drive_compliance(no_screw, 0.0, d.min_length, d.max_length, false);
    if (d.stiffness.base_joint_stiffness > 0.0)
      chain_compliance += 1.0 / d.stiffness.base_joint_stiffness;
    if (d.stiffness.platform_joint_stiffness > 0.0)
      chain_compliance += 1.0 / d.stiffness.platform_joint_stiffness;
    has_screw = drive.has_screw();
    has_chain = has_screw || chain_compliance > 0.0;
    screw_length_min = drive.free_length_at_min;
    screw_length_slope =
        (drive.free_length_at_max - drive.free_length_at_min) / (d.max_length - d.min_length);
    screw_inv_EA =
        has_screw ? 4.0 / (drive.E * std::numbers::pi * drive.root_diameter * drive.root_diameter)
                  : 0.0;
    actuator_error = d.actuator_error;
    const MassModel& mm = d.masses;
    masses = mm.present;
    platform_mass = mm.platform.mass;
    for (int a = 0; a < 3; ++a) {
      com[a] = mm.platform.centre_of_mass(a) - d.tcp(a);
      for (int b = 0; b < 3; ++b) platform_inertia[a][b] = mm.platform.inertia(a, b);
    }
    cylinder_mass = mm.legs.cylinder.mass;
    cylinder_centre = mm.legs.cylinder.centre;
    rod_mass = mm.legs.rod.mass;
    rod_centre = mm.legs.rod.centre;
    leg_inertia = mm.legs.cylinder.inertia + mm.legs.rod.inertia;
    const LegShape& shape = d.leg_shape;
    interference = shape.present();
    two_bodies = shape.two_bodies();
    capsule_radius = 0.5 * shape.diameter;
    cylinder_radius = 0.5 * shape.cylinder_diameter;
    cylinder_length = shape.cylinder_length;
    rod_radius = 0.5 * shape.rod_diameter;
    min_clearance = d.min_clearance;
  }
};

// Results of one block of four poses, lane l = pose l.
struct BlockResult {
  v4 q[6], tau[6];
  v4 stiffness_min, singularity_margin, det_j, tcp_error_max;
  v4 compliance[21];  // C, lower triangle packed by rows: (a, b) at a (a + 1) / 2 + b, b <= a
  v4 tcp_deflection, tcp_rotation_deflection, direction[3], stiffness_min_loaded;
  v4 loaded_tt[3][3];  // (C_T)_tt
  v4 frequencies[6];   // Hz, ascending (with a mass model)
  v4 clearance;        // leg_clearance (m, with a leg shape)
  v4 clearance_pair;   // 6 * first + second (0-based legs), with a leg shape
  m4 reachable;
  m4 fallback;  // lanes to recompute with the scalar path
};

// The kernel, compiled once for the baseline and once for AVX2 + FMA.
namespace baseline {
#include "models/hexapod/hexapod_batch_kernel.inc"
}  // namespace baseline

#if defined(PKMOPT_BATCH_X86)
#pragma GCC push_options
#pragma GCC target("avx2,fma")
#define PKMOPT_BATCH_KERNEL_AVX2 1
namespace avx2 {
#include "models/hexapod/hexapod_batch_kernel.inc"
}  // namespace avx2
#undef PKMOPT_BATCH_KERNEL_AVX2
#pragma GCC pop_options
#endif

std::size_t run_batch_baseline(const Hexapod& hexapod, const Pose* poses, std::size_t n,
                               const Wrench& wrench, PoseMetrics* out, PoseCompliance* matrices) {
  return baseline::run_batch(hexapod, poses, n, wrench, out, matrices);
}

#if defined(PKMOPT_BATCH_X86)
__attribute__((target("avx2,fma"))) std::size_t run_batch_avx2(const Hexapod& hexapod,
                                                               const Pose* poses, std::size_t n,
                                                               const Wrench& wrench,
                                                               PoseMetrics* out,
                                                               PoseCompliance* matrices) {
  return avx2::run_batch(hexapod, poses, n, wrench, out, matrices);
}
#endif

// The solids (plates, tool) are checked pose by pose after the kernel
// (models/geometry/solid_bodies.hpp): the clearance and the reachability take them in, the rest
// stands.
void add_solid_bodies(const Hexapod& hexapod, const Pose* poses, std::size_t n, PoseMetrics* out) {
  if (!hexapod.design().bodies.present()) return;
  for (std::size_t i = 0; i < n; ++i) {
    const Clearance legs{out[i].leg_clearance, out[i].clearance_first, out[i].clearance_second};
    const Clearance c = hexapod.with_solid_bodies(poses[i], legs);
    if (!(c.value < legs.value)) continue;
    out[i].leg_clearance = c.value;
    out[i].clearance_first = c.first;
    out[i].clearance_second = c.second;
    out[i].reachable = out[i].reachable && c.value >= hexapod.design().min_clearance;
  }
}

}  // namespace

bool hexapod_batch_uses_avx2() {
#if defined(PKMOPT_BATCH_X86)
  static const bool available = __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma");
  return available;
#else
  return false;
#endif
}

std::size_t analyze_hexapod_batch(const Hexapod& hexapod, const Pose* poses, std::size_t n,
                                  const Wrench& wrench, PoseMetrics* out, HexapodBatchKernel kernel,
                                  PoseCompliance* matrices) {
  // A CPU without AVX2 (where the scalar fast path is quicker than the baseline kernel) runs pose
  // by pose.
  if (kernel == HexapodBatchKernel::baseline) {
    const std::size_t done = run_batch_baseline(hexapod, poses, n, wrench, out, matrices);
    add_solid_bodies(hexapod, poses, n, out);
    return done;
  }
#if defined(PKMOPT_BATCH_X86)
  if (hexapod_batch_uses_avx2()) {
    const std::size_t done = run_batch_avx2(hexapod, poses, n, wrench, out, matrices);
    add_solid_bodies(hexapod, poses, n, out);
    return done;
  }
#endif
  HexapodData data(hexapod);
  for (std::size_t i = 0; i < n; ++i) {
    hexapod.analyze(data, poses[i], wrench, out[i]);
    if (matrices) matrices[i] = data.matrices;
  }
  return n;
}

}  // namespace pkmopt
