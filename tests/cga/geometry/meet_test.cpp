// The meets (§1.6 eq. 19, §2.4.1, §2.4.4) against their traditional twins on
// seeded random cases, near-degenerate cases (1e-9 from tangent, parallel) and
// exactly degenerate ones, plus hand-computed cases. Tolerances: the error model
// of cases.hpp, kC·eps·A^k·κ·size, with k = kLine (the dual entities are vectors
// carrying ½|x|², the line a 3-blade of two points; a meet is one product of
// two of them) and κ stated per operation.
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

// ---- eq. 19 itself ----

// a = λ b for some λ: |a − λb| ≤ 1e-13·|a| per component, λ from the largest
// component (O(1) random entities: a few roundings of O(1) products).
template <class A, class B>
::testing::AssertionResult proportional(const A& a, const B& b) {
  unsigned big = 0;
  for (unsigned k = 0; k < 32; ++k) big = std::abs(b[k]) > std::abs(b[big]) ? k : big;
  if (b[big] == 0) return ::testing::AssertionFailure() << "zero";
  const double lambda = a[big] / b[big];
  double size = 0;
  for (unsigned k = 0; k < 32; ++k) size = std::max(size, std::abs(a[k]));
  for (unsigned k = 0; k < 32; ++k)
    if (std::abs(a[k] - lambda * b[k]) > 1e-13 * size)
      return ::testing::AssertionFailure() << "blade " << k << ": " << a[k] << " vs " << lambda * b[k];
  return ::testing::AssertionSuccess();
}

TEST(Meet, Equation19AgreesWithTheNarrowForms) {
  // M_r ∨ M_s = [⟨M_r M_s⟩_{10−r−s}]* on the direct blades, against meet.hpp's
  // single products of the dual forms (S1∧S2, π⌋L), up to scale.
  Rng rng(310);
  for (int k = 0; k < 1000; ++k) {
    const auto s1 = C::sphere(rng.point(1), rng.uniform(0.5, 1.5)), s2 = C::sphere(rng.point(1), rng.uniform(0.5, 1.5));
    const auto m1 = undual(s1), m2 = undual(s2);  // direct 4-blades (grade 4 + 4: keep grade 2)
    ASSERT_TRUE(proportional(!grade<2>(m1 * m2), undual(C::meet(s1, s2))));
    const auto l = *C::line_through(rng.point(1), rng.point(1));
    const auto p = C::plane(rng.unit(), rng.uniform(-1, 1));
    ASSERT_TRUE(proportional(!grade<3>(l * undual(p)), C::meet(l, p)));  // grade 3 + 4: keep grade 3
  }
}

// ---- sphere–sphere ----

// κ = 1/sinφ (the radius r = √r²; sinφ = r d/(ρ1ρ2), the angle between the
// surfaces) + ρ/d (the foot of the circle on the line of centres); size ρmax + |c|.
void expect_same_sphere_sphere(const Vec3& c1, double r1, const Vec3& c2, double r2, Worst& worst) {
  const auto x = C::meet_sphere_sphere(C::sphere(c1, r1), C::sphere(c2, r2));
  const auto y = T::meet_sphere_sphere(T::sphere(c1, r1), T::sphere(c2, r2));
  ASSERT_EQ(x.kind, y.kind) << std::setprecision(17) << c1.transpose() << " " << r1 << " | " << c2.transpose()
                            << " " << r2;
  if (y.kind != Kind::circle && y.kind != Kind::tangent) return;
  const double d = (c2 - c1).norm(), rm = std::max(r1, r2);
  const double sin = std::max(y.radius * d / (r1 * r2), 1e-300);
  const double kappa = (y.kind == Kind::circle ? 1 / sin : 0) + rm / d;
  const double tol = kC * kEps * amplification({c1, c2}, kLine) * kappa * (rm + c1.norm());
  worst.see((x.centre - y.centre).norm(), tol);
  ASSERT_TRUE(near(x.centre, y.centre, tol, "centre"));
  ASSERT_TRUE(near(x.radius, y.radius, tol, "radius"));
  ASSERT_TRUE(near(x.normal, y.normal, tol, "normal"));
}

TEST(MeetSphereSphere, MatchesTwinOnRandomCases) {
  Rng rng(311);
  Worst worst;
  int circles = 0;
  for (int k = 0; k < kCases; ++k) {
    const Vec3 o = rng.site(), c1 = o + rng.point(1), c2 = o + rng.point(1);
    if ((c1 - c2).norm() < 0.1) { --k; continue; }
    const double r1 = rng.uniform(0.2, 1.5), r2 = rng.uniform(0.2, 1.5);
    expect_same_sphere_sphere(c1, r1, c2, r2, worst);
    circles += T::meet_sphere_sphere(T::sphere(c1, r1), T::sphere(c2, r2)).kind == Kind::circle;
    if (HasFatalFailure()) return;
  }
  EXPECT_GT(circles, kCases / 4);  // the cases exercise both outcomes
  EXPECT_LT(circles, kCases * 3 / 4);
}

TEST(MeetSphereSphere, TangentNearTangentConcentricDegenerate) {
  Rng rng(312);
  Worst worst;
  for (int k = 0; k < kNearCases; ++k) {
    const Vec3 c1 = rng.point(1.5), u = rng.unit();
    const double r1 = rng.uniform(0.2, 1.5), r2 = rng.uniform(0.2, 1.5);
    // Touching from outside and from inside (built in doubles: gap at rounding level).
    for (const double d : {r1 + r2, std::abs(r1 - r2)}) {
      if (d < 0.1) continue;
      const Vec3 c2 = c1 + d * u;
      EXPECT_EQ(T::meet_sphere_sphere(T::sphere(c1, r1), T::sphere(c2, r2)).kind, Kind::tangent);
      expect_same_sphere_sphere(c1, r1, c2, r2, worst);
      // 1e-9 closer or further: a tiny circle or nothing, both backends alike.
      expect_same_sphere_sphere(c1, r1, c1 + (d - 1e-9) * u, r2, worst);
      expect_same_sphere_sphere(c1, r1, c1 + (d + 1e-9) * u, r2, worst);
    }
    // Concentric: the same sphere, or nested without contact.
    EXPECT_EQ(C::meet_sphere_sphere(C::sphere(c1, r1), C::sphere(c1, r1)).kind, Kind::contained);
    EXPECT_EQ(T::meet_sphere_sphere(T::sphere(c1, r1), T::sphere(c1, r1)).kind, Kind::contained);
    EXPECT_EQ(C::meet_sphere_sphere(C::sphere(c1, r1), C::sphere(c1, r1 + 0.05)).kind, Kind::none);
    EXPECT_EQ(T::meet_sphere_sphere(T::sphere(c1, r1), T::sphere(c1, r1 + 0.05)).kind, Kind::none);
    // Zero or negative radius: no sphere, in both backends.
    EXPECT_EQ(C::meet_sphere_sphere(C::sphere(c1, 0), C::sphere(c1 + u, r1)).kind, Kind::degenerate);
    EXPECT_EQ(T::meet_sphere_sphere(T::sphere(c1, 0), T::sphere(c1 + u, r1)).kind, Kind::degenerate);
    EXPECT_EQ(C::meet_sphere_sphere(C::sphere(c1, -r1), C::sphere(c1 + u, r1)).kind, Kind::degenerate);
    EXPECT_EQ(T::meet_sphere_sphere(T::sphere(c1, -r1), T::sphere(c1 + u, r1)).kind, Kind::degenerate);
    EXPECT_EQ(C::meet_line_sphere(*C::line_through(c1, c1 + u), C::sphere(c1, -r1)).kind, Kind::degenerate);
    EXPECT_EQ(C::meet_sphere_plane(C::sphere(c1, -r1), C::plane(u, 0)).kind, Kind::degenerate);
    EXPECT_NEAR(C::radius(C::sphere(c1, -r1)), -r1, 1e-14);
    if (HasFatalFailure()) return;
  }
}

TEST(MeetSphereSphere, HandComputed) {
  // |c1 c2| = 8, radii 5: a 3-4-5 triangle, circle at x = 4 of radius 3.
  const auto x = C::meet_sphere_sphere(C::sphere({0, 0, 0}, 5), C::sphere({8, 0, 0}, 5));
  EXPECT_EQ(x.kind, Kind::circle);
  EXPECT_TRUE(near(x.centre, {4, 0, 0}, 1e-14));
  EXPECT_NEAR(x.radius, 3, 1e-14);
  EXPECT_TRUE(near(x.normal, {1, 0, 0}, 1e-15));
  // The report's test (§2.4.1): an intersection exists iff the meet squares ≥ 0.
  const auto t = C::meet_sphere_sphere(C::sphere({0, 0, 0}, 1), C::sphere({0, 2, 0}, 1));
  EXPECT_EQ(t.kind, Kind::tangent);
  EXPECT_TRUE(near(t.centre, {0, 1, 0}, 1e-15));
  EXPECT_EQ(C::meet_sphere_sphere(C::sphere({0, 0, 0}, 1), C::sphere({0, 2.5, 0}, 1)).kind, Kind::none);
}

// ---- sphere–plane ----

// κ = 1/sinφ (sinφ = r/ρ), size |c| + ρ.
void expect_same_sphere_plane(const Vec3& c, double r, const Vec3& nrm, double off, Worst& worst) {
  const auto x = C::meet_sphere_plane(C::sphere(c, r), C::plane(nrm, off));
  const auto y = T::meet_sphere_plane(T::sphere(c, r), T::plane(nrm, off));
  ASSERT_EQ(x.kind, y.kind);
  if (y.kind != Kind::circle && y.kind != Kind::tangent) return;
  const double kappa = y.kind == Kind::circle ? r / y.radius : 1;
  const double tol = kC * kEps * amplification({c, off * nrm}, kLine) * kappa * (r + c.norm());
  worst.see((x.centre - y.centre).norm(), tol);
  ASSERT_TRUE(near(x.centre, y.centre, tol, "centre"));
  ASSERT_TRUE(near(x.radius, y.radius, tol, "radius"));
  ASSERT_TRUE(near(x.normal, y.normal, tol, "normal"));
}

TEST(MeetSpherePlane, MatchesTwinOnRandomCases) {
  Rng rng(313);
  Worst worst;
  for (int k = 0; k < kCases; ++k) {
    const Vec3 o = rng.site(), c = o + rng.point(1), nrm = rng.unit();
    expect_same_sphere_plane(c, rng.uniform(0.2, 1.5), nrm, nrm.dot(o) + rng.uniform(-1.5, 1.5), worst);
    if (HasFatalFailure()) return;
  }
}

TEST(MeetSpherePlane, TangentAndNearTangent) {
  Rng rng(314);
  Worst worst;
  for (int k = 0; k < kNearCases; ++k) {
    const Vec3 c = rng.point(1.5), nrm = rng.unit();
    const double r = rng.uniform(0.2, 1.5);
    for (const double side : {1.0, -1.0}) {
      const double off = nrm.dot(c) + side * r;
      EXPECT_EQ(C::meet_sphere_plane(C::sphere(c, r), C::plane(nrm, off)).kind, Kind::tangent);
      expect_same_sphere_plane(c, r, nrm, off, worst);
      expect_same_sphere_plane(c, r, nrm, off + 1e-9, worst);
      expect_same_sphere_plane(c, r, nrm, off - 1e-9, worst);
    }
    EXPECT_EQ(C::meet_sphere_plane(C::sphere(c, 0), C::plane(nrm, 0)).kind, Kind::degenerate);
    if (HasFatalFailure()) return;
  }
  const auto x = C::meet_sphere_plane(C::sphere({0, 0, 0}, 5), C::plane({0, 0, 1}, 3));
  EXPECT_EQ(x.kind, Kind::circle);
  EXPECT_TRUE(near(x.centre, {0, 0, 3}, 1e-14));
  EXPECT_NEAR(x.radius, 4, 1e-14);
}

// ---- line–plane ----

// κ = 1/sinα (sinα = |n̂·u|/|u|, the line against the plane), size |a| + |u| + |x|.
void expect_same_line_plane(const Vec3& a, const Vec3& b, const Vec3& nrm, double off, Worst& worst) {
  const auto lc = C::line_through(a, b);
  const auto lt = T::line_through(a, b);
  ASSERT_TRUE(lc && lt);
  const auto x = C::meet_line_plane(*lc, C::plane(nrm, off));
  const auto y = T::meet_line_plane(*lt, T::plane(nrm, off));
  ASSERT_EQ(x.kind, y.kind) << std::setprecision(17) << a.transpose() << " | " << b.transpose();
  if (y.kind != Kind::point) return;
  const Vec3 u = b - a;
  const double sin = std::abs(nrm.dot(u)) / u.norm();
  const double tol =
      kC * kEps * amplification({a, b, off * nrm}, kLine) / sin * (a.norm() + u.norm() + y.point.norm());
  worst.see((x.point - y.point).norm(), tol);
  ASSERT_TRUE(near(x.point, y.point, tol, "point"));
}

TEST(MeetLinePlane, MatchesTwinOnRandomCases) {
  Rng rng(315);
  Worst worst;
  for (int k = 0; k < kCases; ++k) {
    const Vec3 o = rng.site(), a = o + rng.point(1), b = o + rng.point(1), nrm = rng.unit();
    if ((b - a).norm() < 0.1) { --k; continue; }
    expect_same_line_plane(a, b, nrm, nrm.dot(o) + rng.uniform(-1, 1), worst);
    if (HasFatalFailure()) return;
  }
}

TEST(MeetLinePlane, ParallelContainedAndNearParallel) {
  Rng rng(316);
  Worst worst;
  for (int k = 0; k < kNearCases; ++k) {
    const Vec3 a = rng.point(1.5), nrm = rng.unit();
    const Vec3 u = rng.perpendicular(nrm);  // in the plane's direction
    const double off = nrm.dot(a) + rng.uniform(0.1, 1) * (k % 2 ? 1 : -1);
    const auto lc = C::line_through(a, a + u);
    const auto lt = T::line_through(a, a + u);
    EXPECT_EQ(C::meet_line_plane(*lc, C::plane(nrm, off)).kind, Kind::parallel);
    EXPECT_EQ(T::meet_line_plane(*lt, T::plane(nrm, off)).kind, Kind::parallel);
    EXPECT_EQ(C::meet_line_plane(*lc, C::plane(nrm, nrm.dot(a))).kind, Kind::contained);
    EXPECT_EQ(T::meet_line_plane(*lt, T::plane(nrm, nrm.dot(a))).kind, Kind::contained);
    // Tilted by 1e-9: a crossing ~1e9 away, solved by both.
    expect_same_line_plane(a, a + u + 1e-9 * nrm, nrm, off, worst);
    if (HasFatalFailure()) return;
  }
  const auto x = C::meet_line_plane(*C::line_through({1, 1, 0}, {1, 1, 5}), C::plane({0, 0, 1}, 2));
  EXPECT_EQ(x.kind, Kind::point);
  EXPECT_TRUE(near(x.point, {1, 1, 2}, 1e-15));
}

// ---- line–sphere ----

// κ = 1/sinφ (sinφ = h/ρ, h the half chord) + 1, size |c| + ρ + |a|.
void expect_same_line_sphere(const Vec3& a, const Vec3& b, const Vec3& c, double r, Worst& worst) {
  const auto lc = C::line_through(a, b);
  const auto lt = T::line_through(a, b);
  ASSERT_TRUE(lc && lt);
  const auto x = C::meet_line_sphere(*lc, C::sphere(c, r));
  const auto y = T::meet_line_sphere(*lt, T::sphere(c, r));
  ASSERT_EQ(x.kind, y.kind) << std::setprecision(17) << a.transpose() << " | " << b.transpose() << " | "
                            << c.transpose() << " " << r;
  if (y.kind != Kind::point_pair && y.kind != Kind::tangent) return;
  const double h = 0.5 * (y.second - y.first).norm();
  const double kappa = 1 + (y.kind == Kind::point_pair ? r / h : 0);
  const double tol = kC * kEps * amplification({a, b, c}, kLine) * kappa * (c.norm() + r + a.norm());
  worst.see((x.first - y.first).norm(), tol);
  ASSERT_TRUE(near(x.first, y.first, tol, "first"));
  ASSERT_TRUE(near(x.second, y.second, tol, "second"));
}

TEST(MeetLineSphere, MatchesTwinOnRandomCases) {
  Rng rng(317);
  Worst worst;
  int pairs = 0;
  for (int k = 0; k < kCases; ++k) {
    const Vec3 o = rng.site(), a = o + rng.point(1), b = o + rng.point(1), c = o + rng.point(1);
    if ((b - a).norm() < 0.1) { --k; continue; }
    const double r = rng.uniform(0.2, 1.5);
    expect_same_line_sphere(a, b, c, r, worst);
    pairs += T::meet_line_sphere(*T::line_through(a, b), T::sphere(c, r)).kind == Kind::point_pair;
    if (HasFatalFailure()) return;
  }
  EXPECT_GT(pairs, kCases / 4);
  EXPECT_LT(pairs, kCases * 3 / 4);
}

TEST(MeetLineSphere, TangentIsOnePointNearTangentIsSolved) {
  Rng rng(318);
  Worst worst;
  for (int k = 0; k < kNearCases; ++k) {
    const Vec3 c = rng.point(1.5), p = rng.unit(), u = rng.perpendicular(p);
    const double r = rng.uniform(0.2, 1.5);
    const Vec3 touch = c + r * p;
    const Vec3 a = touch - rng.uniform(0.2, 1) * u, b = touch + rng.uniform(0.2, 1) * u;
    // Tangent: a single touching point, not a pair of NaNs (the known complaint).
    const auto x = C::meet_line_sphere(*C::line_through(a, b), C::sphere(c, r));
    EXPECT_EQ(x.kind, Kind::tangent);
    EXPECT_TRUE(x.first.allFinite());
    expect_same_line_sphere(a, b, c, r, worst);
    // 1e-9 inside: two points ~√(2ρ·1e-9) apart; 1e-9 outside: none.
    expect_same_line_sphere(a - 1e-9 * p, b - 1e-9 * p, c, r, worst);
    expect_same_line_sphere(a + 1e-9 * p, b + 1e-9 * p, c, r, worst);
    EXPECT_EQ(C::meet_line_sphere(*C::line_through(a + 1e-9 * p, b + 1e-9 * p), C::sphere(c, r)).kind, Kind::none);
    if (HasFatalFailure()) return;
  }
  const auto x = C::meet_line_sphere(*C::line_through({1, 1, 0}, {1, 1, 5}), C::sphere({1, 1, 1}, 2));
  EXPECT_EQ(x.kind, Kind::point_pair);
  EXPECT_TRUE(near(x.first, {1, 1, -1}, 1e-15));
  EXPECT_TRUE(near(x.second, {1, 1, 3}, 1e-15));
  const auto t = C::meet_line_sphere(*C::line_through({3, 1, 0}, {3, 1, 5}), C::sphere({1, 1, 1}, 2));
  EXPECT_EQ(t.kind, Kind::tangent);
  EXPECT_TRUE(near(t.first, {3, 1, 1}, 1e-15));
}

// ---- plane–plane ----

// κ = 1/sinθ (θ between the normals); the point is at distance ~|d|/sinθ, so
// size (|d1| + |d2| + 1)/sinθ for it and 1 for the direction.
void expect_same_plane_plane(const Vec3& n1, double d1, const Vec3& n2, double d2, Worst& worst) {
  const auto x = C::meet_plane_plane(C::plane(n1, d1), C::plane(n2, d2));
  const auto y = T::meet_plane_plane(T::plane(n1, d1), T::plane(n2, d2));
  ASSERT_EQ(x.kind, y.kind);
  if (y.kind != Kind::line) return;
  const double sin = n1.normalized().cross(n2.normalized()).norm();
  const double tol = kC * kEps * amplification({d1 * n1, d2 * n2}, kLine) / sin;
  worst.see((x.point - y.point).norm(), tol * (std::abs(d1) + std::abs(d2) + 1) / sin);
  ASSERT_TRUE(near(x.point, y.point, tol * (std::abs(d1) + std::abs(d2) + 1) / sin, "point"));
  ASSERT_TRUE(near(x.direction, y.direction, tol, "direction"));
}

TEST(MeetPlanePlane, MatchesTwinOnRandomCases) {
  Rng rng(319);
  Worst worst;
  for (int k = 0; k < kCases; ++k) {
    const Vec3 o = rng.site(), n1 = rng.unit(), n2 = rng.unit();
    expect_same_plane_plane(n1, n1.dot(o) + rng.uniform(-1, 1), n2, n2.dot(o) + rng.uniform(-1, 1), worst);
    if (HasFatalFailure()) return;
  }
}

TEST(MeetPlanePlane, ParallelCoincidentAndNearParallel) {
  Rng rng(320);
  Worst worst;
  for (int k = 0; k < kNearCases; ++k) {
    const Vec3 n1 = rng.unit();
    const double d = rng.uniform(-2, 2);
    for (const double s : {1.0, -1.0}) {
      EXPECT_EQ(C::meet_plane_plane(C::plane(n1, d), C::plane(s * n1, s * d)).kind, Kind::contained);
      EXPECT_EQ(T::meet_plane_plane(T::plane(n1, d), T::plane(s * n1, s * d)).kind, Kind::contained);
      EXPECT_EQ(C::meet_plane_plane(C::plane(n1, d), C::plane(s * n1, s * (d + 0.5))).kind, Kind::parallel);
      EXPECT_EQ(T::meet_plane_plane(T::plane(n1, d), T::plane(s * n1, s * (d + 0.5))).kind, Kind::parallel);
    }
    const Vec3 n2 = (n1 + 1e-9 * rng.perpendicular(n1)).normalized();
    expect_same_plane_plane(n1, d, n2, d + rng.uniform(-1, 1), worst);
    if (HasFatalFailure()) return;
  }
  const auto x = C::meet_plane_plane(C::plane({0, 0, 1}, 2), C::plane({1, 0, 0}, 3));
  EXPECT_EQ(x.kind, Kind::line);
  EXPECT_TRUE(near(x.point, {3, 0, 2}, 1e-15));
  EXPECT_TRUE(near(x.direction, {0, 1, 0}, 1e-15));
}

}  // namespace
}  // namespace gacompare
