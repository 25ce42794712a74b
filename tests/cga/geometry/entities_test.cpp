// Conformal entities (Table 1, §1.5, §2.4.1) against their traditional twins:
// construction, extraction, the circle through 3 points and the sphere through 4.
// Tolerances: the error model of cases.hpp (kC·eps·A·κ·size), stated per check.
#include "cases.hpp"
#include "cga/geometry/geometry.hpp"
#include "traditional/geometry.hpp"

#include <iomanip>

namespace gacompare {
namespace {
namespace C = cga;
namespace T = traditional;
using geometry::Kind;
using namespace geometry::testing;

TEST(CgaEntities, HandComputed) {
  // Exact binary inputs: every answer below is exact or within a few ulps.
  const auto s = C::sphere({1, 2, 3}, 2);
  EXPECT_TRUE(near(C::centre(s), {1, 2, 3}, 1e-15));
  EXPECT_TRUE(near(C::centre_by_reflection(s), {1, 2, 3}, 1e-15));  // §1.5: reflect n
  EXPECT_NEAR(C::radius(s), 2, 1e-15);
  EXPECT_NEAR(scalar_product(s, C::n_inf()), -1, 1e-15);  // normalised form

  const auto p = C::plane({0, 0, 2}, 4);  // z = 2
  EXPECT_TRUE(near(C::normal(p), {0, 0, 1}, 0));
  EXPECT_EQ(C::offset(p), 2);

  const auto l = C::line_through({1, 1, 0}, {1, 1, 5});
  ASSERT_TRUE(l.has_value());
  EXPECT_TRUE(near(C::direction(*l), {0, 0, 1}, 1e-15));
  EXPECT_TRUE(near(C::point_on(*l), {1, 1, 0}, 1e-15));

  const auto q = C::plane_through({1, 0, 0}, {0, 1, 0}, {0, 0, 1});
  ASSERT_TRUE(q.has_value());
  EXPECT_TRUE(near(C::normal(*q), Vec3(1, 1, 1).normalized(), 1e-15));  // right-handed in a, b, c
  EXPECT_NEAR(C::offset(*q), 1 / std::sqrt(3.0), 1e-15);

  // Degenerate constructions are typed, not NaN.
  EXPECT_FALSE(C::line_through({1, 2, 3}, {1, 2, 3}).has_value());
  EXPECT_FALSE(C::plane_through({0, 0, 0}, {1, 1, 1}, {2, 2, 2}).has_value());
  EXPECT_FALSE(C::plane_through({0, 0, 0}, {0, 0, 0}, {2, 2, 2}).has_value());
}

TEST(CgaEntities, ExtractionMatchesTwin) {
  Rng rng(301);
  Worst worst;
  for (int k = 0; k < kCases; ++k) {
    const Vec3 o = rng.site();
    const Vec3 a = o + rng.point(1), b = o + rng.point(1), c = o + rng.point(1);
    const double r = rng.uniform(0.1, 2);
    const double A = amplification({a, b, c}, kLine);
    // Sphere round trip: size |c| + ρ, well conditioned (κ = 1).
    const auto s = C::sphere(a, r);
    const double ts = kC * kEps * A * (a.norm() + r);
    worst.see((C::centre(s) - a).norm(), ts);
    ASSERT_TRUE(near(C::centre(s), a, ts, "sphere centre"));
    ASSERT_TRUE(near(C::centre_by_reflection(s), a, ts, "centre by reflection"));
    ASSERT_TRUE(near(C::radius(s), r, ts, "sphere radius"));
    // Line: κ = 1 for the direction (|b − a| ≳ 0.1 here, size/|b−a| ≤ 10·A).
    const auto lc = C::line_through(a, b);
    const auto lt = T::line_through(a, b);
    ASSERT_EQ(lc.has_value(), lt.has_value());
    if (lc) {
      const double u = (b - a).norm();
      const double tl = kC * kEps * A * (a.norm() + b.norm()) / u;
      ASSERT_TRUE(near(C::direction(*lc), T::direction(*lt), tl, "line direction"));
      ASSERT_TRUE(near(C::point_on(*lc), T::point_on(*lt), tl * (a.norm() + 1), "line point"));
    }
    // Plane through 3 points: κ = 1/sin of the angle at a.
    const auto pc = C::plane_through(a, b, c);
    const auto pt = T::plane_through(a, b, c);
    ASSERT_EQ(pc.has_value(), pt.has_value());
    if (pc) {
      const Vec3 u = b - a, v = c - a;
      const double sin = u.cross(v).norm() / (u.norm() * v.norm());
      const double tp = kC * kEps * A / sin * (a.norm() + 1) / std::min(u.norm(), v.norm());
      worst.see((C::normal(*pc) - T::normal(*pt)).norm(), tp);
      ASSERT_TRUE(near(C::normal(*pc), T::normal(*pt), tp, "plane normal"));
      ASSERT_TRUE(near(C::offset(*pc), T::offset(*pt), tp * (a.norm() + 1), "plane offset"));
    }
    // Dual plane from parameters.
    const Vec3 nrm = rng.unit();
    const double d = rng.uniform(-3, 3);
    ASSERT_TRUE(near(C::normal(C::plane(nrm, d)), nrm, 4 * kEps, "normal"));
    ASSERT_TRUE(near(C::offset(C::plane(nrm, d)), d, 4 * kEps * std::abs(d), "offset"));
  }
}

// Compare one circumcircle: centre and radius of size R, normal of size 1, each
// with κ = 1/sin(angle at a) and the A of the inputs.
void expect_same_circle(const Vec3& a, const Vec3& b, const Vec3& c, Worst& worst) {
  const auto x = C::circumcircle(a, b, c);
  const auto y = T::circumcircle(a, b, c);
  ASSERT_EQ(x.kind, y.kind) << a.transpose() << " | " << b.transpose() << " | " << c.transpose();
  if (y.kind != Kind::circle) return;
  const Vec3 u = b - a, v = c - a;
  const double sin = u.cross(v).norm() / (u.norm() * v.norm());
  const double tol = kC * kEps * amplification({a, b, c}, kRound) / sin;
  worst.see((x.centre - y.centre).norm(), tol * y.radius);
  ASSERT_TRUE(near(x.centre, y.centre, tol * y.radius, "centre"))
      << std::setprecision(17) << a.transpose() << " | " << b.transpose() << " | " << c.transpose() << " sin " << sin;
  ASSERT_TRUE(near(x.radius, y.radius, tol * y.radius, "radius"));
  ASSERT_TRUE(near(x.normal, y.normal, tol, "normal"));
}

TEST(Circumcircle, MatchesTwinOnRandomCases) {
  Rng rng(302);
  Worst worst;
  for (int k = 0; k < kCases; ++k) {
    const Vec3 o = rng.site();
    const Vec3 a = o + rng.point(1), b = o + rng.point(1), c = o + rng.point(1);
    if (min_distance({a, b, c}) < 0.1) { --k; continue; }
    expect_same_circle(a, b, c, worst);
    if (HasFatalFailure()) return;
  }
}

TEST(Circumcircle, NearCollinearIsSolvedExactlyCollinearIsDegenerate) {
  Rng rng(303);
  Worst worst;
  for (int k = 0; k < kNearCases; ++k) {
    const Vec3 o = rng.point(0.5);
    const Vec3 a = o + rng.point(1), b = o + rng.point(1);
    if ((b - a).norm() < 0.1) { --k; continue; }
    const double t = rng.uniform(-2, 3);
    if (std::abs(t) < 0.1 || std::abs(t - 1) < 0.1) { --k; continue; }  // keep ℓ ≳ 0.1 (cases.hpp)
    const Vec3 on = a + t * (b - a);
    // Within 1e-9 of collinear: a circle of radius ~1e9, both backends solve it.
    const Vec3 c = on + 1e-9 * rng.perpendicular(b - a);
    EXPECT_EQ(T::circumcircle(a, b, c).kind, Kind::circle);
    expect_same_circle(a, b, c, worst);
    expect_same_circle(c, a, b, worst);
    // Collinear up to the rounding of `on`: degenerate in both.
    EXPECT_EQ(C::circumcircle(a, b, on).kind, Kind::degenerate);
    EXPECT_EQ(T::circumcircle(a, b, on).kind, Kind::degenerate);
    // Coincident points.
    EXPECT_EQ(C::circumcircle(a, a, b).kind, Kind::degenerate);
    EXPECT_EQ(T::circumcircle(a, b, b).kind, Kind::degenerate);
    EXPECT_EQ(C::circumcircle(a, b, b).kind, Kind::degenerate);
    if (HasFatalFailure()) return;
  }
}

TEST(Circumcircle, HandComputed) {
  // Right triangle: the centre is the hypotenuse's midpoint (Thales).
  for (const auto& r : {C::circumcircle({0, 0, 0}, {2, 0, 0}, {0, 2, 0}),
                        T::circumcircle({0, 0, 0}, {2, 0, 0}, {0, 2, 0})}) {
    EXPECT_EQ(r.kind, Kind::circle);
    EXPECT_TRUE(near(r.centre, {1, 1, 0}, 1e-15));
    EXPECT_NEAR(r.radius, std::sqrt(2.0), 1e-15);
    EXPECT_TRUE(near(r.normal, {0, 0, 1}, 1e-15));
  }
  // Equilateral triangle of side √2 on the unit axes: centre (1,1,1)/3, R = √(2/3).
  const auto e = C::circumcircle({1, 0, 0}, {0, 1, 0}, {0, 0, 1});
  EXPECT_TRUE(near(e.centre, Vec3(1, 1, 1) / 3, 1e-15));
  EXPECT_NEAR(e.radius, std::sqrt(2.0 / 3), 1e-15);
}

void expect_same_sphere(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d, Worst& worst) {
  const auto x = C::sphere_through(a, b, c, d);
  const auto y = T::sphere_through(a, b, c, d);
  ASSERT_EQ(x.kind, y.kind);
  if (y.kind != Kind::sphere) return;
  const Vec3 u = b - a, v = c - a, w = d - a;
  const double sin = std::abs(u.dot(v.cross(w))) / (u.norm() * v.norm() * w.norm());
  const double tol = kC * kEps * amplification({a, b, c, d}, kRound) / sin * y.radius;
  worst.see((x.centre - y.centre).norm(), tol);
  ASSERT_TRUE(near(x.centre, y.centre, tol, "centre"));
  ASSERT_TRUE(near(x.radius, y.radius, tol, "radius"));
}

TEST(SphereThrough, MatchesTwinOnRandomCases) {
  Rng rng(304);
  Worst worst;
  for (int k = 0; k < kCases; ++k) {
    const Vec3 o = rng.site();
    const Vec3 a = o + rng.point(1), b = o + rng.point(1), c = o + rng.point(1), d = o + rng.point(1);
    if (min_distance({a, b, c, d}) < 0.1) { --k; continue; }
    expect_same_sphere(a, b, c, d, worst);
    if (HasFatalFailure()) return;
  }
}

TEST(SphereThrough, NearCoplanarIsSolvedCoplanarIsDegenerate) {
  Rng rng(305);
  Worst worst;
  for (int k = 0; k < kNearCases; ++k) {
    const Vec3 o = rng.point(0.5);
    const Vec3 a = o + rng.point(1), b = o + rng.point(1), c = o + rng.point(1);
    const Vec3 nrm = (b - a).cross(c - a);
    if (nrm.norm() < 0.1) { --k; continue; }
    const Vec3 in = a + rng.uniform(-1, 2) * (b - a) + rng.uniform(-1, 2) * (c - a);
    const Vec3 d = in + 1e-9 * nrm.normalized();  // within 1e-9 of coplanar
    if (min_distance({a, b, c, d}) < 0.1) { --k; continue; }
    EXPECT_EQ(T::sphere_through(a, b, c, d).kind, Kind::sphere);
    expect_same_sphere(a, b, c, d, worst);
    expect_same_sphere(d, c, b, a, worst);
    EXPECT_EQ(C::sphere_through(a, b, c, in).kind, Kind::degenerate);
    EXPECT_EQ(T::sphere_through(a, b, c, in).kind, Kind::degenerate);
    EXPECT_EQ(C::sphere_through(a, b, b, c).kind, Kind::degenerate);
    if (HasFatalFailure()) return;
  }
  // Four points on one circle: the 4-blade itself vanishes.
  EXPECT_EQ(C::sphere_through({1, 0, 0}, {0, 1, 0}, {-1, 0, 0}, {0, -1, 0}).kind, Kind::degenerate);
  EXPECT_EQ(T::sphere_through({1, 0, 0}, {0, 1, 0}, {-1, 0, 0}, {0, -1, 0}).kind, Kind::degenerate);
}

TEST(SphereThrough, HandComputed) {
  // Centre (1,2,3), radius 2: the four points ±2 along the axes from it.
  const Vec3 c(1, 2, 3);
  for (const auto& r : {C::sphere_through(c + Vec3(2, 0, 0), c + Vec3(0, 2, 0), c + Vec3(0, 0, 2), c - Vec3(2, 0, 0)),
                        T::sphere_through(c + Vec3(2, 0, 0), c + Vec3(0, 2, 0), c + Vec3(0, 0, 2), c - Vec3(2, 0, 0))}) {
    EXPECT_EQ(r.kind, Kind::sphere);
    EXPECT_TRUE(near(r.centre, c, 1e-14));
    EXPECT_NEAR(r.radius, 2, 1e-14);
  }
}

}  // namespace
}  // namespace gacompare
