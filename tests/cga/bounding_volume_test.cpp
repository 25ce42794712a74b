// cga/bounding_volume.hpp (dual spheres from outer products of conformal points,
// overlap by the meet) through the shared bounding-volume cases, and the
// conformal forms it chose checked against the report's: the point pair's centre
// by reflection (P n P), the circle's through cga::circumcircle, and the
// report's direct meet C with its rule C² ≥ 0 (§2.4.1).
#include "../collision_cases.hpp"

#include "cga/geometry/entities.hpp"

namespace gacompare::testing {
INSTANTIATE_TYPED_TEST_SUITE_P(Cga, BoundingVolumeCases, cga::SphereOps);

namespace {
using cga::SphereOps;

// sphere_2 = ½(A + B + (A·B) n): normalised, through A and B, centred where the
// report's reflection of n in the point pair puts it. Tolerance 1e-12: size-1
// inputs, a handful of operations each (the reflection is quadratic in P, ~1e-15).
TEST(CgaBoundingVolume, TwoPointSphereIsCentredWhereThePointPairReflectsN) {
  std::mt19937_64 g(12);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int i = 0; i < 1000; ++i) {
    const Vec3 a(u(g), u(g), u(g)), b(u(g), u(g), u(g));
    if ((a - b).norm() < 0.1) continue;
    const cga::ConformalPoint A = cga::up(a), B = cga::up(b);
    const cga::DualSphere s = SphereOps::sphere_2(A, B);
    EXPECT_NEAR(cga::scalar_product(s, cga::n_inf()), -1, 1e-12);
    EXPECT_NEAR(cga::scalar_product(s, A), 0, 1e-12);
    EXPECT_NEAR(cga::scalar_product(s, B), 0, 1e-12);
    const auto by_reflection = cga::round_centre_by_reflection(A ^ B);
    ASSERT_TRUE(by_reflection.has_value());
    EXPECT_LE((SphereOps::centre(s) - *by_reflection).norm(), 1e-12) << i;
    EXPECT_NEAR(SphereOps::radius(s), 0.5 * (a - b).norm(), 1e-12) << i;
  }
}

// sphere_3 (the dual circle contracted with its plane) against cga::circumcircle's
// centre and radius; 1e-9 as kTol in collision_cases.hpp, draws with sin ≥ 1e-3.
TEST(CgaBoundingVolume, ThreePointSphereIsTheCircumcircles) {
  std::mt19937_64 g(13);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int i = 0; i < 1000; ++i) {
    const Vec3 a(u(g), u(g), u(g)), b(u(g), u(g), u(g)), c(u(g), u(g), u(g));
    if ((b - a).cross(c - a).norm() < 1e-3 * (b - a).norm() * (c - a).norm()) continue;
    const auto s = SphereOps::sphere_3(cga::up(a), cga::up(b), cga::up(c));
    const geometry::CircleResult k = cga::circumcircle(a, b, c);
    ASSERT_TRUE(s.has_value());
    ASSERT_EQ(k.kind, geometry::Kind::circle);
    EXPECT_NEAR(cga::scalar_product(*s, cga::n_inf()), -1, 1e-12);  // normalised
    EXPECT_LE((SphereOps::centre(*s) - k.centre).norm(), kTol) << i;
    EXPECT_NEAR(SphereOps::radius(*s), k.radius, kTol) << i;
  }
}

// The report's rule read literally: C = (S1 ∧ S2)*, the direct meet (eq. 19 for
// two dual spheres), has C² = −(S1∧S2)², and C² ≥ 0 exactly when the surfaces
// cross: |ρ1 − ρ2| ≤ d ≤ ρ1 + ρ2. Nested spheres have C² < 0 like separate ones,
// and SphereOps::overlap still calls them overlapping. Outside a band of 1e-9
// (relative) around both tangencies, where the sign is rounding's; size-1 data.
// SphereOps::overlap (by inner products) and overlap_by_meet say d ≤ ρ1 + ρ2.
TEST(CgaBoundingVolume, TheReportsMeetRuleSeesCrossingSurfacesOnly) {
  std::mt19937_64 g(14);
  std::uniform_real_distribution<double> u(-2, 2), rad(0.05, 1.5);
  int crossing = 0, nested = 0;
  for (int i = 0; i < 20000; ++i) {
    const Vec3 c1(u(g), u(g), u(g)), c2 = i % 2 ? Vec3(u(g), u(g), u(g)) : c1 + 0.1 * Vec3(u(g), u(g), u(g));
    const double r1 = rad(g), r2 = rad(g), d = (c2 - c1).norm();
    const double scale = c1.norm() + c2.norm() + r1 + r2;
    if (std::abs(d - (r1 + r2)) <= 1e-9 * scale || std::abs(d - std::abs(r1 - r2)) <= 1e-9 * scale) continue;
    const cga::DualSphere s1 = cga::sphere(c1, r1), s2 = cga::sphere(c2, r2);
    const auto direct = !(s1 ^ s2);
    const double c2_direct = cga::scalar_product(direct, direct);
    const auto b = s1 ^ s2;
    EXPECT_NEAR(c2_direct, -cga::scalar_product(b, b), 1e-12 * scale * scale * scale * scale) << i;
    const bool cross = std::abs(r1 - r2) <= d && d <= r1 + r2;
    EXPECT_EQ(c2_direct >= 0, cross) << i;
    EXPECT_EQ(SphereOps::overlap(s1, s2), d <= r1 + r2) << i;
    EXPECT_EQ(cga::overlap_by_meet(s1, s2), d <= r1 + r2) << i;
    crossing += cross;
    nested += d < std::abs(r1 - r2);
  }
  EXPECT_GT(crossing, 1000);
  EXPECT_GT(nested, 1000);
}

// overlap and side are independent of the dual sphere's scale and orientation
// (a sphere built as −3·S is the same sphere).
TEST(CgaBoundingVolume, OverlapAndContainsIgnoreScaleAndOrientation) {
  const cga::DualSphere a = cga::sphere(Vec3(0, 0, 0), 2), inner = cga::sphere(Vec3(0.5, 0, 0), 0.5);
  const cga::DualSphere far = cga::sphere(Vec3(5, 0, 0), 1);
  for (double k : {1.0, -3.0, 0.25}) {
    EXPECT_TRUE(SphereOps::overlap(a * k, inner));
    EXPECT_TRUE(SphereOps::overlap(inner, a * k));
    EXPECT_FALSE(SphereOps::overlap(a * k, far));
    EXPECT_TRUE(SphereOps::contains(a * k, cga::up(Vec3(1, 1, 1)), 0));
    EXPECT_FALSE(SphereOps::contains(a * k, cga::up(Vec3(2, 1, 1)), 0));
  }
}

}  // namespace
}  // namespace gacompare::testing
