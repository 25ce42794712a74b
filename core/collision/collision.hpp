#pragma once
// What every collision query answers (§2.4): the two backends'
// narrowphases (traditional/narrowphase.hpp, cga/narrowphase.hpp), the exact
// separating-axis reference (core/sat.hpp) and the referees FCL and Bullet
// (compare/referee.hpp) all return a PairContact, so the harness and the tests
// compare them field by field.
//
// Conventions, once:
//   - A body is a convex Mesh in body coordinates placed by a Pose:
//     x_world = rotation · x_body + position.
//   - `normal` is a unit vector pointing from a towards b: moving b by
//     depth · normal (or a by −depth · normal) separates the pair.
//   - `depth` > 0 is the minimum penetration depth (the shortest translation
//     that separates the bodies). depth ≤ 0 means apart; −depth is then the gap
//     along the best separating axis found, which the separating-axis test only
//     guarantees to be a lower bound of the distance (the closest points of two
//     separated polyhedra need not lie along a face normal or an edge × edge
//     axis). FCL and Bullet report the true distance there.
//   - Within the touching band |signed distance| ≤ kTouchingBand · scale the
//     yes/no answer is decided by rounding, not by geometry: agreement is only
//     asked for outside it.
#include "core/model/mesh.hpp"

#include <Eigen/Core>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>

namespace gacompare::collision {

using core::Mesh;
using core::Vec3;
using Mat3 = Eigen::Matrix3d;

struct Pose {
  Mat3 rotation = Mat3::Identity();
  Vec3 position = Vec3::Zero();
  Vec3 apply(const Vec3& x) const { return rotation * x + position; }
};

// How far a unit vector of the body's frame can move between two of its
// rotations, at most: an upper bound of the spectral norm ‖R1 − R0‖₂ (a
// point at r from the centre moves by at most this times r).
//
// For two rotations Q0, Q1 it is ‖Q1 − Q0‖_F / √2 exactly: Q1 Q0ᵀ has the
// eigenvalues 1, e^{±iθ}, so Q1 − Q0 has the singular values 0, 2 sin(θ/2)
// twice, where the Frobenius norm, the bound used before, is √2 times
// larger. A pose's matrix is a rotation only to rounding (and a scene may
// integrate the matrix itself), so each Rᵢ is taken as Qᵢ(I + Sᵢ), its polar
// decomposition: with dᵢ = ‖RᵢᵀRᵢ − I‖_F ≤ 1/2, every eigenvalue μ of Sᵢ
// has |2μ + μ²| ≤ 1/2, so |μ| ≤ 0.3 and ‖Sᵢ‖_F ≤ dᵢ, and
//   ‖R1 − R0‖₂ ≤ ‖Q1 − Q0‖_F/√2 + d0 + d1 ≤ ‖R1 − R0‖_F/√2 + (1 + 1/√2)(d0 + d1).
// Where a matrix is further from a rotation (or turns space inside out),
// the Frobenius norm, always a bound, is used. Rounding of the sums: the
// caller's margin.
inline double rotation_change_bound(const Mat3& r0, const Mat3& r1) {
  const double frobenius = (r1 - r0).norm();
  const double d0 = (r0.transpose() * r0 - Mat3::Identity()).norm(), d1 = (r1.transpose() * r1 - Mat3::Identity()).norm();
  if (!(d0 <= 0.5 && d1 <= 0.5) || !(r0.determinant() > 0 && r1.determinant() > 0)) return frobenius;
  return std::min(frobenius, frobenius / std::sqrt(2.0) + (1 + 1 / std::sqrt(2.0)) * (d0 + d1 + 1e-15));
}

// A convex body where it is: the mesh (owned elsewhere) and its pose.
struct Placed {
  const Mesh* mesh = nullptr;
  Pose pose;
};

// Which kind of contact decided the answer: the separating-axis family that
// gave the minimum (face of a, face of b, edge of a × edge of b), or the
// report's features (§2.4.3 vertex in body, §2.4.4 edge through facet).
enum class Feature : std::uint8_t { none, face_a, face_b, edge_edge };
const char* feature_name(Feature f);

struct PairContact {
  bool intersect = false;
  double depth = 0;               // see the conventions above
  Vec3 normal = Vec3::Zero();     // unit, from a towards b
  Vec3 contact = Vec3::Zero();    // a world point in the overlap (midway between the surfaces)
  Feature feature = Feature::none;
};

// One point contact of the report's detector (fig. 7), the input of the
// impulse response (§2.5): where, along which normal (from a towards b), how
// deep, and which features met. A pair may have several.
struct FeatureContact {
  Vec3 point = Vec3::Zero();
  Vec3 normal = Vec3::Zero();
  double depth = 0;
  Feature feature = Feature::none;  // face_a: a vertex of b in a face of a; face_b: the reverse
};

// A segment through a triangle (§2.4.4): the point, its parameter along the
// segment (0 at the first end, 1 at the second) and its barycentric
// coordinates in the triangle (t0, t1, t2). Both backends' segment_triangle
// return this, for the tests to compare.
struct SegmentHit {
  Vec3 point = Vec3::Zero();
  double r = 0;
  std::array<double, 3> barycentric{0, 0, 0};
};

// The touching band, relative to the pair's length scale. 1e-9: the signed
// distance is computed from coordinates of size ~scale (after moving to a local
// origin) through a few dozen operations, so its rounding is ~1e-14 · scale;
// near-parallel edge axes (sin θ down to 1e-6 in the corpus) amplify that by
// 1/sin θ. 1e-9 keeps the band above every such error and still far below any
// penetration tolerance a scene uses (≥ 1e-6 · size).
inline constexpr double kTouchingBand = 1e-9;
inline double pair_scale(const Mesh& a, const Mesh& b) { return std::max(a.size(), b.size()); }

}  // namespace gacompare::collision
