// The exact separating-axis reference (core/collision/separating_axis.hpp) against
// analytic answers, and the Minkowski-face pruning rule against brute force.
#include "answers/collision_cases.hpp"
#include "core/collision/separating_axis.hpp"

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

namespace gacompare::collision {
namespace {

Pose at(const Vec3& p, const Eigen::Matrix3d& r = Eigen::Matrix3d::Identity()) { return {r, p}; }
Eigen::Matrix3d about_z(double angle) { return Eigen::AngleAxisd(angle, Vec3::UnitZ()).toRotationMatrix(); }

// Analytic answers are computed from the same doubles the query sees; the
// reference works in long double, so 1e-15 (a few ulps of the unit scale) holds.
constexpr double kExact = 1e-15;

TEST(SatReference, FaceOverlapOfTwoCubes) {
  const Mesh cube = core::make_box({1, 1, 1});
  const auto r = sat_reference({&cube, at({0, 0, 0})}, {&cube, at({0.9, 0.05, 0.02})});
  EXPECT_TRUE(r.intersect);
  EXPECT_NEAR(r.depth, 0.1, kExact);
  EXPECT_NEAR((r.normal - Vec3::UnitX()).norm(), 0, kExact);
  EXPECT_NE(r.feature, Feature::edge_edge);
}

TEST(SatReference, SeparatedCubesGiveTheGap) {
  const Mesh cube = core::make_box({1, 1, 1});
  const auto r = sat_reference({&cube, at({0, 0, 0})}, {&cube, at({0, -1.25, 0.3})});
  EXPECT_FALSE(r.intersect);
  EXPECT_NEAR(r.depth, -0.25, kExact);
  EXPECT_NEAR((r.normal + Vec3::UnitY()).norm(), 0, kExact);
}

// A cube turned 45° about z reaches √2/2 along x: overlap 0.5 + √2/2 − x.
TEST(SatReference, RotatedCubeVertexIntoFace) {
  const Mesh cube = core::make_box({1, 1, 1});
  const double x = 1.1;
  const auto r = sat_reference({&cube, at({0, 0, 0})}, {&cube, at({x, 0, 0}, about_z(std::numbers::pi / 4))});
  EXPECT_TRUE(r.intersect);
  EXPECT_NEAR(r.depth, 0.5 + std::numbers::sqrt2 / 2 - x, 1e-15);
  EXPECT_NEAR((r.normal - Vec3::UnitX()).norm(), 0, 1e-15);
  EXPECT_EQ(r.feature, Feature::face_a);
}

// Two boxes whose edges cross: b is a long bar along y, turned 45° about its
// own axis and lifted so that its lower edge dips δ into a's top-face edge...
// simplest exact edge–edge: a unit cube and the same cube turned 45° about x
// then about z sit edge to edge; their depth is found only on an edge axis.
TEST(SatReference, EdgeEdgeCrossing) {
  const Mesh cube = core::make_box({1, 1, 1});
  // b: turned 45° about y, so its lowest feature is an edge along y at depth
  // −√2/2 below its centre; a: turned 45° about x, its highest feature an edge
  // along x at +√2/2. Centres 1.4 apart along z: the edges cross, depth √2 − 1.4.
  const Eigen::Matrix3d rx = Eigen::AngleAxisd(std::numbers::pi / 4, Vec3::UnitX()).toRotationMatrix();
  const Eigen::Matrix3d ry = Eigen::AngleAxisd(std::numbers::pi / 4, Vec3::UnitY()).toRotationMatrix();
  const auto r = sat_reference({&cube, at({0, 0, 0}, rx)}, {&cube, at({0, 0, 1.4}, ry)});
  EXPECT_TRUE(r.intersect);
  EXPECT_EQ(r.feature, Feature::edge_edge);
  EXPECT_NEAR(r.depth, std::numbers::sqrt2 - 1.4, 1e-15);
  EXPECT_NEAR((r.normal - Vec3::UnitZ()).norm(), 0, 1e-15);
  EXPECT_NEAR((r.contact - Vec3(0, 0, 0.7)).norm(), 0, 1e-15);
}

// Far from the origin the local frame keeps the digits: the same pair moved by
// 1e4 gives the same depth to the rounding of the positions themselves
// (1e4 · 1.1e-16 ≈ 1e-12).
TEST(SatReference, FarFromTheOriginKeepsItsDigits) {
  const Mesh cube = core::make_box({1, 1, 1});
  const Vec3 far(1e4, -1e4, 1e4);
  const auto r = sat_reference({&cube, at(far)}, {&cube, at(far + Vec3(0.9, 0.05, 0.02))});
  EXPECT_NEAR(r.depth, 0.1, 2e-12);
}

// Swapping a and b flips the normal and keeps the depth.
TEST(SatReference, SwapFlipsTheNormal) {
  const auto specs = random_case_specs(7, 40);
  const auto cases = build_cases(specs, "random");
  for (const auto& c : cases) {
    const auto ab = sat_reference(c.a(), c.b()), ba = sat_reference(c.b(), c.a());
    EXPECT_EQ(ab.intersect, ba.intersect) << c.name;
    EXPECT_NEAR(ab.depth, ba.depth, 1e-14) << c.name;
    if (ab.intersect) {
      EXPECT_NEAR((ab.normal + ba.normal).norm(), 0, 1e-9) << c.name;
    }
  }
}

// The Gauss-map rule: an edge pair spans a face of A − B iff some direction u
// has both edges as supporting features, i.e. u lies in both normal cones
// (arc a–b for A, arc −c…−d for B). Brute force: sample each arc finely and
// look for a common direction; compare with the closed-form test on random
// arcs that are not near-tangent.
TEST(SatReference, MinkowskiFaceRuleMatchesBruteForce) {
  std::mt19937_64 rng(11);
  std::normal_distribution<double> g;
  const auto unit = [&] { return Vec3(g(rng), g(rng), g(rng)).normalized(); };
  int checked = 0, faces = 0;
  for (int trial = 0; trial < 4000; ++trial) {
    const Vec3 a = unit(), b = unit(), c = unit(), d = unit();
    if (a.dot(b) < -0.5 || c.dot(d) < -0.5) continue;  // arcs of convex-body edges are < 180°
    // The great circles cross at ±u; the arcs meet iff one of ±u is on both.
    const Vec3 u = (a.cross(b)).cross(c.cross(d)).normalized();
    const auto on_arc = [](const Vec3& p, const Vec3& q, const Vec3& x) {  // x on the short arc p–q
      const Vec3 n = p.cross(q);
      return p.cross(x).dot(n) >= 0 && x.cross(q).dot(n) >= 0;
    };
    bool brute = false;
    for (const Vec3& x : {u, Vec3(-u)}) brute = brute || (on_arc(a, b, x) && on_arc(-c, -d, x));
    // Skip near-tangent configurations (an arc end within 1e-6 of the crossing).
    const double margin = std::min({std::abs(c.dot(a.cross(b))), std::abs(d.dot(a.cross(b))),
                                    std::abs(a.dot(c.cross(d))), std::abs(b.dot(c.cross(d)))});
    if (margin < 1e-6) continue;
    EXPECT_EQ(spans_minkowski_face(a, b, b.cross(a), c, d, d.cross(c)), brute) << trial;
    ++checked;
    faces += brute;
  }
  EXPECT_GT(checked, 2000);
  EXPECT_GT(faces, 50);
}

}  // namespace
}  // namespace gacompare::collision
