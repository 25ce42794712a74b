#include "core/separating_axis.hpp"

#include <Eigen/Geometry>

#include <array>

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

}  // namespace

// Every candidate axis, both bodies projected, the largest gap wins: nothing is
// pruned, so a wrong pruning rule in the fast path shows up against this.
PairContact sat_reference(const Placed& a, const Placed& b) {
  const Vec3 origin = local_origin(a, b);
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
