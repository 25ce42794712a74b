#pragma once
// Bounding spheres, traditional algebra (§2.4.1): the SphereOps policy
// that core/collision/bounding_volume.hpp (exhaustive search, Welzl), core/collision/broadphase.hpp
// (sort and sweep) and core/collision/tree_broadphase.hpp (the sphere tree) run on. A
// sphere is a centre and a radius (4 numbers; §2.4.1 notes the dual sphere's
// 5). Twin: cga/bounding_volume.hpp,
// with the same names in the same order: put them side by side and only the
// algebra differs.
#include "core/collision/bounding_volume.hpp"
#include "traditional/geometry.hpp"

#include <optional>

namespace gacompare::traditional {

struct SphereOps {
  using Sphere = traditional::Sphere;
  using Point = Vec3;
  static constexpr const char* name = "traditional";

  static Point point(const Vec3& x) { return x; }
  static Sphere sphere(const Vec3& centre, double radius) { return traditional::sphere(centre, radius); }

  // §2.4.1 fig. 6a: centred midway, radius half the distance.
  static Sphere sphere_2(const Point& a, const Point& b) { return {0.5 * (a + b), 0.5 * (b - a).norm()}; }

  // §2.4.1 fig. 6b: the circumcircle's centre and radius (traditional::circumcircle:
  // the cross-product closed form relative to a, not the report's eq. 38).
  static std::optional<Sphere> sphere_3(const Point& a, const Point& b, const Point& c) {
    const CircleResult k = circumcircle(a, b, c);
    if (k.kind != Kind::circle) return std::nullopt;  // collinear or coincident
    return Sphere{k.centre, k.radius};
  }

  // §2.4.1 fig. 6c: the circumsphere (traditional::sphere_through: Cramer's rule
  // with cross products relative to a, where the report inverts a 3×3 matrix).
  static std::optional<Sphere> sphere_4(const Point& a, const Point& b, const Point& c, const Point& d) {
    const SphereResult s = sphere_through(a, b, c, d);
    if (s.kind != Kind::sphere) return std::nullopt;  // coplanar
    return Sphere{s.centre, s.radius};
  }

  // Inside or on, by the distance: side(s, x) = ½(|x − c|² − ρ²) ≤ tol, the
  // report's sign convention (negative inside, traditional/geometry.hpp).
  static bool contains(const Sphere& s, const Point& x, double tol) { return side(s, x) <= tol; }

  // The distance test |c1 − c2| ≤ ρ1 + ρ2, squared (no root). Touching overlaps;
  // nested spheres overlap (their balls do, though their surfaces do not meet).
  static bool overlap(const Sphere& s1, const Sphere& s2) { return balls_overlap(s1, s1.radius, s2, s2.radius); }
  // The same with the radii given (those the spheres were built with), as
  // the broadphase asks it of either algebra.
  static bool balls_overlap(const Sphere& s1, double r1, const Sphere& s2, double r2) {
    const double r = r1 + r2;
    return (s2.centre - s1.centre).squaredNorm() <= r * r;
  }

  // The sphere trees' node operations (§4.2.2; core/collision/tree_broadphase.hpp).
  // The smallest sphere enclosing two spheres: one of them when it holds the
  // other, else centred on the line of centres, R = ½(d + ρ1 + ρ2), its
  // surface touching both far sides.
  static Sphere enclosing(const Sphere& s1, const Sphere& s2) {
    const Vec3 d = s2.centre - s1.centre;
    const double dist = d.norm();
    if (dist + s2.radius <= s1.radius) return s1;
    if (dist + s1.radius <= s2.radius) return s2;
    const double R = 0.5 * (dist + s1.radius + s2.radius);
    return {s1.centre + d * ((R - s1.radius) / dist), R};
  }
  // The outer ball holds the inner one: d ≤ ρo − ρi, squared (no root).
  static bool encloses(const Sphere& outer, const Sphere& inner) {
    const double room = outer.radius - inner.radius;
    return room >= 0 && (inner.centre - outer.centre).squaredNorm() <= room * room;
  }
  // The same centre, the radius larger by `by`.
  static Sphere grown(const Sphere& s, double by) { return {s.centre, s.radius + by}; }
  // ρ², the tree's cost (proportional to the surface area).
  static double radius_squared(const Sphere& s) { return s.radius * s.radius; }

  static Vec3 centre(const Sphere& s) { return traditional::centre(s); }
  static double radius(const Sphere& s) { return traditional::radius(s); }
};

}  // namespace gacompare::traditional
