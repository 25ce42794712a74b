#pragma once
// Bounding spheres, conformal algebra (§2.4.1): the SphereOps policy
// that core/collision/bounding_volume.hpp (exhaustive search, Welzl), core/collision/broadphase.hpp
// (sort and sweep) and core/collision/tree_broadphase.hpp (the sphere tree) run on. A
// sphere is the dual sphere S = C − ½ρ²n (§2.4.1 after [7]), a Cl(4,1) vector
// (5 numbers), kept normalised to S·n = −1 by every constructor here. Twin:
// traditional/bounding_volume.hpp, with the same names in the same order: put
// them side by side and only the algebra differs.
#include "cga/geometry/inside.hpp"
#include "cga/geometry/meet.hpp"
#include "core/collision/bounding_volume.hpp"

#include <algorithm>
#include <cmath>
#include <optional>

namespace gacompare::cga {

struct SphereOps {
  using Sphere = DualSphere;  // the vector S, not cga::Sphere (the direct 4-blade)
  using Point = ConformalPoint;
  static constexpr const char* name = "cga";

  static Point point(const Vec3& x) { return up(x); }
  static Sphere sphere(const Vec3& centre, double radius) { return cga::sphere(centre, radius); }

  // §2.4.1 fig. 6a, from the point pair P = A ∧ B. The report forms the centre
  // C and radius first and then M* = C − ½ρ²n; Table 1 would find the centre by
  // reflecting n in the pair, P n P, which is quadratic in P (weight ∝ (A·B)²).
  // Linear instead: contracting P with its carrier direction n⌋P = A − B gives
  // P⌊(n⌋P) = (A·B)(A + B), i.e. the dual sphere ½(A + B) centred on the pair's
  // midpoint, but with S² = ½A·B = −¼|a − b|²: imaginary (an even-grade round
  // and its dual sphere differ in the sign of ρ²). Adding (A·B)n flips ρ² to
  // +¼|a − b|²:
  //   S = ½(A + B + (A·B) n),   S·A = S·B = 0,   S·n = −1 (A, B from up()).
  // One inner product and two additions; no division, no reflection.
  static Sphere sphere_2(const Point& a, const Point& b) { return (a + b + n_inf() * scalar_product(a, b)) * 0.5; }

  // §2.4.1 fig. 6b, from the circle K = A ∧ B ∧ C. The report extracts the
  // centre by C = K n K and the radius, then builds C − ½ρ²n; the sandwich has
  // condition 1/sin² near collinear (entities.hpp, round_centre). Here the dual
  // circle contracted with its carrier plane π = n⌋K* is already the wanted
  // dual sphere: K*⌊π = π²σ − (σ·π)π (σ any sphere through the circle) passes
  // through the circle and is centred in its plane (the construction
  // cga::circumcircle reads its centre from), so no centre, radius or up() is
  // formed at all; only the weight is divided out. Collinear or coincident
  // points: the twin's predicate, |(b−a)×(c−a)| ≤ kSinTol |b−a||c−a|, read off π.
  static std::optional<Sphere> sphere_3(const Point& a, const Point& b, const Point& c) {
    const Bivector5 dual_circle = !((a ^ b) ^ c);
    const DualPlane p = n_inf() | dual_circle;
    const double w2 = p.c[0] * p.c[0] + p.c[1] * p.c[1] + p.c[2] * p.c[2];
    const double uv = 4 * scalar_product(a, b) * scalar_product(a, c);  // |b−a|² |c−a|²
    if (!(w2 > kSinTol * kSinTol * uv)) return std::nullopt;
    const DualSphere s = widen<Vector5::blades>(rc(dual_circle, p));
    const double w = detail::weight(s);
    if (!(w != 0 && std::isfinite(w))) return std::nullopt;
    return s / w;
  }

  // §2.4.1 fig. 6c: "simply a matter of forming a 4-blade directly from the
  // points", dualised and normalised (cga::dual_sphere_through, with the
  // orientation fix of fig. 14, inside.hpp).
  static std::optional<Sphere> sphere_4(const Point& a, const Point& b, const Point& c, const Point& d) {
    return dual_sphere_through(a, b, c, d);
  }

  // Inside or on, by the report's sign convention (inside.hpp): side(S, X) =
  // X·S/(S·n) = ½(|x − c|² − ρ²) ≤ tol, for a sphere of either orientation.
  static bool contains(const Sphere& s, const Point& x, double tol) { return side(s, x) <= tol; }

  // Overlap of the balls, d ≤ ρ1 + ρ2 (touching and nested included, as the
  // twin's distance test): by inner products, overlap_by_inner_products below.
  // The report's meet (overlap_by_meet) decides the same, forming a
  // 10-component bivector to do it; the simulation runs the best form of the
  // algebra, not the report's (the meet costs several times the twin's
  // time: bench/bounding_volume_bench.cpp).
  static bool overlap(const Sphere& s1, const Sphere& s2);
  // The same for spheres built by sphere(c, ρ) whose radii the caller holds
  // (the broadphase keeps them beside the spheres): normalised (S·n = −1),
  // S1·S2 = ½(ρ1² + ρ2² − d²), so d ≤ ρ1 + ρ2 ⟺ S1·S2 + ρ1ρ2 ≥ 0, nested
  // balls included. One inner product where overlap needs three and the
  // weights: the radius is the one thing a dual sphere holds only squared.
  static bool balls_overlap(const Sphere& s1, double r1, const Sphere& s2, double r2) {
    return scalar_product(s1, s2) + r1 * r2 >= 0;
  }

  // The sphere trees' node operations (§4.2.2; core/collision/tree_broadphase.hpp),
  // all from inner products of normalised dual spheres (S·n = −1, which every
  // constructor here keeps): S1² = ρ1², S2² = ρ2², S1·S2 = ½(ρ1² + ρ2² − d²).
  // The smallest sphere enclosing two: one of them when it holds the other;
  // else the affine combination (1−t)S1 + tS2 (still S·n = −1) is a dual
  // sphere centred at (1−t)c1 + tc2, and adding ½(its square − R²) n (n² = 0,
  // n·S = −1) sets its square to R² without moving the centre:
  //   S = (1−t)S1 + tS2 + ½((1−t)² ρ1² + t² ρ2² + 2t(1−t) S1·S2 − R²) n,
  //   R = ½(d + ρ1 + ρ2), t = (R − ρ1)/d.
  // No centre is read and no point is up-projected; the twin forms the same
  // sphere from the centres' difference vector.
  static Sphere enclosing(const Sphere& s1, const Sphere& s2) {
    const double q1 = scalar_product(s1, s1), q2 = scalar_product(s2, s2), q12 = scalar_product(s1, s2);
    const double r1 = std::sqrt(std::max(q1, 0.0)), r2 = std::sqrt(std::max(q2, 0.0));
    const double d = std::sqrt(std::max(q1 + q2 - 2 * q12, 0.0));
    if (d + r2 <= r1) return s1;
    if (d + r1 <= r2) return s2;
    const double R = 0.5 * (d + r1 + r2), t = (R - r1) / d, u = 1 - t;
    const double square = u * u * q1 + t * t * q2 + 2 * t * u * q12;
    return s1 * u + s2 * t + n_inf() * (0.5 * (square - R * R));
  }
  // The outer ball holds the inner one: d ≤ ρo − ρi ⟺ So·Si ≥ ρo ρi (with
  // ρo ≥ ρi, by S1·S2 above); squared, three inner products and no root.
  // The sign is that of ½((ρo − ρi)² − d²), read off numbers of size ρ², so
  // nearly equal concentric spheres are told apart only to a room of
  // ~√ε·ρ (the twin: ~ε·ρ); the trees test rooms of kFatMargin·ρ.
  static bool encloses(const Sphere& outer, const Sphere& inner) {
    const double qo = scalar_product(outer, outer), qi = scalar_product(inner, inner), q = scalar_product(outer, inner);
    return qo >= qi && q >= 0 && q * q >= qo * qi;
  }
  // The radius larger by `by`: S − ½((ρ + by)² − ρ²) n; n changes only the
  // n-part, so the centre stays.
  static Sphere grown(const Sphere& s, double by) {
    const double r = std::sqrt(std::max(scalar_product(s, s), 0.0));
    return s - n_inf() * (by * (r + 0.5 * by));
  }
  // ρ² = S², the tree's cost (proportional to the surface area): one inner product.
  static double radius_squared(const Sphere& s) { return scalar_product(s, s); }

  static Vec3 centre(const Sphere& s) { return cga::centre(s); }
  static double radius(const Sphere& s) { return cga::radius(s); }
};

// §2.4.1: "intersections between spheres are evaluated by finding the Meet
// (see 1.6) of the two spheres, here denoted C. An intersection exists if
// C² ≥ 0." The meet of two dual spheres is the dual circle B = S1 ∧ S2
// (meet.hpp); the direct C = B* has C² = −B² (I² = −1 in Cl(4,1)), and
// −B²/(S1² S2²) = (r d/ρ1ρ2)² = sin² of the angle between the surfaces
// (meet.hpp). So C² ≥ 0 ⟺ B² ≤ 0: the surfaces cross (or touch, B² = 0),
// exactly the twin's |ρ1 − ρ2| ≤ d ≤ ρ1 + ρ2.
// What the report's rule misses: B² > 0 both for spheres apart (d > ρ1 + ρ2)
// and for one inside the other (d < |ρ1 − ρ2|), and nested bounding spheres
// DO overlap. One inner product tells them apart: S1·S2 = ½(ρ1² + ρ2² − d²)
// for normalised spheres, negative when apart ((ρ1 + ρ2)² < d²) and positive
// when nested (d² < (ρ1 − ρ2)²); the weights make it independent of scale and
// orientation. Both signs are computed before they are combined: no branch on
// the data. Kept as the report's form, timed beside SphereOps::overlap.
inline bool overlap_by_meet(const DualSphere& s1, const DualSphere& s2) {
  const Bivector5 c = meet(s1, s2);
  const bool surfaces_meet = scalar_product(c, c) <= 0;  // C² ≥ 0
  const bool nested = scalar_product(s1, s2) * detail::weight(s1) * detail::weight(s2) > 0;
  return surfaces_meet || nested;
}

// The same predicate without forming the meet: for vectors
// (S1∧S2)² = (S1·S2)² − S1² S2² (Lagrange), so "C² ≥ 0 or nested" is
// S1·S2 ≥ 0 (nested, or crossing with d² ≤ ρ1² + ρ2²) or (S1·S2)² ≤ S1² S2².
// Three 5-term inner products instead of the 10-component bivector and its
// square. The sign of S1·S2 is read with the weights, as overlap_by_meet
// does, so a sphere of any scale or orientation (−3 S) is the same sphere.
inline bool overlap_by_inner_products(const DualSphere& s1, const DualSphere& s2) {
  const double s12 = scalar_product(s1, s2);
  const bool near = s12 * s12 <= scalar_product(s1, s1) * scalar_product(s2, s2);
  return s12 * detail::weight(s1) * detail::weight(s2) >= 0 || near;
}
inline bool SphereOps::overlap(const Sphere& s1, const Sphere& s2) { return overlap_by_inner_products(s1, s2); }

}  // namespace gacompare::cga
