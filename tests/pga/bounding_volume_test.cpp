// pga/bounding_volume.hpp (centres as meets of bisector planes) through the
// shared bounding-volume cases, and its constructions against the Euclidean
// closed forms of the matrix backend.
#include "../collision_cases.hpp"

#include "pga/bounding_volume.hpp"
#include "traditional/geometry.hpp"

namespace gacompare::testing {
INSTANTIATE_TYPED_TEST_SUITE_P(Pga, BoundingVolumeCases, pga::SphereOps);

namespace {
using pga::SphereOps;

// The bisector (A + B)·(A ∨ B) holds the midpoint and is orthogonal to b − a;
// the meets of bisectors are the circumcircle's and circumsphere's centres of
// traditional/geometry.hpp (Cramer's rule with cross products). Tolerance
// 1e-11: size-1 points, and a division by a weight that is 8× a volume ≳ 1e-3.
TEST(PgaBoundingVolume, CentresAreMeetsOfBisectors) {
  std::mt19937_64 g(31);
  std::uniform_real_distribution<double> u(-1, 1);
  int compared = 0;
  for (int i = 0; i < 1000; ++i) {
    const Vec3 a(u(g), u(g), u(g)), b(u(g), u(g), u(g)), c(u(g), u(g), u(g)), d(u(g), u(g), u(g));
    const pga::Plane bis = SphereOps::bisector(pga::point(a), pga::point(b));
    EXPECT_NEAR(pga::distance(bis, pga::point(0.5 * (a + b))), 0, 1e-14);
    EXPECT_NEAR(pga::normal(bis).normalized().cross((b - a).normalized()).norm(), 0, 1e-12);
    if (std::abs((b - a).dot((c - a).cross(d - a))) < 1e-3) continue;
    const auto mine = SphereOps::sphere_4(pga::point(a), pga::point(b), pga::point(c), pga::point(d));
    const auto theirs = traditional::sphere_through(a, b, c, d);
    ASSERT_TRUE(mine);
    ASSERT_EQ(theirs.kind, geometry::Kind::sphere);
    EXPECT_NEAR((SphereOps::centre(*mine) - theirs.centre).norm(), 0, 1e-11 * (1 + theirs.radius));
    EXPECT_NEAR(SphereOps::radius(*mine), theirs.radius, 1e-11 * (1 + theirs.radius));
    const auto circle = SphereOps::sphere_3(pga::point(a), pga::point(b), pga::point(c));
    const auto k = traditional::circumcircle(a, b, c);
    ASSERT_TRUE(circle);
    EXPECT_NEAR((SphereOps::centre(*circle) - k.centre).norm(), 0, 1e-11 * (1 + k.radius));
    ++compared;
  }
  EXPECT_GT(compared, 300);
}

}  // namespace
}  // namespace gacompare::testing
