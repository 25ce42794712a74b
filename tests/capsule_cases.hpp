#pragma once
// Capsules (core/collision/capsule.hpp) through a backend: mass
// properties against a numerically integrated solid of revolution; the
// narrowphase on generated families of degenerate placements (aligned,
// turned by 90° and by 1e-9, shifted by 0 and 1e-9, parallel to a face,
// across an edge, inside the box, coincident, zero length) against their
// closed forms and against brute force (the segment densely sampled, each
// sample a sphere through the sphere narrowphase, the best refined by
// golden-section search); the corpus (data/collision/capsule.json) against
// the long-double reference (core/collision/separating_axis.cpp capsule_reference);
// and the capsule scenes (data/scenes/capsule_*.json) against their analytic
// answers. Instantiated by tests/{traditional,cga}/capsule_test.cpp;
// `Backend` is a tag with the backend type and narrowphase() (as
// tests/round_cases.hpp). The backends against each other and against FCL
// and Bullet: tests/compare/capsule_referee_test.cpp.
#include "round_cases.hpp"

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <functional>
#include <memory>
#include <numbers>
#include <string>
#include <vector>

namespace gacompare::testing {

namespace capsule {

using Eigen::Vector3d;
using Mesh = core::Mesh;

inline double angle(const Vector3d& a, const Vector3d& b) { return std::atan2(a.cross(b).norm(), a.dot(b)); }

// A rotation taking z to `axis` (the capsule's local axis to the world's).
inline Eigen::Matrix3d along(const Vector3d& axis) {
  return Eigen::Quaterniond::FromTwoVectors(Vector3d::UnitZ(), axis).toRotationMatrix();
}

// The least of a convex function on [0, 1]: the best of n + 1 samples, then
// golden-section search between its neighbours.
inline double convex_minimum(const std::function<double(double)>& f, int n = 400) {
  int best = 0;
  double fb = f(0);
  for (int i = 1; i <= n; ++i)
    if (const double v = f(static_cast<double>(i) / n); v < fb) fb = v, best = i;
  double lo = std::max(0.0, (best - 1.0) / n), hi = std::min(1.0, (best + 1.0) / n);
  const double g = (std::sqrt(5.0) - 1) / 2;
  double x1 = hi - g * (hi - lo), x2 = lo + g * (hi - lo), f1 = f(x1), f2 = f(x2);
  for (int i = 0; i < 80; ++i) {
    if (f1 <= f2) hi = x2, x2 = x1, f2 = f1, x1 = hi - g * (hi - lo), f1 = f(x1);
    else lo = x1, x1 = x2, f1 = f2, x2 = lo + g * (hi - lo), f2 = f(x2);
  }
  return std::min({fb, f1, f2});
}

// One generated pair with its closed-form answer where it has one.
struct Family {
  std::string name;
  std::shared_ptr<const Mesh> a, b;
  collision::Pose pa, pb;
  double gap = NAN;             // the closed form's signed distance (NAN: none)
  Vector3d normal = Vector3d::Zero();  // a → b, zero where not unique
  int contacts = -1;            // feature contacts within the band (−1: not stated)
};

inline collision::Pose pose(const Eigen::Matrix3d& r, const Vector3d& p) {
  collision::Pose q;
  q.rotation = r, q.position = p;
  return q;
}

// The families, each also turned as a whole by a generic rotation and moved
// (the answer turns with it): identity and q.
inline std::vector<Family> families() {
  std::vector<Family> out;
  const auto cap = [](double r, double l) { return std::make_shared<const Mesh>(core::make_capsule(r, l)); };
  const auto box = std::make_shared<const Mesh>(core::make_box({1, 1, 1}));
  const double e = 1e-9;
  // Capsule–capsule: a (0.2, 1) along z; b (0.3, 0.8) at distance D across y.
  const auto ca = cap(0.2, 1), cb = cap(0.3, 0.8);
  for (const double gap : {-0.05, 0.0, 0.1}) {
    const double d = 0.5 + gap;
    for (const double shift : {0.0, e, 0.3}) {
      const std::string tag = " gap " + std::to_string(gap) + " shift " + std::to_string(shift);
      out.push_back({"aligned" + tag, ca, cb, {}, pose(Eigen::Matrix3d::Identity(), {0, d, shift}), gap,
                     Vector3d::UnitY(), gap <= 0 ? 2 : 0});
      out.push_back({"crossed 90" + tag, ca, cb, {}, pose(along(Vector3d::UnitX()), {0, d, shift}), gap,
                     Vector3d::UnitY(), gap <= 0 ? 1 : 0});
      // Turned by 1e-9 about x: b's end at +z comes 0.4 sin(1e-9) nearer a's
      // line, or (shifted 0.3, that end beyond a's at z = 0.5) b's point
      // beside a's end, 0.2 along.
      const Vector3d tilted(0, -std::sin(e), std::cos(e));
      out.push_back({"turned 1e-9" + tag, ca, cb, {}, pose(along(tilted), {0, d, shift}),
                     gap - (shift > 0.1 ? 0.2 : 0.4) * std::sin(e),
                     Vector3d::Zero(), gap <= 0 ? 2 : 0});
    }
    // End to end along the axis, apart by the gap: one contact.
    out.push_back({"end to end gap " + std::to_string(gap), ca, cb, {}, pose(Eigen::Matrix3d::Identity(), {0, 0, 0.9 + d}),
                   gap, Vector3d::UnitZ(), gap <= 0 ? 1 : 0});
  }
  out.push_back({"coincident", ca, ca, {}, {}, -0.4, Vector3d::Zero(), 2});
  // Capsule–sphere: the sphere's centre on the segment, beside its middle and beyond its end.
  const auto ball = std::make_shared<const Mesh>(core::make_sphere(0.25));
  out.push_back({"sphere on the segment", ca, ball, {}, pose(Eigen::Matrix3d::Identity(), {0, 0, 0.2}), -0.45,
                 Vector3d::Zero(), 1});
  for (const double gap : {-0.05, 0.0, 0.1}) {
    out.push_back({"sphere beside " + std::to_string(gap), ca, ball, {}, pose(Eigen::Matrix3d::Identity(), {0.45 + gap, 0, 0.1}),
                   gap, Vector3d::UnitX(), gap <= 0 ? 1 : 0});
    out.push_back({"sphere beyond the end " + std::to_string(gap), ball, ca, pose(Eigen::Matrix3d::Identity(), {0, 0, 0.95 + gap}), {},
                   gap, -Vector3d::UnitZ(), gap <= 0 ? 1 : 0});
  }
  // Capsule (0.1, 0.6) on the unit box (a, the polyhedron, or b).
  const auto c6 = cap(0.1, 0.6), c2 = cap(0.1, 2);
  const Eigen::Matrix3d x_axis = along(Vector3d::UnitX());
  for (const double gap : {-0.05, 0.0, 0.1}) {
    const std::string g = " gap " + std::to_string(gap);
    const double h = 0.5 + 0.1 + gap;  // the axis above the top face
    for (const double shift : {0.0, e}) {
      const std::string tag = g + " shift " + std::to_string(shift);
      out.push_back({"flat on face" + tag, box, c6, {}, pose(x_axis, {0.1 + shift, 0.05, h}), gap, Vector3d::UnitZ(),
                     gap <= 0 ? 2 : 0});
      out.push_back({"turned 1e-9 on face" + tag, c6, box, pose(along({std::cos(e), 0, std::sin(e)}), {0.1 + shift, 0.05, h}),
                     {}, gap - 0.3 * std::sin(e), Vector3d::Zero(), gap <= 0 ? 2 : 0});
      out.push_back({"end down" + tag, box, c6, {}, pose(Eigen::Matrix3d::Identity(), {0.1, 0.05 + shift, h + 0.3}), gap,
                     Vector3d::UnitZ(), gap <= 0 ? 1 : 0});
      // Half over the face, across its edge x = 0.5: the face's prism clips it at the edge.
      out.push_back({"across an edge" + tag, box, c6, {}, pose(x_axis, {0.5 + shift, 0.05, h}), gap, Vector3d::UnitZ(),
                     gap <= 0 ? 2 : 0});
    }
    // Along the edge x = z = 0.5, off it at 45°: a ridge, one contact.
    const Vector3d out45 = Vector3d(1, 0, 1).normalized();
    out.push_back({"along an edge" + g, box, c6, {}, pose(along(Vector3d::UnitY()), Vector3d(0.5, 0, 0.5) + (0.1 + gap) * out45),
                   gap, out45, gap <= 0 ? 1 : 0});
  }
  // Inside: the segment x ∈ [−0.2, 0.4] at z = 0.2 clears the top face by
  // moving 0.3 (the other faces need 0.5 and more), so 0.3 + r deep.
  out.push_back({"inside the box", box, c6, {}, pose(x_axis, {0.1, 0, 0.2}), -0.4, Vector3d::UnitZ(), 2});
  // Through it, ends outside: 0.2 up clears it (x needs 1.5, y 0.4).
  out.push_back({"through the box", c2, box, pose(x_axis, {0, 0.1, 0.3}), {}, -0.3, -Vector3d::UnitZ(), 2});
  // Zero length is the sphere itself (core/model/mesh.hpp make_capsule).
  const auto c0 = cap(0.1, 0);
  out.push_back({"zero length on face", box, c0, {}, pose(x_axis, {0.1, 0.05, 0.6}), 0, Vector3d::UnitZ(), 1});
  // Turned as a whole: a generic rotation about the origin and a move.
  const Eigen::Matrix3d q = Eigen::Quaterniond(Eigen::Vector4d(0.3, -0.5, 0.7, 0.4).normalized()).toRotationMatrix();
  const Vector3d move(0.3, -1.2, 0.7);
  const std::size_t n = out.size();
  for (std::size_t i = 0; i < n; ++i) {
    Family f = out[i];
    f.name += " (turned)";
    f.pa = pose(q * f.pa.rotation, q * f.pa.position + move), f.pb = pose(q * f.pb.rotation, q * f.pb.position + move);
    f.normal = q * f.normal;
    out.push_back(f);
  }
  return out;
}

// Brute force for an apart pair: each sample of the capsule's segment a
// sphere of its radius against the other body, through the backend's sphere
// narrowphase (core/collision/round.hpp), least gap refined by golden section.
template <class Backend>
double brute_gap(const Family& f) {
  const bool a_capsule = f.a->is_capsule();
  const Mesh& c = a_capsule ? *f.a : *f.b;
  const collision::Pose& pc = a_capsule ? f.pa : f.pb;
  const auto ball = std::make_shared<const Mesh>(core::make_sphere(c.sphere_radius()));
  const Vector3d p0 = pc.apply(c.sphere_centre() - c.capsule_half_axis()), d = 2 * (pc.rotation * c.capsule_half_axis());
  return convex_minimum([&](double s) {
    collision::Pose at;
    at.position = p0 + s * d;
    const collision::Placed sphere{ball.get(), at}, other = a_capsule ? collision::Placed{f.b.get(), f.pb}
                                                                      : collision::Placed{f.a.get(), f.pa};
    return -Backend::narrowphase(sphere, other, collision::Method::sat_then_manifold, nullptr).depth;
  });
}

}  // namespace capsule

// The spheres' fixture (its scene loader).
template <class Backend>
class CapsuleCases : public RoundCases<Backend> {};
TYPED_TEST_SUITE_P(CapsuleCases);

// Mass properties against the capsule integrated numerically as a solid of
// revolution about z: disks of radius ρ(z) (r on the cylinder, √(r² − (|z| −
// ½L)²) on the caps), mass π ρ² dz, moment ½ π ρ⁴ dz about the axis and
// (¼ π ρ⁴ + π ρ² z²) dz across it, by composite Simpson on each piece with
// 2000 intervals. The integrands are polynomials of degree ≤ 4 in z, so
// Simpson's error is ~(h/2000)⁴ relative: 1e-12 relative bounds it.
// Also: length 0 is the sphere (same mass properties, to the bit); the
// inradius about the centre is r; the proxy's vertices all lie on the
// capsule, its box is [−r, r]² × [−(½L + r), ½L + r] and its farthest vertex
// ½L + r from the centre (the broadphase's sphere), to rounding.
TYPED_TEST_P(CapsuleCases, CapsuleMassPropertiesMatchTheSolidOfRevolution) {
  for (const auto& [r, l] : {std::pair{0.3, 1.2}, std::pair{0.1, 0.3}, std::pair{1.0, 1e-3}, std::pair{0.05, 4.0}}) {
    const core::Mesh m = core::make_capsule(r, l);
    const auto p = core::mass_properties(m, 2.0);
    const double h = 0.5 * l;
    const auto rho2 = [&](double z) { return std::abs(z) <= h ? r * r : std::max(0.0, r * r - (std::abs(z) - h) * (std::abs(z) - h)); };
    double mass = 0, axial = 0, across = 0;
    const auto simpson = [&](double z0, double z1) {
      const int n = 2000;
      const double dz = (z1 - z0) / n;
      for (int i = 0; i <= n; ++i) {
        const double z = z0 + i * dz, w = (i == 0 || i == n ? 1 : i % 2 ? 4 : 2) * dz / 3;
        const double a2 = rho2(z);
        mass += w * std::numbers::pi * a2;
        axial += w * 0.5 * std::numbers::pi * a2 * a2;
        across += w * (0.25 * std::numbers::pi * a2 * a2 + std::numbers::pi * a2 * z * z);
      }
    };
    simpson(-h - r, -h), simpson(-h, h), simpson(h, h + r);
    mass *= 2, axial *= 2, across *= 2;  // density 2
    EXPECT_NEAR(p.mass, mass, 1e-12 * mass) << r << " " << l;
    EXPECT_NEAR(p.inertia(2, 2), axial, 1e-12 * axial) << r << " " << l;
    EXPECT_NEAR(p.inertia(0, 0), across, 1e-12 * across) << r << " " << l;
    EXPECT_NEAR(p.inertia(1, 1), across, 1e-12 * across) << r << " " << l;
    EXPECT_EQ(p.inertia(0, 1), 0);
    EXPECT_EQ(p.inertia(0, 2), 0);
    EXPECT_EQ(p.inertia(1, 2), 0);
    EXPECT_EQ(p.centre_of_mass, Eigen::Vector3d::Zero());
    EXPECT_NEAR(core::inradius(m, Eigen::Vector3d::Zero()), r, 1e-15 * r);
    Eigen::Vector3d lo = Eigen::Vector3d::Constant(INFINITY), hi = -lo;
    double far = 0;
    for (const auto& v : m.vertices()) {
      const double t = std::clamp(v.z(), -h, h);
      EXPECT_NEAR((v - Eigen::Vector3d(0, 0, t)).norm(), r, 1e-15 * (r + h));
      lo = lo.cwiseMin(v), hi = hi.cwiseMax(v), far = std::max(far, v.norm());
    }
    EXPECT_NEAR((hi - Eigen::Vector3d(r, r, h + r)).norm(), 0, 1e-15 * (r + h));
    EXPECT_NEAR((lo + Eigen::Vector3d(r, r, h + r)).norm(), 0, 1e-15 * (r + h));
    EXPECT_NEAR(far, h + r, 1e-15 * (r + h));
  }
  const auto s = core::mass_properties(core::make_sphere(0.3)), c0 = core::mass_properties(core::make_capsule(0.3, 0));
  EXPECT_EQ(s.mass, c0.mass);
  EXPECT_EQ(s.inertia, c0.inertia);
  EXPECT_TRUE(core::make_capsule(0.3, 0).is_sphere());
  // A capsule 1e-9 long is the sphere to 1e-8 relative (its extra mass ~ 3L/4r).
  const auto c9 = core::mass_properties(core::make_capsule(0.3, 1e-9));
  EXPECT_NEAR(c9.mass, s.mass, 1e-8 * s.mass);
  EXPECT_NEAR((c9.inertia - s.inertia).norm(), 0, 1e-8 * s.inertia.norm());
}

// The generated families: the closed form's gap within 1e-12 × scale (a few
// dozen roundings of coordinates ≲ 3; the 1e-9 turns are resolved exactly by
// the cross-product form, core/collision/capsule.hpp), its normal within 1e-9 rad where
// it is unique, the number of feature contacts exactly; every apart pair
// against brute force within 1e-12 × scale (the sphere narrowphase's rounding;
// the golden-section search's bracket closes to 1e-18). Overlapping pairs:
// the deepest sampled sphere is a lower bound of the capsule's depth (a
// segment must move as a whole), to 1e-12 × scale.
TYPED_TEST_P(CapsuleCases, GeneratedFamiliesMatchClosedFormsAndBruteForce) {
  int checked = 0;
  for (const auto& f : capsule::families()) {
    const double scale = collision::pair_scale(*f.a, *f.b);
    std::vector<collision::FeatureContact> contacts;
    const auto ours = TypeParam::narrowphase({f.a.get(), f.pa}, {f.b.get(), f.pb}, collision::Method::sat_then_manifold,
                                             &contacts);
    EXPECT_NEAR(-ours.depth, f.gap, 1e-12 * scale) << f.name;
    EXPECT_NEAR(ours.normal.norm(), 1, 1e-15) << f.name;
    if (f.normal != Eigen::Vector3d::Zero()) {
      EXPECT_NEAR(capsule::angle(ours.normal, f.normal), 0, 1e-9) << f.name;
    }
    if (f.contacts >= 0) {
      EXPECT_EQ(static_cast<int>(contacts.size()), f.contacts) << f.name;
    }
    for (const auto& c : contacts) {
      EXPECT_GE(c.depth, -collision::kTouchingBand * scale) << f.name;
      EXPECT_GT(c.normal.dot(ours.normal), 1 - 1e-12) << f.name;  // a line contact: one normal
    }
    if (f.a->is_capsule() || f.b->is_capsule()) {
      const double brute = capsule::brute_gap<TypeParam>(f);
      if (f.gap > 0) {
        EXPECT_NEAR(-ours.depth, brute, 1e-12 * scale) << f.name;
      } else {
        EXPECT_LE(-ours.depth, brute + 1e-12 * scale) << f.name;
      }
    }
    ++checked;
  }
  EXPECT_GE(checked, 100);
}

// The capsule corpus (data/collision/capsule.json, scripts/capsule-corpus.py)
// against the long-double reference: depth within 1e-12 × scale (the
// reference is exact to ~1e-18; ours rounds a few dozen operations on
// coordinates ≲ 3); the normal within 1e-9 rad where the closest points are
// more than 1e-6 × scale apart or the segment is inside (there the normal
// is a direction divided by that distance, or an axis of the Minkowski
// difference); yes/no outside the touching band. Every brute-force-able
// (apart, capsule–polyhedron) pair also against brute force.
TYPED_TEST_P(CapsuleCases, CorpusMatchesTheReference) {
  const auto cases = collision::load_cases(std::filesystem::path(GACOMPARE_DATA_DIR) / "collision" / "capsule.json");
  ASSERT_GE(cases.size(), 80u);
  for (const auto& c : cases) {
    const auto ours = TypeParam::narrowphase(c.a(), c.b(), collision::Method::report, nullptr);
    const auto ref = collision::sat_reference(c.a(), c.b());
    const double scale = collision::pair_scale(*c.mesh_a, *c.mesh_b);
    EXPECT_NEAR(ours.depth, ref.depth, 1e-12 * scale) << c.name;
    const double r = (c.mesh_a->is_round() ? c.mesh_a->sphere_radius() : 0) + (c.mesh_b->is_round() ? c.mesh_b->sphere_radius() : 0);
    if (std::abs(r - ref.depth) > 1e-6 * scale) {  // the cores' distance (< 0: the segment inside)
      EXPECT_NEAR(capsule::angle(ours.normal, ref.normal), 0, 1e-9) << c.name;
    }
    if (std::abs(ref.depth) > collision::kTouchingBand * scale) {
      EXPECT_EQ(ours.intersect, ref.intersect) << c.name;
    }
  }
}

// A capsule dropped flat onto a slab (ε = 0) comes to rest at height r, its
// axis horizontal and not rocking: both ends touch at once and get a
// contact each, so the impulses balance. At rest within the penetration
// tolerance 1e-6 m of touching (the time-of-impact search stops within it);
// the axis's tilt and the angular speed at rounding level (1e-12: measured
// 1e-17); at the final orientation, lowered onto the slab, the narrowphase
// reports the two end contacts.
TYPED_TEST_P(CapsuleCases, CapsuleDroppedFlatRestsAtItsRadiusWithoutRocking) {
  const core::Scene s = this->scene("capsule_rest_flat");
  const core::Run run = core::simulate<typename TypeParam::Backend>(s);
  ASSERT_FALSE(run.error) << *run.error;
  EXPECT_GT(run.counters.at("impulses"), 0u);
  for (const auto& sample : run.samples) {
    const auto& b = sample.bodies[1];
    const Eigen::Vector3d axis = Eigen::Quaterniond(b.orientation[0], b.orientation[1], b.orientation[2], b.orientation[3]) *
                                 Eigen::Vector3d::UnitZ();
    EXPECT_LE(std::abs(axis.z()), 1e-12) << "t = " << sample.t;
    EXPECT_LE(b.angular_velocity.norm(), 1e-12) << "t = " << sample.t;
  }
  const auto& last = run.samples.back().bodies[1];
  EXPECT_NEAR(last.position.z(), 0.1, 1e-6);
  EXPECT_LE(last.velocity.norm(), 1e-9);
  const auto slab = std::make_shared<const core::Mesh>(core::make_box({2, 1, 0.2}));
  const auto cap = std::make_shared<const core::Mesh>(core::make_capsule(0.1, 0.4));
  collision::Pose ps, pc;
  ps.position = {0, 0, -0.1};
  pc.position = last.position - Eigen::Vector3d(0, 0, last.position.z() - 0.1);  // lowered onto the slab
  pc.rotation = Eigen::Quaterniond(last.orientation[0], last.orientation[1], last.orientation[2], last.orientation[3])
                    .toRotationMatrix();
  std::vector<collision::FeatureContact> contacts;
  TypeParam::narrowphase({slab.get(), ps}, {cap.get(), pc}, collision::Method::sat_then_manifold, &contacts);
  EXPECT_EQ(contacts.size(), 2u);
}

// A capsule released across a 30° incline with μ = 0.5 rolls about its axis
// without slipping (tests/round_cases.hpp expect_rolls_down_incline): a =
// g sin θ/(1 + k), k = I/(m r²) = 0.469 from the exact mass properties (the
// cylinder's ½ and the caps' 2/5, weighted by volume), on its two end
// contacts, the contact line at rest. Within 1e-3 relative, the bound.
TYPED_TEST_P(CapsuleCases, CapsuleRollsDownInclineAboutItsAxis) {
  const double r = 0.1;
  const auto p = core::mass_properties(core::make_capsule(r, 0.3));
  expect_rolls_down_incline<typename TypeParam::Backend>(this->scene("capsule_roll_incline"), p.inertia(2, 2) / (p.mass * r * r), r);
}

REGISTER_TYPED_TEST_SUITE_P(CapsuleCases, CapsuleMassPropertiesMatchTheSolidOfRevolution,
                            GeneratedFamiliesMatchClosedFormsAndBruteForce, CorpusMatchesTheReference,
                            CapsuleDroppedFlatRestsAtItsRadiusWithoutRocking, CapsuleRollsDownInclineAboutItsAxis);

}  // namespace gacompare::testing
