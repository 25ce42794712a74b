#pragma once
// Reflection in an entity by sandwiching (§1.7 eq. 20): c' = M c M. Twin:
// traditional/geometry.hpp (same names).
//
// The sandwich is computed as one product kept to grade 1 (the other grades of
// M c M cancel identically, so the compile-time Keep skips them). The scale and
// sign of M c M do not matter: the extraction divides by the weight −c'·n.
#include "cga/geometry/entities.hpp"

namespace gacompare::cga {

// The sandwich M X M kept to a vector, for any blade M (a dual plane or sphere is
// a vector, a line a trivector).
template <BladeSet S>
Vector5 reflect(const Multivector<Cl41, S>& m, const ConformalPoint& x) {
  return product<Product::geometric, Vector5::blades>(m * x, m);
}

// In a plane π X π: the mirror image.
inline Vec3 reflect_in_plane(const Vec3& x, const DualPlane& p) { return *detail::point_of(reflect(p, up(x))); }

// In a sphere S X S: inversion, x' = c + ρ²(x − c)/|x − c|². The centre maps to
// n, the point at infinity (weight 0): Kind::none, as the twin, when
// |x − c|² = ρ² − 2 X·S is within kRelTol²·ρ².
inline PointResult reflect_in_sphere(const Vec3& x, const DualSphere& s) {
  const ConformalPoint X = up(x);
  const double r2 = scalar_product(s, s);
  const double w2 = r2 - 2 * scalar_product(X, s);
  if (!(w2 > kRelTol * kRelTol * r2)) return {Kind::none};
  const auto y = detail::point_of(reflect(s, X));
  if (!y) return {Kind::none};
  return {Kind::point, *y};
}

// In a line L X L: the half-turn about the line.
inline Vec3 reflect_in_line(const Vec3& x, const Line& l) { return *detail::point_of(reflect(l, up(x))); }

// §1.7: the nearest point on a line is the midpoint of x and its reflection.
inline Vec3 nearest_on_line(const Vec3& x, const Line& l) { return 0.5 * (x + reflect_in_line(x, l)); }

}  // namespace gacompare::cga
