// The collision referees: FCL 0.7 (libccd) and Bullet (double) behind one
// PairContact. What each library computes and what we trust it for is in
// referee.hpp; the conversions of their conventions to ours are below, each next
// to the line that makes it.
#include "compare/referee.hpp"

#include "core/error.hpp"

#include <fcl/geometry/shape/capsule.h>
#include <fcl/geometry/shape/convex.h>
#include <fcl/geometry/shape/sphere.h>
#include <fcl/narrowphase/collision.h>
#include <fcl/narrowphase/distance.h>

#include <btBulletCollisionCommon.h>
#include <BulletCollision/NarrowPhaseCollision/btGjkEpaPenetrationDepthSolver.h>
#include <BulletCollision/NarrowPhaseCollision/btGjkPairDetector.h>
#include <BulletCollision/NarrowPhaseCollision/btPointCollector.h>
#include <BulletCollision/NarrowPhaseCollision/btVoronoiSimplexSolver.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

static_assert(sizeof(btScalar) == sizeof(double), "the Bullet referee needs the double build (bullet-float64)");

namespace gacompare::compare {

using collision::Mat3;
using collision::PairContact;
using collision::Pose;
using core::Vec3;

namespace {

std::string vec_text(const Vec3& v) {
  char buf[96];
  std::snprintf(buf, sizeof buf, "(%.9g, %.9g, %.9g)", v.x(), v.y(), v.z());
  return buf;
}

std::string pair_text(const char* who, const std::string& a, const Pose& pa, const std::string& b, const Pose& pb) {
  return std::string(who) + "(" + a + " at " + vec_text(pa.position) + ", " + b + " at " + vec_text(pb.position) + ")";
}

}  // namespace

// ---------------------------------------------------------------------------------
// FCL
// ---------------------------------------------------------------------------------

struct FclShape::Impl {
  std::shared_ptr<const fcl::CollisionGeometryd> geometry;  // fcl::Convexd, or fcl::Sphered / fcl::Capsuled for a round shape
};

namespace {
void require_referee_round(const core::Mesh& mesh) {
  if (mesh.sphere_centre() != Vec3::Zero() || mesh.capsule_half_axis().head<2>() != Eigen::Vector2d::Zero())
    throw input_error(mesh.name() + ": the referees need a round shape about its origin, a capsule along z");
}
}  // namespace

FclShape::FclShape(const core::Mesh& mesh) : name_(mesh.name()), size_(mesh.size()) {
  if (mesh.is_round()) {
    // FCL's own primitives, not the proxy polyhedron (core/model/mesh.hpp); about the
    // mesh's origin, where make_sphere and make_capsule put the centre.
    // fcl::Capsule(radius, lz): lz is the length between the hemispheres'
    // centres, along z (its AABB is ½ lz + radius along z), as ours.
    require_referee_round(mesh);
    auto impl = std::make_shared<Impl>();
    if (mesh.is_sphere())
      impl->geometry = std::make_shared<const fcl::Sphered>(mesh.sphere_radius());
    else
      impl->geometry = std::make_shared<const fcl::Capsuled>(mesh.sphere_radius(), 2 * mesh.capsule_half_axis().z());
    impl_ = std::move(impl);
    return;
  }
  core::require_convex(mesh);
  auto vertices = std::make_shared<std::vector<fcl::Vector3d>>(mesh.vertices().begin(), mesh.vertices().end());
  // FCL's face list: for each face its vertex count, then its vertex indices
  // (counter-clockwise seen from outside, as our triangles are).
  auto faces = std::make_shared<std::vector<int>>();
  faces->reserve(4 * mesh.triangles().size());
  for (const core::Triangle& t : mesh.triangles()) {
    faces->push_back(3);
    faces->insert(faces->end(), t.begin(), t.end());
  }
  auto impl = std::make_shared<Impl>();
  impl->geometry = std::make_shared<const fcl::Convexd>(vertices, static_cast<int>(mesh.triangles().size()), faces);
  impl_ = std::move(impl);
}

namespace {

fcl::Transform3d to_fcl(const Pose& p) {
  fcl::Transform3d t = fcl::Transform3d::Identity();
  t.linear() = p.rotation;
  t.translation() = p.position;
  return t;
}

// libccd's termination tolerances as FCL sets them by default (CollisionRequest::
// gjk_tolerance, DistanceRequest::distance_tolerance): MPR and GJK may disagree by
// this much near contact.
constexpr double kFclTolerance = 1e-6;

}  // namespace

PairContact fcl_collide(const FclShape& a, const Pose& pa, const FclShape& b, const Pose& pb) {
  const fcl::Transform3d ta = to_fcl(pa), tb = to_fcl(pb);
  const fcl::CollisionGeometryd* ga = a.impl().geometry.get();
  const fcl::CollisionGeometryd* gb = b.impl().geometry.get();
  PairContact out;  // feature stays Feature::none: the referees name no features

  fcl::CollisionRequestd request;
  request.num_max_contacts = 1;
  request.enable_contact = true;
  request.gjk_solver_type = fcl::GST_LIBCCD;
  fcl::CollisionResultd result;
  fcl::collide(ga, ta, gb, tb, request, result);
  if (result.isCollision()) {
    const fcl::Contactd& c = result.getContact(0);
    out.intersect = true;
    // MPR's depth along MPR's direction: never below the minimum by more than
    // MPR's 1e-6 tolerance on 47,000 random overlaps (1.4e-7 at worst), often far
    // above it (referee.hpp). Reported as is, not trusted for depth.
    out.depth = c.penetration_depth;
    // FCL 0.7 (fcl/narrowphase/contact.h): "contact normal, pointing from o1 to
    // o2"; o1 = a, so it is already ours. Checked, not assumed: b at (0.9, 0, 0)
    // from a gives (1, 0, 0) (referee_test). For exactly touching bodies MPR
    // returns depth ~1e-16 and a zero normal (seen: unit cubes at (1, 0.3, 0.1));
    // then there is no direction and the normal stays zero.
    const double length = c.normal.norm();
    if (length > 0) out.normal = c.normal / length;
    // contact.pos, in world coordinates: libccd's MPR point, the average of the
    // support points of the final portal on a and on b weighted by the origin's
    // barycentric coordinates in it, i.e. halfway between a point of a's surface
    // and a point of b's surface along the penetration direction (for cubes
    // overlapping by 0.1 along x it lies at x midway between the two faces).
    out.contact = c.pos;
    return out;
  }

  fcl::DistanceRequestd dreq;
  dreq.enable_nearest_points = true;
  dreq.gjk_solver_type = fcl::GST_LIBCCD;
  // Signed: where MPR said "apart" but GJK finds the origin inside the Minkowski
  // difference (bodies touching within rounding, e.g. unit cubes stacked at
  // (0, 0, 1)), the unsigned GJK returns min_distance = −1 and zero nearest
  // points; the signed one runs libccd's EPA there and returns ≈ 0 and real
  // points. Apart, both are the same GJK.
  dreq.enable_signed_distance = true;
  fcl::DistanceResultd dres;
  fcl::distance(ga, ta, gb, tb, dreq, dres);
  const double distance = dres.min_distance;
  if (!std::isfinite(distance) ||
      distance < -(kFclTolerance + collision::kTouchingBand * std::max(a.size(), b.size())))
    throw run_error(pair_text("fcl_collide", a.name(), pa, b.name(), pb) +
                    ": MPR says apart but GJK/EPA says penetrating by " + std::to_string(-distance));
  // FCL 0.7's nearest points for a convex pair through libccd are in world
  // coordinates (checked by referee_test with poses 1e4 from the origin; older
  // FCL returned them in each body's frame).
  const Vec3 on_a = dres.nearest_points[0];
  const Vec3 on_b = dres.nearest_points[1];
  out.intersect = false;
  // depth = −distance; a negative distance within the tolerance above is the
  // touching case (MPR decided "apart"), reported as depth 0.
  out.depth = std::min(-distance, 0.0);
  const Vec3 gap = on_b - on_a;
  const double length = gap.norm();
  if (distance > 0 && length > 0) out.normal = gap / length;
  out.contact = 0.5 * (on_a + on_b);
  return out;
}

// ---------------------------------------------------------------------------------
// Bullet
// ---------------------------------------------------------------------------------

struct BulletShape::Impl {
  std::unique_ptr<btConvexShape> shape;  // btConvexHullShape, or btSphereShape / btCapsuleShapeZ for a round shape
};

BulletShape::BulletShape(const core::Mesh& mesh) : name_(mesh.name()), size_(mesh.size()) {
  auto impl = std::make_shared<Impl>();
  if (mesh.is_round()) {
    // Bullet's primitives: a point (a segment) grown by its margin, the radius
    // (so GJK runs on the centre or the segment and adds the radius back:
    // exact). btCapsuleShapeZ(radius, height): height is the length between
    // the hemispheres' centres along z ("the total height is height +
    // 2 radius"), as ours.
    require_referee_round(mesh);
    if (mesh.is_sphere())
      impl->shape = std::make_unique<btSphereShape>(mesh.sphere_radius());
    else
      impl->shape = std::make_unique<btCapsuleShapeZ>(mesh.sphere_radius(), 2 * mesh.capsule_half_axis().z());
    impl_ = std::move(impl);
    return;
  }
  core::require_convex(mesh);
  auto hull = std::make_unique<btConvexHullShape>();
  for (const Vec3& v : mesh.vertices()) hull->addPoint(btVector3(v.x(), v.y(), v.z()), false);
  // Margin 0: the hull is the mesh itself, not the mesh grown by a rounded skin
  // (Bullet's default margin 0.04 would add 0.04 to every depth).
  hull->setMargin(0);
  hull->recalcLocalAabb();
  impl->shape = std::move(hull);
  impl_ = std::move(impl);
}

namespace {

btTransform to_bullet(const Mat3& r, const Vec3& t) {
  const btMatrix3x3 basis(r(0, 0), r(0, 1), r(0, 2),  //
                          r(1, 0), r(1, 1), r(1, 2),  //
                          r(2, 0), r(2, 1), r(2, 2));
  return btTransform(basis, btVector3(t.x(), t.y(), t.z()));
}

Vec3 to_eigen(const btVector3& v) { return {v.x(), v.y(), v.z()}; }

// The frames a query is tried in: the world frame (turned only by the identity,
// so the first try is Bullet's own answer), then the whole configuration turned
// rigidly by fixed generic rotations. The geometry is the same in every frame;
// only the rounding inside GJK/EPA differs, which is what decides whether EPA's
// polytope expansion runs into the degenerate (coplanar, coincident) support
// points of two boxes with the same orientation. Measured on unit cubes of the
// same orientation with centres within 0.1 of each other (overlaps 0.8 to 1
// deep), 42% fail in the world frame and 1.9% still fail in all five frames
// (then bullet_collide throws; every such pair was deeper than 0.78); within 0.6,
// 0.01% fail in all five. Random orientations and mixed shapes (boxes,
// tetrahedra, octahedra, icosahedra, pyramids, a 40-point hull): no failure in
// 40,000 pairs.
std::array<Mat3, 5> make_frames() {
  std::array<Mat3, 5> frames;
  frames[0] = Mat3::Identity();
  for (int k = 1; k < 5; ++k) {
    const double t = k - 1;
    frames[k] = (Eigen::AngleAxisd(0.3 + 1.7 * t, Vec3::UnitZ()) * Eigen::AngleAxisd(0.7 + 0.9 * t, Vec3::UnitY()) *
                 Eigen::AngleAxisd(1.1 + 0.4 * t, Vec3::UnitX()))
                    .toRotationMatrix();
  }
  return frames;
}
const std::array<Mat3, 5> kFrames = make_frames();

// An answer is accepted when it agrees with Bullet's own support mapping: the
// overlap of the two bodies' projections on the returned normal must equal the
// returned depth (= −distance). This holds for every correct answer, apart or
// penetrating (the minimum translation and the closest points both lie along
// the normal), and fails by a large amount for EPA's degenerate answers (0.05 to
// 0.8 on unit cubes, where the wrong normal is off by tens of degrees). Correct
// answers meet it to 1.3e-11 × scale at worst over 80,000 random pairs of mixed
// shapes (EPA's accuracy is 1e-12); 1e-8 × scale leaves a factor ~1000 for
// other shapes and is still 10^6 below the failures.
constexpr double kSupportCheck = 1e-8;

struct BulletTry {
  bool has_result = false;
  double distance = 0;      // Bullet's: < 0 penetrating
  Vec3 normal_ab;           // unit, a → b, in the try's frame
  Vec3 contact;             // in the try's frame
  double mismatch = 0;      // |overlap along normal − depth|
};

BulletTry bullet_try(const btConvexShape& a, const btTransform& ta, const btConvexShape& b,
                     const btTransform& tb) {
  btVoronoiSimplexSolver simplex;
  btGjkEpaPenetrationDepthSolver epa;
  btGjkPairDetector detector(&a, &b, &simplex, &epa);
  btDiscreteCollisionDetectorInterface::ClosestPointInput input;
  input.m_transformA = ta;
  input.m_transformB = tb;
  // Report separated pairs at any distance (the default input would too, but say so).
  input.m_maximumDistanceSquared = BT_LARGE_FLOAT;
  btPointCollector output;
  detector.getClosestPoints(input, output, nullptr);

  BulletTry r;
  if (!output.m_hasResult || !std::isfinite(output.m_distance)) return r;
  const btVector3 n_on_b = output.m_normalOnBInWorld;  // points from B to A
  const btScalar length = n_on_b.length();
  if (!(std::abs(length - 1) < 1e-6)) return r;  // not a direction: no result
  r.has_result = true;
  r.distance = output.m_distance;  // < 0 penetrating, > 0 apart
  r.normal_ab = -to_eigen(n_on_b) / length;
  // m_pointInWorld is on B; the matching point on A is pointOnB + normalOnB · distance
  // (apart: from B's surface across the gap to A's; penetrating: back through the
  // overlap). The contact is midway.
  const btVector3 on_b = output.m_pointInWorld;
  const btVector3 on_a = on_b + n_on_b * output.m_distance;
  r.contact = to_eigen((on_a + on_b) * 0.5);

  // The support-mapping check, with Bullet's own support functions (margin
  // included: 0 for a hull, the radius of a sphere).
  const btVector3 n(r.normal_ab.x(), r.normal_ab.y(), r.normal_ab.z());
  const btVector3 far_a = ta(a.localGetSupportingVertex(n * ta.getBasis()));   // max of n·x over A
  const btVector3 near_b = tb(b.localGetSupportingVertex(-n * tb.getBasis()));  // min of n·x over B
  const double overlap = n.dot(far_a - near_b);
  r.mismatch = std::abs(overlap - (-r.distance));
  return r;
}

}  // namespace

PairContact bullet_collide(const BulletShape& a, const Pose& pa, const BulletShape& b, const Pose& pb) {
  const double scale = std::max(a.size(), b.size());  // as collision::pair_scale
  // Every frame is centred midway between the two positions, as Bullet centres
  // its own GJK: the check above then runs on coordinates of the pair's size.
  const Vec3 centre = 0.5 * (pa.position + pb.position);
  int no_result = 0;
  BulletTry worst;
  for (const Mat3& q : kFrames) {
    const BulletTry r = bullet_try(*a.impl().shape, to_bullet(q * pa.rotation, q * (pa.position - centre)), *b.impl().shape,
                                   to_bullet(q * pb.rotation, q * (pb.position - centre)));
    if (!r.has_result) {
      ++no_result;
      continue;
    }
    if (r.mismatch <= kSupportCheck * scale) {
      PairContact out;
      out.intersect = r.distance < 0;
      out.depth = -r.distance;
      out.normal = q.transpose() * r.normal_ab;
      out.contact = q.transpose() * r.contact + centre;
      return out;
    }
    if (!worst.has_result || r.mismatch > worst.mismatch) worst = r;
  }
  std::string why = std::to_string(no_result) + " of " + std::to_string(kFrames.size()) + " tries returned no result";
  if (worst.has_result)
    why += "; the rest failed the support check (worst: depth " + std::to_string(-worst.distance) +
           " but overlap along its normal off by " + std::to_string(worst.mismatch) + ")";
  throw run_error(pair_text("bullet_collide", a.name(), pa, b.name(), pb) + ": Bullet GJK/EPA gave no valid answer: " + why);
}

}  // namespace gacompare::compare
