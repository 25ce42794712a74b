#pragma once
// Bounding spheres in plane-based GA (§2.4.1's spheres): the SphereOps policy
// that core/collision/bounding_volume.hpp (exhaustive search, Welzl),
// core/collision/broadphase.hpp and core/collision/tree_broadphase.hpp run on.
// PGA has no round primitive, so a sphere is its centre point (weight 1) and
// radius, as in the matrix backend; what PGA brings is how centres are found:
// as the meet of planes.
//   - The bisector of A and B is the plane through their midpoint orthogonal
//     to their join: (A + B)·(A ∨ B), a point's inner product with a line.
//   - A circle's centre (sphere_3) is the meet of the triangle's plane
//     A ∨ B ∨ C and two bisectors; a circumsphere's (sphere_4) the meet of
//     three bisectors: one outer product of three planes, a point whose weight
//     vanishes exactly when the points are collinear or coplanar.
// Twins: traditional/bounding_volume.hpp, cga/bounding_volume.hpp, with the
// same names in the same order.
#include "pga/narrowphase.hpp"
#include "core/collision/bounding_volume.hpp"
#include "core/geometry.hpp"

#include <algorithm>
#include <cmath>
#include <optional>

namespace gacompare::pga {

struct SphereOps {
  using Sphere = NarrowAlgebra::Sphere;
  using Point = pga::Point;
  static constexpr const char* name = "pga";

  static Point point(const Vec3& x) { return pga::point(x); }
  static Sphere sphere(const Vec3& centre, double radius) { return {pga::point(centre), radius}; }

  // |b − a|², the squared length of the join's direction (weight-1 points).
  static double distance2(const Point& a, const Point& b) { return NarrowAlgebra::distance2(a, b); }
  // The plane bisecting A and B: (A + B)·(A ∨ B), any weight.
  static Plane bisector(const Point& a, const Point& b) {
    return cga::widen<Plane::blades>(cga::inner(a + b, join(a, b)));
  }
  // The meet of three planes as a sphere through `through`; nullopt when the
  // meet is (nearly) ideal: the predicate of the twins, |weight| against
  // kSinTol times the size the weight has when the points are well apart.
  static std::optional<Sphere> centred(const Point& meet, double scale, const Point& through) {
    const double w = weight(meet);
    if (!(std::abs(w) > geometry::kSinTol * scale) || !std::isfinite(w)) return std::nullopt;
    const Point c = meet / w;
    return Sphere{c, std::sqrt(distance2(c, through))};
  }

  // §2.4.1 fig. 6a: the midpoint, (A + B)/2, and half the distance.
  static Sphere sphere_2(const Point& a, const Point& b) { return {(a + b) * 0.5, 0.5 * std::sqrt(distance2(a, b))}; }

  // §2.4.1 fig. 6b: the meet of the triangle's plane and two bisectors. The
  // meet's weight is |(b−a)×(c−a)|² |b−a|²|c−a|²-sized (each bisector's
  // normal is twice the side; the plane's is the cross product): collinear when
  // |(b−a)×(c−a)| ≤ kSinTol |b−a||c−a|, the twin's predicate.
  static std::optional<Sphere> sphere_3(const Point& a, const Point& b, const Point& c) {
    const Plane tri = join(join(a, b), c);
    const double cross = normal(tri).norm(), ab = std::sqrt(distance2(a, b)), ac = std::sqrt(distance2(a, c));
    if (!(cross > geometry::kSinTol * ab * ac)) return std::nullopt;
    return centred((tri ^ bisector(a, b)) ^ bisector(a, c), 0.0, a);
  }

  // §2.4.1 fig. 6c: the meet of three bisectors. Coplanar when the volume
  // |(b−a)·((c−a)×(d−a))| ≤ kSinTol |b−a||c−a||d−a| (the twin's predicate),
  // read off the meet's weight, which is 8 times that volume.
  static std::optional<Sphere> sphere_4(const Point& a, const Point& b, const Point& c, const Point& d) {
    const Point meet = (bisector(a, b) ^ bisector(a, c)) ^ bisector(a, d);
    const double scale = 8 * std::sqrt(distance2(a, b) * distance2(a, c) * distance2(a, d));
    return centred(meet, scale, a);
  }

  // side(s, x) = ½(|x − c|² − ρ²) ≤ tol, the report's sign convention.
  static bool contains(const Sphere& s, const Point& x, double tol) {
    return 0.5 * (distance2(s.centre, x) - s.radius * s.radius) <= tol;
  }
  // |c1 − c2| ≤ ρ1 + ρ2, squared: touching and nested overlap.
  static bool overlap(const Sphere& s1, const Sphere& s2) { return balls_overlap(s1, s1.radius, s2, s2.radius); }
  // The same with the radii given (those the spheres were built with), as
  // the broadphase asks it of every algebra.
  static bool balls_overlap(const Sphere& s1, double r1, const Sphere& s2, double r2) {
    const double r = r1 + r2;
    return distance2(s1.centre, s2.centre) <= r * r;
  }

  // The sphere trees' node operations (§4.2.2; core/collision/tree_broadphase.hpp).
  // The smallest sphere enclosing two: one of them when it holds the other,
  // else centred at the affine combination (1 − t)C1 + t C2 of the two centre
  // points (weight 1 stays 1), R = ½(d + ρ1 + ρ2).
  static Sphere enclosing(const Sphere& s1, const Sphere& s2) {
    const double dist = std::sqrt(distance2(s1.centre, s2.centre));
    if (dist + s2.radius <= s1.radius) return s1;
    if (dist + s1.radius <= s2.radius) return s2;
    const double R = 0.5 * (dist + s1.radius + s2.radius), t = (R - s1.radius) / dist;
    return {s1.centre * (1 - t) + s2.centre * t, R};
  }
  static bool encloses(const Sphere& outer, const Sphere& inner) {
    const double room = outer.radius - inner.radius;
    return room >= 0 && distance2(inner.centre, outer.centre) <= room * room;
  }
  static Sphere grown(const Sphere& s, double by) { return {s.centre, s.radius + by}; }
  static double radius_squared(const Sphere& s) { return s.radius * s.radius; }

  static Vec3 centre(const Sphere& s) { return euclid(s.centre); }
  static double radius(const Sphere& s) { return s.radius; }
};

}  // namespace gacompare::pga
