#include "core/collision/separating_axis.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace gacompare::collision {

const char* feature_name(Feature f) {
  switch (f) {
    case Feature::none: return "none";
    case Feature::face_a: return "face_a";
    case Feature::face_b: return "face_b";
    case Feature::edge_edge: return "edge_edge";
  }
  return "?";
}

Vec3 edge_edge_midpoint(const Vec3& p, const Vec3& d, const Vec3& q, const Vec3& e) {
  // Minimise |p + s d − q − t e|²: the 2×2 normal equations (Ericson §5.1.8).
  const Vec3 r = p - q;
  const double a = d.dot(d), b = d.dot(e), c = e.dot(e), f = d.dot(r), g = e.dot(r);
  const double den = a * c - b * b;  // |d × e|², > 0 for the pairs that reach here
  const double s = (b * g - c * f) / den, t = (a * g - b * f) / den;
  return 0.5 * ((p + s * d) + (q + t * e));
}

namespace {

using LVec = Eigen::Matrix<long double, 3, 1>;

struct Projected {  // a body in the local frame, in long double
  std::vector<LVec> v;
  std::vector<LVec> normals;  // distinct face planes, rotated
};

Projected project(const Placed& body, const Vec3& origin) {
  Projected p;
  const Eigen::Matrix<long double, 3, 3> r = body.pose.rotation.cast<long double>();
  const LVec t = body.pose.position.cast<long double>() - origin.cast<long double>();
  for (const Vec3& x : body.mesh->vertices()) p.v.push_back(r * x.cast<long double>() + t);
  for (const auto& pl : body.mesh->planes()) p.normals.push_back(r * pl.normal.cast<long double>());
  return p;
}

struct Interval {
  long double lo, hi;
  int arg_lo, arg_hi;
};

Interval extent(const std::vector<LVec>& v, const LVec& u) {
  Interval s{u.dot(v[0]), u.dot(v[0]), 0, 0};
  for (int i = 1; i < static_cast<int>(v.size()); ++i) {
    const long double x = u.dot(v[i]);
    if (x < s.lo) s.lo = x, s.arg_lo = i;
    if (x > s.hi) s.hi = x, s.arg_hi = i;
  }
  return s;
}

// The point of triangle (a, b, c) nearest p, by Ericson's Voronoi regions
// (Real-Time Collision Detection §5.1.5): a method independent of the
// narrowphase's (core/collision/round.hpp: face polygons, then edges).
LVec nearest_on_triangle(const LVec& p, const LVec& a, const LVec& b, const LVec& c) {
  const LVec ab = b - a, ac = c - a, ap = p - a;
  const long double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return a;
  const LVec bp = p - b;
  const long double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return b;
  const long double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return a + (d1 / (d1 - d3)) * ab;
  const LVec cp = p - c;
  const long double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return c;
  const long double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return a + (d2 / (d2 - d6)) * ac;
  const long double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) return b + ((d4 - d3) / ((d4 - d3) + (d5 - d6))) * (c - b);
  const long double den = 1 / (va + vb + vc);
  return a + ab * (vb * den) + ac * (vc * den);
}

// The minimum of a convex function on [0, 1] by golden-section search, to
// long double's resolution of the argument: f's value at the minimum is what
// the references read, exact to rounding even where f is flat (a segment
// parallel to a face) or has a kink there (crossing segments). Returns the argument.
template <class F>
long double golden_minimum(const F& f) {
  const long double g = (std::sqrt(5.0L) - 1) / 2;
  long double lo = 0, hi = 1, x1 = hi - g * (hi - lo), x2 = lo + g * (hi - lo);
  long double f1 = f(x1), f2 = f(x2);
  for (int i = 0; i < 120; ++i) {
    if (f1 <= f2) hi = x2, x2 = x1, f2 = f1, x1 = hi - g * (hi - lo), f1 = f(x1);
    else lo = x1, x1 = x2, f1 = f2, x2 = lo + g * (hi - lo), f2 = f(x2);
  }
  // The ends too: a monotone f has its minimum there, which the bracket only approaches.
  long double best = f1 <= f2 ? x1 : x2;
  for (const long double e : {0.0L, 1.0L})
    if (f(e) < f(best)) best = e;
  return best;
}

LVec nearest_on_segment(const LVec& x, const LVec& p0, const LVec& d) {
  const long double dd = d.squaredNorm();
  return dd > 0 ? LVec(p0 + std::clamp((x - p0).dot(d) / dd, 0.0L, 1.0L) * d) : p0;
}

// A capsule pair (core/collision/capsule.hpp; a sphere is the capsule with a zero
// segment) in long double, by methods that share nothing with the
// narrowphase: a segment's distance to the other body is the minimum over
// its points, a convex function of the parameter, found by golden-section
// search (of the clamped point–segment distance, or of the nearest point of
// every triangle); a segment through the polyhedron by the separating axes
// of their Minkowski difference (every face normal, every edge × the
// segment, both ways), plus the radius.
PairContact capsule_reference(const Placed& a, const Placed& b, const Vec3& origin) {
  struct Round {
    LVec p0, d;
    long double r;
  };
  const auto round = [&](const Placed& s) {
    const Eigen::Matrix<long double, 3, 3> rot = s.pose.rotation.cast<long double>();
    const LVec c = rot * s.mesh->sphere_centre().cast<long double>() + s.pose.position.cast<long double>() -
                   origin.cast<long double>();
    const LVec h = rot * s.mesh->capsule_half_axis().cast<long double>();
    return Round{c - h, 2 * h, s.mesh->sphere_radius()};
  };
  LVec normal = LVec::Zero(), on_a = LVec::Zero();  // a → b; a's surface point nearest b
  long double gap = 0;
  if (a.mesh->is_round() && b.mesh->is_round()) {
    const Round A = round(a), B = round(b);
    const auto dist = [&](long double s) {
      const LVec p = A.p0 + s * A.d;
      return (nearest_on_segment(p, B.p0, B.d) - p).norm();
    };
    const LVec p = A.p0 + golden_minimum(dist) * A.d, q = nearest_on_segment(p, B.p0, B.d);
    const long double d = (q - p).norm();
    if (d > 0) {
      normal = (q - p) / d;
    } else {  // the segments meet: across both (or across a's, parallel), towards b
      normal = A.d.cross(B.d);
      if (normal.norm() <= 1e-14L * A.d.norm() * B.d.norm()) {
        const LVec m = A.d.cwiseAbs();
        normal = A.d.cross(m.x() <= m.y() && m.x() <= m.z() ? LVec(1, 0, 0) : m.y() <= m.z() ? LVec(0, 1, 0) : LVec(0, 0, 1));
      }
      normal.normalize();
      if (normal.dot((B.p0 + 0.5L * B.d) - (A.p0 + 0.5L * A.d)) < 0) normal = -normal;
    }
    gap = d - A.r - B.r;
    on_a = p + A.r * normal;
  } else {
    const bool poly_a = !a.mesh->is_round();
    const Round S = round(poly_a ? b : a);
    const Placed& pp = poly_a ? a : b;
    const Projected P = project(pp, origin);
    const auto& planes = pp.mesh->planes();
    const LVec t = pp.pose.position.cast<long double>() - origin.cast<long double>();
    const auto height = [&](const LVec& x) {  // the largest face-plane distance: ≤ 0 inside
      long double most = -std::numeric_limits<long double>::infinity();
      for (std::size_t k = 0; k < planes.size(); ++k)
        most = std::max(most, P.normals[k].dot(x - t) - static_cast<long double>(planes[k].offset));
      return most;
    };
    const auto nearest = [&](const LVec& x) {
      LVec best_q = x;
      long double best = std::numeric_limits<long double>::infinity();
      for (const auto& tri : pp.mesh->triangles()) {
        const LVec q = nearest_on_triangle(x, P.v[tri[0]], P.v[tri[1]], P.v[tri[2]]);
        if ((x - q).squaredNorm() < best) best = (x - q).squaredNorm(), best_q = q;
      }
      return best_q;
    };
    LVec out_of_p = LVec::Zero(), c = LVec::Zero();
    long double to_p = 0;
    if (height(S.p0 + golden_minimum([&](long double s) { return height(S.p0 + s * S.d); }) * S.d) > 0) {
      const long double s = golden_minimum([&](long double u) {
        const LVec x = S.p0 + u * S.d;
        return (x - nearest(x)).norm();
      });
      c = S.p0 + s * S.d;
      const LVec q = nearest(c);
      to_p = (c - q).norm();
      out_of_p = (c - q) / to_p;
    } else {
      long double least = std::numeric_limits<long double>::infinity();
      const auto consider = [&](const LVec& u) {
        const Interval e = extent(P.v, u);
        const long double s0 = u.dot(S.p0), s1 = u.dot(S.p0 + S.d);
        if (e.hi - std::min(s0, s1) < least) least = e.hi - std::min(s0, s1), out_of_p = u, c = s0 <= s1 ? S.p0 : LVec(S.p0 + S.d);
      };
      for (const auto& n : P.normals) consider(n);
      for (const auto& e : pp.mesh->edges()) {
        const LVec u = (P.v[e[1]] - P.v[e[0]]).cross(S.d);
        if (u.norm() <= 1e-14L * (P.v[e[1]] - P.v[e[0]]).norm() * S.d.norm()) continue;
        consider(u.normalized()), consider(-u.normalized());
      }
      to_p = -least;
    }
    gap = to_p - S.r;
    normal = poly_a ? out_of_p : LVec(-out_of_p);
    on_a = poly_a ? LVec(c - to_p * out_of_p) : LVec(c - S.r * out_of_p);
  }
  PairContact out;
  out.depth = static_cast<double>(-gap);
  out.intersect = gap < 0;
  out.normal = normal.cast<double>();
  out.contact = (on_a + 0.5L * gap * normal).cast<double>() + origin;
  return out;
}

// A round pair (core/collision/round.hpp) in long double: sphere–sphere by the centres'
// distance; sphere–polyhedron by the nearest point of every triangle when the
// centre is outside, by the nearest face plane when inside.
PairContact round_reference(const Placed& a, const Placed& b, const Vec3& origin) {
  const auto centre = [&](const Placed& s) {
    return LVec((s.pose.rotation.cast<long double>() * s.mesh->sphere_centre().cast<long double>() +
                 s.pose.position.cast<long double>() - origin.cast<long double>()));
  };
  PairContact out;
  out.feature = Feature::none;
  LVec normal = LVec::Zero(), on_a = LVec::Zero();  // a → b; a's surface point nearest b
  long double gap = 0;
  if (a.mesh->is_sphere() && b.mesh->is_sphere()) {
    const LVec ca = centre(a), cb = centre(b);
    const long double d = (cb - ca).norm(), ra = a.mesh->sphere_radius(), rb = b.mesh->sphere_radius();
    normal = d > 0 ? LVec((cb - ca) / d) : LVec(0, 0, 1);
    gap = d - ra - rb;
    on_a = ca + ra * normal;
  } else {
    const bool poly_a = !a.mesh->is_sphere();
    const Placed& s = poly_a ? b : a;
    const Placed& p = poly_a ? a : b;
    const LVec c = centre(s);
    const long double r = s.mesh->sphere_radius();
    const Projected P = project(p, origin);
    const auto& planes = p.mesh->planes();
    long double most = -std::numeric_limits<long double>::infinity();
    int arg = 0;
    const LVec t = p.pose.position.cast<long double>() - origin.cast<long double>();
    for (std::size_t k = 0; k < planes.size(); ++k) {
      const long double dist = P.normals[k].dot(c - t) - static_cast<long double>(planes[k].offset);
      if (dist > most) most = dist, arg = static_cast<int>(k);
    }
    LVec out_of_p = LVec::Zero(), surface = LVec::Zero();
    long double to_p = 0;
    if (most <= 0) {
      out_of_p = P.normals[arg];
      to_p = most;
      surface = c - most * out_of_p;
    } else {
      long double best = std::numeric_limits<long double>::infinity();
      for (const auto& tri : p.mesh->triangles()) {
        const LVec q = nearest_on_triangle(c, P.v[tri[0]], P.v[tri[1]], P.v[tri[2]]);
        const long double d2 = (c - q).squaredNorm();
        if (d2 < best) best = d2, surface = q;
      }
      to_p = std::sqrt(best);
      out_of_p = (c - surface) / to_p;
    }
    gap = to_p - r;
    normal = poly_a ? out_of_p : LVec(-out_of_p);
    on_a = poly_a ? surface : LVec(c - r * out_of_p);
  }
  out.depth = static_cast<double>(-gap);
  out.intersect = gap < 0;
  out.normal = normal.cast<double>();
  out.contact = (on_a + 0.5L * gap * normal).cast<double>() + origin;
  return out;
}

}  // namespace

// Every candidate axis, both bodies projected, the largest gap wins: nothing is
// pruned, so a wrong pruning rule in the fast path shows up against this.
// Round pairs have their own exact answer (round_reference above).
PairContact sat_reference(const Placed& a, const Placed& b) {
  const Vec3 origin = local_origin(a, b);
  if (a.mesh->is_capsule() || b.mesh->is_capsule()) return capsule_reference(a, b, origin);
  if (a.mesh->is_sphere() || b.mesh->is_sphere()) return round_reference(a, b, origin);
  const Projected A = project(a, origin), B = project(b, origin);
  PairContact best;
  long double gap = -std::numeric_limits<long double>::infinity();
  LVec best_axis = LVec::Zero();
  // The contact: midway between A's support point along the normal and B's
  // support point against it (for an edge pair, between the edge lines).
  LVec point_a = LVec::Zero(), point_b = LVec::Zero();
  std::array<int, 2> edge_pair{-1, -1};
  const auto consider = [&](const LVec& u, Feature feature, std::array<int, 2> edges) {
    const Interval ia = extent(A.v, u), ib = extent(B.v, u);
    const long double forward = ib.lo - ia.hi, backward = ia.lo - ib.hi;  // B beyond A along u, or along −u
    const long double g = std::max(forward, backward);
    if (!(g > gap)) return;
    gap = g;
    best_axis = forward >= backward ? u : LVec(-u);
    point_a = forward >= backward ? A.v[ia.arg_hi] : A.v[ia.arg_lo];
    point_b = forward >= backward ? B.v[ib.arg_lo] : B.v[ib.arg_hi];
    best.feature = feature;
    edge_pair = edges;
  };
  for (const LVec& n : A.normals) consider(n, Feature::face_a, {-1, -1});
  for (const LVec& n : B.normals) consider(n, Feature::face_b, {-1, -1});
  const auto& ea = a.mesh->edges();
  const auto& eb = b.mesh->edges();
  for (std::size_t i = 0; i < ea.size(); ++i) {
    const LVec da = A.v[ea[i][1]] - A.v[ea[i][0]];
    for (std::size_t j = 0; j < eb.size(); ++j) {
      const LVec db = B.v[eb[j][1]] - B.v[eb[j][0]];
      const LVec u = da.cross(db);
      const long double len = u.norm();
      if (!(len > kParallelSinReference * da.norm() * db.norm())) continue;
      consider(u / len, Feature::edge_edge, {static_cast<int>(i), static_cast<int>(j)});
    }
  }
  best.depth = static_cast<double>(-gap);
  best.intersect = gap < 0;
  best.normal = best_axis.cast<double>();
  if (best.feature == Feature::edge_edge) {
    // Every edge pair with the same axis gives the same gap (the projections do
    // not depend on the pair), so the contact comes from the supporting edges:
    // those whose both ends reach the extreme projection.
    const auto supporting = [&](const Projected& p, const std::vector<std::array<int, 2>>& edges, const LVec& u,
                                int fallback) {
      const Interval s = extent(p.v, u);
      const long double tol = 1e-12L * (std::abs(s.hi) + std::abs(s.lo) + 1);
      for (int e = 0; e < static_cast<int>(edges.size()); ++e)
        if (u.dot(p.v[edges[e][0]]) >= s.hi - tol && u.dot(p.v[edges[e][1]]) >= s.hi - tol) return e;
      return fallback;
    };
    const int i = supporting(A, ea, best_axis, edge_pair[0]);
    const int j = supporting(B, eb, LVec(-best_axis), edge_pair[1]);
    const LVec a0 = A.v[ea[i][0]], b0 = B.v[eb[j][0]];
    best.contact = edge_edge_midpoint(a0.cast<double>(), (A.v[ea[i][1]] - a0).cast<double>(), b0.cast<double>(),
                                      (B.v[eb[j][1]] - b0).cast<double>()) +
                   origin;
  } else {
    best.contact = (0.5L * (point_a + point_b)).cast<double>() + origin;
  }
  return best;
}

}  // namespace gacompare::collision
