#pragma once
// Reflection in an entity by sandwiching (§1.7 eq. 20): c' = M c M. Twin:
// traditional/geometry.hpp (same names).
//
// The sandwich is computed as one product kept to grade 1 (the other grades of
// M c M cancel identically, so the compile-time Keep skips them). The scale and
// sign of M c M do not matter: the extraction divides by the weight −c'·n.
// Defaults are the cheapest form of the same algebra (a vector sandwich expanded
// by the product's definition, the nearest point on a line as a meet); the
// literal sandwiches stay as *_by_sandwich / *_by_reflection, tested against the
// defaults and timed beside them.
#include "cga/geometry/meet.hpp"

namespace gacompare::cga {

// The sandwich M X M kept to a vector, for any blade M (a dual plane or sphere is
// a vector, a line a trivector).
template <BladeSet S>
Vector5 reflect(const Multivector<Cl41, S>& m, const ConformalPoint& x) {
  return product<Product::geometric, Vector5::blades>(m * x, m);
}

// The same sandwich for a vector m, expanded by the definition of the geometric
// product: m X m = 2(m·X) m − m² X. Ten multiplications instead of the ~75 of
// the two general products; the result is identical in exact arithmetic. (The
// benchmark times both: BM_reflect_in_plane/cga_sandwich.)
inline Vector5 reflect_by_vector(const Vector5& m, const ConformalPoint& x) {
  return (2 * scalar_product(m, x)) * m - scalar_product(m, m) * x;
}

// In a plane π X π: the mirror image.
inline Vec3 reflect_in_plane(const Vec3& x, const DualPlane& p) {
  return *detail::point_of(reflect_by_vector(p, up(x)));
}

// In a sphere S X S: inversion, x' = c + ρ²(x − c)/|x − c|². The centre maps to
// n, the point at infinity (weight 0): Kind::none, as the twin, when
// |x − c|² = ρ² − 2 X·S is within kRelTol²·ρ².
inline PointResult reflect_in_sphere(const Vec3& x, const DualSphere& s) {
  const ConformalPoint X = up(x);
  const double r2 = scalar_product(s, s);
  const double w2 = r2 - 2 * scalar_product(X, s);
  if (!(w2 > kRelTol * kRelTol * r2)) return {Kind::none};
  const auto y = detail::point_of(reflect_by_vector(s, X));
  if (!y) return {Kind::none};
  return {Kind::point, *y};
}

// In a line L X L (§1.7): the half-turn about the line. The report's form,
// two trivector products; reflect_in_line below is the same point for ~1/10 of
// the cost (benchmarked side by side: BM_reflect_in_line/cga_sandwich).
inline Vec3 reflect_in_line_by_sandwich(const Vec3& x, const Line& l) {
  return *detail::point_of(reflect(l, up(x)));
}
// §1.7: the nearest point on a line is the midpoint of x and its reflection.
inline Vec3 nearest_on_line_by_reflection(const Vec3& x, const Line& l) {
  return 0.5 * (x + reflect_in_line_by_sandwich(x, l));
}

// The nearest point as a meet (the default: docs/architecture.md "best form of the same
// class of algorithm"): the line meets the plane through x normal to it,
// π = u + (u·x) n (u the direction, L's e_i e ē part), in the flat point π⌋L
// (§2.4.4). One vector–trivector contraction instead of the two trivector
// products of L X L, and linear in L (no weight of order |u|² to divide by).
inline Vec3 nearest_on_line(const Vec3& x, const Line& l) {
  const Vec3 u(l[blade::e1eebar], l[blade::e2eebar], l[blade::e3eebar]);
  const double d = u.dot(x);
  const DualPlane p = vector5(u.x(), u.y(), u.z(), d, d);
  return detail::flat_point(p | l);
}
// The half-turn about the line: x' = 2 f − x with f the nearest point.
inline Vec3 reflect_in_line(const Vec3& x, const Line& l) {
  const Vec3 f = nearest_on_line(x, l);
  return {2 * f.x() - x.x(), 2 * f.y() - x.y(), 2 * f.z() - x.z()};
}

// The report's sandwich forms of the vector reflections, for the benchmark.
inline Vec3 reflect_in_plane_by_sandwich(const Vec3& x, const DualPlane& p) {
  return *detail::point_of(reflect(p, up(x)));
}

}  // namespace gacompare::cga
