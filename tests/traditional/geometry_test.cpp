// The traditional twins (traditional/geometry.hpp) against independent answers:
// the defining equations of each result (a point of a meet lies on both
// entities, a circumcentre is equidistant from its points, a reflection's
// midpoint lies on the mirror …) on seeded random cases, near-degenerate and
// degenerate inputs, and hand-computed cases. (The conformal backend is compared
// with these twins in tests/cga/geometry.)
//
// Tolerance of a residual: kC·eps·κ·size (tests/cga/geometry/cases.hpp) with the
// traditional A = 1 (the twins work with differences: no |x|² terms), κ the
// problem's condition number and size the magnitude of the terms that cancel
// in the residual, each stated at its check.
#include "tests/cga/geometry/cases.hpp"
#include "traditional/geometry.hpp"

#include <vector>

namespace gacompare {
namespace {
namespace T = traditional;
using geometry::Kind;
using namespace geometry::testing;

// Points on a circle of the result (centre, radius, unit normal), for residuals.
std::vector<Vec3> circle_points(const Vec3& centre, double r, const Vec3& normal) {
  const Vec3 e1 = normal.unitOrthogonal(), e2 = normal.cross(e1);
  std::vector<Vec3> ps;
  for (int i = 0; i < 6; ++i) ps.push_back(centre + r * (std::cos(i * 1.047) * e1 + std::sin(i * 1.047) * e2));
  return ps;
}

TEST(TraditionalGeometry, CircumcircleAndSphereAreEquidistant) {
  Rng rng(341);
  int degenerate = 0;
  for (int k = 0; k < kCases; ++k) {
    const Vec3 o = rng.site(), a = o + rng.point(1), b = o + rng.point(1), c = o + rng.point(1),
               d = o + rng.point(1);
    if (min_distance({a, b, c, d}) < 0.1) { --k; continue; }
    const auto r = T::circumcircle(a, b, c);
    ASSERT_EQ(r.kind, Kind::circle);
    const Vec3 u = b - a, v = c - a;
    // κ = 1/sin(angle at a): the centre's relative error; size R + |a|.
    const double tol = kC * kEps / (u.cross(v).norm() / (u.norm() * v.norm())) * (r.radius + a.norm());
    for (const Vec3& p : {a, b, c}) ASSERT_NEAR((p - r.centre).norm(), r.radius, tol);
    ASSERT_NEAR(r.normal.dot(r.centre - a), 0, tol);  // in the points' plane
    ASSERT_NEAR(r.normal.norm(), 1, 4 * kEps);
    const auto s = T::sphere_through(a, b, c, d);
    if (s.kind == Kind::degenerate) { ++degenerate; continue; }
    const Vec3 w = d - a;
    const double ts = kC * kEps / (std::abs(u.dot(v.cross(w))) / (u.norm() * v.norm() * w.norm())) *
                      (s.radius + a.norm());
    for (const Vec3& p : {a, b, c, d}) ASSERT_NEAR((p - s.centre).norm(), s.radius, ts);
  }
  EXPECT_EQ(degenerate, 0);  // random points are coplanar with probability 0
}

TEST(TraditionalGeometry, DegenerateInputsAreTyped) {
  Rng rng(342);
  for (int k = 0; k < kNearCases; ++k) {
    const Vec3 a = rng.point(2), b = rng.point(2), c = rng.point(2);
    if (min_distance({a, b, c}) < 0.1) { --k; continue; }
    const Vec3 on = a + rng.uniform(-2, 3) * (b - a);
    EXPECT_EQ(T::circumcircle(a, b, on).kind, Kind::degenerate);
    EXPECT_EQ(T::circumcircle(a, a, b).kind, Kind::degenerate);
    EXPECT_FALSE(T::plane_through(a, on, b).has_value());
    EXPECT_FALSE(T::line_through(a, a).has_value());
    const Vec3 in = a + rng.uniform(-1, 2) * (b - a) + rng.uniform(-1, 2) * (c - a);
    EXPECT_EQ(T::sphere_through(a, b, c, in).kind, Kind::degenerate);
    // 1e-9 off: solved, and the answer satisfies its equations to the
    // conditioning 1/sin ≈ 1e9·|edge|.
    const Vec3 off = on + 1e-9 * rng.perpendicular(b - a);
    if ((off - a).norm() < 0.1 || (off - b).norm() < 0.1) { --k; continue; }
    const auto r = T::circumcircle(a, b, off);
    ASSERT_EQ(r.kind, Kind::circle);
    const Vec3 u = b - a, v = off - a;
    const double tol = kC * kEps / (u.cross(v).norm() / (u.norm() * v.norm())) * (r.radius + a.norm());
    for (const Vec3& p : {a, b, off}) ASSERT_NEAR((p - r.centre).norm(), r.radius, tol);
  }
}

TEST(TraditionalGeometry, MeetsLieOnBothEntities) {
  Rng rng(343);
  int circles = 0, pairs = 0, crossings = 0;
  for (int k = 0; k < kCases; ++k) {
    const Vec3 o = rng.site(), c1 = o + rng.point(1), c2 = o + rng.point(1), a = o + rng.point(1),
               b = o + rng.point(1), n1 = rng.unit(), n2 = rng.unit();
    if (min_distance({c1, c2}) < 0.1 || min_distance({a, b}) < 0.1) { --k; continue; }
    const double r1 = rng.uniform(0.2, 1.5), r2 = rng.uniform(0.2, 1.5);
    const double d1 = n1.dot(o) + rng.uniform(-1, 1), d2 = n2.dot(o) + rng.uniform(-1, 1);
    const auto s1 = T::sphere(c1, r1), s2 = T::sphere(c2, r2);
    const auto p1 = T::plane(n1, d1), p2 = T::plane(n2, d2);
    const auto l = *T::line_through(a, b);
    const double size = o.norm() + 3;
    // Sphere–sphere: κ = 1/sinφ + ρ/d (as in the conformal tests).
    const auto ss = T::meet_sphere_sphere(s1, s2);
    if (ss.kind == Kind::circle) {
      ++circles;
      const double dd = (c2 - c1).norm();
      const double tol = kC * kEps * (r1 * r2 / (ss.radius * dd) + 2 / dd) * size;
      for (const Vec3& p : circle_points(ss.centre, ss.radius, ss.normal)) {
        ASSERT_NEAR((p - c1).norm(), r1, tol);
        ASSERT_NEAR((p - c2).norm(), r2, tol);
      }
    } else {
      ASSERT_EQ(ss.kind, Kind::none);  // generic: never tangent by chance
      const double dd = (c2 - c1).norm();
      ASSERT_TRUE(dd > r1 + r2 || dd < std::abs(r1 - r2));
    }
    // Sphere–plane: κ = ρ/r.
    const auto sp = T::meet_sphere_plane(s1, p1);
    if (sp.kind == Kind::circle) {
      const double tol = kC * kEps * (r1 / sp.radius) * size;
      for (const Vec3& p : circle_points(sp.centre, sp.radius, sp.normal)) {
        ASSERT_NEAR((p - c1).norm(), r1, tol);
        ASSERT_NEAR(n1.dot(p), d1, tol);
      }
    } else {
      ASSERT_EQ(sp.kind, Kind::none);
      ASSERT_GT(std::abs(n1.dot(c1) - d1), r1);
    }
    // Line–plane: κ = 1/sinα.
    const auto lp = T::meet_line_plane(l, p1);
    ASSERT_EQ(lp.kind, Kind::point);  // generic: never parallel by chance
    ++crossings;
    const double sina = std::abs(n1.dot((b - a).normalized()));
    const double tl = kC * kEps / sina * (size + (lp.point - a).norm());
    ASSERT_NEAR(n1.dot(lp.point), d1, tl);
    ASSERT_NEAR((lp.point - a).cross((b - a).normalized()).norm(), 0, tl);
    // Line–sphere: κ = ρ/h; first before second along b − a.
    const auto ls = T::meet_line_sphere(l, s1);
    if (ls.kind == Kind::point_pair) {
      ++pairs;
      const double h = 0.5 * (ls.second - ls.first).norm();
      const double tol = kC * kEps * (1 + r1 / h) * size;
      for (const Vec3& p : {ls.first, ls.second}) {
        ASSERT_NEAR((p - c1).norm(), r1, tol);
        ASSERT_NEAR((p - a).cross((b - a).normalized()).norm(), 0, tol);
      }
      ASSERT_GT((ls.second - ls.first).dot(b - a), 0);
    } else {
      ASSERT_EQ(ls.kind, Kind::none);
    }
    // Plane–plane: κ = 1/sinθ, the point ~|d|/sinθ away.
    const auto pp = T::meet_plane_plane(p1, p2);
    ASSERT_EQ(pp.kind, Kind::line);
    const double sint = n1.cross(n2).norm();
    const double tp = kC * kEps / sint * (size + pp.point.norm());
    ASSERT_NEAR(n1.dot(pp.point), d1, tp);
    ASSERT_NEAR(n2.dot(pp.point), d2, tp);
    ASSERT_NEAR(pp.direction.dot(n1), 0, tp);
    ASSERT_NEAR(pp.direction.dot(n2), 0, tp);
    ASSERT_NEAR(pp.point.dot(pp.direction), 0, tp);  // nearest the origin
  }
  EXPECT_GT(circles, kCases / 10);
  EXPECT_GT(pairs, kCases / 10);
  EXPECT_GT(crossings, kCases / 2);
}

TEST(TraditionalGeometry, ReflectionsAreMirrorImages) {
  Rng rng(344);
  for (int k = 0; k < kCases; ++k) {
    const Vec3 o = rng.site(), x = o + rng.point(1), a = o + rng.point(1), b = o + rng.point(1), nrm = rng.unit();
    if (min_distance({x, a, b}) < 0.1) { --k; continue; }
    const double d = nrm.dot(o) + rng.uniform(-1, 1), r = rng.uniform(0.2, 1.5);
    const double tol = kC * kEps * (o.norm() + 3);  // isometries: κ = 1
    const Vec3 xp = T::reflect_in_plane(x, T::plane(nrm, d));
    ASSERT_NEAR(nrm.dot(0.5 * (x + xp)), d, tol);              // midpoint on the mirror
    ASSERT_NEAR((xp - x).cross(nrm).norm(), 0, tol);            // along the normal
    const auto l = *T::line_through(a, b);
    const Vec3 f = T::nearest_on_line(x, l);
    ASSERT_NEAR((x - f).dot((b - a).normalized()), 0, tol);     // perpendicular foot
    ASSERT_NEAR((f - a).cross((b - a).normalized()).norm(), 0, tol);
    ASSERT_LT((0.5 * (x + T::reflect_in_line(x, l)) - f).norm(), tol);
    const auto inv = T::reflect_in_sphere(x, T::sphere(a, r));
    ASSERT_EQ(inv.kind, Kind::point);
    const double q = 1 + r * r / (x - a).squaredNorm();
    ASSERT_NEAR((inv.point - a).norm() * (x - a).norm(), r * r, tol * q * q);  // |x' − c||x − c| = ρ²
    ASSERT_GT((inv.point - a).dot(x - a), 0);                                 // same ray
    ASSERT_EQ(T::inside(T::sphere(a, r), x), (x - a).norm() < r);
  }
}

TEST(TraditionalGeometry, HandComputed) {
  // The same hand cases as the conformal tests, so a failure names the backend.
  const auto cc = T::circumcircle({0, 0, 0}, {2, 0, 0}, {0, 2, 0});
  EXPECT_TRUE(near(cc.centre, {1, 1, 0}, 1e-15));
  EXPECT_NEAR(cc.radius, std::sqrt(2.0), 1e-15);
  const auto ss = T::meet_sphere_sphere(T::sphere({0, 0, 0}, 5), T::sphere({8, 0, 0}, 5));
  EXPECT_EQ(ss.kind, Kind::circle);
  EXPECT_TRUE(near(ss.centre, {4, 0, 0}, 1e-15));
  EXPECT_NEAR(ss.radius, 3, 1e-15);
  EXPECT_EQ(T::meet_sphere_sphere(T::sphere({0, 0, 0}, 1), T::sphere({0, 2, 0}, 1)).kind, Kind::tangent);
  EXPECT_EQ(T::meet_sphere_sphere(T::sphere({0, 0, 0}, 1), T::sphere({0, 0, 0}, 1)).kind, Kind::contained);
  EXPECT_EQ(T::meet_sphere_sphere(T::sphere({0, 0, 0}, 0), T::sphere({0, 1, 0}, 1)).kind, Kind::degenerate);
  const auto lp = T::meet_line_plane(*T::line_through({1, 1, 0}, {1, 1, 5}), T::plane({0, 0, 1}, 2));
  EXPECT_TRUE(near(lp.point, {1, 1, 2}, 1e-15));
  EXPECT_EQ(T::meet_line_plane(*T::line_through({0, 0, 1}, {1, 0, 1}), T::plane({0, 0, 1}, 2)).kind, Kind::parallel);
  EXPECT_EQ(T::meet_line_plane(*T::line_through({0, 0, 2}, {1, 0, 2}), T::plane({0, 0, 1}, 2)).kind, Kind::contained);
  const auto ls = T::meet_line_sphere(*T::line_through({1, 1, 0}, {1, 1, 5}), T::sphere({1, 1, 1}, 2));
  EXPECT_TRUE(near(ls.first, {1, 1, -1}, 1e-15));
  EXPECT_TRUE(near(ls.second, {1, 1, 3}, 1e-15));
  const auto lt = T::meet_line_sphere(*T::line_through({3, 1, 0}, {3, 1, 5}), T::sphere({1, 1, 1}, 2));
  EXPECT_EQ(lt.kind, Kind::tangent);
  EXPECT_TRUE(near(lt.first, {3, 1, 1}, 1e-15));
  const auto pp = T::meet_plane_plane(T::plane({0, 0, 1}, 2), T::plane({1, 0, 0}, 3));
  EXPECT_TRUE(near(pp.point, {3, 0, 2}, 1e-15));
  EXPECT_TRUE(near(pp.direction, {0, 1, 0}, 1e-15));
  EXPECT_EQ(T::meet_plane_plane(T::plane({0, 0, 1}, 2), T::plane({0, 0, -1}, -2)).kind, Kind::contained);
  EXPECT_EQ(T::meet_plane_plane(T::plane({0, 0, 1}, 2), T::plane({0, 0, 1}, 3)).kind, Kind::parallel);
  EXPECT_TRUE(near(T::reflect_in_sphere({3, 1, 0}, T::sphere({1, 1, 1}, 2)).point, {2.6, 1, 0.2}, 1e-15));
  EXPECT_EQ(T::reflect_in_sphere({1, 1, 1}, T::sphere({1, 1, 1}, 2)).kind, Kind::none);
  EXPECT_DOUBLE_EQ(T::side(T::sphere({1, 2, 3}, 2), {1, 2, 3}), -2);  // inside < 0 (§2.4.1)
}

}  // namespace
}  // namespace gacompare
