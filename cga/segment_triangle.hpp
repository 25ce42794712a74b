#pragma once
// Segment through triangle, the conformal way (§2.4.4 after [7], eq. 43–46).
// Twin: traditional/segment_triangle.hpp (same names, same result type).
//
// Stage 1: the line L = L0 ∧ L1 ∧ n meets the plane Φ = T0 ∧ T1 ∧ T2 ∧ n in a
// flat point; with the plane dual, π = Φ*, the meet is one contraction
//   π⌋L = (π·L0) L1∧n − (π·L1) L0∧n        (π·n = 0 for a plane),
// the flat point of (π·L0) L1 − (π·L1) L0. Its position: divide by the weight
// (meet.hpp's flat_point; the report reads the e_i∧n components alone, right
// only for unit weight). "On the segment": the report compares the point with
// the bounding box of the segment's ends, which fails for a segment parallel to
// an axis (a box of zero width, decided by rounding). The meet's own
// coefficients say it exactly: the point is between L0 and L1 iff π·L0 and
// π·L1, the ends' signed distances from the plane, do not have the same sign.
//
// Stage 2, eq. 43–46: the reciprocal frame of T0, T1, T2 in Φ,
//   T^i = (n ∧ L_i)·Φ / Φ²,  L_0 = T1∧T2, L_1 = T2∧T0, L_2 = T0∧T1,
// gives the barycentric coordinates λ_i = T^i·I of the up-projected point I
// (I·n = −1 makes them sum to 1). Eq. 44 writes |Φ|⁻² with |Φ|² = −Φ²; the sign
// that makes T^i·T_i = +1 in our conventions (tested) is the one used here.
// Inside for every λ_i ≥ 0 (the report also asks λ_i ≤ 1, implied by the sum).
//
// π and the reciprocal frame depend on the triangle alone: PreparedTriangle
// builds them once per triangle (a body tests each triangle against many
// edges), as the twin prepares its eq. 41–42 rows.
//
// Parallel segment: the same predicate as the twin, |π·(L1 − L0)| ≤ kSinTol·|L1 − L0|
// for the normalised plane.
#include "cga/algebra/cl41.hpp"
#include "cga/geometry/meet.hpp"
#include "core/collision/collision.hpp"

#include <array>
#include <cmath>
#include <optional>

namespace gacompare::cga {

struct PreparedTriangle {
  DualPlane pi{};                      // Φ*, any scale
  double pi_norm = 0;                  // |Euclidean part of π|
  std::array<Vector5, 3> reciprocal{};  // T^i, eq. 44

  PreparedTriangle() = default;
  PreparedTriangle(const Eigen::Vector3d& t0, const Eigen::Vector3d& t1, const Eigen::Vector3d& t2) {
    const ConformalPoint T0 = up(t0), T1 = up(t1), T2 = up(t2);
    const auto n = n_inf();
    const Quadvector5 phi = ((T0 ^ T1) ^ T2) ^ n;
    pi = !phi;
    pi_norm = detail::euclid(pi).norm();
    const double inv_phi2 = 1 / scalar_product(phi, phi);
    const auto frame = [&](const ConformalPoint& p, const ConformalPoint& q) {
      return widen<Vector5::blades>((n ^ (p ^ q)) | phi) * inv_phi2;
    };
    reciprocal = {frame(T1, T2), frame(T2, T0), frame(T0, T1)};
  }

  std::optional<collision::SegmentHit> through(const Eigen::Vector3d& l0, const Eigen::Vector3d& l1) const {
    return through(up(l0), up(l1));
  }
  // The segment's ends already lifted (a narrowphase Body stores its vertices
  // as conformal points: no second up() per edge and triangle).
  // up() gives weight 1, so the Euclidean parts are the points themselves.
  std::optional<collision::SegmentHit> through(const ConformalPoint& L0, const ConformalPoint& L1) const {
    const Eigen::Vector3d l0 = detail::euclid(L0), l1 = detail::euclid(L1);
    const double alpha = scalar_product(pi, L0), beta = scalar_product(pi, L1);
    if (!(std::abs(alpha - beta) > kSinTol * pi_norm * (l1 - l0).norm())) return std::nullopt;  // parallel
    if ((alpha > 0 && beta > 0) || (alpha < 0 && beta < 0)) return std::nullopt;              // one side
    // The meet π⌋(L0 ∧ L1 ∧ n) = α L1∧n − β L0∧n (above) is the flat point of
    // α L1 − β L0, of weight α − β (≠ 0: not parallel): its point is read
    // from α and β directly, without forming the line's trivector and the
    // contraction, which costs about twice as much (bench/narrowphase_bench.cpp).
    // Tested against an independent 3×3 solve (tests/narrowphase_cases.hpp);
    // the manifold's cut, the same formula, against the generic meet.
    const Eigen::Vector3d point = (alpha * l1 - beta * l0) / (alpha - beta);
    const ConformalPoint I = up(point);
    const std::array<double, 3> bary{scalar_product(reciprocal[0], I), scalar_product(reciprocal[1], I),
                                     scalar_product(reciprocal[2], I)};
    if (bary[0] < 0 || bary[1] < 0 || bary[2] < 0) return std::nullopt;
    return collision::SegmentHit{point, alpha / (alpha - beta), bary};
  }
};

inline std::optional<collision::SegmentHit> segment_triangle(const Eigen::Vector3d& l0, const Eigen::Vector3d& l1,
                                                             const Eigen::Vector3d& t0, const Eigen::Vector3d& t1,
                                                             const Eigen::Vector3d& t2) {
  return PreparedTriangle(t0, t1, t2).through(l0, l1);
}

}  // namespace gacompare::cga
