#pragma once
// Segment through triangle, the traditional way (§2.4.4, Sunday's parametric
// method [11], eq. 39–42). Twin: cga/segment_triangle.hpp (same name, same
// result type core/collision.hpp SegmentHit).
//
// Stage 1, eq. 39: r = n·(T0 − L0) / n·(L1 − L0), on the segment for 0 ≤ r ≤ 1.
// Stage 2, eq. 41–42: s = w·(n × v)/(u·(n × v)), t = w·(n × u)/(v·(n × u)) with
// u = T1 − T0, v = T2 − T0, w = I − T0; inside for s, t ≥ 0, s + t ≤ 1.
// A segment parallel to the plane (|n·(L1 − L0)| ≤ kSinTol |n||L1 − L0|) is no
// hit: lying in the plane it only touches, which the narrowphase leaves to the
// vertex and face tests (its ends are on the faces).
#include "core/collision.hpp"
#include "core/geometry.hpp"

#include <cmath>
#include <optional>

namespace gacompare::traditional {

inline std::optional<collision::SegmentHit> segment_triangle(const Eigen::Vector3d& l0, const Eigen::Vector3d& l1,
                                                             const Eigen::Vector3d& t0, const Eigen::Vector3d& t1,
                                                             const Eigen::Vector3d& t2) {
  const Eigen::Vector3d u = t1 - t0, v = t2 - t0, n = u.cross(v), d = l1 - l0;
  const double den = n.dot(d);
  if (!(std::abs(den) > geometry::kSinTol * n.norm() * d.norm())) return std::nullopt;
  const double r = n.dot(t0 - l0) / den;  // eq. 39
  if (r < 0 || r > 1) return std::nullopt;
  const Eigen::Vector3d point = l0 + r * d, w = point - t0;
  const Eigen::Vector3d nv = n.cross(v), nu = n.cross(u);
  const double s = w.dot(nv) / u.dot(nv);  // eq. 41
  const double t = w.dot(nu) / v.dot(nu);  // eq. 42
  if (s < 0 || t < 0 || s + t > 1) return std::nullopt;
  return collision::SegmentHit{point, r, {1 - s - t, s, t}};
}

}  // namespace gacompare::traditional
