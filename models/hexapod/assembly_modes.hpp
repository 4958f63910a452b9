// Every assembly mode of a general Gough–Stewart platform: all solutions of its forward
// kinematics for one set of leg lengths, by parameter homotopy (Morgan & Sommese, "Coefficient-
// parameter polynomial continuation", Appl. Math. Comput. 29, 1989).
//
// Unknowns (9, complex): the platform position p and the first two columns r1, r2 of its
// rotation R = [r1, r2, r1 x r2]. Equations (9):
//   r1.r1 = 1,  r2.r2 = 1,  r1.r2 = 0,
//   |p + R b_i - a_i|^2 = L_i^2   (i = 1..6; a_i base points, b_i platform points).
// A general platform has 40 complex solutions (Raghavan 1993; Ronga & Vust; Lazard; Mourrain),
// up to 40 of them real (Dietmaier 1998). The homotopy starts from Dietmaier's geometry, whose 40
// solutions are all real and published (models/hexapod/dietmaier_start.inc), tracks them once to
// a random complex geometry near a typical machine (joint circles of radius 0.6 and 0.25, legs of
// 1, plus complex noise of 0.3; seeded; kept for the process), and from there to the geometry
// asked for, with the lengths divided by the mean leg length. When a path fails (its step falls
// below 1e-12, then below 1e-15 with smaller steps), all 40 paths are run again from a second
// random complex geometry and the run with fewer failures is kept. Paths run in projective
// coordinates X = (X0, X0 x) on a random complex patch, so that a solution that grows without
// bound stays finite and ends at X0 = 0: a solution at infinity (a path is declared so beyond
// s = 0.95 when |X0| < 1e-7 |X|, and an end beyond 1e4 leg lengths counts so: no real pose lies
// there). Because the intermediate geometries are complex and random, the 40 paths avoid the
// geometries where solutions meet with probability 1 (the "gamma trick"): every isolated
// solution of the target is the end of one path. A path whose step falls below 1e-12 is reported
// as failed, never hidden; so are two paths that end at the same solution. Each end is polished
// by Newton's method; a solution is real when its imaginary parts are below 1e-8 (relative).
//
// Special geometries. A planar base and platform with joints in symmetric pairs (the sample
// machines) has 28 finite solutions, 12 at infinity; a 6-3 platform (joints coinciding in pairs
// on the platform) 16 finite ones, as Nanua, Waldron & Murthy found ("Direct kinematic solution
// of a Stewart platform", IEEE Trans. Robotics and Automation 6(4), 1990), 24 at infinity. A
// geometry singular at every pose (architecture singularity, e.g. similar planar base and
// platform; Ma & Angeles 1991) has curves of solutions for any lengths: its paths fail, and
// `architecture_singular` says why (checked by det J at three generic poses).
//
// Tracking: fourth-order Runge–Kutta predictor on dX/ds = -J^-1 dG/ds, Newton corrector (at
// most 3 contracting steps, to 1e-8 relative), step doubled after 3 good steps and halved on a
// failure. One geometry solved many times (AssemblyModeSolver, below) starts from its own
// solutions at random complex lengths: about 1.4 ms per solve against 30 ms from the universal
// start (bench/assembly_modes_bench.cpp).
//
// Example:
//   const pkmopt::AssemblyModes modes = pkmopt::all_assembly_modes(a, b, lengths);
//   for (const auto& m : modes.real) use(m.position, m.rotation);
#pragma once

#include <Eigen/Core>
#include <cstddef>
#include <memory>
#include <string>
#include <vector>

namespace pkmopt {

struct AssemblyMode {
  Eigen::Vector3d position = Eigen::Vector3d::Zero();  ///< p, base frame (units of a_i)
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();
  double residual = 0.0;  ///< max_i | |p + R b_i - a_i| - L_i |
};

struct AssemblyModes {
  std::vector<AssemblyMode> real;     ///< the real solutions, distinct
  std::size_t complex_count = 0;      ///< solutions with imaginary parts (pairs of conjugates)
  std::size_t at_infinity = 0;        ///< paths that grew without bound (or beyond 1e4 lengths)
  std::size_t failed = 0;             ///< paths whose step fell below 1e-12 or did not converge
  std::vector<std::string> failures;  ///< one line per failed path: which and why
  std::size_t paths = 0;              ///< paths tracked (40)
  /// det J = 0 at every pose (e.g. similar planar base and platform): the solutions form curves
  /// (self-motions), not a finite set; the paths that end on them fail.
  bool architecture_singular = false;
};

/// All assembly modes of the platform with base points `base` (columns a_i), platform points
/// `platform` (columns b_i, platform frame) and leg lengths `lengths` (> 0). Throws
/// std::invalid_argument for non-finite input or a length <= 0.
AssemblyModes all_assembly_modes(const Eigen::Matrix<double, 3, 6>& base,
                                 const Eigen::Matrix<double, 3, 6>& platform,
                                 const Eigen::Matrix<double, 6, 1>& lengths);

/// The assembly modes of one geometry for any leg lengths, faster than all_assembly_modes when
/// the geometry is solved more than once. At construction, the 40 paths are tracked once to
/// random complex squared lengths near `typical_lengths` (the coefficient-parameter theorem of
/// Morgan & Sommese applied to the lengths alone): their finite ends are every isolated solution
/// of this geometry for generic lengths (fewer than 40 for a special geometry; the others stay at
/// infinity). Each solve then follows only those from there to the lengths asked for. When a
/// path fails, the solve falls back to all_assembly_modes. Immutable; share it between threads.
class AssemblyModeSolver {
 public:
  /// Throws std::invalid_argument for non-finite points or lengths <= 0.
  AssemblyModeSolver(const Eigen::Matrix<double, 3, 6>& base,
                     const Eigen::Matrix<double, 3, 6>& platform,
                     const Eigen::Matrix<double, 6, 1>& typical_lengths);
  /// The assembly modes for `lengths` (> 0; throws std::invalid_argument otherwise).
  AssemblyModes solve(const Eigen::Matrix<double, 6, 1>& lengths) const;
  /// Finite solutions of this geometry for generic lengths (0 when its start could not be made
  /// and every solve runs all 40 paths).
  std::size_t finite_solutions() const;

 private:
  struct Geometry;
  std::shared_ptr<const Geometry> geometry_;
};

}  // namespace pkmopt
