#pragma once
// The narrowphase for a pair of convex polyhedra (§2.4.2–2.4.4,
// fig. 7), written once over a backend's Body (traditional/narrowphase.hpp,
// cga/narrowphase.hpp), which supplies the algebra: where a point is relative
// to a face, the axis of two edges, a segment through one of its triangles.
//
// Two methods:
//   report: the report's detector (fig. 7). Every vertex of one body tested
//     against the other's faces (§2.4.3) and every edge of one through the
//     other's triangles (§2.4.4); each finding is a FeatureContact (the input
//     of the impulse response), and the pair intersects iff there is one.
//     The minimum depth and its normal, which the report does not give, come
//     from the separating-axis fast path (core/collision/separating_axis.hpp).
//   sat: the separating-axis fast path alone (yes/no, depth, normal, no
//     feature contacts), stopping at the first separating axis.
//   manifold: the separating-axis test, then the contact manifold of its axis
//     of minimum penetration (core/collision/manifold.hpp: the reference face clipped
//     against the incident face, or the closest points of two edges), for
//     pairs within the touching band. Robust where fig. 7 is not: faces
//     meeting faces, edges on edges, vertices on edges (see manifold.hpp).
//   sat_then_manifold: what the simulation runs by default (the collisions
//     effect's method "manifold"); the same, stopping at a separating axis.
//   sat_then_report: the simulation with method "report". The fast path first, stopping
//     at a separating axis; the report's detector only for the pairs it finds
//     within the touching band of contact (most broadphase pairs are apart,
//     and the detector costs edges × triangles). `gacompare collide` and the
//     tests run `report` so that the detector's yes/no is checked on every
//     pair, apart ones included.
// The report's features find every intersection of two closed convex
// polyhedra: if no vertex of either is inside the other, their boundaries
// still cross, and where two boundaries cross an edge of one passes through a
// face of the other.
#include "core/collision/collision.hpp"
#include "core/collision/manifold.hpp"
#include "core/collision/round.hpp"
#include "core/collision/separating_axis.hpp"

#include <algorithm>
#include <set>
#include <utility>
#include <vector>

namespace gacompare::collision {

enum class Method : std::uint8_t { report, sat, sat_then_report, manifold, sat_then_manifold };

namespace detail {

// §2.4.3: the face of `f` the vertex j of `o` is least deep behind, and how far
// (the largest signed distance: < 0 inside, −depth). The vertex is moved into
// f's own frame once, then tested against each of f's planes there.
template <class Body>
std::pair<double, int> least_deep_face(const Body& f, const Body& o, int j) {
  const int planes = static_cast<int>(f.mesh().planes().size());
  const auto x = f.point_from(o, j);
  double best = Body::distance(f.shape().plane(0), x);
  int arg = 0;
  for (int k = 1; k < planes; ++k) {
    const double s = Body::distance(f.shape().plane(k), x);
    if (s > best) best = s, arg = k;
  }
  return {best * f.shape().unit(), arg};
}

// §2.4.3 for every vertex of `o` against `f`, once: each is needed by the
// vertex test and again by the edge test below.
template <class Body>
std::vector<std::pair<double, int>> vertex_depths(const Body& f, const Body& o) {
  std::vector<std::pair<double, int>> out(o.mesh().vertices().size());
  for (int j = 0; j < static_cast<int>(out.size()); ++j) out[j] = least_deep_face(f, o, j);
  return out;
}

// Vertices of `o` inside `f` (§2.4.3): the contact point midway between the
// vertex and the face it is least deep behind, that face's normal. Inside is
// the report's rule as it states it, "no dot product positive", so a vertex on
// the surface counts (depth 0): two equal cubes side by side and overlapping
// have every vertex on the other's edges and faces, and a strict test would
// find nothing there although they overlap by a finite depth. The least-deep
// face is the report's normal; it is only the minimum-depth direction when the
// vertex is near that face (the separating-axis depth does not rely on it).
template <class Body>
void vertices_inside(const Body& f, const Body& o, const std::vector<std::pair<double, int>>& depth, bool f_is_a,
                     std::vector<FeatureContact>& out) {
  for (int j = 0; j < static_cast<int>(depth.size()); ++j) {
    const auto [s, k] = depth[j];
    if (!(s <= 0)) continue;
    const Vec3 n = f.normal(k);
    out.push_back({o.vertex(j) - (0.5 * s) * n, f_is_a ? n : Vec3(-n), -s, f_is_a ? Feature::face_a : Feature::face_b});
  }
}

// §2.4.4: edges of `s` through triangles of `t`, "not due to a vertex entering
// the other body" (fig. 7): an edge with an end inside t is already a
// vertex–face contact, and pairing it with the nearest edge of the face it
// crosses would invent an edge–edge contact with a wrong normal (a cube's edge
// dipping into a large slab is nowhere near the slab's edges). For the rest,
// the crossing found is an edge of s through a face of t, but the contact is
// an edge–edge one (fig. 10): the
// edge of that face nearest the crossing point is taken as the one crossed
// (the report reflects the point in each side's line and compares; the
// distance to the line is the same number) and the normal is the two edges'
// common normal, outward from a. Like the report (fn 30) this can pick the
// wrong edge when the face is as small as the penetration. Pairs (edge of a,
// edge of b) are reported once.
template <class Body>
void edges_through_faces(const Body& a, const Body& b, const Body& s, const Body& t,
                         const std::vector<std::pair<double, int>>& s_depth, bool s_is_a,
                         std::set<std::pair<int, int>>& seen, std::vector<FeatureContact>& out) {
  const auto& se = s.mesh().edges();
  const auto& te = t.mesh().edges();
  const auto& tris = t.mesh().triangles();
  const auto& tplane = t.mesh().triangle_plane();
  const auto& tedge_planes = t.mesh().edge_planes();
  for (int i = 0; i < static_cast<int>(se.size()); ++i) {
    if (s_depth[se[i][0]].first <= 0 || s_depth[se[i][1]].first <= 0) continue;
    // The edge's ends in t's own frame and unit, where t's triangles are prepared.
    const auto l0 = t.point_from(s, se[i][0]), l1 = t.point_from(s, se[i][1]);
    for (int k = 0; k < static_cast<int>(tris.size()); ++k) {
      const auto hit = t.shape().triangle(k).through(l0, l1);
      if (!hit) continue;
      const Vec3 point = hit->point * t.shape().unit();  // about t's position, in metres
      // The nearest feature edge of the face (polygon) this triangle belongs to.
      int j = -1;
      double nearest = 0;
      for (int e = 0; e < static_cast<int>(te.size()); ++e) {
        if (tedge_planes[e][0] != tplane[k] && tedge_planes[e][1] != tplane[k]) continue;
        const Vec3 p = t.shape().vertex(te[e][0]), d = t.shape().vertex(te[e][1]) - p;
        const double dist2 = (point - p).cross(d).squaredNorm() / d.squaredNorm();
        if (j < 0 || dist2 < nearest) nearest = dist2, j = e;
      }
      if (j < 0) continue;
      const int ia = s_is_a ? i : j, ib = s_is_a ? j : i;
      if (!seen.insert({ia, ib}).second) continue;
      const Vec3 a0 = a.vertex(a.mesh().edges()[ia][0]), da = a.vertex(a.mesh().edges()[ia][1]) - a0;
      const Vec3 b0 = b.vertex(b.mesh().edges()[ib][0]), db = b.vertex(b.mesh().edges()[ib][1]) - b0;
      Vec3 axis = Body::edge_axis(da, db);
      const double len = axis.norm();
      if (!(len > kParallelSin * da.norm() * db.norm())) continue;  // parallel edges: faces and vertices decide
      axis /= len;
      if (axis.dot(a0 - a.centre()) < 0) axis = -axis;
      out.push_back({edge_edge_midpoint(a0, da, b0, db), axis, axis.dot(a0 - b0), Feature::edge_edge});
    }
  }
}

}  // namespace detail

// Fig. 7's detector: every FeatureContact of the pair, in the Body frame.
template <class Body>
void report_contacts(const Body& a, const Body& b, std::vector<FeatureContact>& out) {
  const auto b_in_a = detail::vertex_depths(a, b), a_in_b = detail::vertex_depths(b, a);
  detail::vertices_inside(a, b, b_in_a, true, out);
  detail::vertices_inside(b, a, a_in_b, false, out);
  std::set<std::pair<int, int>> seen;
  detail::edges_through_faces(a, b, a, b, a_in_b, true, seen, out);
  detail::edges_through_faces(a, b, b, a, b_in_a, false, seen, out);
}

// The whole narrowphase for two bodies at their shapes' poses (core/collision/shape.hpp:
// each body's geometry built once per detection); points come back in world
// coordinates. `contacts` (optional) receives the feature contacts of the
// method; `hint` (optional) the pair's axis from its last detection, tried
// first by the methods that stop at a separating axis, and the axis of this
// answer afterwards (core/collision/separating_axis.hpp); `choice` (optional)
// what a manifold's face choice was (core/collision/kept_contacts.hpp), left
// unmade for a round pair, an edge contact or another method.
template <class Body>
PairContact narrowphase(const typename Body::Shape& sa, const typename Body::Shape& sb, Method method,
                        std::vector<FeatureContact>* contacts = nullptr, SatHint* hint = nullptr,
                        FaceChoice* choice = nullptr) {
  const Vec3 origin = local_origin(sa.position(), sb.position());
  const Body A(sa, sa.position() - origin), B(sb, sb.position() - origin);
  const double band = kTouchingBand * pair_scale(sa.mesh(), sb.mesh());
  if (round_pair(A, B)) {
    // Every method gives a round pair the same exact answer (core/collision/round.hpp).
    std::vector<FeatureContact>* found = method == Method::sat ? nullptr : contacts;
    const std::size_t first = found ? found->size() : 0;
    PairContact result = round_narrowphase(A, B, band, found);
    if (found)
      for (std::size_t i = first; i < found->size(); ++i) (*found)[i].point += origin;
    result.contact += origin;
    return result;
  }
  if (method == Method::manifold || method == Method::sat_then_manifold) {
    SatAxes axes;
    const bool early = method == Method::sat_then_manifold;
    PairContact result = separating_axis(A, B, early, &axes, hint);
    if (result.depth >= -band) {
      // Within the band: an early exit (at a gap > 0) left the axes incomplete.
      if (result.depth < 0 && early) result = separating_axis(A, B, false, &(axes = {}), hint);
    }
    // Contacts for a pair overlapping or touching (the whole test's gap within
    // the band), never for one apart: whether the test stopped early, and at
    // which axis, then cannot change what a pair reports.
    if (result.depth >= -band) {
      std::vector<FeatureContact> local;
      std::vector<FeatureContact>& found = contacts ? *contacts : local;
      const std::size_t first = found.size();
      manifold_contacts(A, B, axes, band, found, choice);
      if (choice && choice->made && found.size() - first <= choice->local.size()) {
        choice->origin = origin;
        for (std::size_t i = first; i < found.size(); ++i) choice->local[i - first] = found[i].point;
      } else if (choice) {
        choice->made = false;
      }
      for (std::size_t i = first; i < found.size(); ++i) found[i].point += origin;
    }
    result.contact += origin;
    return result;
  }
  PairContact result = separating_axis(A, B, method != Method::report, nullptr, hint);
  result.contact += origin;
  if (method == Method::sat_then_report && result.depth < -band) return result;
  if (method != Method::sat) {
    std::vector<FeatureContact> local;
    std::vector<FeatureContact>& found = contacts ? *contacts : local;
    const std::size_t first = found.size();
    report_contacts(A, B, found);
    for (std::size_t i = first; i < found.size(); ++i) found[i].point += origin;
    result.intersect = found.size() > first;
  }
  return result;
}

// The same for two placed bodies, their geometry built for this pair alone.
template <class Body>
PairContact narrowphase(const Placed& a, const Placed& b, Method method, std::vector<FeatureContact>* contacts = nullptr) {
  const typename Body::Shape sa(a), sb(b);
  return narrowphase<Body>(sa, sb, method, contacts);
}

}  // namespace gacompare::collision
