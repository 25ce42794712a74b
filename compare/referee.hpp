#pragma once
// The collision referees: one convex–convex narrowphase query answered
// by two independent libraries, returned as a collision::PairContact with exactly
// the conventions of core/collision/collision.hpp (normal unit from a towards b; depth > 0
// the penetration depth when intersecting, depth ≤ 0 = −distance when apart;
// contact a world point midway between the two surfaces; feature = none).
//
// What each library does, and what we trust it for:
//
//   FCL 0.7 with libccd (GST_LIBCCD). Yes/no: trusted. `fcl::collide` decides
//     intersection by libccd's MPR (Minkowski portal refinement), exact up to its
//     termination tolerance (gjk_tolerance, 1e-6 by default). Depth: NOT trusted.
//     FCL's convex–convex penetration is MPR's, measured along the portal through
//     the line between the two interior points (vertex averages), so it is not
//     the minimum depth: it exceeded the exact minimum in 2,509 of 9,670 random
//     overlapping pairs of unit cubes (by up to 29%), by up to 2.35× on random
//     1 × 0.6 × 0.3 boxes, 4.3× on random mixed convex shapes and 17× on mixed
//     shapes of the same orientation. It is reported, never used as a yardstick
//     for depth. Distance when apart: libccd's GJK (`fcl::distance`,
//     tolerance 1e-6), which agreed with Bullet's to 1e-15 on separated cubes.
//
//   Bullet (double build, bullet-float64). btGjkPairDetector: GJK for the distance
//     when apart (exact up to rounding on polytopes: it stops when the simplex
//     stops moving, relative tolerance 1e-12 in double), and, when penetrating,
//     EPA (btGjkEpaPenetrationDepthSolver → btGjkEpaSolver2), iterative to an
//     absolute accuracy of 1e-12 in the double build. Trusted for yes/no, distance
//     and minimum penetration depth, with one caveat found here: Bullet's EPA
//     returns a wrong, self-contradictory answer on degenerate Minkowski
//     differences (two boxes with the same orientation: e.g. unit cubes offset by
//     exactly (0.9, 0, 0) give depth 0.0577 along (1,−1,−1)/√3 instead of 0.1
//     along x; 42% of same-orientation cube overlaps deeper than ~0.8). The
//     wrong answers are always self-contradictory, so bullet_collide checks every
//     answer against Bullet's own support mapping and retries in rigidly rotated
//     frames before it throws (see referee.cpp; what is left: 1.9% of
//     same-orientation unit-cube overlaps deeper than 0.78, none seen otherwise).
//
// Both shapes are built once per mesh, outside any timed per-pair loop, and are
// immutable afterwards: copies share the library object, and concurrent queries
// on the same shapes are safe (every query builds its own solver state).
#include "core/collision/collision.hpp"
#include "core/model/mesh.hpp"

#include <memory>
#include <string>

namespace gacompare::compare {

// fcl::Convex<double> from the mesh's vertices and triangles (body coordinates).
// Throws gacompare::input_error if the mesh is not convex (core::require_convex).
class FclShape {
 public:
  explicit FclShape(const core::Mesh& mesh);

  const std::string& name() const { return name_; }
  double size() const { return size_; }  // the mesh's size(): the length scale of tolerances

  struct Impl;  // defined in referee.cpp: the FCL headers stay out of this one
  const Impl& impl() const { return *impl_; }

 private:
  std::shared_ptr<const Impl> impl_;
  std::string name_;
  double size_ = 0;
};

// btConvexHullShape of the mesh's vertices (body coordinates), collision margin 0.
// Throws gacompare::input_error if the mesh is not convex.
class BulletShape {
 public:
  explicit BulletShape(const core::Mesh& mesh);

  const std::string& name() const { return name_; }
  double size() const { return size_; }

  struct Impl;  // defined in referee.cpp: the Bullet headers stay out of this one
  const Impl& impl() const { return *impl_; }

 private:
  std::shared_ptr<const Impl> impl_;
  std::string name_;
  double size_ = 0;
};

// FCL: intersection by MPR (contact depth and normal as FCL reports them), else
// distance by GJK. Where FCL has no direction to give (exactly touching bodies:
// MPR returns a zero normal), `normal` is the zero vector; nothing else is ever
// left at a default. Throws gacompare::run_error if FCL contradicts itself beyond
// its own tolerance (MPR says apart, GJK says penetrating by more than 1e-6).
collision::PairContact fcl_collide(const FclShape& a, const collision::Pose& pa,
                                   const FclShape& b, const collision::Pose& pb);

// Bullet: GJK distance / EPA penetration depth. Throws gacompare::run_error (one
// line naming both shapes) if Bullet returns no result, or only answers that fail
// the support-mapping check in every frame tried.
collision::PairContact bullet_collide(const BulletShape& a, const collision::Pose& pa,
                                      const BulletShape& b, const collision::Pose& pb);

}  // namespace gacompare::compare
