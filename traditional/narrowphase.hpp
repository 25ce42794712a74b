#pragma once
// The narrowphase's algebra in the traditional backend (§2.4.3–2.4.4):
// vertices and face planes as 3-vectors and (normal, offset), a face test by
// the dot product, edge axes by the cross product, Sunday's segment–triangle. What is built once per body
// and how a pair reads it is written once in core/collision/shape.hpp; the algorithms
// over it in core/collision/narrowphase.hpp. Twin: cga/narrowphase.hpp.
#include "core/collision/narrowphase.hpp"
#include "core/collision/shape.hpp"
#include "traditional/segment_triangle.hpp"

#include <vector>

namespace gacompare::traditional {

using Vec3 = Eigen::Vector3d;

struct NarrowAlgebra {
  using Point = Vec3;
  using Plane = core::Plane;
  using PreparedTriangle = traditional::PreparedTriangle;

  static Point lift(const Vec3& x) { return x; }
  static Vec3 position(const Point& p) { return p; }
  // n·x − d has no term that grows with |x|²: metres serve (core/collision/shape.hpp, "Units").
  static double unit(double /*size*/) { return 1; }
  static Plane plane(const Vec3& normal, double offset) { return {normal, offset}; }
  static Vec3 normal(const Plane& f) { return f.normal; }
  static double offset(const Plane& f) { return f.offset; }
  static Plane parallel(const Plane& f, double offset) { return {f.normal, offset}; }
  // §2.4.3: n·x − d, > 0 outside.
  static double distance(const Plane& f, const Point& p) { return f.distance(p); }
  static Vec3 edge_axis(const Vec3& da, const Vec3& db) { return da.cross(db); }

  // The contact manifold's algebra (core/collision/manifold.hpp): the plane through p
  // with normal s (not unit: clipping reads only signs and ratios), and where
  // the segment p0–p1 crosses a plane, its distances d0, d1 interpolated to 0
  // (the line–plane intersection).
  static Plane plane_through(const Point& p, const Vec3& s) { return {s, s.dot(p)}; }
  static Point cut(const Point& p0, double d0, const Point& p1, double d1) { return p0 + (d0 / (d0 - d1)) * (p1 - p0); }

  // Round shapes (core/collision/round.hpp): a ball as centre and radius; the spheres'
  // separation by the distance of their centres, a point's from another by
  // the dot product of their difference.
  struct Sphere {
    Vec3 centre;
    double radius;
  };
  static Sphere sphere(const Vec3& centre, double radius) { return {centre, radius}; }
  static double centre_distance2(const Sphere& a, const Sphere& b) { return (a.centre - b.centre).squaredNorm(); }
  static double distance2(const Point& x, const Point& y) { return (x - y).squaredNorm(); }
};

using Shape = collision::Shape<NarrowAlgebra>;
using Body = collision::BodyView<NarrowAlgebra>;

inline collision::PairContact narrowphase(const collision::Placed& a, const collision::Placed& b,
                                          collision::Method method,
                                          std::vector<collision::FeatureContact>* contacts = nullptr) {
  return collision::narrowphase<Body>(a, b, method, contacts);
}

}  // namespace gacompare::traditional
