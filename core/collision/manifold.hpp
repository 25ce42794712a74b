#pragma once
// The contact manifold of two convex polyhedra, written once over a
// backend's Body (traditional/narrowphase.hpp, cga/narrowphase.hpp), which
// supplies the algebra: a point's signed distance from a plane (n·x − d, or
// X·π), the plane through a point with a given normal, and where a segment
// crosses a plane (line–plane intersection, or the meet of the line and the
// plane, §1.6).
//
// Why the report's detector (fig. 7) is not enough. It finds vertices inside
// the other body and edges through its faces. In the commonest contact of all
// — two boxes meeting face to face, edges aligned — every vertex of the
// leading face lies exactly on the other's boundary: on a side face (y = ±h)
// as much as behind the face it entered. §2.4.3's rule takes the face a vertex
// is least deep behind: for a vertex on the side face that is the side face,
// at depth 0, so the contact's normal is perpendicular to the motion, the
// approach speed along it is 0, and the impulse is skipped. The separating-axis
// depth then still says the pair overlaps, so the positional correction shoves
// the struck body along, step after step, and it is never struck. Which of two
// faces at distance 0 and −1e-17 wins is decided by rounding: the two backends
// round differently, and moving one box by 1 mm to the side puts the vertex
// clearly inside (or outside) that side face, which is why an offset flips
// which backend goes wrong. No edge crosses a face either (the edges lie in the
// faces), so nothing else finds the contact.
//
// The manifold instead takes its normal from the axis of minimum penetration
// that the separating-axis test has already found (the only direction that is
// continuous in the configuration), and its points from the features that
// axis belongs to (Box2D's b2ClipPolygons in 2D, Jolt's ManifoldBetweenTwoFaces,
// Bullet's btPolyhedralContactClipping do the same; this is our own):
//   - a face axis: the face is the reference; the incident face is the other
//     body's face most opposed to its normal; the incident polygon is clipped
//     (Sutherland–Hodgman) by the planes through the reference face's edges
//     perpendicular to it, and the points on or below the reference plane are
//     the contacts, each midway between the incident point and its projection,
//     at its own depth;
//   - an edge axis: the closest points of the two edges' lines, one contact.
// A face is preferred to an edge pair, and a's face to b's, unless the other
// is shallower by more than kFacePreference of the depth (plus the touching
// band): near a face–face contact an edge pair's gap can tie with the face's
// to rounding (a box turned by 1e-9 rad), and one edge point under a resting
// box would rock it. More than kMaxManifoldPoints points (two squares turned
// by 45° clip to an octagon) are reduced to the four that span the largest
// area: four points hold a box as well as eight, and cost half the solver
// rows.
#include "core/collision/collision.hpp"
#include "core/collision/separating_axis.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <span>
#include <vector>

namespace gacompare::collision {

inline constexpr int kMaxManifoldPoints = 4;
inline constexpr double kFacePreference = 0.05;

// What a manifold's choices were, for a pair whose contacts are kept between
// detections (core/collision/kept_contacts.hpp): whether it came from a face,
// which face, how near its choices were to changing, and how far above the
// band the lowest clipped point it left out was (both in metres).
struct FaceChoice {
  bool made = false;
  bool ref_is_a = true;
  int face = -1;
  // The two choices as numbers whose signs make them (in metres): a's face
  // or b's (b's if `faces` > 0), and a face or an edge pair (the face if
  // `edge` > 0; +∞ without an edge pair); and how far apart the normals each
  // compares are (what a translation of the bodies changes the number by,
  // per metre).
  double faces = 0, faces_spread = 0;
  double edge = std::numeric_limits<double>::infinity(), edge_spread = 0;
  double left_out = std::numeric_limits<double>::infinity();
  // The contacts' points in the pair's frame (core/collision/narrowphase.hpp:
  // about `origin`), before they are moved to the world's: there they keep
  // the digits that the world's coordinates round off.
  Vec3 origin = Vec3::Zero();
  std::array<Vec3, kMaxManifoldPoints> local{Vec3::Zero(), Vec3::Zero(), Vec3::Zero(), Vec3::Zero()};
};

namespace detail {

// Sutherland–Hodgman against one plane: keeps the part with distance ≤ 0.
template <class Body>
void clip(const std::vector<typename Body::Point>& in, const typename Body::Plane& side,
          std::vector<typename Body::Point>& out) {
  out.clear();
  const std::size_t n = in.size();
  for (std::size_t i = 0; i < n; ++i) {
    const auto& p = in[i];
    const auto& q = in[(i + 1) % n];
    const double dp = Body::distance(side, p), dq = Body::distance(side, q);
    if (dp <= 0) out.push_back(p);
    if ((dp < 0 && dq > 0) || (dp > 0 && dq < 0)) out.push_back(Body::cut(p, dp, q, dq));
  }
}

// At most kMaxManifoldPoints of the contacts c[first..]: the deepest, the
// farthest from it, the one making the largest triangle with those two, and
// the one making the largest triangle on the other side of their line. In
// place: every pair in contact comes through here, so it allocates nothing.
inline void reduce(std::vector<FeatureContact>& out, std::size_t first, const Vec3& n) {
  const std::span<const FeatureContact> c(out.data() + first, out.size() - first);
  if (c.size() <= static_cast<std::size_t>(kMaxManifoldPoints)) return;
  std::size_t i0 = 0, i1 = 0, i2 = 0, i3 = 0;
  for (std::size_t i = 1; i < c.size(); ++i)
    if (c[i].depth > c[i0].depth) i0 = i;
  double best = -1;
  for (std::size_t i = 0; i < c.size(); ++i)
    if (const double d = (c[i].point - c[i0].point).squaredNorm(); d > best) best = d, i1 = i;
  const Vec3 u = c[i1].point - c[i0].point;
  const auto area = [&](std::size_t i) { return n.dot(u.cross(c[i].point - c[i0].point)); };
  double most = 0, least = 0;
  for (std::size_t i = 0; i < c.size(); ++i) {
    const double s = area(i);
    if (s > most) most = s, i2 = i;
    if (s < least) least = s, i3 = i;
  }
  std::array<FeatureContact, kMaxManifoldPoints> kept{c[i0], c[i1]};
  std::size_t count = 2;
  if (most > 0) kept[count++] = c[i2];
  if (least < 0) kept[count++] = c[i3];
  out.resize(first);
  out.insert(out.end(), kept.begin(), kept.begin() + static_cast<long>(count));
}

// Face k of body r is the reference; `r_is_a` says which of the pair it is.
// `left_out` (optional): lowered to the height above the band of each clipped
// point left out for being above it.
template <class Body>
void face_contacts(const Body& r, const Body& i, int k, bool r_is_a, double band, std::vector<FeatureContact>& out,
                   double* left_out = nullptr) {
  using Point = typename Body::Point;
  const Vec3 n = r.normal(k);
  // The incident face: the other body's face most opposed to n.
  const int planes = static_cast<int>(i.mesh().planes().size());
  int f = 0;
  double most = i.normal(0).dot(n);
  for (int j = 1; j < planes; ++j)
    if (const double c = i.normal(j).dot(n); c < most) most = c, f = j;
  // Each thread's clipping polygons, kept between calls (no allocation once grown).
  thread_local std::vector<Point> poly, next;
  poly.clear();
  for (const int v : i.mesh().faces()[f]) poly.push_back(i.vertex_point(v));
  const auto& loop = r.mesh().faces()[k];
  for (std::size_t e = 0; e < loop.size() && !poly.empty(); ++e) {
    const int u = loop[e], w = loop[(e + 1) % loop.size()];
    // (w − u) × n points out of a counter-clockwise face: the side plane's outside.
    const auto side = Body::plane_through(r.vertex_point(u), Body::edge_axis(r.vertex(w) - r.vertex(u), n));
    clip<Body>(poly, side, next);
    poly.swap(next);
  }
  const std::size_t first = out.size();
  const auto reference = r.face_plane(k);
  for (const Point& p : poly) {
    const double s = Body::distance(reference, p);
    if (s > band) {
      if (left_out) *left_out = std::min(*left_out, s - band);
      continue;
    }
    const Vec3 x = Body::position(p) - (0.5 * s) * n;
    bool duplicate = false;  // clipping can return a corner twice (an incident vertex on a side plane)
    for (std::size_t c = first; c < out.size() && !duplicate; ++c) duplicate = (out[c].point - x).norm() <= band;
    if (!duplicate) out.push_back({x, r_is_a ? n : Vec3(-n), -s, r_is_a ? Feature::face_a : Feature::face_b});
  }
  reduce(out, first, n);
}

}  // namespace detail

// The manifold of a pair in contact (the separating-axis test ran to the end:
// `axes` is complete), in the Bodies' frame. `band` is the touching band in
// length units: points up to that far above the reference face still count.
// `choice` (optional) receives what was chosen and how near it was to changing.
template <class Body>
void manifold_contacts(const Body& a, const Body& b, const SatAxes& axes, double band,
                       std::vector<FeatureContact>& out, FaceChoice* choice = nullptr) {
  const auto slack = [&](double gap) { return kFacePreference * std::abs(gap) + band; };
  const bool use_b = axes.face_b.gap > axes.face_a.gap + slack(axes.face_a.gap);
  const SatAxes::Axis& face = use_b ? axes.face_b : axes.face_a;
  if (choice) {
    choice->made = !(axes.edge.i >= 0 && axes.edge.gap > face.gap + slack(face.gap)) &&
                   std::isfinite(axes.face_a.gap) && std::isfinite(axes.face_b.gap);
    choice->ref_is_a = !use_b;
    choice->face = use_b ? face.j : face.i;
    choice->faces = axes.face_b.gap - (axes.face_a.gap + slack(axes.face_a.gap));
    choice->faces_spread = (axes.face_a.normal - axes.face_b.normal).norm();
    if (axes.edge.i >= 0) {
      choice->edge = face.gap + slack(face.gap) - axes.edge.gap;
      choice->edge_spread = (axes.edge.normal - face.normal).norm();
    }
  }
  double* left_out = choice ? &choice->left_out : nullptr;
  if (axes.edge.i >= 0 && axes.edge.gap > face.gap + slack(face.gap)) {
    const auto& ea = a.mesh().edges()[axes.edge.i];
    const auto& eb = b.mesh().edges()[axes.edge.j];
    const Vec3 p = a.vertex(ea[0]), q = b.vertex(eb[0]);
    const Vec3 x = edge_edge_midpoint(p, a.vertex(ea[1]) - p, q, b.vertex(eb[1]) - q);
    out.push_back({x, axes.edge.normal, -axes.edge.gap, Feature::edge_edge});
    return;
  }
  if (use_b) detail::face_contacts(b, a, face.j, false, band, out, left_out);
  else detail::face_contacts(a, b, face.i, true, band, out, left_out);
}

}  // namespace gacompare::collision
