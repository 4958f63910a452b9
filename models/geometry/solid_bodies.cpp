#include "models/geometry/solid_bodies.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "models/geometry/segment_distance.hpp"

namespace pkmopt {

namespace {

void require(bool ok, const std::string& message) {
  if (!ok) throw std::invalid_argument(message);
}

double cross2(const Eigen::Vector2d& u, const Eigen::Vector2d& v) {
  return u.x() * v.y() - u.y() * v.x();
}

// Twice the signed area of a polygon (> 0 counter-clockwise).
double twice_area(const std::vector<Eigen::Vector2d>& poly) {
  double sum = 0.0;
  for (std::size_t i = 0; i < poly.size(); ++i) sum += cross2(poly[i], poly[(i + 1) % poly.size()]);
  return sum;
}

// Distance from p to the cross-section of the prism (0 inside); `orientation` the sign of the
// polygon's area.
double section_distance(const Eigen::Vector2d& p, const ConvexPrism& prism, double orientation) {
  if (prism.polygon.empty()) return std::max(0.0, p.norm() - prism.radius);
  const auto& poly = prism.polygon;
  bool inside = true;
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < poly.size(); ++i) {
    const Eigen::Vector2d& u = poly[i];
    const Eigen::Vector2d& v = poly[(i + 1) % poly.size()];
    const Eigen::Vector2d e = v - u;
    if (orientation * cross2(e, p - u) < 0.0) inside = false;
    const double t = std::clamp((p - u).dot(e) / e.squaredNorm(), 0.0, 1.0);
    best = std::min(best, (u + t * e - p).norm());
  }
  return inside ? 0.0 : best;
}

// Distance from a point in the prism's local coordinates to the prism.
double local_point_distance(const Eigen::Vector3d& x, const ConvexPrism& prism,
                            double orientation) {
  const double dxy = section_distance(x.head<2>(), prism, orientation);
  const double dz = std::max({0.0, prism.z_min - x.z(), x.z() - prism.z_max});
  return std::hypot(dxy, dz);
}

// A ball (local coordinates) holding the prism.
void bounding_ball(const ConvexPrism& prism, Eigen::Vector3d& centre, double& radius) {
  Eigen::Vector2d c = Eigen::Vector2d::Zero();
  double r = prism.radius;
  if (!prism.polygon.empty()) {
    for (const auto& v : prism.polygon) c += v;
    c /= static_cast<double>(prism.polygon.size());
    r = 0.0;
    for (const auto& v : prism.polygon) r = std::max(r, (v - c).norm());
  }
  const double half = 0.5 * (prism.z_max - prism.z_min);
  centre = Eigen::Vector3d(c.x(), c.y(), prism.z_min + half);
  radius = std::hypot(r, half);
}

// A solid prepared once per call: its prism, what its distance needs, and a ball holding it.
struct Solid {
  const ConvexPrism* prism = nullptr;
  double orientation = 1.0;  // sign of the polygon's area
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  double radius = 0.0;  // the ball (local coordinates)
};

Solid prepare(const ConvexPrism& prism) {
  Solid s;
  s.prism = &prism;
  s.orientation = prism.polygon.empty() || twice_area(prism.polygon) > 0.0 ? 1.0 : -1.0;
  bounding_ball(prism, s.centre, s.radius);
  return s;
}

// Distance from the segment [la, lb] (local coordinates) to the prism: golden-section search of
// the convex distance along it on [0, 1]; 48 steps leave 0.618^48 < 1e-9.
double local_segment_distance(const Eigen::Vector3d& la, const Eigen::Vector3d& lb,
                              const Solid& solid) {
  const Eigen::Vector3d d = lb - la;
  auto f = [&](double s) {
    return local_point_distance(la + s * d, *solid.prism, solid.orientation);
  };
  const double g = 0.5 * (std::sqrt(5.0) - 1.0);
  double lo = 0.0, hi = 1.0;
  double x1 = hi - g * (hi - lo), x2 = lo + g * (hi - lo);
  double f1 = f(x1), f2 = f(x2);
  for (int it = 0; it < 48 && f1 > 0.0 && f2 > 0.0; ++it) {
    if (f1 <= f2) {
      hi = x2;
      x2 = x1;
      f2 = f1;
      x1 = hi - g * (hi - lo);
      f1 = f(x1);
    } else {
      lo = x1;
      x1 = x2;
      f1 = f2;
      x2 = lo + g * (hi - lo);
      f2 = f(x2);
    }
  }
  return std::min({f1, f2, f(0.0), f(1.0)});
}

// A lower bound of the distance from the segment [la, lb] (local coordinates) to the prism: the
// larger of the distance to the slab z in [z_min, z_max] and the distance to the ball holding it.
double distance_lower_bound(const Eigen::Vector3d& la, const Eigen::Vector3d& lb,
                            const Solid& solid) {
  const ConvexPrism& prism = *solid.prism;
  const double slab = std::max(
      {0.0, prism.z_min - std::max(la.z(), lb.z()), std::min(la.z(), lb.z()) - prism.z_max});
  const Eigen::Vector3d& centre = solid.centre;
  const double radius = solid.radius;
  const Eigen::Vector3d d = lb - la;
  const double dd = d.squaredNorm();
  const double t = dd > 0.0 ? std::clamp((centre - la).dot(d) / dd, 0.0, 1.0) : 0.0;
  return std::max(slab, (la + t * d - centre).norm() - radius);
}

// The three solids with their codes, which leg bodies they see and whether they move with the
// platform.
struct Placed {
  const ConvexPrism* prism;
  int code;
  bool on_platform;  // parent frame: the platform (else the base)
};

template <class Visit>
void for_each_pair(std::span<const Capsule> legs, const MachineBodies& bodies,
                   const Eigen::Matrix3d& R, const Eigen::Vector3d& origin, Visit&& visit) {
  const ConvexPrism tool = bodies.tool.present() ? bodies.tool.prism() : ConvexPrism{};
  const Placed solids[3] = {{&bodies.platform, kPlatformBody, true},
                            {&bodies.base, kBaseBody, false},
                            {&tool, kToolBody, true}};
  for (const Placed& placed : solids) {
    const ConvexPrism& prism = *placed.prism;
    if (!prism.present()) continue;
    const Solid solid = prepare(prism);
    // Base frame to the prism's local coordinates: x_local = A^T (x - o).
    const Eigen::Matrix3d A = placed.on_platform ? Eigen::Matrix3d(R * prism.axes) : prism.axes;
    const Eigen::Vector3d o =
        placed.on_platform ? Eigen::Vector3d(origin + R * prism.origin) : prism.origin;
    for (const Capsule& leg : legs) {
      if (placed.code == kPlatformBody && leg.on_platform) continue;
      if (placed.code == kBaseBody && leg.on_base) continue;
      const Eigen::Vector3d la = A.transpose() * (leg.a - o);
      const Eigen::Vector3d lb = A.transpose() * (leg.b - o);
      if (!visit(leg, la, lb, solid, placed.code)) return;
    }
  }
}

}  // namespace

ConvexPrism cylinder_prism(const Eigen::Vector3d& from, const Eigen::Vector3d& to, double radius) {
  ConvexPrism p;
  p.radius = radius;
  const Eigen::Vector3d axis = to - from;
  const double length = axis.norm();
  if (!(length > 0.0)) return p;  // not present
  const Eigen::Vector3d z = axis / length;
  // Any x orthogonal to z (a disc does not depend on it).
  const Eigen::Vector3d helper =
      std::abs(z.x()) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
  const Eigen::Vector3d x = (helper - helper.dot(z) * z).normalized();
  p.axes.col(0) = x;
  p.axes.col(1) = z.cross(x);
  p.axes.col(2) = z;
  p.origin = from;
  p.z_min = 0.0;
  p.z_max = length;
  return p;
}

void check_machine_bodies(const MachineBodies& bodies) {
  const std::pair<const ConvexPrism*, const char*> solids[] = {
      {&bodies.platform, "bodies.platform"}, {&bodies.base, "bodies.base"}};
  for (const auto& [p, key] : solids) {
    const std::string k(key);
    require(std::isfinite(p->z_min) && std::isfinite(p->z_max),
            k + ".z must be two finite numbers");
    const bool any = p->radius != 0.0 || !p->polygon.empty() || p->z_max != p->z_min;
    if (!any) continue;
    require(p->z_max > p->z_min, k + ".z must be [z_min, z_max] with z_min < z_max (m)");
    require((p->radius != 0.0) != !p->polygon.empty(),
            k + ": give either radius (a disc) or polygon, one of them");
    if (p->polygon.empty()) {
      require(std::isfinite(p->radius) && p->radius > 0.0,
              k + ".radius must be a finite number > 0 (m)");
      continue;
    }
    const auto& poly = p->polygon;
    require(poly.size() >= 3, k + ".polygon must have at least 3 vertices [x, y]");
    for (const auto& v : poly)
      require(v.allFinite(), k + ".polygon: every vertex must be two finite numbers (m)");
    const double area2 = twice_area(poly);
    require(std::abs(area2) > 0.0, k + ".polygon must enclose a non-zero area");
    const double sign = area2 > 0.0 ? 1.0 : -1.0;
    for (std::size_t i = 0; i < poly.size(); ++i) {
      const Eigen::Vector2d& u = poly[i];
      const Eigen::Vector2d& v = poly[(i + 1) % poly.size()];
      const Eigen::Vector2d& w = poly[(i + 2) % poly.size()];
      require((v - u).squaredNorm() > 0.0, k + ".polygon has two equal consecutive vertices");
      require(sign * cross2(v - u, w - v) >= 0.0,
              k + ".polygon must be convex, its vertices in order around it (vertex " +
                  std::to_string((i + 1) % poly.size() + 1) + " turns the other way)");
    }
    // Turning one way at every vertex, a star still winds round more than once: every vertex
    // must lie on the inner side of every edge.
    for (std::size_t i = 0; i < poly.size(); ++i)
      for (const Eigen::Vector2d& w : poly) {
        const Eigen::Vector2d& u = poly[i];
        const Eigen::Vector2d e = poly[(i + 1) % poly.size()] - u;
        require(sign * cross2(e, w - u) >= -1e-12 * e.norm() * (w - u).norm(),
                k + ".polygon must be convex and wind round once (a star or a polygon that "
                    "crosses itself is not), its vertices in order around it");
      }
  }
  const ToolBody& t = bodies.tool;
  require(std::isfinite(t.diameter) && t.diameter >= 0.0,
          "bodies.tool.diameter must be a finite number > 0 (m)");
  if (t.present())
    require(t.from.allFinite() && t.to.allFinite() && (t.to - t.from).norm() > 0.0,
            "bodies.tool: 'from' and 'to' must be two different finite points (m)");
}

void check_solids_have_leg_bodies(const MachineBodies& bodies, bool base_side_bodies,
                                  bool platform_side_bodies, const std::string& shape_keys) {
  require(!bodies.platform.present() || base_side_bodies,
          "bodies.platform is checked against the leg bodies on the base side, and these legs "
          "have none (" +
              shape_keys + ")");
  require(!bodies.base.present() || platform_side_bodies,
          "bodies.base is checked against the leg bodies on the platform side, and these legs "
          "have none (" +
              shape_keys + ")");
}

void check_hexapod_bodies(const LegShape& shape, const MachineBodies& bodies) {
  check_machine_bodies(bodies);
  require(!bodies.present() || shape.present(),
          "bodies are checked against the legs: give the legs' shape (legs.diameter, or "
          "legs.cylinder and legs.rod)");
  check_solids_have_leg_bodies(bodies, shape.two_bodies(), shape.rod_diameter > 0.0,
                               "a one-capsule leg (legs.diameter) is jointed to both plates: give "
                               "legs.cylinder and legs.rod");
}

double segment_prism_distance(const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                              const ConvexPrism& prism) {
  return local_segment_distance(prism.axes.transpose() * (a - prism.origin),
                                prism.axes.transpose() * (b - prism.origin), prepare(prism));
}

void body_clearance(std::span<const Capsule> legs, const MachineBodies& bodies,
                    const Eigen::Matrix3d& R, const Eigen::Vector3d& origin, Clearance& best) {
  for_each_pair(legs, bodies, R, origin,
                [&](const Capsule& leg, const Eigen::Vector3d& la, const Eigen::Vector3d& lb,
                    const Solid& solid, int code) {
                  // Pairs that cannot beat the best so far skip the exact distance.
                  if (distance_lower_bound(la, lb, solid) - leg.radius >= best.value) return true;
                  const double gap = local_segment_distance(la, lb, solid) - leg.radius;
                  if (gap < best.value) best = {gap, leg.leg, code};
                  return true;
                });
}

bool bodies_apart(std::span<const Capsule> legs, const MachineBodies& bodies,
                  const Eigen::Matrix3d& R, const Eigen::Vector3d& origin, double min_clearance) {
  bool apart = true;
  for_each_pair(legs, bodies, R, origin,
                [&](const Capsule& leg, const Eigen::Vector3d& la, const Eigen::Vector3d& lb,
                    const Solid& solid, int) {
                  if (distance_lower_bound(la, lb, solid) - leg.radius >= min_clearance)
                    return true;
                  if (local_segment_distance(la, lb, solid) - leg.radius < min_clearance)
                    apart = false;
                  return apart;
                });
  return apart;
}

}  // namespace pkmopt
