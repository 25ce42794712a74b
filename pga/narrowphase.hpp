#pragma once
// The narrowphase's algebra in plane-based geometric algebra: vertices as
// points (trivectors of weight 1), face planes as vectors n − d e0, a face
// test by the meet π ∧ X = n·x − d (a 4-term outer product), edge axes by
// the direction of the line where two planes through the origin meet, the
// crossing of a segment and a plane by their meet, and the join/Plücker
// segment–triangle (segment_triangle.hpp). What is built once per body and
// how a pair reads it is written once in core/collision/shape.hpp; the
// algorithms over it in core/collision/narrowphase.hpp. Twins:
// traditional/narrowphase.hpp, cga/narrowphase.hpp.
//
// Units: π ∧ X has no term growing with |x|² (the conformal X·π has), so a
// shape's own coordinates are metres, as for the matrix backend.
#include "pga/algebra/cl301.hpp"
#include "pga/segment_triangle.hpp"
#include "core/collision/narrowphase.hpp"
#include "core/collision/shape.hpp"

#include <vector>

namespace gacompare::pga {

struct NarrowAlgebra {
  using Point = pga::Point;
  using Plane = pga::Plane;
  using PreparedTriangle = pga::PreparedTriangle;

  static Point lift(const Vec3& x) { return point(x); }
  static Vec3 position(const Point& p) { return coordinates(p); }  // every Point here has weight 1
  static double unit(double /*size*/) { return 1; }
  // n − d e0; a mesh's normals are unit and a rotation keeps them so.
  static Plane plane(const Vec3& normal, double offset) { return pga::plane(normal, offset); }
  static Vec3 normal(const Plane& f) { return pga::normal(f); }
  static double offset(const Plane& f) { return pga::offset(f); }
  // The plane with π's normal at offset d: only its e0 coefficient changes.
  static Plane parallel(const Plane& f, double offset) { return {{-offset, f.c[1], f.c[2], f.c[3]}}; }
  // π ∧ X = n·x − d, > 0 outside (written out for weight 1: cl301.hpp).
  static double distance(const Plane& f, const Point& p) { return distance_of_unit_point(f, p); }
  // Two faces' normals as planes through the origin meet in a line whose
  // direction is the edge pair's axis: the Euclidean part of a ∧ b.
  static Vec3 edge_axis(const Vec3& da, const Vec3& db) {
    return line_direction(cga::widen<Line::blades>(
        product<Product::outer, kEuclideanLine>(plane(da, 0), plane(db, 0))));
  }

  // The contact manifold's algebra (core/collision/manifold.hpp): the plane
  // through X with normal s (n − (s·x) e0, not unit: clipping reads only signs
  // and ratios); where a segment crosses a plane, the meet
  // π ∧ (X0 ∨ X1) = (π ∧ X0) X1 − (π ∧ X1) X0, the point d0 X1 − d1 X0 of
  // weight d0 − d1 (the clipper has d0 and d1 already: one combination).
  static Plane plane_through(const Point& p, const Vec3& s) { return pga::plane(s, s.dot(coordinates(p))); }
  static Point cut(const Point& p0, double d0, const Point& p1, double d1) {
    return (d0 * p1 - d1 * p0) * (1 / (d0 - d1));
  }

  // Round shapes (core/collision/round.hpp): PGA has no round primitive (the
  // conformal model adds one dimension for them), so a ball is its centre point
  // and radius. Two points' squared distance is the squared length of the
  // direction of their join, P ∨ Q = (q − p) + (p × q) e0 for weight 1
  // (written out: cl301.hpp distance2_of_unit_points).
  struct Sphere {
    Point centre;
    double radius;
  };
  static Sphere sphere(const Vec3& centre, double radius) { return {point(centre), radius}; }
  static double distance2(const Point& x, const Point& y) { return distance2_of_unit_points(x, y); }
  static double centre_distance2(const Sphere& a, const Sphere& b) { return distance2(a.centre, b.centre); }
};

using Shape = collision::Shape<NarrowAlgebra>;
using Body = collision::BodyView<NarrowAlgebra>;

inline collision::PairContact narrowphase(const collision::Placed& a, const collision::Placed& b,
                                          collision::Method method,
                                          std::vector<collision::FeatureContact>* contacts = nullptr) {
  return collision::narrowphase<Body>(a, b, method, contacts);
}

}  // namespace gacompare::pga
