#pragma once
// The narrowphase of round shapes: sphere–sphere and
// sphere–convex polyhedron, written once over a backend's BodyView
// (core/collision/shape.hpp), whose algebra (traditional/narrowphase.hpp,
// cga/narrowphase.hpp) supplies:
//   Sphere, sphere(c, r): a ball ((c, r), or the dual sphere S = up(c) − ½r² n);
//   centre_distance2(S1, S2): |c1 − c2|² ((c1 − c2)·(c1 − c2), or (S1 − S2)²
//     = S1² + S2² − 2 S1·S2 = r1² + r2² − 2 S1·S2: the spheres' separation
//     from their inner product);
//   distance(π, X): a point's signed distance from a plane (n·x − d, or X·π;
//     for the centre X of a sphere S, S·π = X·π since π·n = 0);
//   distance2(X, Y): two points' squared distance (|x − y|², or −2 X·Y).
//
// What comes back is what the polyhedra give (core/collision/collision.hpp): the exact
// signed distance as −depth (not a lower bound: a round pair's closest points
// are known), the unit normal from a towards b, the point midway between the
// two surfaces, and at most one FeatureContact for the response (a sphere
// touches a convex body at one point), when the pair is within the touching
// band. So the impulse solver, its friction rows, the time-of-impact search
// and the positional correction run on round pairs unchanged.
//
// Sphere–polyhedron, by the closest feature of the polyhedron to the centre c:
//   - the signed distances s_k of c from every face plane. If none is > 0 the
//     centre is inside: the face with the largest s_k (the least deep) is the
//     shortest way out, depth r − s_k along its normal;
//   - otherwise, a face with s_k > 0 whose polygon contains c's projection
//     (c behind every side plane of the face: the plane through a boundary
//     edge with normal edge × face normal; c's projection and c itself lie on
//     the same side of a plane perpendicular to the face) is the closest
//     feature, at distance s_k: on a convex body c − q in the normal cone at
//     q makes q the unique closest point;
//   - if no face holds it, the closest point lies on the boundary of a face,
//     so on a feature edge (ends included: the vertices): the nearest point of
//     every edge segment, the least distance.
#include "core/collision/collision.hpp"

#include <cmath>
#include <vector>

namespace gacompare::collision {

namespace detail {

// The contact from the signed distance `gap` between the surfaces along the
// unit normal n (from a towards b), with p_a the point of a's surface nearest
// b: the point midway between the surfaces is p_a + ½ gap n.
inline PairContact round_contact(double gap, const Vec3& n, const Vec3& p_a, Feature f) {
  PairContact c;
  c.depth = -gap;
  c.intersect = gap < 0;
  c.normal = n;
  c.contact = p_a + (0.5 * gap) * n;
  c.feature = f;
  return c;
}

// Two spheres, each centre in the pair's frame (metres).
template <class Body>
PairContact sphere_sphere(const Body& a, const Body& b) {
  using A = typename Body::Algebra;
  const Vec3 ca = a.sphere_centre(), cb = b.sphere_centre();
  const double ra = a.shape().radius(), rb = b.shape().radius();
  const double d2 = A::centre_distance2(A::sphere(ca, ra), A::sphere(cb, rb));
  const double d = std::sqrt(std::max(0.0, d2));
  // Concentric spheres: no direction is preferred; +z, typed by the depth.
  const Vec3 n = d > 0 ? Vec3((cb - ca) / d) : Vec3::UnitZ();
  return round_contact(d - ra - rb, n, ca + ra * n, Feature::face_a);
}

// A point's nearest point of a convex polyhedron p (top of the file), in the
// pair's frame: its distance from p's surface (< 0 inside), the unit normal
// out of p at that surface point, the point itself, and the feature (face of
// p, or edge_edge for an edge or vertex). The sphere and the capsule
// (core/collision/capsule.hpp) take their contacts from it.
struct PointNearest {
  double gap_to_p = 0;
  Vec3 n_out = Vec3::Zero();
  Vec3 surface = Vec3::Zero();
  Feature feature = Feature::none;
};

template <class Body>
PointNearest point_polyhedron(const Body& p, const Vec3& c, bool p_is_a) {
  using A = typename Body::Algebra;
  const auto& shape = p.shape();
  const double unit = shape.unit();
  const auto x = p.local_point(c);  // the point in p's own frame and unit
  const Mesh& mesh = p.mesh();
  const int faces = static_cast<int>(mesh.planes().size());
  thread_local std::vector<double> dist;
  dist.resize(static_cast<std::size_t>(faces));
  int deepest = 0;
  for (int k = 0; k < faces; ++k) {
    dist[k] = A::distance(shape.plane(k), x);
    if (dist[k] > dist[deepest]) deepest = k;
  }
  const Feature face = p_is_a ? Feature::face_a : Feature::face_b;
  const auto answer = [&](double gap_to_p, const Vec3& n_out, Feature f) {
    return PointNearest{gap_to_p, n_out, c - gap_to_p * n_out, f};
  };
  if (!(dist[deepest] > 0)) return answer(dist[deepest] * unit, shape.normal(deepest), face);
  for (int k = 0; k < faces; ++k) {
    if (!(dist[k] > 0)) continue;
    const auto& loop = mesh.faces()[k];
    const Vec3 nk = shape.normal(k);
    bool inside = !loop.empty();
    for (std::size_t i = 0; inside && i < loop.size(); ++i) {
      const auto& v0 = shape.point(loop[i]);
      const auto& v1 = shape.point(loop[(i + 1) % loop.size()]);
      const Vec3 side = (A::position(v1) - A::position(v0)).cross(nk);
      inside = A::distance(A::plane_through(v0, side), x) <= 0;
    }
    if (inside) return answer(dist[k] * unit, nk, face);
  }
  // An edge or a vertex: the nearest point of each feature edge.
  const Vec3 xc = A::position(x);
  double best = INFINITY;
  Vec3 nearest = Vec3::Zero();
  for (const auto& e : mesh.edges()) {
    const Vec3 p0 = A::position(shape.point(e[0])), d = A::position(shape.point(e[1])) - p0;
    const double t = std::clamp((xc - p0).dot(d) / d.squaredNorm(), 0.0, 1.0);
    const Vec3 y = p0 + t * d;
    const double q = A::distance2(x, A::lift(y));
    if (q < best) best = q, nearest = y;
  }
  const double gap_to_p = std::sqrt(best) * unit;
  const Vec3 n_out = (xc - nearest).normalized();
  return answer(gap_to_p, n_out, Feature::edge_edge);
}

// A ball of radius r about c (a sphere, or a capsule's segment point) against
// p, from c's nearest point q of p: the normal out of p towards the ball.
inline PairContact ball_polyhedron(const PointNearest& q, const Vec3& c, double r, bool p_is_a) {
  const double gap = q.gap_to_p - r;
  return p_is_a ? round_contact(gap, q.n_out, q.surface, q.feature) : round_contact(gap, -q.n_out, c - r * q.n_out, q.feature);
}

// A sphere s and a convex polyhedron p; the normal out of p towards s.
template <class Body>
PairContact sphere_polyhedron_outward(const Body& s, const Body& p, bool p_is_a) {
  const Vec3 c = s.sphere_centre();
  return ball_polyhedron(point_polyhedron(p, c, p_is_a), c, s.shape().radius(), p_is_a);
}

}  // namespace detail

}  // namespace gacompare::collision

// Capsules build on the functions above (and are included here only).
#include "core/collision/capsule.hpp"

namespace gacompare::collision {

// Whether the pair needs the round narrowphase (either body a sphere or a capsule).
template <class Body>
bool round_pair(const Body& a, const Body& b) {
  return a.mesh().is_round() || b.mesh().is_round();
}

// A round pair's contact, in the Body frame (see the top of the file), and
// its point contacts for the response when within the band: one (a sphere
// touches a convex body at one point), or two where a capsule lies along a
// face or along another capsule (core/collision/capsule.hpp).
template <class Body>
PairContact round_narrowphase(const Body& a, const Body& b, double band, std::vector<FeatureContact>* contacts) {
  if (a.mesh().is_capsule() || b.mesh().is_capsule()) return detail::capsule_narrowphase(a, b, band, contacts);
  // Returned whole from one expression (not assigned to a contact made
  // first): written that way, sphere–sphere took 29 ns instead of 22
  // (bench/narrowphase_bench BM_round_sphere_sphere).
  const PairContact c = a.shape().is_sphere() && b.shape().is_sphere() ? detail::sphere_sphere(a, b)
                        : a.shape().is_sphere()                       ? detail::sphere_polyhedron_outward(a, b, false)
                                                                      : detail::sphere_polyhedron_outward(b, a, true);
  if (contacts && c.depth >= -band) contacts->push_back({c.contact, c.normal, c.depth, c.feature});
  return c;
}

// The contact alone.
template <class Body>
PairContact round_narrowphase(const Body& a, const Body& b) {
  return round_narrowphase(a, b, 0, nullptr);
}

}  // namespace gacompare::collision
