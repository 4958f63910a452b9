#include "models/workspace/workspace.hpp"

#include <fmt/format.h>
#include <omp.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <numbers>
#include <sstream>
#include <stdexcept>
#include <type_traits>
#include <unordered_map>

namespace pkmopt {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// The 7 edge directions of the Freudenthal triangulation, bit d of (index + 1) = step along axis d.
Eigen::Vector3i direction_offset(int direction) {
  const int bits = direction + 1;
  return {bits & 1, (bits >> 1) & 1, (bits >> 2) & 1};
}

int direction_index(const Eigen::Vector3i& offset) {
  return (offset(0) | (offset(1) << 1) | (offset(2) << 2)) - 1;
}

// Decides inside/outside and gathers the metrics at TCP positions for one thread.
class PointEvaluator {
 public:
  PointEvaluator(const Machine& machine, const std::vector<Eigen::Vector3d>& angles,
                 const WorkspaceOptions& options)
      : machine_(machine),
        angles_(angles),
        options_(options),
        data_(machine.make_data()),
        restricted_(options.min_singularity_margin || options.min_stiffness) {
    data_->compliance_metrics = options.compliance_maps;
  }

  bool inside(const Eigen::Vector3d& position) {
    pose_.position = position;
    const int n = static_cast<int>(angles_.size());
    if (n == 0) return false;
    const bool need_all = options_.orientations.mode == OrientationSet::Mode::kAll;
    // The orientation that decided the last query decides most neighbouring queries too.
    if (admissible(last_) != need_all) return !need_all;
    for (int o = 0; o < n; ++o) {
      if (o == last_) continue;
      if (admissible(o) != need_all) {
        last_ = o;
        return !need_all;
      }
    }
    return need_all;
  }

  // The worst metrics over the orientations that count at `position`; false if none counts.
  bool metrics(const Eigen::Vector3d& position, WorkspacePointMetrics& out) {
    pose_.position = position;
    const bool need_all = options_.orientations.mode == OrientationSet::Mode::kAll;
    out.singularity_margin = kInf;
    out.stiffness_min = kInf;
    out.max_leg_force = 0.0;
    out.tcp_error_max = 0.0;
    out.tcp_deflection = 0.0;
    out.stiffness_min_loaded = kInf;
    out.natural_frequency_1 = kInf;
    int counted = 0;
    for (std::size_t o = 0; o < angles_.size(); ++o) {
      pose_.angles = angles_[o];
      machine_.analyze(*data_, pose_, options_.wrench, pose_metrics_);
      if (!need_all && !(pose_metrics_.reachable && meets_restrictions())) continue;
      ++counted;
      out.singularity_margin = std::min(out.singularity_margin, pose_metrics_.singularity_margin);
      out.stiffness_min = std::min(out.stiffness_min, pose_metrics_.stiffness_min);
      out.max_leg_force = std::max(out.max_leg_force, pose_metrics_.tau.cwiseAbs().maxCoeff());
      out.tcp_error_max = std::max(out.tcp_error_max, pose_metrics_.tcp_error_max);
      out.tcp_deflection = std::max(out.tcp_deflection, pose_metrics_.tcp_deflection);
      out.stiffness_min_loaded =
          std::min(out.stiffness_min_loaded, pose_metrics_.stiffness_min_loaded);
      if (pose_metrics_.natural_frequencies.size() > 0)
        out.natural_frequency_1 =
            std::min(out.natural_frequency_1, pose_metrics_.natural_frequencies(0));
    }
    if (!std::isfinite(out.natural_frequency_1)) out.natural_frequency_1 = 0.0;  // no masses
    if (counted == 0) out = WorkspacePointMetrics{};
    return counted > 0;
  }

 private:
  bool meets_restrictions() const {
    if (options_.min_singularity_margin &&
        !(pose_metrics_.singularity_margin >= *options_.min_singularity_margin)) {
      return false;
    }
    if (options_.min_stiffness && !(pose_metrics_.stiffness_min >= *options_.min_stiffness)) {
      return false;
    }
    return true;
  }

  bool admissible(int orientation) {
    pose_.angles = angles_[static_cast<std::size_t>(orientation)];
    if (!machine_.reachable(*data_, pose_)) return false;
    if (!restricted_) return true;
    machine_.analyze(*data_, pose_, options_.wrench, pose_metrics_);
    return pose_metrics_.reachable && meets_restrictions();
  }

  const Machine& machine_;
  const std::vector<Eigen::Vector3d>& angles_;
  const WorkspaceOptions& options_;
  std::unique_ptr<MachineData> data_;
  bool restricted_;
  Pose pose_;
  PoseMetrics pose_metrics_;
  int last_ = 0;
};

std::vector<Eigen::Vector3d> orientation_angles(const std::vector<Eigen::Matrix3d>& rotations) {
  std::vector<Eigen::Vector3d> angles;
  angles.reserve(rotations.size());
  for (const auto& R : rotations) angles.push_back(angles_from_rotation(R));
  return angles;
}

std::string number_text(double v) {
  std::ostringstream os;
  os.precision(17);
  os << v;
  return os.str();
}

// The node grid over a search box, padded by one cell so that its rim lies outside the box.
struct Grid {
  Eigen::Vector3d origin;
  double h = 0.0;
  std::int64_t nx = 0, ny = 0, nz = 0;

  std::int64_t size() const { return nx * ny * nz; }
  std::int64_t index(std::int64_t i, std::int64_t j, std::int64_t k) const {
    return i + nx * (j + ny * k);
  }
  Eigen::Vector3d position(std::int64_t i, std::int64_t j, std::int64_t k) const {
    return origin + h * Eigen::Vector3d(static_cast<double>(i), static_cast<double>(j),
                                        static_cast<double>(k));
  }
  Eigen::Vector3d position(std::int64_t node) const {
    return position(node % nx, (node / nx) % ny, node / (nx * ny));
  }
  bool on_rim(std::int64_t i, std::int64_t j, std::int64_t k) const {
    return i == 0 || j == 0 || k == 0 || i == nx - 1 || j == ny - 1 || k == nz - 1;
  }
};

// Throws std::invalid_argument when the grid would have more than max_nodes nodes; the counts
// are computed in double first, so that a tiny resolution cannot overflow the integer sizes.
Grid make_grid(const Eigen::AlignedBox3d& box, double h, std::int64_t max_nodes) {
  Grid grid;
  grid.h = h;
  grid.origin = box.min() - Eigen::Vector3d::Constant(h);
  const Eigen::Vector3d extent = box.max() - box.min();
  auto count = [&](double length) { return std::ceil(length / h - 1e-9) + 3.0; };
  const Eigen::Vector3d n(count(extent(0)), count(extent(1)), count(extent(2)));
  const double nodes = n(0) * n(1) * n(2);
  if (!(nodes <= static_cast<double>(max_nodes))) {
    throw std::invalid_argument(
        fmt::format("the workspace grid would have {:.4g} nodes ({:.4g} x {:.4g} x {:.4g}) at a "
                    "resolution of {:g} m, more than max_grid_nodes = {}; use a coarser resolution",
                    nodes, n(0), n(1), n(2), h, max_nodes));
  }
  grid.nx = static_cast<std::int64_t>(n(0));
  grid.ny = static_cast<std::int64_t>(n(1));
  grid.nz = static_cast<std::int64_t>(n(2));
  return grid;
}

// Node classes of the fine grid.
struct Classification {
  Grid grid;
  std::vector<std::uint8_t> inside;
  bool touches_rim = false;
  bool at(std::int64_t i, std::int64_t j, std::int64_t k) const {
    return inside[static_cast<std::size_t>(grid.index(i, j, k))] != 0;
  }
};

Classification classify_grid(const Machine& machine, const std::vector<Eigen::Vector3d>& angles,
                             const WorkspaceOptions& options, const Eigen::AlignedBox3d& box) {
  Classification cls;
  Grid& grid = cls.grid;
  grid = make_grid(box, options.resolution, options.max_grid_nodes);
  const std::int64_t nx = grid.nx, ny = grid.ny, nz = grid.nz;
  cls.inside.assign(static_cast<std::size_t>(grid.size()), 0);
  // The padded rim is outside the search box and stays outside, which closes the mesh; the
  // box's own faces are checked so that a cut-off region is reported. Layer k of the grid is
  // computed by the process that owns it (all of them without a share).
#pragma omp parallel
  {
    PointEvaluator evaluator(machine, angles, options);
#pragma omp for schedule(dynamic, 1) collapse(2)
    for (std::int64_t k = 1; k < nz - 1; ++k) {
      for (std::int64_t j = 1; j < ny - 1; ++j) {
        if (!owns(options.share, static_cast<std::size_t>(k))) continue;
        for (std::int64_t i = 1; i < nx - 1; ++i) {
          const bool in = evaluator.inside(grid.position(i, j, k));
          cls.inside[static_cast<std::size_t>(grid.index(i, j, k))] = in ? 1 : 0;
        }
      }
    }
  }
  share_groups(options.share, cls.inside.data(), static_cast<std::size_t>(nz),
               static_cast<std::size_t>(nx * ny));
  for (std::int64_t k = 1; k < nz - 1 && !cls.touches_rim; ++k)
    for (std::int64_t j = 1; j < ny - 1 && !cls.touches_rim; ++j)
      for (std::int64_t i = 1; i < nx - 1; ++i)
        if ((i == 1 || j == 1 || k == 1 || i == nx - 2 || j == ny - 2 || k == nz - 2) &&
            cls.at(i, j, k)) {
          cls.touches_rim = true;
          break;
        }
  return cls;
}

// The boundary mesh: crossings of the grid edges located by bisection, joined by marching
// tetrahedra.
TriangleMesh extract_surface(const Machine& machine, const std::vector<Eigen::Vector3d>& angles,
                             const WorkspaceOptions& options, const Classification& cls,
                             std::int64_t* crossing_count = nullptr) {
  const Grid& grid = cls.grid;
  const std::int64_t mx = grid.nx, my = grid.ny, mz = grid.nz;  // nodes along x, y, z
  auto inside = [&](std::int64_t node) { return cls.inside[static_cast<std::size_t>(node)]; };

  // 1. Grid edges whose ends differ, keyed node * 7 + direction, ascending.
  std::vector<std::vector<std::int64_t>> layer_keys(static_cast<std::size_t>(mz));
#pragma omp parallel for schedule(dynamic, 1)
  for (std::int64_t k = 0; k < mz; ++k) {
    auto& keys = layer_keys[static_cast<std::size_t>(k)];
    for (std::int64_t j = 0; j < my; ++j) {
      for (std::int64_t i = 0; i < mx; ++i) {
        const std::int64_t node = grid.index(i, j, k);
        const std::uint8_t in = inside(node);
        for (int d = 0; d < 7; ++d) {
          const Eigen::Vector3i o = direction_offset(d);
          if (i + o(0) >= mx || j + o(1) >= my || k + o(2) >= mz) continue;
          if (inside(grid.index(i + o(0), j + o(1), k + o(2))) != in) keys.push_back(node * 7 + d);
        }
      }
    }
  }
  std::vector<std::int64_t> crossing_keys;
  for (auto& keys : layer_keys) crossing_keys.insert(crossing_keys.end(), keys.begin(), keys.end());
  const std::int64_t crossings = static_cast<std::int64_t>(crossing_keys.size());
  if (crossing_count) *crossing_count = crossings;

  // 2. Bisect every crossing edge to h / 2^steps.
  TriangleMesh mesh;
  mesh.vertices.resize(static_cast<std::size_t>(crossings));
#pragma omp parallel
  {
    PointEvaluator evaluator(machine, angles, options);
#pragma omp for schedule(dynamic, 64)
    for (std::int64_t c = 0; c < crossings; ++c) {
      if (!owns(options.share, static_cast<std::size_t>(c))) continue;
      const std::int64_t key = crossing_keys[static_cast<std::size_t>(c)];
      const std::int64_t node = key / 7;
      const Eigen::Vector3i o = direction_offset(static_cast<int>(key % 7));
      const Eigen::Vector3d a = grid.position(node);
      const Eigen::Vector3d b = a + grid.h * o.cast<double>();
      const bool a_inside = inside(node) != 0;
      Eigen::Vector3d in = a_inside ? a : b;
      Eigen::Vector3d out = a_inside ? b : a;
      for (int step = 0; step < options.bisection_steps; ++step) {
        const Eigen::Vector3d mid = 0.5 * (in + out);
        (evaluator.inside(mid) ? in : out) = mid;
      }
      mesh.vertices[static_cast<std::size_t>(c)] = 0.5 * (in + out);
    }
  }
  static_assert(sizeof(Eigen::Vector3d) == 3 * sizeof(double));
  static_assert(std::is_trivially_copyable_v<WorkspacePointMetrics>);
  share_groups(options.share, mesh.vertices.data(), static_cast<std::size_t>(crossings),
               sizeof(Eigen::Vector3d));

  // 3. Marching tetrahedra over the 6 Freudenthal tetrahedra of every cell with mixed corners.
  auto vertex_of = [&](std::int64_t node_a, const Eigen::Vector3i& ca, const Eigen::Vector3i& cb) {
    const std::int64_t key = node_a * 7 + direction_index(cb - ca);
    const auto it = std::lower_bound(crossing_keys.begin(), crossing_keys.end(), key);
    return static_cast<int>(it - crossing_keys.begin());
  };
  static constexpr int kPermutations[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2},
                                              {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
  std::vector<std::vector<std::array<int, 3>>> layer_triangles(static_cast<std::size_t>(mz));
#pragma omp parallel for schedule(dynamic, 1)
  for (std::int64_t k = 0; k < mz - 1; ++k) {
    auto& triangles = layer_triangles[static_cast<std::size_t>(k)];
    for (std::int64_t j = 0; j < my - 1; ++j) {
      for (std::int64_t i = 0; i < mx - 1; ++i) {
        int count = 0;
        for (int c = 0; c < 8; ++c) {
          count += inside(grid.index(i + (c & 1), j + ((c >> 1) & 1), k + ((c >> 2) & 1)));
        }
        if (count == 0 || count == 8) continue;
        for (const auto& perm : kPermutations) {
          Eigen::Vector3i corner[4];
          corner[0] = Eigen::Vector3i::Zero();
          corner[1] = corner[0];
          corner[1](perm[0]) = 1;
          corner[2] = corner[1];
          corner[2](perm[1]) = 1;
          corner[3] = Eigen::Vector3i::Ones();
          std::int64_t node[4];
          bool in[4];
          int inside_count = 0;
          for (int v = 0; v < 4; ++v) {
            node[v] = grid.index(i + corner[v](0), j + corner[v](1), k + corner[v](2));
            in[v] = inside(node[v]) != 0;
            inside_count += in[v];
          }
          if (inside_count == 0 || inside_count == 4) continue;
          // Crossing vertex on tetrahedron edge (a, b), a < b (corners increase along the path).
          auto crossing = [&](int a, int b) {
            if (a > b) std::swap(a, b);
            return vertex_of(node[a], corner[a], corner[b]);
          };
          // Orientation from the integer corner coordinates with crossings at edge midpoints
          // (the combinatorial type of the section does not depend on where the crossings are).
          Eigen::Vector3d centre_in = Eigen::Vector3d::Zero(), centre_out = Eigen::Vector3d::Zero();
          for (int v = 0; v < 4; ++v) (in[v] ? centre_in : centre_out) += corner[v].cast<double>();
          centre_in /= inside_count;
          centre_out /= 4 - inside_count;
          const Eigen::Vector3d outward = centre_out - centre_in;
          auto midpoint = [&](int a, int b) {
            return Eigen::Vector3d(0.5 * (corner[a] + corner[b]).cast<double>());
          };
          auto emit = [&](std::array<int, 2> e0, std::array<int, 2> e1, std::array<int, 2> e2) {
            const Eigen::Vector3d m0 = midpoint(e0[0], e0[1]);
            const Eigen::Vector3d normal =
                (midpoint(e1[0], e1[1]) - m0).cross(midpoint(e2[0], e2[1]) - m0);
            std::array<int, 3> tri{crossing(e0[0], e0[1]), crossing(e1[0], e1[1]),
                                   crossing(e2[0], e2[1])};
            if (normal.dot(outward) < 0.0) std::swap(tri[1], tri[2]);
            triangles.push_back(tri);
          };
          if (inside_count == 1 || inside_count == 3) {
            int lone = 0;
            for (int v = 0; v < 4; ++v) {
              if (in[v] == (inside_count == 1)) lone = v;
            }
            int others[3], n = 0;
            for (int v = 0; v < 4; ++v) {
              if (v != lone) others[n++] = v;
            }
            emit({lone, others[0]}, {lone, others[1]}, {lone, others[2]});
          } else {
            int ins[2], outs[2], ni = 0, no = 0;
            for (int v = 0; v < 4; ++v) (in[v] ? ins[ni++] : outs[no++]) = v;
            // The quad ins0-outs0, ins0-outs1, ins1-outs1, ins1-outs0 (a cycle), split in two
            // along its diagonal (ins0-outs0, ins1-outs1); emit orients each half.
            const std::array<int, 2> q0{ins[0], outs[0]}, q1{ins[0], outs[1]}, q2{ins[1], outs[1]},
                q3{ins[1], outs[0]};
            emit(q0, q1, q2);
            emit(q0, q2, q3);
          }
        }
      }
    }
  }
  for (auto& triangles : layer_triangles) {
    mesh.triangles.insert(mesh.triangles.end(), triangles.begin(), triangles.end());
  }
  return mesh;
}

Eigen::AlignedBox3d resolve_box(const Machine& machine, const WorkspaceOptions& options,
                                const std::vector<Eigen::Matrix3d>& rotations) {
  if (options.search_box) return *options.search_box;
  const auto box = workspace_search_box(machine, rotations);
  if (!box) {
    throw std::invalid_argument("no search box is known for machine model '" +
                                std::string(machine.model()) +
                                "': give WorkspaceOptions::search_box");
  }
  return *box;
}

void check_options(const WorkspaceOptions& options) {
  const std::string message = validate(options);
  if (!message.empty()) throw std::invalid_argument(message);
}

}  // namespace

std::int64_t orientation_count(const OrientationSet& set) {
  const double step = set.orientation_step;
  const double rings = set.tilt > 0.0 ? std::ceil(set.tilt / step - 1e-9) : 0.0;
  const double yaws = set.yaw_range > 0.0 ? std::ceil(2.0 * set.yaw_range / step - 1e-9) : 0.0;
  // As sample_orientations' loops, in doubles (a huge set must not overflow the count).
  if (!(rings < 1e7 && yaws < 1e7)) return std::numeric_limits<std::int64_t>::max();
  double count = 0.0;
  for (int ring = static_cast<int>(rings); ring >= 0; --ring) {
    const double theta = rings > 0 ? set.tilt * ring / rings : 0.0;
    const double azimuths =
        ring == 0
            ? 1.0
            : std::max(4.0, std::ceil(2.0 * std::numbers::pi * std::sin(theta) / step - 1e-9));
    count += azimuths * (yaws + 1.0);
    if (count > 9e18) return std::numeric_limits<std::int64_t>::max();
  }
  return static_cast<std::int64_t>(count);
}

std::vector<Eigen::Matrix3d> sample_orientations(const OrientationSet& set) {
  const Eigen::Matrix3d R0 = rotation_zyx<double>(set.nominal_angles);
  const double step = set.orientation_step;
  const int rings = set.tilt > 0.0 ? static_cast<int>(std::ceil(set.tilt / step - 1e-9)) : 0;
  const int yaws =
      set.yaw_range > 0.0 ? static_cast<int>(std::ceil(2.0 * set.yaw_range / step - 1e-9)) : 0;
  std::vector<Eigen::Matrix3d> rotations;
  // Rim first: the extreme tilts are the likeliest to fail, which ends "all" checks early.
  for (int ring = rings; ring >= 0; --ring) {
    const double theta = rings > 0 ? set.tilt * ring / rings : 0.0;
    const int azimuths =
        ring == 0 ? 1
                  : std::max(4, static_cast<int>(std::ceil(
                                    2.0 * std::numbers::pi * std::sin(theta) / step - 1e-9)));
    for (int a = 0; a < azimuths; ++a) {
      const double phi = 2.0 * std::numbers::pi * a / azimuths;
      const Eigen::Matrix3d tilted =
          R0 * Eigen::AngleAxisd(theta, Eigen::Vector3d(std::cos(phi), std::sin(phi), 0.0))
                   .toRotationMatrix();
      for (int m = 0; m <= yaws; ++m) {
        // Yaw ends first as well.
        const int order = (m % 2 == 0) ? m / 2 : yaws - m / 2;
        const double gamma = yaws > 0 ? -set.yaw_range + 2.0 * set.yaw_range * order / yaws : 0.0;
        rotations.push_back(tilted *
                            Eigen::AngleAxisd(gamma, Eigen::Vector3d::UnitZ()).toRotationMatrix());
      }
    }
  }
  return rotations;
}

std::string validate(const WorkspaceOptions& options) {
  auto violated = [](const std::string& name, double value, const std::string& constraint) {
    return "WorkspaceOptions::" + name + " = " + number_text(value) +
           ". Violated constraint: " + constraint;
  };
  const OrientationSet& set = options.orientations;
  if (!set.nominal_angles.allFinite()) {
    return "WorkspaceOptions::orientations.nominal_angles must be finite";
  }
  // The limits users see in degrees (workspace_limits), here in radians.
  using namespace workspace_limits;
  if (!kTiltDeg.accepts(rad_to_deg(set.tilt))) {
    return violated("orientations.tilt", set.tilt, "0 <= tilt < pi");
  }
  if (!kYawRangeDeg.accepts(rad_to_deg(set.yaw_range))) {
    return violated("orientations.yaw_range", set.yaw_range, "0 <= yaw_range < pi");
  }
  if (!kOrientationStepDeg.accepts(rad_to_deg(set.orientation_step))) {
    return violated("orientations.orientation_step", set.orientation_step,
                    "0.01 deg <= orientation_step <= pi/2");
  }
  if (const std::int64_t count = orientation_count(set); count > kMaxOrientations) {
    return fmt::format(
        "WorkspaceOptions::orientations sample {} orientations. Violated constraint: at most {} "
        "(a coarser orientation_step)",
        count, kMaxOrientations);
  }
  if (!(options.resolution > 0.0 && std::isfinite(options.resolution))) {
    return violated("resolution", options.resolution, "resolution > 0 (finite)");
  }
  if (!(options.bisection_steps >= 0 && options.bisection_steps <= 60)) {
    return violated("bisection_steps", options.bisection_steps, "0 <= bisection_steps <= 60");
  }
  if (options.min_singularity_margin &&
      !(*options.min_singularity_margin >= 0.0 && *options.min_singularity_margin <= 1.0)) {
    return violated("min_singularity_margin", *options.min_singularity_margin,
                    "0 <= min_singularity_margin <= 1");
  }
  if (options.min_stiffness &&
      !(*options.min_stiffness >= 0.0 && std::isfinite(*options.min_stiffness))) {
    return violated("min_stiffness", *options.min_stiffness, "min_stiffness >= 0 (finite)");
  }
  if (!wrench_within_limits(options.wrench))
    return "WorkspaceOptions::wrench must be finite with every component within +-1e9 (N, N*m)";
  if (options.search_box) {
    const auto& b = *options.search_box;
    if (!b.min().allFinite() || !b.max().allFinite() ||
        (b.max().array() <= b.min().array()).any()) {
      return "WorkspaceOptions::search_box must be finite with max > min on every axis";
    }
  }
  if (options.max_grid_nodes <= 0) {
    return violated("max_grid_nodes", static_cast<double>(options.max_grid_nodes),
                    "max_grid_nodes > 0");
  }
  return "";
}

WorkspaceResult compute_workspace(const Machine& machine, const WorkspaceOptions& options) {
  check_options(options);
  const std::vector<Eigen::Matrix3d> rotations = sample_orientations(options.orientations);
  const std::vector<Eigen::Vector3d> angles = orientation_angles(rotations);
  WorkspaceResult result;
  result.resolution = options.resolution;
  result.orientation_count = static_cast<int>(rotations.size());
  result.envelope_volume = machine_envelope_volume(machine);
  result.search_box = resolve_box(machine, options, rotations);
  if (result.search_box.isEmpty()) return result;  // nothing reachable

  const Classification cls = classify_grid(machine, angles, options, result.search_box);
  const Grid& grid = cls.grid;
  result.grid_nodes = Eigen::Vector3i(static_cast<int>(grid.nx), static_cast<int>(grid.ny),
                                      static_cast<int>(grid.nz));
  result.touches_search_box = cls.touches_rim;
  result.boundary = extract_surface(machine, angles, options, cls, &result.boundary_edges);
  result.surface_volume = mesh_volume(result.boundary);
  result.volume = result.surface_volume;
  for (const auto& v : result.boundary.vertices) result.bounding_box.extend(v);

  std::vector<std::int64_t> inside_nodes;
  for (std::int64_t n = 0; n < grid.size(); ++n) {
    if (cls.inside[static_cast<std::size_t>(n)]) inside_nodes.push_back(n);
  }
  result.inside_nodes = static_cast<std::int64_t>(inside_nodes.size());
  result.voxel_volume = static_cast<double>(result.inside_nodes) * grid.h * grid.h * grid.h;
  if (result.envelope_volume && *result.envelope_volume > 0.0 && result.volume > 0.0) {
    result.envelope_ratio = *result.envelope_volume / result.volume;
  }
  if (options.compute_hull)
    result.convex_hull_volume = convex_hull_volume(result.boundary.vertices);

  if (options.compute_maps || options.keep_points) {
    const std::int64_t n = result.inside_nodes;
    std::vector<WorkspacePointMetrics> metrics(static_cast<std::size_t>(n));
#pragma omp parallel
    {
      PointEvaluator evaluator(machine, angles, options);
#pragma omp for schedule(dynamic, 256)
      for (std::int64_t p = 0; p < n; ++p) {
        if (!owns(options.share, static_cast<std::size_t>(p))) continue;
        evaluator.metrics(grid.position(inside_nodes[static_cast<std::size_t>(p)]),
                          metrics[static_cast<std::size_t>(p)]);
      }
    }
    share_groups(options.share, metrics.data(), metrics.size(), sizeof(WorkspacePointMetrics));
    WorkspaceMaps& maps = result.maps;
    maps.points = n;
    if (n > 0) {
      maps.singularity_margin_min = kInf;
      maps.stiffness_min_min = kInf;
      maps.stiffness_min_loaded_min = kInf;
      maps.natural_frequencies = machine.dynamics() && options.compliance_maps;
      maps.natural_frequency_min = maps.natural_frequencies ? kInf : 0.0;
      double margin_sum = 0.0, stiffness_sum = 0.0;
      for (const auto& m : metrics) {
        margin_sum += m.singularity_margin;
        stiffness_sum += m.stiffness_min;
        maps.singularity_margin_min = std::min(maps.singularity_margin_min, m.singularity_margin);
        maps.stiffness_min_min = std::min(maps.stiffness_min_min, m.stiffness_min);
        maps.max_leg_force = std::max(maps.max_leg_force, m.max_leg_force);
        maps.tcp_error_max = std::max(maps.tcp_error_max, m.tcp_error_max);
        maps.tcp_deflection_max = std::max(maps.tcp_deflection_max, m.tcp_deflection);
        maps.stiffness_min_loaded_min =
            std::min(maps.stiffness_min_loaded_min, m.stiffness_min_loaded);
        if (maps.natural_frequencies)
          maps.natural_frequency_min = std::min(maps.natural_frequency_min, m.natural_frequency_1);
      }
      maps.global_conditioning_index = margin_sum / static_cast<double>(n);
      maps.stiffness_min_mean = stiffness_sum / static_cast<double>(n);
    }
    if (options.keep_points) {
      result.points.resize(static_cast<std::size_t>(n));
      for (std::int64_t p = 0; p < n; ++p) {
        result.points[static_cast<std::size_t>(p)] = {
            grid.position(inside_nodes[static_cast<std::size_t>(p)]),
            metrics[static_cast<std::size_t>(p)]};
      }
    }
  }
  return result;
}

double workspace_volume(const Machine& machine, const WorkspaceOptions& options) {
  check_options(options);
  const std::vector<Eigen::Matrix3d> rotations = sample_orientations(options.orientations);
  const Eigen::AlignedBox3d box = resolve_box(machine, options, rotations);
  if (box.isEmpty()) return 0.0;
  const std::vector<Eigen::Vector3d> angles = orientation_angles(rotations);
  const Classification cls = classify_grid(machine, angles, options, box);
  return mesh_volume(extract_surface(machine, angles, options, cls));
}

std::optional<Eigen::AlignedBox3d> workspace_search_box(
    const Machine& machine, const std::vector<Eigen::Matrix3d>& orientations) {
  return machine.workspace_search_box(orientations);
}

std::optional<double> machine_envelope_volume(const Machine& machine) {
  return machine.envelope_volume();
}

double mesh_volume(const TriangleMesh& mesh) {
  if (mesh.triangles.empty()) return 0.0;
  // About a point near the mesh so that the products do not lose digits far from the origin.
  Eigen::Vector3d reference = Eigen::Vector3d::Zero();
  for (const auto& v : mesh.vertices) reference += v;
  reference /= static_cast<double>(mesh.vertices.size());
  double six_volume = 0.0;
  for (const auto& t : mesh.triangles) {
    const Eigen::Vector3d a = mesh.vertices[static_cast<std::size_t>(t[0])] - reference;
    const Eigen::Vector3d b = mesh.vertices[static_cast<std::size_t>(t[1])] - reference;
    const Eigen::Vector3d c = mesh.vertices[static_cast<std::size_t>(t[2])] - reference;
    six_volume += a.dot(b.cross(c));
  }
  return six_volume / 6.0;
}

MeshTopology mesh_topology(const TriangleMesh& mesh) {
  // For every undirected edge: how often it is used forwards (low -> high) and backwards.
  std::unordered_map<std::uint64_t, std::array<int, 2>> uses;
  uses.reserve(mesh.triangles.size() * 2);
  for (const auto& t : mesh.triangles) {
    for (int e = 0; e < 3; ++e) {
      const auto a = static_cast<std::uint64_t>(t[static_cast<std::size_t>(e)]);
      const auto b = static_cast<std::uint64_t>(t[static_cast<std::size_t>((e + 1) % 3)]);
      const std::uint64_t key = a < b ? (a << 32 | b) : (b << 32 | a);
      ++uses[key][a < b ? 0 : 1];
    }
  }
  MeshTopology topology;
  topology.edges = static_cast<std::int64_t>(uses.size());
  for (const auto& [key, count] : uses) {
    const int total = count[0] + count[1];
    if (total == 1) {
      ++topology.open_edges;
    } else if (total > 2) {
      ++topology.non_manifold_edges;
    } else if (count[0] != 1) {
      ++topology.misoriented_edges;
    }
  }
  return topology;
}

WorkspaceSlice compute_workspace_slice(const Machine& machine, const WorkspaceOptions& options,
                                       const Eigen::AlignedBox3d& box, char normal_axis,
                                       double offset, double pixel) {
  check_options(options);
  int axis_n = normal_axis - 'x';
  if (axis_n < 0 || axis_n > 2) throw std::invalid_argument("slice axis must be x, y or z");
  if (!(pixel > 0.0 && std::isfinite(pixel)) || !std::isfinite(offset) || box.isEmpty()) {
    throw std::invalid_argument("slice pixel must be > 0, offset finite and the box non-empty");
  }
  const int axis_u = axis_n == 0 ? 1 : 0;
  const int axis_v = axis_n == 2 ? 1 : 2;
  const std::vector<Eigen::Vector3d> angles =
      orientation_angles(sample_orientations(options.orientations));
  WorkspaceSlice slice;
  slice.normal_axis = normal_axis;
  slice.offset = offset;
  slice.pixel = pixel;
  const double length_u = box.max()(axis_u) - box.min()(axis_u);
  const double length_v = box.max()(axis_v) - box.min()(axis_v);
  slice.width = std::max(1, static_cast<int>(std::ceil(length_u / pixel - 1e-9)));
  slice.height = std::max(1, static_cast<int>(std::ceil(length_v / pixel - 1e-9)));
  // Centre the pixel grid on the box.
  slice.origin = Eigen::Vector2d(box.min()(axis_u) + 0.5 * (length_u - (slice.width - 1) * pixel),
                                 box.min()(axis_v) + 0.5 * (length_v - (slice.height - 1) * pixel));
  const std::int64_t count = static_cast<std::int64_t>(slice.width) * slice.height;
  if (count > 100'000'000) throw std::invalid_argument("slice has too many pixels");
  slice.inside.assign(static_cast<std::size_t>(count), 0);
  slice.metrics.assign(static_cast<std::size_t>(count), WorkspacePointMetrics{});
#pragma omp parallel
  {
    PointEvaluator evaluator(machine, angles, options);
#pragma omp for schedule(dynamic, 64)
    for (std::int64_t p = 0; p < count; ++p) {
      if (!owns(options.share, static_cast<std::size_t>(p))) continue;
      Eigen::Vector3d position;
      position(axis_n) = offset;
      position(axis_u) = slice.origin(0) + static_cast<double>(p % slice.width) * pixel;
      position(axis_v) = slice.origin(1) + static_cast<double>(p / slice.width) * pixel;
      if (evaluator.inside(position)) {
        slice.inside[static_cast<std::size_t>(p)] = 1;
        evaluator.metrics(position, slice.metrics[static_cast<std::size_t>(p)]);
      }
    }
  }
  share_groups(options.share, slice.inside.data(), slice.inside.size(), 1);
  share_groups(options.share, slice.metrics.data(), slice.metrics.size(),
               sizeof(WorkspacePointMetrics));
  return slice;
}

}  // namespace pkmopt
