#include "models/hexapod/assembly_modes.hpp"

#include <fmt/format.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdint>
#include <memory>
#include <numbers>
#include <random>
#include <stdexcept>

namespace pkmopt {
namespace {

#include "models/hexapod/dietmaier_start.inc"

using C = std::complex<double>;
using Vec3c = Eigen::Matrix<C, 3, 1>;
using Vec9 = Eigen::Matrix<C, 9, 1>;
using Vec10 = Eigen::Matrix<C, 10, 1>;
using Mat10 = Eigen::Matrix<C, 10, 10>;

constexpr double kTracking = 1e-8;       // Newton step along a path, relative to |X|
constexpr double kConverged = 1e-10;     // Newton step at a path's end, relative to |X|
constexpr double kSolved = 1e-12;        // |G| at which a point solves (lengths scaled to ~1)
constexpr double kSmallestStep = 1e-12;  // in the path parameter s
constexpr double kLargestStep = 0.1;
constexpr double kTowardInfinity = 1e-7;  // |X0| / |X| at which a path is taken to diverge
// |X0| / |X| below which an end counts as at infinity: beyond 1e4 leg lengths. No real solution
// lies there (|p| <= |a_i| + |b_i| + L_i), and a path to a solution at infinity, singular there,
// converges slowly and may stop at |X0| ~ 1e-6 |X| (the 6-3 platform's 24 such paths).
constexpr double kAtInfinity = 1e-4;
constexpr double kRealTolerance = 1e-8;
constexpr int kMaxSteps = 100000;
constexpr double kEndgame = 0.95;              // s beyond which a path may be declared at infinity
constexpr double kStartNoise = 0.3;            // size of the complex noise of the start geometry
constexpr std::uint64_t kGeometrySeed = 1989;  // the random lengths of a geometry's own start
// Size of their complex part: small keeps the paths short (0.03: 2.1 ms per solve against 3.7 ms
// at 0.1, 40 finite solutions, poses 0.3 m and 0.4 rad from the start), and the solutions of
// 1200 random solves agreed with the 40 paths from the universal start.
constexpr double kGeometryNoise = 0.03;

// A geometry: base points a_i, platform points b_i, squared lengths.
struct Params {
  Eigen::Matrix<C, 3, 6> a, b;
  Eigen::Matrix<C, 6, 1> l2;
};

Params operator-(const Params& x, const Params& y) { return {x.a - y.a, x.b - y.b, x.l2 - y.l2}; }
Params along(const Params& p0, const Params& d, double s) {
  return {p0.a + s * d.a, p0.b + s * d.b, p0.l2 + s * d.l2};
}

// u.v and u x v without conjugation (Eigen's cross conjugates complex results).
C bilinear(const Vec3c& u, const Vec3c& v) { return u(0) * v(0) + u(1) * v(1) + u(2) * v(2); }
Vec3c cross(const Vec3c& u, const Vec3c& v) {
  return {u(1) * v(2) - u(2) * v(1), u(2) * v(0) - u(0) * v(2), u(0) * v(1) - u(1) * v(0)};
}

// J^-1 b by Gaussian elimination with partial pivoting (two fifths of Eigen's PartialPivLU time
// for one right-hand side at this size); not finite when J is singular.
Vec10 solve(Mat10 J, Vec10 b) {
  for (int k = 0; k < 10; ++k) {
    int pivot = k;
    double largest = std::norm(J(k, k));
    for (int i = k + 1; i < 10; ++i)
      if (const double n = std::norm(J(i, k)); n > largest) {
        largest = n;
        pivot = i;
      }
    if (pivot != k) {
      J.row(k).swap(J.row(pivot));
      std::swap(b(k), b(pivot));
    }
    const C inverse = 1.0 / J(k, k);
    for (int i = k + 1; i < 10; ++i) {
      const C f = J(i, k) * inverse;
      for (int j = k + 1; j < 10; ++j) J(i, j) -= f * J(k, j);
      b(i) -= f * b(k);
    }
  }
  for (int k = 9; k >= 0; --k) {
    C sum = b(k);
    for (int j = k + 1; j < 10; ++j) sum -= J(k, j) * b(j);
    b(k) = sum / J(k, k);
  }
  return b;
}

// The system in projective coordinates X = (X0, P, R1, R2), x = (P, R1, R2) / X0, so that paths
// whose affine solutions grow without bound stay finite (they end at X0 = 0), on the random
// patch c.X = 1:
//   R1.R1 - X0^2,  R2.R2 - X0^2,  R1.R2,
//   Q_i.Q_i - L_i^2 X0^4 with Q_i = X0 P + b_i,x X0 R1 + b_i,y X0 R2 + b_i,z R1 x R2 - a_i X0^2,
//   c.X - 1.
struct Homogeneous {
  Vec10 patch;  // c

  // The leg vector Q_i.
  static Vec3c leg(const Vec10& X, const Params& P, int i) {
    const C x0 = X(0);
    const Vec3c p = X.segment<3>(1), r1 = X.segment<3>(4), r2 = X.segment<3>(7);
    return x0 * (p + P.b(0, i) * r1 + P.b(1, i) * r2) + P.b(2, i) * cross(r1, r2) -
           x0 * x0 * P.a.col(i);
  }

  void evaluate(const Vec10& X, const Params& P, Vec10& G, Mat10* J) const {
    const C x0 = X(0);
    const Vec3c p = X.segment<3>(1), r1 = X.segment<3>(4), r2 = X.segment<3>(7);
    G(0) = bilinear(r1, r1) - x0 * x0;
    G(1) = bilinear(r2, r2) - x0 * x0;
    G(2) = bilinear(r1, r2);
    if (J) {
      J->setZero();
      (*J)(0, 0) = -2.0 * x0;
      J->block<1, 3>(0, 4) = 2.0 * r1.transpose();
      (*J)(1, 0) = -2.0 * x0;
      J->block<1, 3>(1, 7) = 2.0 * r2.transpose();
      J->block<1, 3>(2, 4) = r2.transpose();
      J->block<1, 3>(2, 7) = r1.transpose();
    }
    const C x0_2 = x0 * x0;
    for (int i = 0; i < 6; ++i) {
      const Vec3c q = leg(X, P, i);
      G(3 + i) = bilinear(q, q) - P.l2(i) * x0_2 * x0_2;
      if (J) {
        const Vec3c dq0 = p + P.b(0, i) * r1 + P.b(1, i) * r2 - 2.0 * x0 * P.a.col(i);
        (*J)(3 + i, 0) = 2.0 * bilinear(q, dq0) - 4.0 * P.l2(i) * x0_2 * x0;
        J->block<1, 3>(3 + i, 1) = 2.0 * x0 * q.transpose();
        J->block<1, 3>(3 + i, 4) =
            2.0 * (P.b(0, i) * x0 * q + P.b(2, i) * cross(r2, q)).transpose();
        J->block<1, 3>(3 + i, 7) =
            2.0 * (P.b(1, i) * x0 * q + P.b(2, i) * cross(q, r1)).transpose();
      }
    }
    G(9) = (patch.transpose() * X)(0) - 1.0;
    if (J) J->row(9) = patch.transpose();
  }

  // dG/ds along P(s) = P0 + s d (d changes only the lengths when `lengths_only`).
  static Vec10 parameter_derivative(const Vec10& X, const Params& P, const Params& d,
                                    bool lengths_only) {
    Vec10 dG = Vec10::Zero();
    const C x0 = X(0);
    if (lengths_only) {
      const C x0_4 = (x0 * x0) * (x0 * x0);
      for (int i = 0; i < 6; ++i) dG(3 + i) = -d.l2(i) * x0_4;
      return dG;
    }
    const Vec3c r1 = X.segment<3>(4), r2 = X.segment<3>(7), c = cross(r1, r2);
    for (int i = 0; i < 6; ++i) {
      const Vec3c q = leg(X, P, i);
      const Vec3c dq =
          x0 * (d.b(0, i) * r1 + d.b(1, i) * r2) + d.b(2, i) * c - x0 * x0 * d.a.col(i);
      dG(3 + i) = 2.0 * bilinear(q, dq) - d.l2(i) * x0 * x0 * x0 * x0;
    }
    return dG;
  }

  // dX/ds = -J^-1 dG/ds.
  Vec10 tangent(const Vec10& X, const Params& P0, const Params& d, double s,
                bool lengths_only) const {
    const Params P = along(P0, d, s);
    Vec10 G;
    Mat10 J;
    evaluate(X, P, G, &J);
    return solve(J, -parameter_derivative(X, P, d, lengths_only));
  }

  // Newton's method at P from y: true when |G| is below kSolved or the steps contract to
  // `tolerance` (relative to |y|) within `iterations`.
  bool correct(Vec10& y, const Params& P, int iterations, double tolerance) const {
    double previous = INFINITY;
    for (int it = 0; it < iterations; ++it) {
      Vec10 G;
      Mat10 J;
      evaluate(y, P, G, &J);
      if (G.cwiseAbs().maxCoeff() < kSolved) return true;
      const Vec10 dx = solve(J, -G);
      const double norm = dx.norm();
      if (!std::isfinite(norm) || (it > 0 && norm > 0.5 * previous)) return false;
      y += dx;
      if (norm < tolerance * y.norm()) return true;
      previous = norm;
    }
    return false;
  }

  // The projective point of an affine one, on the patch.
  Vec10 lift(const Vec9& x) const {
    Vec10 X;
    X(0) = 1.0;
    X.tail<9>() = x;
    return X / (patch.transpose() * X)(0);
  }
};

enum class PathEnd { reached, at_infinity, failed };

struct Path {
  Vec10 x;
  PathEnd end = PathEnd::reached;
  std::string why;
};

// How carefully a path is followed: the first try, and the retry of a path that failed.
struct Tracking {
  double first_step = 0.02;
  double largest_step = kLargestStep;
  double smallest_step = kSmallestStep;
  int corrector_steps = 3;
  int grow_after = 3;  // good steps after which the step is doubled
};
constexpr Tracking kCareful{0.01, 0.01, 1e-15, 4};
// From a geometry's own start (paths in the lengths alone, short and smooth).
constexpr Tracking kFromGeometry{0.25, 1.0, kSmallestStep, 3, 2};

// Follows X from P0 (s = 0) to P1 (s = 1).
Path track(const Homogeneous& H, Vec10 X, const Params& P0, const Params& P1,
           const Tracking& how = {}) {
  const Params d = P1 - P0;
  const bool lengths_only = d.a.isZero(0.0) && d.b.isZero(0.0);
  double s = 0.0, h = how.first_step;
  int good = 0;
  for (int step = 0; step < kMaxSteps; ++step) {
    if (s >= 1.0) return {X, PathEnd::reached, ""};
    h = std::min(h, 1.0 - s);
    const Vec10 k1 = H.tangent(X, P0, d, s, lengths_only);
    const Vec10 k2 = H.tangent(X + 0.5 * h * k1, P0, d, s + 0.5 * h, lengths_only);
    const Vec10 k3 = H.tangent(X + 0.5 * h * k2, P0, d, s + 0.5 * h, lengths_only);
    const Vec10 k4 = H.tangent(X + h * k3, P0, d, s + h, lengths_only);
    Vec10 y = X + (h / 6.0) * (k1 + 2.0 * k2 + 2.0 * k3 + k4);
    const double t = s + h >= 1.0 ? 1.0 : s + h;
    if (y.allFinite() && H.correct(y, along(P0, d, t), how.corrector_steps, kTracking)) {
      X = y;
      s = t;
      // Near the end, beyond 1e7 in lengths scaled to ~1: no machine's pose; the path runs to
      // infinity (earlier, a path may pass near infinity and come back).
      if (s > kEndgame && std::abs(X(0)) < kTowardInfinity * X.norm())
        return {X, PathEnd::at_infinity, ""};
      if (++good >= how.grow_after) {
        h = std::min(2.0 * h, how.largest_step);
        good = 0;
      }
      continue;
    }
    h *= 0.5;
    good = 0;
    if (h < how.smallest_step) {
      if (s > kEndgame && std::abs(X(0)) < 1e-4 * X.norm()) return {X, PathEnd::at_infinity, ""};
      return {X, PathEnd::failed,
              fmt::format("the step fell below {:g} at s = {:.9f}", how.smallest_step, s)};
    }
  }
  return {X, PathEnd::failed, fmt::format("no end after {} steps (s = {:.6f})", kMaxSteps, s)};
}

Params dietmaier() {
  Params P;
  for (int i = 0; i < 6; ++i) {
    for (int k = 0; k < 3; ++k) {
      P.a(k, i) = kDietmaierBase[i][k];
      P.b(k, i) = kDietmaierPlatform[i][k];
    }
    P.l2(i) = kDietmaierLengths[i] * kDietmaierLengths[i];
  }
  return P;
}

// The 40 solutions at a random complex geometry near Dietmaier's, tracked once from his, with
// the random patch.
struct Start {
  Homogeneous H;
  Params P;
  std::vector<Vec10> X;
  Tracking how;  // of the first try of each path
};

Start make_start(std::uint64_t seed) {
  Start s;
  const Params Pd = dietmaier();
  std::mt19937_64 engine(seed);  // the stream is fixed by the standard
  auto uniform = [&] { return static_cast<double>(engine() >> 11) * 0x1.0p-53 * 2.0 - 1.0; };
  for (int k = 0; k < 10; ++k) s.H.patch(k) = C(uniform(), uniform());
  // Near a typical machine in the scaled units: joints in pairs on a base circle of radius
  // 0.6 and a platform circle of 0.25, legs of length 1; then complex noise.
  for (int i = 0; i < 6; ++i) {
    const double pair = (i / 2) * 2.0 * std::numbers::pi / 3.0;
    const double base_angle = pair + (i % 2 ? 0.17 : -0.17);
    const double platform_angle = pair + std::numbers::pi / 3.0 + (i % 2 ? -0.17 : 0.17);
    s.P.a.col(i) = Vec3c(0.6 * std::cos(base_angle), 0.6 * std::sin(base_angle), 0.0);
    s.P.b.col(i) = Vec3c(0.25 * std::cos(platform_angle), 0.25 * std::sin(platform_angle), 0.0);
    s.P.l2(i) = 1.0;
    for (int k = 0; k < 3; ++k) {
      s.P.a(k, i) += kStartNoise * C(uniform(), uniform());
      s.P.b(k, i) += kStartNoise * C(uniform(), uniform());
    }
    s.P.l2(i) += kStartNoise * C(uniform(), uniform());
  }
  for (const auto& row : kDietmaierSolutions) {
    Vec9 x;
    for (int k = 0; k < 9; ++k) x(k) = row[k];
    Vec10 X = s.H.lift(x);
    if (!s.H.correct(X, Pd, 8, kConverged))
      throw std::logic_error("assembly modes: a start point does not solve");
    const Path path = track(s.H, X, Pd, s.P);
    if (path.end != PathEnd::reached)
      throw std::logic_error("assembly modes: a start path did not reach the complex geometry: " +
                             path.why);
    s.X.push_back(path.x);
  }
  return s;
}

// Two start systems, each made once per process: the second, with other random numbers, is
// tried when a path from the first fails.
const Start& complex_start(int which) {
  static const Start first = make_start(20261207);
  if (which == 0) return first;
  static const Start second = make_start(7121962);
  return second;
}

// The ends of the paths from `start` to `target`: each path is tried once more, carefully, when
// it fails.
std::vector<Path> track_all(const Start& start, const Params& target) {
  std::vector<Path> ends;
  ends.reserve(start.X.size());
  for (const Vec10& X : start.X) {
    Path path = track(start.H, X, start.P, target, start.how);
    if (path.end == PathEnd::failed) path = track(start.H, X, start.P, target, kCareful);
    if (path.end == PathEnd::reached && std::abs(path.x(0)) < kAtInfinity * path.x.norm())
      path.end = PathEnd::at_infinity;
    if (path.end == PathEnd::reached && !start.H.correct(path.x, target, 8, kConverged))
      path = {path.x, PathEnd::failed, "its end does not converge"};
    ends.push_back(std::move(path));
  }
  return ends;
}

// The paths from `start` to `target` (scaled by `scale`), classified (see the header).
AssemblyModes solve_from(const Start& start, const Params& target,
                         const Eigen::Matrix<double, 3, 6>& base,
                         const Eigen::Matrix<double, 3, 6>& platform,
                         const Eigen::Matrix<double, 6, 1>& lengths, double scale) {
  AssemblyModes modes;
  std::vector<Vec9> found;
  std::vector<std::size_t> found_path;
  const std::vector<Path> ends = track_all(start, target);
  for (std::size_t k = 0; k < ends.size(); ++k) {
    const Path& path = ends[k];
    ++modes.paths;
    if (path.end == PathEnd::at_infinity) {
      ++modes.at_infinity;
      continue;
    }
    if (path.end == PathEnd::failed) {
      ++modes.failed;
      modes.failures.push_back(fmt::format("path {}: {}", k + 1, path.why));
      continue;
    }
    const Vec9 x = path.x.tail<9>() / path.x(0);
    const double size = 1.0 + x.norm();
    if (x.imag().cwiseAbs().maxCoeff() > kRealTolerance * size) {
      ++modes.complex_count;
      continue;
    }
    Vec10 X = start.H.lift(x.real().cast<C>());
    start.H.correct(X, target, 4, kConverged);
    const Vec9 real = (X.tail<9>() / X(0)).real().cast<C>();
    bool duplicate = false;
    for (std::size_t j = 0; j < found.size() && !duplicate; ++j) {
      if ((found[j] - real).norm() < 1e-6 * size) {
        duplicate = true;
        ++modes.failed;
        modes.failures.push_back(fmt::format(
            "paths {} and {} end at the same solution (a path jumped, or the solution is "
            "singular)",
            found_path[j] + 1, k + 1));
      }
    }
    if (duplicate) continue;
    found.push_back(real);
    found_path.push_back(k);
    AssemblyMode mode;
    const Eigen::Vector3d r1 = real.segment<3>(3).real(), r2 = real.segment<3>(6).real();
    mode.rotation << r1, r2, r1.cross(r2);
    mode.position = scale * real.segment<3>(0).real();
    for (int i = 0; i < 6; ++i)
      mode.residual =
          std::max(mode.residual,
                   std::abs((mode.position + mode.rotation * platform.col(i) - base.col(i)).norm() -
                            lengths(i)));
    modes.real.push_back(mode);
  }
  return modes;
}

// The geometry (base, platform) divided by `scale`, with squared lengths (lengths / scale)^2.
Params scaled(const Eigen::Matrix<double, 3, 6>& base, const Eigen::Matrix<double, 3, 6>& platform,
              const Eigen::Matrix<double, 6, 1>& lengths, double scale) {
  Params P;
  P.a = (base / scale).cast<C>();
  P.b = (platform / scale).cast<C>();
  P.l2 = (lengths / scale).array().square().matrix().cast<C>();
  return P;
}

void check_geometry(const Eigen::Matrix<double, 3, 6>& base,
                    const Eigen::Matrix<double, 3, 6>& platform, const char* who) {
  if (!base.allFinite() || !platform.allFinite())
    throw std::invalid_argument(fmt::format("{}: expected finite joint points", who));
}

void check_lengths(const Eigen::Matrix<double, 6, 1>& lengths, const char* who) {
  if (!lengths.allFinite() || !(lengths.minCoeff() > 0.0))
    throw std::invalid_argument(fmt::format("{}: expected finite leg lengths > 0", who));
}

// Whether det J vanishes at three generic poses: an architecture-singular geometry (every pose
// singular, e.g. similar planar base and platform; Ma & Angeles 1991, Karger 2003), whose
// forward kinematics has curves of solutions (self-motions) for any lengths.
bool singular_at_every_pose(const Eigen::Matrix<double, 3, 6>& base,
                            const Eigen::Matrix<double, 3, 6>& platform) {
  const double size =
      std::max({base.colwise().norm().maxCoeff(), platform.colwise().norm().maxCoeff(), 1e-9});
  const double rho = std::max(platform.colwise().norm().mean(), 1e-9 * size);
  const Eigen::Vector3d positions[3] = {{0.13, -0.07, 1.0}, {-0.21, 0.05, 0.8}, {0.04, 0.17, 1.3}};
  const Eigen::Vector3d axes[3] = {{0.3, -0.5, 0.8}, {-0.7, 0.2, 0.4}, {0.1, 0.9, -0.3}};
  const double angles[3] = {0.37, -0.52, 0.81};
  for (int k = 0; k < 3; ++k) {
    const Eigen::Matrix3d R = Eigen::AngleAxisd(angles[k], axes[k].normalized()).toRotationMatrix();
    const Eigen::Vector3d p = size * positions[k];
    Eigen::Matrix<double, 6, 6> J;
    for (int i = 0; i < 6; ++i) {
      const Eigen::Vector3d r = R * platform.col(i), l = p + r - base.col(i);
      const Eigen::Vector3d s = l / l.norm();
      J.block<1, 3>(i, 0) = s.transpose();
      J.block<1, 3>(i, 3) = r.cross(s).transpose() / rho;
    }
    if (!(std::abs(J.determinant()) < 1e-10)) return false;
  }
  return true;
}

}  // namespace

AssemblyModes all_assembly_modes(const Eigen::Matrix<double, 3, 6>& base,
                                 const Eigen::Matrix<double, 3, 6>& platform,
                                 const Eigen::Matrix<double, 6, 1>& lengths) {
  check_geometry(base, platform, "all_assembly_modes");
  check_lengths(lengths, "all_assembly_modes");
  const double scale = lengths.mean();
  const Params target = scaled(base, platform, lengths, scale);
  AssemblyModes modes = solve_from(complex_start(0), target, base, platform, lengths, scale);
  if (modes.failed > 0) {
    // Another random path for every solution: the failures of the first are reported only when
    // the second fails too.
    AssemblyModes again = solve_from(complex_start(1), target, base, platform, lengths, scale);
    if (again.failed < modes.failed) modes = std::move(again);
  }
  modes.architecture_singular = singular_at_every_pose(base, platform);
  return modes;
}

// The geometry's own start: its finite solutions at random complex squared lengths.
struct AssemblyModeSolver::Geometry {
  Eigen::Matrix<double, 3, 6> base, platform;
  double scale = 1.0;
  Start start;                  // no points when the geometry's start could not be made
  std::size_t at_infinity = 0;  // paths that end at infinity for every set of lengths
  bool architecture_singular = false;
};

AssemblyModeSolver::AssemblyModeSolver(const Eigen::Matrix<double, 3, 6>& base,
                                       const Eigen::Matrix<double, 3, 6>& platform,
                                       const Eigen::Matrix<double, 6, 1>& typical_lengths) {
  check_geometry(base, platform, "AssemblyModeSolver");
  check_lengths(typical_lengths, "AssemblyModeSolver");
  auto g = std::make_shared<Geometry>();
  g->base = base;
  g->platform = platform;
  g->scale = typical_lengths.mean();
  g->architecture_singular = singular_at_every_pose(base, platform);
  Params P = scaled(base, platform, typical_lengths, g->scale);
  std::mt19937_64 engine(kGeometrySeed);  // the stream is fixed by the standard
  auto uniform = [&] { return static_cast<double>(engine() >> 11) * 0x1.0p-53 * 2.0 - 1.0; };
  for (int i = 0; i < 6; ++i) P.l2(i) += kGeometryNoise * C(uniform(), uniform());
  for (int which = 0; which < 2; ++which) {
    // A solution beyond 1e7 leg lengths at these lengths (at infinity, as all_assembly_modes
    // counts it) is dropped: it stays far from any machine's poses for lengths within a
    // machine's range.
    const Start& universal = complex_start(which);
    const std::vector<Path> ends = track_all(universal, P);
    if (std::any_of(ends.begin(), ends.end(),
                    [](const Path& p) { return p.end == PathEnd::failed; }))
      continue;
    Start own{universal.H, P, {}, kFromGeometry};
    std::size_t at_infinity = 0;
    for (const Path& path : ends) {
      if (path.end == PathEnd::at_infinity)
        ++at_infinity;
      else
        own.X.push_back(path.x);
    }
    // Random complex lengths meet no singular solution (probability 1): two equal ends mean a
    // path jumped, and this start is not used.
    bool distinct = true;
    for (std::size_t i = 0; i < own.X.size() && distinct; ++i) {
      const Vec10 xi = own.X[i] / own.X[i](0);
      for (std::size_t j = i + 1; j < own.X.size() && distinct; ++j)
        distinct = (xi - own.X[j] / own.X[j](0)).norm() > 1e-6 * (1.0 + xi.norm());
    }
    if (!distinct) continue;
    g->start = std::move(own);
    g->at_infinity = at_infinity;
    break;
  }
  geometry_ = std::move(g);
}

std::size_t AssemblyModeSolver::finite_solutions() const { return geometry_->start.X.size(); }

AssemblyModes AssemblyModeSolver::solve(const Eigen::Matrix<double, 6, 1>& lengths) const {
  check_lengths(lengths, "AssemblyModeSolver::solve");
  const Geometry& g = *geometry_;
  if (!g.start.X.empty()) {
    const Params target = scaled(g.base, g.platform, lengths, g.scale);
    AssemblyModes modes = solve_from(g.start, target, g.base, g.platform, lengths, g.scale);
    modes.at_infinity += g.at_infinity;
    modes.paths += g.at_infinity;
    modes.architecture_singular = g.architecture_singular;
    if (modes.failed == 0) return modes;
  }
  // The geometry's start failed, or one of its paths did: all 40 paths from the universal start.
  return all_assembly_modes(g.base, g.platform, lengths);
}

}  // namespace pkmopt
