#pragma once
// Cl(3,0,1): plane-based geometric algebra of Euclidean 3-space (Gunn; Dorst &
// De Keninck, "Physical Geometry by Plane-Based Geometric Algebra"). The
// compile-time multivector of cga/algebra/multivector.hpp over a degenerate
// metric: e0² = 0 (bit 0), e1² = e2² = e3² = 1 (bits 1..3).
//
// Vectors are planes, bivectors lines, trivectors points, and the even
// subalgebra (8 numbers) holds the motors, every rigid motion:
//   plane n·x = d        π = n1 e1 + n2 e2 + n3 e3 − d e0
//   point x, weight w    X = w e123 − x e023 + y e013 − z e012 (= x e032 + y e013 + z e021)
//   line, direction a through p   a1 e23 − a2 e13 + a3 e12 + (p × a) on e01 e02 e03
//   rate of a body: ω as the direction, the velocity of the world origin v_o as the
//   moment (ω e + v_o e0), so x' = v + ω × (x − c) reads off one bivector
// (P ∨ D = a + (p × a)e0 and T V T̃ = ω + (v + x × ω)e0: tests/pga/algebra/cl301_test.cpp).
//
// π ∧ X = (n·x − d w) e0123: a plane and a point meet in their signed distance,
// one 4-term outer product. Lines are joins (regressive products ∨, through the
// Poincaré complement: the algebra has no inverse pseudoscalar, I² = 0).
#include "cga/algebra/multivector.hpp"
#include "core/geometry.hpp"

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <cmath>
#include <utility>

namespace gacompare::pga {

using cga::BladeSet;
using cga::Cl301;
using cga::Multivector;
using cga::Product;
using cga::grades;
using cga::product;
using cga::project;
using cga::reverse;
using cga::scalar_product;

namespace e4 {  // basis blades of Cl(3,0,1) as bitmasks
inline constexpr unsigned scalar = 0, e0 = 1, e1 = 2, e01 = 3, e2 = 4, e02 = 5, e12 = 6, e012 = 7, e3 = 8, e03 = 9,
                          e13 = 10, e013 = 11, e23 = 12, e023 = 13, e123 = 14, e0123 = 15;
}

using Plane = Multivector<Cl301, grades<Cl301>({1})>;     // e0 e1 e2 e3
using Line = Multivector<Cl301, grades<Cl301>({2})>;      // e01 e02 e12 e03 e13 e23
using Point = Multivector<Cl301, grades<Cl301>({3})>;     // e012 e013 e023 e123
using Motor = Multivector<Cl301, grades<Cl301>({0, 2, 4})>;  // 1 e01 e02 e12 e03 e13 e23 e0123
using Pseudoscalar = Multivector<Cl301, grades<Cl301>({4})>;
using Full = Multivector<Cl301, Cl301::all>;
inline constexpr BladeSet kIdealLine = (BladeSet{1} << e4::e01) | (BladeSet{1} << e4::e02) | (BladeSet{1} << e4::e03);
inline constexpr BladeSet kEuclideanLine = (BladeSet{1} << e4::e12) | (BladeSet{1} << e4::e13) | (BladeSet{1} << e4::e23);
using Rotor = Multivector<Cl301, 1 | kEuclideanLine>;       // 1 e12 e13 e23: a rotation about the origin
using Translator = Multivector<Cl301, 1 | kIdealLine>;      // 1 e01 e02 e03

using Vec3 = Eigen::Vector3d;

// --- entities from Euclidean coordinates, and back ------------------------------------

inline Plane plane(const Vec3& n, double d) { return {{-d, n.x(), n.y(), n.z()}}; }
inline Vec3 normal(const Plane& p) { return {p.c[1], p.c[2], p.c[3]}; }
inline double offset(const Plane& p) { return -p.c[0]; }

inline Point point(const Vec3& x) { return {{-x.z(), x.y(), -x.x(), 1.0}}; }
// A direction: the ideal point (weight 0) towards which parallel lines meet.
inline Point direction(const Vec3& d) { return {{-d.z(), d.y(), -d.x(), 0.0}}; }
inline double weight(const Point& p) { return p.c[3]; }
// The Euclidean coordinates of a point of weight 1 (the join, meet and motor
// below keep weight 1 where they start from it; euclid() divides otherwise).
inline Vec3 coordinates(const Point& p) { return {-p.c[2], p.c[1], -p.c[0]}; }
inline Vec3 euclid(const Point& p) { return coordinates(p) / weight(p); }

// A line from its direction a and moment m = p × a (Plücker coordinates).
inline Line line(const Vec3& a, const Vec3& m) { return {{m.x(), m.y(), a.z(), m.z(), -a.y(), a.x()}}; }
inline Vec3 line_direction(const Line& l) { return {l.c[5], -l.c[4], l.c[2]}; }
inline Vec3 line_moment(const Line& l) { return {l.c[0], l.c[1], l.c[3]}; }

// --- the Poincaré complement and the regressive product -------------------------------

// The right complement of a blade b: the blade c with b ∧ c = +e0123. It maps
// grade k to 4 − k and needs no metric, which is why the degenerate algebra
// joins with it (the dual X I⁻¹ of Cl(3,0) and Cl(4,1) does not exist here).
namespace detail {
constexpr int complement_sign(unsigned b) { return cga::blade_sign<Cl301>(b, b ^ Cl301::pseudoscalar) ; }
constexpr BladeSet complement_set(BladeSet s) {
  BladeSet r = 0;
  for (unsigned b = 0; b < Cl301::blade_count; ++b)
    if ((s >> b) & 1u) r |= BladeSet{1} << (b ^ Cl301::pseudoscalar);
  return r;
}
// The outer-product sign of b ∧ (its complement): no shared vectors, so the
// metric never enters; for Cl(3,0,1) blade_sign of disjoint blades is that sign.
static_assert(complement_sign(e4::e1) == 1 || complement_sign(e4::e1) == -1);
}  // namespace detail

template <BladeSet S>
constexpr auto complement(const Multivector<Cl301, S>& a) {
  using R = Multivector<Cl301, detail::complement_set(S)>;
  R r;
  [&]<std::size_t... K>(std::index_sequence<K...>) {
    ((r.c[R::slot(Multivector<Cl301, S>::blade_at(int(K)) ^ Cl301::pseudoscalar)] =
          detail::complement_sign(Multivector<Cl301, S>::blade_at(int(K))) * a.c[K]),
     ...);
  }(std::make_index_sequence<Multivector<Cl301, S>::size>{});
  return r;
}
// The inverse map: uncomplement(complement(a)) = a.
template <BladeSet S>
constexpr auto uncomplement(const Multivector<Cl301, S>& a) {
  using R = Multivector<Cl301, detail::complement_set(S)>;
  R r;
  [&]<std::size_t... K>(std::index_sequence<K...>) {
    ((r.c[R::slot(Multivector<Cl301, S>::blade_at(int(K)) ^ Cl301::pseudoscalar)] =
          detail::complement_sign(Multivector<Cl301, S>::blade_at(int(K)) ^ Cl301::pseudoscalar) *
          a.c[K]),
     ...);
  }(std::make_index_sequence<Multivector<Cl301, S>::size>{});
  return r;
}
// a ∨ b, the join: the line through two points, the plane through a line and a
// point; of two lines, a scalar (their mutual moment, the virtual power of a
// rate and a force).
// Keep: the blades of the result wanted (as in cga::product), so a caller
// that reads only a line's direction never computes its moment.
template <BladeSet Keep = ~BladeSet{0}, BladeSet SA, BladeSet SB>
constexpr auto join(const Multivector<Cl301, SA>& a, const Multivector<Cl301, SB>& b) {
  return uncomplement(product<Product::outer, detail::complement_set(Keep & Cl301::all)>(complement(a), complement(b)));
}
// The meet ∧ of planes and lines: two planes meet in a line, three in a point,
// a line and a plane in a point (the outer product, cga::operator^).

// π ∧ X = (n·x − d w) e0123: the signed distance of a point of weight 1 from a
// unit plane, > 0 on the side the normal points to. 4 multiplies, 3 adds.
inline double distance(const Plane& p, const Point& x) {
  return product<Product::outer, BladeSet{1} << e4::e0123>(p, x).template get<e4::e0123>();
}
// The same for a point known to have weight 1, written out by structure: the
// e0 ∧ e123 term is the plane's e0 coefficient itself, one multiply fewer.
// (Every vertex the narrowphase holds has weight 1: the face query's
// innermost operation is this one.)
inline double distance_of_unit_point(const Plane& p, const Point& x) {
  return p.c[2] * x.c[1] - p.c[1] * x.c[2] - p.c[3] * x.c[0] + p.c[0];
}
// |y − x|² for points of weight 1: the squared length of the direction of
// their join, whose components are the differences of theirs (no weights to
// multiply by).
inline double distance2_of_unit_points(const Point& x, const Point& y) {
  const double a = y.c[0] - x.c[0], b = y.c[1] - x.c[1], c = y.c[2] - x.c[2];
  return a * a + b * b + c * c;
}

// --- motors ---------------------------------------------------------------------------

// The rotation by a unit quaternion (w, x, y, z): R = w − x e23 + y e13 − z e12,
// the convention of cga/algebra/cl3.hpp, so X ↦ R X R̃ turns points as the quaternion does.
inline Motor motor_from_quaternion(const Eigen::Quaterniond& q) { return {{q.w(), 0, 0, -q.z(), 0, q.y(), -q.x(), 0}}; }
inline Eigen::Quaterniond quaternion_of(const Motor& m) { return {m.c[0], -m.c[6], m.c[5], -m.c[3]}; }
// T(t) = 1 − ½ t e0 (t1 e01 + t2 e02 + t3 e03): T X T̃ = X + t for a point of weight 1.
inline Translator translator(const Vec3& t) { return {{1.0, -0.5 * t.x(), -0.5 * t.y(), -0.5 * t.z()}}; }
// The rigid motion x ↦ R x + t as one motor, M = T(t) R: the product of a
// 4- and a 4-component motor, the ideal part of M is −½ t R.
inline Motor motor(const Eigen::Quaterniond& q, const Vec3& t) {
  return cga::widen<Motor::blades>(translator(t) * project<1 | kEuclideanLine>(motor_from_quaternion(q)));
}

// M M̃ = ρ + k e0123 (the Study number); a motor is unit when ρ = 1, k = 0.
inline std::pair<double, double> study(const Motor& m) {
  const auto mm = product<Product::geometric, 1 | (BladeSet{1} << e4::e0123)>(m, reverse(m));
  return {mm.template get<e4::scalar>(), mm.template get<e4::e0123>()};
}
// The nearest unit motor: M / √(M M̃), the square root of the dual number
// ρ + k I being √ρ (1 + k/(2ρ) I); its inverse (1/√ρ)(1 − k/(2ρ) I). Fixes both
// the rotor's norm and the Study condition (that its translation is a translation).
inline Motor normalised(const Motor& m) {
  const auto [rho, k] = study(m);
  const double a = 1 / std::sqrt(rho), b = -a * k / (2 * rho);
  return cga::widen<Motor::blades>(a * m + m * Pseudoscalar{{b}});
}

// The translation t of M = T(t) R: the ideal part of M R̃ = T (R R̃) is −½ t R R̃.
inline Vec3 translation(const Motor& m) {
  const Rotor r = project<Rotor::blades>(m);
  const auto mr = product<Product::geometric, kIdealLine>(m, reverse(r));
  const double s = -2 / cga::norm2(r);
  return {s * mr.template get<e4::e01>(), s * mr.template get<e4::e02>(), s * mr.template get<e4::e03>()};
}

// The 3×3 rotation of the motor's rotor part, homogeneous over R R̃: an exact
// rotation for any non-zero rotor, drifted or not (the policy of the other two
// backends: traditional/rigid_body.cpp rotation_of, cga rotation_matrix).
// Its columns are the images of the three directions (the motor's outermorphism).
inline Eigen::Matrix3d rotation_matrix(const Motor& m) {
  return geometry::rotation_of(m.c[0], -m.c[6], m.c[5], -m.c[3]);
}

// M X M̃ for a unit motor and a point of weight 1, by its structure (derived in
// tests/pga/algebra/cl301_test.cpp against the two generic products). With
// s the scalar, q = (e23, −e13, e12) the rotation part, u = (e01, e02, e03) the
// ideal part and p the e0123 part of M:
//   c = q × x + u,   x' = x + 2(q × c − s c − p q)
// 39 operations: 21 multiplies and 18 adds written out, which the compiler
// emits as 18 and 21 (x · 2 becomes x + x; scripts/count-flops.py counts the
// compiled code, docs/results/operations.md).
// The same as the quaternion's x + 2w(k × x) + 2k × (k × x) plus the
// translation, with the translation folded into the cross products.
inline Vec3 apply(const Motor& m, const Vec3& x) {
  // Scalars, not Eigen's cross(): its packet form shuffles more than it multiplies.
  const double s = m.c[0], p = m.c[7], q0 = m.c[6], q1 = -m.c[5], q2 = m.c[3];
  const double c0 = q1 * x.z() - q2 * x.y() + m.c[1];
  const double c1 = q2 * x.x() - q0 * x.z() + m.c[2];
  const double c2 = q0 * x.y() - q1 * x.x() + m.c[4];
  const double d0 = q1 * c2 - q2 * c1 - s * c0 - p * q0;
  const double d1 = q2 * c0 - q0 * c2 - s * c1 - p * q1;
  const double d2 = q0 * c1 - q1 * c0 - s * c2 - p * q2;
  return {x.x() + 2 * d0, x.y() + 2 * d1, x.z() + 2 * d2};
}
inline Point apply(const Motor& m, const Point& x) { return point(apply(m, coordinates(x))); }
// On a direction (an ideal point), only the rotation acts: x + 2(q × c − s c), c = q × x.
inline Vec3 apply_direction(const Motor& m, const Vec3& x) {
  const Vec3 q(m.c[6], -m.c[5], m.c[3]);
  const Vec3 c = q.cross(x);
  return x + 2 * (q.cross(c) - m.c[0] * c);
}

// Composition: the geometric product of two motors, 48 multiplies and 40 adds
// from the compile-time table (64 terms less the 16 that e0² = 0 removes).
inline Motor compose(const Motor& a, const Motor& b) { return a * b; }

// exp of a line (a screw's generator), closed form. B² = −u² + β e0123 with u
// the rotation angle (the Euclidean part's length): with the dual angle
// Θ = u + w e0123 (w = −β/(2u)) and the unit line N = B/Θ, exp B = cos Θ + N sin Θ,
// which written out in u and β alone (no division by u) is
//   exp B = cos u + sinc(u) B − ½β g(u) (B e0123) + ½β sinc(u) e0123,
//   g(u) = (cos u − sinc u)/u²  (→ −1/3 as u → 0).
// A pure translation (u = 0) gives 1 + B. Tested against the power series.
namespace detail {
// sinc u = sin u / u and g(u) = (cos u − sinc u)/u², by their series near 0.
inline std::pair<double, double> sinc_and_g(double u) {
  const double u2 = u * u;
  if (u < 1e-3) return {1 - u2 / 6 + u2 * u2 / 120, -1.0 / 3 + u2 / 30 - u2 * u2 / 840};
  const double sinc = std::sin(u) / u;
  return {sinc, (std::cos(u) - sinc) / u2};
}
inline double rotation_angle2(const Line& b) { return b.c[2] * b.c[2] + b.c[4] * b.c[4] + b.c[5] * b.c[5]; }
}  // namespace detail

inline Motor exp(const Line& b) {
  const double u = std::sqrt(detail::rotation_angle2(b));
  const double beta = product<Product::geometric, BladeSet{1} << e4::e0123>(b, b).template get<e4::e0123>();
  const auto [sinc, g] = detail::sinc_and_g(u);
  const auto bi = b * Pseudoscalar{{1.0}};  // B e0123: its Euclidean part moved onto e0
  Motor m = cga::widen<Motor::blades>(sinc * b + (-0.5 * beta * g) * bi);
  m.c[0] = std::cos(u);
  m.c[7] = 0.5 * beta * sinc;
  return m;
}

// log of a unit motor, its inverse: the line B with exp B = M and a rotation
// angle u ≤ π/2 (−M is the same motion; the shorter way round is taken).
// From exp: s = cos u, the e0123 part ½β sinc u, the Euclidean part sinc(u) E
// and the ideal part sinc(u) D − ½β g(u) (E e0123).
inline Line log(const Motor& motor) {
  const Motor m = motor.c[0] < 0 ? -motor : motor;
  const Line biv = project<Line::blades>(m);
  const double sin_u = std::sqrt(detail::rotation_angle2(biv));
  const double u = std::atan2(sin_u, m.c[0]);
  const auto [sinc, g] = detail::sinc_and_g(u);
  const double beta = 2 * m.c[7] / sinc;
  const auto e = project<kEuclideanLine>(biv) / sinc;
  const auto ideal = project<kIdealLine>(biv) + (0.5 * beta * g) * (e * Pseudoscalar{{1.0}});
  return cga::widen<Line::blades>(e + ideal / sinc);
}

}  // namespace gacompare::pga
