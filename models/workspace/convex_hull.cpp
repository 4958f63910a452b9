// convex_hull_volume: CGAL convex_hull_3 into a Surface_mesh, then its enclosed volume summed in
// exact arithmetic. The hull of grid-based boundary points has many coplanar facets, which CGAL
// may triangulate differently from run to run; an inexact sum over the triangles then differs
// in its last bits. The exact sum (rounded once to double) is the same for every triangulation.
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Mpzf.h>
#include <CGAL/Polygon_2_algorithms.h>
#include <CGAL/Polygon_mesh_processing/measure.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/convex_hull_2.h>
#include <CGAL/convex_hull_3.h>

#include <cmath>
#include <iterator>
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
  // Each tetrahedron (origin, p0, p1, p2) times 6 is a 3x3 determinant of doubles; summed in
  // exact binary floating point (CGAL::Mpzf, GMP) it does not depend on the order or the
  // triangulation of the facets.
  using Exact = CGAL::Mpzf;  // exact for +, - and *
  Exact six_volume = 0;
  for (const auto face : hull.faces()) {
    Exact c[3][3];
    int k = 0;
    for (const auto v : CGAL::vertices_around_face(hull.halfedge(face), hull)) {
      const Point& q = hull.point(v);
      c[k][0] = q.x();
      c[k][1] = q.y();
      c[k][2] = q.z();
      ++k;
    }
    six_volume += c[0][0] * (c[1][1] * c[2][2] - c[1][2] * c[2][1]) -
                  c[0][1] * (c[1][0] * c[2][2] - c[1][2] * c[2][0]) +
                  c[0][2] * (c[1][0] * c[2][1] - c[1][1] * c[2][0]);
  }
  return std::abs(CGAL::to_double(six_volume)) / 6.0;
}

double footprint_area(const std::vector<Eigen::Vector3d>& points) {
  using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
  using Point = Kernel::Point_2;
  std::vector<Point> in;
  in.reserve(points.size());
  for (const auto& p : points) in.emplace_back(p.x(), p.y());
  std::vector<Point> hull;
  CGAL::convex_hull_2(in.begin(), in.end(), std::back_inserter(hull));
  if (hull.size() < 3) return 0.0;
  return std::abs(CGAL::to_double(CGAL::polygon_area_2(hull.begin(), hull.end(), Kernel())));
}

}  // namespace pkmopt
