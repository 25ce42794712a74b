#pragma once
// The separating-axis test for convex polyhedra (beyond the report,
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
#include "core/collision/collision.hpp"
#include "core/collision/shape.hpp"

#include <cmath>
#include <limits>
#include <span>
#include <vector>

namespace gacompare::collision {

inline constexpr double kParallelSin = 1e-8;
// From this many edges of b on, edge pairs are found by walking the Gauss map
// (walk_edge below), not by testing every pair (the crossover:
// bench/narrowphase_bench.cpp BM_manifold_boxes, BM_contacts_manifold).
inline constexpr int kWalkEdges = 16;
inline constexpr long double kParallelSinReference = 2e-10L;

// The local frame: midway between the two bodies' positions.
inline Vec3 local_origin(const Vec3& a, const Vec3& b) { return 0.5 * (a + b); }
inline Vec3 local_origin(const Placed& a, const Placed& b) { return local_origin(a.pose.position, b.pose.position); }

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

// The edges of B whose arcs the arc of A's edge x crosses (the pairs that
// span a face of A − B), found by walking the arc across −B's Gauss map
// instead of testing every edge of B (our own; Gregorius tests all pairs).
// −B's map has a region per vertex v of B, the directions under which v is
// B's lowest vertex, bounded by the arcs of the edges at v. The walk starts
// in the region of `from`, B's lowest vertex under x's first face (the face
// query found it), tests the edges at the current vertex for a crossing,
// reports the one it finds (`on_pair(edge)`, true to stop the test) and steps
// across it to the vertex at its other end, until no edge there is crossed:
// the arc has ended in that region. A region is convex, so the arc leaves it
// at most once; and so every edge the arc crosses is met, in order. Returns
// the vertex it ended at (the caller checks that it is a lowest vertex under
// x's second face: otherwise the walk went wrong in a degenerate spot, an arc
// through a vertex of the map, and the caller tests every edge instead), −1
// if it ran longer than B has edges, −2 if on_pair stopped it.
template <class OnPair>
int walk_arc(const Mesh& b, std::span<const ShapeEdge> eb, const ShapeEdge& x, int from, OnPair&& on_pair) {
  const Vec3 bxa = -x.d;
  int v = from, came = -1;
  for (std::size_t steps = 0; steps <= eb.size(); ++steps) {
    const auto edges = b.vertex_edges(v);
    const auto ends = b.neighbours(v);
    int exit = -1;
    for (int k = 0; k < static_cast<int>(edges.size()); ++k) {
      const int e = edges[k];
      if (e != came && spans_minkowski_face(x.n0, x.n1, bxa, eb[e].n0, eb[e].n1, Vec3(-eb[e].d))) {
        exit = k;
        break;
      }
    }
    if (exit < 0) return v;
    if (on_pair(edges[exit])) return -2;
    came = edges[exit];
    v = ends[exit];
  }
  return -1;
}

// Edge i of body a walked across body b's Gauss map (walk_arc), from b's
// lowest vertex under the edge's first face, below[face], and checked where it
// ended against b's lowest vertex under its second face (the same vertex, or
// one as low: a tie). 1: every crossing was met; 0: the walk cannot be
// trusted, test every edge of b; −1: on_pair stopped it.
template <class Body, class OnPair>
int walk_edge(const Body& a, const Body& b, int i, const std::vector<int>& below, OnPair&& on_pair) {
  const auto& faces = a.mesh().edge_planes()[i];
  const int end = walk_arc(b.mesh(), b.shape().edges(), a.shape().edges()[i], below[faces[0]], on_pair);
  if (end == -2) return -1;
  if (end < 0) return 0;
  if (end == below[faces[1]]) return 1;
  const auto plane = a.plane_toward(faces[1], b);
  return Body::distance(plane, b.shape().point(end)) > Body::distance(plane, b.shape().point(below[faces[1]])) ? 0 : 1;
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

// The axis that decided a pair at one detection, tried first at the next
// (temporal coherence; Jolt warm-starts GJK from the last separating
// axis, Box2D keeps its manifolds' features from step to step): a pair that
// stays apart is done after this one axis. Indices as in SatAxes: face_a is
// plane i of a with b's support vertex j (where hill climbing starts next
// time), face_b vertex i of a and plane j of b, edge_edge edges i of a and j
// of b.
struct SatHint {
  Feature feature = Feature::none;
  int i = -1, j = -1;
  bool kept = false;  // written: the answer is the remembered axis's (it still separates)
  bool operator==(const SatHint&) const = default;
};

// The face of f most turned towards o's centre (−1 if none compares): the
// first axis tried for a pair with no remembered one, as it separates most
// pairs that are apart (separating_axis, face_gap).
template <class Body>
int facing(const Body& f, const Body& o) {
  const Vec3 towards = o.centre() - f.centre();
  int k = -1;
  double most = -std::numeric_limits<double>::infinity();
  for (int i = 0; i < static_cast<int>(f.mesh().planes().size()); ++i)
    if (const double c = f.normal(i).dot(towards); c > most) most = c, k = i;
  return k;
}

// The fast path over two bodies of a pair (core/collision/shape.hpp's BodyView over a
// backend's algebra: traditional/narrowphase.hpp, cga/narrowphase.hpp).
//
// early_exit: stop at the first axis that separates the bodies (its gap is
// then the answer's −depth: still a lower bound of the distance, no longer the
// best one). The broadphase-then-narrowphase path and the benchmarks' "sat"
// path use it; the time-of-impact search does not (it needs a depth that is
// continuous in time on both sides of contact).
//
// axes (optional): the best axis of each family, for the contact manifold
// (core/collision/manifold.hpp), which prefers a face to a marginally better edge pair.
// Complete only when the test ran to the end (no early exit).
//
// hint (optional): read with early_exit, where the remembered axis is tried
// first (without one, a guess: below); if it separates, that is the answer.
// Otherwise the test runs from scratch, so that a pair in contact gets exactly
// the answer it gets without a hint (the first axis is tried twice: one axis,
// against the test's hundreds). Written always: the axis of the answer (the
// separating axis found, or the best one). A pair apart gets a separating
// axis either way, not always the same one: its depth is then only a bound.
template <class Body>
PairContact separating_axis(const Body& a, const Body& b, bool early_exit = false, SatAxes* axes = nullptr,
                            SatHint* hint = nullptr) {
  PairContact best;
  double gap = -std::numeric_limits<double>::infinity();
  SatHint found;
  const auto note = [&](SatAxes::Axis& axis, double g, int i, int j, const Vec3& n) {
    if (axes && g > axis.gap) axis = {g, i, j, n};
  };
  const auto done = [&] {
    best.depth = -gap;
    best.intersect = gap < 0;
    if (hint) *hint = found;
    return best;
  };
  // Face k of f: the gap is o's support point's distance from the face, found
  // from `arg` (core/collision/shape.hpp), which then holds the support. True when the
  // test may stop.
  const auto face = [&](const Body& f, const Body& o, Feature which, int k, int& arg) {
    const auto [lowest, j] = o.shape().lowest(f.plane_toward(k, o), arg);
    const double lo = lowest * o.shape().unit();
    arg = j;
    if (axes) {
      const Vec3 n = f.normal(k);
      if (which == Feature::face_a) note(axes->face_a, lo, k, j, n);
      else note(axes->face_b, lo, j, k, Vec3(-n));
    }
    if (!(lo > gap)) return false;
    gap = lo;
    const Vec3 n = f.normal(k);
    best.normal = which == Feature::face_a ? n : Vec3(-n);
    best.contact = o.vertex(j) - (0.5 * lo) * n;  // midway between the surfaces
    best.feature = which;
    found = which == Feature::face_a ? SatHint{which, k, j} : SatHint{which, j, k};
    return early_exit && gap > 0;
  };
  // The walk over b's edges needs b's support under each face of a: kept here
  // (per thread, reused: no allocation once grown).
  thread_local std::vector<int> below;
  const auto faces = [&](const Body& f, const Body& o, Feature which) {
    const int planes = static_cast<int>(f.mesh().planes().size());
    if (which == Feature::face_a && static_cast<int>(below.size()) < planes) below.resize(planes);
    int arg = 0;  // hill climbing starts from the last face's support
    for (int k = 0; k < planes; ++k) {
      const bool stop = face(f, o, which, k, arg);
      if (which == Feature::face_a) below[k] = arg;
      if (stop) return true;
    }
    return false;
  };
  // Edge pairs that span a face of A − B; each body's edges are read relative
  // to its own position (ShapeEdge), and `q` is x's point in b's frame.
  const Vec3 delta = b.offset() - a.offset(), ca = a.shape().centre();
  // edge_gap: a pair known to span a face; edge: any pair.
  const auto edge_gap = [&](int i, int j, const ShapeEdge& x, const Vec3& q, const ShapeEdge& y) {
    Vec3 axis = Body::edge_axis(x.d, y.d);
    const double len2 = axis.squaredNorm();  // squared: no square roots for the edges' lengths
    if (!(len2 > kParallelSin * kParallelSin * x.d.squaredNorm() * y.d.squaredNorm())) return false;
    axis /= std::sqrt(len2);
    if (axis.dot(x.p - ca) < 0) axis = -axis;  // outward from A
    const double s = axis.dot(y.p - q);
    if (axes) note(axes->edge, s, i, j, axis);
    if (!(s > gap)) return false;
    gap = s;
    best.normal = axis;
    best.contact = edge_edge_midpoint(Vec3(x.p + a.offset()), x.d, Vec3(y.p + b.offset()), y.d);
    best.feature = Feature::edge_edge;
    found = {Feature::edge_edge, i, j};
    return early_exit && gap > 0;
  };
  const auto edge = [&](int i, int j, const ShapeEdge& x, const Vec3& q, const ShapeEdge& y) {
    return spans_minkowski_face(x.n0, x.n1, Vec3(-x.d), y.n0, y.n1, Vec3(-y.d)) && edge_gap(i, j, x, q, y);
  };

  // With early_exit, one axis first: the pair's remembered one, or else the
  // face of a most turned towards b's centre, which separates most pairs that
  // are apart (bench/narrowphase_bench.cpp BM_pair_apart_cached).
  const bool remembered = hint && hint->feature != Feature::none;
  SatHint first = remembered ? *hint : SatHint{};
  if (early_exit && !remembered)
    if (const int k = facing(a, b); k >= 0) first = {Feature::face_a, k, 0};
  if (early_exit && first.feature != Feature::none) {
    const SatHint h = first;
    const int pa = static_cast<int>(a.mesh().planes().size()), pb = static_cast<int>(b.mesh().planes().size());
    const int va = static_cast<int>(a.mesh().vertices().size()), vb = static_cast<int>(b.mesh().vertices().size());
    const int na = static_cast<int>(a.mesh().edges().size()), nb = static_cast<int>(b.mesh().edges().size());
    const auto in = [](int x, int n) { return x >= 0 && x < n; };
    bool apart = false;
    if (h.feature == Feature::face_a && in(h.i, pa) && in(h.j, vb)) {
      int arg = h.j;
      apart = face(a, b, Feature::face_a, h.i, arg);
    } else if (h.feature == Feature::face_b && in(h.i, va) && in(h.j, pb)) {
      int arg = h.i;
      apart = face(b, a, Feature::face_b, h.j, arg);
    } else if (h.feature == Feature::edge_edge && in(h.i, na) && in(h.j, nb)) {
      const ShapeEdge& x = a.shape().edges()[h.i];
      apart = edge(h.i, h.j, x, Vec3(x.p - delta), b.shape().edges()[h.j]);
    }
    found.kept = remembered;
    if (apart) return done();
    best = {};
    gap = -std::numeric_limits<double>::infinity();
    found = {};
    if (axes) *axes = {};
  }

  if (faces(a, b, Feature::face_a) || faces(b, a, Feature::face_b)) return done();
  const std::span<const ShapeEdge> ea = a.shape().edges();
  const std::span<const ShapeEdge> eb = b.shape().edges();
  // Every vertex of b a corner (its regions tile the sphere), and enough edges
  // for the walk to pay: testing a box's 12 edges is cheaper than walking
  // them, and boxes meet face to face, where their maps share arcs and every
  // walk ends where it cannot be trusted.
  const bool walk = b.mesh().corners_only() && static_cast<int>(eb.size()) >= kWalkEdges;
  // The first crossing test below reads each of b's face normals along x.d,
  // and every face borders several edges (a box's, four): the products are
  // taken once per face here, not twice per edge of b. y.n0 and y.n1 are
  // copies of these normals (Shape::build_edges), so each product, and each
  // answer, is the one the test took per edge.
  const auto& sides = b.mesh().edge_planes();
  const int pb = static_cast<int>(b.mesh().planes().size());
  thread_local std::vector<Vec3> normal_b;
  thread_local std::vector<double> along;
  bool normals = false;  // normal_b filled (after a walk, only where one cannot be trusted)
  for (int i = 0; i < static_cast<int>(ea.size()); ++i) {
    const ShapeEdge& x = ea[i];
    const Vec3 q = x.p - delta;
    if (walk) {
      const int walked = walk_edge(a, b, i, below, [&](int j) { return edge(i, j, x, q, eb[j]); });
      if (walked < 0) return done();
      if (walked > 0) continue;
    }
    if (!normals) {
      normal_b.resize(static_cast<std::size_t>(pb)), along.resize(static_cast<std::size_t>(pb));
      for (int k = 0; k < pb; ++k) normal_b[static_cast<std::size_t>(k)] = b.normal(k);
      normals = true;
    }
    for (int k = 0; k < pb; ++k) along[static_cast<std::size_t>(k)] = normal_b[static_cast<std::size_t>(k)].dot(x.d);
    for (int j = 0; j < static_cast<int>(eb.size()); ++j) {
      // spans_minkowski_face here, where it rejects most pairs without a
      // call, with its signs taken out (exact: a negation rounds nothing):
      // −c·(b × a) = c·x.d with b × a = −x.d, and a·(d × c) = −a·y.d with
      // d × c = −y.d. Nearly aligned boxes (a stack) pass the first test
      // about half the time, the whole test far less often.
      const ShapeEdge& y = eb[j];
      const auto& side = sides[static_cast<std::size_t>(j)];
      const double cba = along[static_cast<std::size_t>(side[0])];
      if (!(cba * along[static_cast<std::size_t>(side[1])] < 0)) continue;
      const double ady = x.n0.dot(y.d), bdy = x.n1.dot(y.d);
      if (!(ady * bdy < 0 && cba * bdy < 0)) continue;
      if (edge_gap(i, j, x, q, y)) return done();
    }
  }
  return done();
}

// The largest gap along the two bodies' face normals: a lower bound of their
// distance (≤ 0 when no face separates them) that no remembered axis changes,
// for the islands' links (core/collision/collisions.hpp, apart_beyond_reach). Every face's
// support query, none of the edge pairs' (the costly part of the whole test).
// With `enough`, it stops at the first gap above it:
// whether some face normal separates the pair by more than `enough` is then
// its answer (> enough or not), found in any order; each body's face most
// turned towards the other's centre goes first, and usually decides.
template <class Body>
double face_gap(const Body& a, const Body& b, double enough = std::numeric_limits<double>::infinity()) {
  double gap = -std::numeric_limits<double>::infinity();
  const auto face = [&](const Body& f, const Body& o, int k, int& arg) {
    const auto [lowest, j] = o.shape().lowest(f.plane_toward(k, o), arg);
    gap = std::max(gap, lowest * o.shape().unit());
    arg = j;  // the next face's support is near this one's: the climb starts there
    return gap > enough;
  };
  const int ka = facing(a, b), kb = facing(b, a);
  int arg_a = 0, arg_b = 0;  // supports of b under a's faces, of a under b's
  if ((ka >= 0 && face(a, b, ka, arg_b)) || (kb >= 0 && face(b, a, kb, arg_a))) return gap;
  for (int k = 0; k < static_cast<int>(a.mesh().planes().size()); ++k)
    if (k != ka && face(a, b, k, arg_b)) return gap;
  for (int k = 0; k < static_cast<int>(b.mesh().planes().size()); ++k)
    if (k != kb && face(b, a, k, arg_a)) return gap;
  return gap;
}

}  // namespace gacompare::collision
