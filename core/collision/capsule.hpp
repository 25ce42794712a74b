#pragma once
// Capsules: the points within r of a segment (core/model/mesh.hpp
// make_capsule), against a sphere, a capsule or a convex polyhedron, written
// once over a backend's BodyView like the spheres (core/collision/round.hpp, which
// includes this file after its sphere functions and dispatches to it). The
// answer is a round pair's: the exact signed distance as −depth, the unit
// normal from a towards b, the point midway between the surfaces.
//
// Every pair reduces to the segment's closest point(s) to the other body; a
// capsule of radius r is then the ball of radius r about that point.
//   - Capsule–sphere: the segment's point nearest the centre (the projection
//     clamped to the ends), then sphere–sphere.
//   - Capsule–capsule: the segments' closest points (Ericson, Real-Time
//     Collision Detection §5.1.9: the lines' closest points, then clamped to
//     the segments, the other parameter re-projected), then sphere–sphere.
//     Better than the textbook's ratio (b f − c e)/(a e − b²): its numerator and
//     denominator lose every digit for segments turned by 1e-9 (a e − b² ≈
//     1e-18 from numbers ≈ 1); by Lagrange's identity the same ratio is
//     n·(d2 × w)/n·n with n = d1 × d2, whose components keep their relative
//     precision, so the crossing of near-parallel segments is found to
//     rounding. Parallel segments (sin θ < 1e-14, where any choice moves the
//     distance by < 1e-14 of a length) have a line of closest points where
//     their projections overlap: the midpoint of the overlap is taken, the
//     one choice that does not depend on which end is called first and that
//     moves continuously as the overlap does; it is also the centre of a
//     uniform line contact, so one impulse there gives no spurious torque.
//   - Capsule–polyhedron: whether the segment meets the polyhedron (clipped
//     against every face plane, Cyrus–Beck). If not, the distance is the least
//     of each end's distance (core/collision/round.hpp point_polyhedron: face, edge or
//     vertex) and of the segment's distance to each feature edge: a closest
//     point inside the segment lies over a face interior only when the
//     segment is parallel to it, and then either both ends are over the
//     face too or the segment crosses over one of its edges, at the same
//     distance. If it meets it, the penetration depth is the segment's (the
//     shortest translation that clears it: the least overlap over the
//     polyhedron's face normals and its edges × the segment, the facets of
//     their Minkowski difference) plus r.
//
// Contacts for the response, within the touching band: a capsule lying along
// a face (or along another capsule) touches along a line, and one point there
// lets it rock. So the segment is clipped to the prism of the face most
// aligned with the normal (or to the other segment's projection), and when
// both ends of that piece are within the band, each end is a contact at its
// own depth; otherwise the one exact contact. A piece no longer than the
// band is a point (crossed segments, a capsule standing on its end). A
// segment turned by 1e-9 on a face of a unit body keeps both ends inside the
// 1e-9 band.
//
// What each algebra costs. The parameters along the segments are Euclidean
// ratios in both backends (the conformal projection of a point on the line
// X0 ∧ X1 ∧ n costs a 5D outer product and its inverse for one scalar). The
// cross products n = d1 × d2 are edge_axis: d1 × d2, or the dual (d1 ∧ d2)*
// of Cl(3,0)'s outer product. Distances are the algebra's: the closest
// points' separation as centre_distance2 of the two balls ((c1 − c2)², or
// (S1 − S2)² of dual spheres), a point's from a polyhedron edge as distance2
// (|x − y|², or −2 X·Y), an end's from a face plane as distance (n·x − d, or
// X·π) — once per end per face, the clipping reading those same numbers.
#include "core/collision/collision.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

namespace gacompare::collision::detail {

// sin²θ below which two directions count as parallel (see the top).
inline constexpr double kParallel2 = 1e-28;

// A unit vector perpendicular to u ≠ 0, the same for the same u.
inline Vec3 perpendicular(const Vec3& u) {
  const Vec3 m = u.cwiseAbs();
  const Vec3 least = m.x() <= m.y() && m.x() <= m.z() ? Vec3::UnitX() : m.y() <= m.z() ? Vec3::UnitY() : Vec3::UnitZ();
  return u.cross(least).normalized();
}

// The parameter of x's nearest point on the segment p0 + s d, s ∈ [0, 1].
inline double segment_parameter(const Vec3& x, const Vec3& p0, const Vec3& d) {
  const double dd = d.squaredNorm();
  return dd > 0 ? std::clamp((x - p0).dot(d) / dd, 0.0, 1.0) : 0.0;
}

// The closest points p0 + s d1 and q0 + t d2 of two segments (top of the file).
struct SegmentParameters {
  double s = 0, t = 0;
};
template <class A>
SegmentParameters closest_segment_parameters(const Vec3& p0, const Vec3& d1, const Vec3& q0, const Vec3& d2) {
  const double a = d1.squaredNorm(), e = d2.squaredNorm();
  if (a == 0) return {0, segment_parameter(p0, q0, d2)};
  if (e == 0) return {segment_parameter(q0, p0, d1), 0};
  const Vec3 w = p0 - q0;
  const Vec3 n = A::edge_axis(d1, d2);
  const double nn = n.squaredNorm();
  double s = 0;
  if (nn > kParallel2 * a * e) {
    s = std::clamp(n.dot(A::edge_axis(d2, w)) / nn, 0.0, 1.0);
  } else {
    // b's ends on a's line; the midpoint of the overlap with [0, 1], else the nearer end.
    const double s0 = -w.dot(d1) / a, s1 = s0 + d1.dot(d2) / a;
    const double lo = std::max(0.0, std::min(s0, s1)), hi = std::min(1.0, std::max(s0, s1));
    s = lo <= hi ? 0.5 * (lo + hi) : (std::max(s0, s1) < 0 ? 0.0 : 1.0);
  }
  const double u = (w + s * d1).dot(d2) / e;  // P(s)'s parameter on b's line
  if (u >= 0 && u <= 1) return {s, u};
  const double t = std::clamp(u, 0.0, 1.0);
  return {segment_parameter(q0 + t * d2, p0, d1), t};
}

// A capsule's segment in the pair's frame.
template <class Body>
struct Segment {
  Vec3 p0, d;
  explicit Segment(const Body& c) : p0(c.capsule_end(0)), d(c.capsule_end(1) - c.capsule_end(0)) {}
  Vec3 at(double s) const { return p0 + s * d; }
};

// Balls of radii ra, rb about pa and pb, by the algebra's sphere separation;
// `fallback` the normal when the centres coincide.
template <class A>
PairContact balls(const Vec3& pa, double ra, const Vec3& pb, double rb, const Vec3& fallback, Feature f) {
  const double d = std::sqrt(std::max(0.0, A::centre_distance2(A::sphere(pa, ra), A::sphere(pb, rb))));
  const Vec3 n = d > 0 ? Vec3((pb - pa) / d) : fallback;
  return round_contact(d - ra - rb, n, pa + ra * n, f);
}

inline void push(std::vector<FeatureContact>* out, const PairContact& c) {
  if (out) out->push_back({c.contact, c.normal, c.depth, c.feature});
}

// A line contact (top of the file): the piece [lo, hi] of a segment of this
// length, `end(t)` the contact at parameter t. Both ends go to `contacts`
// when the piece is longer than the band (a shorter one is a point) and
// both are within the band; returns whether they did.
template <class End>
bool line_contacts(double lo, double hi, double length, double band, std::vector<FeatureContact>* contacts, const End& end) {
  if (!((hi - lo) * length > band)) return false;
  const PairContact e0 = end(lo);
  if (e0.depth < -band) return false;
  const PairContact e1 = end(hi);
  if (e1.depth < -band) return false;
  push(contacts, e0), push(contacts, e1);
  return true;
}

// Capsule a against a ball (sphere b of radius rb about c); a centre on the
// segment is pushed out across it.
template <class Body>
PairContact capsule_ball(const Body& a, const Vec3& c, double rb) {
  using A = typename Body::Algebra;
  const Segment<Body> sa(a);
  return balls<A>(sa.at(segment_parameter(c, sa.p0, sa.d)), a.shape().radius(), c, rb, perpendicular(sa.d),
                  Feature::face_a);
}

template <class Body>
PairContact capsule_capsule(const Body& a, const Body& b, double band, std::vector<FeatureContact>* contacts) {
  using A = typename Body::Algebra;
  const Segment<Body> sa(a), sb(b);
  const double ra = a.shape().radius(), rb = b.shape().radius();
  const auto [s, t] = closest_segment_parameters<A>(sa.p0, sa.d, sb.p0, sb.d);
  // Crossing segments: out along d_a × d_b (their common perpendicular), towards b's side.
  Vec3 fallback = A::edge_axis(sa.d, sb.d);
  fallback = fallback.squaredNorm() > kParallel2 * sa.d.squaredNorm() * sb.d.squaredNorm() ? Vec3(fallback.normalized())
                                                                                             : perpendicular(sa.d);
  if (fallback.dot(b.centre() - a.centre()) < 0) fallback = -fallback;
  const PairContact c = balls<A>(sa.at(s), ra, sb.at(t), rb, fallback, Feature::edge_edge);
  if (!contacts || c.depth < -band) return c;
  // Along each other: the ends of b's projection on a, when both are within the band.
  const double a2 = sa.d.squaredNorm();
  const double s0 = (sb.p0 - sa.p0).dot(sa.d) / a2, s1 = s0 + sb.d.dot(sa.d) / a2;
  const double lo = std::max(0.0, std::min(s0, s1)), hi = std::min(1.0, std::max(s0, s1));
  if (!line_contacts(lo, hi, std::sqrt(a2), band, contacts, [&](double e) {
        const Vec3 p = sa.at(e);
        return balls<A>(p, ra, sb.at(segment_parameter(p, sb.p0, sb.d)), rb, c.normal, Feature::edge_edge);
      }))
    push(contacts, c);
  return c;
}

// Capsule c against a convex polyhedron p (top of the file); the normal out of p.
template <class Body>
PairContact capsule_polyhedron_outward(const Body& c, const Body& p, bool p_is_a, double band,
                                       std::vector<FeatureContact>* contacts) {
  using A = typename Body::Algebra;
  const auto& shape = p.shape();
  const Mesh& mesh = p.mesh();
  const double unit = shape.unit(), r = c.shape().radius();
  const Segment<Body> seg(c);
  const auto x0 = p.local_point(seg.p0), x1 = p.local_point(seg.at(1));  // p's own frame and unit
  const Vec3 y0 = A::position(x0), dy = A::position(x1) - y0;
  const int faces = static_cast<int>(mesh.planes().size());
  thread_local std::vector<double> d0, d1;
  d0.resize(static_cast<std::size_t>(faces)), d1.resize(static_cast<std::size_t>(faces));
  double enter = 0, leave = 1;  // the piece of the segment behind every face plane
  for (int k = 0; k < faces; ++k) {
    d0[k] = A::distance(shape.plane(k), x0), d1[k] = A::distance(shape.plane(k), x1);
    if (d0[k] > 0 && d1[k] > 0) enter = 2;
    else if (d0[k] > 0) enter = std::max(enter, d0[k] / (d0[k] - d1[k]));
    else if (d1[k] > 0) leave = std::min(leave, d0[k] / (d0[k] - d1[k]));
  }
  const Feature face = p_is_a ? Feature::face_a : Feature::face_b;
  // Candidates within rounding of the best are ties, kept in the order tried
  // (ends, then edges; faces, then edges), so that a segment parallel to a
  // face or an edge, whose closest points are a piece of it, gets the same
  // point and axis in both backends.
  const double tie = 1e-3 * band;
  PointNearest q;  // of the segment point `at` (pair frame)
  Vec3 at = Vec3::Zero();
  if (enter > leave) {
    // Apart: the ends, then every feature edge against the segment.
    q = point_polyhedron(p, seg.p0, p_is_a), at = seg.p0;
    const PointNearest q1 = point_polyhedron(p, seg.at(1), p_is_a);
    if (q1.gap_to_p < q.gap_to_p - tie) q = q1, at = seg.at(1);
    for (const auto& e : mesh.edges()) {
      const Vec3 v0 = A::position(shape.point(e[0])), dv = A::position(shape.point(e[1])) - v0;
      const auto [s, t] = closest_segment_parameters<A>(y0, dy, v0, dv);
      const Vec3 ys = y0 + s * dy, vt = v0 + t * dv;
      const double gap = std::sqrt(A::distance2(A::lift(ys), A::lift(vt))) * unit;
      if (gap < q.gap_to_p - tie) {
        at = seg.at(s);
        q = {gap, Vec3((ys - vt).normalized()), at - gap * Vec3((ys - vt).normalized()), Feature::edge_edge};
      }
    }
  } else {
    // Through it: the least overlap over the face normals and the edges × the segment.
    double least = INFINITY;
    Vec3 axis = Vec3::Zero();
    Feature f = face;
    for (int k = 0; k < faces; ++k) {
      const double o = -std::min(d0[k], d1[k]);
      if (o < least - tie / unit) {
        least = o, axis = shape.normal(k), f = face;
        // The deeper end; parallel to the face (to rounding), the middle of the piece inside.
        at = d0[k] < d1[k] - tie / unit ? seg.p0 : d1[k] < d0[k] - tie / unit ? seg.at(1) : seg.at(0.5 * (enter + leave));
      }
    }
    const double dyy = dy.squaredNorm();
    for (const auto& e : mesh.edges()) {
      const Vec3 v0 = A::position(shape.point(e[0])), dv = A::position(shape.point(e[1])) - v0;
      Vec3 u = A::edge_axis(dv, dy);
      if (!(u.squaredNorm() > kParallel2 * dv.squaredNorm() * dyy)) continue;
      u.normalize();
      const auto plane = A::plane(u, 0);
      double hi = -INFINITY, lo = INFINITY;
      for (int j = 0; j < static_cast<int>(mesh.vertices().size()); ++j) {
        const double h = A::distance(plane, shape.point(j));
        hi = std::max(hi, h), lo = std::min(lo, h);
      }
      const double su = A::distance(plane, x0);
      for (const double sign : {1.0, -1.0}) {
        const double o = sign > 0 ? hi - su : su - lo;
        if (o < least - tie / unit) {
          least = o, axis = sign * u, f = Feature::edge_edge;
          at = seg.at(closest_segment_parameters<A>(y0, dy, v0, dv).s);
        }
      }
    }
    q = {-least * unit, axis, at + least * unit * axis, f};
  }
  const PairContact result = ball_polyhedron(q, at, r, p_is_a);
  if (!contacts || result.depth < -band) return result;
  // Along a face: the segment clipped to the prism of the face most aligned with the normal.
  int k = 0;
  for (int i = 1; i < faces; ++i)
    if (shape.normal(i).dot(q.n_out) > shape.normal(k).dot(q.n_out)) k = i;
  const auto& loop = mesh.faces()[k];
  const Vec3 nk = shape.normal(k);
  double lo = 0, hi = 1;
  for (std::size_t i = 0; i < loop.size() && lo < hi; ++i) {
    const auto& v0 = shape.point(loop[i]);
    const auto side = A::plane_through(v0, Vec3((A::position(shape.point(loop[(i + 1) % loop.size()])) -
                                                  A::position(v0)).cross(nk)));
    const double g0 = A::distance(side, x0), g1 = A::distance(side, x1);
    if (g0 > 0 && g1 > 0) lo = 2;
    else if (g0 > 0) lo = std::max(lo, g0 / (g0 - g1));
    else if (g1 > 0) hi = std::min(hi, g0 / (g0 - g1));
  }
  if (loop.empty() || !line_contacts(lo, hi, seg.d.norm(), band, contacts, [&](double t) {
        const double gap = ((1 - t) * d0[k] + t * d1[k]) * unit - r;
        const Vec3 x = seg.at(t);
        // a's surface point: p's foot below x, or the capsule's lowest point over it.
        return p_is_a ? round_contact(gap, nk, x - (gap + r) * nk, face) : round_contact(gap, -nk, x - r * nk, face);
      }))
    push(contacts, result);
  return result;
}

// A pair with at least one capsule (the dispatch of core/collision/round.hpp).
template <class Body>
PairContact capsule_narrowphase(const Body& a, const Body& b, double band, std::vector<FeatureContact>* contacts) {
  const bool ca = a.mesh().is_capsule(), cb = b.mesh().is_capsule();
  if (ca && cb) return capsule_capsule(a, b, band, contacts);
  PairContact c;
  if (ca && b.mesh().is_sphere()) {
    c = capsule_ball(a, b.sphere_centre(), b.shape().radius());
  } else if (cb && a.mesh().is_sphere()) {
    c = capsule_ball(b, a.sphere_centre(), a.shape().radius());
    c.normal = -c.normal;  // the midway point is the same either way round
  } else {
    return ca ? capsule_polyhedron_outward(a, b, false, band, contacts)
              : capsule_polyhedron_outward(b, a, true, band, contacts);
  }
  if (c.depth >= -band) push(contacts, c);
  return c;
}

}  // namespace gacompare::collision::detail
