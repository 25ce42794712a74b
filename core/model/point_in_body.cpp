#include "core/model/point_in_body.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

namespace gacompare::core {

double max_face_distance(const Mesh& mesh, const Vec3& p) {
  double worst = -std::numeric_limits<double>::infinity();
  for (const auto& plane : mesh.planes()) worst = std::max(worst, plane.distance(p));
  return worst;
}

Where classify_convex(const Mesh& mesh, const Vec3& p, double tolerance) {
  const double d = max_face_distance(mesh, p);
  if (d > tolerance) return Where::outside;
  return d < -tolerance ? Where::inside : Where::boundary;
}

double distance_to_triangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return ap.norm();
  const Vec3 bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return bp.norm();
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return (p - (a + d1 / (d1 - d3) * ab)).norm();
  const Vec3 cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return cp.norm();
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return (p - (a + d2 / (d2 - d6) * ac)).norm();
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0)
    return (p - (b + (d4 - d3) / ((d4 - d3) + (d5 - d6)) * (c - b))).norm();
  const double denom = 1 / (va + vb + vc);
  return (p - (a + ab * (vb * denom) + ac * (vc * denom))).norm();
}

namespace {

// Relative margin, in barycentric units and in the sine of the ray–plane angle:
// 1e-9 is ~1e7 times the rounding of the quantities it is compared with, and the
// chance that a random direction falls within it of some edge is ~1e-9 × (number
// of triangles) per try, so a second direction is almost never needed unless a
// test aims the ray on purpose.
constexpr double kMargin = 1e-9;
constexpr int kMaxDirections = 64;

enum class Cast { clean, ambiguous };

// Counts the triangles the ray p + t d (t > 0) crosses, by Möller–Trumbore;
// reports `ambiguous` as soon as one crossing is too close to an edge, a vertex,
// the ray's origin or a parallel plane to trust.
Cast cast(const Mesh& mesh, const Vec3& p, const Vec3& d, double tolerance, int& crossings) {
  crossings = 0;
  const auto& v = mesh.vertices();
  for (const auto& [ia, ib, ic] : mesh.triangles()) {
    const Vec3 &a = v[ia], &b = v[ib], &c = v[ic];
    const Vec3 e1 = b - a, e2 = c - a, s = p - a;
    const Vec3 pv = d.cross(e2);
    const double det = e1.dot(pv);
    const double area2 = e1.cross(e2).norm();
    if (std::abs(det) <= kMargin * area2) {
      // Near-parallel: harmless unless the ray's line passes near the triangle.
      const Vec3 centre = (a + b + c) / 3;
      const double radius = std::max({(a - centre).norm(), (b - centre).norm(), (c - centre).norm()});
      const Vec3 q = centre - p;
      const double along = std::max(0.0, q.dot(d));
      if ((q - along * d).norm() <= radius * (1 + kMargin) + tolerance) return Cast::ambiguous;
      continue;
    }
    const double inv = 1 / det;
    const double u = s.dot(pv) * inv;
    const Vec3 qv = s.cross(e1);
    const double w = d.dot(qv) * inv;
    const double t = e2.dot(qv) * inv;
    const double x = 1 - u - w;
    const double lo = std::min({u, w, x});
    if (lo < -kMargin) continue;  // clearly misses
    if (lo <= kMargin) {
      if (t > -tolerance - kMargin * mesh.size()) return Cast::ambiguous;  // through an edge or vertex, ahead
      continue;                                                            // behind the origin: irrelevant
    }
    if (std::abs(t) <= tolerance + kMargin * mesh.size()) return Cast::ambiguous;  // at the origin
    if (t > 0) ++crossings;
  }
  return Cast::clean;
}

}  // namespace

ParityResult classify_by_parity(const Mesh& mesh, const Vec3& p, double tolerance, std::optional<Vec3> first) {
  ParityResult r;
  const auto& v = mesh.vertices();
  for (const auto& [a, b, c] : mesh.triangles())
    if (distance_to_triangle(p, v[a], v[b], v[c]) <= tolerance) {
      r.where = Where::boundary;
      return r;
    }
  // A fixed seed: the same point gets the same rays on every run.
  std::mt19937_64 rng(0x9a3c0f1e5bd7ULL);
  std::normal_distribution<double> gauss;
  for (r.directions_tried = 1; r.directions_tried <= kMaxDirections; ++r.directions_tried) {
    Vec3 d;
    if (r.directions_tried == 1 && first)
      d = first->normalized();
    else
      do d = Vec3(gauss(rng), gauss(rng), gauss(rng)); while (d.norm() < 1e-3);
    d.normalize();
    if (cast(mesh, p, d, tolerance, r.crossings) == Cast::clean) {
      r.direction = d;
      r.where = r.crossings % 2 ? Where::inside : Where::outside;
      return r;
    }
  }
  // Only reachable for a point within rounding of the surface yet outside the
  // tolerance (e.g. tolerance 0): every direction grazes the nearby features.
  r.where = Where::boundary;
  r.crossings = 0;
  return r;
}

}  // namespace gacompare::core
