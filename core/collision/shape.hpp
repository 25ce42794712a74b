#pragma once
// A body's narrowphase geometry where it is, computed once per detection and
// read by every pair the body takes part in, and the light
// view of it that one pair works with. Written once over a backend's algebra
// (traditional/narrowphase.hpp, cga/narrowphase.hpp), which supplies:
//   Point, Plane: a vertex (a 3-vector, or the conformal point up(x)) and a
//     face plane ((n, d), or the dual plane n̂ + d n);
//   lift(x), position(X), plane(n, d), normal(π), offset(π), parallel(π, d)
//     (the plane with π's normal at offset d), distance(π, X) (> 0 outside:
//     n·x − d or X·π);
//   unit(size): the length a shape's own coordinates are measured in (below);
//   edge_axis, plane_through, cut (core/collision/separating_axis.hpp, core/collision/manifold.hpp);
//   PreparedTriangle: segment–triangle with the triangle prepared (§2.4.4).
//
// Why a body keeps its own frame and not the pair's. Before, every pair built
// both bodies in a frame midway between them (x → R x + p − o, each face plane
// moved the same way, and for cga every vertex lifted to a conformal point):
// each pair paid for every vertex and face of both bodies plus the
// allocations, which dominated the narrowphase's profile in large scenes
// (bench/narrowphase_bench.cpp). A Shape holds R x and (R n, d): the body about its
// own position in the world's orientation, built once per detection; a pair
// places each body at its translation t = p − o in the pair's frame
// (o = local_origin) without touching its vertices:
//   - the distance of vertex j of body o from face k of body f is that of o's
//     own vertex R x_j from f's plane moved into o's frame (its offset
//     d + n·(t_f − t_o)): one shift per face, then n·x − d or X·π per vertex;
//   - edge pairs read each body's edges relative to its own position and add
//     t_b − t_a once per edge of a.
//
// Units. X·π = n̂·x + d(X_e − X_ē) adds terms of size |d| ½|x|² that cancel, so
// a conformal face test rounds to ~eps·|d|·|x|², not ~eps·|x| as n·x − d does:
// a 1e3 m cube measured in metres kept 12 digits of its depth, not 16 (body
// centred, a face 500 m from the centre, vertices up to 870 m; the pair's frame
// had hidden it for the face in contact, which passes near o). So a shape's own
// coordinates are in a unit of the algebra's choosing: cga measures each body
// in the power of two nearest below its size (exact to scale by: no rounding
// in or out; |x|, |d| ≲ 1 for every shape), traditional in metres
// (unit 1: n·x − d has no such term). Offsets moved between two shapes are
// rescaled with them (the dilation by the ratio of the units, a power of two).
//
// Support points. The face query asks, per face, for the other body's vertex
// lowest under the plane. Bodies with few vertices scan them all; from
// kHillClimbVertices on, when every vertex is a corner of the solid
// (Mesh::corners_only), the search walks the edge graph downhill from the
// previous face's support, which is usually a few steps away: on a convex
// body a vertex with no lower neighbour is a lowest vertex (ties: one with
// the same distance).
#include "core/collision/collision.hpp"
#include "core/model/mesh.hpp"

#include <boost/container/small_vector.hpp>

#include <atomic>
#include <concepts>
#include <cstdint>
#include <optional>
#include <span>
#include <thread>
#include <utility>
#include <vector>

namespace gacompare::collision {

// From this many vertices on, hill climbing finds support points; below, the
// scan is cheaper (bench/narrowphase_bench.cpp BM_support_*).
inline constexpr int kHillClimbVertices = 40;

// A feature edge relative to its body's position: a point, the direction, and
// the normals of its two faces (its arc on the Gauss map). The triangle of
// plane edge_planes()[i][0] runs the edge from edges()[i][0] to [1], so the
// direction is n0 × n1 up to length.
struct ShapeEdge {
  Vec3 p, d, n0, n1;
};

// The narrowphase's algebra a backend supplies (listed at the top of this
// file): a missing operation is a compile error naming it.
template <class A>
concept NarrowphaseAlgebra = requires(const Vec3& x, double d, const typename A::Point& p,
                                      const typename A::Plane& f, const typename A::Sphere& s,
                                      const typename A::PreparedTriangle& t) {
  { A::lift(x) } -> std::convertible_to<typename A::Point>;
  { A::position(p) } -> std::convertible_to<Vec3>;
  { A::unit(d) } -> std::convertible_to<double>;
  { A::plane(x, d) } -> std::convertible_to<typename A::Plane>;
  { A::normal(f) } -> std::convertible_to<Vec3>;
  { A::offset(f) } -> std::convertible_to<double>;
  { A::parallel(f, d) } -> std::convertible_to<typename A::Plane>;
  { A::distance(f, p) } -> std::convertible_to<double>;
  { A::edge_axis(x, x) } -> std::convertible_to<Vec3>;
  { A::plane_through(p, x) } -> std::convertible_to<typename A::Plane>;
  { A::cut(p, d, p, d) } -> std::convertible_to<typename A::Point>;
  { typename A::PreparedTriangle(x, x, x) };
  { t.through(x, x) } -> std::convertible_to<std::optional<SegmentHit>>;
  // Round shapes (core/collision/round.hpp): a ball, two balls' squared
  // centre distance, two points' squared distance.
  { A::sphere(x, d) } -> std::convertible_to<typename A::Sphere>;
  { A::centre_distance2(s, s) } -> std::convertible_to<double>;
  { A::distance2(p, p) } -> std::convertible_to<double>;
};

// Room inside a Shape for a box's geometry (8 vertices, 6 faces, 12 edges;
// an octahedron's 8 faces): the pairs read a body's vertices, faces and edges
// from one block beside its pose, not from three blocks of the heap. A larger
// mesh keeps the rest on the heap.
inline constexpr std::size_t kInlineVertices = 8, kInlineFaces = 8, kInlineEdges = 12;

template <NarrowphaseAlgebra A>
class Shape {
 public:
  using Algebra = A;
  using Point = typename Algebra::Point;
  using Plane = typename Algebra::Plane;
  using Prepared = typename Algebra::PreparedTriangle;

  Shape() = default;
  explicit Shape(const Placed& placed) { place(placed); }

  // The body at a new pose, in the storage it already has (no allocation
  // after the first time). The same mesh at the same pose, bit for bit (a
  // static body), keeps everything, edges and triangles included.
  void place(const Placed& placed) {
    if (mesh_ == placed.mesh && pose_.position == placed.pose.position && pose_.rotation == placed.pose.rotation)
      return;
    mesh_ = placed.mesh;
    pose_ = placed.pose;
    const Mat3& r = pose_.rotation;
    unit_ = Algebra::unit(mesh_->size());
    const double per = 1 / unit_;  // a power of two (or 1): exact
    edges_state_ = kNotBuilt, triangles_ready_ = false;
    if (mesh_->is_round()) {
      // A round shape (core/collision/round.hpp, core/collision/capsule.hpp) is its centre, radius
      // and a capsule's half axis: the proxy polyhedron (core/model/mesh.hpp) is
      // never placed.
      centre_ = r * mesh_->sphere_centre();
      half_axis_ = r * mesh_->capsule_half_axis();
      points_.clear(), planes_.clear();
      climb_ = false;
      return;
    }
    const auto& v = mesh_->vertices();
    points_.resize(v.size());
    Vec3 sum = Vec3::Zero();
    for (std::size_t i = 0; i < v.size(); ++i) {
      const Vec3 x = r * v[i];
      points_[i] = Algebra::lift(Vec3(x * per));
      sum += x;
    }
    centre_ = sum / static_cast<double>(v.size());
    const auto& p = mesh_->planes();
    planes_.resize(p.size());
    for (std::size_t k = 0; k < p.size(); ++k) planes_[k] = Algebra::plane(r * p[k].normal, p[k].offset * per);
    climb_ = mesh_->corners_only() && static_cast<int>(v.size()) >= kHillClimbVertices;
  }

  // Forgets the pose, so that the next place() builds everything again (for
  // timing one pair's first meeting; the storage stays).
  void reset() { mesh_ = nullptr; }

  const Mesh& mesh() const { return *mesh_; }
  const Pose& pose() const { return pose_; }
  const Vec3& position() const { return pose_.position; }
  // In the shape's own frame and unit: R x / unit(), (R n, d / unit()).
  const Point& point(int i) const { return points_[i]; }
  const Plane& plane(int k) const { return planes_[k]; }
  double unit() const { return unit_; }
  // In metres, about the body's position.
  Vec3 vertex(int i) const { return Algebra::position(points_[i]) * unit_; }
  Vec3 normal(int k) const { return Algebra::normal(planes_[k]); }
  double offset(int k) const { return Algebra::offset(planes_[k]) * unit_; }
  const Vec3& centre() const { return centre_; }  // the mean of the vertices: inside a convex body
  // A round shape (core/collision/round.hpp): its radius (0 for a polyhedron); its
  // centre is centre(), about the body's position in metres.
  bool is_sphere() const { return mesh_->is_sphere(); }
  double radius() const { return mesh_->sphere_radius(); }
  // A capsule's segment is centre() ± half_axis() (in the world's orientation).
  bool is_capsule() const { return mesh_->is_capsule(); }
  const Vec3& half_axis() const { return half_axis_; }

  // The feature edges, built on first use after a place(): a pair decided by a
  // face never needs them. Pairs tested on several threads may ask at once:
  // the first builds them, the others wait for it (the same numbers whoever
  // builds them). Built up front for every placed shape instead, they cost
  // about a tenth of the narrowphase on the 1,000-body box.
  std::span<const ShapeEdge> edges() const {
    std::atomic_ref<std::uint8_t> state(edges_state_);
    if (state.load(std::memory_order_acquire) != kBuilt) build_edges(state);
    return {edge_list_.data(), edge_list_.size()};
  }

  // Triangle k prepared for segment tests (§2.4.4), built on first use: the
  // report's detector tests each triangle against many edges.
  const Prepared& triangle(int k) const {
    if (!triangles_ready_) {
      const auto& t = mesh_->triangles();
      triangles_.resize(t.size());
      const auto at = [&](int i) { return Algebra::position(points_[i]); };  // in the shape's unit
      for (std::size_t i = 0; i < t.size(); ++i) triangles_[i] = Prepared(at(t[i][0]), at(t[i][1]), at(t[i][2]));
      triangles_ready_ = true;
    }
    return triangles_[k];
  }

  // The vertex lowest under the plane (in this shape's frame and unit) and
  // its signed distance (in the unit): the support point against the plane's
  // normal. `start` is where hill climbing begins (see the top of the file).
  std::pair<double, int> lowest(const Plane& plane, int start = 0) const {
    return climb_ ? climb(plane, start) : scan(plane);
  }
  // Both searches, for the tests and the benchmarks.
  std::pair<double, int> scan(const Plane& plane) const {
    int arg = 0;
    double lo = Algebra::distance(plane, points_[0]);
    for (int j = 1; j < static_cast<int>(points_.size()); ++j) {
      const double s = Algebra::distance(plane, points_[j]);
      if (s < lo) lo = s, arg = j;
    }
    return {lo, arg};
  }
  // Steepest descent over the edge graph; stops at a vertex no neighbour is
  // strictly lower than.
  std::pair<double, int> climb(const Plane& plane, int start) const {
    int at = start;
    double lo = Algebra::distance(plane, points_[at]);
    for (;;) {
      int next = -1;
      for (const int w : mesh_->neighbours(at)) {
        const double s = Algebra::distance(plane, points_[w]);
        if (s < lo) lo = s, next = w;
      }
      if (next < 0) return {lo, at};
      at = next;
    }
  }
  bool climbs() const { return climb_; }

 private:
  static constexpr std::uint8_t kNotBuilt = 0, kBuilding = 1, kBuilt = 2;

  void build_edges(std::atomic_ref<std::uint8_t>& state) const {
    std::uint8_t expected = kNotBuilt;
    if (!state.compare_exchange_strong(expected, kBuilding, std::memory_order_acquire)) {
      while (state.load(std::memory_order_acquire) != kBuilt) std::this_thread::yield();
      return;
    }
    const auto& e = mesh_->edges();
    const auto& ep = mesh_->edge_planes();
    edge_list_.resize(e.size());
    for (std::size_t i = 0; i < e.size(); ++i) {
      const Vec3 p = vertex(e[i][0]);
      edge_list_[i] = {p, vertex(e[i][1]) - p, normal(ep[i][0]), normal(ep[i][1])};
    }
    state.store(kBuilt, std::memory_order_release);
  }

  // What place() writes comes first, the flags beside the pose: in a large
  // scene every place() misses the cache, and the edges (a kilobyte, built
  // for few pairs) would put the flags a dozen cache lines away.
  const Mesh* mesh_ = nullptr;
  double unit_ = 1;
  bool climb_ = false;
  // kNotBuilt, kBuilding or kBuilt, read and written through atomic_ref
  // (edges()); place() resets it before any pair reads the shape.
  mutable std::uint8_t edges_state_ = kNotBuilt;
  mutable bool triangles_ready_ = false;
  Pose pose_;
  Vec3 centre_ = Vec3::Zero();
  Vec3 half_axis_ = Vec3::Zero();
  boost::container::small_vector<Point, kInlineVertices> points_;
  boost::container::small_vector<Plane, kInlineFaces> planes_;
  mutable boost::container::small_vector<ShapeEdge, kInlineEdges> edge_list_;
  mutable std::vector<Prepared> triangles_;
};

// One body of a pair: its Shape at translation `offset` in the pair's frame.
// Two pointers' worth; copies nothing. Every Vec3 it returns is in the pair's
// frame; shape() reads the body's own.
template <NarrowphaseAlgebra A>
class BodyView {
 public:
  using Algebra = A;
  using Shape = collision::Shape<Algebra>;
  using Point = typename Algebra::Point;
  using Plane = typename Algebra::Plane;

  BodyView(const Shape& shape, const Vec3& offset) : shape_(&shape), offset_(offset) {}

  const Shape& shape() const { return *shape_; }
  const Mesh& mesh() const { return shape_->mesh(); }
  const Vec3& offset() const { return offset_; }
  Vec3 vertex(int i) const { return shape_->vertex(i) + offset_; }
  Vec3 normal(int k) const { return shape_->normal(k); }
  Vec3 centre() const { return shape_->centre() + offset_; }
  Vec3 sphere_centre() const { return centre(); }  // a round shape's centre (core/collision/round.hpp)
  // A capsule's segment ends (end 0: centre − half axis), in the pair's frame.
  Vec3 capsule_end(int i) const { return centre() + (i == 0 ? -1.0 : 1.0) * shape_->half_axis(); }
  // A point of the pair's frame (metres) in this body's own frame and unit.
  Point local_point(const Vec3& x) const { return Algebra::lift(Vec3((x - offset_) / shape_->unit())); }
  // Face k of this body as a plane in `other`'s own frame and unit, and vertex
  // j of `other` as a point in this body's.
  Plane plane_toward(int k, const BodyView& other) const {
    const Shape& o = *other.shape_;
    return Algebra::parallel(shape_->plane(k),
                             (shape_->offset(k) + shape_->normal(k).dot(offset_ - other.offset_)) / o.unit());
  }
  Point point_from(const BodyView& other, int j) const {
    return Algebra::lift(Vec3((other.shape_->vertex(j) + (other.offset_ - offset_)) / shape_->unit()));
  }

  // The contact manifold's algebra (core/collision/manifold.hpp), in the pair's frame in metres.
  Point vertex_point(int i) const { return Algebra::lift(vertex(i)); }
  Plane face_plane(int k) const {
    return Algebra::parallel(shape_->plane(k), shape_->offset(k) + shape_->normal(k).dot(offset_));
  }
  static Plane plane_through(const Point& p, const Vec3& s) { return Algebra::plane_through(p, s); }
  static double distance(const Plane& f, const Point& p) { return Algebra::distance(f, p); }
  static Point cut(const Point& p0, double d0, const Point& p1, double d1) { return Algebra::cut(p0, d0, p1, d1); }
  static Vec3 position(const Point& p) { return Algebra::position(p); }
  static Vec3 edge_axis(const Vec3& da, const Vec3& db) { return Algebra::edge_axis(da, db); }

 private:
  const Shape* shape_;
  Vec3 offset_;
};

// A narrowphase body type: the view of a shape over a NarrowphaseAlgebra.
template <class B>
concept NarrowphaseBody =
    NarrowphaseAlgebra<typename B::Algebra> && std::same_as<B, BodyView<typename B::Algebra>>;

}  // namespace gacompare::collision
