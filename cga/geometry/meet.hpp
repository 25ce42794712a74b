#pragma once
// Intersections by the meet (§1.6 eq. 19), each followed by the classification
// and extraction the caller needs. Twin: traditional/geometry.hpp (same names).
//
// Eq. 19, M_r ∨ M_s = [⟨M_r M_s⟩_{10−r−s}]*, dualises both operands, takes a
// grade part of a full geometric product and dualises back. With one or both
// operands already dual (spheres and planes are stored as vectors), the same
// meet is a single narrow product: (A ∨ B)* = A* ∧ B* for two dual entities and
// A* ⌋ B for a dual and a direct one. That computes only the grade that survives
// (eq. 19 computes the whole product and throws most of it away) and needs no
// duals at all. The results agree with eq. 19 up to a nonzero scale, which every
// extraction below divides out.
//
// Classification uses the twin's predicates (kSinTol, kRelTol), written with
// scale-free conformal invariants, e.g. for two spheres
//   −(S1∧S2)² / (S1² S2²) = (r d / ρ1ρ2)²,
// the squared sine of the angle between the surfaces, which the report's "C² ≥ 0"
// test (§2.4.1) only reads the sign of; tangency compares it with kTangentTol.
#include "cga/geometry/entities.hpp"

namespace gacompare::cga {

namespace detail {
inline double sq(double x) { return x * x; }
inline double euclid2(const Vector5& v) { return sq(v.c[0]) + sq(v.c[1]) + sq(v.c[2]); }
// The position of a flat point F = λ(x∧n − e∧ē): x_i = −F[e_i e] / F[e ē]
// (§2.4.4 reads F[e_i e] alone, right only for λ = 1). Callers have checked
// that the weight F[e ē] is not negligible.
inline Vec3 flat_point(const Bivector5& f) {
  const double k = -1 / f[blade::eebar];
  return {k * f[blade::e1e], k * f[blade::e2e], k * f[blade::e3e]};
}
}  // namespace detail

// ---- the meets themselves (blades, for code that keeps working in the algebra) ----

// Dual circle of two spheres, or of a sphere and a plane (a dual "round" bivector).
inline Bivector5 meet(const DualSphere& s1, const DualSphere& s2) { return s1 ^ s2; }
// Flat point (a bivector X ∧ n, §2.4.4) of a line and a dual plane; point pair of
// a line and a dual sphere: both are the contraction π⌋L / S⌋L.
inline Bivector5 meet(const Line& l, const DualPlane& p) { return p | l; }

// ---- sphere–sphere (§2.4.1) ----

// Circle, tangent point or nothing. Normal: (c2 − c1)/|c2 − c1|, as the twin.
// n⌋(S1∧S2) = S1 − S2 for normalised spheres: its square is d² and its Euclidean
// part c1 − c2.
inline CircleResult meet_sphere_sphere(const DualSphere& s1, const DualSphere& s2) {
  const double r1 = scalar_product(s1, s1), r2 = scalar_product(s2, s2);  // ρ²
  if (!(detail::real_radius(s1, r1) && detail::real_radius(s2, r2))) return {Kind::degenerate};
  const Bivector5 b = s1 ^ s2;
  const double b2 = scalar_product(b, b);
  const double sin2 = -b2 / (r1 * r2);
  const Vector5 nb = n_inf() | b;
  const double d2 = scalar_product(nb, nb);
  const double scale2 = detail::euclid2(s1) + detail::euclid2(s2) + r1 + r2;
  if (d2 <= kRelTol * kRelTol * scale2)  // concentric: same sphere or nested
    return {std::abs(sin2) <= kRelTol * kRelTol ? Kind::contained : Kind::none};
  const Vec3 un = -detail::euclid(nb) / std::sqrt(d2);
  if (std::abs(sin2) <= kTangentTol) return {Kind::tangent, *round_centre(b, nb), 0.0, un};
  if (sin2 < 0) return {Kind::none};
  return {Kind::circle, *round_centre(b, nb), std::sqrt(-b2 / d2), un};  // ρ² = −B²/(n⌋B)²
}

// ---- sphere–plane ----

// n⌋(S∧π) = −π (π·n = 0), so (n⌋B)² = π² = 1 and sin² = −B²/ρ². Normal: the plane's.
inline CircleResult meet_sphere_plane(const DualSphere& s, const DualPlane& p) {
  const double r2 = scalar_product(s, s);
  if (!detail::real_radius(s, r2)) return {Kind::degenerate};
  const Bivector5 b = s ^ p;
  const double b2 = scalar_product(b, b), p2 = scalar_product(p, p);
  const double sin2 = -b2 / (r2 * p2);
  if (sin2 < -kTangentTol) return {Kind::none};
  const Vec3 nrm = detail::euclid(p) / std::sqrt(p2);
  const Vector5 nb = -p;  // n⌋(S∧π) = (n·S)π − (n·π)S = −π
  if (std::abs(sin2) <= kTangentTol) return {Kind::tangent, *round_centre(b, nb), 0.0, nrm};
  const double w = detail::weight(s);  // 1 for the normalised form; any scale divides out
  return {Kind::circle, *round_centre(b, nb), std::sqrt(-b2 / (p2 * w * w)), nrm};
}

// ---- line–plane (§2.4.4) ----

// The flat point F = π⌋L = λ(x∧n − e∧ē). §2.4.4 reads x_i off the e_i∧n
// components, which is right only when λ = 1; the meet has an arbitrary scale,
// so we divide by the e∧ē weight (detail::flat_point).
// Parallel when the weight, λ = ±(n̂·u), is at most kSinTol |u| (L² = |u|²);
// then F = dist·(u∧n) and the line lies in the plane when dist is at rounding
// level of |p0| + |d| + |u| (p0 the line's point nearest the origin; |p0||u| is
// the size of L's e_ij e part, its moment).
inline PointResult meet_line_plane(const Line& l, const DualPlane& p) {
  const Bivector5 f = p | l;
  const double w = f[blade::eebar];
  const double u2 = scalar_product(l, l);
  if (detail::sq(w) <= kSinTol * kSinTol * u2 * scalar_product(p, p)) {
    const double gap = std::sqrt(detail::sq(f[blade::e1e]) + detail::sq(f[blade::e2e]) + detail::sq(f[blade::e3e]));
    const double moment =
        std::sqrt(detail::sq(l[blade::e12e]) + detail::sq(l[blade::e13e]) + detail::sq(l[blade::e23e]));
    const double u = std::sqrt(u2);
    const double scale = moment + std::abs(offset(p)) * u + u2;  // (|p0| + |d| + |u|)·|u|
    return {gap <= kRelTol * scale ? Kind::contained : Kind::parallel};
  }
  return {Kind::point, detail::flat_point(f)};
}

// ---- line–sphere ----

// Point pair T = S⌋L. T²/(n⌋T)² is the squared half chord h², (n⌋T)² = |u|², so
// sin² = T² / ((n⌋T)² S²) = h²/ρ². The points are (T ± √T²)(n⌋T); with S
// normalised and L = A∧B∧n the + sign is the one nearer A (first, as the twin).
inline PairResult meet_line_sphere(const Line& l, const DualSphere& s) {
  const double r2 = scalar_product(s, s);
  if (!detail::real_radius(s, r2)) return {Kind::degenerate};
  const Bivector5 t = s | l;
  const double t2 = scalar_product(t, t);
  const Vector5 nt = n_inf() | t;
  const double sin2 = t2 / (scalar_product(nt, nt) * r2);
  const Vector5 tn = product<Product::geometric, Vector5::blades>(t, nt);  // ⟨T (n⌋T)⟩₁
  if (std::abs(sin2) <= kTangentTol) {
    const Vec3 x = *detail::point_of(tn);
    return {Kind::tangent, x, x};
  }
  if (sin2 < 0) return {Kind::none};
  // n⌋T has no weight (n·(n⌋T) = (n∧n)⌋T = 0), so both points share tn's:
  // one division for the pair.
  const double k = 1 / detail::weight(tn);
  const Vec3 mid = detail::euclid(tn) * k, step = detail::euclid(nt) * (std::sqrt(t2) * k);
  return {Kind::point_pair, mid + step, mid - step};
}

// ---- plane–plane ----

// Dual line B = π1∧π2 = n̂1∧n̂2 + (d2 n̂1 − d1 n̂2)∧n. Its Euclidean bivector is
// n̂1∧n̂2, dual to the direction n̂1×n̂2 (so −B² = sin²).
// Parallel: B = (d2 ∓ d1) n̂∧n, coincident when that gap is at rounding level
// of |d1| + |d2|.
inline LineResult meet_plane_plane(const DualPlane& p1, const DualPlane& p2) {
  const Bivector5 b = p1 ^ p2;
  const Vec3 u(b[blade::e23], -b[blade::e13], b[blade::e12]);  // axial(n̂1∧n̂2) = n̂1×n̂2
  const double s2 = u.squaredNorm();
  if (s2 <= kSinTol * kSinTol * scalar_product(p1, p1) * scalar_product(p2, p2)) {
    const double gap = std::sqrt(detail::sq(b[blade::e1e]) + detail::sq(b[blade::e2e]) + detail::sq(b[blade::e3e]));
    const double scale = std::abs(offset(p1)) + std::abs(offset(p2));
    return {gap <= kRelTol * scale ? Kind::contained : Kind::parallel};
  }
  // The point nearest the origin is where the line meets the plane through the
  // origin normal to it, π0 = u (offset 0): the flat point π0⌋L of §2.4.4 with
  // L = B* the direct line. That is linear in B. Reflecting the origin in the
  // line (§1.7, B O B) is quadratic, with a weight of order sin²θ that is lost
  // for nearly parallel planes (the point is then ~|d|/sinθ away).
  const Bivector5 f = embed(vector3(u)) | !b;
  return {Kind::line, detail::flat_point(f), u / std::sqrt(s2)};
}

}  // namespace gacompare::cga
