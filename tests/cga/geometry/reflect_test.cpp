// Reflection (§1.7 eq. 20), the nearest point on a line, and the inside/outside
// convention with the orientation fix of Appendix A fig. 14, against the
// traditional twins. Tolerances: cases.hpp's kC·eps·A^k·κ·size with k = kLine
// (a point against a vector or a 3-blade of two points), κ stated per check.
#include "cases.hpp"
#include "cga/geometry/geometry.hpp"
#include "traditional/geometry.hpp"

namespace gacompare {
namespace {
namespace C = cga;
namespace T = traditional;
using geometry::Kind;
using namespace geometry::testing;

TEST(Reflect, MatchesTwinOnRandomCases) {
  Rng rng(321);
  Worst worst;
  for (int k = 0; k < kCases; ++k) {
    const Vec3 o = rng.site(), x = o + rng.point(1), a = o + rng.point(1), b = o + rng.point(1);
    if (min_distance({x, a, b}) < 0.1) { --k; continue; }
    const Vec3 nrm = rng.unit();
    const double off = nrm.dot(o) + rng.uniform(-1, 1), r = rng.uniform(0.2, 1.5);
    const double size = x.norm() + a.norm() + std::abs(off) + 1;
    // Plane and line: isometries, κ = 1.
    const double tol = kC * kEps * amplification({x, a, b, off * nrm}, kLine) * size;
    const Vec3 pc = C::reflect_in_plane(x, C::plane(nrm, off)), pt = T::reflect_in_plane(x, T::plane(nrm, off));
    worst.see((pc - pt).norm(), tol);
    ASSERT_TRUE(near(pc, pt, tol, "plane"));
    const auto lc = C::line_through(a, b);
    const auto lt = T::line_through(a, b);
    ASSERT_TRUE(near(C::reflect_in_line(x, *lc), T::reflect_in_line(x, *lt), tol, "line"));
    ASSERT_TRUE(near(C::nearest_on_line(x, *lc), T::nearest_on_line(x, *lt), tol, "nearest"));
    // The report's sandwich forms (§1.7): the same points. Their weight is of
    // order |u|² (κ = 1/|u|² ≤ 100 for |u| ≥ 0.1).
    const double tw = tol / (b - a).squaredNorm();
    ASSERT_TRUE(near(C::reflect_in_line_by_sandwich(x, *lc), T::reflect_in_line(x, *lt), tw, "line (LXL)"));
    ASSERT_TRUE(near(C::nearest_on_line_by_reflection(x, *lc), T::nearest_on_line(x, *lt), tw, "nearest (LXL)"));
    ASSERT_TRUE(near(C::reflect_in_plane_by_sandwich(x, C::plane(nrm, off)), pt, tol, "plane (πXπ)"));
    // Sphere (inversion): x' − c = ρ²(x − c)/|x − c|² magnifies by ρ²/|x − c|²
    // and its error by as much again through |x − c|²: κ = (1 + ρ²/|x − c|²)².
    const auto sc = C::reflect_in_sphere(x, C::sphere(a, r));
    const auto st = T::reflect_in_sphere(x, T::sphere(a, r));
    ASSERT_EQ(sc.kind, st.kind);
    const double q = 1 + r * r / (x - a).squaredNorm();
    ASSERT_TRUE(near(sc.point, st.point, tol * q * q, "sphere"));
    worst.see((sc.point - st.point).norm(), tol * q * q);
    if (HasFatalFailure()) return;
  }
}

TEST(Reflect, HandComputedAndDegenerate) {
  const Vec3 x(3, 1, 0);
  // Plane z = 2: (3,1,4). Line x = 1, y = 1: the half-turn gives (−1,1,0), the
  // nearest point (1,1,0). Sphere c = (1,1,1), ρ = 2: c + 4(2,0,−1)/5.
  EXPECT_TRUE(near(C::reflect_in_plane(x, C::plane({0, 0, 1}, 2)), {3, 1, 4}, 1e-15));
  const auto l = *C::line_through({1, 1, 0}, {1, 1, 5});
  EXPECT_TRUE(near(C::reflect_in_line(x, l), {-1, 1, 0}, 1e-15));
  EXPECT_TRUE(near(C::nearest_on_line(x, l), {1, 1, 0}, 1e-15));
  EXPECT_TRUE(near(C::nearest_on_line_by_reflection(x, l), {1, 1, 0}, 1e-15));
  EXPECT_TRUE(near(C::reflect_in_line_by_sandwich(x, l), {-1, 1, 0}, 1e-15));
  const auto s = C::reflect_in_sphere(x, C::sphere({1, 1, 1}, 2));
  EXPECT_EQ(s.kind, Kind::point);
  EXPECT_TRUE(near(s.point, {2.6, 1, 0.2}, 1e-15));
  // The centre inverts to the point at infinity: typed, not inf/NaN.
  EXPECT_EQ(C::reflect_in_sphere({1, 1, 1}, C::sphere({1, 1, 1}, 2)).kind, Kind::none);
  EXPECT_EQ(T::reflect_in_sphere({1, 1, 1}, T::sphere({1, 1, 1}, 2)).kind, Kind::none);
  // A point on the sphere is fixed; reflection is an involution.
  EXPECT_TRUE(near(C::reflect_in_sphere({3, 1, 1}, C::sphere({1, 1, 1}, 2)).point, {3, 1, 1}, 1e-15));
  // (The normal (1,2,3)/√14 is rounded: a few ulps of |x| ≈ 3.)
  EXPECT_TRUE(near(C::reflect_in_plane(C::reflect_in_plane(x, C::plane({1, 2, 3}, 1)), C::plane({1, 2, 3}, 1)), x, 1e-14));
}

TEST(Inside, ConventionMatchesTwinAndReport) {
  Rng rng(322);
  Worst worst;
  for (int k = 0; k < kCases; ++k) {
    const Vec3 o = rng.site(), c = o + rng.point(1), x = o + rng.point(1.5);
    const double r = rng.uniform(0.2, 1.5);
    // side = ½(|x − c|² − ρ²): κ = 1, size (|x| + |c| + ρ)².
    const double tol = kC * kEps * amplification({c, x}, kPoint) * std::pow(x.norm() + c.norm() + r, 2);
    const double sc = C::side(C::sphere(c, r), x), st = T::side(T::sphere(c, r), x);
    worst.see(std::abs(sc - st), tol);
    ASSERT_TRUE(near(sc, st, tol, "side"));
    if (std::abs(st) > tol) {
      ASSERT_EQ(C::inside(C::sphere(c, r), x), T::inside(T::sphere(c, r), x));
      ASSERT_EQ(C::outside(C::sphere(c, r), x), T::outside(T::sphere(c, r), x));
    }
  }
  // The report's rule (§2.4.1): inside < 0. The centre is inside, n (far away) outside.
  const auto s = C::sphere({1, 2, 3}, 2);
  EXPECT_LT(C::side(s, Vec3(1, 2, 3)), 0);
  EXPECT_TRUE(C::inside(s, {1, 2, 4}));
  EXPECT_TRUE(C::outside(s, {1, 2, 6}));
  EXPECT_NEAR(C::side(s, Vec3(1, 2, 5)), 0, 1e-15);
  EXPECT_NEAR(C::side(s, Vec3(1, 2, 3)), -2, 1e-15);  // ½(0 − 4)
}

TEST(Inside, OrientationFixOfFigure14) {
  // The four points in both orders: the raw dual of A∧B∧C∧D changes sign with
  // the order (fig. 14's problem), so X·S alone cannot say inside. Fig. 14's
  // check reads the scalar part of n·M, a 3-vector: always zero, never flips.
  const Vec3 c(1, 2, 3);
  const auto A = C::up(c + Vec3(2, 0, 0)), B = C::up(c + Vec3(0, 2, 0)), Cc = C::up(c + Vec3(0, 0, 2)),
             D = C::up(c - Vec3(2, 0, 0));
  const auto m1 = ((A ^ B) ^ Cc) ^ D, m2 = ((B ^ A) ^ Cc) ^ D;
  const auto raw1 = !m1, raw2 = !m2;
  const auto X = C::up(c);  // the centre: inside
  EXPECT_LT(scalar_product(X, raw1) * scalar_product(X, raw2), 0);  // opposite signs
  EXPECT_EQ(inner(C::n_inf(), m1).get<0>(), 0);                     // fig. 14's test is void
  // side() is orientation- and scale-free; four_point_sphere() normalises.
  EXPECT_LT(C::side(raw1, X), 0);
  EXPECT_LT(C::side(raw2, X), 0);
  EXPECT_LT(C::side(-3.0 * raw2, X), 0);
  for (const auto& s : {*C::four_point_sphere(A, B, Cc, D), *C::four_point_sphere(B, A, Cc, D),
                        C::oriented(raw1), C::oriented(-2.0 * raw2)}) {
    EXPECT_NEAR(scalar_product(s, C::n_inf()), -1, 1e-15);
    EXPECT_NEAR(C::side(s, X), -2, 1e-14);
    EXPECT_TRUE(near(C::centre(s), c, 1e-14));
    EXPECT_NEAR(C::radius(s), 2, 1e-14);
  }
  // Four points on one circle (z = 3): the blade vanishes, no sphere.
  EXPECT_FALSE(C::four_point_sphere(A, B, D, C::up(c + Vec3(0, -2, 0))).has_value());
}

TEST(Rounds, ReflectingNIsWorseConditionedThanTheCarrierPlane) {
  // The report's centre K n K (Table 1) against round_centre (entities.hpp) on
  // the same near-collinear circle: both are fine on a fat triangle; at 1e-6
  // from collinear the sandwich has lost most of its digits.
  const Vec3 a(0.3, -0.2, 0.1), b(1.1, 0.4, -0.3);
  const Vec3 fat = 0.5 * (a + b) + Vec3(0.2, -0.1, 0.6);
  const Vec3 thin = a + 0.5 * (b - a) + 1e-6 * (b - a).cross(Vec3(0, 0, 1)).normalized();
  for (const Vec3& c : {fat, thin}) {
    const auto truth = T::circumcircle(a, b, c);
    const auto k = (C::up(a) ^ C::up(b)) ^ C::up(c);
    const double err_carrier = (*C::circle_centre(k) - truth.centre).norm() / truth.radius;
    const double err_reflect = (*C::round_centre_by_reflection(k) - truth.centre).norm() / truth.radius;
    if (c == fat) {
      EXPECT_LT(err_reflect, 1e-14);
      EXPECT_LT(err_carrier, 1e-14);
    } else {
      EXPECT_LT(err_carrier, 1e-9);   // condition 1/sin ≈ 1e6: ~1e-10 expected
      EXPECT_GT(err_reflect, 1e-7);   // condition 1/sin² ≈ 1e12: the digits are gone
    }
  }
}

}  // namespace
}  // namespace gacompare
