// convex_hull_volume: CGAL convex_hull_3 into a Surface_mesh, then its enclosed volume.
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/measure.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/convex_hull_3.h>

#include <vector>

#include "models/workspace/workspace.hpp"

namespace pkmopt {

double convex_hull_volume(const std::vector<Eigen::Vector3d>& points) {
  using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
  using Point = Kernel::Point_3;
  if (points.size() < 4) return 0.0;
  std::vector<Point> cgal_points;
  cgal_points.reserve(points.size());
  for (const auto& p : points) cgal_points.emplace_back(p.x(), p.y(), p.z());
  CGAL::Surface_mesh<Point> hull;
  CGAL::convex_hull_3(cgal_points.begin(), cgal_points.end(), hull);
  // Coplanar or collinear input gives a degenerate hull (not a closed triangle mesh).
  if (hull.number_of_faces() < 4 || !CGAL::is_closed(hull) || !CGAL::is_triangle_mesh(hull)) {
    return 0.0;
  }
  return CGAL::to_double(CGAL::Polygon_mesh_processing::volume(hull));
}

}  // namespace pkmopt
