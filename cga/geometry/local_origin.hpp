#pragma once
// The precision remedy: build conformal entities relative to a local origin near
// the bodies, and move the Euclidean answers back.
//
// Why: up(x) carries ½x² on e and ē next to x on e1 e2 e3. Far from the origin
// the products of the meet and the sandwiches subtract terms of size |x|²·(…)
// to leave answers of the size of the feature, so about log10(|x|²/ℓ²) digits
// are lost for features of size ℓ (measured by bench/geometry_precision: at
// |x| = 1e6 and ℓ = 1 the conformal answers keep only a few digits; the
// traditional ones, which work with differences, lose log10(|x|/ℓ)).
// Translating the inputs in Euclidean coordinates first (x − o: exact when x is
// near o, by Sterbenz) and the outputs back (y + o) keeps the squares of size ℓ².
// The collision code picks o per pair of bodies (e.g. one body's centre).
//
// The entities carry no memory of the origin they were built in: mixing entities
// of different LocalOrigins in one meet is a bug the types cannot catch, so the
// operations below take Euclidean inputs and do the whole round trip.
#include "cga/geometry/inside.hpp"
#include "cga/geometry/meet.hpp"
#include "cga/geometry/reflect.hpp"

namespace gacompare::cga {

struct LocalOrigin {
  Vec3 origin = Vec3::Zero();

  // Into the local frame.
  Vec3 local(const Vec3& x) const { return x - origin; }
  ConformalPoint point(const Vec3& x) const { return up(local(x)); }
  DualSphere sphere(const Vec3& centre, double radius) const { return cga::sphere(local(centre), radius); }
  // {n̂·x = d} becomes {n̂·x' = d − n̂·o}.
  DualPlane plane(const Vec3& normal, double offset) const {
    const Vec3 u = normal.normalized();
    return cga::plane(u, offset / normal.norm() - u.dot(origin));
  }
  std::optional<Line> line_through(const Vec3& a, const Vec3& b) const {
    return cga::line_through(local(a), local(b));
  }

  // Back to the world frame.
  Vec3 world(const Vec3& x) const { return x + origin; }
  PointResult world(PointResult r) const {
    if (r.kind == Kind::point || r.kind == Kind::tangent) r.point = world(r.point);
    return r;
  }
  PairResult world(PairResult r) const {
    if (r.kind == Kind::point_pair || r.kind == Kind::tangent) {
      r.first = world(r.first);
      r.second = world(r.second);
    }
    return r;
  }
  CircleResult world(CircleResult r) const {
    if (r.kind == Kind::circle || r.kind == Kind::tangent) r.centre = world(r.centre);
    return r;
  }
  SphereResult world(SphereResult r) const {
    if (r.kind == Kind::sphere) r.centre = world(r.centre);
    return r;
  }
  // A line's reference point is the one nearest the origin: re-project for the
  // world origin.
  LineResult world(LineResult r) const {
    if (r.kind == Kind::line) {
      const Vec3 p = world(r.point);
      r.point = p - p.dot(r.direction) * r.direction;
    }
    return r;
  }
};

// Each operation in a local origin at its first input (the remedy as the
// collision code uses it). Same names, in namespace local.
namespace local {

inline CircleResult circumcircle(const Vec3& a, const Vec3& b, const Vec3& c) {
  const LocalOrigin o{a};
  return o.world(cga::circumcircle(o.local(a), o.local(b), o.local(c)));
}
inline SphereResult sphere_through(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  const LocalOrigin o{a};
  return o.world(cga::sphere_through(o.local(a), o.local(b), o.local(c), o.local(d)));
}
inline CircleResult meet_sphere_sphere(const Vec3& c1, double r1, const Vec3& c2, double r2) {
  const LocalOrigin o{c1};
  return o.world(cga::meet_sphere_sphere(o.sphere(c1, r1), o.sphere(c2, r2)));
}
inline CircleResult meet_sphere_plane(const Vec3& c, double r, const Vec3& normal, double offset) {
  const LocalOrigin o{c};
  return o.world(cga::meet_sphere_plane(o.sphere(c, r), o.plane(normal, offset)));
}
inline PointResult meet_line_plane(const Vec3& a, const Vec3& b, const Vec3& normal, double offset) {
  const LocalOrigin o{a};
  const auto l = o.line_through(a, b);
  if (!l) return {Kind::degenerate};
  return o.world(cga::meet_line_plane(*l, o.plane(normal, offset)));
}
inline PairResult meet_line_sphere(const Vec3& a, const Vec3& b, const Vec3& c, double r) {
  const LocalOrigin o{a};
  const auto l = o.line_through(a, b);
  if (!l) return {Kind::degenerate};
  return o.world(cga::meet_line_sphere(*l, o.sphere(c, r)));
}
// Two planes have no point of their own: the origin is a point of the first
// plane nearest the given hint (typically the bodies' position).
inline LineResult meet_plane_plane(const Vec3& n1, double d1, const Vec3& n2, double d2, const Vec3& hint) {
  const Vec3 u1 = n1.normalized();
  const LocalOrigin o{hint - (u1.dot(hint) - d1 / n1.norm()) * u1};
  return o.world(cga::meet_plane_plane(o.plane(n1, d1), o.plane(n2, d2)));
}
inline Vec3 reflect_in_plane(const Vec3& x, const Vec3& normal, double offset) {
  const LocalOrigin o{x};
  return o.world(cga::reflect_in_plane(o.local(x), o.plane(normal, offset)));
}
inline PointResult reflect_in_sphere(const Vec3& x, const Vec3& c, double r) {
  const LocalOrigin o{c};
  return o.world(cga::reflect_in_sphere(o.local(x), o.sphere(c, r)));
}
inline Vec3 reflect_in_line(const Vec3& x, const Vec3& a, const Vec3& b) {
  const LocalOrigin o{a};
  return o.world(cga::reflect_in_line(o.local(x), *o.line_through(a, b)));
}
inline Vec3 nearest_on_line(const Vec3& x, const Vec3& a, const Vec3& b) {
  const LocalOrigin o{a};
  return o.world(cga::nearest_on_line(o.local(x), *o.line_through(a, b)));
}
inline double side(const Vec3& c, double r, const Vec3& x) {
  const LocalOrigin o{c};
  return cga::side(o.sphere(c, r), o.local(x));
}

}  // namespace local
}  // namespace gacompare::cga
