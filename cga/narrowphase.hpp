#pragma once
// The narrowphase's view of a placed convex body in conformal geometric algebra
// (issue #6, §2.4.3–2.4.4): vertices as conformal points X = up(x), face planes
// as dual planes π = n̂ + d n, a face test by the inner product X·π = n̂·x − d,
// edge axes by the dual of the outer product (a ∧ b)* in Cl(3,0), and the
// meet/reciprocal-frame segment–triangle. The algorithm over it is written
// once: core/narrowphase.hpp. Twin: traditional/narrowphase.hpp.
//
// The rotation reaches the vertices as the rotor's 3×3 matrix, applied once
// per vertex: the outermorphism form that is GA's best practice for many
// points (docs/architecture.md, "Fair comparison"); bench/rigid_bench times the sandwich.
#include "cga/algebra/cl3.hpp"
#include "cga/geometry/entities.hpp"
#include "cga/segment_triangle.hpp"
#include "core/narrowphase.hpp"

#include <vector>

namespace gacompare::cga {

class Body {
 public:
  Body(const collision::Placed& placed, const Vec3& origin) : mesh_(placed.mesh) {
    const Eigen::Matrix3d& r = placed.pose.rotation;
    const Vec3 t = placed.pose.position - origin;
    points_.reserve(mesh_->vertices().size());
    Vec3 sum = Vec3::Zero();
    for (const Vec3& x : mesh_->vertices()) {
      const Vec3 y = r * x + t;
      points_.push_back(up(y));
      sum += y;
    }
    centre_ = sum / static_cast<double>(points_.size());
    planes_.reserve(mesh_->planes().size());
    for (const auto& p : mesh_->planes()) {
      const Vec3 n = r * p.normal;
      planes_.push_back(plane(n, p.offset + n.dot(t)));
    }
  }
  const core::Mesh& mesh() const { return *mesh_; }
  Vec3 vertex(int i) const { return detail::euclid(points_[i]); }  // up() gives weight 1: no division
  Vec3 normal(int k) const { return detail::euclid(planes_[k]); }  // unit: plane() normalises
  Vec3 centre() const { return centre_; }
  // §2.4.3: X·π = n̂·x − d, > 0 outside (entities.hpp).
  double plane_distance(int k, const Body& other, int j) const { return scalar_product(other.points_[j], planes_[k]); }
  static Vec3 edge_axis(const Vec3& da, const Vec3& db) { return to_eigen(axial(vector3(da) ^ vector3(db))); }
  // §2.4.4: the edge i0–i1 of body s through triangle k of this body, the
  // triangle prepared once per body and query (segment_triangle.hpp), the
  // edge's ends the conformal points s already holds.
  std::optional<collision::SegmentHit> segment_through(int k, const Body& s, int i0, int i1) const {
    return prepared_.at(*this, k).through(s.points_[i0], s.points_[i1]);
  }

  // The contact manifold's algebra (core/manifold.hpp): points as conformal
  // points, planes as dual planes with the distance X·π, and where a segment
  // crosses a plane by the meet of their line and the plane (§1.6).
  using Point = ConformalPoint;
  using Plane = DualPlane;
  const Point& vertex_point(int i) const { return points_[i]; }
  const Plane& face_plane(int k) const { return planes_[k]; }
  // The dual plane through X with normal s: X⌋(s ∧ n) = s + (s·x) n, written
  // out (not unit: clipping reads only signs and ratios).
  static Plane plane_through(const Point& p, const Vec3& s) {
    const double d = s.dot(detail::euclid(p));
    return vector5(s.x(), s.y(), s.z(), d, d);
  }
  static double distance(const Plane& f, const Point& p) { return scalar_product(p, f); }
  // The meet of the line X0 ∧ X1 ∧ n with π (§1.6, as in segment_triangle.hpp):
  // π⌋(X0 ∧ X1 ∧ n) = (π·X0) X1∧n − (π·X1) X0∧n, the flat point of
  // d0 X1 − d1 X0 with weight d0 − d1; the clipper has d0 = π·X0 and d1 = π·X1
  // already, so the meet costs one combination. Its point is lifted again (up):
  // the combination is a flat point, not a null vector.
  static Point cut(const Point& p0, double d0, const Point& p1, double d1) {
    return up(detail::euclid(d0 * p1 - d1 * p0) * (1 / (d0 - d1)));
  }
  static Vec3 position(const Point& p) { return detail::euclid(p); }  // up() gives weight 1

 private:
  const core::Mesh* mesh_;
  std::vector<ConformalPoint> points_;
  std::vector<DualPlane> planes_;
  Vec3 centre_;
  collision::PreparedTriangles<PreparedTriangle> prepared_;
};

inline collision::PairContact narrowphase(const collision::Placed& a, const collision::Placed& b,
                                          collision::Method method,
                                          std::vector<collision::FeatureContact>* contacts = nullptr) {
  return collision::narrowphase<Body>(a, b, method, contacts);
}

}  // namespace gacompare::cga
