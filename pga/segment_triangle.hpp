#pragma once
// Segment through triangle in plane-based GA (§2.4.4's question in PGA's own
// terms). Twin: cga/segment_triangle.hpp, traditional/segment_triangle.hpp
// (same names, same result type).
//
// The triangle is the plane π = T0 ∨ T1 ∨ T2 (the join of its corners) and
// its three edge lines E0 = T1 ∨ T2, E1 = T2 ∨ T0, E2 = T0 ∨ T1; the segment
// is the line L = L0 ∨ L1.
// Stage 1: the ends' signed distances α = π ∧ L0, β = π ∧ L1 (scalars of
// e0123): the segment crosses the plane iff they differ in sign, and it
// crosses at the meet π ∧ L, a point.
// Stage 2: L ∨ E_i, the mutual moment of two lines (a scalar: the signed
// volume of the tetrahedron L0 L1 T_j T_k), is the barycentric coordinate of
// the crossing opposite corner i up to a common factor (Plücker's side test):
// inside iff the three agree in sign; λ_i = (L ∨ E_i)/Σ.
// The report's reciprocal frame and the matrix backend's Sunday rows have no
// twin here: the edges' lines are the frame.
//
// π and the edge lines depend on the triangle alone: PreparedTriangle builds
// them once per triangle. Parallel segment: the same predicate as the twins,
// |α − β| ≤ kSinTol·|n|·|L1 − L0| with n the plane's normal.
#include "pga/algebra/cl301.hpp"
#include "core/collision/collision.hpp"
#include "core/geometry.hpp"

#include <array>
#include <cmath>
#include <optional>

namespace gacompare::pga {

struct PreparedTriangle {
  Plane pi{};                 // T0 ∨ T1 ∨ T2, any scale
  double pi_norm = 0;         // |normal of π|
  std::array<Line, 3> edge{};  // E_i, opposite corner i

  PreparedTriangle() = default;
  PreparedTriangle(const Vec3& t0, const Vec3& t1, const Vec3& t2) {
    const Point T0 = point(t0), T1 = point(t1), T2 = point(t2);
    edge = {join(T1, T2), join(T2, T0), join(T0, T1)};
    pi = join(edge[2], T2);
    pi_norm = normal(pi).norm();
  }

  std::optional<collision::SegmentHit> through(const Vec3& l0, const Vec3& l1) const {
    return through(point(l0), point(l1));
  }
  // The segment's ends as points of weight 1 (a narrowphase Body stores its
  // vertices so).
  std::optional<collision::SegmentHit> through(const Point& L0, const Point& L1) const {
    const double alpha = distance_of_unit_point(pi, L0), beta = distance_of_unit_point(pi, L1);
    const double length = (coordinates(L1) - coordinates(L0)).norm();
    if (!(std::abs(alpha - beta) > geometry::kSinTol * pi_norm * length)) return std::nullopt;  // parallel
    if ((alpha > 0 && beta > 0) || (alpha < 0 && beta < 0)) return std::nullopt;               // one side
    const Line L = join(L0, L1);
    const std::array<double, 3> side{join(L, edge[0]).c[0], join(L, edge[1]).c[0], join(L, edge[2]).c[0]};
    const bool negative = side[0] < 0 || side[1] < 0 || side[2] < 0;
    const bool positive = side[0] > 0 || side[1] > 0 || side[2] > 0;
    if (negative && positive) return std::nullopt;
    const double sum = side[0] + side[1] + side[2];
    if (!(sum != 0)) return std::nullopt;
    const Point meet = pi ^ L;
    return collision::SegmentHit{euclid(meet), alpha / (alpha - beta), {side[0] / sum, side[1] / sum, side[2] / sum}};
  }
};

inline std::optional<collision::SegmentHit> segment_triangle(const Vec3& l0, const Vec3& l1, const Vec3& t0,
                                                             const Vec3& t1, const Vec3& t2) {
  return PreparedTriangle(t0, t1, t2).through(l0, l1);
}

}  // namespace gacompare::pga
