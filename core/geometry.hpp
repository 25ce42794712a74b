#pragma once
// Results of the geometric operations, shared by both backends:
// traditional/geometry.hpp and cga/geometry/*.hpp return these Euclidean answers,
// so a test or the harness compares them field by field. Degenerate inputs get a
// kind, never a NaN; the thresholds that decide it are here, once.
#include <Eigen/Core>

#include <cstdint>

namespace gacompare::geometry {

// What an operation produced. Degenerate inputs get a kind, never a NaN: the
// caller can tell "the inputs define nothing" from "well defined, no hit".
enum class Kind : std::uint8_t {
  none,        // well posed, empty: spheres apart, line misses sphere, image at infinity
  tangent,     // touching in a single point (line–sphere, sphere–sphere, sphere–plane)
  point,       // a transversal single point (line–plane)
  point_pair,  // line–sphere secant
  circle,      // circumcircle, sphere–sphere, sphere–plane
  line,        // plane–plane
  sphere,      // sphere through 4 points
  parallel,    // line ∥ plane, plane ∥ plane, disjoint
  contained,   // line in the plane, coincident planes, coincident spheres
  degenerate,  // the inputs define no entity: coincident / collinear / coplanar points, radius ≤ 0
};

// Dimensionless thresholds, one geometric predicate in both backends (each
// backend computes the same quantity its own way; only rounding differs).
//
// kSinTol: the sine of the angle that vanishes at the degeneracy: the angle at
// the first point (collinear), the normalised volume a·(b×c)/(|a||b||c|)
// (coplanar), line against plane and plane against plane (parallel). Below 1e-11
// an answer would carry a relative error of eps/sin ≈ 2e-5 or worse (fewer than
// five digits), so we call the case degenerate instead; the issue's
// near-degenerate inputs (1e-9 from collinear or coplanar, sin ≈ 1e-9) are 100×
// above it and are solved, and exactly degenerate inputs (sin at rounding level,
// ≲ 1e-14 in the conformal backend for |x| ≲ 5) are 1000× below it.
//
// kRelTol: a distance compared with the magnitudes of the inputs that produced
// it (coincident points, a line lying in a plane, coincident planes/spheres):
// rounding of those inputs is eps·|input|, so anything within 1e-11 of them is
// indistinguishable from equal after a few operations.
//
// Tangency is a gap, not an angle: near contact the sine of the angle between
// the surfaces grows like the square root of the gap g (sin² = 2g/ρ for a line
// at distance ρ − g from the centre, 2(ρ1+ρ2)g/(ρ1ρ2) for two spheres), so a
// tangent configuration built in doubles, with g at rounding level, already has
// sin ≈ 1e-8. We therefore compare sin² (∝ the relative gap) with kTangentTol =
// 2·kRelTol: tangent when the gap is within kRelTol of the radius.
inline constexpr double kSinTol = 1e-11;
inline constexpr double kRelTol = 1e-11;
inline constexpr double kTangentTol = 2 * kRelTol;

struct PointResult {  // line–plane, reflection in a sphere
  Kind kind = Kind::none;
  Eigen::Vector3d point = Eigen::Vector3d::Zero();
};
struct PairResult {  // line–sphere: first before second along the line's direction
  Kind kind = Kind::none;
  Eigen::Vector3d first = Eigen::Vector3d::Zero(), second = Eigen::Vector3d::Zero();
};
struct CircleResult {  // tangent: centre is the touching point, radius 0
  Kind kind = Kind::none;
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  double radius = 0;
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();  // unit; orientation documented per operation
};
struct SphereResult {
  Kind kind = Kind::none;
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  double radius = 0;
};
struct LineResult {  // point: the line's point nearest the origin; direction unit
  Kind kind = Kind::none;
  Eigen::Vector3d point = Eigen::Vector3d::Zero(), direction = Eigen::Vector3d::Zero();
};

// The rotation of the quaternion (w, x, y, z) of any non-zero norm: the
// homogeneous form (every entry quadratic) over w² + x² + y² + z², an exact
// rotation for a drifted quaternion, rotor or motor alike, with one division
// and no square root (cga's rotor and pga's motor read their rotation here).
inline Eigen::Matrix3d rotation_of(double w, double x, double y, double z) {
  const double s = 1 / (w * w + x * x + y * y + z * z);
  Eigen::Matrix3d m;
  m << w * w + x * x - y * y - z * z, 2 * (x * y - w * z), 2 * (x * z + w * y),
       2 * (x * y + w * z), w * w - x * x + y * y - z * z, 2 * (y * z - w * x),
       2 * (x * z - w * y), 2 * (y * z + w * x), w * w - x * x - y * y + z * z;
  return s * m;
}

}  // namespace gacompare::geometry
