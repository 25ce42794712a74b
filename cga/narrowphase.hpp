#pragma once
// The narrowphase's algebra in conformal geometric algebra
// (§2.4.3–2.4.4): vertices as conformal points X = up(x), face planes as dual
// planes π = n̂ + d n, a face test by the inner product X·π = n̂·x − d (each
// body measured in a unit of its own size: core/collision/shape.hpp, "Units"), edge axes by
// the dual of the outer product (a ∧ b)* in Cl(3,0), and the
// meet/reciprocal-frame segment–triangle. What is built once per body and how
// a pair reads it is written once in core/collision/shape.hpp; the algorithms over it in
// core/collision/narrowphase.hpp. Twin: traditional/narrowphase.hpp.
//
// The rotation reaches the vertices as the rotor's 3×3 matrix, applied once
// per vertex: the outermorphism form that is GA's best practice for many
// points (docs/architecture.md, "Fair comparison"); bench/rigid_bench times the sandwich.
#include "cga/algebra/cl3.hpp"
#include "cga/geometry/entities.hpp"
#include "cga/segment_triangle.hpp"
#include "core/collision/narrowphase.hpp"
#include "core/collision/shape.hpp"

#include <cmath>
#include <vector>

namespace gacompare::cga {

struct NarrowAlgebra {
  using Point = ConformalPoint;
  using Plane = DualPlane;
  using PreparedTriangle = cga::PreparedTriangle;

  static Point lift(const Vec3& x) { return up(x); }
  static Vec3 position(const Point& p) { return detail::euclid(p); }  // up() gives weight 1: no division
  // The power of two nearest below the size: X·π's terms of size |d|·½|x|²
  // stay ≲ 1 (core/collision/shape.hpp, "Units"); a dilation by it is exact.
  static double unit(double size) { return std::ldexp(1.0, std::ilogb(size)); }
  // n̂ + d n: a mesh's normals are unit and a rotation keeps them so (to
  // rounding, as the twin uses them); cga::plane() would divide by |n| again.
  static Plane plane(const Vec3& normal, double offset) {
    return vector5(normal.x(), normal.y(), normal.z(), offset, offset);
  }
  static Vec3 normal(const Plane& f) { return detail::euclid(f); }
  static double offset(const Plane& f) { return f[e5::e]; }         // π = n̂ + d n puts d on e (and ē)
  // The plane parallel to π at offset d: n̂ + d n, n̂ already unit. (Moving π
  // by a is the translator's T π T̃ = π + (n̂·a) n; the offset it gives is
  // computed by the caller, who also rescales it.)
  static Plane parallel(const Plane& f, double offset) { return vector5(f.c[0], f.c[1], f.c[2], offset, offset); }
  // §2.4.3: X·π = n̂·x − d, > 0 outside (entities.hpp). The face query's
  // innermost operation: flattened, because GCC otherwise calls the generic
  // product (a fold over its table's terms) once per vertex, 30 % of an apart
  // pair's time (perf, BM_pair_apart_cached/cga); the twin's dot product is
  // inlined by Eigen.
  [[gnu::flatten]] static double distance(const Plane& f, const Point& p) { return scalar_product(p, f); }
  static Vec3 edge_axis(const Vec3& da, const Vec3& db) { return to_eigen(axial(vector3(da) ^ vector3(db))); }

  // The contact manifold's algebra (core/collision/manifold.hpp): the dual plane through
  // X with normal s, X⌋(s ∧ n) = s + (s·x) n, written out (not unit: clipping
  // reads only signs and ratios); and where a segment crosses a plane, by the
  // meet of the line X0 ∧ X1 ∧ n with π (§1.6, as in segment_triangle.hpp):
  // π⌋(X0 ∧ X1 ∧ n) = (π·X0) X1∧n − (π·X1) X0∧n, the flat point of
  // d0 X1 − d1 X0 with weight d0 − d1; the clipper has d0 = π·X0 and d1 = π·X1
  // already, so the meet costs one combination. Its point is lifted again (up):
  // the combination is a flat point, not a null vector.
  static Plane plane_through(const Point& p, const Vec3& s) {
    const double d = s.dot(detail::euclid(p));
    return vector5(s.x(), s.y(), s.z(), d, d);
  }
  static Point cut(const Point& p0, double d0, const Point& p1, double d1) {
    return up(detail::euclid(d0 * p1 - d1 * p0) * (1 / (d0 - d1)));
  }

  // Round shapes (core/collision/round.hpp): a ball as the dual sphere S = up(c) − ½r² n
  // (entities.hpp). Two spheres' separation from their inner product:
  // S1·S2 = ½(r1² + r2² − d²) and S·S = r², so d² = S1² + S2² − 2 S1·S2 =
  // (S1 − S2)², one scalar product of the difference. A point's distance from
  // another, X·Y = −½|x − y|². (A sphere's centre X against a face is X·π =
  // S·π, as π·n = 0: distance() above.)
  using Sphere = DualSphere;
  static Sphere sphere(const Vec3& centre, double radius) { return cga::sphere(centre, radius); }
  [[gnu::flatten]] static double centre_distance2(const Sphere& a, const Sphere& b) {
    const Sphere d = a - b;
    return scalar_product(d, d);
  }
  [[gnu::flatten]] static double distance2(const Point& x, const Point& y) { return -2 * scalar_product(x, y); }
};

using Shape = collision::Shape<NarrowAlgebra>;
using Body = collision::BodyView<NarrowAlgebra>;

inline collision::PairContact narrowphase(const collision::Placed& a, const collision::Placed& b,
                                          collision::Method method,
                                          std::vector<collision::FeatureContact>* contacts = nullptr) {
  return collision::narrowphase<Body>(a, b, method, contacts);
}

}  // namespace gacompare::cga
