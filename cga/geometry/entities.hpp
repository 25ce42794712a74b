#pragma once
// Conformal entities of Table 1 (§1.5): construction from points (direct form,
// outer products) or from Euclidean parameters (dual form), and extraction of
// the Euclidean parameters back. Twin: traditional/geometry.hpp (same names).
//
// Representations used by the geometry (narrowest grade that holds them):
//   point        Vector5     X = up(x)                        (§1.3 eq. 10)
//   dual sphere  Vector5     S = C − ½ρ² n, kept normalised: S·n = −1
//   dual plane   Vector5     π = n̂ + d n, |n̂| = 1, {x : n̂·x = d}
//   line         Trivector5  L = A ∧ B ∧ n                    (direct)
//   circle       Trivector5  K = A ∧ B ∧ C                    (direct)
// With this normalisation X·S = ½(ρ² − |x − c|²) and X·π = n̂·x − d (a signed
// distance); inside.hpp turns the former into the report's "inside < 0".
//
// Degeneracy: every test is the same dimensionless predicate as the twin's
// (kSinTol, kRelTol in traditional/geometry.hpp), computed from conformal
// invariants: −2 A·B = |a − b|², (A∧B∧C∧n)* has Euclidean part (b−a)×(c−a),
// (A∧B∧C∧D)*·n = (b−a)·((c−a)×(d−a)), L² = |b − a|².
#include "cga/algebra/cl41.hpp"
#include "core/geometry.hpp"

#include <algorithm>
#include <cmath>
#include <optional>

namespace gacompare::cga {

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

namespace blade {  // Cl(4,1) blades the extractions read
inline constexpr unsigned e1e = e5::e1 | e5::e, e2e = e5::e2 | e5::e, e3e = e5::e3 | e5::e;
inline constexpr unsigned eebar = e5::e | e5::ebar;
inline constexpr unsigned e1eebar = e5::e1 | eebar, e2eebar = e5::e2 | eebar, e3eebar = e5::e3 | eebar;
inline constexpr unsigned e12e = e5::e1 | e5::e2 | e5::e, e13e = e5::e1 | e5::e3 | e5::e,
                          e23e = e5::e2 | e5::e3 | e5::e;
inline constexpr unsigned e12 = e5::e1 | e5::e2, e13 = e5::e1 | e5::e3, e23 = e5::e2 | e5::e3;
}  // namespace blade

namespace detail {
// The Euclidean (e1 e2 e3) part of a vector: for a point or a dual sphere, λ·x;
// for a dual plane, the normal.
template <BladeSet S>
Vec3 euclid(const Multivector<Cl41, S>& v) { return {v[e5::e1], v[e5::e2], v[e5::e3]}; }
// −X·n, the weight that down() divides by.
inline double weight(const Vector5& v) { return v.c[4] - v.c[3]; }
// down() without its size test. down() refuses a weight below 1e-15 of the sum
// of the components, which also refuses genuine points beyond |x| ≈ 3e7 (their
// ½|x|² dwarfs the weight), e.g. the centre of a circle through three points
// 1e-9 from collinear. Where this is used, a predicate has already established
// that the result is a finite point; only a zero or non-finite weight fails.
inline std::optional<Vec3> point_of(const Vector5& v) {
  const double w = weight(v);
  const Vec3 x = euclid(v) * (1 / w);  // one division, not three
  if (!(w != 0 && x.allFinite())) return std::nullopt;
  return x;
}
// Whether a dual sphere has a real, nonzero radius that its representation can
// resolve. S² = ρ² is computed from components of size ½|c|², so its rounding
// noise is eps·|S|² (|S|² the sum of squared components); a ρ² below kRelTol·|S|²
// is a point, or an imaginary sphere, to working precision. (The twin only needs
// ρ > 0; this floor, ρ ≳ 3e-6·(1 + |c|²/2) in units of the scene, is a limit of
// the conformal representation itself.)
inline bool real_radius(const Vector5& s, double r2) {
  double size = 0;
  for (double x : s.c) size += x * x;
  return r2 > kRelTol * size;
}
}  // namespace detail

// ---- construction ----

inline ConformalPoint point(const Vec3& x) { return up(x); }

// M* = C − ½ρ² n (§2.4.1, after [7]). A negative radius builds the imaginary
// sphere C + ½ρ² n (S² = −ρ² < 0) rather than silently the real one: no meet
// accepts it, as the twin rejects ρ ≤ 0, and radius() reports it as −|ρ|.
inline DualSphere sphere(const Vec3& centre, double radius) {
  return up(centre) - n_inf() * (0.5 * radius * std::abs(radius));
}

// {x : normal·x = offset}, normalised. The normal must be nonzero (as for the
// twin): a zero normal is a caller's bug, not a degenerate configuration.
inline DualPlane plane(const Vec3& normal, double offset) {
  const double k = normal.norm();
  const double d = offset / k;
  return vector5(normal.x() / k, normal.y() / k, normal.z() / k, d, d);
}

// Line A ∧ B ∧ n (Table 1). Coincident points when L² = |b − a|² is at rounding
// level of the coordinates (the twin's |b − a| ≤ kRelTol·max(|a|, |b|)).
inline std::optional<Line> line_through(const Vec3& a, const Vec3& b) {
  const ConformalPoint A = up(a), B = up(b);
  const Line l = widen<Line::blades>((A ^ B) ^ n_inf());
  const double scale2 = std::max(a.squaredNorm(), b.squaredNorm());
  if (!(scalar_product(l, l) > kRelTol * kRelTol * scale2)) return std::nullopt;
  return l;
}

// Plane A ∧ B ∧ C ∧ n, returned in dual form and normalised. Its dual's
// Euclidean part is −(b−a)×(c−a) (so we negate: the normal is right-handed in
// a, b, c, as the twin's). Collinear when |(b−a)×(c−a)| ≤ kSinTol |b−a||c−a|.
inline std::optional<DualPlane> plane_through(const Vec3& a, const Vec3& b, const Vec3& c) {
  const ConformalPoint A = up(a), B = up(b), C = up(c);
  const DualPlane p = -!(((A ^ B) ^ C) ^ n_inf());
  const double w2 = p.c[0] * p.c[0] + p.c[1] * p.c[1] + p.c[2] * p.c[2];
  const double uv = 4 * scalar_product(A, B) * scalar_product(A, C);  // |b−a|² |c−a|²
  if (!(w2 > kSinTol * kSinTol * uv)) return std::nullopt;
  return p / std::sqrt(w2);
}

// ---- extraction ----

// The centre of a dual sphere: §1.5 reflects n in the sphere (S n S = −2 C for a
// normalised S), but the dual form already holds C: S/(−S·n) has C's e1 e2 e3
// part (n adds only e and ē). Reading it costs a division, not a sandwich;
// centre_by_reflection() keeps the report's form for the tests.
inline Vec3 centre(const DualSphere& s) { return detail::euclid(s) / detail::weight(s); }
inline Vec3 centre_by_reflection(const DualSphere& s) {
  return *detail::point_of(product<Product::geometric, Vector5::blades>(s * n_inf(), s));
}
// ρ² = S² / (S·n)²: S² = ρ² for the normalised form. An imaginary sphere
// (S² < 0) has no real radius: NaN would hide it, so we report −ρ (negative).
inline double radius(const DualSphere& s) {
  const double r2 = scalar_product(s, s) / (detail::weight(s) * detail::weight(s));
  return r2 >= 0 ? std::sqrt(r2) : -std::sqrt(-r2);
}
inline Vec3 normal(const DualPlane& p) { return detail::euclid(p).normalized(); }
// π = n̂ + d n puts d on e and on ē alike; read both (their mean).
inline double offset(const DualPlane& p) {
  return 0.5 * (p[e5::e] + p[e5::ebar]) / detail::euclid(p).norm();
}
// A ∧ B ∧ n = a∧b∧n + (b − a)∧e∧ē: the direction is the e_i e ē part.
inline Vec3 direction(const Line& l) {
  return Vec3(l[blade::e1eebar], l[blade::e2eebar], l[blade::e3eebar]).normalized();
}
// §1.7: reflect a point in the line and take the midpoint; for the origin the
// midpoint is half the reflection.
inline Vec3 point_on(const Line& l) {
  const auto o = n_origin() * -0.5;  // up(0) = −½ n̄, narrow (e, ē only)
  return 0.5 * *detail::point_of(product<Product::geometric, Vector5::blades>(l * o, l));
}

// ---- rounds: circle through 3 points, sphere through 4 (§2.4.1) ----

// Centre of a round. Table 1 (§1.5) reflects n in it, C = X n X. That sandwich
// is quadratic in X, and so is its weight −(XnX)·n = −((X⌊n)² + (X∧n)²): both
// are of order sin² for three points at angle sin from collinear, so the centre
// has condition 1/sin² (at 1e-9 from collinear the answer is noise; measured in
// the tests). Better: contract the dual round with its carrier plane. For a dual
// circle B = σ∧π (σ any sphere through it, π its plane, n⌋B ∝ π),
//   B⌊π = π² σ − (σ·π) π,
// the dual sphere through the circle centred in its plane: its centre is the
// circle's, read off as for any dual sphere. Condition 1/sin, like the twin.
// round_centre takes the dual round (bivector); circle_centre a direct circle.
// nb: n⌋B, when the caller has it already.
inline std::optional<Vec3> round_centre(const Bivector5& b, const Vector5& nb) {
  const Vector5 s = widen<Vector5::blades>(rc(b, nb));
  const double w = detail::weight(s);
  const Vec3 c = detail::euclid(s) * (1 / w);
  if (!(w != 0 && c.allFinite())) return std::nullopt;
  return c;
}
inline std::optional<Vec3> round_centre(const Bivector5& b) { return round_centre(b, n_inf() | b); }
inline std::optional<Vec3> circle_centre(const Circle& k) { return round_centre(!k); }
// The report's C = K n K, kept for the tests that show why it is not used.
template <BladeSet S>
std::optional<Vec3> round_centre_by_reflection(const Multivector<Cl41, S>& x) {
  return detail::point_of(product<Product::geometric, Vector5::blades>(x * n_inf(), x));
}

// Circle A ∧ B ∧ C (§2.4.1, Table 1); centre from the dual circle and its carrier
// plane K ∧ n (round_centre, better conditioned than the report's K n K), which
// also gives the normal; radius |centre − a| (−K²/(n⌋K)² is as ill-conditioned
// as K n K). The report prefers the conformal centre to eq. 38 (which it finds
// "non trivial"); the twin uses a better closed form than eq. 38 too, so the
// comparison is best against best.
inline CircleResult circumcircle(const Vec3& a, const Vec3& b, const Vec3& c) {
  const ConformalPoint A = up(a), B = up(b), C = up(c);
  const Bivector5 dual_circle = !((A ^ B) ^ C);
  // n⌋K* = (n∧K)* is the carrier plane, (K∧n)* with the sign of plane_through:
  // one product serves the normal, the collinearity test and the centre.
  const DualPlane p = n_inf() | dual_circle;
  const double w2 = p.c[0] * p.c[0] + p.c[1] * p.c[1] + p.c[2] * p.c[2];
  const double uv = 4 * scalar_product(A, B) * scalar_product(A, C);
  if (!(w2 > kSinTol * kSinTol * uv)) return {Kind::degenerate};  // collinear or coincident
  const auto centre = round_centre(dual_circle, p);
  if (!centre) return {Kind::degenerate};
  return {Kind::circle, *centre, (*centre - a).norm(), detail::euclid(p) * (1 / std::sqrt(w2))};
}

// The sphere A ∧ B ∧ C ∧ D (Table 1) in dual form, normalised to S·n = −1. The
// normalisation is also the orientation fix of Appendix A fig. 14: dividing by
// −S·n flips a wrongly oriented sphere (see inside.hpp). S·n is the volume
// (b−a)·((c−a)×(d−a)): coplanar points (including four on a circle, where the
// blade itself vanishes) give nullopt.
inline std::optional<DualSphere> dual_sphere_through(const ConformalPoint& A, const ConformalPoint& B,
                                                     const ConformalPoint& C, const ConformalPoint& D) {
  const DualSphere s = !(((A ^ B) ^ C) ^ D);
  const double vol = detail::weight(s);
  const double uvw = -8 * scalar_product(A, B) * scalar_product(A, C) * scalar_product(A, D);
  if (!(vol * vol > kSinTol * kSinTol * uvw)) return std::nullopt;
  return s / vol;
}
inline SphereResult sphere_through(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  const auto s = dual_sphere_through(up(a), up(b), up(c), up(d));
  if (!s) return {Kind::degenerate};
  return {Kind::sphere, detail::euclid(*s), std::sqrt(scalar_product(*s, *s))};
}

}  // namespace gacompare::cga
