#pragma once
// The traditional twins of cga/geometry: the same operations, the
// same function names and the same Euclidean result types, with vectors, dot and
// cross products (Eigen). Put this file beside cga/geometry/*.hpp: only the
// algebra differs.
//
// The result types and the degeneracy thresholds are shared with the cga
// backend: core/geometry.hpp.
#include "core/geometry.hpp"

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <optional>

namespace gacompare::traditional {

using geometry::CircleResult;
using geometry::Kind;
using geometry::kRelTol;
using geometry::kSinTol;
using geometry::kTangentTol;
using geometry::LineResult;
using geometry::PairResult;
using geometry::PointResult;
using geometry::SphereResult;
using Vec3 = Eigen::Vector3d;

struct Sphere {
  Vec3 centre;
  double radius;
};
struct Plane {  // {x : normal·x = offset}, normal of unit length
  Vec3 normal;
  double offset;
};
struct Line {  // point + t·direction; direction not normalised (b − a)
  Vec3 point;
  Vec3 direction;
};

// ---- construction and extraction (the twins of cga/geometry/entities.hpp) ----

inline Sphere sphere(const Vec3& centre, double radius) { return {centre, radius}; }
// The normal must be nonzero: a zero normal is a caller's bug, not a degenerate
// configuration (no typed result can describe "no plane was given").
inline Plane plane(const Vec3& normal, double offset) {
  const double k = normal.norm();
  return {normal / k, offset / k};
}
inline std::optional<Line> line_through(const Vec3& a, const Vec3& b) {
  const Vec3 u = b - a;
  if (!(u.norm() > kRelTol * std::max(a.norm(), b.norm()))) return std::nullopt;  // coincident
  return Line{a, u};
}
// Normal (b − a)×(c − a) / |…| (counter-clockwise seen from the normal's side).
inline std::optional<Plane> plane_through(const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 u = b - a, v = c - a, w = u.cross(v);
  const double k = w.norm();
  if (!(k > kSinTol * u.norm() * v.norm())) return std::nullopt;  // collinear or coincident
  const Vec3 nrm = w / k;
  return Plane{nrm, nrm.dot(a)};
}
inline Vec3 centre(const Sphere& s) { return s.centre; }
inline double radius(const Sphere& s) { return s.radius; }
inline Vec3 normal(const Plane& p) { return p.normal; }
inline double offset(const Plane& p) { return p.offset; }
inline Vec3 direction(const Line& l) { return l.direction.normalized(); }
// The line's point nearest the origin.
inline Vec3 point_on(const Line& l) {
  return l.point - (l.point.dot(l.direction) / l.direction.squaredNorm()) * l.direction;
}

// ---- circumcircle, sphere through 4 points (§2.4.1) ----

// §2.4.1 eq. 38 first maps the points into 2D plane coordinates and then works
// with x² + y² of absolute coordinates: it needs a frame, and squares of large
// coordinates cancel catastrophically away from the origin. Better: everything
// relative to a, in 3D, with the cross-product closed form
//   c = a + ((|u|² v − |v|² u) × (u × v)) / (2 |u × v|²),  u = b − a, v = c − a,
// whose only cancellation is in u × v itself (sin of the angle at a).
// Normal: (u × v)/|u × v|, the right-handed normal of a, b, c.
inline CircleResult circumcircle(const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 u = b - a, v = c - a, w = u.cross(v);
  const double w2 = w.squaredNorm();
  if (!(w2 > kSinTol * kSinTol * u.squaredNorm() * v.squaredNorm())) return {Kind::degenerate};
  const Vec3 off = (u.squaredNorm() * v - v.squaredNorm() * u).cross(w) / (2 * w2);
  return {Kind::circle, a + off, off.norm(), w / std::sqrt(w2)};
}

// The 3×3 system 2 (p_i − a)·x = |p_i − a|² solved by Cramer's rule with cross
// products, relative to a for the same reason as above (the report, §2.4.1, only
// mentions "inversion of a 3×3 matrix"; we never form it).
inline SphereResult sphere_through(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  const Vec3 u = b - a, v = c - a, w = d - a;
  const Vec3 vw = v.cross(w), wu = w.cross(u), uv = u.cross(v);
  const double vol = u.dot(vw);
  if (!(std::abs(vol) > kSinTol * u.norm() * v.norm() * w.norm())) return {Kind::degenerate};  // coplanar
  const Vec3 off = (u.squaredNorm() * vw + v.squaredNorm() * wu + w.squaredNorm() * uv) / (2 * vol);
  return {Kind::sphere, a + off, off.norm()};
}

// ---- intersections (the twins of cga/geometry/meet.hpp, §1.6) ----

// Two spheres: the circle lies in the plane ⊥ (c2 − c1) at a = (d² + ρ1² − ρ2²)/2d
// from c1 with radius r, where 4d²r² = 16·area² of the triangle (ρ1, ρ2, d) in
// Heron's factored form: no cancellation near tangency (ρ1² − a² would lose it).
// Tangency when sin² = (r d/(ρ1ρ2))², the squared sine of the angle between the
// surfaces, is within kTangentTol. Normal: (c2 − c1)/d.
inline CircleResult meet_sphere_sphere(const Sphere& s1, const Sphere& s2) {
  const double r1 = s1.radius, r2 = s2.radius;
  if (!(r1 > 0 && r2 > 0)) return {Kind::degenerate};
  const Vec3 dc = s2.centre - s1.centre;
  const double d = dc.norm();
  const double heron = (d + r1 + r2) * (r1 + r2 - d) * (d - r1 + r2) * (d + r1 - r2);  // 4 d² r²
  const double sin2 = heron / (4 * r1 * r1 * r2 * r2);
  // Concentric (d at rounding level of the inputs): the same sphere when the
  // radii agree (then sin2 ≈ −(ρ1−ρ2)²/ρ², tiny), else nested without contact.
  const double scale2 = s1.centre.squaredNorm() + s2.centre.squaredNorm() + r1 * r1 + r2 * r2;
  if (d * d <= kRelTol * kRelTol * scale2)
    return {std::abs(sin2) <= kRelTol * kRelTol ? Kind::contained : Kind::none};
  const Vec3 un = dc / d;
  const double a = (d * d + (r1 - r2) * (r1 + r2)) / (2 * d);
  const Vec3 foot = s1.centre + a * un;
  if (std::abs(sin2) <= kTangentTol) return {Kind::tangent, foot, 0.0, un};
  if (sin2 < 0) return {Kind::none};
  return {Kind::circle, foot, std::sqrt(heron) / (2 * d), un};
}

// Sphere and plane: the centre's signed height h above the plane; r² = (ρ−h)(ρ+h).
// Normal: the plane's.
inline CircleResult meet_sphere_plane(const Sphere& s, const Plane& p) {
  const double r = s.radius;
  if (!(r > 0)) return {Kind::degenerate};
  const double h = p.normal.dot(s.centre) - p.offset;
  const double r2 = (r - h) * (r + h);
  const Vec3 foot = s.centre - h * p.normal;
  if (std::abs(r2) <= kTangentTol * r * r) return {Kind::tangent, foot, 0.0, p.normal};
  if (r2 < 0) return {Kind::none};
  return {Kind::circle, foot, std::sqrt(r2), p.normal};
}

// §2.4.4 eq. 39: r = n·(T0 − L0) / n·(L1 − L0), with the plane as (n, offset).
inline PointResult meet_line_plane(const Line& l, const Plane& p) {
  const double den = p.normal.dot(l.direction);
  const double dist = p.normal.dot(l.point) - p.offset;
  if (std::abs(den) <= kSinTol * l.direction.norm()) {
    // In the plane when the gap is at rounding level of the inputs: the line's
    // point nearest the origin, the plane's offset and the line's length.
    const double scale = point_on(l).norm() + std::abs(p.offset) + l.direction.norm();
    return {std::abs(dist) <= kRelTol * scale ? Kind::contained : Kind::parallel};
  }
  return {Kind::point, l.point - (dist / den) * l.direction};
}

// Line and sphere: foot f of the perpendicular from the centre, half chord
// h² = (ρ − δ)(ρ + δ) with δ = |c − f|; points f ∓ h û (first along the direction).
inline PairResult meet_line_sphere(const Line& l, const Sphere& s) {
  const double r = s.radius;
  if (!(r > 0)) return {Kind::degenerate};
  const double u2 = l.direction.squaredNorm();
  const Vec3 w = l.point - s.centre;
  const Vec3 f = l.point - (w.dot(l.direction) / u2) * l.direction;
  const double dist = (f - s.centre).norm();
  const double h2 = (r - dist) * (r + dist);
  if (std::abs(h2) <= kTangentTol * r * r) return {Kind::tangent, f, f};
  if (h2 < 0) return {Kind::none};
  const Vec3 step = (std::sqrt(h2) / std::sqrt(u2)) * l.direction;
  return {Kind::point_pair, f - step, f + step};
}

// Two planes: direction n1 × n2, point nearest the origin ((d1 n2 − d2 n1) × u)/|u|².
inline LineResult meet_plane_plane(const Plane& p1, const Plane& p2) {
  const Vec3 u = p1.normal.cross(p2.normal);
  const double s = u.norm();
  if (s <= kSinTol) {
    const double gap = p1.offset - std::copysign(1.0, p1.normal.dot(p2.normal)) * p2.offset;
    const double scale = std::abs(p1.offset) + std::abs(p2.offset);
    return {std::abs(gap) <= kRelTol * scale ? Kind::contained : Kind::parallel};
  }
  return {Kind::line, (p1.offset * p2.normal - p2.offset * p1.normal).cross(u) / (s * s), u / s};
}

// ---- reflection (the twins of cga/geometry/reflect.hpp, §1.7) ----

inline Vec3 reflect_in_plane(const Vec3& x, const Plane& p) {
  return x - 2 * (p.normal.dot(x) - p.offset) * p.normal;
}
// Inversion x' = c + ρ² (x − c)/|x − c|²; the centre goes to infinity (Kind::none).
inline PointResult reflect_in_sphere(const Vec3& x, const Sphere& s) {
  const Vec3 w = x - s.centre;
  const double w2 = w.squaredNorm();
  if (!(w2 > kRelTol * kRelTol * s.radius * s.radius)) return {Kind::none};
  return {Kind::point, s.centre + (s.radius * s.radius / w2) * w};
}
inline Vec3 nearest_on_line(const Vec3& x, const Line& l) {
  return l.point + ((x - l.point).dot(l.direction) / l.direction.squaredNorm()) * l.direction;
}
inline Vec3 reflect_in_line(const Vec3& x, const Line& l) { return 2 * nearest_on_line(x, l) - x; }

// ---- inside / outside (the twins of cga/geometry/inside.hpp, §2.4.1) ----

// The report's convention (§2.4.1, last paragraph): negative inside, positive
// outside, zero on the sphere. The value is ½(|x − c|² − ρ²), the same number the
// conformal X·S gives up to the sign.
inline double side(const Sphere& s, const Vec3& x) {
  return 0.5 * ((x - s.centre).squaredNorm() - s.radius * s.radius);
}
inline bool inside(const Sphere& s, const Vec3& x) { return side(s, x) < 0; }
inline bool outside(const Sphere& s, const Vec3& x) { return side(s, x) > 0; }

}  // namespace gacompare::traditional
