#pragma once
// Round shapes (core/collision/round.hpp) through a backend: the
// narrowphase of sphere pairs against closed forms and against the
// long-double reference (core/collision/separating_axis.cpp, round_reference: Ericson's
// nearest point of every triangle, a method that shares nothing with the
// narrowphase's face polygons and edges), and the round scenes
// (data/scenes/sphere_*.json) against their analytic answers. Instantiated by
// tests/{traditional,cga}/round_test.cpp; `Backend` is a tag with the backend
// type and narrowphase() (as tests/narrowphase_cases.hpp).
#include "answers/collision_cases.hpp"
#include "core/model/mass_properties.hpp"
#include "core/model/mesh.hpp"
#include "core/collision/separating_axis.hpp"
#include "core/dynamics/simulator.hpp"

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <memory>
#include <numbers>
#include <random>
#include <string>

namespace gacompare::testing {

// A round body of radius r released on the 30° incline (body 1 of the scene)
// rolls without slipping when μ is above tan θ k/(1 + k), k = I/(m r²) about
// its rolling axis: a = g sin θ/(1 + k) (5/7 g sin θ for a sphere, k = 2/5),
// so after t the speed is a t and the distance ½ a t², and the contact point
// is at rest (|v + ω × (−r n)| = 0). Within 1e-3 relative, the bound.
template <class Backend>
void expect_rolls_down_incline(const core::Scene& s, double k, double r) {
  const core::Run run = core::simulate<Backend>(s);
  ASSERT_FALSE(run.error) << *run.error;
  EXPECT_GT(run.counters.at("friction_contacts"), 0u);
  const double theta = std::numbers::pi / 6, g = 9.81;
  const Eigen::Vector3d n(std::sin(theta), 0, std::cos(theta)), along(std::cos(theta), 0, -std::sin(theta));
  const double a = g * std::sin(theta) / (1 + k);
  const auto& first = run.samples.front().bodies[1];
  const auto& last = run.samples.back().bodies[1];
  const double t = run.samples.back().t;
  EXPECT_NEAR(last.velocity.dot(along), a * t, 1e-3 * a * t);
  EXPECT_NEAR((last.position - first.position).dot(along), 0.5 * a * t * t, 1e-3 * 0.5 * a * t * t);
  for (const auto& sample : run.samples) {
    const auto& b = sample.bodies[1];
    if (sample.t < 0.05) continue;
    const Eigen::Vector3d slip = b.velocity + b.angular_velocity.cross(-r * n);
    EXPECT_LE(slip.norm(), 1e-3 * b.velocity.norm()) << "t = " << sample.t;
  }
}

template <class Backend>
class RoundCases : public ::testing::Test {
 protected:
  static core::Scene scene(const std::string& name) {
    return core::load_scene(std::filesystem::path(GACOMPARE_DATA_DIR) / "scenes" / (name + ".json"));
  }
};
TYPED_TEST_SUITE_P(RoundCases);

// Seeded random sphere pairs against the closed form: gap |c_b − c_a| − r_a − r_b,
// normal (c_b − c_a)/d, the contact midway between the surfaces, one feature
// contact exactly when within the touching band. 1e-14 relative to the pair's
// scale: a handful of operations on coordinates of size ≲ 3 in the pair's
// frame (cga's (S1 − S2)² rounds its ½|c|² terms, of the same size).
TYPED_TEST_P(RoundCases, SphereSphereMatchesTheClosedForm) {
  std::mt19937_64 rng(2026);
  std::uniform_real_distribution<double> u(-1, 1), radius(0.05, 1);
  for (int k = 0; k < 500; ++k) {
    const double ra = radius(rng), rb = radius(rng);
    const auto ma = std::make_shared<const core::Mesh>(core::make_sphere(ra));
    const auto mb = std::make_shared<const core::Mesh>(core::make_sphere(rb));
    collision::Pose pa, pb;
    pa.position = {u(rng), u(rng), u(rng)};
    pb.position = pa.position + 1.5 * (ra + rb) * Eigen::Vector3d(u(rng), u(rng), u(rng)).normalized() * std::abs(u(rng));
    pa.rotation = Eigen::Quaterniond(Eigen::Vector4d(u(rng), u(rng), u(rng), u(rng)).normalized()).toRotationMatrix();
    const Eigen::Vector3d d = pb.position - pa.position;
    const double dist = d.norm(), gap = dist - ra - rb, scale = collision::pair_scale(*ma, *mb);
    std::vector<collision::FeatureContact> contacts;
    const auto r = TypeParam::narrowphase({ma.get(), pa}, {mb.get(), pb}, collision::Method::sat_then_manifold, &contacts);
    EXPECT_NEAR(r.depth, -gap, 1e-14 * scale) << k;
    EXPECT_EQ(r.intersect, gap < 0) << k;
    EXPECT_NEAR((r.normal - d / dist).norm(), 0, 1e-14 * scale / dist) << k;
    const Eigen::Vector3d mid = 0.5 * ((pa.position + ra * d / dist) + (pb.position - rb * d / dist));
    EXPECT_NEAR((r.contact - mid).norm(), 0, 1e-14 * scale) << k;
    EXPECT_EQ(contacts.size(), gap <= collision::kTouchingBand * scale ? 1u : 0u) << k;
  }
}

// The round corpus (data/collision/round.json, scripts/round-corpus.py):
//   - the hand-placed sphere–box pairs have their gap in the name (touching 0,
//     apart 0.1, overlapping −0.05) and the sphere inside the box its depth;
//   - every pair against the long-double reference: depth within 1e-12 × scale
//     (the reference is exact to ~1e-18; ours rounds a few dozen operations on
//     coordinates ≲ 3, cga also ½|x|² terms of the shape's unit ≲ 1); the
//     normal within 1e-9 rad where the surfaces are more than 1e-6 × scale from
//     the centre's nearest feature (the normal of an edge or a vertex is the
//     direction to it, divided by that distance), the contact within 1e-12 × scale.
TYPED_TEST_P(RoundCases, SpherePolyhedronMatchesTheReference) {
  const auto cases = collision::load_cases(std::filesystem::path(GACOMPARE_DATA_DIR) / "collision" / "round.json");
  ASSERT_GE(cases.size(), 90u);
  int hand = 0;
  for (const auto& c : cases) {
    const auto ours = TypeParam::narrowphase(c.a(), c.b(), collision::Method::report, nullptr);
    const auto ref = collision::sat_reference(c.a(), c.b());
    const double scale = collision::pair_scale(*c.mesh_a, *c.mesh_b);
    EXPECT_NEAR(ours.depth, ref.depth, 1e-12 * scale) << c.name;
    // The angle as atan2(|n × m|, n·m): acos(n·m) cannot resolve below √(2 eps) ≈ 1.5e-8.
    EXPECT_NEAR(std::atan2(ours.normal.cross(ref.normal).norm(), ours.normal.dot(ref.normal)), 0, 1e-9) << c.name;
    EXPECT_NEAR((ours.contact - ref.contact).norm(), 0, 1e-12 * scale) << c.name;
    if (std::abs(ref.depth) > collision::kTouchingBand * scale) {
      EXPECT_EQ(ours.intersect, ref.intersect) << c.name;
    }
    const auto expect_gap = [&](const std::string& tag, double gap) {
      if (c.name.find("sphere-box") == 0 && c.name.find(tag) != std::string::npos) {
        EXPECT_NEAR(ours.depth, -gap, 1e-12) << c.name;
        ++hand;
      }
    };
    expect_gap("touching", 0), expect_gap("apart", 0.1), expect_gap("overlapping", -0.05);
    // Centre at (0.1, 0, 0.3) in the unit box: 0.2 below the top face, so
    // 0.3 + 0.2 deep along it.
    if (c.name == "sphere inside box") {
      EXPECT_NEAR(ours.depth, 0.5, 1e-12);
      ++hand;
    }
  }
  EXPECT_EQ(hand, 10);
}

// Mass properties, exact: m = ρ 4/3 π r³, I = 2/5 m r² (not the proxy
// polyhedron's); the inradius the tunnelling rule uses is r. 1e-15 relative:
// one product each.
TYPED_TEST_P(RoundCases, SphereMassPropertiesAreExact) {
  const core::Mesh m = core::make_sphere(0.3);
  const auto p = core::mass_properties(m, 2.0);
  const double mass = 2.0 * 4.0 / 3.0 * std::numbers::pi * 0.027;
  EXPECT_NEAR(p.mass, mass, 1e-15 * mass);
  EXPECT_NEAR((p.inertia - 0.4 * mass * 0.09 * Eigen::Matrix3d::Identity()).norm(), 0, 1e-15 * mass);
  EXPECT_EQ(core::inradius(m, Eigen::Vector3d::Zero()), 0.3);
  // The proxy bounds exactly: every vertex on the sphere, ±r on each axis.
  double lo = INFINITY, hi = 0;
  for (const auto& v : m.vertices()) lo = std::min(lo, v.norm()), hi = std::max(hi, v.norm());
  EXPECT_NEAR(lo, 0.3, 1e-15);
  EXPECT_NEAR(hi, 0.3, 1e-15);
  EXPECT_NEAR(m.size(), 0.6 * std::sqrt(3.0), 1e-15);
}

// Off-centre elastic collision of equal spheres (no gravity, ε = 1, μ = 0):
// momentum and kinetic energy conserved to 1e-9 (one impulse along the line
// of centres conserves both exactly; what is left is rounding and the
// time-of-impact search's step, which moves positions, not velocities), the
// exit velocities at 90° to each other (equal masses: v1'·v2' = 0 for any
// normal) to 1e-9 rad, and the struck sphere along the line of centres at
// impact, 30° from x (sin = offset / (r1 + r2) = 0.5), to 1e-3 rad: the
// impact is found within the penetration tolerance 1e-6 m, which turns the
// line of centres by ~1e-5.
TYPED_TEST_P(RoundCases, OffCentreElasticCollisionConservesAndExitsAtRightAngles) {
  const core::Scene s = this->scene("sphere_collision_offcentre");
  const core::Run run = core::simulate<typename TypeParam::Backend>(s);
  ASSERT_FALSE(run.error) << *run.error;
  EXPECT_GT(run.counters.at("impulses"), 0u);
  const auto& first = run.samples.front();
  const auto& last = run.samples.back();
  EXPECT_NEAR((last.linear_momentum - first.linear_momentum).norm(), 0, 1e-9);
  EXPECT_NEAR(last.kinetic, first.kinetic, 1e-9 * first.kinetic);
  const Eigen::Vector3d v1 = last.bodies[0].velocity, v2 = last.bodies[1].velocity;
  ASSERT_GT(v1.norm(), 0.1);
  ASSERT_GT(v2.norm(), 0.1);
  EXPECT_NEAR(std::acos(v1.dot(v2) / (v1.norm() * v2.norm())), std::numbers::pi / 2, 1e-9);
  EXPECT_NEAR(std::atan2(-v2.y(), v2.x()), std::numbers::pi / 6, 1e-3);
  EXPECT_NEAR(v2.norm(), std::cos(std::numbers::pi / 6), 1e-3);
}

// A sphere dropped 1 m onto a slab with ε = 0.5 rises to ε² = 0.25 m: the
// lowest point's highest height after the first bounce, within 1e-3 relative
// (the bounce is found within the penetration tolerance 1e-6 m, and the
// samples every 1 ms catch the apex within ½ g (0.5 ms)² ≈ 1e-6 m).
TYPED_TEST_P(RoundCases, DroppedSphereBouncesToEpsilonSquaredHeight) {
  const core::Scene s = this->scene("sphere_bounce");
  const core::Run run = core::simulate<typename TypeParam::Backend>(s);
  ASSERT_FALSE(run.error) << *run.error;
  bool bounced = false;
  double apex = 0;
  for (const auto& sample : run.samples) {
    const auto& b = sample.bodies[1];
    if (b.velocity.z() > 0) bounced = true;
    if (bounced) apex = std::max(apex, b.position.z() - 0.1);
  }
  ASSERT_TRUE(bounced);
  EXPECT_NEAR(apex, 0.25, 1e-3 * 0.25);
}

// A solid sphere released on a 30° incline with μ = 0.5 > 2/7 tan 30° rolls
// without slipping at a = 5/7 g sin θ (expect_rolls_down_incline, k = 2/5).
TYPED_TEST_P(RoundCases, SphereRollsDownInclineAtFiveSevenths) {
  expect_rolls_down_incline<typename TypeParam::Backend>(this->scene("sphere_roll_incline"), 0.4, 0.1);
}

REGISTER_TYPED_TEST_SUITE_P(RoundCases, SphereSphereMatchesTheClosedForm, SpherePolyhedronMatchesTheReference,
                            SphereMassPropertiesAreExact, OffCentreElasticCollisionConservesAndExitsAtRightAngles,
                            DroppedSphereBouncesToEpsilonSquaredHeight, SphereRollsDownInclineAtFiveSevenths);

}  // namespace gacompare::testing
