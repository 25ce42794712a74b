#pragma once
// The separating-axis test for convex polyhedra (issue #6; beyond the report,
// whose fig. 7 detector finds contacts but no minimum penetration depth).
//
// Two convex polyhedra are disjoint iff some plane separates them, and the
// candidate planes are finite: the face normals of each body and the cross
// products of one edge of each. The penetration depth (the shortest translation
// that separates them) is the distance from the origin to the boundary of the
// Minkowski difference A − B, whose faces have exactly those normals; so the
// largest signed gap over the candidate axes is −(penetration depth) when the
// bodies overlap, exactly, and a lower bound of the distance when apart.
//
// Two versions, which share no code on purpose so that one checks the other:
//   sat_reference: every face normal and every edge pair, both bodies projected
//     onto each axis in long double (64-bit mantissa, 2048× finer than double).
//     Slow (edges² × vertices), simple, the yardstick of the tests and of
//     `gacompare collide`'s "sat" column.
//   separating_axis<Body>: the fast path each backend runs in its own algebra.
//     Face axes take the other body's support point; edge pairs are pruned on
//     the Gauss map (Gregorius, "The Separating Axis Test between Convex
//     Polyhedra", GDC 2013): a pair of edges spans a face of A − B only if the
//     arcs of their adjacent face normals cross on the unit sphere, and then
//     the gap is the distance between the two edge lines, no projection needed.
//
// Both work in a local frame centred between the two bodies (see local_origin),
// so a pair 1e4 from the world origin keeps the digits of a pair at the origin.
//
// Nearly parallel edges: the axis of an edge pair at angle θ has a rounding error
// eps/sin θ, which moves the gap by up to eps·L/sin θ (L the edge length); the
// face of A − B they span is at most L·sin θ wide, so skipping it moves the depth
// by at most that much. Skipping below sin θ = √eps balances the two: in double
// (kParallelSin = 1e-8) the depth is then within 1e-8·L in the worst case and
// within 1e-10·L for sin θ ≥ 1e-6; in long double (kParallelSinReference = 2e-10)
// within 2e-10·L. Exactly parallel edges span no face at all.
#include "core/collision.hpp"

#include <cmath>
#include <limits>
#include <vector>

namespace gacompare::collision {

inline constexpr double kParallelSin = 1e-8;
inline constexpr long double kParallelSinReference = 2e-10L;

// The local frame: midway between the two bodies' positions.
inline Vec3 local_origin(const Placed& a, const Placed& b) { return 0.5 * (a.pose.position + b.pose.position); }

// The exact reference (see above). Throws nothing; any two valid convex meshes.
PairContact sat_reference(const Placed& a, const Placed& b);

// Closest points of the lines p + s·d and q + t·e (not parallel): the midpoint
// of the two, the contact point of an edge–edge contact.
Vec3 edge_edge_midpoint(const Vec3& p, const Vec3& d, const Vec3& q, const Vec3& e);

// Whether the arc of face normals (a, b) of an edge of A and the arc (−c, −d)
// of an edge of B cross on the unit sphere, i.e. the two edges span a face of
// the Minkowski difference A − B. bxa = b × a and dxc = d × c are the edges'
// directions (up to length), which the caller has already.
inline bool spans_minkowski_face(const Vec3& a, const Vec3& b, const Vec3& bxa, const Vec3& c, const Vec3& d,
                                 const Vec3& dxc) {
  // With c, d negated: c and d on opposite sides of the plane of a, b; a and b
  // on opposite sides of the plane of −c, −d; and the two arcs in the same
  // hemisphere (not the antipodal crossing of the two great circles).
  // The first test alone rejects most pairs: the other two products wait for it.
  const double cba = -c.dot(bxa), dba = -d.dot(bxa);
  if (!(cba * dba < 0)) return false;
  const double adc = a.dot(dxc), bdc = b.dot(dxc);
  return adc * bdc < 0 && cba * bdc > 0;
}

// The best axis of each family, in the pair's local frame: the gap (as the
// answer's −depth), the features (face of a, vertex of b; vertex of a, face of
// b; edge of a, edge of b: indices into the meshes' planes, vertices, edges) and
// the unit normal from a towards b.
struct SatAxes {
  struct Axis {
    double gap = -std::numeric_limits<double>::infinity();
    int i = -1, j = -1;
    Vec3 normal = Vec3::Zero();
  };
  Axis face_a, face_b, edge;
};

// The fast path over a backend's view of a placed body. Body provides, in its
// own algebra (traditional/narrowphase.hpp, cga/narrowphase.hpp):
//   const Mesh& mesh();  Vec3 vertex(int i);  Vec3 normal(int plane);  Vec3 centre();
//   double plane_distance(int plane, const Body& other, int vertex)   (> 0 outside)
//   static Vec3 edge_axis(const Vec3& da, const Vec3& db)   (da × db, unnormalised)
//
// early_exit: stop at the first axis that separates the bodies (its gap is
// then the answer's −depth: still a lower bound of the distance, no longer the
// best one). The broadphase-then-narrowphase path and the benchmarks' "sat"
// path use it; the time-of-impact search does not (it needs a depth that is
// continuous in time on both sides of contact).
//
// axes (optional): the best axis of each family, for the contact manifold
// (core/manifold.hpp), which prefers a face to a marginally better edge pair.
// Complete only when the test ran to the end (no early exit).
template <class Body>
PairContact separating_axis(const Body& a, const Body& b, bool early_exit = false, SatAxes* axes = nullptr) {
  PairContact best;
  double gap = -std::numeric_limits<double>::infinity();
  const auto note = [&](SatAxes::Axis& axis, double g, int i, int j, const Vec3& n) {
    if (axes && g > axis.gap) axis = {g, i, j, n};
  };
  // Face axes: the gap is the other body's support point's distance from the face.
  const auto faces = [&](const Body& f, const Body& o, Feature which) {
    const int planes = static_cast<int>(f.mesh().planes().size());
    const int vertices = static_cast<int>(o.mesh().vertices().size());
    for (int k = 0; k < planes; ++k) {
      int arg = 0;
      double lo = f.plane_distance(k, o, 0);
      for (int j = 1; j < vertices; ++j) {
        const double s = f.plane_distance(k, o, j);
        if (s < lo) lo = s, arg = j;
      }
      if (axes) {
        const Vec3 n = f.normal(k);
        if (which == Feature::face_a) note(axes->face_a, lo, k, arg, n);
        else note(axes->face_b, lo, arg, k, Vec3(-n));
      }
      if (lo > gap) {
        gap = lo;
        const Vec3 n = f.normal(k);
        best.normal = which == Feature::face_a ? n : Vec3(-n);
        best.contact = o.vertex(arg) - (0.5 * lo) * n;  // midway between the surfaces
        best.feature = which;
        if (early_exit && gap > 0) return true;
      }
    }
    return false;
  };
  const auto done = [&] {
    best.depth = -gap;
    best.intersect = gap < 0;
    return best;
  };
  if (faces(a, b, Feature::face_a) || faces(b, a, Feature::face_b)) return done();

  // Edge pairs that span a face of A − B. Each body's edges are read once into
  // a flat list (a point, the direction, the two face normals), so the E_a × E_b
  // loop touches contiguous data only.
  struct Edge {
    Vec3 p, d, n0, n1;
  };
  const auto edges_of = [](const Body& body) {
    const auto& e = body.mesh().edges();
    const auto& ep = body.mesh().edge_planes();
    std::vector<Edge> out(e.size());
    for (std::size_t i = 0; i < e.size(); ++i) {
      const Vec3 p = body.vertex(e[i][0]);
      // The triangle of plane ep[i][0] runs the edge from [0] to [1], so the
      // edge direction is n0 × n1 and Gregorius' b × a is −d.
      out[i] = {p, body.vertex(e[i][1]) - p, body.normal(ep[i][0]), body.normal(ep[i][1])};
    }
    return out;
  };
  const std::vector<Edge> ea = edges_of(a), eb = edges_of(b);
  const Vec3 ca = a.centre();
  for (std::size_t i = 0; i < ea.size(); ++i) {
    const Edge& x = ea[i];
    const Vec3 bxa = -x.d;
    for (std::size_t j = 0; j < eb.size(); ++j) {
      const Edge& y = eb[j];
      if (!spans_minkowski_face(x.n0, x.n1, bxa, y.n0, y.n1, Vec3(-y.d))) continue;
      Vec3 axis = Body::edge_axis(x.d, y.d);
      const double len = axis.norm();
      if (!(len > kParallelSin * x.d.norm() * y.d.norm())) continue;
      axis /= len;
      if (axis.dot(x.p - ca) < 0) axis = -axis;  // outward from A
      const double s = axis.dot(y.p - x.p);
      if (axes) note(axes->edge, s, static_cast<int>(i), static_cast<int>(j), axis);
      if (s > gap) {
        gap = s;
        best.normal = axis;
        best.contact = edge_edge_midpoint(x.p, x.d, y.p, y.d);
        best.feature = Feature::edge_edge;
        if (early_exit && gap > 0) return done();
      }
    }
  }
  return done();
}

}  // namespace gacompare::collision
