#pragma once
// The narrowphase's view of a placed convex body in the traditional algebra
// (issue #6, §2.4.3–2.4.4): vertices and face planes as 3-vectors and
// (normal, offset), a face test by the dot product, edge axes by the cross
// product, Sunday's segment–triangle. The algorithm over it is written once:
// core/narrowphase.hpp. Twin: cga/narrowphase.hpp.
#include "core/narrowphase.hpp"
#include "traditional/segment_triangle.hpp"

#include <vector>

namespace gacompare::traditional {

using Vec3 = Eigen::Vector3d;

class Body {
 public:
  // The body moved into the pair's local frame: x → R x + (p − origin), face
  // planes n → R n with offsets d + (R n)·(p − origin).
  Body(const collision::Placed& placed, const Vec3& origin) : mesh_(placed.mesh) {
    const Eigen::Matrix3d& r = placed.pose.rotation;
    const Vec3 t = placed.pose.position - origin;
    vertices_.reserve(mesh_->vertices().size());
    centre_.setZero();
    for (const Vec3& x : mesh_->vertices()) {
      vertices_.push_back(r * x + t);
      centre_ += vertices_.back();
    }
    centre_ /= static_cast<double>(vertices_.size());
    planes_.reserve(mesh_->planes().size());
    for (const auto& p : mesh_->planes()) {
      const Vec3 n = r * p.normal;
      planes_.push_back({n, p.offset + n.dot(t)});
    }
  }
  const core::Mesh& mesh() const { return *mesh_; }
  Vec3 vertex(int i) const { return vertices_[i]; }
  Vec3 normal(int k) const { return planes_[k].normal; }
  Vec3 centre() const { return centre_; }  // the mean of the vertices: inside a convex body
  // §2.4.3: n·x − d, > 0 outside.
  double plane_distance(int k, const Body& other, int j) const { return planes_[k].distance(other.vertices_[j]); }
  static Vec3 edge_axis(const Vec3& da, const Vec3& db) { return da.cross(db); }
  // §2.4.4: the edge i0–i1 of body s through triangle k of this body, the
  // triangle prepared once per body and query (segment_triangle.hpp).
  std::optional<collision::SegmentHit> segment_through(int k, const Body& s, int i0, int i1) const {
    return prepared_.at(*this, k).through(s.vertices_[i0], s.vertices_[i1]);
  }

  // The contact manifold's algebra (core/manifold.hpp): points as 3-vectors,
  // planes as (normal, offset) with the distance n·x − d, and where a segment
  // crosses a plane by the line–plane intersection.
  using Point = Vec3;
  using Plane = core::Plane;
  const Point& vertex_point(int i) const { return vertices_[i]; }
  const Plane& face_plane(int k) const { return planes_[k]; }
  // The plane through p with normal s (not unit: clipping reads only signs and ratios).
  static Plane plane_through(const Point& p, const Vec3& s) { return {s, s.dot(p)}; }
  static double distance(const Plane& f, const Point& p) { return f.distance(p); }
  // The segment p0–p1 crosses the plane where the distances d0, d1 interpolate to 0.
  static Point cut(const Point& p0, double d0, const Point& p1, double d1) { return p0 + (d0 / (d0 - d1)) * (p1 - p0); }
  static Vec3 position(const Point& p) { return p; }

 private:
  const core::Mesh* mesh_;
  std::vector<Vec3> vertices_;
  std::vector<core::Plane> planes_;
  Vec3 centre_;
  collision::PreparedTriangles<PreparedTriangle> prepared_;
};

inline collision::PairContact narrowphase(const collision::Placed& a, const collision::Placed& b,
                                          collision::Method method,
                                          std::vector<collision::FeatureContact>* contacts = nullptr) {
  return collision::narrowphase<Body>(a, b, method, contacts);
}

}  // namespace gacompare::traditional
