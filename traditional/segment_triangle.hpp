#pragma once
// Segment through triangle, the traditional way (§2.4.4, Sunday's parametric
// method [11], eq. 39–42). Twin: cga/segment_triangle.hpp (same names, same
// result type core/collision/collision.hpp SegmentHit).
//
// Stage 1, eq. 39: r = n·(T0 − L0) / n·(L1 − L0), on the segment for 0 ≤ r ≤ 1.
// Stage 2, eq. 41–42: s = w·(n × v)/(u·(n × v)), t = w·(n × u)/(v·(n × u)) with
// u = T1 − T0, v = T2 − T0, w = I − T0; inside for s, t ≥ 0, s + t ≤ 1.
// A segment parallel to the plane (|n·(L1 − L0)| ≤ kSinTol |n||L1 − L0|) is no
// hit: lying in the plane it only touches, which the narrowphase leaves to the
// vertex and face tests (its ends are on the faces).
//
// What depends on the triangle alone (n and the two scaled perpendiculars of
// eq. 41–42) is prepared once per triangle (PreparedTriangle), as a body tests
// each of its triangles against many edges; the twin prepares its reciprocal
// frame the same way.
#include "core/collision/collision.hpp"
#include "core/geometry.hpp"

#include <Eigen/Geometry>

#include <cmath>
#include <optional>

namespace gacompare::traditional {

struct PreparedTriangle {
  Eigen::Vector3d t0, n, s_row, t_row;  // s = w·s_row, t = w·t_row (eq. 41, 42)
  double n_norm = 0;

  PreparedTriangle() = default;
  PreparedTriangle(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c) : t0(a) {
    const Eigen::Vector3d u = b - a, v = c - a;
    n = u.cross(v);
    n_norm = n.norm();
    const Eigen::Vector3d nv = n.cross(v), nu = n.cross(u);
    s_row = nv / u.dot(nv);
    t_row = nu / v.dot(nu);
  }

  std::optional<collision::SegmentHit> through(const Eigen::Vector3d& l0, const Eigen::Vector3d& l1) const {
    const Eigen::Vector3d d = l1 - l0;
    const double den = n.dot(d);
    if (!(std::abs(den) > geometry::kSinTol * n_norm * d.norm())) return std::nullopt;
    const double r = n.dot(t0 - l0) / den;  // eq. 39
    if (r < 0 || r > 1) return std::nullopt;
    const Eigen::Vector3d point = l0 + r * d, w = point - t0;
    const double s = w.dot(s_row), t = w.dot(t_row);  // eq. 41, 42
    if (s < 0 || t < 0 || s + t > 1) return std::nullopt;
    return collision::SegmentHit{point, r, {1 - s - t, s, t}};
  }
};

inline std::optional<collision::SegmentHit> segment_triangle(const Eigen::Vector3d& l0, const Eigen::Vector3d& l1,
                                                             const Eigen::Vector3d& t0, const Eigen::Vector3d& t1,
                                                             const Eigen::Vector3d& t2) {
  return PreparedTriangle(t0, t1, t2).through(l0, l1);
}

}  // namespace gacompare::traditional
