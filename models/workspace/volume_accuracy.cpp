#include "models/workspace/volume_accuracy.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace pkmopt {
namespace {

WorkspaceOptions volume_options(const WorkspaceOptions& options, double resolution) {
  WorkspaceOptions o = options;
  o.resolution = resolution;
  o.compute_maps = false;
  o.compute_hull = false;
  o.keep_points = false;
  return o;
}

// Nodes of a grid of spacing h over the search box (as workspace.cpp counts them).
double grid_nodes(const Eigen::AlignedBox3d& box, double h) {
  const Eigen::Vector3d size = box.sizes();
  double nodes = 1.0;
  for (int a = 0; a < 3; ++a) nodes *= std::floor(size(a) / h) + 2.0;
  return nodes;
}

constexpr double kMaxAutoNodes = 3e7;

}  // namespace

VolumeAccuracy workspace_volume_accuracy(const Machine& machine, const WorkspaceOptions& options,
                                         std::optional<double> volume) {
  VolumeAccuracy out;
  out.resolution = options.resolution;
  out.volume =
      volume ? *volume : workspace_volume(machine, volume_options(options, options.resolution));
  out.coarse_volume = workspace_volume(machine, volume_options(options, 2.0 * options.resolution));
  out.error = std::abs(out.volume - out.coarse_volume);
  out.grids = 2;
  return out;
}

VolumeAccuracy choose_workspace_resolution(const Machine& machine, const WorkspaceOptions& options,
                                           double tolerance, std::optional<double> start) {
  if (!(tolerance > 0.0 && tolerance < 1.0)) {
    throw std::invalid_argument("tolerance = " + std::to_string(tolerance) +
                                ". Violated constraint: 0 < tolerance < 1");
  }
  const Eigen::AlignedBox3d box =
      options.search_box ? *options.search_box
                         : workspace_search_box(machine, sample_orientations(options.orientations))
                               .value_or(Eigen::AlignedBox3d());
  if (box.isEmpty()) throw std::invalid_argument("the machine has no workspace search box");
  double h = start ? *start : box.sizes().maxCoeff() / 16.0;
  if (!(h > 0.0 && std::isfinite(h))) throw std::invalid_argument("start resolution must be > 0");
  VolumeAccuracy out;
  out.tolerance = tolerance;
  double coarse = workspace_volume(machine, volume_options(options, 2.0 * h));
  out.grids = 1;
  for (;;) {
    const double fine = workspace_volume(machine, volume_options(options, h));
    ++out.grids;
    out.resolution = h;
    out.volume = fine;
    out.coarse_volume = coarse;
    out.error = std::abs(fine - coarse);
    out.met = fine > 0.0 && out.error <= tolerance * fine;
    if (out.met) return out;
    if (fine == 0.0 && coarse == 0.0) return out;  // nothing reachable: no grid finds it
    // At most kMaxAutoNodes nodes (about 10 s for a hexapod), and never past the options' limit.
    const double limit = std::min(kMaxAutoNodes, static_cast<double>(options.max_grid_nodes));
    if (grid_nodes(box, 0.5 * h) > limit) return out;
    // At most 7 halvings (1/16 to 1/2048 of the box): a volume that does not converge by then
    // (a tripod's, which grows with the grid spacing) will not, and each grid costs more.
    if (out.grids >= 8) return out;
    coarse = fine;
    h *= 0.5;
  }
}

}  // namespace pkmopt
